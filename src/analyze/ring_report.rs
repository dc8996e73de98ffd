//! Tables, figures and summary of the ring analysis, per run and across trials.

use std::collections::BTreeMap;
use std::path::Path;

use super::fit::mean_std;
use super::plot::{save, Chart, Curve, Style};
use super::ring::{self, RingResult};
use super::table::Table;
use super::AnalyzeError;

/// Write one run's tables and figures (names prefixed with `tag`); return the summary lines.
pub fn write_run(dir: &Path, tag: &str, r: &RingResult) -> Result<Vec<String>, AnalyzeError> {
    let name = |base: &str| dir.join(format!("{tag}{base}"));
    write_run_tables(&name, r)?;
    write_run_figures(&name, r)?;
    Ok(run_summary(r))
}

/// One run's `ring_states.csv`, `ring_surface.csv` and `ring_spectrum.csv` (paths from
/// `name`).
fn write_run_tables(
    name: &dyn Fn(&str) -> std::path::PathBuf,
    r: &RingResult,
) -> Result<(), AnalyzeError> {
    let mut t = Table::new(&[
        "t_s",
        "r_in_m",
        "r_out_m",
        "r_mean_m",
        "amplitude",
        "rms",
        "front_m",
        "edge_m",
    ]);
    for s in &r.states {
        t.push(&[
            s.t,
            s.r_in,
            s.r_out,
            s.r_mean,
            s.amplitude,
            s.rms,
            s.front,
            s.edge,
        ]);
    }
    t.write(&name("ring_states.csv"))?;
    let mut t = Table::new(&["theta_rad", "R_m"]);
    for s in &r.surface {
        t.push(&[s.0, s.1]);
    }
    t.write(&name("ring_surface.csv"))?;
    let mut t = Table::new(&["band_r0_m", "band_r1_m", "mode", "power_N2"]);
    for b in &r.bands {
        for (m, p) in b.power.iter().enumerate() {
            t.push(&[b.radii.0, b.radii.1, (m + 1) as f64, *p]);
        }
    }
    t.write(&name("ring_spectrum.csv"))?;
    Ok(())
}

/// One run's `ring_radii.png` and `ring_spectrum.png` (paths from `name`).
fn write_run_figures(
    name: &dyn Fn(&str) -> std::path::PathBuf,
    r: &RingResult,
) -> Result<(), AnalyzeError> {
    let mm = |v: f64| v * 1e3;
    let series = |f: fn(&ring::RingState) -> f64| -> Vec<(f64, f64)> {
        r.states.iter().map(|s| (s.t, mm(f(s)))).collect()
    };
    let radii = Chart {
        title: "Ring: disturbed surface and compaction front".into(),
        x_label: "t (s)".into(),
        y_label: "radius (mm)".into(),
        curves: vec![
            Curve::new(
                "surface inner radius (min R)",
                series(|s| s.r_in),
                Style::Line,
            ),
            Curve::new(
                "surface outer radius (max R)",
                series(|s| s.r_out),
                Style::Line,
            ),
            Curve::new("compaction front", series(|s| s.front), Style::Line),
            Curve::new("outer edge of the ring", series(|s| s.edge), Style::Dashed),
        ],
        ..Default::default()
    };
    let amp = Chart {
        title: "Corrugation of the inner surface".into(),
        x_label: "t (s)".into(),
        y_label: "relative amplitude".into(),
        curves: vec![
            Curve::new(
                "(max R - min R) / (2 mean R)",
                r.states.iter().map(|s| (s.t, s.amplitude)).collect(),
                Style::Line,
            ),
            Curve::new(
                "std R / mean R",
                r.states.iter().map(|s| (s.t, s.rms)).collect(),
                Style::Line,
            ),
        ],
        ..Default::default()
    };
    let surf = Chart {
        title: "Inner surface R(theta), last snapshot".into(),
        x_label: "theta (degrees)".into(),
        y_label: "R (mm)".into(),
        curves: vec![Curve::new(
            "",
            r.surface
                .iter()
                .map(|s| (s.0.to_degrees(), mm(s.1)))
                .collect(),
            Style::Line,
        )],
        ..Default::default()
    };
    save(&name("ring_radii.png"), &[radii, amp, surf], 900, 400)?;
    let spectrum = Chart {
        title: "Azimuthal spectrum of the force field, last snapshot".into(),
        x_label: "azimuthal mode m".into(),
        y_label: "power (N^2)".into(),
        log_y: true,
        curves: r
            .bands
            .iter()
            .map(|b| {
                Curve::new(
                    &format!(
                        "r {:.2}-{:.2} mm: m = {}, spacing {:.1} d",
                        mm(b.radii.0),
                        mm(b.radii.1),
                        b.mode,
                        b.spacing_diameters
                    ),
                    b.power
                        .iter()
                        .enumerate()
                        .map(|(m, p)| ((m + 1) as f64, *p))
                        .collect(),
                    Style::Line,
                )
            })
            .collect(),
        ..Default::default()
    };
    save(&name("ring_spectrum.png"), &[spectrum], 900, 500)?;
    Ok(())
}

