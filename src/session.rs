//! Running and checking decks end to end: open the script, set up screen and log, check the
//! whole deck before any step runs, then run it.

use std::collections::BTreeMap;
use std::io::{Read, Write};
use std::path::Path;

use crate::cli::DeckOptions;
use crate::error::{Diagnostic, ExitStatus, Severity};
use crate::lang::system::Mode;
use crate::script::interp::{Interpreter, Output, Source};

/// The first line regolith writes to screen and log (LIGGGHTS writes its version there).
pub fn banner() -> String {
    format!(
        "regolith {} (runs LIGGGHTS-PUBLIC 3.8.0 decks)\n",
        env!("CARGO_PKG_VERSION")
    )
}

/// Read the deck named by `-in`, or standard input.
pub fn load_source(input: Option<&str>) -> Result<Source, Diagnostic> {
    match input {
        Some(name) => {
            let bytes = std::fs::read(name).map_err(|e| {
                Diagnostic::error(format!("Cannot open input script {name}"))
                    .with_help(e.to_string())
            })?;
            Ok(Source::from_text(
                name,
                &String::from_utf8_lossy(&bytes),
                false,
            ))
        }
        None => {
            let mut text = String::new();
            std::io::stdin().read_to_string(&mut text).map_err(|e| {
                Diagnostic::error("Cannot read input script from standard input")
                    .with_help(e.to_string())
            })?;
            Ok(Source::from_text("-", &text, true))
        }
    }
}

/// Check a deck without running it: every problem found, in order.
pub fn check_deck(source: Source, opts: &DeckOptions) -> Vec<Diagnostic> {
    check_deck_in(source, opts, None)
}

/// Check a deck as `check_deck` does; also the time-step margins its runs would have
/// (one text per `run` where it changed).
pub fn check_deck_with_margins(
    source: Source,
    opts: &DeckOptions,
) -> (Vec<Diagnostic>, Vec<String>) {
    let c = check_deck_full(source, opts, None);
    (c.diagnostics, c.margins)
}

/// Check a deck as if run from folder `cwd` (default: the current directory).
pub fn check_deck_in(source: Source, opts: &DeckOptions, cwd: Option<&Path>) -> Vec<Diagnostic> {
    check_deck_full(source, opts, cwd).diagnostics
}

/// What a check found.
struct Checked {
    diagnostics: Vec<Diagnostic>,
    margins: Vec<String>,
    /// The processor grid lines LIGGGHTS would print at each box-creating command.
    grid: Vec<String>,
}

fn check_deck_full(source: Source, opts: &DeckOptions, cwd: Option<&Path>) -> Checked {
    let mut interp = Interpreter::new(Mode::Check, Output::silent());
    interp.engine.sim.procs.nprocs = opts.ranks.size as i64;
    interp.engine.sim.procs.procs_per_node = opts.ranks.per_node as i64;
    interp.engine.sim.seed_tolerant = opts.seed_tolerant;
    interp.engine.sim.zero_restitution = opts.zero_restitution;
    interp.engine.sim.accel.fast = opts.fast;
    interp.engine.sim.accel.ask_threads(opts.threads);
    if let Some(dir) = cwd {
        interp.sys.cwd = dir.to_path_buf();
    }
    for (name, values) in &opts.vars {
        if let Err(d) = interp.set_command_line_variable(name, values) {
            interp.diagnostics.push(d);
        }
    }
    let _ = interp.run_source(source);
    let margins = std::mem::take(&mut interp.engine.sim.margin_notes);
    let diagnostics = interp.diagnostics;
    let reported = std::mem::take(&mut interp.engine.sim.procs.reported);
    Checked {
        diagnostics,
        margins,
        grid: reported.into_iter().map(|(lines, _)| lines).collect(),
    }
}

/// The exit status a list of check diagnostics leads to.
pub fn status_of(diagnostics: &[Diagnostic]) -> ExitStatus {
    if diagnostics.iter().any(|d| d.severity == Severity::Error) {
        ExitStatus::DeckError
    } else if diagnostics
        .iter()
        .any(|d| d.severity == Severity::Unsupported)
    {
        ExitStatus::Unsupported
    } else {
        ExitStatus::Success
    }
}

