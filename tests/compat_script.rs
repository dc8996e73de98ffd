//! The script language against Debian's LIGGGHTS: every deck in compat/script/ is run by
//! regolith exactly as compat/regenerate.sh ran it with liggghts, and the screen output, the
//! log, every file the deck wrote and the exit status must equal the committed references.
//! Decks named `err_*` end in an error: regolith must fail too and say what LIGGGHTS says.

use std::path::{Path, PathBuf};
use std::process::Command;

fn compat_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/script")
}

fn copy_tree(from: &Path, to: &Path) {
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.path().is_dir() {
            std::fs::create_dir_all(&target).unwrap();
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// Every file below `dir`, as relative path -> contents.
fn files_below(dir: &Path) -> std::collections::BTreeMap<String, Vec<u8>> {
    let mut out = std::collections::BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().to_string_lossy().into_owned();
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    out
}

fn without_first_line(text: &str) -> String {
    text.split_once('\n')
        .map(|(_, rest)| rest.to_string())
        .unwrap_or_default()
}

/// First difference between two texts, as a short report.
fn first_difference(what: &str, expected: &str, got: &str) -> Option<String> {
    if expected == got {
        return None;
    }
    let (e, g): (Vec<&str>, Vec<&str>) = (expected.lines().collect(), got.lines().collect());
    let n = e.iter().zip(&g).take_while(|(a, b)| a == b).count();
    Some(format!(
        "  {what} differs at line {}:\n    liggghts: {:?}\n    regolith: {:?}",
        n + 1,
        e.get(n).copied().unwrap_or("<end>"),
        g.get(n).copied().unwrap_or("<end>")
    ))
}

fn run_deck(name: &str) -> Vec<String> {
    let dir = compat_dir();
    let work = std::env::temp_dir().join(format!("regolith-compat-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).unwrap();
    let deck = format!("in.{name}");
    std::fs::copy(dir.join(&deck), work.join(&deck)).unwrap();
    let inputs = dir.join(format!("{name}.inputs"));
    if inputs.is_dir() {
        copy_tree(&inputs, &work);
    }
    let before = files_below(&work);
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["-in", &deck, "-log", "log.txt"])
        .current_dir(&work)
        .env_remove("REGOLITH_COMPAT_SET")
        .output()
        .expect("regolith runs");
    let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap_or_default();
    let expected_status: i32 = read(&format!("{name}.status")).trim().parse().unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let status = out.status.code().unwrap_or(-1);
    let mut problems = Vec::new();

    if name.starts_with("err_") {
        if status == 0 {
            problems.push(format!(
                "  exit status 0, liggghts failed with {expected_status}"
            ));
        }
        // LIGGGHTS prints "ERROR: message (./src/file.cpp:N)"; regolith must give the message
        for line in read(&format!("{name}.out")).lines() {
            if let Some(msg) = line.strip_prefix("ERROR: ") {
                let msg = msg.rsplit_once(" (./src/").map_or(msg, |(m, _)| m);
                if !stderr.contains(&format!("ERROR: {msg}")) {
                    problems.push(format!(
                        "  no 'ERROR: {msg}' in regolith's stderr:\n{stderr}"
                    ));
                }
            }
        }
        if status > 1 || stderr.contains("panicked") {
            problems.push(format!("  status {status}, stderr:\n{stderr}"));
        }
    } else {
        let expected_code = if expected_status == 0 { 0 } else { 1 };
        if status != expected_code {
            problems.push(format!(
                "  exit status {status}, expected {expected_code}; stderr:\n{stderr}"
            ));
        }
        problems.extend(first_difference(
            "screen",
            &read(&format!("{name}.out")),
            &without_first_line(&stdout),
        ));
        let log = std::fs::read_to_string(work.join("log.txt")).unwrap_or_default();
        problems.extend(first_difference(
            "log",
            &read(&format!("{name}.log")),
            &without_first_line(&log),
        ));
        let expected_files = {
            let d = dir.join(format!("{name}.files"));
            if d.is_dir() {
                files_below(&d)
            } else {
                Default::default()
            }
        };
        let mut written = files_below(&work);
        written.retain(|k, v| k != "log.txt" && before.get(k) != Some(v));
        for (path, want) in &expected_files {
            match written.get(path) {
                None => problems.push(format!("  file {path} was not written")),
                Some(got) => problems.extend(first_difference(
                    &format!("file {path}"),
                    &String::from_utf8_lossy(want),
                    &String::from_utf8_lossy(got),
                )),
            }
        }
        for path in written.keys() {
            if !expected_files.contains_key(path) {
                problems.push(format!("  file {path} written, liggghts wrote none"));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&work);
    problems
}

#[test]
fn script_decks_match_liggghts() {
    let mut decks: Vec<String> = std::fs::read_dir(compat_dir())
        .unwrap()
        .filter_map(|e| {
            e.unwrap()
                .file_name()
                .to_str()?
                .strip_prefix("in.")
                .map(str::to_string)
        })
        .collect();
    decks.sort();
    assert!(decks.len() >= 15, "compat/script holds the language decks");
    let mut failures = Vec::new();
    for name in &decks {
        let problems = run_deck(name);
        if !problems.is_empty() {
            failures.push(format!("{name}:\n{}", problems.join("\n")));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} decks differ from LIGGGHTS:\n{}",
        failures.len(),
        decks.len(),
        failures.join("\n")
    );
}
