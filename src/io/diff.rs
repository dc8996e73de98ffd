//! `regolith diff A B`: two dumps (text or gzip, one file or a `*` series, from regolith or
//! LIGGGHTS) compared atom by atom (matched by ID), step by step and column by column; or
//! the thermo columns of two logs (or screen captures), matched by run and step. A value
//! pair agrees when |a - b| <= atol + rtol max(|a|, |b|); in scale-relative mode
//! (`--scale max|rms`) when |a - b| <= atol + rtol S, S being the column's largest magnitude
//! or its root mean square in the first file (the reference), so values near zero in a
//! column of large ones do not dominate.

use std::collections::BTreeMap;
use std::io::Read;

use crate::io::dump_compare::{parse, Snapshot};
pub use crate::io::error::{DiffError, TextError};

/// What to compare and how closely.
#[derive(Debug, Clone)]
pub struct DiffOptions {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance (units of each column).
    pub atol: f64,
    /// Only these columns (None: every column both files have, except `id`).
    pub columns: Option<Vec<String>>,
    /// Only steps in these inclusive ranges (None: all).
    pub steps: Option<Vec<(i64, i64)>>,
    /// `dump local` files: match entries by their place in the order of these columns
    /// (None: all columns, first to last).
    pub key: Option<Vec<String>>,
    /// Deviations relative to each column's scale in the reference (A) instead of to each
    /// value pair's magnitude.
    pub scale: Option<Scale>,
}

impl Default for DiffOptions {
    fn default() -> Self {
        DiffOptions {
            rtol: 1e-6,
            atol: 0.0,
            columns: None,
            steps: None,
            key: None,
            scale: None,
        }
    }
}

/// A column's scale in scale-relative comparisons.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// The largest magnitude of the column in the reference.
    Max,
    /// The root mean square of the column in the reference.
    Rms,
}

impl Scale {
    /// `max` or `rms`.
    pub fn parse(word: &str) -> Result<Scale, DiffError> {
        match word {
            "max" => Ok(Scale::Max),
            "rms" => Ok(Scale::Rms),
            w => Err(DiffError::Scale(w.to_string())),
        }
    }

    fn word(self) -> &'static str {
        match self {
            Scale::Max => "max",
            Scale::Rms => "rms",
        }
    }
}

/// Per column: the running largest magnitude, sum of squares and count of finite values.
#[derive(Debug, Clone, Copy, Default)]
struct Accumulated {
    max: f64,
    squares: f64,
    count: usize,
}

/// The scale of every column of the reference, from the values it holds.
#[derive(Debug, Clone, Default)]
struct Scales(BTreeMap<String, Accumulated>);

impl Scales {
    fn push(&mut self, column: &str, v: f64) {
        if !v.is_finite() {
            return;
        }
        let a = self.0.entry(column.to_string()).or_default();
        a.max = a.max.max(v.abs());
        a.squares += v * v;
        a.count += 1;
    }

    fn get(&self, column: &str, kind: Scale) -> f64 {
        self.0.get(column).map_or(0.0, |a| match kind {
            Scale::Max => a.max,
            Scale::Rms if a.count > 0 => (a.squares / a.count as f64).sqrt(),
            Scale::Rms => 0.0,
        })
    }
}

/// Parse `--steps` text: `N`, `A:B`, or a comma list of them.
pub fn parse_steps(text: &str) -> Result<Vec<(i64, i64)>, DiffError> {
    text.split(',')
        .map(|part| {
            let bad = || DiffError::Steps(part.to_string());
            match part.split_once(':') {
                Some((a, b)) => {
                    let lo = if a.is_empty() {
                        i64::MIN
                    } else {
                        a.parse().map_err(|_| bad())?
                    };
                    let hi = if b.is_empty() {
                        i64::MAX
                    } else {
                        b.parse().map_err(|_| bad())?
                    };
                    Ok((lo, hi))
                }
                None => {
                    let n = part.trim().parse().map_err(|_| bad())?;
                    Ok((n, n))
                }
            }
        })
        .collect()
}

