//! The standard benchmark beds: settled lunar-material beds of 10 000, 50 000 and 200 000
//! spheres (periodic in x and y, a floor wall), built once by `benches/beds/in.make_bed`
//! and kept in a cache folder, then timed at rest and under a 10 m/s piston shock with
//! three contact models (`benches/beds/in.bench`).

use std::path::{Path, PathBuf};

use super::measure::{median, run_once, Measure, Program};
use crate::tool_error::ToolError;

/// The deck that builds a bed.
pub const MAKE_BED: &str = include_str!("../../benches/beds/in.make_bed");
/// The deck that times a bed.
pub const BENCH_DECK: &str = include_str!("../../benches/beds/in.bench");

/// The bed sizes: (tag, spheres asked for).
pub const SIZES: &[(&str, usize)] = &[("10k", 10_000), ("50k", 50_000), ("200k", 200_000)];
/// The contact models of `in.bench`.
pub const MODELS: &[&str] = &["hh", "sjkr", "epsd"];
/// The states of `in.bench`.
pub const STATES: &[&str] = &["rest", "shock"];

/// What the suite runs.
#[derive(Debug, Clone)]
pub struct SuiteOptions {
    /// Bed tags (10k, 50k, 200k).
    pub sizes: Vec<String>,
    /// Models (hh, sjkr, epsd).
    pub models: Vec<String>,
    /// States (rest, shock).
    pub states: Vec<String>,
    /// Thread counts of the fast path.
    pub threads: Vec<usize>,
    /// Also time the exact path (one thread).
    pub exact: bool,
    /// Also time Debian's `liggghts`.
    pub liggghts: bool,
    /// Interleaved repeats of every program.
    pub repeat: usize,
    /// Steps per run (default: about 2e7 particle-steps).
    pub steps: Option<u64>,
    /// Where the beds are kept.
    pub beds: PathBuf,
    /// Write the medians as CSV here.
    pub csv: Option<PathBuf>,
}

/// The default bed cache: `$REGOLITH_BEDS`, else `$XDG_CACHE_HOME/regolith/beds`, else
/// `~/.cache/regolith/beds`.
pub fn default_bed_dir() -> PathBuf {
    if let Some(d) = std::env::var_os("REGOLITH_BEDS") {
        return PathBuf::from(d);
    }
    let base = std::env::var_os("XDG_CACHE_HOME")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))
        .unwrap_or_else(std::env::temp_dir);
    base.join("regolith").join("beds")
}

/// The restart file of a bed for a model (epsd stores rolling history too).
pub fn bed_file(tag: &str, model: &str) -> String {
    let kind = if model == "epsd" { "r" } else { "h" };
    format!("bed_{tag}_{kind}.restart")
}

/// Build the bed `tag` in `dir` unless both its restart files are there.
pub fn ensure_bed(dir: &Path, tag: &str, me: &Path) -> Result<(), ToolError> {
    let n = SIZES
        .iter()
        .find(|(t, _)| *t == tag)
        .map(|(_, n)| *n)
        .ok_or_else(|| ToolError::Usage(format!("unknown bed '{tag}' (beds: 10k, 50k, 200k)")))?;
    if ["hh", "epsd"]
        .iter()
        .all(|m| dir.join(bed_file(tag, m)).is_file())
    {
        return Ok(());
    }
    std::fs::create_dir_all(dir).map_err(ToolError::file(dir))?;
    let make = dir.join("in.make_bed");
    std::fs::write(&make, MAKE_BED).map_err(ToolError::file(&make))?;
    eprintln!(
        "building the {tag} bed in {} (once; the 200k bed takes tens of minutes)",
        dir.display()
    );
    let status = std::process::Command::new(me)
        .args([
            "-sf",
            "fast",
            "-in",
            "in.make_bed",
            "-log",
            "none",
            "-screen",
            "none",
        ])
        .args(["-var", "n", &n.to_string(), "-var", "tag", tag])
        .current_dir(dir)
        .status()
        .map_err(|e| ToolError::Run(format!("cannot start {}: {e}", me.display())))?;
    if !status.success() {
        return Err(ToolError::Run(format!(
            "building the {tag} bed failed ({status})"
        )));
    }
    Ok(())
}

