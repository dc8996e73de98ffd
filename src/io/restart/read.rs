//! Reading: the byte cursor, sections 1-4 and 6 of a restart file, `%` files, and the
//! particles and box of a file for `regolith convert`.

use super::format::{as_int, flag, kind_of, unpack_image, Value};
use super::{AtomRecord, Restart, RestartError};
use crate::state::domain::Domain;
use crate::state::particles::Particles;

/// A cursor over restart bytes that names the file and offset in its errors.
pub(super) struct Reader<'a> {
    /// The bytes.
    pub(super) bytes: &'a [u8],
    /// The offset of the next byte to read.
    pub(super) at: usize,
    /// The file's name (for messages).
    pub(super) name: &'a str,
}

impl<'a> Reader<'a> {
    /// The file's name, for messages.
    pub(super) fn file(&self) -> String {
        self.name.to_string()
    }

    pub(super) fn take(&mut self, n: usize, what: &'static str) -> Result<&'a [u8], RestartError> {
        if self.bytes.len() - self.at < n {
            return Err(RestartError::Truncated {
                file: self.name.to_string(),
                offset: self.at,
                reading: what,
                size: self.bytes.len(),
            });
        }
        let s = &self.bytes[self.at..self.at + n];
        self.at += n;
        Ok(s)
    }
    pub(super) fn i32(&mut self) -> Result<i32, RestartError> {
        Ok(i32::from_le_bytes(
            self.take(4, "an int")?.try_into().expect("4 bytes"),
        ))
    }
    pub(super) fn i64(&mut self) -> Result<i64, RestartError> {
        Ok(i64::from_le_bytes(
            self.take(8, "a bigint")?.try_into().expect("8 bytes"),
        ))
    }
    pub(super) fn f64(&mut self) -> Result<f64, RestartError> {
        Ok(f64::from_le_bytes(
            self.take(8, "a double")?.try_into().expect("8 bytes"),
        ))
    }
    pub(super) fn count(
        &mut self,
        what: &'static str,
        limit: usize,
    ) -> Result<usize, RestartError> {
        let at = self.at;
        let n = self.i32()?;
        if n < 0 || n as usize > limit {
            return Err(RestartError::Implausible {
                file: self.name.to_string(),
                offset: at,
                what,
                value: n,
            });
        }
        Ok(n as usize)
    }
    pub(super) fn string(&mut self) -> Result<String, RestartError> {
        let n = self.count("string length", 1 << 16)?;
        let at = self.at;
        let raw = self.take(n, "a string")?;
        let raw = raw.strip_suffix(&[0]).unwrap_or(raw);
        String::from_utf8(raw.to_vec()).map_err(|_| RestartError::NotText {
            file: self.name.to_string(),
            offset: at,
        })
    }
    pub(super) fn doubles(&mut self, n: usize) -> Result<Vec<f64>, RestartError> {
        let raw = self.take(8 * n, "doubles")?;
        Ok(raw
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect())
    }
}

/// Decode the atom records stored in `raw` (little-endian doubles), one record at a time
/// (no copy of the whole chunk as doubles: a large bed's file is read with one copy of it
/// in memory).
fn records(
    raw: &[u8],
    nfix: usize,
    name: &str,
    out: &mut Vec<AtomRecord>,
) -> Result<(), RestartError> {
    let n = raw.len() / 8;
    let at = |k: usize| {
        let mut b = [0u8; 8];
        b.copy_from_slice(&raw[8 * k..8 * k + 8]);
        f64::from_le_bytes(b)
    };
    let mut r = Vec::new();
    let mut m = 0;
    while m < n {
        let first = at(m);
        let len = first as usize;
        if !(17..=n - m).contains(&len) || first.fract() != 0.0 {
            return Err(RestartError::RecordLength {
                file: name.to_string(),
                record: out.len() + 1,
                length: first,
            });
        }
        r.clear();
        r.extend((m..m + len).map(at));
        let r = &r[..];
        let mut extra = Vec::with_capacity(nfix);
        let mut k = 17;
        for f in 0..nfix {
            let bl = r.get(k).copied().unwrap_or(0.0) as usize;
            if bl < 1 || bl > len - k {
                return Err(RestartError::FixBlockOverrun {
                    file: name.to_string(),
                    atom: as_int(r[4]),
                    fix: f + 1,
                });
            }
            extra.push(r[k + 1..k + bl].to_vec());
            k += bl;
        }
        if k != len {
            return Err(RestartError::LeftOver {
                file: name.to_string(),
                atom: as_int(r[4]),
                count: len - k,
            });
        }
        out.push(AtomRecord {
            x: [r[1], r[2], r[3]],
            id: as_int(r[4]),
            kind: as_int(r[5]),
            mask: as_int(r[6]),
            image: as_int(r[7]),
            v: [r[8], r[9], r[10]],
            radius: r[11],
            mass: r[12],
            density: r[13],
            omega: [r[14], r[15], r[16]],
            extra,
        });
        m += len;
    }
    Ok(())
}

impl Restart {
    /// Parse a whole restart file (`bytes` of the file `name`; `chunks` reads the
    /// per-processor files of a `%` restart).
    pub fn parse(
        bytes: &[u8],
        name: &str,
        chunks: Option<&dyn Fn(usize) -> Result<Vec<u8>, RestartError>>,
    ) -> Result<Restart, RestartError> {
        let file = || name.to_string();
        if bytes.starts_with(b"LammpS RestartT") {
            return Err(RestartError::NewerLammps { file: file() });
        }
        if bytes.len() >= 8 && bytes[..4] == [0, 0, 0, 0] {
            let le = u32::from_le_bytes(bytes[4..8].try_into().expect("4 bytes"));
            let be = u32::from_be_bytes(bytes[4..8].try_into().expect("4 bytes"));
            if le > 4096 && be <= 4096 {
                return Err(RestartError::BigEndian { file: file() });
            }
        }
        let mut r = Reader { bytes, at: 0, name };
        let mut out = Restart::default();
        out.read_header(&mut r)?;
        out.read_groups(&mut r)?;
        out.read_settings(&mut r)?;
        let nperatom = out.read_fixes(&mut r)?;
        out.read_atoms(&mut r, nperatom, chunks)?;
        Ok(out)
    }

