//! PNG figures: line and scatter charts with titles, axis labels (with units), legends, optional
//! log axes and error bars, one or several panels stacked in one image.

use std::path::Path;
use std::sync::Once;

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;

use super::AnalyzeError;

/// How a curve is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    /// Connected points.
    Line,
    /// A dashed line (fits, estimates).
    Dashed,
    /// Markers only (measurements).
    Points,
    /// Connected markers (a measured series).
    LinePoints,
}

/// One data set of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// (x, y) in the chart's units.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
    /// Optional symmetric y error bar per point (same units as y).
    pub errors: Option<Vec<f64>>,
    /// Optional short text beside each point (a setting's name).
    pub notes: Option<Vec<String>>,
}

impl Curve {
    /// A curve without error bars.
    pub fn new(label: &str, points: Vec<(f64, f64)>, style: Style) -> Curve {
        Curve {
            label: label.to_string(),
            points,
            style,
            errors: None,
            notes: None,
        }
    }
}

/// One panel: title, axis labels with units, curves.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Chart {
    /// Title above the panel.
    pub title: String,
    /// x-axis label, with the unit, e.g. "y (m)".
    pub x_label: String,
    /// y-axis label, with the unit.
    pub y_label: String,
    /// Logarithmic x axis (non-positive x values are left out).
    pub log_x: bool,
    /// Logarithmic y axis (non-positive y values are left out).
    pub log_y: bool,
    /// The data.
    pub curves: Vec<Curve>,
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(90, 90, 90),
];

pub(crate) fn register_fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
        let _ = plotters::style::register_font("sans-serif", FontStyle::Bold, dejavu::sans::bold());
    });
}

/// Save the charts stacked vertically in one PNG, each panel `width` x `panel_height` pixels.
pub fn save(
    path: &Path,
    charts: &[Chart],
    width: u32,
    panel_height: u32,
) -> Result<(), AnalyzeError> {
    register_fonts();
    let err = |m: String| AnalyzeError::Write {
        path: path.display().to_string(),
        message: m,
    };
    let height = panel_height * charts.len().max(1) as u32;
    // drawn beside the target under a temporary name (same extension: it picks the format),
    // then renamed over it, so a reader never sees half a figure
    let name = path
        .file_name()
        .map_or("figure".into(), |n| n.to_string_lossy());
    let tmp = path.with_file_name(format!(".{}.{name}", std::process::id()));
    let drawn = (|| {
        let root = BitMapBackend::new(&tmp, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(e.to_string()))?;
        for (area, chart) in root.split_evenly((charts.len(), 1)).iter().zip(charts) {
            draw(area, chart).map_err(|e| err(e.to_string()))?;
        }
        root.present().map_err(|e| err(e.to_string()))
    })()
    .and_then(|()| std::fs::rename(&tmp, path).map_err(|e| err(e.to_string())));
    if drawn.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    drawn
}

/// The data range of the chart's points along one axis, padded; positive only for log axes.
fn range(chart: &Chart, axis: usize, log: bool) -> (f64, f64) {
    let vals = chart.curves.iter().flat_map(|c| {
        c.points.iter().enumerate().flat_map(move |(k, p)| {
            let v = if axis == 0 { p.0 } else { p.1 };
            let e = match (&c.errors, axis) {
                (Some(e), 1) => e.get(k).copied().unwrap_or(0.0).abs(),
                _ => 0.0,
            };
            [v - e, v + e]
        })
    });
    let vals: Vec<f64> = vals
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .collect();
    let lo = vals.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = vals.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if !lo.is_finite() {
        return if log { (0.1, 10.0) } else { (0.0, 1.0) };
    }
    if log {
        let (l, h) = (lo.log10(), hi.log10().max(lo.log10() + 0.3));
        let pad = 0.05 * (h - l);
        (10f64.powf(l - pad), 10f64.powf(h + pad))
    } else {
        let span = if hi > lo {
            hi - lo
        } else {
            lo.abs().max(1e-12)
        };
        (lo - 0.05 * span, hi + 0.05 * span)
    }
}

/// Why drawing on a bitmap failed (plotters' error).
type DrawError = DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>;

