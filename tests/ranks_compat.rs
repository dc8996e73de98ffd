//! The engine decks on several ranks: the first 100 steps of every deck in compat/engine/
//! with a top-level first run (cut as `compat_engine` cuts them, every particle dumped every
//! 10 steps at full precision) on the serial fast path and on 2 and 3 ranks (in-process:
//! N ranks are N threads, one engine thread each). Each deck either runs on both rank counts
//! with every dumped value within 1e-10 of its column's scale of the serial run, or is
//! refused on ranks by name ("... on more than one MPI rank: not supported yet"); anything
//! else (a disagreement, a crash, a hang, an error that names nothing) fails the test.
//!
//! The decks name their files relative to their folder and a run resolves them from the
//! process's working directory (`DeckOptions` has no folder of its own), so this file holds a
//! single test that moves the process's working directory from deck copy to deck copy, one
//! deck at a time: no other test of this binary runs meanwhile.

mod common;

use std::path::{Path, PathBuf};
use std::sync::mpsc::RecvTimeoutError;
use std::time::Duration;

use common::{engine_deck_copy, engine_decks, engine_dir, fastcheck_dumps, first_hundred_steps};
use regolith::cli::DeckOptions;
use regolith::error::ExitStatus;
use regolith::util::comm::Ranks;

/// The rank counts each deck runs on.
const RANKS: [usize; 2] = [2, 3];

/// At least this many decks run on every rank count and agree with one process.
const AGREEING_AT_LEAST: usize = 92;

/// How long one 100-step run may take before it counts as a hang.
const HANG: Duration = Duration::from_secs(120);

/// How one run on ranks ended.
enum Outcome {
    /// It ran; every dumped value within 1e-10 of its column's scale.
    Agrees,
    /// Refused by name: the refusal's first line.
    Refused(String),
    /// Anything else, said.
    Failed(String),
}

/// The options of a run of `deck` on `size` ranks (0: one process), its log in `log`.
fn options(deck: &Path, log: &Path, size: usize, rank: usize) -> DeckOptions {
    DeckOptions {
        input: Some(deck.to_string_lossy().into_owned()),
        log: Some(log.to_string_lossy().into_owned()),
        screen: Some("none".into()),
        fast: true,
        threads: Some(1),
        ranks: Ranks {
            size: size.max(1),
            rank,
            per_node: size.max(1),
        },
        ..DeckOptions::default()
    }
}

/// Run deck `in.NAME` in folder `work` (made the working directory) on `n` ranks (0: one
/// process): Ok(every rank succeeded), Err(what went wrong) for a failure, a panic or a
/// run longer than [`HANG`] (its threads are left behind; the caller stops there).
fn run(name: &str, work: &Path, n: usize) -> Result<bool, String> {
    std::env::set_current_dir(work).unwrap();
    let deck = work.join(format!("in.{name}"));
    let log = work.join("log.txt");
    let (tx, rx) = std::sync::mpsc::channel();
    let handle = std::thread::spawn(move || {
        let status = common::run_on_ranks(n, |size, rank| options(&deck, &log, size, rank));
        let _ = tx.send(status);
    });
    match rx.recv_timeout(HANG) {
        Ok(status) => {
            let _ = handle.join();
            Ok(status.iter().all(|s| *s == ExitStatus::Success))
        }
        Err(RecvTimeoutError::Timeout) => Err(format!("no end after {} s", HANG.as_secs())),
        Err(RecvTimeoutError::Disconnected) => {
            let payload = handle.join().err();
            let said = payload
                .as_ref()
                .and_then(|p| {
                    p.downcast_ref::<String>()
                        .cloned()
                        .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                })
                .unwrap_or_default();
            Err(format!("panicked: {said}"))
        }
    }
}

/// Why a run of `in.NAME` in `work` on `n` ranks did not succeed: the deck check's
/// refusals and errors on `n` ranks, else the `ERROR:` line of the run's log.
fn why_not(name: &str, work: &Path, n: usize) -> String {
    let deck = work.join(format!("in.{name}"));
    let text = std::fs::read_to_string(&deck).unwrap();
    let source = regolith::script::interp::Source::from_text(&format!("in.{name}"), &text, false);
    let opts = options(&deck, &work.join("check.txt"), n, 0);
    let found: Vec<String> = regolith::session::check_deck_in(source, &opts, Some(work))
        .iter()
        .filter(|d| d.severity != regolith::error::Severity::Warning)
        .map(|d| d.one_line())
        .collect();
    if let Some(first) = found.first() {
        return first.clone();
    }
    let log = std::fs::read_to_string(work.join("log.txt")).unwrap_or_default();
    log.lines()
        .find_map(|l| l.strip_prefix("ERROR: "))
        .unwrap_or("failed without an error in the log")
        .to_string()
}

/// Does `message` name what is refused and say it does not run on more than one rank yet?
fn refused_by_name(message: &str) -> bool {
    let Some((what, rest)) = message.split_once(" on more than one MPI rank") else {
        return false;
    };
    // "in.NAME:LINE: what" or "what"
    let what = what.rsplit(": ").next().unwrap_or(what).trim();
    !what.is_empty() && rest.contains("not supported yet")
}

