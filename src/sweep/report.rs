//! A sweep's errors, its printed table, `sweep.csv` and `sweep.png`; and `--merge`, which
//! gathers several sweeps' CSV files into one Markdown table and one figure.

use std::path::{Path, PathBuf};

use crate::analyze::plot::{self, Chart, Curve, Style};

use super::runner::{Run, Status};
use super::{setting_label, Plan};
use crate::tool_error::ToolError;

/// A finished sweep.
#[derive(Debug, Clone)]
pub struct SweepResult {
    /// The deck's file name.
    pub deck: String,
    /// The swept names, in axis order.
    pub axes: Vec<String>,
    /// Observable names.
    pub names: Vec<String>,
    /// Per observable: the value errors are measured against, and whether it is a known
    /// answer (`--expect`) rather than the reference run's value.
    pub reference_values: Vec<(Option<f64>, bool)>,
    /// The runs, in setting order.
    pub runs: Vec<Run>,
    /// Index of the reference run.
    pub reference: usize,
}

/// |v - r| / |r|, or |v - r| when the reference is 0.
pub fn error(v: f64, r: f64) -> f64 {
    if r == 0.0 {
        (v - r).abs()
    } else {
        (v - r).abs() / r.abs()
    }
}

impl SweepResult {
    /// Errors against the reference run's values (or the expected ones).
    pub fn new(plan: &Plan, runs: Vec<Run>, reference: usize) -> SweepResult {
        let reference_values = plan
            .observables
            .iter()
            .enumerate()
            .map(|(k, o)| match o.expect {
                Some(v) => (Some(v), true),
                None => (
                    runs.get(reference)
                        .and_then(|r| r.values.get(k))
                        .and_then(|v| v.as_ref().ok().copied()),
                    false,
                ),
            })
            .collect();
        SweepResult {
            deck: plan
                .deck
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            axes: plan.axes.iter().map(|a| a.name.clone()).collect(),
            names: plan.observables.iter().map(|o| o.name.clone()).collect(),
            reference_values,
            runs,
            reference,
        }
    }

    /// Observable `k`'s error in run `r` (None: no value or no reference).
    pub fn error(&self, r: usize, k: usize) -> Option<f64> {
        let v = self.runs[r].values.get(k)?.as_ref().ok()?;
        let reference = self.reference_values[k].0?;
        Some(error(*v, reference))
    }

    /// Is observable `k`'s error absolute (its reference value is 0)?
    fn absolute(&self, k: usize) -> bool {
        self.reference_values[k].0 == Some(0.0)
    }

    /// The printed table.
    pub fn table(&self) -> String {
        let ref_run = &self.runs[self.reference];
        let mut out = format!(
            "sweep of {}: {} runs; reference {}",
            self.deck,
            self.runs.len(),
            setting_label(&ref_run.setting)
        );
        let known: Vec<String> = self
            .names
            .iter()
            .zip(&self.reference_values)
            .filter(|(_, r)| r.1)
            .map(|(n, r)| format!("{n} = {}", fmt(r.0.unwrap_or(f64::NAN))))
            .collect();
        if !known.is_empty() {
            out.push_str(&format!(" (known answers: {})", known.join(", ")));
        }
        out.push('\n');
        let mut header = vec!["setting".to_string(), "wall (s)".into(), "steps".into()];
        for (k, n) in self.names.iter().enumerate() {
            header.push(n.clone());
            header.push(if self.absolute(k) {
                format!("|err| {n}")
            } else {
                format!("err {n}")
            });
        }
        let mut rows = vec![header];
        let mut notes = Vec::new();
        for (r, run) in self.runs.iter().enumerate() {
            let mut label = setting_label(&run.setting);
            if r == self.reference {
                label.push_str(" (ref)");
            }
            let mut row = vec![label, fmt_time(run.wall), run.steps.to_string()];
            for k in 0..self.names.len() {
                match (&run.status, run.values.get(k)) {
                    (Status::Failed(_), _) => {
                        row.push("failed".into());
                        row.push("-".into());
                    }
                    (_, Some(Ok(v))) => {
                        row.push(fmt(*v));
                        row.push(match self.error(r, k) {
                            Some(e) if self.absolute(k) => fmt(e),
                            Some(e) => percent(e),
                            None => "-".into(),
                        });
                    }
                    (_, Some(Err(m))) => {
                        row.push("-".into());
                        row.push("-".into());
                        notes.push((
                            setting_label(&run.setting),
                            format!("{}: {m}", self.names[k]),
                        ));
                    }
                    (_, None) => {
                        row.push("-".into());
                        row.push("-".into());
                    }
                }
            }
            if let Status::Failed(m) = &run.status {
                notes.push((setting_label(&run.setting), m.clone()));
            }
            rows.push(row);
        }
        out.push_str(&aligned(&rows));
        out.push_str(&grouped_notes(notes, self.runs.len()));
        out
    }