/// Draw `chart` on its panel `area`, each axis linear or logarithmic.
fn draw(area: &DrawingArea<BitMapBackend<'_>, Shift>, chart: &Chart) -> Result<(), DrawError> {
    let (x0, x1) = range(chart, 0, chart.log_x);
    let (y0, y1) = range(chart, 1, chart.log_y);
    match (chart.log_x, chart.log_y) {
        (false, false) => draw_in(area, chart, x0..x1, y0..y1),
        (true, false) => draw_in(area, chart, (x0..x1).log_scale(), y0..y1),
        (false, true) => draw_in(area, chart, x0..x1, (y0..y1).log_scale()),
        (true, true) => draw_in(area, chart, (x0..x1).log_scale(), (y0..y1).log_scale()),
    }
}

/// A compact number for tick labels: 0.25, 1.5e-06, 3000.
pub fn tick(v: &f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e5).contains(&a) {
        format!("{v:.1e}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

fn draw_in<X, Y>(
    area: &DrawingArea<BitMapBackend<'_>, Shift>,
    chart: &Chart,
    xs: X,
    ys: Y,
) -> Result<(), DrawError>
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut ctx = ChartBuilder::on(area)
        .caption(&chart.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(48)
        .y_label_area_size(80)
        .build_cartesian_2d(xs, ys)?;
    ctx.configure_mesh()
        .x_desc(chart.x_label.as_str())
        .y_desc(chart.y_label.as_str())
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()?;
    let keep = |p: &(f64, f64)| {
        p.0.is_finite()
            && p.1.is_finite()
            && (!chart.log_x || p.0 > 0.0)
            && (!chart.log_y || p.1 > 0.0)
    };
    for (k, c) in chart.curves.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let pts: Vec<(f64, f64)> = c.points.iter().copied().filter(keep).collect();
        let anno = match c.style {
            Style::Line => ctx.draw_series(LineSeries::new(pts, color.stroke_width(2)))?,
            Style::Dashed => {
                ctx.draw_series(DashedLineSeries::new(pts, 8, 5, color.stroke_width(2)))?
            }
            Style::Points => {
                ctx.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?
            }
            Style::LinePoints => {
                ctx.draw_series(pts.iter().map(|&p| Circle::new(p, 4, color.filled())))?;
                ctx.draw_series(LineSeries::new(pts, color.stroke_width(2)))?
            }
        };
        if !c.label.is_empty() {
            anno.label(c.label.as_str()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], color.stroke_width(3))
            });
        }
        if let Some(errs) = &c.errors {
            let bars = c
                .points
                .iter()
                .zip(errs)
                .filter(|(p, _)| keep(p))
                .map(|(&(x, y), &s)| {
                    let lo = if chart.log_y {
                        (y - s).max(y * 1e-3)
                    } else {
                        y - s
                    };
                    PathElement::new(vec![(x, lo), (x, y + s)], color.stroke_width(2))
                });
            ctx.draw_series(bars)?;
        }
        if let Some(notes) = &c.notes {
            let text = c
                .points
                .iter()
                .zip(notes)
                .filter(|(p, n)| keep(p) && !n.is_empty())
                .map(|(&p, n)| {
                    Text::new(
                        n.clone(),
                        p,
                        ("sans-serif", 13).into_font().color(&color.mix(0.9)),
                    )
                });
            ctx.draw_series(text)?;
        }
    }
    if chart.curves.iter().any(|c| !c.label.is_empty()) {
        ctx.configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 15))
            .position(SeriesLabelPosition::UpperLeft)
            .draw()?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_png_is_written() {
        let path = std::env::temp_dir().join(format!("regolith_plot_{}.png", std::process::id()));
        let mut c = Chart {
            title: "test".into(),
            x_label: "v (m/s)".into(),
            y_label: "c (m/s)".into(),
            log_x: true,
            log_y: true,
            ..Default::default()
        };
        let mut data = Curve::new(
            "data",
            vec![(1e-3, 2.0), (1e-2, 3.0), (0.0, 1.0)],
            Style::Points,
        );
        data.errors = Some(vec![0.1, 0.2, 0.0]);
        c.curves.push(data);
        c.curves.push(Curve::new(
            "fit",
            vec![(1e-3, 2.0), (1e-2, 3.0)],
            Style::Dashed,
        ));
        let lin = Chart {
            log_x: false,
            log_y: false,
            ..c.clone()
        };
        save(&path, &[c, lin], 400, 300).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        std::fs::remove_file(&path).unwrap();
        assert_eq!(tick(&0.25), "0.25");
        assert_eq!(tick(&1.5e-6), "1.5e-6");
    }
}
