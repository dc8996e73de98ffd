//! Writing: a restart file's bytes, `%` files written by a processor grid, and a bed
//! written back as a restart file.

use super::format::{flag, from_int, pack_image, Value};
use super::header::{fresh_header, set_header};
use super::read::open_error;
use super::{AtomRecord, Restart, RestartError};

/// Append an `int`.
pub(super) fn put_int(b: &mut Vec<u8>, i: i32) {
    b.extend_from_slice(&i.to_le_bytes());
}

/// Append a string: its length with the terminating NUL, the bytes, the NUL.
pub(super) fn put_string(b: &mut Vec<u8>, s: &str) {
    put_int(b, (s.len() + 1) as i32);
    b.extend_from_slice(s.as_bytes());
    b.push(0);
}

impl Restart {
    /// The file's bytes (single-file form).
    pub fn to_bytes(&self) -> Vec<u8> {
        // sized up front: a file of many atom types or atoms is not built by doubling
        let pair = self
            .pair
            .as_ref()
            .map_or(0, |(s, raw)| s.len() + raw.len() + 16);
        let fixes: usize = self.global_fixes.iter().map(|f| f.state.len() + 64).sum();
        let atoms: usize = self
            .atoms
            .iter()
            .map(|a| 8 * (18 + a.extra.iter().map(|e| e.len() + 1).sum::<usize>()))
            .sum();
        let mut b = Vec::with_capacity(4096 + pair + fixes + atoms);
        self.write_base(&mut b);
        let chunk = self.atom_chunk();
        b.extend_from_slice(&(chunk.len() as i32).to_le_bytes());
        for d in chunk {
            b.extend_from_slice(&d.to_le_bytes());
        }
        b
    }

    /// Sections 1-5 (the base file of a `%` restart). The processor count is written as 1.
    pub fn write_base(&self, b: &mut Vec<u8>) {
        self.write_base_for(b, [1, 1, 1]);
    }

    /// Sections 1-5 with the processor grid `grid` (and the product as the processor
    /// count) in the header, as a base file written on that grid holds them.
    pub fn write_base_for(&self, b: &mut Vec<u8>, grid: [i32; 3]) {
        let (int, string) = (put_int, put_string);
        for (f, v) in &self.header {
            int(b, *f);
            match (f, v) {
                (7, Value::Int(_)) => int(b, grid.iter().product()),
                (8..=10, Value::Int(_)) => int(b, grid[(f - 8) as usize]),
                (_, Value::Int(i)) => int(b, *i),
                (_, Value::Big(i)) => b.extend_from_slice(&i.to_le_bytes()),
                (_, Value::Double(d)) => b.extend_from_slice(&d.to_le_bytes()),
                (_, Value::Text(t)) => string(b, t),
            }
        }
        int(b, -1);
        int(b, self.ngroup);
        // as LIGGGHTS: slots up to the last named group (a deleted group leaves an empty slot;
        // empty slots after the last named one are not written, readers stop there)
        let mut named = 0;
        for g in &self.groups {
            if named == self.ngroup {
                break;
            }
            match g {
                Some(name) => {
                    string(b, name);
                    named += 1;
                }
                None => int(b, 0),
            }
        }
        if let Some(m) = &self.masses {
            int(b, 0);
            for x in m {
                b.extend_from_slice(&x.to_le_bytes());
            }
        }
        int(b, -1);
        if let Some((style, raw)) = &self.pair {
            int(b, 0);
            string(b, style);
            b.extend_from_slice(raw);
        }
        int(b, -1);
        self.write_fixes(b);
    }

    /// All atom records as one chunk of doubles.
    pub fn atom_chunk(&self) -> Vec<f64> {
        let all: Vec<usize> = (0..self.atoms.len()).collect();
        self.atom_chunk_of(&all)
    }

