//! The runs of a sweep: each in a folder of its own under `OUT/runs/`, holding a copy of the
//! deck (with the observables' lines appended), copies of the files beside it and links to
//! the folders beside it (a fresh `post/`), so runs at once never share an output file.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use super::observe::{appendix, read};
use super::{setting_label, Plan, Setting};
use crate::tool_error::ToolError;

/// How a run ended.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// Exit status 0.
    Ok,
    /// It failed: the first error line (a blow-up names step, atoms and cause).
    Failed(String),
}

/// One finished run.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// Its setting.
    pub setting: Setting,
    /// How it ended.
    pub status: Status,
    /// Wall time of the whole process (s).
    pub wall: f64,
    /// The sum of the log's `Loop time of` lines (s).
    pub loop_time: f64,
    /// Steps run (the sum of the log's `for N steps`).
    pub steps: u64,
    /// Each observable's value, or why there is none.
    pub values: Vec<Result<f64, ToolError>>,
    /// Its folder.
    pub dir: PathBuf,
}

/// Names in the deck's folder a run does not see: earlier output and sweeps.
const SKIPPED: &[&str] = &["post", "study", "sweep", "log.liggghts"];

fn prepare(plan: &Plan, dir: &Path, deck_text: &str) -> Result<PathBuf, ToolError> {
    let err = |p: &Path, e: std::io::Error| ToolError::file(p)(e);
    if dir.exists() {
        std::fs::remove_dir_all(dir).map_err(|e| err(dir, e))?;
    }
    std::fs::create_dir_all(dir.join("post")).map_err(|e| err(dir, e))?;
    let deck_name = plan
        .deck
        .file_name()
        .ok_or_else(|| ToolError::Usage(format!("{}: not a file", plan.deck.display())))?;
    let folder = plan
        .deck
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let out = plan.out.canonicalize().ok();
    for entry in std::fs::read_dir(folder).map_err(|e| err(folder, e))? {
        let entry = entry.map_err(|e| err(folder, e))?;
        let name = entry.file_name();
        let path = entry.path();
        if name == deck_name
            || SKIPPED.iter().any(|s| name == *s)
            || path.canonicalize().ok() == out
        {
            continue;
        }
        let target = dir.join(&name);
        let meta = std::fs::metadata(&path).map_err(|e| err(&path, e))?;
        if meta.is_dir() {
            let abs = path.canonicalize().map_err(|e| err(&path, e))?;
            std::os::unix::fs::symlink(abs, &target).map_err(|e| err(&target, e))?;
        } else if meta.is_file() {
            std::fs::copy(&path, &target).map_err(|e| err(&path, e))?;
        }
    }
    let deck = dir.join(deck_name);
    let text = format!("{deck_text}{}", appendix(&plan.observables));
    std::fs::write(&deck, text).map_err(|e| err(&deck, e))?;
    Ok(deck)
}

/// The `Loop time of X on P procs for N steps` lines of a log: (sum of X, sum of N).
pub fn loop_totals(log: &str) -> (f64, u64) {
    let mut t = 0.0;
    let mut n = 0;
    for l in log.lines().filter(|l| l.starts_with("Loop time of ")) {
        let w: Vec<&str> = l.split_whitespace().collect();
        t += w.get(3).and_then(|x| x.parse::<f64>().ok()).unwrap_or(0.0);
        if let Some(k) = w.iter().position(|x| *x == "for") {
            n += w
                .get(k + 1)
                .and_then(|x| x.parse::<u64>().ok())
                .unwrap_or(0);
        }
    }
    (t, n)
}

/// The first error line of a failed run's standard error (or log).
fn failure(stderr: &str, log: &str) -> String {
    let error = first_error(stderr, log);
    // a guard's warning before the error says why the run went wrong (step, atoms, bound)
    let warned = log
        .lines()
        .chain(stderr.lines())
        .find_map(|l| l.strip_prefix("WARNING: step "))
        .map(|w| w.split(" (").next().unwrap_or(w));
    match warned {
        Some(w) if !error.contains("blow-up") => format!("{error} (after step {w})"),
        _ => error,
    }
}

fn first_error(stderr: &str, log: &str) -> String {
    let pick = |t: &str| {
        t.lines()
            .find(|l| l.starts_with("ERROR"))
            .map(|l| l.trim_start_matches("ERROR: ").to_string())
    };
    pick(stderr)
        .or_else(|| pick(log))
        .or_else(|| {
            stderr
                .lines()
                .rev()
                .find(|l| !l.trim().is_empty())
                .map(str::to_string)
        })
        .unwrap_or_else(|| "failed without a message".into())
}