    /// The CSV text: setting, axis values, reference flag, status, wall and loop time, steps,
    /// then per observable its value and error (`NAME_relerr`, or `NAME_abserr` when the
    /// reference value is 0).
    pub fn csv(&self) -> String {
        let mut s = String::from("setting");
        for a in &self.axes {
            s.push_str(&format!(",{a}"));
        }
        s.push_str(",reference,status,wall_s,loop_s,steps");
        for (k, n) in self.names.iter().enumerate() {
            let kind = if self.absolute(k) { "abserr" } else { "relerr" };
            s.push_str(&format!(",{n},{n}_{kind}"));
        }
        s.push('\n');
        for (r, run) in self.runs.iter().enumerate() {
            let label = setting_label(&run.setting);
            s.push_str(&csv_word(&label));
            for a in &self.axes {
                let v = run
                    .setting
                    .iter()
                    .find(|(n, _)| n == a)
                    .map_or("", |(_, v)| v.as_str());
                s.push_str(&format!(",{}", csv_word(v)));
            }
            let status = match &run.status {
                Status::Ok => "ok".to_string(),
                Status::Failed(m) => format!("failed: {m}"),
            };
            s.push_str(&format!(
                ",{},{},{},{},{}",
                u8::from(r == self.reference),
                csv_word(&status),
                run.wall,
                run.loop_time,
                run.steps
            ));
            for k in 0..self.names.len() {
                let v = run.values.get(k).and_then(|v| v.as_ref().ok());
                let e = self.error(r, k);
                s.push_str(&format!(
                    ",{},{}",
                    v.map_or(String::new(), |v| v.to_string()),
                    e.map_or(String::new(), |e| e.to_string())
                ));
            }
            s.push('\n');
        }
        s
    }

    /// The figure: error against wall time (log axes), one curve per observable; and against
    /// the first swept variable when its values are numbers.
    pub fn charts(&self) -> Vec<Chart> {
        let ref_label = setting_label(&self.runs[self.reference].setting);
        let y_label = if (0..self.names.len()).all(|k| self.absolute(k)) {
            "error |value - reference|"
        } else {
            "error |value - ref| / |ref|"
        };
        let mut by_wall = Chart {
            title: format!(
                "{}: error against wall time (reference {ref_label})",
                self.deck
            ),
            x_label: "wall time of the run (s)".into(),
            y_label: y_label.into(),
            log_x: true,
            log_y: true,
            curves: Vec::new(),
        };
        let first_numeric = self.axes.first().filter(|_| {
            self.runs.iter().all(|r| {
                r.setting
                    .first()
                    .is_some_and(|(_, v)| v.parse::<f64>().is_ok_and(|x| x > 0.0))
            })
        });
        let mut by_axis = first_numeric.map(|a| Chart {
            title: format!("{}: error against {a}", self.deck),
            x_label: a.clone(),
            y_label: y_label.into(),
            log_x: true,
            log_y: true,
            curves: Vec::new(),
        });
        // one curve per observable and combination of the later axes, along the first axis
        let mut rests: Vec<Vec<(String, String)>> = Vec::new();
        for run in &self.runs {
            let rest = run.setting.get(1..).unwrap_or(&[]).to_vec();
            if !rests.contains(&rest) {
                rests.push(rest);
            }
        }
        for (k, name) in self.names.iter().enumerate() {
            for rest in &rests {
                let mut pts: Vec<(f64, f64, String, f64)> = Vec::new();
                for (r, run) in self.runs.iter().enumerate() {
                    if run.status != Status::Ok
                        || run.setting.get(1..).unwrap_or(&[]) != rest.as_slice()
                    {
                        continue;
                    }
                    let Some(e) = self.error(r, k) else { continue };
                    let (first, x_axis) = run
                        .setting
                        .first()
                        .map_or((String::new(), f64::NAN), |(_, v)| {
                            (v.clone(), v.parse::<f64>().unwrap_or(f64::NAN))
                        });
                    pts.push((run.wall, e, first, x_axis));
                }
                let kind = if self.absolute(k) { " (absolute)" } else { "" };
                let label = if rests.len() > 1 {
                    format!("{name}{kind} ({})", setting_label(rest))
                } else {
                    format!("{name}{kind}")
                };
                let mut c = Curve::new(
                    &label,
                    pts.iter().map(|p| (p.0, p.1)).collect(),
                    Style::LinePoints,
                );
                c.notes = Some(pts.iter().map(|p| format!(" {}", p.2)).collect());
                by_wall.curves.push(c);
                if let Some(chart) = by_axis.as_mut() {
                    pts.sort_by(|a, b| a.3.total_cmp(&b.3));
                    chart.curves.push(Curve::new(
                        &label,
                        pts.iter().map(|p| (p.3, p.1)).collect(),
                        Style::LinePoints,
                    ));
                }
            }
        }
        let mut charts = vec![by_wall];
        charts.extend(by_axis);
        charts
    }

