//! `dump custom` and `dump atom` snapshots in LIGGGHTS's exact text layout:
//! `ITEM:` header lines, box bounds printed with `%g` after the boundary letters, a trailing
//! blank after every column name and every value, `%d` for integer columns and `%g` for the
//! rest unless `dump_modify format` gives one C format per column.

use std::io::Write;

pub use crate::io::error::ColumnError;
use crate::state::domain::Domain;
use crate::state::particles::Particles;
use crate::util::format::{self, CFormat, Piece};

/// A per-atom quantity a dump column shows.
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// Atom ID.
    Id,
    /// Atom type.
    Type,
    /// Molecule ID: the multisphere body tag (-1 outside a body).
    Mol,
    /// Position component 0..3 (length).
    X(usize),
    /// Position scaled to the box, 0..1.
    Scaled(usize),
    /// Unwrapped position (length).
    Unwrapped(usize),
    /// Image count.
    Image(usize),
    /// Velocity component (length/time).
    V(usize),
    /// Force component (force).
    F(usize),
    /// Angular velocity component (1/time).
    Omega(usize),
    /// Torque component (force length).
    Torque(usize),
    /// Radius (length).
    Radius,
    /// Diameter (length).
    Diameter,
    /// Mass.
    Mass,
    /// Density (mass/length^3).
    Density,
    /// A compute, fix or variable value (`c_ID`, `c_ID[N]`, `f_ID[N]`, `v_name`): the
    /// caller supplies these through the `extra` callback, numbered in column order.
    Reference(String),
}

impl Column {
    /// Parse one column keyword of `dump custom`.
    pub fn parse(word: &str) -> Result<Column, ColumnError> {
        let axis = |c: char| match c {
            'x' => Some(0),
            'y' => Some(1),
            'z' => Some(2),
            _ => None,
        };
        Ok(match word {
            "id" => Column::Id,
            "type" => Column::Type,
            "mol" => Column::Mol,
            "x" | "y" | "z" => Column::X(axis(word.chars().next().unwrap()).unwrap()),
            "xs" | "ys" | "zs" => Column::Scaled(axis(word.chars().next().unwrap()).unwrap()),
            "xu" | "yu" | "zu" => Column::Unwrapped(axis(word.chars().next().unwrap()).unwrap()),
            "ix" | "iy" | "iz" => Column::Image(axis(word.chars().nth(1).unwrap()).unwrap()),
            "vx" | "vy" | "vz" => Column::V(axis(word.chars().nth(1).unwrap()).unwrap()),
            "fx" | "fy" | "fz" => Column::F(axis(word.chars().nth(1).unwrap()).unwrap()),
            "omegax" | "omegay" | "omegaz" => {
                Column::Omega(axis(word.chars().nth(5).unwrap()).unwrap())
            }
            "tqx" | "tqy" | "tqz" => Column::Torque(axis(word.chars().nth(2).unwrap()).unwrap()),
            "radius" => Column::Radius,
            "diameter" => Column::Diameter,
            "mass" => Column::Mass,
            "density" => Column::Density,
            w if w.starts_with("c_") || w.starts_with("f_") || w.starts_with("v_") => {
                Column::Reference(w.to_string())
            }
            w => return Err(ColumnError::Attribute(w.to_string())),
        })
    }

    /// The value of an atom column for particle `i` (`Reference` columns give NaN: their
    /// values come from the compute, fix or variable).
    #[inline]
    pub fn value(&self, p: &Particles, domain: &Domain, i: usize) -> f64 {
        match self {
            Column::Id => p.id[i] as f64,
            Column::Type => p.kind[i] as f64,
            Column::Mol => crate::state::bodies::body_tags(p).map_or(-1.0, |t| t[i]),
            Column::X(d) => p.x[i][*d],
            // LIGGGHTS multiplies by the reciprocal length (its `invxprd`)
            Column::Scaled(d) => (p.x[i][*d] - domain.lo[*d]) * (1.0 / domain.length(*d)),
            Column::Unwrapped(d) => p.x[i][*d] + p.image[i][*d] as f64 * domain.length(*d),
            Column::Image(d) => p.image[i][*d] as f64,
            Column::V(d) => p.v[i][*d],
            Column::F(d) => p.f[i][*d],
            Column::Omega(d) => p.omega[i][*d],
            Column::Torque(d) => p.torque[i][*d],
            Column::Radius => p.radius[i],
            Column::Diameter => 2.0 * p.radius[i],
            Column::Mass => p.mass[i],
            Column::Density => p.density[i],
            Column::Reference(_) => f64::NAN,
        }
    }

    /// True for the columns LIGGGHTS prints as integers.
    pub fn is_integer(&self) -> bool {
        matches!(
            self,
            Column::Id | Column::Type | Column::Mol | Column::Image(_)
        )
    }
}

/// The columns `dump atom` writes: id type xs ys zs (scaled positions).
pub fn atom_style_columns() -> Vec<Column> {
    vec![
        Column::Id,
        Column::Type,
        Column::Scaled(0),
        Column::Scaled(1),
        Column::Scaled(2),
    ]
}

