//! The `regolith analyze` command line and what each subcommand prints and writes.

use std::path::{Path, PathBuf};

use clap::{Args, Subcommand};

use super::run::RunRequest;
use super::table::ensure_dir;
use super::AnalyzeError;

/// Options every analysis takes.
#[derive(Args, Debug, Clone)]
pub struct Common {
    /// Time step (s), turning dump steps into seconds.
    #[arg(long)]
    pub dt: Option<f64>,
    /// Read the time step from this log (the last echoed `timestep` command).
    #[arg(long)]
    pub log: Option<PathBuf>,
    /// Folder for the CSV tables and PNG figures.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Run this deck first (from its own folder, screen off, log in log.liggghts there); the
    /// dump names are then relative to the deck's folder.
    #[arg(long)]
    pub run: Option<PathBuf>,
    /// Deck variables for --run: --var NAME VALUE (repeatable).
    #[arg(long = "var", num_args = 2, value_names = ["NAME", "VALUE"], action = clap::ArgAction::Append)]
    pub vars: Vec<String>,
    /// With --run: run Debian's `liggghts` instead of regolith.
    #[arg(long)]
    pub liggghts: bool,
}

/// `regolith analyze ...`
#[derive(Subcommand, Debug, Clone)]
pub enum AnalyzeCommand {
    /// Struck chain: peak force per particle, arrival times, wave speed c_w; with several
    /// --set V DUMPS, c_w against the impact speed v_im with its exponent and the weak-impact
    /// sound speed.
    Chain(ChainArgs),
    /// Lunar channel: sensor grid, wave arrival, c_w and c_p, bed height and dilation,
    /// initial overlap against depth, per-particle panels; with several --set V_P DUMPS,
    /// speeds and dilation against the piston speed (mean and spread over seeds).
    Channel(ChannelArgs),
    /// Radial blast: inner/outer radius of the disturbed surface, compaction front,
    /// corrugation amplitude over time, azimuthal force spectrum in annular bands; with
    /// several --set LABEL DUMPS, the trials compared (mean and spread over seeds).
    Ring(RingArgs),
}

/// `regolith analyze ring`.
#[derive(Args, Debug, Clone)]
pub struct RingArgs {
    /// One run's dumps (a file or a `*` series); default post/ring_*.dump with --run.
    pub dumps: Option<String>,
    /// A run of a comparison: its label (trial name) and dumps (repeatable; repeated labels
    /// are seeds, averaged).
    #[arg(long = "set", num_args = 2, value_names = ["LABEL", "DUMPS"], action = clap::ArgAction::Append)]
    pub sets: Vec<String>,
    /// Angular sectors for the surface R(theta).
    #[arg(long, default_value_t = 72)]
    pub sectors: usize,
    /// Annular bands of the force spectrum.
    #[arg(long, default_value_t = 3)]
    pub bands: usize,
    /// The compaction front is where the mean radial velocity falls below this fraction of
    /// its peak.
    #[arg(long, default_value_t = 0.1)]
    pub front_fraction: f64,
    #[command(flatten)]
    pub common: Common,
}

/// `regolith analyze channel`.
#[derive(Args, Debug, Clone)]
pub struct ChannelArgs {
    /// One shock run's dumps (a file or a `*` series); default post/shock_*.dump with --run.
    pub dumps: Option<String>,
    /// A run of a sweep: its piston speed (m/s) and dumps (repeatable; repeated speeds are
    /// seeds, averaged).
    #[arg(long = "set", num_args = 2, value_names = ["V_P", "DUMPS"], action = clap::ArgAction::Append)]
    pub sets: Vec<String>,
    /// `dump local` of compute pair/gran/local (ids, ..., overlap last) at the first step,
    /// for the initial overlap against depth; default contacts_0.dump beside the dumps.
    #[arg(long)]
    pub contacts: Option<String>,
    /// Sensor cell edge (m).
    #[arg(long, default_value_t = 0.005)]
    pub cell: f64,
    /// Particles averaged for a column's height.
    #[arg(long, default_value_t = 10)]
    pub top_n: usize,
    /// Times of the per-particle panels (s), comma-separated.
    #[arg(long, value_delimiter = ',')]
    pub panel_times: Vec<f64>,
    /// Column of the yy per-atom stress.
    #[arg(long, default_value = "c_stress[2]")]
    pub syy: String,
    /// Column of the yz per-atom stress.
    #[arg(long, default_value = "c_stress[6]")]
    pub syz: String,
    /// Gravity (m/s2) for the overlap estimate.
    #[arg(long, default_value_t = 1.625)]
    pub gravity: f64,
    #[command(flatten)]
    pub common: Common,
}

