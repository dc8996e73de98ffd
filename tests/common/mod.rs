//! Helpers shared by the integration tests that compare regolith with LIGGGHTS.
// each test crate that includes this module uses only some of it
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh, empty directory `regolith-TAG-PID` in the build's temporary folder (target/tmp).
pub fn scratch_dir(tag: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Run regolith in `dir` with `args` (stdin empty), its output captured.
pub fn regolith(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// Captured output bytes as text (invalid UTF-8 replaced).
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Run regolith in `dir` on `deck`, written there as `file`, with `-log none` and `args`.
pub fn run_deck(dir: &Path, file: &str, deck: &str, args: &[&str]) -> Output {
    std::fs::write(dir.join(file), deck).unwrap();
    Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["-in", file, "-log", "none"])
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// Run blocks as compat/regenerate.sh cuts them from LIGGGHTS's screen output: from each
/// header line starting with `Step` up to (not including) `Loop time`, so lines that fixes
/// print during a run (fix print, warnings) are compared too.
pub fn thermo_lines(stdout: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in stdout.lines() {
        if line.starts_with("Loop time") {
            inside = false;
        }
        if inside {
            out.push(line.to_string());
        }
        if line.trim_start().starts_with("Step ") {
            inside = true;
            out.push(line.to_string());
        }
    }
    out
}

/// The official LIGGGHTS tutorials of Debian's liggghts-doc (or `REGOLITH_TUTORIALS`);
/// fails the test with the install command when they are missing.
pub fn tutorials_root() -> PathBuf {
    let root = std::env::var("REGOLITH_TUTORIALS").unwrap_or_else(|_| {
        "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public".to_string()
    });
    let root = PathBuf::from(root);
    assert!(
        root.is_dir(),
        "the LIGGGHTS tutorials are missing at {}: apt-get install -y liggghts-doc",
        root.display()
    );
    root
}

/// The largest difference of dump text `b` from dump text `a` in units of each column's
/// scale (its largest magnitude in `a`'s snapshot), atoms matched by ID; fails the test when
/// the snapshots' counts, steps or atoms differ.
pub fn scale_deviation(a: &str, b: &str) -> f64 {
    use regolith::io::dump_compare::parse;
    let (a, b) = (parse(a).unwrap(), parse(b).unwrap());
    assert_eq!(a.len(), b.len(), "snapshot counts");
    let mut worst: f64 = 0.0;
    for (sa, sb) in a.iter().zip(&b) {
        assert_eq!(sa.step, sb.step, "snapshot steps");
        assert!(
            sa.rows.keys().eq(sb.rows.keys()),
            "step {}: other atoms",
            sa.step
        );
        for c in 0..sa.columns.len() {
            let scale = sa.rows.values().map(|r| r[c].abs()).fold(0.0, f64::max);
            if scale > 0.0 {
                for (id, r) in &sa.rows {
                    worst = worst.max((r[c] - sb.rows[id][c]).abs() / scale);
                }
            }
        }
    }
    worst
}