fn open_output(name: &str) -> Result<Option<Box<dyn Write>>, Diagnostic> {
    if name == "none" {
        return Ok(None);
    }
    let f = std::fs::File::create(name).map_err(|e| {
        Diagnostic::error(format!("Cannot open file {name}")).with_help(e.to_string())
    })?;
    Ok(Some(Box::new(std::io::BufWriter::new(f))))
}

/// Run a deck as `liggghts -in ...` would. Problems go to standard error.
pub fn run_deck(opts: &DeckOptions) -> ExitStatus {
    run_deck_on(opts, None)
}

/// [`run_deck`] as one of `opts.ranks.size` ranks joined by `comm` (None: one process).
/// Only rank 0 writes to the screen, the log and output files.
pub fn run_deck_on(opts: &DeckOptions, comm: Option<crate::util::comm::RankComm>) -> ExitStatus {
    // with more than one MPI rank only rank 0 speaks
    let report = |d: &Diagnostic| {
        if opts.ranks.rank == 0 {
            let _ = std::io::stderr().write_all(d.render().as_bytes());
        }
    };
    let source = match load_source(opts.input.as_deref()) {
        Ok(s) => s,
        Err(d) => {
            report(&d);
            return ExitStatus::DeckError;
        }
    };
    if let Some(refused) = check_before_running(opts, &source, comm.is_some(), &report) {
        return refused;
    }
    let (observer, mut out) = match open_streams(opts) {
        Ok(streams) => streams,
        Err(d) => {
            report(&d);
            return ExitStatus::DeckError;
        }
    };
    out.both(&banner());
    let mut interp = Interpreter::new(Mode::Run, out);
    let sim = &mut interp.engine.sim;
    sim.seed_tolerant = opts.seed_tolerant;
    sim.zero_restitution = opts.zero_restitution;
    sim.accel.fast = opts.fast;
    sim.accel.ask_threads(opts.threads);
    sim.observer = observer;
    sim.procs.nprocs = opts.ranks.size as i64;
    sim.procs.procs_per_node = opts.ranks.per_node as i64;
    sim.accel.ranks_per_node = opts.ranks.per_node;
    sim.comm = comm;
    for (name, values) in &opts.vars {
        if let Err(d) = interp.set_command_line_variable(name, values) {
            report(&d);
            return ExitStatus::DeckError;
        }
    }
    let status = match interp.run_source(source) {
        // LIGGGHTS 3.8.0 leaves through Error::done(), which exits with status 1
        Ok(()) if interp.quit_requested() => ExitStatus::DeckError,
        Ok(()) => ExitStatus::Success,
        Err(d) => {
            interp.out.log(&format!("ERROR: {}\n", d.one_line()));
            interp.out.flush();
            report(&d);
            d.exit_status()
        }
    };
    interp.out.flush();
    with_lost_output(&interp.out, status)
}

/// The whole deck checked first: nothing unsupported or misspelled starts a run. The exit
/// status when the deck is refused (its problems reported), None when it may run. On more
/// than one rank without `ranks_joined` (a communicator), every deck is refused.
fn check_before_running(
    opts: &DeckOptions,
    source: &Source,
    ranks_joined: bool,
    report: &dyn Fn(&Diagnostic),
) -> Option<ExitStatus> {
    let checked = check_deck_full(
        Source {
            name: source.name.clone(),
            lines: source.lines.clone(),
            from_stdin: source.from_stdin,
        },
        opts,
        None,
    );
    let problems: Vec<Diagnostic> = checked
        .diagnostics
        .into_iter()
        .filter(|d| d.severity != Severity::Warning)
        .collect();
    if opts.ranks.size > 1 && (!ranks_joined || !problems.is_empty()) {
        // on more than one rank: rank 0 reports the grid as LIGGGHTS would, then the refusals
        if opts.ranks.rank == 0 {
            print!("{}", checked.grid.concat());
            for d in &problems {
                report(d);
            }
            if !ranks_joined {
                report(&Diagnostic::unsupported(format!(
                    "this run {}",
                    crate::util::comm::MANY_RANKS
                )));
            }
        }
        return Some(match status_of(&problems) {
            ExitStatus::Success => ExitStatus::Unsupported,
            other => other,
        });
    }
    if !problems.is_empty() {
        for d in &problems {
            report(d);
        }
        let _ = writeln!(
            std::io::stderr(),
            "regolith: {} problem(s) found before running; nothing was run",
            problems.len()
        );
        return Some(status_of(&problems));
    }
    None
}

