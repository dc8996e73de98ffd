//! Every full-size deck and stage in inputs/ runs in regolith for a few steps (the list in
//! inputs/smoke.txt, which inputs/smoke.sh runs in Debian's LIGGGHTS): each folder is copied to
//! a scratch directory and its runs go in order, so the shock runs read the bed the
//! preparation deck wrote.

use std::path::{Path, PathBuf};
use std::process::Command;

fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        let target = to.join(e.file_name());
        if e.path().is_dir() {
            copy_tree(&e.path(), &target);
        } else {
            std::fs::copy(e.path(), target).unwrap();
        }
    }
}

#[test]
fn every_inputs_deck_runs_a_few_steps() {
    let inputs = Path::new(env!("CARGO_MANIFEST_DIR")).join("inputs");
    let scratch: PathBuf = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-inputs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&scratch);
    let list = std::fs::read_to_string(inputs.join("smoke.txt")).unwrap();
    let mut runs = 0;
    for line in list.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.is_empty() || words[0].starts_with('#') {
            continue;
        }
        let (folder, deck, vars) = (words[0], words[1], &words[2..]);
        let dir = scratch.join(folder);
        if !dir.is_dir() {
            copy_tree(&inputs.join(folder), &dir);
        }
        let mut cmd = Command::new(env!("CARGO_BIN_EXE_regolith"));
        cmd.current_dir(&dir)
            .args(["-in", deck, "-log", "log.smoke", "-screen", "none"]);
        for pair in vars.chunks(2) {
            cmd.arg("-var").args(pair);
        }
        let out = cmd.output().unwrap();
        let log = std::fs::read_to_string(dir.join("log.smoke")).unwrap_or_default();
        assert!(
            out.status.success(),
            "{folder}/{deck} {vars:?} failed:\n{}\n{}",
            String::from_utf8_lossy(&out.stderr),
            log.lines().rev().take(8).collect::<Vec<_>>().join("\n")
        );
        runs += 1;
    }
    assert!(runs >= 16, "{runs} runs listed");
    std::fs::remove_dir_all(&scratch).unwrap();
}
