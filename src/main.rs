//! `regolith`: run LIGGGHTS decks (`regolith -in in.deck`), or check, diff and convert.

use std::process::ExitCode;

use clap::{Parser, Subcommand};
use regolith::cli::{parse_deck_flags, DeckOptions};
use regolith::error::ExitStatus;
use regolith::session;
use regolith::util::comm::Ranks;
use std::path::PathBuf;

/// Large arrays (particles, neighbour lists, contact history) on huge pages where Linux allows.
#[global_allocator]
static ALLOCATOR: regolith::util::huge_pages::HugePages = regolith::util::huge_pages::HugePages;

#[derive(Parser)]
#[command(
    name = "regolith",
    disable_help_subcommand = true,
    version,
    about = "Soft-sphere DEM solver that runs LIGGGHTS 3.8.0 decks unchanged",
    long_about = "Soft-sphere DEM solver that runs LIGGGHTS 3.8.0 decks unchanged.\n\n\
        Drop-in use takes liggghts's own flags:\n  \
        regolith -in in.deck [-var NAME VALUE ...] [-log FILE|none] [-screen FILE|none] [-echo none|screen|log|both] [-nocite]\n\
        With no -in, the deck is read from standard input."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run a deck (same as `regolith -in DECK`); LIGGGHTS flags may follow.
    Run {
        /// The input deck.
        deck: String,
        /// LIGGGHTS-style flags: -var NAME VALUE..., -log FILE, -screen FILE, -echo MODE.
        #[arg(trailing_var_arg = true, allow_hyphen_values = true)]
        flags: Vec<String>,
    },
    /// Parse and validate whole decks without running a step; lists every problem as file:line: message.
    Check {
        /// Print a Markdown support table for all the decks instead (each checked from its own folder).
        #[arg(long)]
        table: bool,
        /// With --table: show deck paths relative to this folder.
        #[arg(long, requires = "table")]
        root: Option<String>,
        /// Deck files, then LIGGGHTS-style flags (-var NAME VALUE ...).
        #[arg(required = true, trailing_var_arg = true, allow_hyphen_values = true)]
        args: Vec<String>,
    },
    /// The commands and styles regolith runs: `help` lists them, `help COMMAND [STYLE]` prints
    /// one's declared signature (arguments, keywords with their kinds, description).
    Help {
        /// A command, then a style (`fix wall/gran`).
        words: Vec<String>,
        /// Print the Markdown table of every command and style instead (compat/SUPPORT.md).
        #[arg(long)]
        markdown: bool,
    },
    /// Compare two dumps (text or gzip, a file or a `*` series) atom by atom, or the thermo
    /// columns of two logs. Exit 0 within tolerance, 1 outside, 2 on unreadable input.
    Diff {
        /// First dump or log.
        a: String,
        /// Second dump or log.
        b: String,
        /// Relative tolerance: values agree when |a-b| <= atol + rtol max(|a|,|b|).
        #[arg(long, default_value_t = 1e-6)]
        rtol: f64,
        /// Absolute tolerance (units of each column).
        #[arg(long, default_value_t = 0.0)]
        atol: f64,
        /// Only these columns, comma-separated (default: all shared columns but id).
        #[arg(long, value_delimiter = ',')]
        columns: Option<Vec<String>>,
        /// Only these steps: N, A:B, or a comma list of them.
        #[arg(long)]
        steps: Option<String>,
        /// `dump local` files: match entries in the order of these columns, comma-separated
        /// (default: all columns, first to last); e.g. the id columns of a compute.
        #[arg(long, value_delimiter = ',')]
        key: Option<Vec<String>>,
        /// Scale-relative mode: |a-b| relative to each column's largest magnitude (max) or
        /// root mean square (rms) in A, the reference, instead of to max(|a|,|b|) per value.
        #[arg(long)]
        scale: Option<String>,
    },
    /// Convert between LIGGGHTS restart files, data files, text dumps (gzip for .gz) and VTK:
    /// restart -> data|dump|vtk|restart, data -> restart|dump|vtk, dump -> vtk.
    Convert {
        /// Input file (a `%` restart name reads the base and per-processor files).
        input: String,
        /// Output file (`*` in a VTK name becomes the step).
        output: String,
        /// Input format if the name does not say: restart, data, dump.
        #[arg(long)]
        from: Option<String>,
        /// Output format if the name does not say: restart, data, dump, vtk.
        #[arg(long)]
        to: Option<String>,
        /// Boundary of a data file's box (data files carry none), e.g. "p p f"; default "p p p".
        #[arg(long)]
        boundary: Option<String>,
    },
    /// Post-process a study's dumps into numbers, CSV tables and PNG figures (chain, channel,
    /// ring); --run DECK runs the deck first.
    Analyze {
        #[command(subcommand)]
        what: regolith::analyze::args::AnalyzeCommand,
    },
    /// Run a deck at every combination of settings (--var NAME V1,V2,...; sf off,fast for the
    /// engine path), measure observables (--observe NAME=EXPR) and their error against a
    /// reference run against wall time: a table, sweep.csv and sweep.png.
    Sweep(regolith::sweep::SweepArgs),
    /// Time a scene (built-in: settled_bed, struck_chain; or a deck path) and print loop
    /// times and particle-steps per second; --liggghts times Debian's LIGGGHTS too.
    Bench {
        /// `beds` (the standard beds), a built-in scene name or a deck file.
        #[arg(default_value = "settled_bed")]
        scene: String,
        /// Runs per program (interleaved).
        #[arg(long, default_value_t = 1)]
        repeat: usize,
        /// Also run Debian's `liggghts` on the same deck.
        #[arg(long)]
        liggghts: bool,
        /// Time the exact path (one thread); on unless only --fast or --liggghts is given.
        #[arg(long)]
        exact: bool,
        /// Time the fast path (at each --threads count).
        #[arg(long)]
        fast: bool,
        /// Thread counts of the fast path, e.g. 1,2.
        #[arg(long, value_delimiter = ',', default_value = "1")]
        threads: Vec<usize>,
        /// Also time the fast path under `mpirun -np N` (one thread per rank) for each of
        /// these rank counts, e.g. 1,2 (needs a regolith built with the `mpi` feature).
        #[arg(long, value_delimiter = ',')]
        ranks: Vec<usize>,
        /// Deck variables: --var NAME VALUE (repeatable).
        #[arg(long = "var", num_args = 2, value_names = ["NAME", "VALUE"], action = clap::ArgAction::Append)]
        vars: Vec<String>,
        /// beds: sizes, e.g. 10k,50k,200k.
        #[arg(long, value_delimiter = ',', default_value = "10k,50k")]
        sizes: Vec<String>,
        /// beds: contact models hh, sjkr, epsd.
        #[arg(long, value_delimiter = ',', default_value = "hh,sjkr,epsd")]
        models: Vec<String>,
        /// beds: states rest, shock.
        #[arg(long, value_delimiter = ',', default_value = "rest,shock")]
        states: Vec<String>,
        /// beds: steps per run (default: about 2e7 particle-steps).
        #[arg(long)]
        steps: Option<u64>,
        /// beds: where the beds are built and kept (default $REGOLITH_BEDS or ~/.cache/regolith/beds).
        #[arg(long)]
        beds: Option<PathBuf>,
        /// Write the medians as CSV to this file.
        #[arg(long)]
        csv: Option<PathBuf>,
        /// Write a PNG of particle-steps/s against thread count to this file.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
}