    /// The records of the atoms `which` (indices into [`Self::atoms`], in that order) as one
    /// chunk of doubles.
    pub fn atom_chunk_of(&self, which: &[usize]) -> Vec<f64> {
        let mut out = Vec::new();
        for a in which.iter().filter_map(|&k| self.atoms.get(k)) {
            let len = 17 + a.extra.iter().map(|e| e.len() + 1).sum::<usize>();
            out.push(len as f64);
            out.extend_from_slice(&a.x);
            out.push(from_int(a.id));
            out.push(from_int(a.kind));
            out.push(from_int(a.mask));
            out.push(from_int(a.image));
            out.extend_from_slice(&a.v);
            out.push(a.radius);
            out.push(a.mass);
            out.push(a.density);
            out.extend_from_slice(&a.omega);
            for e in &a.extra {
                out.push((e.len() + 1) as f64);
                out.extend_from_slice(e);
            }
        }
        out
    }
}

/// Write a restart file atomically (a `%` name gives the base file and one processor file).
pub fn write(restart: &Restart, path: &str) -> Result<(), RestartError> {
    if path.contains('%') {
        let all: Vec<usize> = (0..restart.atoms.len()).collect();
        return write_processor_files(restart, path, [1, 1, 1], 0, &all);
    }
    crate::io::write_atomically(path, &restart.to_bytes()).map_err(|e| open_error(path, e))
}

/// Processor `me`'s part of a `%` restart written by the processor grid `grid` (as LIGGGHTS
/// writes one in parallel): processor 0 writes the base file (`%` replaced by `base`, the
/// processor count and grid in its header) and every processor the file of its own number
/// with its atoms, `mine` (indices into the file's atoms, in that order). A name without
/// `%` is written whole by processor 0.
pub fn write_processor_files(
    restart: &Restart,
    path: &str,
    grid: [i32; 3],
    me: usize,
    mine: &[usize],
) -> Result<(), RestartError> {
    let Some(k) = path.find('%') else {
        if me == 0 {
            return write(restart, path);
        }
        return Ok(());
    };
    let named = |what: &str| format!("{}{what}{}", &path[..k], &path[k + 1..]);
    let chunk = restart.atom_chunk_of(mine);
    let mut c = Vec::with_capacity(4 + 8 * chunk.len());
    c.extend_from_slice(&(chunk.len() as i32).to_le_bytes());
    for d in chunk {
        c.extend_from_slice(&d.to_le_bytes());
    }
    let own = named(&me.to_string());
    crate::io::write_atomically(&own, &c).map_err(|e| open_error(&own, e))?;
    if me == 0 {
        let base = named("base");
        let mut b = Vec::new();
        restart.write_base_for(&mut b, grid);
        crate::io::write_atomically(&base, &b).map_err(|e| open_error(&base, e))?;
    }
    Ok(())
}

/// Write a bed as a restart file: the particles (masks, images, spins) with the rest of
/// the restart it came from, or a fresh header (units si, no pair style, no fixes) for a
/// bed read from a data file.
pub fn write_bed(bed: &crate::io::convert::Bed, path: &str) -> Result<(), RestartError> {
    let mut r = match &bed.restart {
        Some(r) => r.clone(),
        None => fresh_header(&bed.domain, bed.ntypes, "si"),
    };
    set_header(&mut r, flag::NTIMESTEP, Value::Big(bed.step));
    set_header(&mut r, flag::NATOMS, Value::Big(bed.particles.len() as i64));
    let keep_extra = bed.restart.is_some();
    let old: std::collections::HashMap<i64, &AtomRecord> = bed
        .restart
        .as_ref()
        .map(|r| r.atoms.iter().map(|a| (a.id, a)).collect())
        .unwrap_or_default();
    let p = &bed.particles;
    let nfix = r.peratom_fixes.len();
    r.atoms = (0..p.len())
        .map(|i| AtomRecord {
            x: p.x[i],
            id: p.id[i],
            kind: p.kind[i] as i64,
            mask: p.mask[i] as i64,
            image: pack_image(p.image[i]),
            v: p.v[i],
            radius: p.radius[i],
            mass: p.mass[i],
            density: p.density[i],
            omega: p.omega[i],
            extra: match (keep_extra, old.get(&p.id[i])) {
                (true, Some(a)) => a.extra.clone(),
                _ => vec![Vec::new(); nfix],
            },
        })
        .collect();
    write(&r, path)
}
