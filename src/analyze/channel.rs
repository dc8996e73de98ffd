//! The lunar channel (SCENES.md, scene B): sensor-grid averages, wave arrival per cell, the
//! wave speed c_w near the piston and the solitary speed c_p further on, bed height and
//! dilation per column, initial overlap against depth with the 1D-chain estimate and the
//! sound-speed estimate, and per-particle profiles along the channel.
//!
//! In a channel of length L shorter than the c_p range's far end (50 cm), both fit ranges are
//! scaled by L / 50 cm (c_w then fits the first 30 %, c_p the last 40 %); the end exclusion of
//! the dilation (50 cm of a 2 m channel) is scaled by L / 2 m when L is shorter.

use std::collections::HashMap;

use super::fit::{fit_line_clipped, mean_std, LineFit};
use super::sensor::{arrival, CellStats, Grid, Probe};
use super::series::{norm, Frame, Series};
use super::AnalyzeError;

/// Settings; lengths in metres, times in seconds.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelOptions {
    /// Sensor cell edge (m).
    pub cell: f64,
    /// Arrival: the first maximum above this multiple of the initial mean force.
    pub arrival_factor: f64,
    /// y range of the c_w fit in a 2 m channel (m).
    pub cw_range: (f64, f64),
    /// y range of the c_p fit in a 2 m channel (m).
    pub cp_range: (f64, f64),
    /// Residuals beyond this many standard deviations are dropped from the fits.
    pub clip_sigma: f64,
    /// Channel length the end exclusion is given for (m).
    pub reference_length: f64,
    /// Particles averaged for the height of a column.
    pub top_n: usize,
    /// The final height is the mean over this last stretch of the run (s), at most half the
    /// run.
    pub final_window: f64,
    /// Columns this close to an end wall are left out of the dilation (m, in a 2 m channel).
    pub end_exclusion: f64,
    /// Times of the per-particle panels (s); empty: when the fitted front is at a quarter,
    /// half and three quarters of the channel.
    pub panel_times: Vec<f64>,
    /// Column names of the yy and yz per-atom stress.
    pub stress_columns: (Vec<String>, Vec<String>),
}

impl Default for ChannelOptions {
    fn default() -> Self {
        ChannelOptions {
            cell: 0.005,
            arrival_factor: 10.0,
            cw_range: (0.0, 0.15),
            cp_range: (0.30, 0.50),
            clip_sigma: 2.0,
            reference_length: 2.0,
            top_n: 10,
            final_window: 0.2,
            end_exclusion: 0.5,
            panel_times: Vec::new(),
            stress_columns: (
                vec!["c_stress[2]".into(), "syy".into(), "stress_yy".into()],
                vec!["c_stress[6]".into(), "syz".into(), "stress_yz".into()],
            ),
        }
    }
}

/// One cell's arrival.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arrival {
    /// Cell centre y (m), from the piston wall.
    pub y: f64,
    /// Cell centre z (m).
    pub z: f64,
    /// Arrival time (s).
    pub t: f64,
}

/// A fitted speed with the points it used. Arrival time is regressed on cell position (the
/// position is exact, the time is the measurement), t = t0 + y / c, so a late outlier is
/// clipped rather than levering the line.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedFit {
    /// y range actually used (m).
    pub range: (f64, f64),
    /// The speed c (m/s).
    pub speed: f64,
    /// Its standard error (m/s).
    pub speed_err: f64,
    /// t = intercept + slope y: slope 1/c (s/m), intercept t0 (s).
    pub fit: LineFit,
    /// (y, t) points kept after the outlier removal.
    pub kept: Vec<(f64, f64)>,
}

/// Bed height per column over time.
#[derive(Debug, Clone, PartialEq)]
pub struct Heights {
    /// Column centres (m).
    pub y: Vec<f64>,
    /// (time s, height per column m); NaN for an empty column.
    pub frames: Vec<(f64, Vec<f64>)>,
}

/// Everything measured on one run.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelResult {
    /// The sensor grid.
    pub grid: Grid,
    /// Channel length (m) and the factor the study's lengths were scaled by.
    pub length: f64,
    /// Scale factor of the end exclusion, min(1, L / reference length).
    pub scale: f64,
    /// Scale factor of the fit ranges, min(1, L / far end of the c_p range).
    pub fit_scale: f64,
    /// Cell statistics per frame (time s, stats).
    pub cells: Vec<(f64, CellStats)>,
    /// Arrivals per cell.
    pub arrivals: Vec<Arrival>,
    /// Wave speed near the piston.
    pub c_w: Option<SpeedFit>,
    /// Solitary-wave speed further on.
    pub c_p: Option<SpeedFit>,
    /// Bed height per column.
    pub heights: Heights,
    /// Dilation per column (y m, final minus initial height m, excluded near an end).
    pub dilation: Vec<(f64, f64, bool)>,
    /// Columns this close to an end wall were left out of the dilation (m).
    pub end_margin: f64,
    /// Mean and spread of the dilation over the columns kept (m).
    pub dilation_mean: Option<(f64, f64)>,
    /// Surface rise behind the front: mean and spread of the final minus initial height over
    /// the columns of the c_w range past the first (the piston's) cell (m).
    pub rise: Option<(f64, f64)>,
    /// Mean packing fraction of the bed's filled cells at the first frame.
    pub packing: f64,
    /// Per-particle profiles at the panel times.
    pub panels: Vec<Panel>,
}