    /// Section 1, the header: flag and value pairs up to a negative flag, refusing what
    /// regolith cannot read.
    fn read_header(&mut self, r: &mut Reader) -> Result<(), RestartError> {
        loop {
            let at = r.at;
            let f = r.i32()?;
            if f < 0 {
                break;
            }
            let read = kind_of(f).ok_or_else(|| RestartError::UnknownFlag {
                file: r.file(),
                offset: at,
                flag: f,
            })?;
            if (flag::XY..=flag::YZ).contains(&f) {
                return Err(RestartError::Triclinic { file: r.file() });
            }
            let v = read(r)?;
            if f == flag::VERSION {
                let Value::Text(t) = &v else { unreachable!() };
                let major = t
                    .split_whitespace()
                    .nth(2)
                    .and_then(|s| s.split('.').next())
                    .and_then(|s| s.parse::<i32>().ok());
                if !t.starts_with("Version LIGGGHTS") || major.is_none_or(|m| m < 3) {
                    return Err(RestartError::Version {
                        file: r.file(),
                        version: t.clone(),
                    });
                }
            }
            if f == flag::ATOM_STYLE {
                let Value::Text(t) = &v else { unreachable!() };
                if t != "granular" && t != "sphere" {
                    return Err(RestartError::AtomStyle {
                        file: r.file(),
                        style: t.clone(),
                    });
                }
            }
            if matches!(f, 25 | 28 | 31 | 34) && v != Value::Big(0) {
                return Err(RestartError::Molecular { file: r.file() });
            }
            self.header.push((f, v));
        }
        if self.text(flag::VERSION).is_none() {
            return Err(RestartError::NoVersion { file: r.file() });
        }
        Ok(())
    }

    /// Section 2, the group names (an empty name for an unused group bit).
    fn read_groups(&mut self, r: &mut Reader) -> Result<(), RestartError> {
        self.ngroup = r.count("group count", 32)? as i32;
        let mut found = 0;
        while found < self.ngroup as usize {
            if self.groups.len() >= 32 {
                return Err(RestartError::TooManyGroups { file: r.file() });
            }
            let n = r.count("group name length", 4096)?;
            if n == 0 {
                self.groups.push(None);
                continue;
            }
            let raw = r.take(n, "a group name")?;
            let raw = raw.strip_suffix(&[0]).unwrap_or(raw);
            self.groups
                .push(Some(String::from_utf8_lossy(raw).into_owned()));
            found += 1;
        }
        Ok(())
    }