    /// Write `sweep.csv`, `sweep.png` and `summary.txt` into `out`; the table is returned.
    pub fn write(&self, out: &Path) -> Result<String, ToolError> {
        let table = self.table();
        let w = |p: PathBuf, text: &str| {
            crate::io::write_atomically(&p.to_string_lossy(), text.as_bytes())
                .map_err(ToolError::file(&p))
        };
        w(out.join("sweep.csv"), &self.csv())?;
        w(out.join("summary.txt"), &table)?;
        let charts = self.charts();
        plot::save(&out.join("sweep.png"), &charts, 1000, 560)?;
        Ok(format!(
            "{table}CSV, table and figure in {}\n",
            out.display()
        ))
    }
}

fn csv_word(w: &str) -> String {
    if w.contains([',', '"', '\n']) {
        format!("\"{}\"", w.replace('"', "\"\"").replace('\n', " "))
    } else {
        w.to_string()
    }
}

/// A value with 6 significant digits.
pub fn fmt(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let a = v.abs();
    if (1e-3..1e6).contains(&a) {
        let digits = (5 - a.log10().floor() as i32).max(0) as usize;
        format!("{v:.digits$}")
    } else {
        format!("{v:.5e}")
    }
}

/// A relative error in percent, two significant digits.
pub fn percent(e: f64) -> String {
    let p = 100.0 * e;
    if p == 0.0 {
        "0".into()
    } else if p >= 10.0 {
        format!("{p:.0} %")
    } else {
        let digits = (1 - p.log10().floor() as i32).clamp(0, 12) as usize;
        format!("{p:.digits$} %")
    }
}

fn fmt_time(t: f64) -> String {
    if t >= 100.0 {
        format!("{t:.0}")
    } else if t >= 0.001 {
        let digits = (2 - t.log10().floor() as i32).max(0) as usize;
        format!("{t:.digits$}")
    } else if t.is_finite() {
        format!("{t:.1e}")
    } else {
        "-".into()
    }
}

/// One sweep read back from its `sweep.csv`.
#[derive(Debug, Clone, PartialEq)]
pub struct ReadSweep {
    /// The sweep's label (its folder's name).
    pub label: String,
    /// The swept names.
    pub axes: Vec<String>,
    /// Observables: (name, absolute error?).
    pub observables: Vec<(String, bool)>,
    /// Rows: (axis values, reference?, status, wall, errors).
    pub rows: Vec<ReadRow>,
}

/// One run of a [`ReadSweep`].
#[derive(Debug, Clone, PartialEq)]
pub struct ReadRow {
    /// The axis values.
    pub values: Vec<String>,
    /// The reference run.
    pub reference: bool,
    /// `ok`, or `failed: ...`.
    pub status: String,
    /// Wall time (s).
    pub wall: f64,
    /// Steps run (None in a CSV without a steps column).
    pub steps: Option<f64>,
    /// Per observable its error.
    pub errors: Vec<Option<f64>>,
}