/// One compared value that disagrees (or the worst one).
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// The step.
    pub step: i64,
    /// Atom ID (0 for thermo rows).
    pub id: i64,
    /// Column name.
    pub column: String,
    /// Value in A.
    pub a: f64,
    /// Value in B.
    pub b: f64,
    /// |a - b| / scale (0 when both are 0).
    pub rel: f64,
    /// What the deviation is relative to: max(|a|, |b|), or the column's scale in
    /// scale-relative mode.
    pub scale: f64,
}

/// Per-column summary.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ColumnStats {
    /// Values compared.
    pub count: usize,
    /// Values outside tolerance.
    pub outside: usize,
    /// Largest relative deviation.
    pub max_rel: f64,
    /// Largest absolute deviation.
    pub max_abs: f64,
}

/// The outcome of a comparison.
#[derive(Debug, Clone, Default)]
pub struct Report {
    /// Per column, in first-seen order.
    pub columns: Vec<(String, ColumnStats)>,
    /// The worst entries by relative deviation (at most 10).
    pub worst: Vec<Entry>,
    /// Structural differences: steps, atoms or columns only in one file.
    pub mismatches: Vec<String>,
    /// Steps compared.
    pub steps: usize,
    /// Rows are `dump local` entries (numbered in key order), not atoms.
    pub local: bool,
    /// Scale-relative mode, with each column's scale.
    pub scaled: Option<(Scale, Vec<(String, f64)>)>,
}

impl Report {
    /// What a row is: an atom, or an entry of a `dump local`.
    fn row_word(&self) -> &'static str {
        if self.local {
            "entry"
        } else {
            "atom"
        }
    }

    /// True when every value is within tolerance and nothing is missing.
    pub fn agrees(&self) -> bool {
        self.mismatches.is_empty() && self.columns.iter().all(|(_, s)| s.outside == 0)
    }

    /// Largest relative and absolute deviation over all columns.
    pub fn maxima(&self) -> (f64, f64) {
        self.columns.iter().fold((0.0, 0.0), |(r, a), (_, s)| {
            (f64::max(r, s.max_rel), f64::max(a, s.max_abs))
        })
    }

    fn add(&mut self, opts: &DiffOptions, e: Entry) {
        let abs = (e.a - e.b).abs();
        let k = match self.columns.iter().position(|(n, _)| *n == e.column) {
            Some(k) => k,
            None => {
                self.columns
                    .push((e.column.clone(), ColumnStats::default()));
                self.columns.len() - 1
            }
        };
        let s = &mut self.columns[k].1;
        s.count += 1;
        let both_nan = e.a.is_nan() && e.b.is_nan();
        // one NaN side is outside any tolerance
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        let outside = !both_nan && !(abs <= opts.atol + opts.rtol * e.scale);
        if outside {
            s.outside += 1;
        }
        s.max_abs = s.max_abs.max(abs);
        s.max_rel = s.max_rel.max(e.rel);
        if e.rel > 0.0 || outside {
            self.worst.push(e);
            if self.worst.len() > 40 {
                self.trim_worst();
            }
        }
    }

    fn trim_worst(&mut self) {
        // a NaN deviation (a value that is not a number in one file) ranks as the worst
        let key = |r: f64| if r.is_nan() { f64::INFINITY } else { r };
        self.worst.sort_by(|x, y| key(y.rel).total_cmp(&key(x.rel)));
        self.worst.truncate(10);
    }

    /// The human-readable report; its last line gives the maxima.
    pub fn render(&mut self, name_a: &str, name_b: &str) -> String {
        self.trim_worst();
        let mut out = format!("A: {name_a}\nB: {name_b}\n{} steps compared\n", self.steps);
        for m in self.mismatches.iter().take(20) {
            out.push_str(&format!("mismatch: {m}\n"));
        }
        if self.mismatches.len() > 20 {
            out.push_str(&format!(
                "... {} more mismatches\n",
                self.mismatches.len() - 20
            ));
        }
        let scale_of = |name: &str| {
            self.scaled
                .as_ref()
                .and_then(|(_, s)| s.iter().find(|(n, _)| n == name).map(|(_, v)| *v))
        };
        match &self.scaled {
            None => out.push_str(&format!(
                "{:<16} {:>10} {:>10} {:>13} {:>13}\n",
                "column", "values", "outside", "max rel", "max abs"
            )),
            Some((kind, _)) => out.push_str(&format!(
                "{:<16} {:>10} {:>10} {:>13} {:>13} {:>13}\n",
                "column",
                "values",
                "outside",
                "max dev/scale",
                "max abs",
                format!("scale ({})", kind.word())
            )),
        }
        for (name, s) in &self.columns {
            out.push_str(&format!(
                "{:<16} {:>10} {:>10} {:>13.6e} {:>13.6e}",
                name, s.count, s.outside, s.max_rel, s.max_abs
            ));
            if let Some(v) = scale_of(name) {
                out.push_str(&format!(" {v:>13.6e}"));
            }
            out.push('\n');
        }
        if !self.worst.is_empty() {
            out.push_str(&format!(
                "worst values (step, {}, column: A vs B):\n",
                self.row_word()
            ));
            let dev = if self.scaled.is_some() {
                "dev/scale"
            } else {
                "rel"
            };
            for e in &self.worst {
                out.push_str(&format!(
                    "  step {} {} {} {}: {:.17e} vs {:.17e} ({dev} {:.3e})\n",
                    e.step,
                    self.row_word(),
                    e.id,
                    e.column,
                    e.a,
                    e.b,
                    e.rel
                ));
            }
        }
        let (rel, abs) = self.maxima();
        let at = self
            .worst
            .first()
            .map(|e| {
                format!(
                    " (step {}, {} {}, {})",
                    e.step,
                    self.row_word(),
                    e.id,
                    e.column
                )
            })
            .unwrap_or_default();
        let what = match &self.scaled {
            None => "relative deviation",
            Some((Scale::Max, _)) => "deviation relative to the column's largest magnitude",
            Some((Scale::Rms, _)) => "deviation relative to the column's RMS",
        };
        out.push_str(&format!(
            "max {what} {rel:.6e}{at}; max absolute deviation {abs:.6e}\n"
        ));
        out
    }

    /// Record the column scales used (scale-relative mode).
    fn set_scales(&mut self, kind: Scale, scales: &Scales) {
        let list = scales.0.keys().map(|n| (n.clone(), scales.get(n, kind)));
        self.scaled = Some((kind, list.collect()));
    }
}