/// `in.NAME` cut to its first 100 steps (`early`) on `n` ranks against the serial dumps
/// `serial`.
fn on_ranks(
    name: &str,
    early: &str,
    n: usize,
    serial: &[regolith::io::dump_compare::Snapshot],
) -> Result<Outcome, String> {
    let work = engine_deck_copy(name, early, &format!("ranks{n}"));
    let ran = run(name, &work, n)?;
    let outcome = if ran {
        let got = fastcheck_dumps(&work);
        match common::snapshots_deviation(serial, &got) {
            Ok(d) if d <= 1e-10 => Outcome::Agrees,
            Ok(d) => Outcome::Failed(format!(
                "{n} ranks differ from one process by {d:e} of a column's scale"
            )),
            Err(e) => Outcome::Failed(format!("{n} ranks against one process: {e}")),
        }
    } else {
        let why = why_not(name, &work, n);
        if refused_by_name(&why) {
            Outcome::Refused(why)
        } else {
            Outcome::Failed(format!("{n} ranks: {why}"))
        }
    };
    let _ = std::fs::remove_dir_all(&work);
    Ok(outcome)
}

/// The message without its `in.NAME:LINE: ` prefix and help.
fn reason(message: &str) -> &str {
    let m = message.split_once(": ").map_or(message, |(_, r)| r);
    let m = m.split_once(": ").map_or(m, |(l, r)| {
        if l.chars().all(|c| c.is_ascii_digit()) {
            r
        } else {
            m
        }
    });
    m.split(" on more than one MPI rank").next().unwrap_or(m)
}

#[test]
fn engine_decks_on_two_and_three_ranks_agree_with_one_process() {
    let home: PathBuf = std::env::current_dir().unwrap();
    let only = std::env::var("REGOLITH_ENGINE_DECKS").ok();
    let decks: Vec<String> = engine_decks()
        .into_iter()
        .filter(|d| only.as_ref().is_none_or(|v| v.split(',').any(|x| x == d)))
        .collect();
    let mut agreeing = Vec::new();
    let mut refused: Vec<(String, String)> = Vec::new();
    let mut failures = Vec::new();
    let mut without_run = Vec::new();
    let mut serial_fails = Vec::new();
    'decks: for name in &decks {
        let text = std::fs::read_to_string(engine_dir().join(format!("in.{name}"))).unwrap();
        let Some(early) = first_hundred_steps(&text) else {
            without_run.push(name.clone());
            continue;
        };
        let work = engine_deck_copy(name, &early, "serial");
        match run(name, &work, 0) {
            Ok(true) => {}
            Ok(false) => {
                // the cut deck does not run as one process either (a fix's period that does
                // not fit 100 steps): nothing to compare with
                serial_fails.push(format!("{name}: {}", why_not(name, &work, 1)));
                let _ = std::fs::remove_dir_all(&work);
                continue;
            }
            Err(e) => {
                failures.push(format!("{name}: one process: {e}"));
                break;
            }
        }
        let serial = fastcheck_dumps(&work);
        let _ = std::fs::remove_dir_all(&work);
        let mut outcomes = Vec::new();
        for n in RANKS {
            match on_ranks(name, &early, n, &serial) {
                Ok(o) => outcomes.push(o),
                Err(e) => {
                    // a hang or a panic: the rank threads may still run in the folder
                    failures.push(format!("{name}: {n} ranks: {e}"));
                    break 'decks;
                }
            }
        }
        let failed: Vec<&String> = outcomes
            .iter()
            .filter_map(|o| match o {
                Outcome::Failed(e) => Some(e),
                _ => None,
            })
            .collect();
        let refusal = outcomes.iter().find_map(|o| match o {
            Outcome::Refused(r) => Some(r.clone()),
            _ => None,
        });
        let agree = outcomes
            .iter()
            .filter(|o| matches!(o, Outcome::Agrees))
            .count();
        if !failed.is_empty() {
            for e in failed {
                failures.push(format!("{name}: {e}"));
            }
        } else if agree == RANKS.len() {
            agreeing.push(name.clone());
        } else if agree == 0 {
            refused.push((name.clone(), refusal.unwrap_or_default()));
        } else {
            failures.push(format!(
                "{name}: refused on some rank counts only: {}",
                refusal.unwrap_or_default()
            ));
        }
    }
    std::env::set_current_dir(home).unwrap();
    let mut by_reason: std::collections::BTreeMap<&str, Vec<&str>> = Default::default();
    for (name, why) in &refused {
        by_reason.entry(reason(why)).or_default().push(name);
    }
    println!(
        "{} decks: {} agree on {RANKS:?} ranks, {} refused, {} failed; {} without a top-level \
         first run, {} cut to 100 steps do not run as one process",
        decks.len(),
        agreeing.len(),
        refused.len(),
        failures.len(),
        without_run.len(),
        serial_fails.len()
    );
    println!("without a top-level first run: {}", without_run.join(" "));
    for s in &serial_fails {
        println!("not run as one process: {s}");
    }
    for (why, names) in &by_reason {
        println!("refused ({}): {why}: {}", names.len(), names.join(" "));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    if only.is_none() {
        assert!(
            agreeing.len() >= AGREEING_AT_LEAST,
            "only {} decks agree on ranks: {agreeing:?}",
            agreeing.len()
        );
    }
}
