//! LAMMPS/LIGGGHTS data files for the granular (sphere) atom style: `read_data` and
//! `write_data`. Layout as Debian's LIGGGHTS 3.8.0 writes it: a title line, `N atoms`,
//! `N atom types`, the box bounds with `%.16e`, then `Atoms` rows
//! `id type diameter density x y z ix iy iz` and `Velocities` rows
//! `id vx vy vz omegax omegay omegaz`, in memory order. 17 significant digits make a round
//! trip exact.

use std::fmt::Write as _;

pub use crate::io::error::DataError;
use crate::io::error::Line;
use crate::state::domain::Domain;
use crate::state::particles::Particles;

/// One atom of a data file.
#[derive(Debug, Clone, PartialEq)]
pub struct DataAtom {
    /// Atom ID.
    pub id: i64,
    /// Atom type (1-based).
    pub kind: u32,
    /// Diameter (length).
    pub diameter: f64,
    /// Density (mass/length^3; the mass itself for a diameter of 0).
    pub density: f64,
    /// Position (length).
    pub x: [f64; 3],
    /// Image counts (0 when the file has none).
    pub image: [i32; 3],
    /// Velocity (length/time), zero unless a Velocities section gives it.
    pub v: [f64; 3],
    /// Angular velocity (1/time).
    pub omega: [f64; 3],
}

/// The contents of a data file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DataFile {
    /// Number of atom types.
    pub ntypes: u32,
    /// Box lower bounds (length).
    pub lo: [f64; 3],
    /// Box upper bounds (length).
    pub hi: [f64; 3],
    /// The atoms in file order.
    pub atoms: Vec<DataAtom>,
    /// Number of Velocities lines read.
    pub velocities: usize,
}

fn number<T: std::str::FromStr>(w: &str, at: &Line, what: &'static str) -> Result<T, DataError> {
    w.parse().map_err(|_| DataError::Expected {
        at: at.clone(),
        what,
        found: w.to_string(),
    })
}

/// A real number of the file: finite (`nan`, `inf` and overflowing values like `1e400` are
/// errors naming the word).
fn real(w: &str, at: &Line, what: &'static str) -> Result<f64, DataError> {
    let x: f64 = number(w, at, what)?;
    if !x.is_finite() {
        return Err(DataError::NotFinite {
            at: at.clone(),
            what,
            found: w.to_string(),
        });
    }
    Ok(x)
}

/// Parse a data file; errors name `path` and the line.
pub fn parse(text: &str, path: &str) -> Result<DataFile, DataError> {
    let lines: Vec<&str> = text.lines().collect();
    let (mut data, natoms, mut k) = header(&lines, path)?;
    // body: sections, each a keyword line, one skipped line, then its rows
    let mut index = std::collections::HashMap::new();
    while k < lines.len() {
        let l = strip(lines[k]);
        let at = line_at(path, k + 1);
        if l.is_empty() {
            k += 1;
            continue;
        }
        let section = l.clone();
        k += 2;
        match section.as_str() {
            "Atoms" => {
                for r in 0..natoms {
                    let (at, text) = section_row(&lines, path, k, r, natoms, "Atoms")?;
                    let atom = atom_row(&text, at.clone(), data.ntypes)?;
                    if index.insert(atom.id, data.atoms.len()).is_some() {
                        return Err(DataError::DuplicateId { at, id: atom.id });
                    }
                    data.atoms.push(atom);
                }
                k += natoms;
            }
            "Velocities" => {
                for r in 0..natoms {
                    let (at, text) = section_row(&lines, path, k, r, natoms, "Velocities")?;
                    let w: Vec<&str> = text.split_whitespace().collect();
                    if w.len() != 7 {
                        return Err(DataError::VelocityColumns { at, found: w.len() });
                    }
                    let id: i64 = number(w[0], &at, "an atom ID")?;
                    let i = *index
                        .get(&id)
                        .ok_or_else(|| DataError::VelocityWithoutAtom { at: at.clone(), id })?;
                    for d in 0..3 {
                        data.atoms[i].v[d] = real(w[1 + d], &at, "a velocity")?;
                        data.atoms[i].omega[d] = real(w[4 + d], &at, "an angular velocity")?;
                    }
                }
                data.velocities = natoms;
                k += natoms;
            }
            other => {
                return Err(DataError::UnsupportedSection {
                    at,
                    section: other.to_string(),
                })
            }
        }
    }
    if data.atoms.len() != natoms && natoms > 0 {
        return Err(DataError::NoAtoms {
            path: path.to_string(),
            atoms: natoms,
        });
    }
    Ok(data)
}

/// A line without its `#` comment, trimmed.
fn strip(l: &str) -> String {
    l.split('#').next().unwrap_or("").trim().to_string()
}

