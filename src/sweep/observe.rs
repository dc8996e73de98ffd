//! Observables of a sweep and how each is read from a finished run.
//!
//! `--observe NAME=EXPR` where EXPR is
//! - `thermo:COLUMN`: the column's value on the last thermo line of the log;
//! - `analyze:chain:c_w`, `analyze:channel:c_w|c_p|dilation|rise|packing`,
//!   `analyze:ring:r_mean|amplitude|front` (optionally `:DUMPS`, a file or `*` series relative
//!   to the run's folder; default `post/chain_*.dump`, `post/shock_*.dump`, `post/ring_*.dump`):
//!   a `regolith analyze` result from the run's dumps, its time step from the run's log;
//! - anything else: an equal-style expression (`v_e`, `c_ke/2`, `x[2]-x[1]`), evaluated when
//!   the deck ends: the sweep appends `variable` and `print` lines to its copy of the deck.

use std::path::Path;

use crate::analyze::series::Series;
use crate::tool_error::ToolError;

/// Where an observable's value comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// A thermo column at the last thermo line.
    Thermo(String),
    /// An equal-style expression evaluated after the deck's last command.
    Expr(String),
    /// A `regolith analyze` result from the run's dumps.
    Analyze {
        /// chain, channel or ring.
        kind: String,
        /// The quantity.
        quantity: String,
        /// The dumps (relative to the run's folder).
        dumps: String,
    },
}

/// One observable.
#[derive(Debug, Clone, PartialEq)]
pub struct Observable {
    /// Its name (CSV column, legend).
    pub name: String,
    /// Where its value comes from.
    pub source: Source,
    /// A known answer: errors are measured against it instead of the reference run.
    pub expect: Option<f64>,
}

const ANALYSES: &[(&str, &[&str], &str)] = &[
    ("chain", &["c_w"], "post/chain_*.dump"),
    (
        "channel",
        &["c_w", "c_p", "dilation", "rise", "packing"],
        "post/shock_*.dump",
    ),
    (
        "ring",
        &["r_mean", "r_in", "r_out", "amplitude", "front"],
        "post/ring_*.dump",
    ),
];

/// Parse `NAME=EXPR`.
pub fn parse(text: &str) -> Result<Observable, ToolError> {
    let (name, expr) = text
        .split_once('=')
        .ok_or_else(|| ToolError::Usage(format!("--observe {text}: expected NAME=EXPR")))?;
    let name = name.trim();
    if name.is_empty()
        || !name
            .chars()
            .all(|c| c.is_alphanumeric() || c == '_' || c == '-')
    {
        return Err(ToolError::Usage(format!(
            "--observe {text}: a name is letters, digits, '_' and '-'"
        )));
    }
    let expr = expr.trim();
    if expr.is_empty() {
        return Err(ToolError::Usage(format!("--observe {text}: no expression")));
    }
    let source = if let Some(col) = expr.strip_prefix("thermo:") {
        Source::Thermo(col.to_string())
    } else if let Some(rest) = expr.strip_prefix("analyze:") {
        let mut parts = rest.splitn(3, ':');
        let kind = parts.next().unwrap_or("");
        let quantity = parts.next().unwrap_or("");
        let Some((_, quantities, default)) = ANALYSES.iter().find(|a| a.0 == kind) else {
            return Err(ToolError::Usage(format!(
                "--observe {text}: analyses are chain, channel and ring"
            )));
        };
        if !quantities.contains(&quantity) {
            return Err(ToolError::Usage(format!(
                "--observe {text}: analyze:{kind} gives {}",
                quantities.join(", ")
            )));
        }
        Source::Analyze {
            kind: kind.to_string(),
            quantity: quantity.to_string(),
            dumps: parts.next().unwrap_or(default).to_string(),
        }
    } else {
        if expr.contains('"') {
            return Err(ToolError::Usage(format!(
                "--observe {text}: an expression cannot hold double quotes"
            )));
        }
        Source::Expr(expr.to_string())
    };
    Ok(Observable {
        name: name.to_string(),
        source,
        expect: None,
    })
}

/// The prefix of the lines the appended `print` commands write.
pub const MARK: &str = "regolith-sweep";

/// Lines appended to the run's copy of the deck: one equal-style variable and one `print`
/// per expression observable.
pub fn appendix(observables: &[Observable]) -> String {
    let mut s = String::new();
    for (k, o) in observables.iter().enumerate() {
        if let Source::Expr(e) = &o.source {
            if s.is_empty() {
                s.push_str(
                    "\n# appended by regolith sweep: the observables at the end of the deck\n",
                );
            }
            s.push_str(&format!(
                "variable regolith_sweep_{k} equal \"{e}\"\nprint \"{MARK} {k} ${{regolith_sweep_{k}}}\"\n"
            ));
        }
    }
    s
}