fn exit(status: ExitStatus) -> ExitCode {
    ExitCode::from(status as u8)
}

/// Refuse `what` on more than one MPI rank (rank 0 says so; every rank fails).
fn many_ranks(what: &str) -> ExitCode {
    if ranks().rank == 0 {
        eprintln!(
            "ERROR (regolith): {what} {}: not supported yet (start regolith without mpirun)",
            regolith::util::comm::MANY_RANKS
        );
    }
    exit(ExitStatus::Unsupported)
}

fn deck_flags(deck: Option<String>, flags: &[String]) -> Result<DeckOptions, ExitCode> {
    match parse_deck_flags(flags) {
        Ok(mut o) => {
            if deck.is_some() {
                o.input = deck;
            }
            o.ranks = ranks();
            Ok(o)
        }
        Err(e) => {
            eprintln!("ERROR: {}", e.message);
            if let Some(h) = &e.help {
                eprintln!("  = {h}");
            }
            Err(exit(ExitStatus::Usage))
        }
    }
}

fn run_with(opts: DeckOptions) -> ExitCode {
    if opts.help {
        use clap::CommandFactory;
        let _ = Cli::command().print_long_help();
        return exit(ExitStatus::Success);
    }
    if opts.ranks.size > 1 && opts.restart_to_data.is_some() {
        return many_ranks("-restart");
    }
    if let Some((restart, data)) = &opts.restart_to_data {
        // `liggghts -r RESTART DATAFILE`: convert and exit
        use regolith::io::convert::{convert, ConvertOptions, Format};
        let o = ConvertOptions {
            from: Some(Format::Restart),
            to: Some(Format::Data),
            boundary: None,
        };
        return match convert(restart, data, &o) {
            Ok(summary) => {
                println!("{summary}");
                exit(ExitStatus::Success)
            }
            Err(m) => {
                eprintln!("ERROR: {m}");
                exit(ExitStatus::DeckError)
            }
        };
    }
    let comm = COMM.lock().ok().and_then(|mut c| c.take());
    exit(session::run_deck_on(&opts, comm))
}

