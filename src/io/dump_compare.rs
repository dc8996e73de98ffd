//! Reading text dumps back and comparing two of them atom by atom, column by column
//! (the core of `regolith diff`).

use std::collections::BTreeMap;

pub use crate::io::error::DumpReadError;

/// One snapshot of a text dump.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// The timestep.
    pub step: i64,
    /// Box bounds, lo/hi per direction.
    pub bounds: [[f64; 2]; 3],
    /// Column names from the `ITEM: ATOMS` line.
    pub columns: Vec<String>,
    /// Rows keyed by atom ID (the `id` column); for `dump local`, by entry number (1, 2, ...
    /// in file order).
    pub rows: BTreeMap<i64, Vec<f64>>,
    /// A `dump local` snapshot (entries of a local compute, without atom IDs).
    pub local: bool,
}

impl Snapshot {
    /// Number a `dump local` snapshot's entries 1, 2, ... in the order of the `key` columns
    /// (all columns, first to last, if None), so that two programs' entries, which come in
    /// different orders, meet by their place in that order. Err names a missing key column.
    pub fn order_entries(&mut self, key: Option<&[String]>) -> Result<(), DumpReadError> {
        let idx: Vec<usize> = match key {
            Some(names) => names
                .iter()
                .map(|n| {
                    self.columns.iter().position(|c| c == n).ok_or_else(|| {
                        DumpReadError::NoKeyColumn {
                            step: self.step,
                            column: n.clone(),
                        }
                    })
                })
                .collect::<Result<_, _>>()?,
            None => (0..self.columns.len()).collect(),
        };
        let mut rows: Vec<Vec<f64>> = std::mem::take(&mut self.rows).into_values().collect();
        rows.sort_by(|a, b| {
            idx.iter()
                .map(|&k| a[k].total_cmp(&b[k]))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        self.rows = rows
            .into_iter()
            .enumerate()
            .map(|(k, r)| (k as i64 + 1, r))
            .collect();
        Ok(())
    }
}

/// Parse every snapshot of a `dump custom`/`dump atom` text file.
pub fn parse(text: &str) -> Result<Vec<Snapshot>, DumpReadError> {
    let mut lines = text.lines().enumerate().peekable();
    let mut out = Vec::new();
    let mut next = |what: &'static str| -> Result<(usize, &str), DumpReadError> {
        lines
            .next()
            .ok_or(DumpReadError::DumpEnds { expected: what })
    };
    while let Ok((n, l)) = next("ITEM: TIMESTEP") {
        if l.trim().is_empty() {
            continue;
        }
        if l.trim() != "ITEM: TIMESTEP" {
            return Err(DumpReadError::Expected {
                line: n + 1,
                expected: "'ITEM: TIMESTEP'",
                found: l.to_string(),
            });
        }
        let (n, l) = next("a timestep")?;
        let step: i64 = l.trim().parse().map_err(|_| bad(n, "timestep", l))?;
        let (n, l) = next("ITEM: NUMBER OF ATOMS")?;
        let local = l.trim() == "ITEM: NUMBER OF ENTRIES";
        if !local && l.trim() != "ITEM: NUMBER OF ATOMS" {
            return Err(DumpReadError::Expected {
                line: n + 1,
                expected: "'ITEM: NUMBER OF ATOMS' or 'ITEM: NUMBER OF ENTRIES'",
                found: l.to_string(),
            });
        }
        let (n, l) = next("an atom count")?;
        let count: usize = l.trim().parse().map_err(|_| bad(n, "atom count", l))?;
        next("ITEM: BOX BOUNDS")?;
        let mut bounds = [[0.0; 2]; 3];
        for b in &mut bounds {
            let (n, l) = next("box bounds")?;
            let v: Vec<f64> = l
                .split_whitespace()
                .filter_map(|w| w.parse().ok())
                .collect();
            if v.len() < 2 {
                return Err(bad(n, "box bounds", l));
            }
            *b = [v[0], v[1]];
        }
        let (n, l) = next("ITEM: ATOMS")?;
        let item = if local {
            "ITEM: ENTRIES"
        } else {
            "ITEM: ATOMS"
        };
        let columns: Vec<String> = l
            .strip_prefix(item)
            .ok_or(DumpReadError::MissingItem { line: n + 1, item })?
            .split_whitespace()
            .map(str::to_string)
            .collect();
        let id_col = if local {
            None
        } else {
            Some(
                columns
                    .iter()
                    .position(|c| c == "id")
                    .ok_or(DumpReadError::NoIdColumn)?,
            )
        };
        let mut rows = BTreeMap::new();
        for _ in 0..count {
            let (n, l) = next("an atom line")?;
            let v: Result<Vec<f64>, _> = l.split_whitespace().map(str::parse::<f64>).collect();
            let v = v.map_err(|_| DumpReadError::NonNumeric {
                line: n + 1,
                text: l.to_string(),
            })?;
            if v.len() != columns.len() {
                return Err(DumpReadError::RowLength {
                    line: n + 1,
                    values: v.len(),
                    columns: columns.len(),
                });
            }
            let key = id_col.map_or(rows.len() as i64 + 1, |c| v[c] as i64);
            rows.insert(key, v);
        }
        out.push(Snapshot {
            step,
            bounds,
            columns,
            rows,
            local,
        });
    }
    Ok(out)
}

/// A value on 0-based line `n` that does not read as `what`.
fn bad(n: usize, what: &'static str, line: &str) -> DumpReadError {
    DumpReadError::Bad {
        line: n + 1,
        what,
        found: line.to_string(),
    }
}

/// Parse a legacy ASCII VTK particle file (`dump custom/vtk`, `dump vtk`) as one snapshot at
/// `step`: columns x y z from POINTS, then every point array of the FIELD (or SCALARS and
/// VECTORS) sections, a 3-component array `v` giving `vx vy vz`. Atoms are keyed by `id`.
pub fn parse_vtk(text: &str, step: i64) -> Result<Snapshot, DumpReadError> {
    let tokens: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .skip(2)
        .flat_map(|(n, l)| l.split_whitespace().map(move |w| (n + 1, w)))
        .collect();
    let mut t = Tokens { tokens, at: 0 };
    let mut npoints = None;
    let mut columns: Vec<String> = Vec::new();
    let mut data: Vec<Vec<f64>> = Vec::new();
    let mut add = |name: &str, ncomp: usize, values: Vec<f64>, n: usize| {
        for c in 0..ncomp {
            columns.push(match (ncomp, name) {
                (1, _) => name.to_string(),
                (3, "points") => ["x", "y", "z"][c].to_string(),
                (3, _) => format!("{name}{}", ["x", "y", "z"][c]),
                _ => format!("{name}[{}]", c + 1),
            });
            data.push((0..n).map(|i| values[i * ncomp + c]).collect());
        }
    };
    while let Ok((n, w)) = t.next("") {
        match w {
            "ASCII" => {}
            "BINARY" => return Err(DumpReadError::BinaryVtk { line: n }),
            "DATASET" => {
                t.next("a dataset type")?;
            }
            "POINTS" => {
                let np = t.count("a point count")?;
                t.next("a data type")?;
                npoints = Some(np);
                add("points", 3, t.numbers(3 * np)?, np);
            }
            "VERTICES" | "CELLS" | "LINES" | "POLYGONS" => {
                let (rows, size) = (t.count("a count")?, t.count("a size")?);
                // the 5.1 layout has OFFSETS and CONNECTIVITY blocks of `rows` and `size`
                // entries; the older one `size` numbers
                if t.peek() == Some("OFFSETS") {
                    t.skip(2 + rows)?;
                    t.skip(2 + size)?;
                } else {
                    t.skip(size)?;
                }
            }
            "POINT_DATA" => {
                let np = t.count("a point count")?;
                if npoints.is_some_and(|p| p != np) {
                    return Err(DumpReadError::PointData { line: n, count: np });
                }
            }
            "CELL_DATA" => break,
            "FIELD" => {
                t.next("a field name")?;
                for _ in 0..t.count("an array count")? {
                    let (_, name) = t.next("an array name")?;
                    let ncomp = t.count("a component count")?;
                    let nt = t.count("a tuple count")?;
                    t.next("a data type")?;
                    add(name, ncomp, t.numbers(ncomp * nt)?, nt);
                }
            }
            "SCALARS" | "VECTORS" => {
                let (_, name) = t.next("an array name")?;
                t.next("a data type")?;
                let ncomp = if w == "VECTORS" { 3 } else { 1 };
                if t.peek() == Some("LOOKUP_TABLE") {
                    t.skip(2)?;
                }
                let np = npoints.unwrap_or(0);
                add(name, ncomp, t.numbers(ncomp * np)?, np);
            }
            other => {
                return Err(DumpReadError::Unexpected {
                    line: n,
                    word: other.to_string(),
                })
            }
        }
    }
    let id_col = columns
        .iter()
        .position(|c| c == "id")
        .ok_or(DumpReadError::NoIdArray)?;
    let np = npoints.ok_or(DumpReadError::NoPoints)?;
    let mut rows = BTreeMap::new();
    for i in 0..np {
        let row: Vec<f64> = data.iter().map(|c| c[i]).collect();
        rows.insert(row[id_col] as i64, row);
    }
    Ok(Snapshot {
        step,
        bounds: [[0.0; 2]; 3],
        columns,
        rows,
        local: false,
    })
}

/// A cursor over the words of a file, with their line numbers.
struct Tokens<'a> {
    tokens: Vec<(usize, &'a str)>,
    at: usize,
}

impl<'a> Tokens<'a> {
    fn next(&mut self, what: &'static str) -> Result<(usize, &'a str), DumpReadError> {
        let t = self
            .tokens
            .get(self.at)
            .copied()
            .ok_or(DumpReadError::FileEnds { expected: what })?;
        self.at += 1;
        Ok(t)
    }
    fn peek(&self) -> Option<&'a str> {
        self.tokens.get(self.at).map(|t| t.1)
    }
    fn skip(&mut self, n: usize) -> Result<(), DumpReadError> {
        if self.at + n > self.tokens.len() {
            return Err(DumpReadError::FileEndsInBlock);
        }
        self.at += n;
        Ok(())
    }
    fn count(&mut self, what: &'static str) -> Result<usize, DumpReadError> {
        let (n, w) = self.next(what)?;
        w.parse().map_err(|_| DumpReadError::Expected {
            line: n,
            expected: what,
            found: w.to_string(),
        })
    }
    fn numbers(&mut self, k: usize) -> Result<Vec<f64>, DumpReadError> {
        (0..k)
            .map(|_| {
                let (n, w) = self.next("a value")?;
                w.parse().map_err(|_| DumpReadError::Expected {
                    line: n,
                    expected: "a number",
                    found: w.to_string(),
                })
            })
            .collect()
    }
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