/// What `--merge` plots (and tabulates) as a run's cost.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Cost {
    /// Wall time relative to the reference run's (the figure only).
    #[default]
    Wall,
    /// Steps relative to the reference run's: deterministic (for a fixed simulated time,
    /// 1 / dt); the table gains a `steps` and a `wall (s)` row per sweep.
    Steps,
}

fn split_csv(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                cur.push('"');
                chars.next();
            }
            '"' => quoted = !quoted,
            ',' if !quoted => out.push(std::mem::take(&mut cur)),
            c => cur.push(c),
        }
    }
    out.push(cur);
    out
}

/// Read a sweep's CSV.
pub fn read_csv(label: &str, text: &str) -> Result<ReadSweep, ToolError> {
    let mut lines = text.lines();
    let header = split_csv(lines.next().ok_or(ToolError::content("empty file"))?);
    let at = |name: &str| header.iter().position(|h| h == name);
    let missing = |what: &str| ToolError::content(what);
    let reference =
        at("reference").ok_or_else(|| missing("no reference column: not a sweep.csv"))?;
    let (status, wall) = (
        at("status").ok_or_else(|| missing("no status column"))?,
        at("wall_s").ok_or_else(|| missing("no wall_s column"))?,
    );
    let steps = at("steps");
    let axes: Vec<String> = header[1..reference].to_vec();
    let mut observables = Vec::new();
    let mut err_cols = Vec::new();
    for (c, h) in header.iter().enumerate() {
        if let Some(n) = h.strip_suffix("_relerr") {
            observables.push((n.to_string(), false));
            err_cols.push(c);
        } else if let Some(n) = h.strip_suffix("_abserr") {
            observables.push((n.to_string(), true));
            err_cols.push(c);
        }
    }
    let mut rows = Vec::new();
    for line in lines.filter(|l| !l.trim().is_empty()) {
        let w = split_csv(line);
        if w.len() < header.len() {
            return Err(ToolError::Content(format!("short row: {line}")));
        }
        rows.push(ReadRow {
            values: w[1..reference].to_vec(),
            reference: w[reference] == "1",
            status: w[status].clone(),
            wall: w[wall].parse().unwrap_or(f64::NAN),
            steps: steps.and_then(|c| w[c].parse().ok()),
            errors: err_cols.iter().map(|&c| w[c].parse().ok()).collect(),
        });
    }
    Ok(ReadSweep {
        label: label.to_string(),
        axes,
        observables,
        rows,
    })
}