/// The communicator of a run on several MPI ranks (taken by the run).
static COMM: std::sync::Mutex<Option<regolith::util::comm::RankComm>> = std::sync::Mutex::new(None);

/// The MPI ranks this process is one of (set once at start).
static RANKS: std::sync::OnceLock<Ranks> = std::sync::OnceLock::new();

fn ranks() -> Ranks {
    RANKS.get().copied().unwrap_or_default()
}

/// One malloc arena for every thread. glibc otherwise gives each thread a heap of its own
/// that keeps what the thread freed: the neighbour lists built on a second thread held 12 MB
/// more on a 10 000-sphere bed (a third more memory). The step loop does not allocate, so
/// threads do not contend for the one arena.
fn one_malloc_arena() {
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    // SAFETY: a documented glibc setting, made before any other thread starts
    unsafe {
        libc::mallopt(libc::M_ARENA_MAX, 1);
    }
}

fn main() -> ExitCode {
    one_malloc_arena();
    // under mpirun: a build without MPI stops here; with MPI, the ranks are learnt (and MPI
    // ends when `launch` is dropped, after everything else)
    let launch = match regolith::launch::start() {
        Ok(l) => l,
        Err(m) => {
            let rank = regolith::util::comm::launcher_rank(|k| std::env::var(k).ok());
            if rank == 0 {
                eprintln!("ERROR: {m}");
            }
            return exit(ExitStatus::Unsupported);
        }
    };
    let _ = RANKS.set(launch.ranks);
    let mut launch = launch;
    if let Ok(mut c) = COMM.lock() {
        *c = launch.take_comm();
    }
    // `launch` lives until `dispatch` has returned
    let code = dispatch();
    // a communicator no run took (`check` on ranks) ends MPI here, on every rank
    drop(COMM.lock().ok().and_then(|mut c| c.take()));
    code
}