/// The deviation of a value pair and what it is relative to: max(|a|, |b|), or in
/// scale-relative mode the column's scale (max(|a|, |b|) still when the reference column is
/// all zero).
fn deviation(a: f64, b: f64, column_scale: Option<f64>) -> (f64, f64) {
    match column_scale {
        Some(s) if s > 0.0 => ((a - b).abs() / s, s),
        _ => (relative(a, b), a.abs().max(b.abs())),
    }
}

fn relative(a: f64, b: f64) -> f64 {
    let scale = a.abs().max(b.abs());
    if scale == 0.0 {
        0.0
    } else {
        (a - b).abs() / scale
    }
}

fn wanted_step(opts: &DiffOptions, step: i64) -> bool {
    opts.steps
        .as_ref()
        .is_none_or(|r| r.iter().any(|&(lo, hi)| step >= lo && step <= hi))
}

fn wanted_column(opts: &DiffOptions, name: &str) -> bool {
    match &opts.columns {
        Some(c) => c.iter().any(|n| n == name),
        None => name != "id",
    }
}

/// Compare two parsed dumps.
pub fn compare_dumps(a: &[Snapshot], b: &[Snapshot], opts: &DiffOptions) -> Report {
    let mut r = Report::default();
    let mut scales = Scales::default();
    if let Some(kind) = opts.scale {
        for sa in a.iter().filter(|s| wanted_step(opts, s.step)) {
            for (c, name) in sa.columns.iter().enumerate() {
                if wanted_column(opts, name) {
                    for row in sa.rows.values() {
                        scales.push(name, row[c]);
                    }
                }
            }
        }
        r.set_scales(kind, &scales);
    }
    let scale_of = |name: &str| opts.scale.map(|k| scales.get(name, k));
    let by_step: BTreeMap<i64, &Snapshot> = b.iter().map(|s| (s.step, s)).collect();
    for sa in a.iter().filter(|s| wanted_step(opts, s.step)) {
        let Some(sb) = by_step.get(&sa.step) else {
            r.mismatches.push(format!("step {} only in A", sa.step));
            continue;
        };
        r.steps += 1;
        r.local |= sa.local;
        let cols: Vec<(usize, usize, &String)> = sa
            .columns
            .iter()
            .enumerate()
            .filter(|(_, n)| wanted_column(opts, n))
            .filter_map(|(ca, n)| match sb.columns.iter().position(|c| c == n) {
                Some(cb) => Some((ca, cb, n)),
                None => {
                    r.mismatches
                        .push(format!("step {}: column {n} only in A", sa.step));
                    None
                }
            })
            .collect();
        if let Some(want) = &opts.columns {
            for n in want.iter().filter(|n| !sa.columns.contains(n)) {
                r.mismatches
                    .push(format!("step {}: column {n} not in A", sa.step));
            }
        }
        for (id, ra) in &sa.rows {
            let Some(rb) = sb.rows.get(id) else {
                r.mismatches
                    .push(format!("step {}: {} {id} only in A", sa.step, r.row_word()));
                continue;
            };
            for &(ca, cb, name) in &cols {
                let (x, y) = (ra[ca], rb[cb]);
                let (rel, scale) = deviation(x, y, scale_of(name));
                r.add(
                    opts,
                    Entry {
                        step: sa.step,
                        id: *id,
                        column: name.clone(),
                        a: x,
                        b: y,
                        rel,
                        scale,
                    },
                );
            }
        }
        for id in sb.rows.keys().filter(|id| !sa.rows.contains_key(id)) {
            r.mismatches
                .push(format!("step {}: {} {id} only in B", sa.step, r.row_word()));
        }
    }
    for sb in b.iter().filter(|s| wanted_step(opts, s.step)) {
        if !a.iter().any(|s| s.step == sb.step) {
            r.mismatches.push(format!("step {} only in B", sb.step));
        }
    }
    r
}

