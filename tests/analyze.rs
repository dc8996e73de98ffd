//! `regolith analyze` end to end: the struck chain run by `--run` in regolith gives the same
//! wave speed as the same analysis of Debian LIGGGHTS's dumps of the same deck
//! (compat/analyze/chain_liggghts.dump.gz, written by compat/regenerate.sh analyze).

use std::path::{Path, PathBuf};
use std::process::Command;

use regolith::analyze::chain::{analyze, ChainOptions};
use regolith::analyze::series::Series;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn liggghts_reference() -> String {
    root()
        .join("compat/analyze/chain_liggghts.dump.gz")
        .display()
        .to_string()
}

fn work_dir(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-analyze-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The c_w printed on a summary line `...: wave speed c_w = X +/- E m/s ...`.
fn printed_speed(stdout: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.contains("wave speed c_w = "))
        .unwrap_or_else(|| panic!("no wave speed in:\n{stdout}"));
    let rest = line.split("c_w = ").nth(1).unwrap();
    rest.split_whitespace().next().unwrap().parse().unwrap()
}

#[test]
fn chain_run_in_regolith_matches_liggghts_dumps() {
    let work = work_dir("chain");
    std::fs::copy(
        root().join("examples/struck_chain/in.struck_chain"),
        work.join("in.struck_chain"),
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["analyze", "chain", "--run"])
        .arg(work.join("in.struck_chain"))
        .args(["--var", "nlayers", "10", "--var", "vim", "0.1"])
        .args(["--var", "nsteps", "30000", "--var", "dN", "1000"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("v_im = 1e-1 m/s"), "{stdout}");
    // 0.1 m/s is above the soft beads' Hertz elastic limit (0.0094 m/s): flagged
    assert!(stdout.contains("WARNING: v_im = 1e-1 m/s is above the Hertz elastic limit"));
    let analysis = work.join("post/analysis");
    for f in [
        "chain_arrival.png",
        "chain_layers.csv",
        "chain_particles.csv",
    ] {
        assert!(analysis.join(f).is_file(), "{f} missing");
    }

    // the same analysis of LIGGGHTS's dumps, and of regolith's, in the library
    let o = ChainOptions::default();
    let lig = analyze(&Series::open(&liggghts_reference(), 1e-6).unwrap(), &o).unwrap();
    let pattern = work.join("post/chain_*.dump").display().to_string();
    let reg = analyze(&Series::open(&pattern, 1e-6).unwrap(), &o).unwrap();
    assert_eq!(lig.layers.len(), 10);
    for (a, b) in lig.layers.iter().zip(&reg.layers) {
        assert_eq!((a.arrival, a.fitted), (b.arrival, b.fitted));
        assert!((a.peak_force - b.peak_force).abs() <= 1e-6 * a.peak_force);
    }
    assert!((lig.fit.slope - reg.fit.slope).abs() <= 1e-9 * lig.fit.slope);
    assert!((printed_speed(&stdout) - lig.fit.slope).abs() < 1e-4);
    // a Hertz shock at 0.1 m/s: a few times the soft beads' weak-impact speed
    assert!(lig.fit.slope > 5.0 && lig.fit.slope < 15.0, "{:?}", lig.fit);
    std::fs::remove_dir_all(&work).unwrap();
}

#[test]
fn chain_sweep_from_the_command_line() {
    let work = work_dir("sweep");
    let r = liggghts_reference();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["analyze", "chain", "--dt", "1e-6", "--out"])
        .arg(&work)
        .args(["--set", "0.1", &r, "--set", "0.1", &r])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(work.join("run2_chain_arrival.png").is_file());
    // one speed only: no sweep figure
    assert!(!work.join("chain_sweep.png").exists());
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["analyze", "chain", &r])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--dt SECONDS or --log LOGFILE"));
    std::fs::remove_dir_all(&work).unwrap();
}