fn dispatch() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let legacy = match args.get(1).map(String::as_str) {
        None => true,
        Some(a) => a.starts_with('-') && !matches!(a, "--help" | "--version" | "-V"),
    };
    if legacy {
        return match deck_flags(None, &args[1..]) {
            Ok(o) => run_with(o),
            Err(code) => code,
        };
    }
    let cli = Cli::parse();
    if ranks().size > 1 && !matches!(cli.command, Command::Run { .. } | Command::Check { .. }) {
        return many_ranks("this command");
    }
    match cli.command {
        Command::Run { deck, flags } => match deck_flags(Some(deck), &flags) {
            Ok(o) => run_with(o),
            Err(code) => code,
        },
        cmd @ Command::Check { .. } => check_decks(cmd),
        Command::Help { words, markdown } => {
            if markdown {
                print!("{}", regolith::commands::specs::markdown());
                return ExitCode::from(0);
            }
            let words: Vec<&str> = words.iter().map(String::as_str).collect();
            match regolith::commands::specs::help(&words) {
                Ok(text) => {
                    print!("{text}");
                    ExitCode::from(0)
                }
                Err(m) => {
                    eprintln!("regolith help: {m}");
                    ExitCode::from(2)
                }
            }
        }
        cmd @ Command::Diff { .. } => diff_files(cmd),
        Command::Convert {
            input,
            output,
            from,
            to,
            boundary,
        } => {
            use regolith::io::convert::{convert, ConvertOptions, Format};
            let parse = |w: Option<String>| w.map(|w| Format::parse(&w)).transpose();
            let opts = match (parse(from), parse(to)) {
                (Ok(from), Ok(to)) => ConvertOptions { from, to, boundary },
                (Err(m), _) | (_, Err(m)) => {
                    eprintln!("ERROR: {m}");
                    return ExitCode::from(2);
                }
            };
            match convert(&input, &output, &opts) {
                Ok(summary) => {
                    println!("{summary}");
                    ExitCode::from(0)
                }
                Err(m) => {
                    eprintln!("ERROR: {m}");
                    ExitCode::from(1)
                }
            }
        }
        Command::Analyze { what } => match regolith::analyze::args::analyze(&what) {
            Ok(()) => ExitCode::from(0),
            Err(e) => {
                eprintln!("ERROR: {e}");
                ExitCode::from(1)
            }
        },
        Command::Sweep(a) => match regolith::sweep::args::run(&a) {
            Ok(text) => {
                print!("{text}");
                ExitCode::from(0)
            }
            Err(m) => {
                eprintln!("ERROR: {m}");
                ExitCode::from(1)
            }
        },
        cmd @ Command::Bench { .. } => bench(cmd),
    }
}

/// `regolith check DECK ...`: the diagnostics of each deck (or `--table`: the support table).
fn check_decks(cmd: Command) -> ExitCode {
    let Command::Check { table, root, args } = cmd else {
        unreachable!("dispatched on its variant")
    };
    let split = args
        .iter()
        .position(|a| a.starts_with('-'))
        .unwrap_or(args.len());
    let (decks, flags) = args.split_at(split);
    let opts = match deck_flags(None, flags) {
        Ok(o) => o,
        Err(code) => return code,
    };
    // `check -in DECK` names its deck as `run` does; with none at all, nothing is checked
    let mut decks = decks.to_vec();
    decks.extend(opts.input.clone());
    if decks.is_empty() {
        eprintln!(
            "ERROR: regolith check: no deck file given (flags such as -var go after the deck \
             files: regolith check DECK -var NAME VALUE, or give the deck as -in DECK)"
        );
        return exit(ExitStatus::Usage);
    }
    if table {
        return match session::support_table(&decks, root.as_deref(), &opts) {
            Ok(text) => {
                print!("{text}");
                exit(ExitStatus::Success)
            }
            Err(d) => {
                eprint!("{}", d.render());
                exit(ExitStatus::DeckError)
            }
        };
    }
    let mut worst = ExitStatus::Success;
    for deck in &decks {
        let source = match session::load_source(Some(deck.as_str())) {
            Ok(s) => s,
            Err(d) => {
                eprint!("{}", d.render());
                return exit(ExitStatus::DeckError);
            }
        };
        let (diagnostics, margins) = session::check_deck_with_margins(source, &opts);
        // with more than one MPI rank only rank 0 speaks
        if opts.ranks.rank == 0 {
            for d in &diagnostics {
                println!("{}", d.one_line());
            }
            for m in &margins {
                print!("{m}");
            }
        }
        let status = session::status_of(&diagnostics);
        if status == ExitStatus::DeckError || worst == ExitStatus::Success {
            worst = status;
        }
    }
    exit(worst)
}