/// The value of observable `k` from a finished run: its folder and log text.
pub fn read(o: &Observable, k: usize, dir: &Path, log: &str) -> Result<f64, ToolError> {
    match &o.source {
        Source::Expr(_) => {
            let prefix = format!("{MARK} {k} ");
            let line =
                log.lines()
                    .rev()
                    .find(|l| l.starts_with(&prefix))
                    .ok_or(ToolError::content(
                        "not printed: the deck did not reach its end (an error or quit?)",
                    ))?;
            let w = line[prefix.len()..].trim();
            w.parse::<f64>()
                .map_err(|_| ToolError::Content(format!("printed '{w}', not a number")))
        }
        Source::Thermo(col) => {
            let rows = crate::io::diff::parse_thermo(log);
            let (_, last) = rows
                .iter()
                .next_back()
                .ok_or(ToolError::content("no thermo output in the log"))?;
            last.get(col).copied().ok_or_else(|| {
                ToolError::Content(format!(
                    "no thermo column {col} (the last thermo lines have: {})",
                    last.keys().cloned().collect::<Vec<_>>().join(" ")
                ))
            })
        }
        Source::Analyze {
            kind,
            quantity,
            dumps,
        } => {
            let dt = crate::analyze::dt_from_log(log).ok_or(ToolError::content(
                "no echoed `timestep` in the log, so no time step for the analysis",
            ))?;
            let pattern = dir.join(dumps).display().to_string();
            let series =
                Series::open(&pattern, dt).map_err(|e| ToolError::Content(e.to_string()))?;
            analysis(kind, quantity, &series)
                .map_err(|e| ToolError::Content(format!("analyze {kind}: {e}")))
        }
    }
}

fn analysis(
    kind: &str,
    quantity: &str,
    series: &Series,
) -> Result<f64, crate::analyze::AnalyzeError> {
    use crate::analyze::{chain, channel, ring, AnalyzeError};
    let missing = |what: &str| AnalyzeError::Fit(format!("no {what} measured"));
    match kind {
        "chain" => Ok(chain::analyze(series, &chain::ChainOptions::default())?
            .fit
            .slope),
        "channel" => {
            let r = channel::analyze(series, &channel::ChannelOptions::default())?;
            match quantity {
                "c_w" => r.c_w.map(|s| s.speed).ok_or_else(|| missing("c_w")),
                "c_p" => r.c_p.map(|s| s.speed).ok_or_else(|| missing("c_p")),
                "dilation" => r
                    .dilation_mean
                    .map(|d| d.0)
                    .ok_or_else(|| missing("dilation")),
                "rise" => r.rise.map(|d| d.0).ok_or_else(|| missing("rise")),
                _ => Ok(r.packing),
            }
        }
        _ => {
            let r = ring::analyze(series, &ring::RingOptions::default())?;
            let last = r.states.last().ok_or_else(|| missing("snapshot"))?;
            Ok(match quantity {
                "r_mean" => last.r_mean,
                "r_in" => last.r_in,
                "r_out" => last.r_out,
                "amplitude" => last.amplitude,
                _ => last.front,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_of_observables() {
        let o = parse("e=v_e").unwrap();
        assert_eq!(o.source, Source::Expr("v_e".into()));
        let o = parse("ke = thermo:c_ke").unwrap();
        assert_eq!(
            (o.name.as_str(), o.source),
            ("ke", Source::Thermo("c_ke".into()))
        );
        let o = parse("cw=analyze:chain:c_w").unwrap();
        assert!(
            matches!(o.source, Source::Analyze { ref dumps, .. } if dumps == "post/chain_*.dump")
        );
        let o = parse("rise=analyze:channel:dilation:out/s_*.dump").unwrap();
        assert!(matches!(o.source, Source::Analyze { ref dumps, .. } if dumps == "out/s_*.dump"));
        let o = parse("rise=analyze:channel:rise").unwrap();
        assert!(
            matches!(o.source, Source::Analyze { ref quantity, ref dumps, .. } if quantity == "rise" && dumps == "post/shock_*.dump")
        );
        assert!(parse("x").is_err());
        assert!(parse("a b=1").is_err());
        assert!(parse("c=analyze:chain:speed").is_err());
        assert!(parse("c=analyze:pile:c_w").is_err());
        assert!(parse("q=\"x\"").is_err());
    }

    #[test]
    fn values_from_a_log() {
        let obs = [parse("e=v_e").unwrap(), parse("ke=thermo:c_ke").unwrap()];
        let app = appendix(&obs);
        assert!(
            app.contains("variable regolith_sweep_0 equal \"v_e\"\n"),
            "{app}"
        );
        assert!(
            app.contains("print \"regolith-sweep 0 ${regolith_sweep_0}\"\n"),
            "{app}"
        );
        let log = "    Step           c_ke \n       0              2 \n     100            1.5 \nLoop time of 0.1 on 1 procs\nprint \"regolith-sweep 0 ${regolith_sweep_0}\"\nregolith-sweep 0 0.4999698\n";
        let dir = Path::new(".");
        assert_eq!(read(&obs[0], 0, dir, log), Ok(0.4999698));
        assert_eq!(read(&obs[1], 1, dir, log), Ok(1.5));
        assert!(read(&obs[0], 0, dir, "").is_err());
        let bad = parse("x=thermo:nope").unwrap();
        assert!(read(&bad, 1, dir, log)
            .unwrap_err()
            .to_string()
            .contains("c_ke"));
    }
}
