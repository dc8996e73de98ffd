//! Mutated decks and corrupted files run through the built binary, as a hostile user would
//! write them: the compatibility decks with words deleted, duplicated and swapped, numbers
//! replaced by extreme values (1e400, -0, NaN, inf, huge counts), lines cut short and bytes
//! that are not UTF-8; restart files truncated, with bytes flipped and extreme values written
//! into their atoms; data files and dumps mutated like decks. Each case runs `check` and a
//! short run (run lengths are capped) under a time and an address-space limit, and must end
//! with:
//!
//! * no panic, no abort or other signal, no hang (the time limit);
//! * a non-zero exit status only with a message naming the file and line (`in.fuzz:12`) or,
//!   for the file readers, the file;
//! * no NaN or infinity in the thermo output, dumps and data or restart files of a run that
//!   exits with status 0.
//!
//! The cases come from fixed seeds, so every run tries the same inputs. A failing case is
//! written to `target/fuzz-failures/` with the command that reproduces it.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Wall-clock limit of one invocation (the debug binary; a clean run of a capped compat deck
/// takes well under a second).
const TIME_LIMIT: Duration = Duration::from_secs(20);

/// Address-space limit of one invocation (`ulimit -v`, kB).
const MEMORY_LIMIT_KB: u64 = 2_000_000;

/// Steps a mutated deck's `run` may take.
const MAX_RUN_STEPS: i64 = 40;

/// Monte Carlo samples a mutated deck may ask for (`ntry` of a multisphere template, `ntry_mc`
/// of an insertion): a valid request for billions of samples is work LIGGGHTS does too, not a
/// hang, so it is capped like a run's length.
const MAX_SAMPLES: i64 = 1_000_000;

/// The cases' seed and count: fixed, unless `REGOLITH_FUZZ_SEED` (a number mixed into every
/// seed) and `REGOLITH_FUZZ_SCALE` (a factor on every count) ask for a longer search.
fn plan(seed: u64, cases: usize) -> (u64, usize) {
    let var = |name: &str| std::env::var(name).ok().and_then(|v| v.parse::<u64>().ok());
    let seed = seed
        ^ var("REGOLITH_FUZZ_SEED")
            .unwrap_or(0)
            .wrapping_mul(0x2545_F491_4F6C_DD1D);
    let scale = var("REGOLITH_FUZZ_SCALE").unwrap_or(1).max(1) as usize;
    (seed, cases * scale)
}

/// SplitMix64: small, fast and the same everywhere.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Numbers a deck may hold that are valid words but extreme values: signed zero, the edges of
/// a double, subnormals, negatives, huge and tiny magnitudes.
const EXTREMES: &[&str] = &[
    "-0",
    "0",
    "0.0",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "4.9e-324",
    "1e-320",
    "-1",
    "-1e-30",
    "1e30",
    "1e-30",
    "1e10",
    "-1e10",
    "1e-300",
];

/// Words in the place of a number that are not numbers LIGGGHTS accepts: overflow, NaN,
/// infinities, broken exponents, hexadecimal.
const NOT_NUMBERS: &[&str] = &[
    "1e400", "-1e400", "NaN", "nan", "-nan", "inf", "-inf", "1e+", ".", "-", "+", "1e", "0x10",
    "1e-400",
];

/// Counts far beyond any machine or LIGGGHTS's ints.
const HUGE_COUNTS: &[&str] = &[
    "2147483647",
    "2147483648",
    "4294967296",
    "99999999999",
    "9223372036854775807",
    "99999999999999999999",
    "1000000000",
];

/// Control-flow lines are not mutated: `jump SELF` without its label, a loop bound of 1e30 or
/// a condition that never turns true make a deck loop for ever in LIGGGHTS as in regolith.
fn control_flow(first: &str) -> bool {
    matches!(first, "jump" | "label" | "next" | "if")
}

/// Lines where huge magnitudes would be loop bounds or run lengths (only non-numbers go
/// there).
fn unbounded(first: &str) -> bool {
    control_flow(first) || matches!(first, "variable" | "run")
}

fn is_number(w: &str) -> bool {
    let w = w.trim_matches(|c| c == '"' || c == '\'');
    !w.is_empty() && w.parse::<f64>().is_ok() && w.bytes().any(|b| b.is_ascii_digit())
}