fn run_one(plan: &Plan, index: usize, setting: &Setting, deck_text: &str) -> Run {
    let dir = plan.out.join("runs").join(format!("run_{:03}", index + 1));
    let mut run = Run {
        setting: setting.clone(),
        status: Status::Ok,
        wall: f64::NAN,
        loop_time: f64::NAN,
        steps: 0,
        values: Vec::new(),
        dir: dir.clone(),
    };
    let fail_all = |run: &mut Run, e: ToolError| {
        run.values = plan.observables.iter().map(|_| Err(e.clone())).collect();
        run.status = Status::Failed(e.to_string());
    };
    let deck = match prepare(plan, &dir, deck_text) {
        Ok(d) => d,
        Err(m) => {
            fail_all(&mut run, m);
            return run;
        }
    };
    let program = if plan.liggghts {
        PathBuf::from("liggghts")
    } else {
        match std::env::current_exe() {
            Ok(p) => p,
            Err(e) => {
                fail_all(&mut run, ToolError::Run(e.to_string()));
                return run;
            }
        }
    };
    let mut cmd = Command::new(&program);
    cmd.current_dir(&dir)
        .arg("-in")
        .arg(deck.file_name().unwrap_or_default())
        .args(["-log", "log.liggghts"]);
    for (n, v) in plan.fixed.iter().chain(setting.iter()) {
        match n.as_str() {
            "sf" if v == "fast" => {
                cmd.args(["-sf", "fast"]);
            }
            "sf" => {}
            "pk" => {
                cmd.args(["-pk", "fast", v]);
            }
            _ => {
                cmd.args(["-var", n, v]);
            }
        }
    }
    let files = (
        std::fs::File::create(dir.join("screen.txt")),
        std::fs::File::create(dir.join("stderr.txt")),
    );
    let (Ok(screen), Ok(stderr)) = files else {
        fail_all(
            &mut run,
            ToolError::Run(format!("{}: cannot create output files", dir.display())),
        );
        return run;
    };
    cmd.stdin(Stdio::null())
        .stdout(Stdio::from(screen))
        .stderr(Stdio::from(stderr));
    let started = Instant::now();
    let status = cmd.status();
    run.wall = started.elapsed().as_secs_f64();
    let log = std::fs::read_to_string(dir.join("log.liggghts"))
        .or_else(|_| std::fs::read_to_string(dir.join("screen.txt")))
        .unwrap_or_default();
    let err_text = std::fs::read_to_string(dir.join("stderr.txt")).unwrap_or_default();
    (run.loop_time, run.steps) = loop_totals(&log);
    match status {
        Err(e) => {
            let why = format!("cannot start {}: {e}", program.display());
            fail_all(&mut run, ToolError::Run(why));
            return run;
        }
        Ok(s) if !s.success() => {
            fail_all(&mut run, ToolError::Run(failure(&err_text, &log)));
            return run;
        }
        Ok(_) => {}
    }
    run.values = plan
        .observables
        .iter()
        .enumerate()
        .map(|(k, o)| read(o, k, &dir, &log))
        .collect();
    run
}

/// Run every setting, `plan.jobs` at once; results in the order of `list`. Progress goes to
/// standard error as runs finish.
pub fn run_all(plan: &Plan, list: &[Setting]) -> Result<Vec<Run>, ToolError> {
    let deck_text = std::fs::read_to_string(&plan.deck).map_err(ToolError::file(&plan.deck))?;
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Run>>> = Mutex::new(vec![None; list.len()]);
    let workers = plan.jobs.clamp(1, list.len().max(1));
    std::thread::scope(|scope| {
        for _ in 0..workers {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::SeqCst);
                if k >= list.len() {
                    break;
                }
                let run = run_one(plan, k, &list[k], &deck_text);
                let n = done.fetch_add(1, Ordering::SeqCst) + 1;
                let what = match &run.status {
                    Status::Ok => format!("{:.2} s", run.wall),
                    Status::Failed(m) => format!("failed: {m}"),
                };
                eprintln!("[{n}/{}] {}: {what}", list.len(), setting_label(&list[k]));
                if let Ok(mut r) = results.lock() {
                    r[k] = Some(run);
                }
            });
        }
    });
    let results = results
        .into_inner()
        .map_err(|e| ToolError::Run(e.to_string()))?;
    Ok(results.into_iter().flatten().collect())
}

#[cfg(test)]
mod tests {
    #[test]
    fn loop_lines_and_failures() {
        let log = "Loop time of 0.5 on 1 procs for 1000 steps with 2 atoms\n\nLoop time of 0.25 on 1 procs for 500 steps with 2 atoms, finish time X\n";
        assert_eq!(super::loop_totals(log), (0.75, 1500));
        assert_eq!(
            super::failure("  --> in.x:3\nERROR: blow-up at step 5: ...\n", ""),
            "blow-up at step 5: ..."
        );
        assert_eq!(super::failure("", ""), "failed without a message");
        assert_eq!(
            super::failure(
                "ERROR: Variable atom ID is not currently defined\n",
                "WARNING: step 1: atoms 1 and 2 overlap by 61.8 % of the smaller radius (more than 50 %); ...\n"
            ),
            "Variable atom ID is not currently defined (after step 1: atoms 1 and 2 overlap by 61.8 % of the smaller radius)"
        );
    }
}