/// Thermo rows of a log or screen capture: (run index, step) -> column name -> value.
/// `CPU` columns (wall-clock time) are left out.
pub fn parse_thermo(text: &str) -> BTreeMap<(usize, i64), BTreeMap<String, f64>> {
    let mut out = BTreeMap::new();
    let mut header: Option<Vec<String>> = None;
    let mut run = 0;
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.first() == Some(&"Step") {
            header = Some(words.iter().map(|w| w.to_string()).collect());
            run += 1;
            continue;
        }
        if line.starts_with("Loop time") {
            header = None;
            continue;
        }
        let Some(h) = &header else { continue };
        let values: Vec<f64> = words.iter().filter_map(|w| w.parse().ok()).collect();
        if values.len() != h.len() || values.len() != words.len() {
            continue; // warnings and prints inside a run
        }
        let step = values[0] as i64;
        let row = h
            .iter()
            .zip(&values)
            .skip(1)
            .filter(|(n, _)| n.as_str() != "CPU")
            .map(|(n, v)| (n.clone(), *v))
            .collect();
        out.insert((run, step), row);
    }
    out
}

/// Compare the thermo output of two logs.
pub fn compare_logs(a: &str, b: &str, opts: &DiffOptions) -> Report {
    let (ta, tb) = (parse_thermo(a), parse_thermo(b));
    let mut r = Report::default();
    let mut scales = Scales::default();
    if let Some(kind) = opts.scale {
        for ((_, _), row) in ta.iter().filter(|((_, s), _)| wanted_step(opts, *s)) {
            for (name, v) in row.iter().filter(|(n, _)| wanted_column(opts, n)) {
                scales.push(name, *v);
            }
        }
        r.set_scales(kind, &scales);
    }
    let scale_of = |name: &str| opts.scale.map(|k| scales.get(name, k));
    for ((run, step), ra) in ta.iter().filter(|((_, s), _)| wanted_step(opts, *s)) {
        let Some(rb) = tb.get(&(*run, *step)) else {
            r.mismatches
                .push(format!("run {run} step {step} only in A"));
            continue;
        };
        r.steps += 1;
        for (name, x) in ra.iter().filter(|(n, _)| wanted_column(opts, n)) {
            let Some(y) = rb.get(name) else {
                r.mismatches
                    .push(format!("run {run} step {step}: column {name} only in A"));
                continue;
            };
            let (rel, scale) = deviation(*x, *y, scale_of(name));
            r.add(
                opts,
                Entry {
                    step: *step,
                    id: 0,
                    column: name.clone(),
                    a: *x,
                    b: *y,
                    rel,
                    scale,
                },
            );
        }
    }
    for (run, step) in tb.keys().filter(|(_, s)| wanted_step(opts, *s)) {
        if !ta.contains_key(&(*run, *step)) {
            r.mismatches
                .push(format!("run {run} step {step} only in B"));
        }
    }
    r
}