/// The run's screen (with the progress line when standard error is a terminal), log and
/// echo settings as the flags set them; ranks above 0 write neither screen nor log.
fn open_streams(
    opts: &DeckOptions,
) -> Result<(Option<Box<dyn crate::progress::StepObserver>>, Output), Diagnostic> {
    let quiet = opts.ranks.rank > 0;
    let screen: Option<Box<dyn Write>> = match opts.screen.as_deref() {
        _ if quiet => None,
        None => Some(Box::new(std::io::stdout())),
        Some(name) => open_output(name)?,
    };
    let (observer, screen) = crate::progress::attach(screen);
    let log_name = if quiet {
        "none"
    } else {
        opts.log.as_deref().unwrap_or("log.liggghts")
    };
    let log = open_output(log_name)?;
    let (echo_screen, echo_log) = match opts.echo.as_deref() {
        Some("none") => (false, false),
        Some("screen") => (true, false),
        Some("both") => (true, true),
        _ => (false, true),
    };
    let out = Output {
        screen,
        log,
        echo_screen,
        echo_log,
        write_errors: [None, None],
        stdout_apart: !quiet && opts.screen.is_some(),
    };
    Ok((observer, out))
}

/// The run's exit status once the output it asked for and did not get is reported: a
/// run that lost output did not end cleanly.
fn with_lost_output(out: &Output, status: ExitStatus) -> ExitStatus {
    let lost: Vec<String> = out.write_errors.iter().flatten().cloned().collect();
    if !lost.is_empty() {
        for m in &lost {
            let _ = writeln!(std::io::stderr(), "ERROR: {m}");
        }
        if status == ExitStatus::Success {
            return ExitStatus::DeckError;
        }
    }
    status
}

/// A Markdown table of what each deck needs that regolith lacks, every deck checked from its
/// own folder (as the LIGGGHTS tutorials are run). Deck names are shown relative to `root`.
pub fn support_table(
    decks: &[String],
    root: Option<&str>,
    opts: &DeckOptions,
) -> Result<String, Diagnostic> {
    let mut rows = Vec::new();
    for deck in decks {
        let path = Path::new(deck);
        let shown = match root {
            Some(r) => path
                .strip_prefix(r)
                .unwrap_or(path)
                .to_string_lossy()
                .into_owned(),
            None => deck.clone(),
        };
        let source = load_source(Some(deck))?;
        let source = Source {
            name: shown.clone(),
            ..source
        };
        let dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let diagnostics = check_deck_in(source, opts, Some(dir));
        // one entry per distinct message, with the lines it occurs on
        let mut items: BTreeMap<(u8, String), Vec<usize>> = BTreeMap::new();
        for d in &diagnostics {
            let rank = match d.severity {
                Severity::Error => 0,
                Severity::Unsupported => 1,
                Severity::Warning => 2,
            };
            let line = d.location.as_ref().map_or(0, |l| l.line);
            items
                .entry((rank, d.message.replace('|', "\\|")))
                .or_default()
                .push(line);
        }
        let sph = diagnostics
            .iter()
            .any(|d| d.message.contains("out of scope: SPH"));
        let status = match status_of(&diagnostics) {
            ExitStatus::Success => "runs",
            ExitStatus::Unsupported if sph => "out of scope (SPH)",
            ExitStatus::Unsupported => "unsupported",
            _ => "invalid",
        };
        let list: Vec<String> = items
            .into_iter()
            .map(|((rank, msg), lines)| {
                let lines: Vec<String> = lines.iter().map(usize::to_string).collect();
                let tag = if rank == 0 { "error: " } else { "" };
                format!("{tag}{msg} (line {})", lines.join(", "))
            })
            .collect();
        rows.push(format!(
            "| `{shown}` | {status} | {} |",
            if list.is_empty() {
                "-".to_string()
            } else {
                list.join("<br>")
            }
        ));
    }
    let mut out =
        String::from("| deck | status | what regolith lacks (or what is wrong) |\n|---|---|---|\n");
    for r in rows {
        out.push_str(&r);
        out.push('\n');
    }
    Ok(out)
}
