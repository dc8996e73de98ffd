//! Tables, figures and the printed summary of the struck-chain analysis.

use std::path::Path;

use super::chain::{ChainResult, Sweep};
use super::plot::{save, Chart, Curve, Style};
use super::table::Table;
use super::AnalyzeError;

/// Write `chain_particles.csv`, `chain_layers.csv` and `chain_arrival.png` into `dir` (file
/// names prefixed with `tag` when not empty); return the one-line result.
pub fn write_run(dir: &Path, tag: &str, r: &ChainResult) -> Result<String, AnalyzeError> {
    let name = |base: &str| dir.join(format!("{tag}{base}"));
    let mut t = Table::new(&["id", "distance_m", "peak_force_N", "peak_time_s"]);
    for p in &r.particles {
        t.push(&[p.id as f64, p.distance, p.peak_force, p.peak_time]);
    }
    t.write(&name("chain_particles.csv"))?;
    let mut t = Table::new(&["layer", "distance_m", "peak_force_N", "arrival_s", "fitted"]);
    for l in &r.layers {
        let fitted = if l.fitted { 1.0 } else { 0.0 };
        t.push(&[l.index as f64, l.distance, l.peak_force, l.arrival, fitted]);
    }
    t.write(&name("chain_layers.csv"))?;

    let (used, unused): (Vec<_>, Vec<_>) = r.layers.iter().partition(|l| l.fitted);
    let peaks = Chart {
        title: "Peak force along the struck column".into(),
        x_label: "distance from the struck end (m)".into(),
        y_label: "peak |f| (N)".into(),
        curves: vec![
            Curve::new(
                "strongest particle of each layer",
                r.layers
                    .iter()
                    .map(|l| (l.distance, l.peak_force))
                    .collect(),
                Style::Line,
            ),
            Curve::new(
                "every particle",
                r.particles
                    .iter()
                    .map(|p| (p.distance, p.peak_force))
                    .collect(),
                Style::Points,
            ),
        ],
        ..Default::default()
    };
    let t_end = used.last().map_or(r.span.1, |l| l.arrival);
    let fit = &r.fit;
    let arrival = Chart {
        title: format!(
            "Wave arrival: c_w = {:.4} +/- {:.4} m/s",
            fit.slope, fit.slope_err
        ),
        x_label: "arrival time of the peak force (s)".into(),
        y_label: "distance from the struck end (m)".into(),
        curves: vec![
            Curve::new(
                "layers in the fit",
                used.iter().map(|l| (l.arrival, l.distance)).collect(),
                Style::Points,
            ),
            Curve::new(
                "layers left out",
                unused.iter().map(|l| (l.arrival, l.distance)).collect(),
                Style::Points,
            ),
            Curve::new(
                &format!("fit: c_w = {:.3} m/s", fit.slope),
                vec![(0.0, fit.at(0.0)), (t_end, fit.at(t_end))],
                Style::Dashed,
            ),
        ],
        ..Default::default()
    };
    save(&name("chain_arrival.png"), &[peaks, arrival], 900, 450)?;
    Ok(format!(
        "wave speed c_w = {:.4} +/- {:.4} m/s ({} layers fitted, rms {:.2e} m)",
        fit.slope, fit.slope_err, fit.n, fit.rms
    ))
}

/// Write `chain_sweep.csv` and `chain_sweep.png` into `dir`; return the summary lines.
pub fn write_sweep(dir: &Path, s: &Sweep) -> Result<Vec<String>, AnalyzeError> {
    let mut t = Table::new(&[
        "v_im_m_s",
        "c_w_m_s",
        "c_w_err_m_s",
        "runs",
        "above_elastic_limit",
    ]);
    for p in &s.points {
        let above = if p.above_limit { 1.0 } else { 0.0 };
        t.push(&[p.v_im, p.c_w, p.c_w_err, p.runs as f64, above]);
    }
    t.write(&dir.join("chain_sweep.csv"))?;
    let mut lines = Vec::new();
    let mut curves = Vec::new();
    for (above, label) in [
        (false, "c_w (Hertz regime)"),
        (true, "c_w above the Hertz elastic limit"),
    ] {
        let pts: Vec<_> = s.points.iter().filter(|p| p.above_limit == above).collect();
        if pts.is_empty() {
            continue;
        }
        let mut c = Curve::new(
            label,
            pts.iter().map(|p| (p.v_im, p.c_w)).collect(),
            Style::Points,
        );
        c.errors = Some(pts.iter().map(|p| p.c_w_err).collect());
        curves.push(c);
    }
    let (vlo, vhi) = (s.points[0].v_im, s.points[s.points.len() - 1].v_im);
    if let Some(p) = &s.power {
        let line: Vec<(f64, f64)> = (0..=20)
            .map(|k| {
                let v = s.weak_max.max(vlo) * (vhi / s.weak_max.max(vlo)).powf(k as f64 / 20.0);
                (v, p.prefactor * v.powf(p.exponent))
            })
            .collect();
        curves.push(Curve::new(
            &format!(
                "fit c_w ~ v_im^{:.3} (+/- {:.3})",
                p.exponent, p.exponent_err
            ),
            line,
            Style::Dashed,
        ));
        lines.push(format!(
            "exponent of c_w ~ v_im^p over v_im > {} m/s: p = {:.4} +/- {:.4} (Hertz shocks: 0.2), {} speeds",
            s.weak_max, p.exponent, p.exponent_err, p.n
        ));
    }
    let weak_exponent = s.weak_power.map(|p| p.exponent);
    if let Some((c0, spread)) = s.sound_speed {
        let constant = weak_exponent.is_none_or(|p| p.abs() < 0.05);
        if constant {
            curves.push(Curve::new(
                &format!("weak-impact speed c_0 = {c0:.3} m/s"),
                vec![(vlo, c0), (s.weak_max.max(vlo), c0)],
                Style::Line,
            ));
        }
        lines.push(format!(
            "weak-impact speed (v_im <= {} m/s): c_0 = {c0:.4} m/s, spread {spread:.2e} m/s",
            s.weak_max
        ));
        if let (Some(p), false) = (s.weak_power, constant) {
            lines.push(format!(
                "  but the weak impacts are not at one speed: c_w ~ v_im^{:.3} (+/- {:.3}) there too, \
                 as in a chain without precompression (no linear sound speed)",
                p.exponent, p.exponent_err
            ));
        }
    }
    let flagged: Vec<String> = s
        .points
        .iter()
        .filter(|p| p.above_limit)
        .map(|p| format!("{:e}", p.v_im))
        .collect();
    if !flagged.is_empty() {
        lines.push(format!(
            "WARNING: v_im = {} m/s above the Hertz elastic limit ({:.3e} m/s): outside Hertz theory",
            flagged.join(", "),
            s.elastic_limit
        ));
    }
    let chart = Chart {
        title: "Struck chain: wave speed against impact speed".into(),
        x_label: "impact speed v_im (m/s)".into(),
        y_label: "wave speed c_w (m/s)".into(),
        log_x: true,
        log_y: true,
        curves,
    };
    save(&dir.join("chain_sweep.png"), &[chart], 900, 600)?;
    Ok(lines)
}
