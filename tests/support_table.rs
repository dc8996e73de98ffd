//! compat/SUPPORT.md must equal what `regolith check --table` says of the official tutorials
//! now, and checking them must never panic.

use std::path::Path;
use std::process::Command;

mod common;

fn tutorial_decks(root: &Path) -> Vec<String> {
    let mut decks = Vec::new();
    let mut stack = vec![root.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("readable tutorial folder") {
            let path = entry.expect("dir entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path
                .file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("in."))
            {
                decks.push(path.to_string_lossy().into_owned());
            }
        }
    }
    decks.sort();
    decks
}

#[test]
fn support_table_is_current() {
    let root = common::tutorials_root();
    let root = root.as_path();
    let decks = tutorial_decks(root);
    assert_eq!(decks.len(), 28, "liggghts-doc ships 28 tutorial decks");
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args([
            "check",
            "--table",
            "--root",
            &format!("{}/", root.display()),
        ])
        .args(&decks)
        .output()
        .expect("regolith runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "check --table failed: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    let table = String::from_utf8(out.stdout).expect("utf-8 table");
    assert_eq!(table.lines().count(), 2 + 28, "{table}");

    let committed =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/compat/SUPPORT.md"))
            .expect("compat/SUPPORT.md exists");
    let start = committed
        .find("| deck |")
        .expect("SUPPORT.md holds the table");
    assert_eq!(
        &committed[start..],
        table,
        "compat/SUPPORT.md is out of date: run compat/support.sh"
    );
}

#[test]
fn support_table_lists_the_declared_commands() {
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["help", "--markdown"])
        .output()
        .expect("regolith runs");
    assert!(out.status.success());
    let table = String::from_utf8(out.stdout).expect("utf-8 table");
    assert!(table.contains("| `fix` | `wall/gran` |"), "{table}");
    let committed =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/compat/SUPPORT.md"))
            .expect("compat/SUPPORT.md exists");
    assert!(
        committed.contains(&table),
        "compat/SUPPORT.md is out of date: run compat/support.sh"
    );
}