/// A deck as lines of words.
fn words_of(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .map(|l| l.split_whitespace().map(str::to_string).collect())
        .collect()
}

fn join(lines: &[Vec<String>]) -> String {
    let mut s = String::new();
    for l in lines {
        s.push_str(&l.join(" "));
        s.push('\n');
    }
    s
}

/// Every `run N` capped to [`MAX_RUN_STEPS`] (after `run` and `every`), also inside the quoted
/// commands of an `if`, and every sample count (`ntry`, `ntry_mc`) to [`MAX_SAMPLES`].
fn cap_runs(lines: &mut [Vec<String>]) {
    for l in lines.iter_mut() {
        for k in 1..l.len() {
            let prev = l[k - 1].trim_start_matches(['"', '\'']);
            let cap = if prev == "run" || (prev == "every" && l.iter().any(|w| w.ends_with("run")))
            {
                MAX_RUN_STEPS
            } else if prev == "ntry" || prev == "ntry_mc" {
                MAX_SAMPLES
            } else {
                continue;
            };
            let digits = l[k].trim_end_matches(['"', '\'']);
            let quotes = &l[k][digits.len()..];
            if let Ok(n) = digits.parse::<i64>() {
                if n > cap {
                    l[k] = format!("{cap}{quotes}");
                }
            }
        }
    }
}

/// Apply one to three random edits to a deck, a data file or a dump (comment lines are left
/// alone): half of them put an extreme value in place of a number, the rest delete,
/// duplicate or swap words or lines, or cut the text short or put bytes that are not UTF-8
/// into it.
fn mutate(text: &str, rng: &mut Rng) -> Vec<u8> {
    let mut lines = words_of(text);
    let positions = |lines: &[Vec<String>]| -> Vec<(usize, usize)> {
        lines
            .iter()
            .enumerate()
            .filter(|(_, l)| {
                !l.first()
                    .is_some_and(|w| w.starts_with('#') || control_flow(w))
            })
            .flat_map(|(i, l)| (0..l.len()).map(move |k| (i, k)))
            .collect()
    };
    let mut raw_edit: Option<u8> = None;
    let edits = *rng.pick(&[1, 1, 1, 1, 1, 1, 2, 2, 2, 3]);
    for _ in 0..edits {
        let pos = positions(&lines);
        if pos.is_empty() {
            break;
        }
        let (i, k) = *rng.pick(&pos);
        let numbers: Vec<(usize, usize)> = pos
            .iter()
            .copied()
            .filter(|&(a, b)| is_number(&lines[a][b]))
            .collect();
        match rng.below(20) {
            0..=5 if numbers.iter().any(|&(a, _)| !unbounded(&lines[a][0])) => {
                let bounded: Vec<(usize, usize)> = numbers
                    .iter()
                    .copied()
                    .filter(|&(a, _)| !unbounded(&lines[a][0]))
                    .collect();
                let (a, b) = *rng.pick(&bounded);
                lines[a][b] = rng.pick(EXTREMES).to_string();
            }
            6..=7 if !numbers.is_empty() => {
                let (a, b) = *rng.pick(&numbers);
                lines[a][b] = rng.pick(NOT_NUMBERS).to_string();
            }
            8..=9 => {
                // not where a count is work to do (tries), which is slow in any program
                let work = |a: usize, b: usize| {
                    b > 0 && matches!(lines[a][b - 1].as_str(), "ntry_mc" | "maxattempt")
                };
                let counts: Vec<(usize, usize)> = numbers
                    .iter()
                    .copied()
                    .filter(|&(a, b)| !unbounded(&lines[a][0]) && !work(a, b))
                    .collect();
                if !counts.is_empty() {
                    let (a, b) = *rng.pick(&counts);
                    lines[a][b] = rng.pick(HUGE_COUNTS).to_string();
                }
            }
            10..=11 => {
                lines[i].remove(k);
            }
            12..=13 => {
                let w = lines[i][k].clone();
                lines[i].insert(k, w);
            }
            14..=15 => {
                let (j, m) = *rng.pick(&pos);
                let w = std::mem::take(&mut lines[i][k]);
                let v = std::mem::replace(&mut lines[j][m], w);
                lines[i][k] = v;
            }
            16 => {
                let l = lines[i].clone();
                lines.insert(i, l);
            }
            17 => {
                lines.remove(i);
            }
            18 if rng.below(2) == 0 => {
                // every number (outside loops and runs) at once
                let v = rng.pick(EXTREMES).to_string();
                for &(a, b) in &numbers {
                    if !unbounded(&lines[a][0]) {
                        lines[a][b] = v.clone();
                    }
                }
            }
            _ => raw_edit = Some(rng.below(2) as u8),
        }
    }
    cap_runs(&mut lines);
    let mut bytes = join(&lines).into_bytes();
    match raw_edit {
        Some(0) if !bytes.is_empty() => {
            // cut short anywhere, even inside a word or a quote (but not inside a jump:
            // `jump SELF label` cut to `jump SELF` loops for ever, in LIGGGHTS too)
            let mut at = rng.below(bytes.len());
            let line_start = bytes[..at]
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |k| k + 1);
            let line = String::from_utf8_lossy(&bytes[line_start..at]).into_owned();
            if line.split_whitespace().next().is_some_and(control_flow) {
                at = line_start;
            }
            bytes.truncate(at);
        }
        Some(_) => {
            // bytes that are not UTF-8
            let bad: &[&[u8]] = &[
                b"\xff",
                b"\xfe\xfe",
                b"\xc3\x28",
                b"\xe2\x82",
                b"\x00",
                b"\xed\xa0\x80",
            ];
            let at = rng.below(bytes.len() + 1);
            let b = rng.pick(bad);
            bytes.splice(at..at, b.iter().copied());
        }
        None => {}
    }
    bytes
}

