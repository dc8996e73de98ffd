//! `regolith sweep` on a deck with a known answer: the two-sphere Hertz collision of the trade
//! study (examples/trade/in.collision). Its restitution converges to the coefficient the deck
//! sets as the time step shrinks, its elastic contact time to Hertz theory's; the exact and
//! fast paths agree; a time step past the stability limit is reported as a failed run; the CSV,
//! table and figure are written, and `--merge` gathers sweeps into one table.

use std::path::{Path, PathBuf};
use std::process::Command;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("regolith-sweep-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn deck() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/trade/in.collision")
}

fn sweep(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .arg("sweep")
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The CSV as rows of (header -> value).
fn rows(csv: &str) -> Vec<Vec<(String, String)>> {
    let mut lines = csv.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    lines
        .map(|l| {
            // settings hold no commas here; a failure message may (it is quoted, and last
            // among the columns read below)
            let mut cells = Vec::new();
            let mut cur = String::new();
            let mut quoted = false;
            for c in l.chars() {
                match c {
                    '"' => quoted = !quoted,
                    ',' if !quoted => cells.push(std::mem::take(&mut cur)),
                    c => cur.push(c),
                }
            }
            cells.push(cur);
            header.iter().cloned().zip(cells).collect()
        })
        .collect()
}

fn get<'a>(row: &'a [(String, String)], name: &str) -> &'a str {
    &row.iter().find(|(h, _)| h == name).unwrap().1
}

fn num(row: &[(String, String)], name: &str) -> f64 {
    get(row, name).parse().unwrap()
}

#[test]
fn restitution_converges_to_e_and_paths_agree() {
    let dir = scratch("restitution");
    let out = dir.join("out");
    let (code, stdout, stderr) = sweep(&[
        deck().to_str().unwrap(),
        "--var",
        "frac",
        "0.3,0.1,0.03,0.005",
        "--var",
        "sf",
        "off,fast",
        "--observe",
        "e=v_e_meas",
        "--observe",
        "tc=v_tc",
        "--expect",
        "e=0.5",
        "--reference",
        "frac=0.005",
        "--out",
        out.to_str().unwrap(),
        "--jobs",
        "2",
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.contains("reference frac=0.005 sf=off"), "{stdout}");
    assert!(stdout.contains("known answers: e = 0.500000"), "{stdout}");
    for f in ["sweep.csv", "sweep.png", "summary.txt"] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    assert_eq!(&std::fs::read(out.join("sweep.png")).unwrap()[1..4], b"PNG");
    let csv = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let r = rows(&csv);
    assert_eq!(r.len(), 8, "{csv}");
    let exact: Vec<_> = r.iter().filter(|row| get(row, "sf") == "off").collect();
    // the error against e: 5 % at 30 % of the Rayleigh time, below 0.1 % at 0.5 % (not
    // monotone in between: where the contact starts within a step matters, at 0.1 and 0.5 %)
    let errs: Vec<f64> = exact.iter().map(|row| num(row, "e_relerr")).collect();
    assert!(errs[0] > 0.03, "{errs:?}");
    assert!(errs[1] < 0.01 && errs[2] < 0.01, "{errs:?}");
    assert!(errs[3] < 1e-3, "{errs:?}");
    // contact time: against the reference run, converging monotonically
    assert_eq!(num(exact[3], "tc_relerr"), 0.0);
    assert_eq!(get(exact[3], "reference"), "1");
    let tc: Vec<f64> = exact.iter().map(|row| num(row, "tc_relerr")).collect();
    assert!(tc[0] > tc[1] && tc[1] > tc[2] && tc[2] > 0.0, "{tc:?}");
    // two spheres: the fast path gives the exact path's numbers
    for (a, b) in r.iter().step_by(2).zip(r.iter().skip(1).step_by(2)) {
        assert_eq!(get(a, "frac"), get(b, "frac"));
        assert_eq!(get(b, "sf"), "fast");
        assert_eq!(get(a, "e"), get(b, "e"));
        assert_eq!(get(a, "tc"), get(b, "tc"));
        assert!(num(a, "steps") > 0.0 && num(a, "wall_s") > 0.0);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn elastic_contact_time_meets_hertz_and_blow_ups_are_reported() {
    let dir = scratch("elastic");
    let out = dir.join("elastic");
    // e = 1: the contact time of Hertz theory (2.87 (m*^2 / (R* E*^2 v))^(1/5) is itself
    // good to about 0.1 %); dt 3 x the Rayleigh time is past the stability limit
    let (code, stdout, stderr) = sweep(&[
        deck().to_str().unwrap(),
        "--var",
        "frac",
        "0.005,0.1,3",
        "--set",
        "e",
        "1",
        "--observe",
        "tc=v_tc",
        "--observe",
        "th=v_tc_hertz",
        "--observe",
        "drift=v_drift",
        "--expect",
        "drift=0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let r = rows(&std::fs::read_to_string(out.join("sweep.csv")).unwrap());
    let (fine, coarse, past) = (&r[0], &r[1], &r[2]);
    assert!(
        (num(fine, "tc") / num(fine, "th") - 1.0).abs() < 2e-3,
        "{fine:?}"
    );
    // an elastic collision keeps its energy: drift is measured absolutely (reference 0)
    assert!(num(fine, "drift").abs() < 1e-5, "{fine:?}");
    assert!(num(coarse, "drift_abserr") > num(fine, "drift_abserr"));
    assert!(get(past, "status").starts_with("failed: "), "{past:?}");
    // the guard warned of the overlap before the deck failed on the lost atoms
    assert!(
        get(past, "status").contains("after step 1: atoms 1 and 2 overlap by"),
        "{past:?}"
    );
    assert!(stdout.contains("failed"), "{stdout}");
    // merged: a table with the reference, the errors and the failure
    let merged = dir.join("merged");
    let (code, stdout, stderr) = sweep(&[
        "--merge",
        out.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    let md = std::fs::read_to_string(merged.join("trade.md")).unwrap();
    assert!(
        md.starts_with("| sweep | observable | frac 0.005 | frac 0.1 | frac 3 |"),
        "{md}"
    );
    assert!(md.contains("| elastic | tc | ref |"), "{md}");
    assert!(md.contains("| elastic | drift (abs.) | "), "{md}");
    assert!(md.contains("blow-up"), "{md}");
    assert!(merged.join("trade.png").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_requests_are_refused() {
    let d = deck();
    let d = d.to_str().unwrap();
    for (args, want) in [
        (vec![d, "--observe", "e=v_e_meas"], "nothing to sweep"),
        (vec![d, "--var", "frac", "0.1"], "nothing to measure"),
        (
            vec![d, "--var", "sf", "gpu", "--observe", "e=v_e_meas"],
            "--var sf gpu",
        ),
        (
            vec![d, "--var", "frac", "0.1", "--observe", "e=analyze:pile:x"],
            "analyses are",
        ),
        (
            vec![
                d,
                "--var",
                "frac",
                "0.1",
                "--observe",
                "e=v_e_meas",
                "--reference",
                "dt=1",
            ],
            "not a swept variable",
        ),
        (
            vec![
                "missing.deck",
                "--var",
                "frac",
                "0.1",
                "--observe",
                "e=v_e_meas",
            ],
            "no such deck",
        ),
    ] {
        let (code, _, stderr) = sweep(&args);
        assert_eq!(code, 1, "{args:?}");
        assert!(stderr.contains(want), "{args:?}: {stderr}");
    }
}
