//! `regolith analyze channel`: options to analysis, per run and over a sweep.

use std::path::Path;

use super::args::{in_folder, out_dir, pairs, parse_f64, prepare, ChannelArgs};
use super::chain::Material;
use super::channel::{self, ChannelOptions, ChannelResult};
use super::channel_report::{write_run, write_sweep, SweepRun};
use super::overlap::{contact_depths, profile, Bed, OverlapProfile};
use super::run::resolve_dt;
use super::series::Series;
use super::AnalyzeError;

/// The contacts file beside a dump pattern (`contacts_0.dump`, plain or gzip), if present.
fn contacts_beside(pattern: &str) -> Option<String> {
    let dir = Path::new(pattern).parent().unwrap_or(Path::new(""));
    ["contacts_0.dump", "contacts_0.dump.gz"]
        .iter()
        .map(|n| dir.join(n))
        .find(|p| p.exists())
        .map(|p| p.display().to_string())
}

fn overlap_profile(
    series: &Series,
    contacts: &str,
    r: &ChannelResult,
    gravity: f64,
) -> Result<OverlapProfile, AnalyzeError> {
    let first_step = series.steps().first().copied().unwrap_or(0);
    let mut first = None;
    series.for_steps(&[first_step], |fr| {
        first.get_or_insert(fr);
        Ok(())
    })?;
    let first = first.ok_or_else(|| AnalyzeError::Read("no first snapshot".into()))?;
    let rad = first.col(&["radius"])?;
    let radius = first.rows.iter().map(|w| w[rad]).sum::<f64>() / first.rows.len().max(1) as f64;
    let pairs = contact_depths(contacts, &first, (0, 1), None)?;
    let heights: Vec<f64> = r.heights.frames[0]
        .1
        .iter()
        .copied()
        .filter(|h| h.is_finite())
        .collect();
    let surface = heights.iter().sum::<f64>() / heights.len().max(1) as f64;
    let bed = Bed {
        material: Material::SOFT,
        radius,
        packing: r.packing,
        gravity,
    };
    Ok(profile(&pairs, surface, r.grid.cell, &bed))
}

/// Analyse one run or a sweep of runs.
pub fn analyze_channel(a: &ChannelArgs) -> Result<(), AnalyzeError> {
    let (folder, log) = prepare(&a.common)?;
    let dt = resolve_dt(a.common.dt, log.as_deref())?;
    let out = out_dir(&a.common, &folder, "post/analysis")?;
    let o = ChannelOptions {
        cell: a.cell,
        top_n: a.top_n,
        panel_times: a.panel_times.clone(),
        stress_columns: (vec![a.syy.clone()], vec![a.syz.clone()]),
        ..ChannelOptions::default()
    };
    let mut sets: Vec<(Option<f64>, String)> = Vec::new();
    for (v, p) in pairs(&a.sets) {
        sets.push((Some(parse_f64("--set", &v)?), in_folder(&folder, &p)));
    }
    let single = a
        .dumps
        .clone()
        .or_else(|| a.common.run.as_ref().map(|_| "post/shock_*.dump".into()));
    if let Some(d) = single {
        let vp = pairs(&a.common.vars)
            .iter()
            .find(|(n, _)| n == "vp")
            .map(|(_, v)| parse_f64("--var vp", v))
            .transpose()?;
        sets.push((vp, in_folder(&folder, &d)));
    }
    if sets.is_empty() {
        return Err(AnalyzeError::Usage(
            "no dumps: give DUMPS, --set V_P DUMPS, or --run DECK".into(),
        ));
    }
    let mut runs: Vec<SweepRun> = Vec::new();
    for (k, (vp, pattern)) in sets.iter().enumerate() {
        let series = Series::open(pattern, dt)?;
        let r = channel::analyze(&series, &o)?;
        let contacts = match (&a.contacts, sets.len()) {
            (Some(c), 1) => Some(in_folder(&folder, c)),
            _ => contacts_beside(pattern),
        };
        let overlap = contacts
            .map(|c| overlap_profile(&series, &c, &r, a.gravity))
            .transpose()?;
        let tag = if sets.len() > 1 {
            format!("run{}_", k + 1)
        } else {
            String::new()
        };
        let head = vp.map_or(String::new(), |v| format!(" (v_p = {v} m/s)"));
        println!("{pattern}{head}:");
        for line in write_run(&out, &tag, &r, overlap.as_ref())? {
            println!("  {line}");
        }
        if let Some(v) = vp {
            runs.push((
                *v,
                r.c_w.map(|s| s.speed),
                r.c_p.map(|s| s.speed),
                r.dilation_mean.map(|d| d.0),
                overlap.as_ref().map(|p| p.c0_chain),
            ));
        }
    }
    if runs.len() > 1 {
        for line in write_sweep(&out, &runs)? {
            println!("{line}");
        }
    }
    println!("tables and figures in {}", out.display());
    Ok(())
}