    #[test]
    fn broken_dumps_give_variants() {
        let e = parse("ITEM: TIMESTEP\nx\n").unwrap_err();
        assert_eq!(
            e,
            DumpReadError::Bad {
                line: 2,
                what: "timestep",
                found: "x".into()
            }
        );
        assert_eq!(e.to_string(), "line 2: bad timestep 'x'");
        let e = parse(&DUMP.replace("0.5 ", "nan? ")).unwrap_err();
        assert!(
            matches!(&e, DumpReadError::NonNumeric { line: 10, .. }),
            "{e:?}"
        );
        let e = parse(&DUMP.replace("\n1 0.25 \n", "\n")).unwrap_err();
        assert_eq!(
            e,
            DumpReadError::DumpEnds {
                expected: "an atom line"
            }
        );
        let e = parse(&DUMP.replace("ATOMS id x", "ATOMS type x")).unwrap_err();
        assert_eq!(e, DumpReadError::NoIdColumn);
        let e = parse_vtk(&VTK.replace("ASCII", "BINARY"), 0).unwrap_err();
        assert_eq!(e, DumpReadError::BinaryVtk { line: 3 });
    }

    /// A LIGGGHTS `dump custom/vtk` file (VTK 5.1 layout), two atoms.
    const VTK: &str = "# vtk DataFile Version 5.1\nGenerated by LIGGGHTS\nASCII\nDATASET POLYDATA\nPOINTS 2 float\n0.1 0.2 0.3 1 2 3 \nVERTICES 3 2\nOFFSETS vtktypeint64\n0 1 2 \nCONNECTIVITY vtktypeint64\n0 1 \nPOINT_DATA 2\nFIELD FieldData 2\nid 1 2 int\n7 4 \nv 3 2 double\n1 2 3 4 5 6 \n";

    #[test]
    fn legacy_vtk_particles() {
        let s = parse_vtk(VTK, 300).unwrap();
        assert_eq!(s.columns, ["x", "y", "z", "id", "vx", "vy", "vz"]);
        assert_eq!(s.rows[&4], vec![1.0, 2.0, 3.0, 4.0, 4.0, 5.0, 6.0]);
        assert_eq!(s.rows[&7][..3], [0.1, 0.2, 0.3]);
        assert_eq!(s.step, 300);
        assert!(parse_vtk(&VTK.replace("id 1 2", "ident 1 2"), 0).is_err());
        assert!(parse_vtk(&VTK.replace("4 5 6", "4 5"), 0).is_err());
    }
}
