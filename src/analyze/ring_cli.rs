//! `regolith analyze ring`: options to analysis, per run and across trials.

use super::args::{in_folder, out_dir, pairs, prepare, RingArgs};
use super::ring::{self, RingOptions};
use super::ring_report::{write_run, write_trials};
use super::run::resolve_dt;
use super::series::Series;
use super::AnalyzeError;

/// `regolith analyze ring`.
pub fn analyze_ring(a: &RingArgs) -> Result<(), AnalyzeError> {
    let (folder, log) = prepare(&a.common)?;
    let dt = resolve_dt(a.common.dt, log.as_deref())?;
    let out = out_dir(&a.common, &folder, "post/analysis")?;
    let o = RingOptions {
        sectors: a.sectors,
        bands: a.bands,
        front_fraction: a.front_fraction,
        ..RingOptions::default()
    };
    let mut sets: Vec<(String, String)> = pairs(&a.sets)
        .into_iter()
        .map(|(l, p)| (l, in_folder(&folder, &p)))
        .collect();
    let single = a
        .dumps
        .clone()
        .or_else(|| a.common.run.as_ref().map(|_| "post/ring_*.dump".into()));
    if let Some(d) = single {
        sets.push(("run".into(), in_folder(&folder, &d)));
    }
    if sets.is_empty() {
        return Err(AnalyzeError::Usage(
            "no dumps: give DUMPS, --set LABEL DUMPS, or --run DECK".into(),
        ));
    }
    let mut runs = Vec::new();
    for (k, (label, pattern)) in sets.iter().enumerate() {
        let r = ring::analyze(&Series::open(pattern, dt)?, &o)?;
        let tag = if sets.len() > 1 {
            format!("{label}_run{}_", k + 1)
        } else {
            String::new()
        };
        println!("{pattern} ({label}):");
        for line in write_run(&out, &tag, &r)? {
            println!("  {line}");
        }
        runs.push((label.clone(), r));
    }
    if runs.len() > 1 {
        for line in write_trials(&out, &runs)? {
            println!("{line}");
        }
    }
    println!("tables and figures in {}", out.display());
    Ok(())
}
