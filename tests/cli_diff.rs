//! `regolith diff` from the command line: exit 0 within tolerance, 1 outside, 2 on
//! unreadable input; gzip and `*` series read like plain dumps; the last line gives the
//! maxima.

use std::io::Write;
use std::process::Command;

const DUMP: &str = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id x fx \n1 0.25 1e-3 \n2 0.5 -2 \n";

fn diff(dir: &std::path::Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .arg("diff")
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn exit_statuses_and_formats() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-cli-diff-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("a.dump"), DUMP).unwrap();
    // the same atoms in another order, fx off by 2e-7 relative, gzipped
    let b = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id x fx \n2 0.5 -2.0000004 \n1 0.25 1e-3 \n";
    let mut gz = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    gz.write_all(b.as_bytes()).unwrap();
    std::fs::write(dir.join("b.dump.gz"), gz.finish().unwrap()).unwrap();
    std::fs::write(dir.join("s0.dump"), DUMP).unwrap();
    std::fs::write(
        dir.join("s10.dump"),
        DUMP.replace("TIMESTEP\n0", "TIMESTEP\n10"),
    )
    .unwrap();
    std::fs::write(
        dir.join("t.dump"),
        format!("{DUMP}{}", DUMP.replace("TIMESTEP\n0", "TIMESTEP\n10")),
    )
    .unwrap();

    let (code, out, _) = diff(&dir, &["a.dump", "b.dump.gz"]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.lines()
            .last()
            .unwrap()
            .starts_with("max relative deviation 2.000000e-7 (step 0, atom 2, fx)"),
        "{out}"
    );
    let (code, _, _) = diff(&dir, &["a.dump", "b.dump.gz", "--rtol", "1e-8"]);
    assert_eq!(code, 1);
    let (code, _, _) = diff(
        &dir,
        &["a.dump", "b.dump.gz", "--rtol", "0", "--columns", "x"],
    );
    assert_eq!(code, 0);
    let (code, out, _) = diff(&dir, &["s*.dump", "t.dump", "--rtol", "0"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("2 steps compared"), "{out}");
    let (code, _, err) = diff(&dir, &["a.dump", "missing.dump"]);
    assert_eq!(code, 2);
    assert!(err.contains("missing.dump"), "{err}");
    std::fs::write(dir.join("broken.gz"), [0x1f, 0x8b, 8, 0, 1, 2]).unwrap();
    let (code, _, err) = diff(&dir, &["a.dump", "broken.gz"]);
    assert_eq!(code, 2);
    assert!(err.contains("corrupted gzip"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn dump_local_entries_meet_in_key_order() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-cli-diff-local-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let head = "ITEM: TIMESTEP\n500\nITEM: NUMBER OF ENTRIES\n3\nITEM: BOX BOUNDS ff ff ff\n-0.05 0.05\n-0.03 0.03\n-0.02 0.04\nITEM: ENTRIES c_w[1] c_w[2] c_w[3] c_w[4] \n";
    // (mesh, triangle, atom, force): LIGGGHTS lists contacts by triangle, regolith by atom
    let a = format!("{head}0 1 7 0.25 \n0 3 2 0.5 \n1 0 7 -1.5 \n");
    let b = format!("{head}0 3 2 0.5 \n0 1 7 0.25 \n1 0 7 -1.5 \n");
    let c = format!("{head}0 3 2 0.5 \n0 1 7 0.2501 \n1 0 7 -1.5 \n");
    for (name, text) in [("a.dump", &a), ("b.dump", &b), ("c.dump", &c)] {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let (status, out, err) = diff(&dir, &["a.dump", "b.dump"]);
    assert_eq!(status, 0, "{out}{err}");
    let (status, out, _) = diff(&dir, &["a.dump", "c.dump", "--key", "c_w[1],c_w[2],c_w[3]"]);
    assert_eq!(status, 1, "{out}");
    assert!(
        out.contains("(step 500, entry 1, c_w[4])"),
        "the first entry in (mesh, triangle, atom) order: {out}"
    );
    let (status, _, err) = diff(&dir, &["a.dump", "b.dump", "--key", "c_w[9]"]);
    assert_eq!(status, 2);
    assert!(err.contains("no key column c_w[9]"), "{err}");
}

#[test]
fn scale_relative_mode_from_the_command_line() {
    // the case: a stress column of scale ~1e-9 whose near-zero value differs by
    // 1e-17 (2e-4 relative to itself, 1e-8 of the column's scale)
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-cli-diff-scale-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let a = "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id c_stress[6] \n1 1.2e-9 \n2 5e-14 \n3 -8e-10 \n";
    std::fs::write(dir.join("a.dump"), a).unwrap();
    std::fs::write(dir.join("b.dump"), a.replace("5e-14", "5.001e-14")).unwrap();
    let (code, out, _) = diff(&dir, &["a.dump", "b.dump"]);
    assert_eq!(code, 1, "{out}");
    let (code, out, _) = diff(&dir, &["a.dump", "b.dump", "--scale", "max"]);
    assert_eq!(code, 0, "{out}");
    let last = out.lines().last().unwrap();
    assert!(
        last.starts_with("max deviation relative to the column's largest magnitude 8.333333e-9 (step 0, atom 2, c_stress[6])"),
        "{out}"
    );
    let (code, out, _) = diff(&dir, &["a.dump", "b.dump", "--scale", "rms"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("scale (rms)"), "{out}");
    // --rtol and --atol keep their meaning: the bound is atol + rtol x scale
    let (code, _, _) = diff(
        &dir,
        &["a.dump", "b.dump", "--scale", "max", "--rtol", "1e-9"],
    );
    assert_eq!(code, 1);
    let (code, _, _) = diff(
        &dir,
        &[
            "a.dump", "b.dump", "--scale", "max", "--rtol", "0", "--atol", "1e-16",
        ],
    );
    assert_eq!(code, 0);
    let (code, _, err) = diff(&dir, &["a.dump", "b.dump", "--scale", "column"]);
    assert_eq!(code, 2);
    assert!(err.contains("--scale column"), "{err}");
    let _ = std::fs::remove_dir_all(&dir);
}
