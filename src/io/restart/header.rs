//! Section 1, the header: its values by flag, and a fresh header as LIGGGHTS writes one.

use super::format::{flag, Value, VERSION};
use super::Restart;
use crate::state::domain::{Boundary, Domain};

impl Restart {
    /// An `int` header value.
    pub fn int(&self, f: i32) -> Option<i64> {
        self.header
            .iter()
            .find(|(k, _)| *k == f)
            .and_then(|(_, v)| match v {
                Value::Int(i) => Some(*i as i64),
                Value::Big(i) => Some(*i),
                _ => None,
            })
    }

    /// A `double` header value.
    pub fn double(&self, f: i32) -> Option<f64> {
        self.header
            .iter()
            .find(|(k, _)| *k == f)
            .and_then(|(_, v)| match v {
                Value::Double(d) => Some(*d),
                _ => None,
            })
    }

    /// A string header value.
    pub fn text(&self, f: i32) -> Option<&str> {
        self.header
            .iter()
            .find(|(k, _)| *k == f)
            .and_then(|(_, v)| match v {
                Value::Text(t) => Some(t.as_str()),
                _ => None,
            })
    }

    /// Set the timestep count.
    pub fn set_step(&mut self, step: i64) {
        for (k, v) in &mut self.header {
            if *k == flag::NTIMESTEP {
                *v = Value::Big(step);
            }
        }
    }

    /// The major and minor version LIGGGHTS reads from the version string: the numbers
    /// before the first two dots after its second blank (as `atoi` reads them), if both
    /// dots are there.
    pub fn version_numbers(&self) -> Option<(i64, i64)> {
        let v = self.text(flag::VERSION)?;
        let space1 = v.find(' ')?;
        let space2 = space1 + 1 + v[space1 + 1..].find(' ')?;
        let dot1 = space2 + 1 + v[space2 + 1..].find('.')?;
        let dot2 = dot1 + 1 + v[dot1 + 1..].find('.')?;
        let atoi = crate::util::numbers::c_atoi;
        Some((atoi(&v[space2 + 1..dot1]), atoi(&v[dot1 + 1..dot2])))
    }

    /// The timestep count.
    pub fn step(&self) -> i64 {
        self.int(flag::NTIMESTEP).unwrap_or(0)
    }

    /// Unit style (`si`, `cgs`, `lj`, ...).
    pub fn units(&self) -> &str {
        self.text(flag::UNITS).unwrap_or("lj")
    }

    /// Number of atom types.
    pub fn ntypes(&self) -> u32 {
        self.int(flag::NTYPES).unwrap_or(0) as u32
    }

    /// Box bounds.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let b = |k: i32| self.double(flag::BOXLO_0 + k).unwrap_or(0.0);
        ([b(0), b(2), b(4)], [b(1), b(3), b(5)])
    }

    /// Boundary codes per direction and face (0 p, 1 f, 2 s, 3 m).
    pub fn boundary(&self) -> [[Boundary; 2]; 3] {
        let mut out = [[Boundary::Periodic; 2]; 3];
        for (d, faces) in out.iter_mut().enumerate() {
            for (s, b) in faces.iter_mut().enumerate() {
                *b = match self
                    .int(flag::BOUNDARY_00 + 2 * d as i32 + s as i32)
                    .unwrap_or(0)
                {
                    0 => Boundary::Periodic,
                    1 => Boundary::Fixed,
                    2 => Boundary::Shrink,
                    _ => Boundary::ShrinkMin,
                };
            }
        }
        out
    }
}

/// Set header value `f` (appended when the header lacks it).
pub(super) fn set_header(r: &mut Restart, f: i32, v: Value) {
    match r.header.iter_mut().find(|(k, _)| *k == f) {
        Some(slot) => slot.1 = v,
        None => r.header.push((f, v)),
    }
}

/// A header as LIGGGHTS 3.8.0 writes it for a granular system without a pair style.
pub fn fresh_header(domain: &Domain, ntypes: u32, units: &str) -> Restart {
    use Value::*;
    let code = |b: Boundary| match b {
        Boundary::Periodic => 0,
        Boundary::Fixed => 1,
        Boundary::Shrink => 2,
        Boundary::ShrinkMin => 3,
    };
    let mut h = vec![
        (0, Text(VERSION.into())),
        (1, Int(4)),
        (2, Int(4)),
        (3, Int(8)),
        (4, Text(units.into())),
        (5, Big(0)),
        (6, Int(3)),
        (7, Int(1)),
        (8, Int(1)),
        (9, Int(1)),
        (10, Int(1)),
        (11, Int(0)),
        (12, Int(0)),
    ];
    for d in 0..3 {
        h.push((flag::XPERIODIC + d as i32, Int(domain.periodic(d) as i32)));
    }
    for d in 0..3 {
        for s in 0..2 {
            h.push((
                flag::BOUNDARY_00 + 2 * d as i32 + s as i32,
                Int(code(domain.boundary[d][s])),
            ));
        }
    }
    h.push((flag::ATOM_STYLE, Text("granular".into())));
    h.push((flag::NATOMS, Big(0)));
    h.push((flag::NTYPES, Int(ntypes as i32)));
    for (f, v) in [
        (25, 0),
        (26, 0),
        (27, 0),
        (28, 0),
        (29, 0),
        (30, 0),
        (31, 0),
        (32, 0),
        (33, 0),
        (34, 0),
        (35, 0),
        (36, 0),
    ] {
        h.push((
            f,
            if matches!(f, 25 | 28 | 31 | 34) {
                Big(v)
            } else {
                Int(v as i32)
            },
        ));
    }
    for d in 0..3 {
        h.push((flag::BOXLO_0 + 2 * d as i32, Double(domain.lo[d])));
        h.push((flag::BOXLO_0 + 2 * d as i32 + 1, Double(domain.hi[d])));
    }
    for f in 43..=48 {
        h.push((f, Double(0.0)));
    }
    Restart {
        header: h,
        ngroup: 1,
        groups: vec![Some("all".into())],
        ..Restart::default()
    }
}