/// `regolith diff A B`: compare two dump, thermo or data files within tolerances.
fn diff_files(cmd: Command) -> ExitCode {
    let Command::Diff {
        a,
        b,
        rtol,
        atol,
        columns,
        steps,
        key,
        scale,
    } = cmd
    else {
        unreachable!("dispatched on its variant")
    };
    let scale = match scale
        .map(|s| regolith::io::diff::Scale::parse(&s))
        .transpose()
    {
        Ok(s) => s,
        Err(m) => {
            eprintln!("ERROR: {m}");
            return ExitCode::from(2);
        }
    };
    let steps = match steps
        .map(|s| regolith::io::diff::parse_steps(&s))
        .transpose()
    {
        Ok(s) => s,
        Err(m) => {
            eprintln!("ERROR: {m}");
            return ExitCode::from(2);
        }
    };
    let opts = regolith::io::diff::DiffOptions {
        rtol,
        atol,
        columns,
        steps,
        key,
        scale,
    };
    match regolith::io::diff::diff(&a, &b, &opts) {
        Ok(mut report) => {
            print!("{}", report.render(&a, &b));
            ExitCode::from(if report.agrees() { 0 } else { 1 })
        }
        Err(m) => {
            eprintln!("ERROR: {m}");
            ExitCode::from(2)
        }
    }
}

/// `regolith bench SCENE`: time regolith (and LIGGGHTS) on a scene or the suite of beds.
fn bench(cmd: Command) -> ExitCode {
    let Command::Bench {
        scene,
        repeat,
        liggghts,
        exact,
        fast,
        threads,
        ranks,
        vars,
        sizes,
        models,
        states,
        steps,
        beds,
        csv,
        plot,
    } = cmd
    else {
        unreachable!("dispatched on its variant")
    };
    let choice = regolith::bench::ProgramChoice {
        liggghts,
        exact: exact || (!fast && ranks.is_empty()),
        fast_threads: if fast { threads } else { Vec::new() },
        ranks,
    };
    let result = if scene == "beds" {
        let opts = regolith::bench::beds::SuiteOptions {
            sizes,
            models,
            states,
            threads: choice.fast_threads.clone(),
            exact: choice.exact,
            liggghts,
            repeat: repeat.max(1),
            steps,
            beds: beds.unwrap_or_else(regolith::bench::beds::default_bed_dir),
            csv: csv.clone(),
        };
        choice.programs().and_then(|programs| {
            let me = std::env::current_exe()
                .map_err(|e| regolith::tool_error::ToolError::Run(e.to_string()))?;
            let rows = regolith::bench::beds::suite(&opts, &programs, &me)?;
            if let Some(path) = &csv {
                regolith::io::write_atomically(
                    &path.to_string_lossy(),
                    regolith::bench::csv(&rows).as_bytes(),
                )
                .map_err(regolith::tool_error::ToolError::file(path))?;
            }
            if let Some(path) = &plot {
                regolith::bench::plot(&rows, path)?;
            }
            Ok(format!(
                "{}\n{}",
                regolith::bench::speed_table(&rows),
                regolith::bench::details(&rows)
            ))
        })
    } else {
        let opts = regolith::bench::BenchOptions {
            scene,
            repeat: repeat.max(1),
            choice,
            vars: vars
                .chunks(2)
                .map(|c| (c[0].clone(), c.get(1).cloned().unwrap_or_default()))
                .collect(),
        };
        regolith::bench::bench(&opts)
    };
    match result {
        Ok(report) => {
            print!("{report}");
            ExitCode::from(0)
        }
        Err(m) => {
            eprintln!("ERROR: {m}");
            ExitCode::from(1)
        }
    }
}