/// `--merge`: the sweeps in `dirs` (each holding a `sweep.csv`) as one Markdown table (a row
/// per sweep, observable and combination of the later axes; a column per value of the first
/// axis) and one figure; written to `out` as `trade.md` and `trade.png`. Returns the table.
pub fn merge(dirs: &[PathBuf], out: &Path, title: &str, cost: Cost) -> Result<String, ToolError> {
    let sweeps = read_sweeps(dirs)?;
    let first_axis = sweeps
        .first()
        .and_then(|s| s.axes.first())
        .cloned()
        .unwrap_or_default();
    let columns = first_axis_values(&sweeps);
    let mut md = format!(
        "| sweep | observable | {} |\n",
        columns
            .iter()
            .map(|c| format!("{first_axis} {c}"))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    md.push_str(&format!("|---|---|{}\n", "---|".repeat(columns.len())));
    let (mut by_axis, mut by_cost) = trade_charts(title, &first_axis, cost);
    for s in &sweeps {
        let ref_row = s.rows.iter().find(|r| r.reference);
        let ref_cost = ref_row.map_or(f64::NAN, |r| match cost {
            Cost::Wall => r.wall,
            Cost::Steps => r.steps.unwrap_or(f64::NAN),
        });
        // rows of the table: each combination of the later axes
        let mut rests: Vec<Vec<String>> = Vec::new();
        for r in &s.rows {
            let rest = r.values.get(1..).unwrap_or(&[]).to_vec();
            if !rests.contains(&rest) {
                rests.push(rest);
            }
        }
        for rest in &rests {
            let suffix = if rest.is_empty() {
                String::new()
            } else {
                let named: Vec<String> = s.axes[1..]
                    .iter()
                    .zip(rest)
                    .map(|(n, v)| format!("{n}={v}"))
                    .collect();
                format!(" ({})", named.join(" "))
            };
            for (k, (name, absolute)) in s.observables.iter().enumerate() {
                let mut cells = Vec::new();
                let mut pts = Vec::new();
                let mut costs = Vec::new();
                for c in &columns {
                    let row = s.rows.iter().find(|r| {
                        r.values.first() == Some(c)
                            && r.values.get(1..).unwrap_or(&[]) == rest.as_slice()
                    });
                    cells.push(match row {
                        None => String::new(),
                        Some(r) if r.status != "ok" => "blow-up".to_string(),
                        Some(r) if r.reference => "ref".to_string(),
                        Some(r) => match r.errors.get(k).copied().flatten() {
                            None => "-".into(),
                            Some(e) => {
                                if let Ok(x) = c.parse::<f64>() {
                                    pts.push((x, e));
                                }
                                let c = match cost {
                                    Cost::Wall => r.wall,
                                    Cost::Steps => r.steps.unwrap_or(f64::NAN),
                                };
                                if ref_cost > 0.0 && c > 0.0 {
                                    costs.push((c / ref_cost, e));
                                }
                                if *absolute {
                                    fmt(e)
                                } else {
                                    percent(e)
                                }
                            }
                        },
                    });
                }
                let mark = if *absolute { " (abs.)" } else { "" };
                md.push_str(&format!(
                    "| {}{suffix} | {name}{mark} | {} |\n",
                    s.label,
                    cells.join(" | ")
                ));
                let legend = format!("{}{suffix}: {name}{mark}", s.label);
                by_axis
                    .curves
                    .push(Curve::new(&legend, pts, Style::LinePoints));
                costs.sort_by(|a, b| a.0.total_cmp(&b.0));
                by_cost
                    .curves
                    .push(Curve::new(&legend, costs, Style::LinePoints));
            }
            if cost == Cost::Steps {
                // the cost of each setting: its steps, and its wall time on this machine
                let cell = |c: &String, f: &dyn Fn(&ReadRow) -> String| {
                    s.rows
                        .iter()
                        .find(|r| {
                            r.values.first() == Some(c)
                                && r.values.get(1..).unwrap_or(&[]) == rest.as_slice()
                        })
                        .map_or(String::new(), f)
                };
                let steps: Vec<String> = columns
                    .iter()
                    .map(|c| cell(c, &|r| r.steps.map_or("-".into(), |n| format!("{n}"))))
                    .collect();
                let walls: Vec<String> = columns
                    .iter()
                    .map(|c| cell(c, &|r| fmt_time(r.wall)))
                    .collect();
                md.push_str(&format!(
                    "| {}{suffix} | steps | {} |\n",
                    s.label,
                    steps.join(" | ")
                ));
                md.push_str(&format!(
                    "| {}{suffix} | wall (s) | {} |\n",
                    s.label,
                    walls.join(" | ")
                ));
            }
        }
    }
    std::fs::create_dir_all(out).map_err(ToolError::file(out))?;
    let md_path = out.join("trade.md");
    crate::io::write_atomically(&md_path.to_string_lossy(), md.as_bytes())
        .map_err(ToolError::file(&md_path))?;
    plot::save(&out.join("trade.png"), &[by_axis, by_cost], 1100, 700)?;
    Ok(md)
}

/// Table rows as text: the first column left-aligned, the others right-aligned, each as
/// wide as its widest cell.
fn aligned(rows: &[Vec<String>]) -> String {
    let mut out = String::new();
    let widths: Vec<usize> = (0..rows[0].len())
        .map(|c| rows.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    for row in rows {
        let cells: Vec<String> = row
            .iter()
            .enumerate()
            .map(|(c, w)| {
                if c == 0 {
                    format!("{w:<width$}", width = widths[c])
                } else {
                    format!("{w:>width$}", width = widths[c])
                }
            })
            .collect();
        out.push_str(cells.join("  ").trim_end());
        out.push('\n');
    }
    out
}

/// Notes (run label, message) as `note (RUNS): MESSAGE` lines, a message from several runs
/// once with the runs it came from ("every run" when all `runs_total` gave it).
fn grouped_notes(notes: Vec<(String, String)>, runs_total: usize) -> String {
    // the same message from several runs once, with the runs it came from
    let mut out = String::new();
    let mut grouped: Vec<(String, Vec<String>)> = Vec::new();
    for (who, what) in notes {
        match grouped.iter_mut().find(|g| g.0 == what) {
            Some(g) => g.1.push(who),
            None => grouped.push((what, vec![who])),
        }
    }
    for (what, who) in grouped {
        let runs = if who.len() == runs_total && who.len() > 1 {
            "every run".to_string()
        } else {
            who.join("; ")
        };
        out.push_str(&format!("note ({runs}): {what}\n"));
    }
    out
}

/// The `sweep.csv` of each directory, labelled with the directory's name.
fn read_sweeps(dirs: &[PathBuf]) -> Result<Vec<ReadSweep>, ToolError> {
    let mut sweeps = Vec::new();
    for d in dirs {
        let p = d.join("sweep.csv");
        let text = std::fs::read_to_string(&p).map_err(ToolError::file(&p))?;
        let label = d
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let sweep = read_csv(&label, &text).map_err(|m| ToolError::File {
            path: p.clone(),
            why: m.to_string(),
        })?;
        sweeps.push(sweep);
    }
    Ok(sweeps)
}

/// The values of the first axis over all sweeps, numerically ordered when they are numbers.
fn first_axis_values(sweeps: &[ReadSweep]) -> Vec<String> {
    let mut columns: Vec<String> = Vec::new();
    for s in sweeps {
        for r in &s.rows {
            if let Some(v) = r.values.first() {
                if !columns.contains(v) {
                    columns.push(v.clone());
                }
            }
        }
    }
    if columns.iter().all(|c| c.parse::<f64>().is_ok()) {
        columns.sort_by(|a, b| {
            let (x, y) = (
                a.parse::<f64>().unwrap_or(0.0),
                b.parse::<f64>().unwrap_or(0.0),
            );
            x.total_cmp(&y)
        });
    }
    columns
}

/// The two empty figures of a merge: error against the first axis, and against the cost.
fn trade_charts(title: &str, first_axis: &str, cost: Cost) -> (Chart, Chart) {
    let by_axis = Chart {
        title: format!("{title}: error against {first_axis}"),
        x_label: first_axis.to_string(),
        y_label: "error |value - ref| / |ref| (absolute where marked)".into(),
        log_x: true,
        log_y: true,
        curves: Vec::new(),
    };
    let (cost_title, cost_label) = match cost {
        Cost::Wall => ("wall time", "wall time / wall time of the reference run"),
        Cost::Steps => (
            "cost (steps)",
            "steps / steps of the reference run (deterministic cost)",
        ),
    };
    let by_cost = Chart {
        title: format!("{title}: error against {cost_title}"),
        x_label: cost_label.into(),
        y_label: "error".into(),
        log_x: true,
        log_y: true,
        curves: Vec::new(),
    };
    (by_axis, by_cost)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_the_table() {
        assert_eq!(percent(0.0123), "1.2 %");
        assert_eq!(percent(0.000123), "0.012 %");
        assert_eq!(percent(0.5), "50 %");
        assert_eq!(fmt(0.4999698), "0.499970");
        assert_eq!(fmt(1234.5678), "1234.57");
        assert_eq!(fmt(2.5e-7), "2.50000e-7");
        assert_eq!(error(0.49, 0.5), 0.020000000000000018);
        assert_eq!(error(1e-3, 0.0), 1e-3);
    }

    #[test]
    fn csv_read_back() {
        let text = "setting,frac,sf,reference,status,wall_s,loop_s,steps,e,e_relerr,d,d_abserr\n\
                    frac=0.1 sf=off,0.1,off,0,ok,1.5,1.2,100,0.49,0.02,1e-4,1e-4\n\
                    frac=0.01 sf=off,0.01,off,1,ok,3,2.5,1000,0.5,0,0,0\n\
                    frac=0.4 sf=off,0.4,off,0,\"failed: blow-up at step 5, atoms 1, 2\",0.1,,3,,,,\n";
        let s = read_csv("collision", text).unwrap();
        assert_eq!(s.axes, vec!["frac", "sf"]);
        assert_eq!(s.observables, vec![("e".into(), false), ("d".into(), true)]);
        assert_eq!(s.rows.len(), 3);
        assert!(s.rows[1].reference);
        assert!(s.rows[2]
            .status
            .starts_with("failed: blow-up at step 5, atoms 1, 2"));
        assert_eq!(s.rows[0].errors, vec![Some(0.02), Some(1e-4)]);
        assert_eq!(s.rows[2].errors, vec![None, None]);
    }
}