/// One run's summary lines: the last snapshot's surface, front and edge (mm), and each
/// band's dominant mode and force-chain spacing.
fn run_summary(r: &RingResult) -> Vec<String> {
    let mm = |v: f64| v * 1e3;
    let s = r.states[r.states.len() - 1];
    let mut lines = vec![format!(
        "t = {:.3e} s: surface radius {:.4}-{:.4} mm (mean {:.4}), relative amplitude {:.4} (rms {:.4}), front {:.4} mm, edge {:.4} mm",
        s.t, mm(s.r_in), mm(s.r_out), mm(s.r_mean), s.amplitude, s.rms, mm(s.front), mm(s.edge)
    )];
    for b in &r.bands {
        lines.push(format!(
            "band {:.3}-{:.3} mm: dominant mode {}, force-chain spacing {:.3} mm = {:.2} particle diameters",
            mm(b.radii.0), mm(b.radii.1), b.mode, mm(b.spacing), b.spacing_diameters
        ));
    }
    lines
}

/// Across trials: `ring_trials.csv` and `ring_trials.png` (amplitude against time, the mean
/// over each label's runs); return the summary lines.
pub fn write_trials(
    dir: &Path,
    runs: &[(String, RingResult)],
) -> Result<Vec<String>, AnalyzeError> {
    let mut by: BTreeMap<&str, Vec<&RingResult>> = BTreeMap::new();
    for (label, r) in runs {
        by.entry(label).or_default().push(r);
    }
    let mut t = Table::new(&[
        "trial",
        "runs",
        "amplitude",
        "amplitude_spread",
        "rms",
        "rms_spread",
        "spacing_d",
        "spacing_d_spread",
    ]);
    let mut lines = Vec::new();
    let mut curves = Vec::new();
    for (label, rs) in &by {
        let last = |f: fn(&RingResult) -> f64| {
            mean_std(&rs.iter().map(|r| f(r)).collect::<Vec<_>>()).unwrap_or((f64::NAN, 0.0))
        };
        let amp = last(|r| r.states[r.states.len() - 1].amplitude);
        let rms = last(|r| r.states[r.states.len() - 1].rms);
        let sp = last(|r| r.bands.first().map_or(f64::NAN, |b| b.spacing_diameters));
        t.push_words(
            [label.to_string(), rs.len().to_string()]
                .into_iter()
                .chain(
                    [amp.0, amp.1, rms.0, rms.1, sp.0, sp.1]
                        .iter()
                        .map(|v| format!("{v}")),
                )
                .collect(),
        );
        lines.push(format!(
            "{label} ({} runs): relative amplitude {:.4} +/- {:.4}, rms {:.4} +/- {:.4}, force-chain spacing {:.2} +/- {:.2} d",
            rs.len(), amp.0, amp.1, rms.0, rms.1, sp.0, sp.1
        ));
        let n = rs.iter().map(|r| r.states.len()).min().unwrap_or(0);
        let stats: Vec<(f64, (f64, f64))> = (0..n)
            .map(|k| {
                let a: Vec<f64> = rs.iter().map(|r| r.states[k].amplitude).collect();
                (rs[0].states[k].t, mean_std(&a).unwrap_or((f64::NAN, 0.0)))
            })
            .collect();
        let mut c = Curve::new(
            &format!("{label} ({} runs)", rs.len()),
            stats.iter().map(|(t, m)| (*t, m.0)).collect(),
            Style::Line,
        );
        if rs.len() > 1 {
            c.errors = Some(stats.iter().map(|(_, m)| m.1).collect());
        }
        curves.push(c);
    }
    t.write(&dir.join("ring_trials.csv"))?;
    let chart = Chart {
        title: "Corrugation of the inner surface by trial (mean and spread over runs)".into(),
        x_label: "t (s)".into(),
        y_label: "relative amplitude (max R - min R) / (2 mean R)".into(),
        curves,
        ..Default::default()
    };
    save(&dir.join("ring_trials.png"), &[chart], 900, 550)?;
    Ok(lines)
}