/// The text of a file, gunzipped when it starts with the gzip magic bytes.
pub fn read_text(path: &str) -> Result<String, TextError> {
    let bytes = std::fs::read(path).map_err(|source| TextError::Open {
        path: path.to_string(),
        source,
    })?;
    if bytes.starts_with(&[0x1f, 0x8b]) {
        let mut s = String::new();
        flate2::read::MultiGzDecoder::new(&bytes[..])
            .read_to_string(&mut s)
            .map_err(|source| TextError::Gzip {
                path: path.to_string(),
                source,
            })?;
        return Ok(s);
    }
    String::from_utf8(bytes).map_err(|_| TextError::NotText {
        path: path.to_string(),
    })
}

/// The files a name stands for: itself, or for a name with `*`, every file in its folder
/// that matches, ordered by the number in place of the `*`.
pub fn expand(pattern: &str) -> Result<Vec<String>, DiffError> {
    let Some(star) = pattern.find('*') else {
        return Ok(vec![pattern.to_string()]);
    };
    let (dir, file) = match pattern[..star].rfind('/') {
        Some(k) => (&pattern[..k], &pattern[k + 1..]),
        None => (".", pattern),
    };
    let (prefix, suffix) = file.split_once('*').expect("has a star");
    let mut found = Vec::new();
    let folder = |source| DiffError::Folder {
        pattern: pattern.to_string(),
        source,
    };
    for e in std::fs::read_dir(dir).map_err(folder)? {
        let name = e.map_err(folder)?.file_name();
        let Some(name) = name.to_str() else { continue };
        if let Some(mid) = name
            .strip_prefix(prefix)
            .and_then(|r| r.strip_suffix(suffix))
        {
            if let Ok(n) = mid.parse::<i64>() {
                let path = if dir == "." && !pattern.starts_with("./") {
                    name.to_string()
                } else {
                    format!("{dir}/{name}")
                };
                found.push((n, path));
            }
        }
    }
    if found.is_empty() {
        return Err(DiffError::NoMatch(pattern.to_string()));
    }
    found.sort();
    Ok(found.into_iter().map(|(_, p)| p).collect())
}

/// The last run of digits in a file name (0 if none): the step of a `*` series file.
fn step_of_name(path: &str) -> i64 {
    let name = path.rsplit('/').next().unwrap_or(path);
    let digits: String = name
        .chars()
        .rev()
        .skip_while(|c| !c.is_ascii_digit())
        .take_while(|c| c.is_ascii_digit())
        .collect();
    digits
        .chars()
        .rev()
        .collect::<String>()
        .parse()
        .unwrap_or(0)
}

/// What a file holds.
pub enum Loaded {
    /// Dump snapshots.
    Dump(Vec<Snapshot>),
    /// Log or screen text with thermo output.
    Log(String),
}

