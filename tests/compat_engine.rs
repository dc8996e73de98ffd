//! The engine against Debian's LIGGGHTS: each deck in compat/engine/ runs in regolith as
//! compat/regenerate.sh ran it in liggghts; every dump must agree atom by atom within
//! relative 1e-6 and every thermo line must be identical to the printed precision.

use std::path::{Path, PathBuf};
use std::process::Command;

mod common;

use common::{
    copy_tree, engine_deck_copy, engine_decks, engine_dir, fastcheck_dumps, first_hundred_steps,
    snapshots_deviation, thermo_lines,
};
use regolith::io::dump_compare::{compare, parse};

const RTOL: f64 = 1e-6;
const ATOL: f64 = 1e-12;

/// Decks named by `REGOLITH_ENGINE_DECKS` (comma-separated), or all.
fn selected(deck: &str) -> bool {
    std::env::var("REGOLITH_ENGINE_DECKS").map_or(true, |v| v.split(',').any(|d| d == deck))
}

/// The lines of a `dump local` file, entry lines sorted within each snapshot.
fn local_entries(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut entries: Vec<String> = Vec::new();
    let mut inside = false;
    for line in text.lines() {
        if line == "ITEM: TIMESTEP" {
            entries.sort();
            out.append(&mut entries);
            inside = false;
        }
        if inside {
            entries.push(line.to_string());
        } else {
            out.push(line.to_string());
        }
        if line.starts_with("ITEM: ENTRIES") {
            inside = true;
        }
    }
    entries.sort();
    out.append(&mut entries);
    out
}

fn files_below(dir: &Path, base: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files_below(&p, base, out);
        } else {
            out.push(p.strip_prefix(base).unwrap().to_path_buf());
        }
    }
}

