//! The `regolith sweep` command line.

use std::path::PathBuf;

use clap::Args;

use super::{observe, parse_axis, parse_reference, Plan};
use crate::tool_error::ToolError;

/// `regolith sweep DECK --var NAME V1,V2,... --observe NAME=EXPR ...`, or
/// `regolith sweep --merge DIR... --out DIR`.
#[derive(Args, Debug, Clone)]
pub struct SweepArgs {
    /// The deck (run from a copy of its folder, one folder per run).
    #[arg(required_unless_present = "merge")]
    pub deck: Option<PathBuf>,
    /// A swept variable and its values: --var NAME V1,V2,... (repeatable: every combination is
    /// run). `sf` sweeps the engine path (off, fast) and `pk` the fast path's threads; other
    /// names are deck variables (-var NAME VALUE).
    #[arg(long = "var", num_args = 2, value_names = ["NAME", "V1,V2,..."], action = clap::ArgAction::Append, allow_hyphen_values = true)]
    pub vars: Vec<String>,
    /// A deck variable every run gets: --set NAME VALUE (repeatable).
    #[arg(long = "set", num_args = 2, value_names = ["NAME", "VALUE"], action = clap::ArgAction::Append, allow_hyphen_values = true)]
    pub set: Vec<String>,
    /// An observable, NAME=EXPR (repeatable): thermo:COLUMN (last thermo line), an equal-style
    /// expression evaluated when the deck ends (v_e, c_ke/2, x[2]-x[1]), or
    /// analyze:chain:c_w, analyze:channel:c_w|c_p|dilation|packing,
    /// analyze:ring:r_mean|r_in|r_out|amplitude|front (optionally :DUMPS).
    #[arg(long = "observe", allow_hyphen_values = true)]
    pub observe: Vec<String>,
    /// A known answer, NAME=VALUE (repeatable): that observable's error is measured against it
    /// instead of the reference run.
    #[arg(long = "expect", allow_hyphen_values = true)]
    pub expect: Vec<String>,
    /// The reference setting, NAME=VALUE[,NAME=VALUE]; names not given take their first value.
    /// Default: the first setting. A value that is not swept is run in addition.
    #[arg(long)]
    pub reference: Option<String>,
    /// Output folder: runs/, sweep.csv, sweep.png, summary.txt (default: sweep/NAME beside the
    /// deck). With --merge: where trade.md and trade.png go.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Runs at once (default: the number of cores).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// Run Debian's `liggghts` instead of regolith (to check reference values).
    #[arg(long)]
    pub liggghts: bool,
    /// Merge the sweeps in these folders (each with a sweep.csv) into one table and figure.
    #[arg(long, num_args = 1.., conflicts_with = "deck")]
    pub merge: Vec<PathBuf>,
    /// With --merge: the figure's title.
    #[arg(long, default_value = "speed/accuracy trade")]
    pub title: String,
    /// With --merge: the cost the figure plots errors against, `wall` (wall time relative to
    /// the reference run's) or `steps` (steps relative to the reference run's: deterministic;
    /// the table then gains a steps and a wall-time row per sweep).
    #[arg(long, value_enum, default_value = "wall")]
    pub cost: super::report::Cost,
}

fn pairs(v: &[String]) -> Vec<(String, String)> {
    v.chunks(2)
        .map(|c| (c[0].clone(), c.get(1).cloned().unwrap_or_default()))
        .collect()
}

/// The plan the arguments describe.
pub fn plan(a: &SweepArgs) -> Result<Plan, ToolError> {
    let deck = a.deck.clone().ok_or(ToolError::usage("no deck"))?;
    if !deck.is_file() {
        return Err(ToolError::Usage(format!(
            "{}: no such deck",
            deck.display()
        )));
    }
    let mut axes = Vec::new();
    for (n, v) in pairs(&a.vars) {
        if axes.iter().any(|x: &super::Axis| x.name == n) {
            return Err(ToolError::Usage(format!("--var {n} is given twice")));
        }
        axes.push(parse_axis(&n, &v)?);
    }
    if axes.is_empty() {
        return Err(ToolError::usage(
            "nothing to sweep: give --var NAME V1,V2,...",
        ));
    }
    let mut observables = Vec::new();
    for o in &a.observe {
        let o = observe::parse(o)?;
        if observables
            .iter()
            .any(|x: &observe::Observable| x.name == o.name)
        {
            return Err(ToolError::Usage(format!(
                "--observe {}: the name is used twice",
                o.name
            )));
        }
        observables.push(o);
    }
    if observables.is_empty() {
        return Err(ToolError::usage(
            "nothing to measure: give --observe NAME=EXPR",
        ));
    }
    for e in &a.expect {
        let (n, v) = e
            .split_once('=')
            .ok_or_else(|| ToolError::Usage(format!("--expect {e}: expected NAME=VALUE")))?;
        let value: f64 = v
            .trim()
            .parse()
            .map_err(|_| ToolError::Usage(format!("--expect {e}: '{v}' is not a number")))?;
        let o = observables
            .iter_mut()
            .find(|o| o.name == n.trim())
            .ok_or_else(|| ToolError::Usage(format!("--expect {e}: no observable named {n}")))?;
        o.expect = Some(value);
    }
    let reference = parse_reference(a.reference.as_deref(), &axes)?;
    let stem = deck
        .file_name()
        .map(|n| n.to_string_lossy().trim_start_matches("in.").to_string())
        .unwrap_or_else(|| "deck".into());
    let folder = deck
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map_or_else(|| PathBuf::from("."), PathBuf::from);
    let out = a
        .out
        .clone()
        .unwrap_or_else(|| folder.join("sweep").join(stem));
    let jobs = a.jobs.unwrap_or_else(|| {
        std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
    });
    Ok(Plan {
        deck,
        axes,
        fixed: pairs(&a.set),
        observables,
        reference,
        out,
        jobs: jobs.max(1),
        liggghts: a.liggghts,
    })
}

/// Run the command; the text to print.
pub fn run(a: &SweepArgs) -> Result<String, ToolError> {
    if !a.merge.is_empty() {
        let out = a.out.clone().unwrap_or_else(|| PathBuf::from("."));
        let md = super::report::merge(&a.merge, &out, &a.title, a.cost)?;
        return Ok(format!(
            "{md}table and figure: {}, {}\n",
            out.join("trade.md").display(),
            out.join("trade.png").display()
        ));
    }
    super::sweep(&plan(a)?)
}
