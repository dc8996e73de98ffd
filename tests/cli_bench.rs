//! `regolith bench` runs a deck and reports its loop time and rate (the figures are
//! measured, not asserted); an unknown scene is an error naming the built-in ones.

use std::process::Command;

#[test]
fn bench_reports_loop_times() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-bench-test-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let deck =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine/in.hertz_pairs");
    std::fs::copy(&deck, dir.join("in.hertz_pairs")).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["bench", "in.hertz_pairs", "--repeat", "2"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // two runs of 3000 + 2000 steps of 4 atoms each
    let rows: Vec<&str> = text.lines().filter(|l| l.starts_with("exact ")).collect();
    assert_eq!(rows.len(), 2, "{text}");
    for r in rows {
        let w: Vec<&str> = r.split_whitespace().collect();
        assert_eq!(w[3], "5000", "{r}");
        assert!(
            w[2].parse::<f64>().unwrap() > 0.0 && w[4].parse::<f64>().unwrap() > 0.0,
            "{r}"
        );
    }
    // the medians table: rate, contacts, neighbour builds and the time split
    assert!(
        text.lines()
            .any(|l| l.starts_with("| in.hertz_pairs | exact | ") && l.ends_with(" |")),
        "{text}"
    );
    // the fast path at two thread counts, interleaved with the exact path
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args([
            "bench",
            "in.hertz_pairs",
            "--exact",
            "--fast",
            "--threads",
            "1,2",
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    for label in ["exact ", "fast 1t ", "fast 2t "] {
        assert_eq!(
            text.lines().filter(|l| l.starts_with(label)).count(),
            1,
            "{label}: {text}"
        );
    }
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["bench", "no_such_scene"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("settled_bed, struck_chain"));
    let _ = std::fs::remove_dir_all(&dir);
}
