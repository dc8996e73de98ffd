//! The script language against Debian's LIGGGHTS 3.8.0: every deck `compat/script/in.NAME`
//! is run by regolith the way `compat/regenerate.sh` ran it with liggghts, and must give the
//! same screen output, the same files and the same exit status.
//!
//! Convention (see also compat/regenerate.sh):
//! * run: `regolith -in <absolute path of the deck> -log none -echo none` in a fresh empty
//!   temp directory, with every `REGOLITH_COMPAT_*` variable removed from the environment;
//!   the side files in `compat/script/NAME.inputs/` (if any) are copied into that directory
//!   first, so decks use relative paths only.
//! * `NAME.out`: stdout without its first (banner) line, compared exactly, line by line;
//!   regolith's banner is its own first line and must start with `regolith`.
//! * `NAME.status`: the exit status (LIGGGHTS gives 1 for errors and for `quit`).
//! * `NAME.files/`: every file the deck created or changed in its directory, compared exactly;
//!   writing any other file is a failure too.
//! * Decks named `err_*` end in a LIGGGHTS error. regolith must exit non-zero (no panic, no
//!   signal), and its stdout or stderr must contain the text of every LIGGGHTS `ERROR` line of
//!   `NAME.out` (without `ERROR: ` / `ERROR on proc N: ` and without the ` (./src/file.cpp:N)`
//!   suffix). Its other output is not compared: regolith may report errors before running.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// A deck that runs longer than this is killed and reported (runaway jump loops).
const DECK_TIMEOUT: Duration = Duration::from_secs(10);

fn compat_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/script")
}

