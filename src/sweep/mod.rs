//! `regolith sweep`: run one deck at every combination of settings, record each run's wall
//! time and observables, and measure each observable's error against a reference run (or a
//! known value): the speed/accuracy trade of a deck, as a table, a CSV file and a figure.
//!
//! - [`args`]: the command line;
//! - [`observe`]: what an observable is (a thermo column, an equal-style expression evaluated
//!   when the deck ends, a `regolith analyze` result) and how it is read from a run;
//! - [`runner`]: the runs, each in a folder of its own, several at once;
//! - [`report`]: errors, the printed table, CSV and PNG; `--merge` of several sweeps.

pub mod args;
pub mod observe;
pub mod report;
pub mod runner;

use std::path::PathBuf;

pub use args::SweepArgs;
use observe::Observable;

use crate::tool_error::ToolError;

/// One swept quantity: a deck variable (`-var NAME VALUE`), or one of the command-line
/// switches `sf` (the engine path: `off`/`exact` or `fast`) and `pk` (threads of the fast
/// path).
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Variable name.
    pub name: String,
    /// Its values, in the order given.
    pub values: Vec<String>,
}

/// One combination of values, in axis order: (name, value).
pub type Setting = Vec<(String, String)>;

/// A setting as text: `frac=0.1 sf=fast`.
pub fn setting_label(s: &Setting) -> String {
    s.iter()
        .map(|(n, v)| format!("{n}={v}"))
        .collect::<Vec<_>>()
        .join(" ")
}

/// Every combination of the axes' values, the first axis varying slowest.
pub fn settings(axes: &[Axis]) -> Vec<Setting> {
    let mut out: Vec<Setting> = vec![Vec::new()];
    for a in axes {
        let mut next = Vec::with_capacity(out.len() * a.values.len());
        for s in &out {
            for v in &a.values {
                let mut t = s.clone();
                t.push((a.name.clone(), v.clone()));
                next.push(t);
            }
        }
        out = next;
    }
    out
}

/// Parse `--var NAME V1,V2,...`.
pub fn parse_axis(name: &str, values: &str) -> Result<Axis, ToolError> {
    if name.is_empty() || !name.chars().all(|c| c.is_alphanumeric() || c == '_') {
        return Err(ToolError::Usage(format!(
            "--var {name}: a variable name is letters, digits and underscores"
        )));
    }
    let values: Vec<String> = values
        .split(',')
        .map(|v| v.trim().to_string())
        .filter(|v| !v.is_empty())
        .collect();
    if values.is_empty() {
        return Err(ToolError::Usage(format!(
            "--var {name}: no values (give V1,V2,...)"
        )));
    }
    for v in &values {
        match name {
            "sf" if !matches!(v.as_str(), "off" | "exact" | "fast") => {
                return Err(ToolError::Usage(format!(
                    "--var sf {v}: the engine path is off (exact) or fast"
                )))
            }
            "pk" if v.parse::<usize>().map_or(true, |n| n == 0) => {
                return Err(ToolError::Usage(format!(
                    "--var pk {v}: threads of the fast path, an integer >= 1"
                )))
            }
            _ => {}
        }
    }
    Ok(Axis {
        name: name.to_string(),
        values,
    })
}

/// Parse `--reference NAME=VALUE[,NAME=VALUE...]` against the axes: names not given take their
/// axis's first value; a value need not be one of the swept ones (the reference is then run
/// in addition).
pub fn parse_reference(text: Option<&str>, axes: &[Axis]) -> Result<Setting, ToolError> {
    let mut s: Setting = axes
        .iter()
        .map(|a| (a.name.clone(), a.values[0].clone()))
        .collect();
    let Some(text) = text else {
        return Ok(s);
    };
    for part in text.split([',', ' ']).filter(|p| !p.is_empty()) {
        let (n, v) = part.split_once('=').ok_or_else(|| {
            ToolError::Usage(format!(
                "--reference {text}: expected NAME=VALUE[,NAME=VALUE...], got '{part}'"
            ))
        })?;
        match s.iter_mut().find(|(name, _)| name == n) {
            Some(slot) => slot.1 = v.to_string(),
            None => {
                return Err(ToolError::Usage(format!(
                    "--reference {text}: {n} is not a swept variable (swept: {})",
                    axes.iter()
                        .map(|a| a.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )))
            }
        }
    }
    Ok(s)
}

/// Everything a sweep needs.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The deck.
    pub deck: PathBuf,
    /// The swept quantities.
    pub axes: Vec<Axis>,
    /// Variables every run gets (`--var NAME VALUE` with one value is an axis of one value;
    /// these are given with `--set`).
    pub fixed: Vec<(String, String)>,
    /// What is measured.
    pub observables: Vec<Observable>,
    /// The reference setting.
    pub reference: Setting,
    /// Where runs, CSV and figures go.
    pub out: PathBuf,
    /// Runs at once.
    pub jobs: usize,
    /// Run Debian's `liggghts` instead of regolith (no `sf`/`pk` axes then).
    pub liggghts: bool,
}

/// Run a whole sweep and write its report; returns the printed text.
pub fn sweep(plan: &Plan) -> Result<String, ToolError> {
    if plan.liggghts && plan.axes.iter().any(|a| a.name == "sf" || a.name == "pk") {
        return Err(ToolError::usage(
            "--liggghts: LIGGGHTS has no fast path, so sf and pk cannot be swept",
        ));
    }
    let mut list = settings(&plan.axes);
    let reference_index = match list.iter().position(|s| *s == plan.reference) {
        Some(k) => k,
        None => {
            list.push(plan.reference.clone());
            list.len() - 1
        }
    };
    std::fs::create_dir_all(&plan.out).map_err(ToolError::file(&plan.out))?;
    let runs = runner::run_all(plan, &list)?;
    let result = report::SweepResult::new(plan, runs, reference_index);
    let text = result.write(&plan.out)?;
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn product_of_axes_and_reference() {
        let axes = vec![
            parse_axis("frac", "0.4,0.1").unwrap(),
            parse_axis("sf", "off,fast").unwrap(),
        ];
        let s = settings(&axes);
        assert_eq!(s.len(), 4);
        assert_eq!(setting_label(&s[1]), "frac=0.4 sf=fast");
        let r = parse_reference(Some("frac=0.01"), &axes).unwrap();
        assert_eq!(setting_label(&r), "frac=0.01 sf=off");
        assert!(parse_reference(Some("dt=1"), &axes).is_err());
        assert!(parse_reference(Some("frac"), &axes).is_err());
        assert!(parse_axis("sf", "gpu").is_err());
        assert!(parse_axis("pk", "0").is_err());
        assert!(parse_axis("a b", "1").is_err());
        assert!(parse_axis("a", ",").is_err());
    }
}