/// Line `k` (1-based) of the file at `path`, for messages.
fn line_at(path: &str, k: usize) -> Line {
    Line {
        path: path.to_string(),
        line: k,
    }
}

/// The header: the first line is a title, then keyword lines until one is not. Gives the
/// file with its types and box set, the atom count, and the index of the first body line.
fn header(lines: &[&str], path: &str) -> Result<(DataFile, usize, usize), DataError> {
    let mut data = DataFile::default();
    let mut natoms: Option<usize> = None;
    let mut bounds = [None; 3];
    let file = || path.to_string();
    let mut k = 1;
    while k < lines.len() {
        let l = strip(lines[k]);
        let at = line_at(path, k + 1);
        if l.is_empty() {
            k += 1;
            continue;
        }
        let w: Vec<&str> = l.split_whitespace().collect();
        match w.as_slice() {
            [n, "atoms"] => natoms = Some(number(n, &at, "an atom count")?),
            [n, "atom", "types"] => data.ntypes = number(n, &at, "a type count")?,
            [lo, hi, axis @ ("xlo" | "ylo" | "zlo"), _] => {
                let d = ["xlo", "ylo", "zlo"]
                    .iter()
                    .position(|a| a == axis)
                    .unwrap_or(0);
                bounds[d] = Some((real(lo, &at, "a number")?, real(hi, &at, "a number")?));
            }
            [_, _, _, "xy", "xz", "yz"] => return Err(DataError::Triclinic { at }),
            [n, what, ..]
                if matches!(
                    *what,
                    "bonds"
                        | "angles"
                        | "dihedrals"
                        | "impropers"
                        | "extra"
                        | "ellipsoids"
                        | "lines"
                        | "triangles"
                        | "bond"
                        | "angle"
                        | "dihedral"
                        | "improper"
                ) =>
            {
                if n.parse::<i64>() != Ok(0) {
                    return Err(DataError::Molecular { at, text: l });
                }
            }
            _ => break,
        }
        k += 1;
    }
    let natoms = natoms.ok_or_else(|| DataError::MissingHeader {
        path: file(),
        line: "N atoms",
    })?;
    if data.ntypes == 0 {
        return Err(DataError::MissingHeader {
            path: file(),
            line: "N atom types",
        });
    }
    for (d, b) in bounds.iter().enumerate() {
        let (lo, hi) = b.ok_or_else(|| DataError::MissingHeader {
            path: file(),
            line: ["xlo xhi", "ylo yhi", "zlo zhi"][d],
        })?;
        if lo >= hi || !(hi - lo).is_finite() {
            return Err(DataError::NotABox {
                path: file(),
                lo,
                hi,
            });
        }
        data.lo[d] = lo;
        data.hi[d] = hi;
    }
    Ok((data, natoms, k))
}

/// Row `r` of the section whose rows start at line index `k`: its line (for messages) and
/// its text without comment; an error when the file ends first.
fn section_row(
    lines: &[&str],
    path: &str,
    k: usize,
    r: usize,
    natoms: usize,
    section: &'static str,
) -> Result<(Line, String), DataError> {
    let text = lines.get(k + r).ok_or_else(|| DataError::SectionEnds {
        path: path.to_string(),
        section,
        read: r,
        atoms: natoms,
    })?;
    Ok((line_at(path, k + r + 1), strip(text)))
}

/// The density LIGGGHTS writes for a particle (mass/length^3): recomputed from its mass and
/// radius as `mass / (4 pi/3 r^3)` (so it can differ from the set density in the last
/// digits), the mass itself for a radius of 0; the kept `density` where the quotient
/// overflows (a radius near the smallest double).
fn written_density(mass: f64, radius: f64, density: f64) -> f64 {
    if radius == 0.0 {
        return mass;
    }
    let d = mass / (4.0 * std::f64::consts::PI / 3.0 * radius * radius * radius);
    if d.is_finite() {
        d
    } else {
        density
    }
}

/// One row of the `Atoms` section (`id type diameter density x y z [ix iy iz]`), checked.
fn atom_row(text: &str, at: Line, ntypes: u32) -> Result<DataAtom, DataError> {
    let w: Vec<&str> = text.split_whitespace().collect();
    if w.len() != 7 && w.len() != 10 {
        return Err(DataError::AtomColumns { at, found: w.len() });
    }
    let kind: u32 = number(w[1], &at, "an atom type")?;
    if kind < 1 || kind > ntypes {
        return Err(DataError::TypeRange { at, kind, ntypes });
    }
    let mut atom = DataAtom {
        id: number(w[0], &at, "an atom ID")?,
        kind,
        diameter: real(w[2], &at, "a diameter")?,
        density: real(w[3], &at, "a density")?,
        x: [0.0; 3],
        image: [0; 3],
        v: [0.0; 3],
        omega: [0.0; 3],
    };
    for d in 0..3 {
        atom.x[d] = real(w[4 + d], &at, "a coordinate")?;
        if w.len() == 10 {
            atom.image[d] = number(w[7 + d], &at, "an image count")?;
        }
    }
    if atom.diameter < 0.0 || atom.density <= 0.0 {
        return Err(DataError::BadSize { at });
    }
    if atom.diameter > 0.0 {
        crate::state::limits::check_sphere(atom.diameter, atom.density, "diameter").map_err(
            |reason| DataError::Sphere {
                at: at.clone(),
                id: atom.id,
                reason,
            },
        )?;
    }
    Ok(atom)
}