/// `regolith analyze chain`.
#[derive(Args, Debug, Clone)]
pub struct ChainArgs {
    /// One run's dumps (a file or a `*` series); default post/chain_*.dump with --run.
    pub dumps: Option<String>,
    /// A run of a sweep: its impact speed (m/s) and dumps (repeatable; repeated speeds are
    /// seeds or repeats, averaged).
    #[arg(long = "set", num_args = 2, value_names = ["V_IM", "DUMPS"], action = clap::ArgAction::Append)]
    pub sets: Vec<String>,
    /// Impact speed of the single run (m/s); default the --var vim given with --run.
    #[arg(long)]
    pub vim: Option<f64>,
    /// Material for the sound speed and the Hertz elastic limit: soft or steel.
    #[arg(long, default_value = "soft")]
    pub material: String,
    /// Axis of the column: x, y or z.
    #[arg(long, default_value = "z")]
    pub axis: String,
    /// Layers next to the struck end left out of the fit.
    #[arg(long, default_value_t = 2)]
    pub skip_first: usize,
    /// Layers at the free end left out of the fit.
    #[arg(long, default_value_t = 1)]
    pub skip_last: usize,
    /// Impacts up to this speed (m/s) are weak (sound speed); faster ones enter the power law.
    #[arg(long, default_value_t = 1e-4)]
    pub weak_max: f64,
    #[command(flatten)]
    pub common: Common,
}

pub(super) fn pairs(v: &[String]) -> Vec<(String, String)> {
    v.chunks(2)
        .map(|c| (c[0].clone(), c.get(1).cloned().unwrap_or_default()))
        .collect()
}

/// Run the deck if asked; return (folder the dump names are relative to, log to read dt from).
pub(super) fn prepare(c: &Common) -> Result<(PathBuf, Option<PathBuf>), AnalyzeError> {
    let Some(deck) = &c.run else {
        return Ok((PathBuf::from("."), c.log.clone()));
    };
    let req = RunRequest {
        deck: deck.clone(),
        vars: pairs(&c.vars),
        liggghts: c.liggghts,
    };
    eprintln!(
        "running {} in {} ({}; log {})",
        deck.display(),
        req.folder().display(),
        if c.liggghts { "liggghts" } else { "regolith" },
        req.log().display()
    );
    req.run()?;
    Ok((req.folder(), c.log.clone().or_else(|| Some(req.log()))))
}

pub(super) fn in_folder(folder: &Path, pattern: &str) -> String {
    if folder == Path::new(".") || Path::new(pattern).is_absolute() {
        pattern.to_string()
    } else {
        folder.join(pattern).display().to_string()
    }
}

pub(super) fn out_dir(c: &Common, folder: &Path, default: &str) -> Result<PathBuf, AnalyzeError> {
    let dir = c.out.clone().unwrap_or_else(|| folder.join(default));
    ensure_dir(&dir)?;
    Ok(dir)
}

pub(super) fn parse_f64(what: &str, w: &str) -> Result<f64, AnalyzeError> {
    w.parse()
        .map_err(|_| AnalyzeError::Usage(format!("{what}: '{w}' is not a number")))
}

/// Run an analysis; the summary goes to standard output.
pub fn analyze(cmd: &AnalyzeCommand) -> Result<(), AnalyzeError> {
    match cmd {
        AnalyzeCommand::Chain(a) => super::chain_cli::analyze_chain(a),
        AnalyzeCommand::Channel(a) => super::channel_cli::analyze_channel(a),
        AnalyzeCommand::Ring(a) => super::ring_cli::analyze_ring(a),
    }
}