/// Read a dump (series) or log.
pub fn load(pattern: &str) -> Result<Loaded, DiffError> {
    let files = expand(pattern)?;
    let first = read_text(&files[0])?;
    if first.starts_with("# vtk DataFile") {
        // legacy VTK particle files: the step is the last number in the file name
        let mut snaps = Vec::new();
        for (k, f) in files.iter().enumerate() {
            let text = if k == 0 { first.clone() } else { read_text(f)? };
            snaps.push(
                crate::io::dump_compare::parse_vtk(&text, step_of_name(f)).map_err(|source| {
                    DiffError::Parse {
                        file: f.clone(),
                        source,
                    }
                })?,
            );
        }
        return Ok(Loaded::Dump(snaps));
    }
    if first.trim_start().starts_with("ITEM: TIMESTEP") {
        let mut snaps = Vec::new();
        for (k, f) in files.iter().enumerate() {
            let text = if k == 0 { first.clone() } else { read_text(f)? };
            snaps.extend(parse(&text).map_err(|source| DiffError::Parse {
                file: f.clone(),
                source,
            })?);
        }
        return Ok(Loaded::Dump(snaps));
    }
    if first
        .lines()
        .any(|l| l.split_whitespace().next() == Some("Step"))
    {
        if files.len() > 1 {
            return Err(DiffError::SeriesOfLogs(pattern.to_string()));
        }
        return Ok(Loaded::Log(first));
    }
    Err(DiffError::Unknown(files[0].clone()))
}

