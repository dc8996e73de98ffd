//! Tables, figures and the printed summary of the channel analysis.

use std::collections::BTreeMap;
use std::path::Path;

use super::channel::{ChannelResult, SpeedFit};
use super::fit::mean_std;
use super::overlap::OverlapProfile;
use super::plot::{save, Chart, Curve, Style};
use super::table::Table;
use super::AnalyzeError;

fn speed_text(name: &str, s: &Option<SpeedFit>) -> String {
    match s {
        Some(s) => format!(
            "{name} = {:.3} +/- {:.3} m/s (y in [{:.3}, {:.3}] m, {} cells)",
            s.speed, s.speed_err, s.range.0, s.range.1, s.fit.n
        ),
        None => format!("{name}: no fit (too few cells with an arrival in its range)"),
    }
}

/// Write the run's tables and figures into `dir` (names prefixed with `tag`); return the
/// summary lines.
pub fn write_run(
    dir: &Path,
    tag: &str,
    r: &ChannelResult,
    overlap: Option<&OverlapProfile>,
) -> Result<Vec<String>, AnalyzeError> {
    let name = |base: &str| dir.join(format!("{tag}{base}"));
    let mut t = Table::new(&[
        "t_s",
        "y_m",
        "z_m",
        "particles",
        "force_N",
        "overlap_m",
        "packing",
    ]);
    for (time, c) in &r.cells {
        for k in 0..r.grid.len() {
            let (y, z) = r.grid.center(k);
            t.push(&[
                *time,
                y,
                z,
                c.count[k] as f64,
                c.force[k],
                c.overlap[k],
                c.packing[k],
            ]);
        }
    }
    t.write(&name("channel_cells.csv"))?;
    let mut t = Table::new(&["y_m", "z_m", "arrival_s"]);
    for a in &r.arrivals {
        t.push(&[a.y, a.z, a.t]);
    }
    t.write(&name("channel_arrival.csv"))?;
    let mut t = Table::new(&["t_s", "y_m", "height_m"]);
    for (time, h) in &r.heights.frames {
        for (y, v) in r.heights.y.iter().zip(h) {
            t.push(&[*time, *y, *v]);
        }
    }
    t.write(&name("channel_height.csv"))?;
    let mut t = Table::new(&["y_m", "dilation_m", "excluded"]);
    for d in &r.dilation {
        t.push(&[d.0, d.1, if d.2 { 1.0 } else { 0.0 }]);
    }
    t.write(&name("channel_dilation.csv"))?;

    arrival_figure(&name("channel_arrival.png"), r)?;
    dilation_figure(&name("channel_dilation.png"), r)?;
    super::channel_panels::write(&name("channel_panels"), r)?;
    let mut lines = vec![
        speed_text("wave speed c_w", &r.c_w),
        speed_text("solitary speed c_p", &r.c_p),
    ];
    lines.push(match r.dilation_mean {
        Some((m, s)) => format!(
            "dilation (final minus initial bed height, {:.3} m from the ends left out): {:.3e} m, spread {:.2e} m over {} columns",
            r.end_margin,
            m,
            s,
            r.dilation.iter().filter(|d| !d.2).count()
        ),
        None => "dilation: no column away from the ends".into(),
    });
    lines.push(match (r.rise, &r.c_w) {
        (Some((m, s)), Some(c)) => format!(
            "surface rise behind the front (final minus initial bed height, columns in ({:.3}, {:.3}] m): {m:.3e} m, spread {s:.2e} m",
            r.grid.cell, c.range.1
        ),
        (Some((m, s)), None) => format!("surface rise behind the front: {m:.3e} m, spread {s:.2e} m"),
        (None, _) => "surface rise behind the front: no column".into(),
    });
    lines.push(format!(
        "initial packing fraction of the bed: {:.4}",
        r.packing
    ));
    if let Some(p) = overlap {
        let mut t = Table::new(&[
            "depth_m",
            "measured_overlap_m",
            "contacts",
            "chain_estimate_m",
        ]);
        for b in &p.bins {
            t.push(&[b.depth, b.measured, b.contacts as f64, b.estimate]);
        }
        t.write(&name("channel_overlap.csv"))?;
        overlap_figure(&name("channel_overlap.png"), p)?;
        lines.push(format!(
            "sound-speed estimate c_0: {:.3} m/s from the 1D-chain overlap{}",
            p.c0_chain,
            p.c0_measured.map_or(String::new(), |c| format!(
                ", {c:.3} m/s from the measured mean overlap"
            ))
        ));
    }
    Ok(lines)
}