/// How one dump lays out its snapshots.
#[derive(Debug, Clone)]
pub struct Layout {
    /// Column keywords as written in the command (for the `ITEM: ATOMS` line).
    pub names: Vec<String>,
    /// The parsed columns.
    pub columns: Vec<Column>,
    /// One C conversion per column (`dump_modify format`), or None for `%d`/`%g`.
    pub format: Option<Vec<CFormat>>,
    /// Sort atoms by ID (`dump_modify sort id`).
    pub sort_by_id: bool,
    /// Values separated by single blanks without a trailing one (LAMMPS's `dump atom`);
    /// LIGGGHTS's `dump custom` ends every name and value with a blank.
    pub no_trailing_blank: bool,
    /// `dump_modify binary yes` of VTK dumps: binary legacy files, base64 XML arrays.
    pub binary: bool,
}

impl Layout {
    /// A layout for the given column keywords.
    pub fn new(names: &[&str]) -> Result<Layout, ColumnError> {
        let columns = names
            .iter()
            .map(|n| Column::parse(n))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Layout {
            names: names.iter().map(|s| s.to_string()).collect(),
            columns,
            format: None,
            sort_by_id: false,
            no_trailing_blank: false,
            binary: false,
        })
    }

    /// `dump_modify format "..."`: one element per column, separated by blanks. LIGGGHTS
    /// prints each value with its element as a `printf` format: text around the conversion
    /// is printed as it is, and an element without a conversion prints only its text (the
    /// column's value is left out).
    pub fn set_format(&mut self, text: &str) -> Result<(), ColumnError> {
        let mut convs = Vec::new();
        for token in text.split(' ').filter(|t| !t.is_empty()) {
            let parsed = CFormat::parse(token)?;
            let n = parsed
                .pieces
                .iter()
                .filter(|p| matches!(p, Piece::Convert(_)))
                .count();
            if n > 1 {
                return Err(ColumnError::NotSingle(token.to_string()));
            }
            convs.push(parsed);
        }
        let ncols = self.columns.len().max(self.names.len());
        if convs.len() < ncols {
            return Err(ColumnError::TooShort);
        }
        convs.truncate(ncols);
        self.format = Some(convs);
        Ok(())
    }

    /// Write one snapshot at `step` of the atoms selected by `group` bits. `extra(k, i)`
    /// gives the value of the k-th `Reference` column for atom i.
    pub fn write_snapshot(
        &self,
        out: &mut impl Write,
        step: i64,
        p: &Particles,
        group: u32,
        domain: &Domain,
        mut extra: impl FnMut(usize, usize) -> f64,
    ) -> std::io::Result<()> {
        let mut atoms: Vec<usize> = (0..p.len()).filter(|&i| p.mask[i] & group != 0).collect();
        if self.sort_by_id {
            atoms.sort_by_key(|&i| p.id[i]);
        }
        writeln!(
            out,
            "ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ATOMS\n{}",
            atoms.len()
        )?;
        writeln!(out, "ITEM: BOX BOUNDS {}", domain.boundary_label())?;
        for d in 0..3 {
            writeln!(
                out,
                "{} {}",
                format::g(domain.lo[d]),
                format::g(domain.hi[d])
            )?;
        }
        let mut header = String::from("ITEM: ATOMS ");
        for n in &self.names {
            header.push_str(n);
            header.push(' ');
        }
        if self.no_trailing_blank {
            header.pop();
        }
        writeln!(out, "{header}")?;
        let mut line = String::with_capacity(16 * self.columns.len());
        for &i in &atoms {
            line.clear();
            let mut reference = 0;
            for (k, col) in self.columns.iter().enumerate() {
                let value = match col {
                    Column::Reference(_) => {
                        reference += 1;
                        extra(reference - 1, i)
                    }
                    col => col.value(p, domain, i),
                };
                match &self.format {
                    Some(convs) => format::push_element(&mut line, &convs[k], value),
                    None if col.is_integer() => {
                        use std::fmt::Write as _;
                        let _ = write!(line, "{}", value as i64);
                    }
                    None => format::push_g(&mut line, value),
                }
                line.push(' ');
            }
            if self.no_trailing_blank {
                line.pop();
            }
            writeln!(out, "{line}")?;
        }
        Ok(())
    }
}