/// Per-particle values of one snapshot along the channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Time (s).
    pub t: f64,
    /// Per particle: y (m), |f| (N), vz (m/s), |v| (m/s), yy and yz stress x volume (N m).
    pub rows: Vec<[f64; 6]>,
}

fn probes(fr: &Frame, overlap: Option<usize>) -> Result<Vec<Probe>, AnalyzeError> {
    let [_, y, z] = fr.xyz()?;
    let (f, r) = (fr.force()?, fr.col(&["radius"])?);
    Ok(fr
        .rows
        .iter()
        .map(|row| Probe {
            y: row[y],
            z: row[z],
            r: row[r],
            force: norm(row, f),
            overlap: overlap.map(|c| row[c]),
        })
        .collect())
}

/// Height of each column: the mean top (z + r) of its `top_n` highest particles.
fn column_heights(fr: &Frame, grid: &Grid, top_n: usize) -> Result<Vec<f64>, AnalyzeError> {
    let [_, y, z] = fr.xyz()?;
    let r = fr.col(&["radius"])?;
    let mut tops: Vec<Vec<f64>> = vec![Vec::new(); grid.ny];
    for row in &fr.rows {
        let iy = ((row[y] - grid.y0) / grid.cell).floor();
        if iy >= 0.0 && (iy as usize) < grid.ny {
            tops[iy as usize].push(row[z] + row[r]);
        }
    }
    Ok(tops
        .into_iter()
        .map(|mut t| {
            if t.is_empty() {
                return f64::NAN;
            }
            t.sort_by(|a, b| b.total_cmp(a));
            let n = t.len().min(top_n.max(1));
            t[..n].iter().sum::<f64>() / n as f64
        })
        .collect())
}

/// Analyse a shock run's dumps (id type x y z vx vy vz fx fy fz radius, optionally the
/// per-atom stress and an `overlap` column).
pub fn analyze(series: &Series, o: &ChannelOptions) -> Result<ChannelResult, AnalyzeError> {
    let mut grid: Option<Grid> = None;
    let mut cells = Vec::new();
    let mut height_frames = Vec::new();
    series.for_each(|fr| {
        if grid.is_none() {
            let b = fr.bounds;
            // up to a cell above the bed's initial top
            let (z, r) = (fr.xyz()?[2], fr.col(&["radius"])?);
            let top = fr.rows.iter().map(|w| w[z] + w[r]).fold(b[2][0], f64::max);
            let z1 = b[2][1].min(top + o.cell);
            grid = Some(Grid::covering(
                (b[1][0], b[1][1]),
                (b[2][0].max(0.0), z1),
                o.cell,
                b[0][1] - b[0][0],
            ));
        }
        let g = grid.as_ref().expect("set above");
        let overlap = fr.opt_col(&["overlap", "c_overlap", "f_overlap"]);
        cells.push((fr.time, g.measure(&probes(&fr, overlap)?)));
        height_frames.push((fr.time, column_heights(&fr, g, o.top_n)?));
        Ok(())
    })?;
    let grid = grid.ok_or_else(|| AnalyzeError::Read("no snapshots".into()))?;
    let length = grid.ny as f64 * grid.cell;
    let scale = (length / o.reference_length).min(1.0);
    let fit_scale = (length / o.cp_range.1).min(1.0);
    let arrivals = arrivals(&grid, &cells, o.arrival_factor);
    let speed = |range: (f64, f64)| {
        let range = (range.0 * fit_scale, range.1 * fit_scale);
        let pts: Vec<(f64, f64)> = arrivals
            .iter()
            .filter(|a| a.y >= range.0 && a.y <= range.1)
            .map(|a| (a.y - grid.y0, a.t))
            .collect();
        fit_line_clipped(&pts, o.clip_sigma)
            .ok()
            // a speed only when the slowness differs from zero by two standard errors
            .filter(|(fit, _)| fit.slope > 2.0 * fit.slope_err)
            .map(|(fit, kept)| SpeedFit {
                range,
                speed: 1.0 / fit.slope,
                speed_err: fit.slope_err / (fit.slope * fit.slope),
                fit,
                kept,
            })
    };
    let (c_w, c_p) = (speed(o.cw_range), speed(o.cp_range));
    let heights = Heights {
        y: (0..grid.ny).map(|k| grid.center(k * grid.nz).0).collect(),
        frames: height_frames,
    };
    let (dilation, dilation_mean) = dilation(&heights, o, scale, grid.y0, length);
    let rise = rise(&dilation, grid.y0, grid.cell, o.cw_range.1 * fit_scale);
    let packing = bed_packing(&grid, &cells[0].1, &heights.frames[0].1);
    let mut times = o.panel_times.clone();
    let t_end = cells.last().map_or(0.0, |c| c.0);
    if times.is_empty() {
        times = [0.25, 0.5, 0.75]
            .iter()
            .map(|q| match &c_w {
                Some(s) => s.fit.at(q * length).clamp(0.0, t_end),
                _ => q * t_end,
            })
            .collect();
    }
    let panels = panels(series, &times, o)?;
    Ok(ChannelResult {
        grid,
        length,
        scale,
        fit_scale,
        cells,
        arrivals,
        c_w,
        c_p,
        heights,
        dilation,
        end_margin: o.end_exclusion * scale,
        dilation_mean,
        rise,
        packing,
        panels,
    })
}