fn arrival_figure(path: &Path, r: &ChannelResult) -> Result<(), AnalyzeError> {
    let mut curves = vec![Curve::new(
        "arrival per 0.5 cm cell",
        r.arrivals.iter().map(|a| (a.t, a.y)).collect(),
        Style::Points,
    )];
    for (label, s) in [("c_w", &r.c_w), ("c_p", &r.c_p)] {
        if let Some(s) = s {
            let y0 = s.kept.iter().map(|p| p.0).fold(f64::INFINITY, f64::min);
            let y1 = s.kept.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
            curves.push(Curve::new(
                &format!("{label} = {:.3} +/- {:.3} m/s", s.speed, s.speed_err),
                vec![(s.fit.at(y0), y0), (s.fit.at(y1), y1)],
                Style::Line,
            ));
        }
    }
    let chart = Chart {
        title: "Wave arrival (first force maximum above 10x the initial mean)".into(),
        x_label: "arrival time (s)".into(),
        y_label: "distance from the piston y (m)".into(),
        curves,
        ..Default::default()
    };
    save(path, &[chart], 900, 600)
}

fn dilation_figure(path: &Path, r: &ChannelResult) -> Result<(), AnalyzeError> {
    let h = &r.heights;
    let first = &h.frames[0].1;
    let last = &h.frames[h.frames.len() - 1];
    let heights = Chart {
        title: "Bed height per 0.5 cm column".into(),
        x_label: "y (m)".into(),
        y_label: "height (m)".into(),
        curves: vec![
            Curve::new(
                "initial",
                h.y.iter().copied().zip(first.iter().copied()).collect(),
                Style::Line,
            ),
            Curve::new(
                &format!("t = {:.3} s", last.0),
                h.y.iter().copied().zip(last.1.iter().copied()).collect(),
                Style::Line,
            ),
        ],
        ..Default::default()
    };
    let (kept, ends): (Vec<&(f64, f64, bool)>, Vec<_>) = r.dilation.iter().partition(|d| !d.2);
    let dil = Chart {
        title: match r.dilation_mean {
            Some((m, s)) => format!("Dilation: {:.3} +/- {:.3} mm", m * 1e3, s * 1e3),
            None => "Dilation".into(),
        },
        x_label: "y (m)".into(),
        y_label: "final minus initial height (mm)".into(),
        curves: vec![
            Curve::new(
                "columns used",
                kept.iter().map(|d| (d.0, d.1 * 1e3)).collect(),
                Style::Points,
            ),
            Curve::new(
                "next to an end wall (left out)",
                ends.iter().map(|d| (d.0, d.1 * 1e3)).collect(),
                Style::Points,
            ),
        ],
        ..Default::default()
    };
    save(path, &[heights, dil], 900, 420)
}

fn overlap_figure(path: &Path, p: &OverlapProfile) -> Result<(), AnalyzeError> {
    let chart = Chart {
        title: "Initial contact overlap against depth".into(),
        x_label: "depth below the surface (m)".into(),
        y_label: "overlap (um)".into(),
        curves: vec![
            Curve::new(
                "measured (mean per 0.5 cm)",
                p.bins
                    .iter()
                    .filter(|b| b.contacts > 0)
                    .map(|b| (b.depth, b.measured * 1e6))
                    .collect(),
                Style::Points,
            ),
            Curve::new(
                "1D-chain estimate",
                p.bins.iter().map(|b| (b.depth, b.estimate * 1e6)).collect(),
                Style::Dashed,
            ),
        ],
        ..Default::default()
    };
    save(path, &[chart], 900, 500)
}

