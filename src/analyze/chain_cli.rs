//! `regolith analyze chain`: options to analysis, per run and over a sweep.

use super::args::{in_folder, out_dir, pairs, parse_f64, prepare, ChainArgs};
use super::chain::{self, ChainOptions, Material};
use super::run::resolve_dt;
use super::series::Series;
use super::AnalyzeError;

/// Analyse one run or a sweep of runs.
pub fn analyze_chain(a: &ChainArgs) -> Result<(), AnalyzeError> {
    let (folder, log) = prepare(&a.common)?;
    let dt = resolve_dt(a.common.dt, log.as_deref())?;
    let out = out_dir(&a.common, &folder, "post/analysis")?;
    let material = match a.material.as_str() {
        "soft" => Material::SOFT,
        "steel" => Material::STEEL,
        m => {
            return Err(AnalyzeError::Usage(format!(
                "--material {m}: soft or steel"
            )))
        }
    };
    let axis = match a.axis.as_str() {
        "x" => 0,
        "y" => 1,
        "z" => 2,
        w => return Err(AnalyzeError::Usage(format!("--axis {w}: x, y or z"))),
    };
    let o = ChainOptions {
        axis,
        skip_first: a.skip_first,
        skip_last: a.skip_last,
        ..ChainOptions::default()
    };
    let mut sets: Vec<(Option<f64>, String)> = Vec::new();
    for (v, p) in pairs(&a.sets) {
        sets.push((Some(parse_f64("--set", &v)?), in_folder(&folder, &p)));
    }
    let single = a
        .dumps
        .clone()
        .or_else(|| a.common.run.as_ref().map(|_| "post/chain_*.dump".into()));
    if let Some(d) = single {
        let vim = match a.vim {
            Some(v) => Some(v),
            None => pairs(&a.common.vars)
                .iter()
                .find(|(n, _)| n == "vim")
                .map(|(_, v)| parse_f64("--var vim", v))
                .transpose()?,
        };
        sets.push((vim, in_folder(&folder, &d)));
    }
    if sets.is_empty() {
        return Err(AnalyzeError::Usage(
            "no dumps: give DUMPS, --set V_IM DUMPS, or --run DECK".into(),
        ));
    }
    let mut runs = Vec::new();
    for (k, (vim, pattern)) in sets.iter().enumerate() {
        let r = chain::analyze(&Series::open(pattern, dt)?, &o)?;
        let tag = if sets.len() > 1 {
            format!("run{}_", k + 1)
        } else {
            String::new()
        };
        let line = super::chain_report::write_run(&out, &tag, &r)?;
        let v = vim.map_or(String::new(), |v| format!("v_im = {v:e} m/s: "));
        println!("{pattern}: {v}{line}");
        if let Some(v) = vim {
            if *v > material.elastic_limit() {
                println!(
                    "WARNING: v_im = {v:e} m/s is above the Hertz elastic limit ({:.3e} m/s): outside Hertz theory",
                    material.elastic_limit()
                );
            }
            runs.push((*v, r.fit));
        }
    }
    let speeds: std::collections::BTreeSet<u64> = runs.iter().map(|r| r.0.to_bits()).collect();
    if speeds.len() > 1 {
        let s = chain::sweep(&runs, a.weak_max, &material);
        for line in super::chain_report::write_sweep(&out, &s)? {
            println!("{line}");
        }
    }
    println!("tables and figures in {}", out.display());
    Ok(())
}