/// One invocation's result.
struct Outcome {
    status: Option<i32>,
    signal: Option<i32>,
    stdout: String,
    stderr: String,
    hung: bool,
}

/// Run the binary with `args` in `dir` under the time and memory limits.
fn run(dir: &Path, args: &[&str]) -> Outcome {
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {MEMORY_LIMIT_KB}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_regolith"))
        .args(args)
        .current_dir(dir)
        .env("RUST_BACKTRACE", "0")
        .env_remove("REGOLITH_PARALLEL_PAIRS")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let read = |r: Option<Box<dyn std::io::Read + Send>>| {
        std::thread::spawn(move || {
            let mut s = Vec::new();
            if let Some(mut r) = r {
                let _ = r.read_to_end(&mut s);
            }
            String::from_utf8_lossy(&s).into_owned()
        })
    };
    let out = read(child.stdout.take().map(|s| Box::new(s) as _));
    let err = read(child.stderr.take().map(|s| Box::new(s) as _));
    let start = Instant::now();
    let mut hung = false;
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > TIME_LIMIT {
            hung = true;
            let _ = child.kill();
            break child.wait().unwrap();
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    use std::os::unix::process::ExitStatusExt;
    Outcome {
        status: status.code(),
        signal: status.signal(),
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
        hung,
    }
}

/// Does `text` name a place `FILE:LINE` (the deck, or a file it includes)?
fn names_a_line(text: &str) -> bool {
    text.match_indices(':').any(|(i, _)| {
        // the word before the colon names a file: it has a letter, a dot or a slash
        let word = text[..i].rsplit(char::is_whitespace).next().unwrap_or("");
        let file_like = word
            .chars()
            .any(|c| c.is_alphabetic() || c == '.' || c == '/');
        let after = text[i + 1..].chars().next();
        file_like && after.is_some_and(|c| c.is_ascii_digit())
    })
}

/// A word that is a NaN or an infinity as C and Rust print them.
fn non_finite_word(text: &str) -> Option<String> {
    text.split(|c: char| c.is_whitespace() || c == ',' || c == '[' || c == ']' || c == '"')
        .find(|w| {
            let w = w.trim_start_matches(['-', '+']).to_ascii_lowercase();
            w == "nan" || w == "inf" || w == "infinity"
        })
        .map(str::to_string)
}

/// Thermo blocks of a screen output (header to `Loop time`).
fn thermo_text(stdout: &str) -> String {
    let mut out = String::new();
    let mut inside = false;
    for l in stdout.lines() {
        if l.starts_with("Loop time") {
            inside = false;
        }
        if l.trim_start().starts_with("Step") {
            inside = true;
        }
        if inside {
            out.push_str(l);
            out.push('\n');
        }
    }
    out
}

/// Problems with the simulation outputs in `dir` of a run that exited 0: non-finite values
/// in dumps, data files and restart files.
fn output_problems(dir: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    let mut files = Vec::new();
    collect(dir, &mut files);
    for f in files {
        let name = f.to_string_lossy().into_owned();
        let base = f.file_name().unwrap().to_string_lossy().into_owned();
        // the inputs of the case (the deck, the corrupted file, meshes) are not outputs
        if base.starts_with("in.") || base.starts_with("f.") || base.ends_with(".stl") {
            continue;
        }
        let Ok(bytes) = std::fs::read(&f) else {
            continue;
        };
        if bytes.starts_with(b"ITEM:") || base.ends_with(".data") || base.ends_with(".vtk") {
            let text = String::from_utf8_lossy(&bytes);
            if let Some(w) = non_finite_word(&text) {
                problems.push(format!("{name} holds '{w}'"));
            }
        } else if base.contains("restart") || base.ends_with(".rst") {
            if let Ok(r) = regolith::io::restart::Restart::parse(&bytes, &name, None) {
                let bad = r.atoms.iter().find(|a| {
                    !a.x.iter()
                        .chain(&a.v)
                        .chain(&a.omega)
                        .chain([&a.radius, &a.mass])
                        .all(|c| c.is_finite())
                });
                if let Some(a) = bad {
                    problems.push(format!("{name}: atom {} is not finite", a.id));
                }
            }
        }
    }
    problems
}

fn collect(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            collect(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// The verdict on one invocation: None if it kept every promise.
fn judge(
    o: &Outcome,
    file: &str,
    line_numbers: bool,
    dir: &Path,
    check_outputs: bool,
) -> Option<String> {
    let all = format!("{}{}", o.stdout, o.stderr);
    if o.hung {
        return Some(format!("no end within {TIME_LIMIT:?} (a hang)"));
    }
    if let Some(s) = o.signal {
        return Some(format!("killed by signal {s} (an abort?)"));
    }
    if o.status == Some(101) || all.contains("panicked") {
        return Some("panicked".into());
    }
    match o.status {
        Some(0) => {
            if check_outputs {
                if let Some(w) = non_finite_word(&thermo_text(&o.stdout)) {
                    return Some(format!("exit 0 with '{w}' in the thermo output"));
                }
                let p = output_problems(dir);
                if !p.is_empty() {
                    return Some(format!("exit 0 with {}", p.join("; ")));
                }
            }
            None
        }
        // `quit`: status 1 without an error (every error is written to standard error)
        Some(1) if o.stderr.trim().is_empty() => None,
        Some(_) => {
            let located = if line_numbers {
                names_a_line(&all)
            } else {
                all.contains(file)
            };
            (!located).then(|| format!("exit {:?} without naming {file} and a line", o.status))
        }
        None => Some("no exit status".into()),
    }
}

/// Record a failure for the report (and as a file to reproduce it).
fn fail(
    failures: &mut Vec<String>,
    kind: &str,
    case: usize,
    what: &str,
    args: &[&str],
    input: &[u8],
    o: &Outcome,
) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/fuzz-failures");
    let _ = std::fs::create_dir_all(&root);
    let keep = root.join(format!("{kind}-{case}"));
    let _ = std::fs::write(&keep, input);
    failures.push(format!(
        "{kind} case {case}: {what}\n  regolith {}\n  input kept in {}\n  stderr: {}",
        args.join(" "),
        keep.display(),
        o.stderr
            .lines()
            .take(6)
            .collect::<Vec<_>>()
            .join("\n          ")
    ));
}

/// A folder for one test's cases, removed when the test ends.
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn scratch(name: &str) -> Scratch {
    let d = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-fuzz-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    Scratch(d)
}

fn copy_tree(from: &Path, to: &Path) {
    let Ok(entries) = std::fs::read_dir(from) else {
        return;
    };
    for e in entries.flatten() {
        if e.path().is_dir() {
            std::fs::create_dir_all(to.join(e.file_name())).unwrap();
            copy_tree(&e.path(), &to.join(e.file_name()));
        } else {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

/// A clean directory for one case of deck `name` from `folder`, with the deck's side files.
fn stage(work: &Path, folder: &Path, name: &str) {
    let _ = std::fs::remove_dir_all(work);
    std::fs::create_dir_all(work.join("post")).unwrap();
    copy_tree(&folder.join(format!("{name}.inputs")), work);
}

/// The decks of a compat folder: (name, text).
fn decks(folder: &Path) -> Vec<(String, String)> {
    let mut out: Vec<(String, String)> = std::fs::read_dir(folder)
        .unwrap()
        .flatten()
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let deck = name.strip_prefix("in.")?.to_string();
            Some((deck, std::fs::read_to_string(e.path()).ok()?))
        })
        .collect();
    out.sort();
    out
}

/// Mutated decks of `folder`: `cases` of them, each checked and run.
fn fuzz_decks(folder: &str, kind: &str, seed: u64, cases: usize) {
    let (seed, cases) = plan(seed, cases);
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let seeds = decks(&folder);
    let work = scratch(kind);
    let mut rng = Rng(seed);
    let mut failures = Vec::new();
    let (mut rejected, mut ran) = (0, 0);
    let start = Instant::now();
    for case in 0..cases {
        let (name, text) = rng.pick(&seeds).clone();
        // shell commands run arbitrary programs: not in decks that are run mutated
        let text: String = text
            .lines()
            .filter(|l| !l.trim_start().starts_with("shell"))
            .map(|l| format!("{l}\n"))
            .collect();
        let mut lines = words_of(&text);
        cap_runs(&mut lines);
        let deck = mutate(&join(&lines), &mut rng);
        for mode in ["check", "run"] {
            stage(&work, &folder, &name);
            std::fs::write(work.join("in.fuzz"), &deck).unwrap();
            let args: &[&str] = if mode == "check" {
                &["check", "in.fuzz"]
            } else {
                &["-in", "in.fuzz", "-log", "log.fuzz", "-echo", "none"]
            };
            let t0 = Instant::now();
            let o = run(&work, args);
            if std::env::var_os("REGOLITH_FUZZ_VERBOSE").is_some() {
                eprintln!(
                    "{kind} {case} {name} {mode} {:.2}: {:?} {}",
                    t0.elapsed().as_secs_f64(),
                    o.status,
                    o.stderr.lines().next().unwrap_or("")
                );
            }
            if let Some(what) = judge(&o, "in.fuzz", true, &work, mode == "run") {
                fail(
                    &mut failures,
                    kind,
                    case,
                    &format!("{mode} of mutated {name}: {what}"),
                    args,
                    &deck,
                    &o,
                );
            } else if mode == "run" {
                if o.status == Some(0) {
                    ran += 1;
                } else {
                    rejected += 1;
                }
            }
        }
    }
    eprintln!(
        "{kind}: {cases} mutated decks, each checked and run ({ran} ran cleanly, {rejected} refused with a located error) in {:.0?}",
        start.elapsed()
    );
    assert!(
        failures.is_empty(),
        "{} of {cases} cases failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn mutated_engine_decks() {
    fuzz_decks("compat/engine", "engine", 0x5EED_0001, 1500);
}

#[test]
fn mutated_script_decks() {
    fuzz_decks("compat/script", "script", 0x5EED_0002, 600);
}

/// Materials, pair style and integration for the two atom types of the seed files.
const CONTINUE: &str = "fix m1 all property/global youngsModulus peratomtype 5e6 5e6
fix m2 all property/global poissonsRatio peratomtype 0.3 0.3
fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5
fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5
pair_style gran model hertz tangential history
pair_coeff * *
neighbor 0.001 bin
neigh_modify delay 0
fix gr all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
timestep 1e-6
thermo_style custom step atoms ke
thermo 1
run 5
write_data out.data
write_restart out.restart
";

/// A corrupted file read by `convert` (into `to`) and by a deck (`head` then [`CONTINUE`]),
/// checked and run; the verdicts, or None.
fn read_corrupted(
    work: &Path,
    file: &str,
    bytes: &[u8],
    to: &str,
    convert_extra: &[&str],
    head: &str,
) -> Vec<(String, Vec<String>, Outcome)> {
    let mut problems = Vec::new();
    let _ = std::fs::remove_dir_all(work);
    std::fs::create_dir_all(work).unwrap();
    std::fs::write(work.join(file), bytes).unwrap();
    let mut args = vec!["convert", file, to];
    args.extend_from_slice(convert_extra);
    let o = run(work, &args);
    if let Some(what) = judge(&o, file, false, work, true) {
        problems.push((
            format!("convert: {what}"),
            args.iter().map(|a| a.to_string()).collect(),
            o,
        ));
    }
    std::fs::write(work.join("in.read"), format!("{head}{CONTINUE}")).unwrap();
    for args in [
        &["check", "in.read"][..],
        &["-in", "in.read", "-log", "none", "-echo", "none"],
    ] {
        let o = run(work, args);
        if std::env::var_os("REGOLITH_FUZZ_VERBOSE").is_some() {
            eprintln!(
                "{file} {}: {:?} {}",
                args[0],
                o.status,
                o.stderr.lines().next().unwrap_or("")
            );
        }
        if let Some(what) = judge(&o, "in.read", true, work, args[0] == "-in") {
            problems.push((what, args.iter().map(|a| a.to_string()).collect(), o));
        }
    }
    problems
}

fn seed_file(path: &str) -> Vec<u8> {
    std::fs::read(Path::new(env!("CARGO_MANIFEST_DIR")).join(path)).unwrap()
}

const BAD_DOUBLES: &[f64] = &[
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e300,
    -1e300,
    0.0,
    -0.0,
    -1.0,
    4.9e-324,
    1e30,
    2147483648.0,
    -2147483649.0,
];

const BAD_INTS: &[i32] = &[i32::MIN, -1, 0, i32::MAX, 1 << 30, 65536, 2, 17];

/// Restart files truncated, with bytes flipped, or extreme values written into their header
/// (ints) and atoms (doubles); read by `convert` and by a deck that continues the run.
#[test]
fn corrupted_restart_files() {
    let seeds = [
        seed_file("compat/convert/bed.restart"),
        seed_file("compat/engine/liggghts_reads.inputs/regolith.restart"),
    ];
    let work = scratch("restart");
    let (seed, cases) = plan(0x5EED_0003, 1500);
    let mut rng = Rng(seed);
    let mut failures = Vec::new();
    let start = Instant::now();
    for case in 0..cases {
        let mut b = rng.pick(&seeds).clone();
        // the atoms are the file's last n doubles after an int n
        let chunk = 8 * (b.len() - 4) / 8;
        let atoms_at = b.len() - chunk.min(b.len() / 2);
        for _ in 0..*rng.pick(&[1, 1, 1, 2, 2, 3]) {
            match rng.below(10) {
                0 => {
                    let at = rng.below(b.len());
                    b.truncate(at);
                }
                1..=2 => {
                    let at = rng.below(b.len().max(1));
                    if at < b.len() {
                        b[at] ^= 1 + rng.below(255) as u8;
                    }
                }
                3..=7 => {
                    // an atom value (aligned to the atom records at the file's end)
                    let n = b.len().saturating_sub(atoms_at) / 8;
                    if n > 0 {
                        let at = b.len() - 8 * (1 + rng.below(n));
                        b[at..at + 8].copy_from_slice(&rng.pick(BAD_DOUBLES).to_le_bytes());
                    }
                }
                _ => {
                    // a header int or count
                    let end = atoms_at.min(b.len()).saturating_sub(4);
                    if end > 0 {
                        let at = rng.below(end / 4) * 4;
                        b[at..at + 4].copy_from_slice(&rng.pick(BAD_INTS).to_le_bytes());
                    }
                }
            }
        }
        let head = "read_restart f.restart\natom_modify sort 0 0\ncommunicate single vel yes\n";
        for (what, args, o) in read_corrupted(&work, "f.restart", &b, "o.data", &[], head) {
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            fail(&mut failures, "restart", case, &what, &args, &b, &o);
        }
    }
    eprintln!(
        "restart: {cases} corrupted restart files, each converted, checked and run, in {:.0?}",
        start.elapsed()
    );
    assert!(
        failures.is_empty(),
        "{} of {cases} cases failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// Data files and dumps mutated like decks (words, extreme numbers, truncation, bytes that
/// are not UTF-8): data files converted to restarts and read by a deck that runs them;
/// dumps converted to VTK and compared with `diff`.
#[test]
fn corrupted_data_files_and_dumps() {
    let data_seeds = [
        String::from_utf8(seed_file("compat/convert/bed.data")).unwrap(),
        String::from_utf8(seed_file("compat/engine/data_files.inputs/bed.data")).unwrap(),
    ];
    let dump_seeds = [
        "compat/engine/freefall.ref/post/freefall.dump",
        "compat/engine/hysteresis.ref/post/contacts.dump",
        "compat/engine/insert_stream_all_in.ref/post/all_in_2000.dump",
    ];
    let work = scratch("data");
    let (seed, data_cases) = plan(0x5EED_0004, 800);
    let dump_cases = plan(0, 1000).1;
    let mut rng = Rng(seed);
    let mut failures = Vec::new();
    let start = Instant::now();
    for case in 0..data_cases {
        let text = rng.pick(&data_seeds).clone();
        let b = mutate(&text, &mut rng);
        let head = "atom_style granular\natom_modify map array sort 0 0\nboundary p p f\n\
                    newton off\ncommunicate single vel yes\nread_data f.data\n";
        let extra = ["--boundary", "p p f"];
        for (what, args, o) in read_corrupted(&work, "f.data", &b, "o.restart", &extra, head) {
            let args: Vec<&str> = args.iter().map(String::as_str).collect();
            fail(&mut failures, "data", case, &what, &args, &b, &o);
        }
    }
    for case in 0..dump_cases {
        let path = *rng.pick(&dump_seeds);
        let original = seed_file(path);
        let b = mutate(&String::from_utf8_lossy(&original), &mut rng);
        let _ = std::fs::remove_dir_all(&work);
        std::fs::create_dir_all(&work).unwrap();
        std::fs::write(work.join("f.dump"), &b).unwrap();
        std::fs::write(work.join("orig.dump"), &original).unwrap();
        for args in [
            &["convert", "f.dump", "o_*.vtk"][..],
            &["diff", "f.dump", "orig.dump"],
        ] {
            let o = run(&work, args);
            // diff: 0 same, 1 different, 2 unreadable (which must name the file)
            let verdict = match o.status {
                Some(1) if args[0] == "diff" && !o.hung => None,
                _ => judge(&o, "f.dump", false, &work, false),
            };
            if let Some(what) = verdict {
                fail(
                    &mut failures,
                    "dump",
                    case,
                    &format!("{}: {what}", args[0]),
                    args,
                    &b,
                    &o,
                );
            }
        }
    }
    eprintln!(
        "data: {data_cases} mutated data files (converted, checked, run) and {dump_cases} mutated dumps (converted, compared) in {:.0?}",
        start.elapsed()
    );
    let cases = data_cases + dump_cases;
    assert!(
        failures.is_empty(),
        "{} of {cases} cases failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// The verdicts themselves: what counts as a located error and as a non-finite output.
#[test]
fn the_judge_sees_what_it_must() {
    assert!(names_a_line(
        "ERROR: Illegal run command\n  --> in.fuzz:12\n"
    ));
    assert!(names_a_line("in.fuzz:3: Unknown command: foo"));
    assert!(!names_a_line("ERROR: Illegal run command\n"));
    assert!(!names_a_line("time 12:30 and a: 5"));
    for bad in ["-nan", "nan", "inf", "-inf", "NaN", "[NaN,"] {
        assert!(
            non_finite_word(&format!("  20 2 {bad} 0.5")).is_some(),
            "{bad}"
        );
    }
    for fine in ["info", "infinite-loop", "nanometre", "0.5e-3", "Inf0"] {
        assert_eq!(non_finite_word(&format!("  20 2 {fine}")), None, "{fine}");
    }
    let screen =
        "Setting up\n    Step Atoms KinEng\n       0 2 -nan\nLoop time of 0.1\nnan later\n";
    assert_eq!(
        thermo_text(screen),
        "    Step Atoms KinEng\n       0 2 -nan\n"
    );
    let mut lines = words_of("if \"${p} == 1\" then \"run 21001\" \"print x\" else 'run 16000'\n");
    cap_runs(&mut lines);
    assert_eq!(
        join(&lines),
        "if \"${p} == 1\" then \"run 40\" \"print x\" else 'run 40'\n"
    );
    let mut rng = Rng(7);
    let deck = "# a comment 5\njump SELF loop\nregion reg block 0 1 0 1 0 1\nrun 100000\n";
    for _ in 0..200 {
        let m = String::from_utf8_lossy(&mutate(deck, &mut rng)).into_owned();
        // control flow and comments are left alone; runs stay short
        assert!(!m.lines().any(|l| l == "jump SELF" || l == "jump"), "{m}");
        let long = |l: &str| l.starts_with("run") && l.split_whitespace().nth(1) == Some("100000");
        assert!(!m.lines().any(long), "{m}");
    }
}