/// One run of a sweep: piston speed (m/s), c_w, c_p (m/s), dilation (m), sound-speed
/// estimate (m/s).
pub type SweepRun = (f64, Option<f64>, Option<f64>, Option<f64>, Option<f64>);

/// Write `channel_sweep.csv` and `channel_sweep.png`: mean and spread over the runs at each
/// piston speed; return the summary lines.
pub fn write_sweep(dir: &Path, runs: &[SweepRun]) -> Result<Vec<String>, AnalyzeError> {
    let mut by_v: BTreeMap<u64, Vec<&SweepRun>> = BTreeMap::new();
    for r in runs {
        by_v.entry(r.0.to_bits()).or_default().push(r);
    }
    // a quantity counts at a speed when more than half of its runs measured it
    let stat = |rs: &[&SweepRun], f: fn(&SweepRun) -> Option<f64>| {
        let vals: Vec<f64> = rs.iter().filter_map(|r| f(r)).collect();
        (2 * vals.len() > rs.len())
            .then(|| mean_std(&vals))
            .flatten()
    };
    let mut t = Table::new(&[
        "v_p_m_s",
        "runs",
        "c_w_m_s",
        "c_w_spread",
        "c_p_m_s",
        "c_p_spread",
        "dilation_m",
        "dilation_spread",
    ]);
    let mut series: [Vec<(f64, f64, f64)>; 3] = Default::default();
    let mut lines = Vec::new();
    for (bits, rs) in &by_v {
        let v = f64::from_bits(*bits);
        let stats = [stat(rs, |r| r.1), stat(rs, |r| r.2), stat(rs, |r| r.3)];
        let mut row = vec![v, rs.len() as f64];
        for (k, s) in stats.iter().enumerate() {
            let (m, e) = s.unwrap_or((f64::NAN, f64::NAN));
            row.extend([m, e]);
            if s.is_some() {
                series[k].push((v, m, e));
            }
        }
        t.push(&row);
        let fmt = |s: Option<(f64, f64)>, scale: f64| {
            s.map_or("-".to_string(), |(m, e)| {
                format!("{:.3} +/- {:.3}", m * scale, e * scale)
            })
        };
        lines.push(format!(
            "v_p = {v} m/s ({} runs; - where at most half measured it): c_w {} m/s, c_p {} m/s, dilation {} mm",
            rs.len(),
            fmt(stats[0], 1.0),
            fmt(stats[1], 1.0),
            fmt(stats[2], 1e3)
        ));
    }
    t.write(&dir.join("channel_sweep.csv"))?;
    let c0: Vec<f64> = runs.iter().filter_map(|r| r.4).collect();
    let curve = |label: &str, pts: &[(f64, f64, f64)], scale: f64| {
        let mut c = Curve::new(
            label,
            pts.iter().map(|p| (p.0, p.1 * scale)).collect(),
            Style::Line,
        );
        c.errors = Some(pts.iter().map(|p| p.2 * scale).collect());
        c
    };
    let speeds = Chart {
        title: "Wave speeds against piston speed (mean and spread over seeds)".into(),
        x_label: "piston speed v_p (m/s)".into(),
        y_label: "speed (m/s)".into(),
        log_x: true,
        curves: {
            let mut c = vec![
                curve("c_w (near the piston)", &series[0], 1.0),
                curve("c_p (solitary wave)", &series[1], 1.0),
            ];
            if let (Some((m, _)), Some(a), Some(b)) =
                (mean_std(&c0), by_v.keys().next(), by_v.keys().last())
            {
                c.push(Curve::new(
                    &format!("sound-speed estimate c_0 = {m:.2} m/s"),
                    vec![(f64::from_bits(*a), m), (f64::from_bits(*b), m)],
                    Style::Dashed,
                ));
            }
            c
        },
        ..Default::default()
    };
    let dil = Chart {
        title: "Surface dilation against piston speed".into(),
        x_label: "piston speed v_p (m/s)".into(),
        y_label: "dilation (mm)".into(),
        log_x: true,
        curves: vec![curve("final minus initial height", &series[2], 1e3)],
        ..Default::default()
    };
    save(&dir.join("channel_sweep.png"), &[speeds, dil], 900, 450)?;
    Ok(lines)
}