fn copy_tree(from: &Path, to: &Path) {
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        let target = to.join(entry.file_name());
        if entry.file_type().unwrap().is_dir() {
            std::fs::create_dir_all(&target).unwrap();
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// Every file below `dir`, as relative path (with `/`) -> contents.
fn files_below(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for entry in entries {
            let entry = entry.unwrap();
            let p = entry.path();
            if entry.file_type().map(|t| t.is_dir()).unwrap_or(false) {
                stack.push(p);
            } else if let Ok(bytes) = std::fs::read(&p) {
                let rel: Vec<String> = p
                    .strip_prefix(dir)
                    .unwrap()
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                out.insert(rel.join("/"), bytes);
            }
        }
    }
    out
}

/// `text` without its first line (and the first line itself).
fn split_banner(text: &str) -> (&str, &str) {
    match text.split_once('\n') {
        Some((first, rest)) => (first, rest),
        None => (text, ""),
    }
}

/// A short unified-style diff around the first difference, or None when equal.
fn difference(what: &str, expected: &[u8], got: &[u8]) -> Option<String> {
    if expected == got {
        return None;
    }
    let (e_text, g_text) = (
        String::from_utf8_lossy(expected),
        String::from_utf8_lossy(got),
    );
    let e: Vec<&str> = e_text.split('\n').collect();
    let g: Vec<&str> = g_text.split('\n').collect();
    let n = e.iter().zip(&g).take_while(|(a, b)| a == b).count();
    let mut out = format!(
        "  {what} differs at line {} (--- liggghts, +++ regolith):\n",
        n + 1
    );
    if n >= e.len().min(g.len()) && e.len() == g.len() {
        // same lines, different bytes: invalid UTF-8 only
        out.push_str("    (lines equal after lossy UTF-8 decoding; raw bytes differ)\n");
        return Some(out);
    }
    const CONTEXT: usize = 2;
    const SHOWN: usize = 6;
    for line in &e[n.saturating_sub(CONTEXT)..n] {
        out.push_str(&format!("     {line}\n"));
    }
    let show = |out: &mut String, sign: char, lines: &[&str], text: &str| {
        let rest = &lines[n.min(lines.len())..];
        if rest.is_empty() {
            out.push_str(&format!("    {sign} <end of text, no final newline>\n"));
        }
        // the empty piece after the final newline is shown as <end of text>
        for (i, line) in rest.iter().take(SHOWN).enumerate() {
            if n + i + 1 == lines.len() && line.is_empty() {
                out.push_str(&format!("    {sign} <end of text>\n"));
            } else if n + i + 1 == lines.len() && !text.ends_with('\n') {
                out.push_str(&format!("    {sign} {line}  <no final newline>\n"));
            } else {
                out.push_str(&format!("    {sign} {line}\n"));
            }
        }
        if rest.len() > SHOWN {
            out.push_str(&format!(
                "    {sign} ... {} more lines\n",
                rest.len() - SHOWN
            ));
        }
    };
    show(&mut out, '-', &e, &e_text);
    show(&mut out, '+', &g, &g_text);
    Some(out.trim_end().to_string())
}

/// The message of a LIGGGHTS error line: `ERROR: msg (./src/f.cpp:N)` or
/// `ERROR on proc 0: msg (./src/f.cpp:N)` -> `msg`.
fn error_message(line: &str) -> Option<&str> {
    let rest = line.strip_prefix("ERROR")?;
    let msg = match rest.strip_prefix(": ") {
        Some(m) => m,
        None => rest.strip_prefix(" on proc ")?.split_once(": ")?.1,
    };
    Some(
        msg.rsplit_once(" (./src/")
            .map_or(msg, |(m, _)| m)
            .trim_end(),
    )
}

struct Outcome {
    status: Option<i32>,
    stdout: Vec<u8>,
    stderr: Vec<u8>,
    timed_out: bool,
}

fn run_regolith(deck: &Path, work: &Path, capture: &Path) -> Outcome {
    let out_path = capture.join("stdout");
    let err_path = capture.join("stderr");
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_regolith"));
    cmd.arg("-in")
        .arg(deck)
        .args(["-log", "none", "-echo", "none"])
        .current_dir(work)
        .stdin(Stdio::null())
        .stdout(std::fs::File::create(&out_path).unwrap())
        .stderr(std::fs::File::create(&err_path).unwrap());
    for (key, _) in std::env::vars_os() {
        if key.to_string_lossy().starts_with("REGOLITH_COMPAT_") {
            cmd.env_remove(key);
        }
    }
    let mut child = cmd.spawn().expect("regolith starts");
    let start = Instant::now();
    let mut timed_out = false;
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > DECK_TIMEOUT {
            let _ = child.kill();
            timed_out = true;
            break child.wait().unwrap();
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    Outcome {
        status: status.code(),
        stdout: std::fs::read(&out_path).unwrap_or_default(),
        stderr: std::fs::read(&err_path).unwrap_or_default(),
        timed_out,
    }
}

fn check_deck(name: &str) -> Vec<String> {
    let dir = compat_dir();
    let mut problems = Vec::new();
    let reference = |ext: &str| std::fs::read(dir.join(format!("{name}.{ext}")));
    let (Ok(expected_out), Ok(status_text)) = (reference("out"), reference("status")) else {
        return vec![format!(
            "  no {name}.out / {name}.status: run compat/regenerate.sh script"
        )];
    };
    let expected_status: i32 = String::from_utf8_lossy(&status_text)
        .trim()
        .parse()
        .expect("status file holds an integer");

    let base = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "regolith-compat-script-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&base);
    let work = base.join("work");
    std::fs::create_dir_all(&work).unwrap();
    let inputs = dir.join(format!("{name}.inputs"));
    if inputs.is_dir() {
        copy_tree(&inputs, &work);
    }
    let before = files_below(&work);
    let deck = dir.join(format!("in.{name}"));
    let out = run_regolith(&deck, &work, &base);
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let stderr_tail = || {
        let lines: Vec<&str> = stderr.lines().collect();
        lines[lines.len().saturating_sub(12)..].join("\n      ")
    };

    if out.timed_out {
        problems.push(format!(
            "  killed after {DECK_TIMEOUT:?} (liggghts finished in well under a second)"
        ));
    }
    if out.status == Some(101) || stderr.contains("panicked") {
        problems.push(format!("  regolith panicked:\n      {}", stderr_tail()));
    } else if out.status.is_none() && !out.timed_out {
        problems.push("  regolith was killed by a signal".to_string());
    }

    if name.starts_with("err_") {
        if out.status == Some(0) {
            problems.push(format!(
                "  exit status 0, liggghts failed with status {expected_status}"
            ));
        }
        let expected_text = String::from_utf8_lossy(&expected_out);
        let messages: Vec<&str> = expected_text.lines().filter_map(error_message).collect();
        if messages.is_empty() {
            problems.push(format!(
                "  {name}.out has no ERROR line: an err_ deck must end in a LIGGGHTS error"
            ));
        }
        for msg in messages {
            if !stdout.contains(msg) && !stderr.contains(msg) {
                problems.push(format!(
                    "  LIGGGHTS says \"ERROR: {msg}\"; regolith's output lacks that text. stderr:\n      {}",
                    stderr_tail()
                ));
            }
        }
    } else {
        let (banner, screen) = split_banner(&stdout);
        if !banner.starts_with("regolith") {
            problems.push(format!(
                "  first stdout line should be regolith's banner, got {banner:?}"
            ));
        }
        if out.status != Some(expected_status) {
            problems.push(format!(
                "  exit status {:?}, liggghts exited with {expected_status}; stderr:\n      {}",
                out.status,
                stderr_tail()
            ));
        }
        problems.extend(difference(
            "screen output",
            &expected_out,
            screen.as_bytes(),
        ));

        let expected_files = files_below(&dir.join(format!("{name}.files")));
        let mut written = files_below(&work);
        written.retain(|path, bytes| before.get(path) != Some(bytes));
        for (path, want) in &expected_files {
            match written.get(path) {
                None => problems.push(format!("  file {path} was not written")),
                Some(got) => problems.extend(difference(&format!("file {path}"), want, got)),
            }
        }
        for path in written.keys() {
            if !expected_files.contains_key(path) {
                problems.push(format!(
                    "  file {path} was written; liggghts wrote no such file"
                ));
            }
        }
    }
    let _ = std::fs::remove_dir_all(&base);
    problems
}

#[test]
fn script_decks_match_liggghts() {
    let mut decks: Vec<String> = std::fs::read_dir(compat_dir())
        .unwrap()
        .filter_map(|e| {
            let e = e.unwrap();
            if !e.file_type().ok()?.is_file() {
                return None;
            }
            e.file_name()
                .to_str()?
                .strip_prefix("in.")
                .map(str::to_string)
        })
        .collect();
    decks.sort();
    assert!(decks.len() >= 15, "compat/script holds the language decks");
    let mut failures = Vec::new();
    for name in &decks {
        let problems = check_deck(name);
        if !problems.is_empty() {
            failures.push(format!(
                "deck compat/script/in.{name}:\n{}",
                problems.join("\n")
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} script decks differ from LIGGGHTS 3.8.0 \
         (references: compat/script/NAME.out/.status/.files, made by compat/regenerate.sh):\n\n{}\n",
        failures.len(),
        decks.len(),
        failures.join("\n\n")
    );
}

#[test]
fn error_lines_are_parsed() {
    assert_eq!(
        error_message("ERROR: Divide by 0 in variable formula (./src/variable.cpp:1594)"),
        Some("Divide by 0 in variable formula")
    );
    assert_eq!(
        error_message("ERROR on proc 0: Substitution for illegal variable (./src/input.cpp:505)"),
        Some("Substitution for illegal variable")
    );
    assert_eq!(
        error_message("ERROR: Unknown command: then (./src/input.cpp:327)"),
        Some("Unknown command: then")
    );
    assert_eq!(error_message("no error"), None);
    assert!(difference("x", b"a\nb\n", b"a\nb\n").is_none());
    let d = difference("x", b"a\nb\nc\n", b"a\nB\nc\n").unwrap();
    assert!(
        d.contains("line 2") && d.contains("- b") && d.contains("+ B"),
        "{d}"
    );
    let d = difference("x", b"a\n", b"a").unwrap();
    assert!(
        d.contains("<end of text>") || d.contains("no final newline"),
        "{d}"
    );
}