fn check_deck(name: &str) -> Vec<String> {
    let dir = engine_dir();
    let work = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-engine-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).unwrap();
    let deck = format!("in.{name}");
    std::fs::copy(dir.join(&deck), work.join(&deck)).unwrap();
    let inputs = dir.join(format!("{name}.inputs"));
    if inputs.is_dir() {
        copy_tree(&inputs, &work);
    }
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["-in", &deck, "-log", "none"])
        .current_dir(&work)
        .output()
        .unwrap();
    let mut problems = Vec::new();
    if !out.status.success() {
        problems.push(format!(
            "exit status {:?}: {}",
            out.status.code(),
            String::from_utf8_lossy(&out.stderr)
        ));
        return problems;
    }
    let reference = dir.join(format!("{name}.ref"));
    let want = std::fs::read_to_string(reference.join("thermo.txt")).unwrap();
    let got = thermo_lines(&String::from_utf8_lossy(&out.stdout));
    let want: Vec<&str> = want.lines().collect();
    if got != want {
        let k = got.iter().zip(&want).take_while(|(a, b)| a == b).count();
        problems.push(format!(
            "thermo line {} differs:\n  liggghts: {:?}\n  regolith: {:?}",
            k + 1,
            want.get(k),
            got.get(k)
        ));
    }
    let mut files = Vec::new();
    files_below(&reference, &reference, &mut files);
    for f in files.iter().filter(|f| f.as_os_str() != "thermo.txt") {
        let bytes = std::fs::read(reference.join(f)).unwrap();
        let gzipped = f.extension().is_some_and(|e| e == "gz");
        if !gzipped
            && (f.extension().is_some_and(|e| e == "bin") || std::str::from_utf8(&bytes).is_err())
        {
            // LAMMPS's binary dumps and binary VTK files: byte for byte
            let want = bytes;
            let got = std::fs::read(work.join(f)).unwrap_or_default();
            if got != want {
                let k = want.iter().zip(&got).take_while(|(x, y)| x == y).count();
                problems.push(format!(
                    "{} differs from byte {k} ({} bytes, liggghts {})",
                    f.display(),
                    got.len(),
                    want.len()
                ));
            }
            continue;
        }
        // a gzipped reference stands for the plain file the deck writes
        let (want, f) = if f.extension().is_some_and(|e| e == "gz") {
            let text = regolith::io::diff::read_text(&reference.join(f).to_string_lossy()).unwrap();
            (text, &f.with_extension(""))
        } else {
            (std::fs::read_to_string(reference.join(f)).unwrap(), f)
        };
        if f.extension().is_some_and(|e| e == "vtr" || e == "pvtr") {
            // VTK names a box's coordinate arrays after their addresses (`Array 0x...`): the
            // files agree but for those names
            let unnamed = |t: &str| {
                t.lines()
                    .map(|l| match l.find(" Name=\"") {
                        Some(k) => {
                            let rest = &l[k + 7..];
                            let end = rest.find('"').map_or(rest.len(), |e| e + 1);
                            format!("{}{}", &l[..k], &rest[end..])
                        }
                        None => l.to_string(),
                    })
                    .collect::<Vec<_>>()
            };
            let got = std::fs::read_to_string(work.join(f)).unwrap_or_default();
            if unnamed(&got) != unnamed(&want) {
                problems.push(format!(
                    "{} differs:\n  liggghts: {want:?}\n  regolith: {got:?}",
                    f.display()
                ));
            }
            continue;
        }
        if f.extension().is_some_and(|e| e == "stats") {
            // end-of-run statistics of chaotic decks: each value within 1 %
            let got = std::fs::read_to_string(work.join(f)).unwrap_or_default();
            let parse = |t: &str| {
                t.split_whitespace()
                    .filter_map(|w| w.parse::<f64>().ok())
                    .collect::<Vec<_>>()
            };
            let (a, b) = (parse(&want), parse(&got));
            let close = a.len() == b.len()
                && a.iter()
                    .zip(&b)
                    .all(|(x, y)| (x - y).abs() <= 0.01 * x.abs().max(y.abs()));
            if !close {
                problems.push(format!(
                    "{} beyond 1 %:\n  liggghts: {want:?}\n  regolith: {got:?}",
                    f.display()
                ));
            }
            continue;
        }
        if want.contains("ITEM: ENTRIES") && !f.to_string_lossy().contains(".exact.") {
            // dump local: the same entries per snapshot, in any order (entries start with
            // the atom IDs); values as printed, or within RTOL when printed with more digits
            // than the decks stay bit-identical for
            let got = std::fs::read_to_string(work.join(f)).unwrap_or_default();
            let (a, b) = (local_entries(&got), local_entries(&want));
            let same_line = |x: &String, y: &String| {
                x == y || {
                    let (xs, ys): (Vec<&str>, Vec<&str>) = (
                        x.split_whitespace().collect(),
                        y.split_whitespace().collect(),
                    );
                    xs.len() == ys.len()
                        && xs.iter().zip(&ys).all(|(u, v)| {
                            u == v
                                || matches!((u.parse::<f64>(), v.parse::<f64>()),
                                    (Ok(p), Ok(q)) if (p - q).abs() <= RTOL * p.abs().max(q.abs()))
                        })
                }
            };
            if a.len() != b.len() || !a.iter().zip(&b).all(|(x, y)| same_line(x, y)) {
                problems.push(format!("{} (dump local) differs", f.display()));
            }
            continue;
        }
        if !want.starts_with("ITEM:") {
            // not a dump: printed values, compared exactly (a data file's title line names
            // the program that wrote it)
            let got = std::fs::read_to_string(work.join(f)).unwrap_or_default();
            let title = "LAMMPS data file via write_data";
            let stl = f.extension().is_some_and(|e| e == "stl");
            if (want.starts_with(title) && got.starts_with(title)) || stl {
                // data files: the same words, numbers within RTOL (17 printed digits show
                // the round-off of periodic pairs)
                let body = |t: &str| {
                    let t = if stl {
                        Some(("", t))
                    } else {
                        t.split_once('\n')
                    };
                    t.map(|(_, b)| b.split_whitespace().map(str::to_string).collect::<Vec<_>>())
                        .unwrap_or_default()
                };
                let (a, b) = (body(&want), body(&got));
                let close = |x: &String, y: &String| match (x.parse::<f64>(), y.parse::<f64>()) {
                    (Ok(u), Ok(v)) => (u - v).abs() <= ATOL.max(RTOL * u.abs().max(v.abs())),
                    _ => x == y,
                };
                if a.len() != b.len() || !a.iter().zip(&b).all(|(x, y)| close(x, y)) {
                    let k = a.iter().zip(&b).take_while(|(x, y)| close(x, y)).count();
                    problems.push(format!(
                        "{} differs at word {k}: liggghts {:?}, regolith {:?}",
                        f.display(),
                        a.get(k),
                        b.get(k)
                    ));
                }
                continue;
            }
            if got != want {
                problems.push(format!(
                    "{} differs:\n  liggghts: {want:?}\n  regolith: {got:?}",
                    f.display()
                ));
            }
            continue;
        }
        if f.to_string_lossy().contains(".exact.") {
            // dumps a deck declares bit-identical (17 significant digits): byte for byte
            let got = std::fs::read_to_string(work.join(f)).unwrap_or_default();
            if got != want {
                let k = want
                    .lines()
                    .zip(got.lines())
                    .take_while(|(x, y)| x == y)
                    .count();
                problems.push(format!(
                    "{} differs from line {}: liggghts {:?}, regolith {:?}",
                    f.display(),
                    k + 1,
                    want.lines().nth(k),
                    got.lines().nth(k)
                ));
            }
            continue;
        }
        let a = parse(&want).unwrap();
        let Ok(text) = std::fs::read_to_string(work.join(f)) else {
            problems.push(format!("{} not written", f.display()));
            continue;
        };
        let b = match parse(&text) {
            Ok(b) => b,
            Err(e) => {
                problems.push(format!("{}: {e}", f.display()));
                continue;
            }
        };
        let d = compare(&a, &b, ATOL);
        if !d.mismatches.is_empty() || d.max_rel > RTOL {
            problems.push(format!(
                "{}: max relative deviation {:e} at {:?}; {:?}",
                f.display(),
                d.max_rel,
                d.worst,
                d.mismatches
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&work);
    problems
}

#[test]
fn engine_decks_match_liggghts() {
    let decks: Vec<String> = engine_decks().into_iter().filter(|d| selected(d)).collect();
    assert!(!decks.is_empty());
    let failures: Vec<String> = decks
        .iter()
        .filter_map(|d| {
            let p = check_deck(d);
            (!p.is_empty()).then(|| format!("{d}:\n  {}", p.join("\n  ")))
        })
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Run `deck_text` (named `in.NAME`) in a fresh copy of the deck's folder with `flags`;
/// (exit success, stdout, the folder).
fn run_in_copy(name: &str, deck_text: &str, flags: &[&str], tag: &str) -> (bool, String, PathBuf) {
    let work = engine_deck_copy(name, deck_text, tag);
    let deck = format!("in.{name}");
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(flags)
        .args(["-in", &deck, "-log", "none"])
        .current_dir(&work)
        .output()
        .unwrap();
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        work,
    )
}

/// The fast path against the exact path over the first 100 steps of every engine deck
/// (only the order of summation differs: every dumped value within 1e-10 of its column's
/// largest magnitude), and every deck run to its end on the fast path with two threads.
#[test]
fn engine_decks_on_the_fast_path() {
    let decks: Vec<String> = engine_decks().into_iter().filter(|d| selected(d)).collect();
    let fast = ["-sf", "fast", "-pk", "fast", "2"];
    let mut failures = Vec::new();
    let mut compared = 0;
    for name in &decks {
        let text = std::fs::read_to_string(engine_dir().join(format!("in.{name}"))).unwrap();
        // the whole deck runs on the fast path
        let (ok, stdout, work) = run_in_copy(name, &text, &fast, "fast");
        let _ = std::fs::remove_dir_all(&work);
        if !ok {
            failures.push(format!(
                "{name}: the fast path failed: {}",
                stdout.lines().rev().take(3).collect::<Vec<_>>().join(" | ")
            ));
            continue;
        }
        // the first hundred steps against the exact path
        let Some(early) = first_hundred_steps(&text) else {
            continue;
        };
        let (ok_e, _, work_e) = run_in_copy(name, &early, &[], "e100");
        let (ok_f, _, work_f) = run_in_copy(name, &early, &fast, "f100");
        if ok_e && ok_f {
            let (a, b) = (fastcheck_dumps(&work_e), fastcheck_dumps(&work_f));
            if !a.is_empty() {
                compared += 1;
                match snapshots_deviation(&a, &b) {
                    Ok(d) if d <= 1e-10 => {}
                    Ok(d) => {
                        failures.push(format!("{name}: fast vs exact {d:e} of a column's scale"))
                    }
                    Err(e) => failures.push(format!("{name}: fast vs exact: {e}")),
                }
            }
        } else if ok_e != ok_f {
            failures.push(format!(
                "{name}: first 100 steps: exact ok {ok_e}, fast ok {ok_f}"
            ));
        }
        let _ = std::fs::remove_dir_all(&work_e);
        let _ = std::fs::remove_dir_all(&work_f);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    // most decks have a top-level first run
    assert!(
        compared * 3 >= decks.len() * 2,
        "only {compared} of {} decks compared",
        decks.len()
    );
}

/// `fix move wiggle` is matched to the last bit: the tapped bed in a box without periodic
/// faces gives LIGGGHTS's dumps byte for byte (printed with 17 digits) for 4 000 steps.
#[test]
fn fix_move_wiggle_is_bit_identical_to_liggghts() {
    let name = "move_wiggle_closed";
    let text = std::fs::read_to_string(engine_dir().join(format!("in.{name}"))).unwrap();
    let (ok, stdout, work) = run_in_copy(name, &text, &[], "bits");
    assert!(ok, "the deck failed:\n{stdout}");
    let reference = engine_dir().join(format!("{name}.ref/post"));
    let mut checked = 0;
    for e in std::fs::read_dir(&reference).unwrap() {
        let e = e.unwrap();
        let want = std::fs::read(e.path()).unwrap();
        let got = std::fs::read(work.join("post").join(e.file_name())).unwrap_or_default();
        assert!(want == got, "{:?} differs from LIGGGHTS's", e.file_name());
        checked += 1;
    }
    assert_eq!(checked, 5, "dumps at steps 0, 1000, ..., 4000");
    let _ = std::fs::remove_dir_all(&work);
}