/// Run a comparison of two files; Err for unreadable input.
pub fn diff(a: &str, b: &str, opts: &DiffOptions) -> Result<Report, DiffError> {
    match (load(a)?, load(b)?) {
        (Loaded::Dump(mut x), Loaded::Dump(mut y)) => {
            for s in x.iter_mut().chain(y.iter_mut()).filter(|s| s.local) {
                s.order_entries(opts.key.as_deref())?;
            }
            Ok(compare_dumps(&x, &y, opts))
        }
        (Loaded::Log(x), Loaded::Log(y)) => Ok(compare_logs(&x, &y, opts)),
        _ => Err(DiffError::Mixed {
            a: a.to_string(),
            b: b.to_string(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DUMP: &str = "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id x fx \n2 0.5 1 \n1 0.25 0 \n";

    #[test]
    fn tolerances_and_worst_entries() {
        let a = parse(DUMP).unwrap();
        let b = parse(&DUMP.replace("0.25", "0.2500001")).unwrap();
        let mut r = compare_dumps(&a, &b, &DiffOptions::default());
        assert!(r.agrees()); // 4e-7 is inside the default rtol 1e-6
        assert!((r.maxima().0 - 4e-7 / 1.000_000_4).abs() < 1e-12);
        let text = r.render("a", "b");
        assert!(
            text.lines()
                .last()
                .unwrap()
                .starts_with("max relative deviation 3.999998e-7 (step 5, atom 1, x)"),
            "{text}"
        );
        let loose = DiffOptions {
            rtol: 1e-6,
            ..Default::default()
        };
        let strict = DiffOptions {
            rtol: 1e-7,
            ..Default::default()
        };
        assert!(compare_dumps(&a, &b, &loose).agrees());
        assert!(!compare_dumps(&a, &b, &strict).agrees());
        let only_fx = DiffOptions {
            rtol: 0.0,
            columns: Some(vec!["fx".into()]),
            ..Default::default()
        };
        assert!(compare_dumps(&a, &b, &only_fx).agrees());
        let other_step = DiffOptions {
            rtol: 0.0,
            steps: Some(vec![(6, 10)]),
            ..Default::default()
        };
        assert_eq!(compare_dumps(&a, &b, &other_step).steps, 0);
    }

    #[test]
    fn missing_atoms_and_steps_are_mismatches() {
        let a = parse(DUMP).unwrap();
        let fewer = DUMP
            .replace("ATOMS\n2", "ATOMS\n1")
            .replace("1 0.25 0 \n", "");
        let b = parse(&fewer).unwrap();
        let r = compare_dumps(&a, &b, &DiffOptions::default());
        assert_eq!(r.mismatches, vec!["step 5: atom 1 only in A".to_string()]);
        let c = parse(&DUMP.replace("TIMESTEP\n5", "TIMESTEP\n6")).unwrap();
        assert_eq!(
            compare_dumps(&a, &c, &DiffOptions::default())
                .mismatches
                .len(),
            2
        );
    }

    #[test]
    fn scale_relative_mode_ignores_near_zero_values() {
        // a stress column of scale 1e-9 with one value near zero that differs by 1e-17: per
        // value that is a 2e-4 relative deviation; against the column's scale, 1e-8
        let dump = "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n3\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id s \n1 1e-9 \n2 -5e-14 \n3 3e-10 \n";
        let a = parse(dump).unwrap();
        let b = parse(&dump.replace("-5e-14", "-5.001e-14")).unwrap();
        let plain = compare_dumps(&a, &b, &DiffOptions::default());
        assert!(!plain.agrees());
        assert!((plain.maxima().0 - 1e-17 / 5.001e-14).abs() < 1e-9);
        for (kind, scale) in [
            (Scale::Max, 1e-9),
            (Scale::Rms, ((1e-18 + 25e-28 + 9e-20) / 3.0f64).sqrt()),
        ] {
            let o = DiffOptions {
                scale: Some(kind),
                ..Default::default()
            };
            let mut r = compare_dumps(&a, &b, &o);
            assert!(r.agrees(), "{kind:?}");
            assert!((r.maxima().0 - 1e-17 / scale).abs() < 1e-12 * 1e-17 / scale + 1e-20);
            let text = r.render("a", "b");
            assert!(text.contains("scale ("), "{text}");
            assert!(
                text.lines().last().unwrap().contains("step 5, atom 2, s"),
                "{text}"
            );
        }
        // a real disagreement is still one
        let c = parse(&dump.replace("3e-10", "3.1e-10")).unwrap();
        let o = DiffOptions {
            scale: Some(Scale::Max),
            ..Default::default()
        };
        assert!(!compare_dumps(&a, &c, &o).agrees());
        // an all-zero reference column falls back to per-value deviations
        let z = "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id s \n1 0 \n";
        let r = compare_dumps(
            &parse(z).unwrap(),
            &parse(&z.replace("1 0 ", "1 1e-30 ")).unwrap(),
            &o,
        );
        assert_eq!(r.maxima().0, 1.0);
        assert!(Scale::parse("column").is_err());
    }

    #[test]
    fn scale_relative_thermo() {
        let a = "    Step         KinEng             Fz \n       0              1          1e-12 \n    1000              2            100 \nLoop time of 1\n";
        let b = a.replace("1e-12", "2e-12");
        assert!(!compare_logs(a, &b, &DiffOptions::default()).agrees());
        let o = DiffOptions {
            scale: Some(Scale::Max),
            ..Default::default()
        };
        let r = compare_logs(a, &b, &o);
        assert!(r.agrees());
        assert!((r.maxima().0 - 1e-14).abs() < 1e-20);
    }

    #[test]
    fn thermo_of_logs() {
        let a = "x\n    Step    Atoms         KinEng            CPU \n       0       75  4.0906154e-05              0 \n    1000       73  4.3873333e-05     0.01 \nLoop time of 1\n";
        let b = a.replace("4.3873333e-05     0.01", "4.3873334e-05     0.03");
        let r = compare_logs(a, &b, &DiffOptions::default());
        assert_eq!(r.steps, 2);
        assert!(r.agrees()); // 2.3e-8 relative, CPU ignored
        let r = compare_logs(
            a,
            &b,
            &DiffOptions {
                rtol: 1e-9,
                ..Default::default()
            },
        );
        assert!(!r.agrees());
        assert_eq!(
            parse_steps("0:500,700").unwrap(),
            vec![(0, 500), (700, 700)]
        );
        assert!(parse_steps("a:b").is_err());
    }
}