/// Mean and spread of the per-column height change over the columns whose centres lie
/// between one cell from the piston wall and `end` (m from it).
fn rise(per_column: &[(f64, f64, bool)], y0: f64, cell: f64, end: f64) -> Option<(f64, f64)> {
    let kept: Vec<f64> = per_column
        .iter()
        .filter(|c| c.0 - y0 >= cell && c.0 - y0 <= end && c.1.is_finite())
        .map(|c| c.1)
        .collect();
    mean_std(&kept)
}

fn arrivals(grid: &Grid, cells: &[(f64, CellStats)], factor: f64) -> Vec<Arrival> {
    (0..grid.len())
        .filter_map(|k| {
            let s: Vec<(f64, f64)> = cells.iter().map(|(t, c)| (*t, c.force[k])).collect();
            let (y, z) = grid.center(k);
            arrival(&s, factor).map(|t| Arrival { y, z, t })
        })
        .collect()
}

/// Final minus initial height per column; the mean and spread away from the end walls.
#[allow(clippy::type_complexity)]
fn dilation(
    h: &Heights,
    o: &ChannelOptions,
    scale: f64,
    y0: f64,
    length: f64,
) -> (Vec<(f64, f64, bool)>, Option<(f64, f64)>) {
    let Some((t_end, _)) = h.frames.last() else {
        return (Vec::new(), None);
    };
    let window = o.final_window.min(0.5 * (t_end - h.frames[0].0));
    let last: Vec<&Vec<f64>> = h
        .frames
        .iter()
        .filter(|(t, _)| *t >= t_end - window - 1e-12)
        .map(|(_, v)| v)
        .collect();
    let margin = o.end_exclusion * scale;
    let per_column: Vec<(f64, f64, bool)> =
        h.y.iter()
            .enumerate()
            .map(|(k, &y)| {
                let fin = last.iter().map(|v| v[k]).sum::<f64>() / last.len() as f64;
                let excluded = y - y0 < margin || y0 + length - y < margin;
                (y, fin - h.frames[0].1[k], excluded)
            })
            .collect();
    let kept: Vec<f64> = per_column
        .iter()
        .filter(|c| !c.2 && c.1.is_finite())
        .map(|c| c.1)
        .collect();
    (per_column, mean_std(&kept))
}

/// Mean packing fraction of the cells lying wholly below the bed's lowest column top.
fn bed_packing(grid: &Grid, first: &CellStats, heights: &[f64]) -> f64 {
    let top = heights
        .iter()
        .copied()
        .filter(|h| h.is_finite())
        .fold(f64::INFINITY, f64::min);
    let inside: Vec<f64> = (0..grid.len())
        .filter(|&k| grid.center(k).1 + 0.5 * grid.cell <= top)
        .map(|k| first.packing[k])
        .collect();
    mean_std(&inside).map_or(0.0, |m| m.0)
}

fn panels(series: &Series, times: &[f64], o: &ChannelOptions) -> Result<Vec<Panel>, AnalyzeError> {
    let steps = series.steps();
    let mut wanted: HashMap<i64, Vec<f64>> = HashMap::new();
    for &t in times {
        if let Some(&s) = steps.iter().min_by(|a, b| {
            let da = (**a as f64 * series.dt() - t).abs();
            let db = (**b as f64 * series.dt() - t).abs();
            da.total_cmp(&db)
        }) {
            wanted.entry(s).or_default().push(t);
        }
    }
    let syy_names: Vec<&str> = o.stress_columns.0.iter().map(String::as_str).collect();
    let syz_names: Vec<&str> = o.stress_columns.1.iter().map(String::as_str).collect();
    let mut out = Vec::new();
    series.for_steps(&wanted.keys().copied().collect::<Vec<_>>(), |fr| {
        let [_, y, _] = fr.xyz()?;
        let f = fr.force()?;
        let v = [fr.col(&["vx"])?, fr.col(&["vy"])?, fr.col(&["vz"])?];
        let (syy, syz) = (fr.opt_col(&syy_names), fr.opt_col(&syz_names));
        let rows = fr
            .rows
            .iter()
            .map(|r| {
                let s = |c: Option<usize>| c.map_or(f64::NAN, |c| r[c]);
                [r[y], norm(r, f), r[v[2]], norm(r, v), s(syy), s(syz)]
            })
            .collect();
        out.push(Panel { t: fr.time, rows });
        Ok(())
    })?;
    Ok(out)
}

#[cfg(test)]
mod tests;