/// Medians of one program on one case.
#[derive(Debug, Clone)]
pub struct Row {
    /// Bed, model and state.
    pub case: (String, String, String),
    /// Program label and threads.
    pub program: String,
    /// Threads.
    pub threads: usize,
    /// Median figures (rate-relevant fields are medians of the runs).
    pub rate: f64,
    /// Median contacts per second (regolith's contact count, for LIGGGHTS too).
    pub contacts_rate: f64,
    /// Median time split as fractions of the loop time (pair, neigh, comm, output, other).
    pub split: [f64; 5],
    /// Neighbour-list builds and dangerous builds of the first run.
    pub builds: (u64, u64),
    /// Peak memory per particle (bytes).
    pub bytes_per_particle: f64,
    /// Particles.
    pub atoms: u64,
    /// Runs measured.
    pub runs: usize,
}

/// Summarise the runs of one program.
pub fn summarise(
    case: (String, String, String),
    p: &Program,
    runs: &[Measure],
    contacts: Option<u64>,
) -> Row {
    let rate: Vec<f64> = runs.iter().map(Measure::rate).collect();
    let frac = |k: usize| {
        let v: Vec<f64> = runs
            .iter()
            .map(|m| {
                let other = (m.seconds - m.split.iter().sum::<f64>()).max(0.0);
                let parts = [m.split[0], m.split[1], m.split[2], m.split[3], other];
                parts[k] / m.seconds.max(1e-12)
            })
            .collect();
        median(&v)
    };
    let first = runs.first().copied().unwrap_or_default();
    let contacts = first.contacts.or(contacts).unwrap_or(0) as f64;
    let atoms = first.atoms.max(1);
    let peak: Vec<f64> = runs
        .iter()
        .filter_map(|m| m.peak_bytes)
        .map(|b| b as f64)
        .collect();
    let r = median(&rate);
    Row {
        case,
        program: p.label.clone(),
        threads: p.threads,
        rate: r,
        contacts_rate: r * contacts / atoms as f64,
        split: std::array::from_fn(frac),
        builds: (first.builds, first.dangerous),
        bytes_per_particle: median(&peak) / atoms as f64,
        atoms,
        runs: runs.len(),
    }
}

/// Run the suite; the rows in case order, programs in the order given.
pub fn suite(opts: &SuiteOptions, programs: &[Program], me: &Path) -> Result<Vec<Row>, ToolError> {
    let dir = &opts.beds;
    for tag in &opts.sizes {
        ensure_bed(dir, tag, me)?;
    }
    let deck = dir.join("in.bench");
    std::fs::write(&deck, BENCH_DECK).map_err(ToolError::file(&deck))?;
    let mut rows = Vec::new();
    for tag in &opts.sizes {
        let n = SIZES.iter().find(|(t, _)| t == tag).map_or(10_000, |s| s.1);
        let steps = opts
            .steps
            .unwrap_or_else(|| (2.0e7 / n as f64).round().max(100.0) as u64);
        for model in &opts.models {
            if !MODELS.contains(&model.as_str()) {
                return Err(ToolError::Usage(format!(
                    "unknown model '{model}' (hh, sjkr, epsd)"
                )));
            }
            for state in &opts.states {
                if !STATES.contains(&state.as_str()) {
                    return Err(ToolError::Usage(format!(
                        "unknown state '{state}' (rest, shock)"
                    )));
                }
                let vars = vec![
                    ("bed".to_string(), bed_file(tag, model)),
                    ("model".to_string(), model.clone()),
                    ("state".to_string(), state.clone()),
                    ("steps".to_string(), steps.to_string()),
                ];
                let mut runs: Vec<Vec<Measure>> = vec![Vec::new(); programs.len()];
                for _ in 0..opts.repeat.max(1) {
                    for (k, p) in programs.iter().enumerate() {
                        runs[k].push(run_once(p, dir, "in.bench", &vars)?);
                    }
                }
                // LIGGGHTS does not count contacts: take regolith's for the same bed
                let contacts = runs.iter().flatten().find_map(|m| m.contacts);
                for (k, p) in programs.iter().enumerate() {
                    let case = (tag.clone(), model.clone(), state.clone());
                    let row = summarise(case, p, &runs[k], contacts);
                    eprintln!(
                        "{} {} {} {:<10} {:>8.3} M particle-steps/s",
                        tag,
                        model,
                        state,
                        p.label,
                        row.rate / 1e6
                    );
                    rows.push(row);
                }
            }
        }
    }
    Ok(rows)
}
