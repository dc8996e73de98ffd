//! `regolith convert` on a restart file and data file that Debian's LIGGGHTS wrote of the
//! same settled bed (compat/convert): restart -> data equals LIGGGHTS's write_data, restart
//! -> restart is byte-identical, restart -> data -> restart keeps every per-atom value
//! exactly, dumps become VTK, and broken files give a clear error and no output.

use std::path::{Path, PathBuf};
use std::process::Command;

fn convert_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/convert")
}

fn regolith(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
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

fn body(text: &str) -> &str {
    text.split_once('\n').unwrap().1
}

#[test]
fn restart_conversions() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-convert-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let src = convert_dir();
    std::fs::copy(src.join("bed.restart"), dir.join("bed.restart")).unwrap();
    let liggghts_data = std::fs::read_to_string(src.join("bed.data")).unwrap();

    // restart -> data: LIGGGHTS's own write_data of the same state, after the title line
    let (code, out, err) = regolith(&dir, &["convert", "bed.restart", "out.data"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("125 atoms, step 3000"), "{out}");
    let ours = std::fs::read_to_string(dir.join("out.data")).unwrap();
    assert_eq!(body(&ours), body(&liggghts_data));

    // restart -> restart: the same bytes
    let (code, _, err) = regolith(&dir, &["convert", "bed.restart", "copy.restart"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        std::fs::read(dir.join("copy.restart")).unwrap(),
        std::fs::read(dir.join("bed.restart")).unwrap()
    );

    // restart -> data -> restart: every per-atom value of the data layout survives
    let (code, _, err) = regolith(
        &dir,
        &["convert", "out.data", "back.restart", "--boundary", "p p f"],
    );
    assert_eq!(code, 0, "{err}");
    for (from, to) in [("bed.restart", "a.dump"), ("back.restart", "b.dump")] {
        let (code, _, err) = regolith(&dir, &["convert", from, to]);
        assert_eq!(code, 0, "{err}");
    }
    let (code, out, _) = regolith(&dir, &["diff", "a.dump", "b.dump", "--rtol", "0"]);
    assert_eq!(
        code, 1,
        "the step differs (data files carry none), values must not: {out}"
    );
    let (code, out, _) = regolith(
        &dir,
        &["diff", "a.dump", "b.dump", "--rtol", "0", "--steps", "0:0"],
    );
    assert!(code == 1 && out.contains("0 steps compared"), "{out}");
    let strip_step = |t: String| t.replacen("ITEM: TIMESTEP\n3000\n", "ITEM: TIMESTEP\n0\n", 1);
    let a = strip_step(std::fs::read_to_string(dir.join("a.dump")).unwrap());
    let b = std::fs::read_to_string(dir.join("b.dump")).unwrap();
    assert_eq!(a, b);

    // restart -> VTK, and dump -> VTK
    let (code, _, err) = regolith(&dir, &["convert", "bed.restart", "bed.vtk"]);
    assert_eq!(code, 0, "{err}");
    let vtk = std::fs::read_to_string(dir.join("bed.vtk")).unwrap();
    assert!(vtk.starts_with("# vtk DataFile Version 5.1\n") && vtk.contains("POINTS 125 float\n"));
    assert!(dir.join("bed_boundingBox.vtk").exists());
    let (code, _, err) = regolith(&dir, &["convert", "a.dump", "snap*.vtk"]);
    assert_eq!(code, 0, "{err}");
    assert!(std::fs::read_to_string(dir.join("snap3000.vtk"))
        .unwrap()
        .contains("omega 3 125 double"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn broken_restart_files_are_refused_without_output() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-broken-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let good = std::fs::read(convert_dir().join("bed.restart")).unwrap();
    let mut swapped = good.clone();
    swapped[4..8].reverse(); // the version string's length in the other byte order
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "cut.restart",
            good[..good.len() / 2].to_vec(),
            "truncated at byte",
        ),
        ("swap.restart", swapped, "big-endian"),
        (
            "text.restart",
            b"ITEM: TIMESTEP\n0\n".to_vec(),
            "unknown header flag",
        ),
        (
            "lammps.restart",
            b"LammpS RestartT\0\0\0\0".to_vec(),
            "newer LAMMPS",
        ),
    ];
    for (name, bytes, message) in cases {
        std::fs::write(dir.join(name), bytes).unwrap();
        let (code, _, err) = regolith(&dir, &["convert", name, "out.data"]);
        assert_eq!(code, 1, "{name}");
        assert!(err.contains(name) && err.contains(message), "{name}: {err}");
        assert!(!dir.join("out.data").exists(), "{name}: partial output");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn regolith_writes_the_restart_liggghts_was_given() {
    // compat/engine/in.liggghts_reads has LIGGGHTS continue from this file; it must stay
    // exactly what regolith writes for compat/convert/in.make_bed
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-writes-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(convert_dir().join("in.make_bed"), dir.join("in.make_bed")).unwrap();
    let (code, _, err) = regolith(&dir, &["-in", "in.make_bed", "-log", "none"]);
    assert_eq!(code, 0, "{err}");
    let committed = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("compat/engine/liggghts_reads.inputs/regolith.restart");
    assert!(
        std::fs::read(dir.join("bed.restart")).unwrap() == std::fs::read(committed).unwrap(),
        "regolith's restart of in.make_bed changed: rerun compat/regenerate.sh after copying it"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn dash_r_converts_like_liggghts() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-dash-r-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let restart = convert_dir().join("bed.restart");
    let (code, _, err) = regolith(&dir, &["-r", restart.to_str().unwrap(), "r.data"]);
    assert_eq!(code, 0, "{err}");
    let ours = std::fs::read_to_string(dir.join("r.data")).unwrap();
    let theirs = std::fs::read_to_string(convert_dir().join("bed.data")).unwrap();
    assert_eq!(body(&ours), body(&theirs));
    let _ = std::fs::remove_dir_all(&dir);
}