impl Layout {
    /// Write one snapshot at `step` in LAMMPS's binary dump format, as LIGGGHTS writes files
    /// whose names end in `.bin`: the step and atom count (8-byte integers), the triclinic
    /// flag and the six boundary codes (4-byte; p 0, f 1, s 2, m 3), the box bounds, the
    /// values per atom and the process count (one), then the value count and every value as
    /// a double, atom by atom; little-endian as LIGGGHTS on this machine.
    pub fn write_binary_snapshot(
        &self,
        out: &mut impl Write,
        step: i64,
        p: &Particles,
        group: u32,
        domain: &Domain,
        mut extra: impl FnMut(usize, usize) -> f64,
    ) -> std::io::Result<()> {
        use crate::state::domain::Boundary;
        let mut atoms: Vec<usize> = (0..p.len()).filter(|&i| p.mask[i] & group != 0).collect();
        if self.sort_by_id {
            atoms.sort_by_key(|&i| p.id[i]);
        }
        let mut bytes = Vec::with_capacity(100 + 8 * atoms.len() * self.columns.len());
        bytes.extend_from_slice(&step.to_le_bytes());
        bytes.extend_from_slice(&(atoms.len() as i64).to_le_bytes());
        bytes.extend_from_slice(&0i32.to_le_bytes());
        for b in domain.boundary.iter().flatten() {
            let code: i32 = match b {
                Boundary::Periodic => 0,
                Boundary::Fixed => 1,
                Boundary::Shrink => 2,
                Boundary::ShrinkMin => 3,
            };
            bytes.extend_from_slice(&code.to_le_bytes());
        }
        for d in 0..3 {
            bytes.extend_from_slice(&domain.lo[d].to_le_bytes());
            bytes.extend_from_slice(&domain.hi[d].to_le_bytes());
        }
        let ncols = self.columns.len() as i32;
        bytes.extend_from_slice(&ncols.to_le_bytes());
        bytes.extend_from_slice(&1i32.to_le_bytes());
        bytes.extend_from_slice(&(atoms.len() as i32 * ncols).to_le_bytes());
        for &i in &atoms {
            let mut reference = 0;
            for col in &self.columns {
                let value = match col {
                    Column::Reference(_) => {
                        reference += 1;
                        extra(reference - 1, i)
                    }
                    col => col.value(p, domain, i),
                };
                bytes.extend_from_slice(&value.to_le_bytes());
            }
        }
        out.write_all(&bytes)
    }
}

/// Write one `dump local` snapshot in LIGGGHTS's layout: `NUMBER OF ENTRIES`, the box,
/// `ITEM: ENTRIES` with the column names, then the values (`%g`, or the `dump_modify format`
/// conversions) each followed by a blank.
pub fn write_local(
    out: &mut impl Write,
    step: i64,
    domain: &Domain,
    names: &[String],
    formats: Option<&[CFormat]>,
    rows: usize,
    value: impl Fn(usize, usize) -> f64,
) -> std::io::Result<()> {
    writeln!(
        out,
        "ITEM: TIMESTEP\n{step}\nITEM: NUMBER OF ENTRIES\n{rows}"
    )?;
    writeln!(out, "ITEM: BOX BOUNDS {}", domain.boundary_label())?;
    for d in 0..3 {
        writeln!(
            out,
            "{} {}",
            format::g(domain.lo[d]),
            format::g(domain.hi[d])
        )?;
    }
    let mut header = String::from("ITEM: ENTRIES ");
    for n in names {
        header.push_str(n);
        header.push(' ');
    }
    writeln!(out, "{header}")?;
    let mut line = String::new();
    for r in 0..rows {
        line.clear();
        for c in 0..names.len() {
            match formats {
                Some(convs) => format::push_element(&mut line, &convs[c], value(r, c)),
                None => format::push_g(&mut line, value(r, c)),
            }
            line.push(' ');
        }
        writeln!(out, "{line}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::state::domain::parse_boundary;

    #[test]
    fn liggghts_layout() {
        let mut p = Particles::default();
        p.push(2, 1, [0.5, -0.0, 1e-7], 0.001, 2500.0);
        p.push(1, 2, [0.25, 0.125, 3.0], 0.002, 2500.0);
        p.v[1] = [1.0 / 3.0, 0.0, -2.0];
        let mut domain = Domain::default();
        domain.boundary = parse_boundary(&["p", "f", "fm"]).unwrap();
        domain.create([0.0; 3], [1.0, 0.5, 4.0]);
        let mut layout =
            Layout::new(&["id", "type", "x", "y", "z", "vx", "radius", "c_s[1]"]).unwrap();
        layout.sort_by_id = true;
        let mut out = Vec::new();
        layout
            .write_snapshot(&mut out, 1000, &p, 1, &domain, |k, i| (k * 10 + i) as f64)
            .unwrap();
        let text = String::from_utf8(out).unwrap();
        assert_eq!(
            text,
            "ITEM: TIMESTEP\n1000\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS pp ff fm\n0 1\n0 0.5\n0 4\n\
             ITEM: ATOMS id type x y z vx radius c_s[1] \n\
             1 2 0.25 0.125 3 0.333333 0.002 1 \n\
             2 1 0.5 -0 1e-07 0 0.001 0 \n"
        );
        layout.set_format("%d %d %.17g %g %g %g %g %g").unwrap();
        let mut out = Vec::new();
        layout
            .write_snapshot(&mut out, 0, &p, 1, &domain, |_, _| 0.0)
            .unwrap();
        assert!(String::from_utf8(out)
            .unwrap()
            .contains("\n1 2 0.25 0.125 3 0.333333 0.002 0 \n"));
        assert!(layout.set_format("%d %d").is_err());
        assert!(Column::parse("velocity").is_err());
    }
}
