//! Reading text dumps back and comparing two of them atom by atom, column by column
//! (the core of `regolith diff`).

use std::collections::BTreeMap;

/// One snapshot of a text dump.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// The timestep.
    pub step: i64,
    /// Box bounds, lo/hi per direction.
    pub bounds: [[f64; 2]; 3],
    /// Column names from the `ITEM: ATOMS` line.
    pub columns: Vec<String>,
    /// Rows keyed by atom ID (the `id` column).
    pub rows: BTreeMap<i64, Vec<f64>>,
}

/// Parse every snapshot of a `dump custom`/`dump atom` text file.
pub fn parse(text: &str) -> Result<Vec<Snapshot>, String> {
    let mut lines = text.lines().enumerate().peekable();
    let mut out = Vec::new();
    let mut next = |what: &str| -> Result<(usize, &str), String> {
        lines
            .next()
            .ok_or_else(|| format!("dump ends early: expected {what}"))
    };
    loop {
        let (n, l) = match next("ITEM: TIMESTEP") {
            Ok(x) => x,
            Err(_) => break,
        };
        if l.trim().is_empty() {
            continue;
        }
        if l.trim() != "ITEM: TIMESTEP" {
            return Err(format!(
                "line {}: expected 'ITEM: TIMESTEP', found '{l}'",
                n + 1
            ));
        }
        let (n, l) = next("a timestep")?;
        let step: i64 = l
            .trim()
            .parse()
            .map_err(|_| format!("line {}: bad timestep '{l}'", n + 1))?;
        next("ITEM: NUMBER OF ATOMS")?;
        let (n, l) = next("an atom count")?;
        let count: usize = l
            .trim()
            .parse()
            .map_err(|_| format!("line {}: bad atom count '{l}'", n + 1))?;
        next("ITEM: BOX BOUNDS")?;
        let mut bounds = [[0.0; 2]; 3];
        for b in &mut bounds {
            let (n, l) = next("box bounds")?;
            let v: Vec<f64> = l
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect();
            if v.len() < 2 {
                return Err(format!("line {}: bad box bounds '{l}'", n + 1));
            }
            *b = [v[0], v[1]];
        }
        let (n, l) = next("ITEM: ATOMS")?;
        let columns: Vec<String> = l
            .strip_prefix("ITEM: ATOMS")
            .ok_or_else(|| format!("line {}: expected 'ITEM: ATOMS'", n + 1))?
            .split_whitespace()
            .map(str::to_string)
            .collect();
        let id_col = columns
            .iter()
            .position(|c| c == "id")
            .ok_or("dump has no id column")?;
        let mut rows = BTreeMap::new();
        for _ in 0..count {
            let (n, l) = next("an atom line")?;
            let v: Result<Vec<f64>, _> = l.split_whitespace().map(str::parse::<f64>).collect();
            let v = v.map_err(|_| format!("line {}: non-numeric value in '{l}'", n + 1))?;
            if v.len() != columns.len() {
                return Err(format!(
                    "line {}: {} values for {} columns",
                    n + 1,
                    v.len(),
                    columns.len()
                ));
            }
            rows.insert(v[id_col] as i64, v);
        }
        out.push(Snapshot {
            step,
            bounds,
            columns,
            rows,
        });
    }
    Ok(out)
}

/// The largest deviation found between two dumps.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Deviation {
    /// Largest relative deviation |a-b| / max(|a|,|b|) over values above the absolute floor.
    pub max_rel: f64,
    /// Largest absolute deviation.
    pub max_abs: f64,
    /// Where the largest relative deviation is: (step, atom id, column).
    pub worst: Option<(i64, i64, String)>,
    /// Structural differences (missing steps, atoms or columns).
    pub mismatches: Vec<String>,
}

/// Compare dumps `a` and `b` step by step, atom by atom (matched by ID), column by column.
/// Values whose magnitudes are both below `atol` count as equal.
pub fn compare(a: &[Snapshot], b: &[Snapshot], atol: f64) -> Deviation {
    let mut dev = Deviation::default();
    let steps_b: BTreeMap<i64, &Snapshot> = b.iter().map(|s| (s.step, s)).collect();
    for sa in a {
        let Some(sb) = steps_b.get(&sa.step) else {
            dev.mismatches
                .push(format!("step {} only in the first dump", sa.step));
            continue;
        };
        if sa.rows.len() != sb.rows.len() {
            dev.mismatches.push(format!(
                "step {}: {} atoms vs {}",
                sa.step,
                sa.rows.len(),
                sb.rows.len()
            ));
        }
        for (ca, name) in sa.columns.iter().enumerate() {
            let Some(cb) = sb.columns.iter().position(|c| c == name) else {
                dev.mismatches
                    .push(format!("column {name} only in the first dump"));
                continue;
            };
            for (id, ra) in &sa.rows {
                let Some(rb) = sb.rows.get(id) else {
                    dev.mismatches.push(format!(
                        "step {}: atom {id} only in the first dump",
                        sa.step
                    ));
                    break;
                };
                let (x, y) = (ra[ca], rb[cb]);
                let abs = (x - y).abs();
                dev.max_abs = dev.max_abs.max(abs);
                let scale = x.abs().max(y.abs());
                if scale > atol {
                    let rel = abs / scale;
                    if rel > dev.max_rel {
                        dev.max_rel = rel;
                        dev.worst = Some((sa.step, *id, name.clone()));
                    }
                }
            }
        }
    }
    for sb in b {
        if !a.iter().any(|s| s.step == sb.step) {
            dev.mismatches
                .push(format!("step {} only in the second dump", sb.step));
        }
    }
    dev
}

#[cfg(test)]
mod tests {
    use super::*;

    const DUMP: &str = "ITEM: TIMESTEP\n5\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n0 1\n0 1\n0 1\nITEM: ATOMS id x \n2 0.5 \n1 0.25 \n";

    #[test]
    fn parse_and_compare() {
        let a = parse(DUMP).unwrap();
        assert_eq!(a[0].rows[&1], vec![1.0, 0.25]);
        let b = parse(&DUMP.replace("0.25", "0.2500001")).unwrap();
        let d = compare(&a, &b, 1e-12);
        assert!((d.max_rel - 4e-7).abs() < 1e-9, "{d:?}");
        assert_eq!(d.worst, Some((5, 1, "x".into())));
        assert!(d.mismatches.is_empty());
        let c = parse(&DUMP.replace("TIMESTEP\n5", "TIMESTEP\n6")).unwrap();
        assert_eq!(compare(&a, &c, 0.0).mismatches.len(), 2);
        assert!(parse("ITEM: TIMESTEP\nx\n").is_err());
        assert!(parse(&DUMP.replace("0.5 ", "nan? ")).is_err());
    }
}
