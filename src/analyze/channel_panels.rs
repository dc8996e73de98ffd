//! Per-particle panels along the channel: |f|, vz, |v| and the yy and yz per-atom stress
//! (`compute stress/atom`, pressure x volume) against y, one colour per snapshot.

use std::path::Path;

use super::channel::ChannelResult;
use super::plot::{save, Chart, Curve, Style};
use super::table::Table;
use super::AnalyzeError;

const QUANTITIES: [(&str, &str); 5] = [
    ("Particle force", "|f| (N)"),
    ("Vertical velocity", "vz (m/s)"),
    ("Speed", "|v| (m/s)"),
    ("yy stress x volume (stress/atom)", "s_yy (N m)"),
    ("yz stress x volume (stress/atom)", "s_yz (N m)"),
];

/// Write `<base>.csv` and `<base>.png` (panels without data, e.g. no stress columns, are
/// left out of the figure).
pub fn write(base: &Path, r: &ChannelResult) -> Result<(), AnalyzeError> {
    let mut t = Table::new(&[
        "t_s",
        "y_m",
        "force_N",
        "vz_m_s",
        "speed_m_s",
        "syy_Nm",
        "syz_Nm",
    ]);
    for p in &r.panels {
        for row in &p.rows {
            let mut v = vec![p.t];
            v.extend_from_slice(row);
            t.push(&v);
        }
    }
    t.write(&base.with_extension("csv"))?;
    let mut charts = Vec::new();
    for (q, (title, unit)) in QUANTITIES.iter().enumerate() {
        let curves: Vec<Curve> = r
            .panels
            .iter()
            .map(|p| {
                Curve::new(
                    &format!("t = {:.4} s", p.t),
                    p.rows.iter().map(|row| (row[0], row[q + 1])).collect(),
                    Style::Points,
                )
            })
            .filter(|c| c.points.iter().any(|p| p.1.is_finite()))
            .collect();
        if curves.is_empty() {
            continue;
        }
        charts.push(Chart {
            title: format!("{title} along the channel"),
            x_label: "y (m)".into(),
            y_label: unit.to_string(),
            curves,
            ..Default::default()
        });
    }
    if charts.is_empty() {
        return Ok(());
    }
    save(&base.with_extension("png"), &charts, 1000, 320)
}