fn e16(x: f64) -> String {
    crate::util::format::with_spec("%.16e", x).unwrap_or_else(|_| x.to_string())
}

/// The data file LIGGGHTS's `write_data` writes for these particles at `step`.
pub fn write(p: &Particles, domain: &Domain, ntypes: u32, step: i64, version: &str) -> String {
    let mut s = format!(
        "LAMMPS data file via write_data, version {version}, timestep = {step}\n\n{} atoms\n{ntypes} atom types\n\n",
        p.len()
    );
    for (d, axis) in ["x", "y", "z"].iter().enumerate() {
        let _ = writeln!(
            s,
            "{} {} {axis}lo {axis}hi",
            e16(domain.lo[d]),
            e16(domain.hi[d])
        );
    }
    s.push_str("\nAtoms\n\n");
    for i in 0..p.len() {
        let x = p.x[i];
        let im = p.image[i];
        let _ = writeln!(
            s,
            "{} {} {} {} {} {} {} {} {} {}",
            p.id[i],
            p.kind[i],
            e16(2.0 * p.radius[i]),
            e16(written_density(p.mass[i], p.radius[i], p.density[i])),
            e16(x[0]),
            e16(x[1]),
            e16(x[2]),
            im[0],
            im[1],
            im[2]
        );
    }
    s.push_str("\nVelocities\n\n");
    for i in 0..p.len() {
        let (v, w) = (p.v[i], p.omega[i]);
        let _ = writeln!(
            s,
            "{} {} {} {} {} {} {}",
            p.id[i],
            e16(v[0]),
            e16(v[1]),
            e16(v[2]),
            e16(w[0]),
            e16(w[1]),
            e16(w[2])
        );
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "title\n\n2 atoms\n1 atom types\n0 1 xlo xhi\n0 1 ylo yhi\n0 1 zlo zhi\n\nAtoms\n\n1 1 0.1 2500 0.5 0.5 0.5\n2 1 0.1 2500 0.2 0.5 0.5\n";

    fn fails(text: &str) -> DataError {
        parse(text, "in.data").unwrap_err()
    }

    #[test]
    fn bad_files_give_variants_naming_file_and_line() {
        assert_eq!(parse(GOOD, "in.data").unwrap().atoms.len(), 2);
        let e = fails(&GOOD.replace("2 atoms", "two atoms"));
        assert_eq!(
            e,
            DataError::Expected {
                at: Line {
                    path: "in.data".into(),
                    line: 3
                },
                what: "an atom count",
                found: "two".into()
            }
        );
        assert_eq!(
            e.to_string(),
            "in.data:3: expected an atom count, found 'two'"
        );
        let e = fails(&GOOD.replace("0.2 0.5", "inf 0.5"));
        assert!(
            matches!(&e, DataError::NotFinite { at, what: "a coordinate", .. } if at.line == 12),
            "{e:?}"
        );
        let e = fails(&GOOD.replace("0 1 ylo yhi\n", ""));
        assert_eq!(
            e,
            DataError::MissingHeader {
                path: "in.data".into(),
                line: "ylo yhi"
            }
        );
        assert_eq!(e.to_string(), "in.data: no 'ylo yhi' line in the header");
        let e = fails(&GOOD.replace("2 1 0.1", "1 1 0.1"));
        assert!(matches!(e, DataError::DuplicateId { id: 1, .. }), "{e:?}");
        let e = fails(&GOOD.replace("2 1 0.1", "2 3 0.1"));
        assert!(
            matches!(
                e,
                DataError::TypeRange {
                    kind: 3,
                    ntypes: 1,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = fails(&format!("{GOOD}\nBonds\n\n1 1 1 2\n"));
        assert!(e.is_unsupported(), "{e:?}");
        assert!(matches!(&e, DataError::UnsupportedSection { section, .. } if section == "Bonds"));
        let e = fails(&GOOD.replace("2 1 0.1 2500 0.2 0.5 0.5\n", ""));
        assert_eq!(
            e,
            DataError::SectionEnds {
                path: "in.data".into(),
                section: "Atoms",
                read: 1,
                atoms: 2
            }
        );
    }
}