    /// Sections 3 and 4, the per-type masses and the pair style's settings.
    fn read_settings(&mut self, r: &mut Reader) -> Result<(), RestartError> {
        let ntypes = self.ntypes() as usize;
        loop {
            let at = r.at;
            match r.i32()? {
                f if f < 0 => break,
                0 => self.masses = Some(r.doubles(ntypes)?),
                f => {
                    return Err(RestartError::TypeArrayFlag {
                        file: r.file(),
                        offset: at,
                        flag: f,
                    })
                }
            }
        }
        // 4. force fields
        loop {
            let at = r.at;
            match r.i32()? {
                f if f < 0 => break,
                0 => {
                    let style = r.string()?;
                    if style != "gran" {
                        return Err(RestartError::PairStyle {
                            file: r.file(),
                            style,
                        });
                    }
                    // 8 bytes of model hash, an int per type pair (i <= j)
                    let size = ntypes
                        .checked_mul(ntypes + 1)
                        .and_then(|n| (n / 2).checked_mul(4))
                        .and_then(|n| n.checked_add(8))
                        .ok_or_else(|| RestartError::PairSize {
                            file: r.file(),
                            ntypes,
                        })?;
                    let raw = r.take(size, "pair gran settings")?;
                    self.pair = Some((style, raw.to_vec()));
                }
                f => {
                    return Err(RestartError::TopologyStyle {
                        file: r.file(),
                        offset: at,
                        flag: f,
                    })
                }
            }
        }
        Ok(())
    }

    /// Section 6, the atoms: from the file itself or from the per-processor files `chunks`
    /// reads, their count checked against the header's.
    fn read_atoms(
        &mut self,
        r: &mut Reader,
        nperatom: usize,
        chunks: Option<&dyn Fn(usize) -> Result<Vec<u8>, RestartError>>,
    ) -> Result<(), RestartError> {
        let nprocs = self.int(flag::NPROCS).unwrap_or(1).max(1) as usize;
        match chunks {
            None => {
                // every record takes at least 17 doubles of what is left of the file
                let natoms = self.int(flag::NATOMS).unwrap_or(0).max(0) as usize;
                let room = (r.bytes.len() - r.at) / (17 * 8);
                self.atoms.reserve_exact(natoms.min(room));
                for _ in 0..nprocs {
                    let n = r.count("atom chunk size", usize::MAX >> 4)?;
                    let raw = r.take(8 * n, "doubles")?;
                    records(raw, nperatom, r.name, &mut self.atoms)?;
                }
                if r.at != r.bytes.len() {
                    return Err(RestartError::Trailing {
                        file: r.file(),
                        count: r.bytes.len() - r.at,
                    });
                }
            }
            Some(read_chunk) => {
                for p in 0..nprocs {
                    let data = read_chunk(p)?;
                    let pname = format!("{} (processor file {p})", r.name);
                    let mut c = Reader {
                        bytes: &data,
                        at: 0,
                        name: &pname,
                    };
                    let n = c.count("atom chunk size", usize::MAX >> 4)?;
                    let raw = c.take(8 * n, "doubles")?;
                    records(raw, nperatom, &pname, &mut self.atoms)?;
                }
            }
        }
        let natoms = self.int(flag::NATOMS).unwrap_or(-1);
        if natoms != self.atoms.len() as i64 {
            return Err(RestartError::AtomCount {
                file: r.file(),
                header: natoms,
                found: self.atoms.len(),
            });
        }
        Ok(())
    }
}

/// Read a restart file: a plain name, or a `%` name (base file plus one per processor).
pub fn read(path: &str) -> Result<Restart, RestartError> {
    if let Some(k) = path.find('%') {
        let base = format!("{}base{}", &path[..k], &path[k + 1..]);
        let bytes = std::fs::read(&base).map_err(|e| open_error(&base, e))?;
        let chunk = |p: usize| {
            let f = format!("{}{p}{}", &path[..k], &path[k + 1..]);
            std::fs::read(&f).map_err(|e| open_error(&f, e))
        };
        return Restart::parse(&bytes, &base, Some(&chunk));
    }
    let bytes = std::fs::read(path).map_err(|e| open_error(path, e))?;
    Restart::parse(&bytes, path, None)
}

/// The error for a file that cannot be opened, read or written.
pub(super) fn open_error(path: &str, source: std::io::Error) -> RestartError {
    RestartError::Open {
        path: path.to_string(),
        source,
    }
}

/// The particles and box of a restart file.
pub fn read_bed(path: &str) -> Result<crate::io::convert::Bed, RestartError> {
    let r = read(path)?;
    crate::io::restart_values::check_restart_values(&r, true).map_err(|reason| {
        RestartError::Values {
            path: path.to_string(),
            reason,
        }
    })?;
    let mut domain = Domain::default();
    domain.boundary = r.boundary();
    let (lo, hi) = r.bounds();
    domain.create(lo, hi);
    let mut p = Particles::default();
    for a in &r.atoms {
        p.push(a.id, a.kind as u32, a.x, a.radius, a.density);
        let i = p.len() - 1;
        p.mass[i] = a.mass;
        p.mask[i] = a.mask as u32;
        p.image[i] = unpack_image(a.image);
        p.v[i] = a.v;
        p.omega[i] = a.omega;
    }
    Ok(crate::io::convert::Bed {
        particles: p,
        domain,
        ntypes: r.ntypes(),
        step: r.step(),
        restart: Some(r),
    })
}
