//! LIGGGHTS 3.x binary restart files (`write_restart`, `restart`, `read_restart`), read and
//! written byte-compatibly with Debian's LIGGGHTS 3.8.0.
//!
//! Layout (native little-endian; `int` 4 bytes, `bigint` 8, `double` 8, strings as an `int`
//! length counting the terminating NUL, then the bytes):
//! 1. header: (`int` flag, value) pairs until flag -1; the flag says the value's type
//!    (version, sizes, units, step, dimension, processors, newton, periodicity, boundary
//!    codes, atom style, counts, box, special factors);
//! 2. groups: `int` count, then per group slot an `int` name length (0: empty) and the name;
//! 3. type arrays: (`int` flag 0, ntypes masses) pairs until -1;
//! 4. force fields: (`int` flag, style string, the style's own settings) until -1; `gran`
//!    writes an `int64` contact-model hash and one `int` set-flag per type pair i <= j;
//! 5. fixes: `int` count of fixes with global state, each id, style and an `int` byte
//!    count with that many bytes; `int` count of fixes with per-atom state, each id, style
//!    and the largest per-atom block;
//! 6. atoms: per processor chunk an `int` n and n doubles holding records, each
//!    `[length, x, y, z, id, type, mask, image, vx, vy, vz, radius, mass, density, wx, wy,
//!    wz]` followed by one block per per-atom fix, each block starting with its length.
//!    Integers inside records are stored bit for bit as 64-bit integers.
//!
//! A `%` in the name means a base file (`%` replaced by `base`) with sections 1-5 and one
//! file per processor (`%` replaced by its number) with `int` n and n doubles.

pub use crate::io::restart_error::RestartError;
use crate::state::domain::{Boundary, Domain};
use crate::state::particles::Particles;

/// Header flags, in LIGGGHTS's numbering.
pub mod flag {
    pub const VERSION: i32 = 0;
    pub const UNITS: i32 = 4;
    pub const NTIMESTEP: i32 = 5;
    pub const NPROCS: i32 = 7;
    pub const XPERIODIC: i32 = 13;
    pub const BOUNDARY_00: i32 = 16;
    pub const ATOM_STYLE: i32 = 22;
    pub const NATOMS: i32 = 23;
    pub const NTYPES: i32 = 24;
    pub const BOXLO_0: i32 = 37;
    pub const XY: i32 = 49;
    pub const YZ: i32 = 51;
}

/// One header value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// `int`.
    Int(i32),
    /// `bigint` (64-bit).
    Big(i64),
    /// `double`.
    Double(f64),
    /// A string.
    Text(String),
}

/// Reads one header value of a given type.
type ReadValue = fn(&mut Reader) -> Result<Value, RestartError>;

/// The value type of header flag `f` (None: unknown flag).
fn kind_of(f: i32) -> Option<ReadValue> {
    Some(match f {
        0 | 4 | 22 => |r| r.string().map(Value::Text),
        5 | 23 | 25 | 28 | 31 | 34 => |r| r.i64().map(Value::Big),
        1..=3 | 6..=21 | 24 | 26 | 27 | 29 | 30 | 32 | 33 | 35 | 36 => |r| r.i32().map(Value::Int),
        37..=51 => |r| r.f64().map(Value::Double),
        _ => return None,
    })
}

/// A fix's global restart state.
#[derive(Debug, Clone, PartialEq)]
pub struct GlobalFix {
    /// Fix ID.
    pub id: String,
    /// Fix style.
    pub style: String,
    /// The fix's bytes.
    pub state: Vec<u8>,
}

/// A fix that stores values with every atom.
#[derive(Debug, Clone, PartialEq)]
pub struct PeratomFix {
    /// Fix ID.
    pub id: String,
    /// Fix style.
    pub style: String,
    /// Largest per-atom block (doubles, length included).
    pub maxsize: i32,
}

/// One atom's record.
#[derive(Debug, Clone, PartialEq)]
pub struct AtomRecord {
    /// Position (length).
    pub x: [f64; 3],
    /// Atom ID.
    pub id: i64,
    /// Atom type.
    pub kind: i64,
    /// Group bits.
    pub mask: i64,
    /// Image flags, packed as LIGGGHTS packs them (10 bits per direction, offset 512).
    pub image: i64,
    /// Velocity (length/time).
    pub v: [f64; 3],
    /// Radius (length).
    pub radius: f64,
    /// Mass (mass).
    pub mass: f64,
    /// Density (mass/length^3).
    pub density: f64,
    /// Angular velocity (1/time).
    pub omega: [f64; 3],
    /// One block per per-atom fix, in the file's order, without the length word.
    pub extra: Vec<Vec<f64>>,
}

/// Unpack LIGGGHTS image flags.
pub fn unpack_image(image: i64) -> [i32; 3] {
    let i = image as i32;
    [(i & 1023) - 512, ((i >> 10) & 1023) - 512, (i >> 20) - 512]
}

/// Pack image flags as LIGGGHTS does.
pub fn pack_image(image: [i32; 3]) -> i64 {
    let c = |k: i32| (k.wrapping_add(512) & 1023) as i64;
    c(image[0]) | (c(image[1]) << 10) | ((image[2] as i64 + 512) << 20)
}

/// A whole restart file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Restart {
    /// Header (flag, value) pairs in file order.
    pub header: Vec<(i32, Value)>,
    /// Group count and group slots (None: empty slot).
    pub ngroup: i32,
    /// Group names by slot (bit).
    pub groups: Vec<Option<String>>,
    /// Per-type masses, if the file has them.
    pub masses: Option<Vec<f64>>,
    /// The pair style and its settings bytes.
    pub pair: Option<(String, Vec<u8>)>,
    /// Fixes with global state.
    pub global_fixes: Vec<GlobalFix>,
    /// Fixes with per-atom state.
    pub peratom_fixes: Vec<PeratomFix>,
    /// The atoms.
    pub atoms: Vec<AtomRecord>,
}

/// A cursor over restart bytes that names the file and offset in its errors.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
    name: &'a str,
}

impl<'a> Reader<'a> {
    /// The file's name, for messages.
    fn file(&self) -> String {
        self.name.to_string()
    }

    fn take(&mut self, n: usize, what: &'static str) -> Result<&'a [u8], RestartError> {
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
    fn i32(&mut self) -> Result<i32, RestartError> {
        Ok(i32::from_le_bytes(
            self.take(4, "an int")?.try_into().expect("4 bytes"),
        ))
    }
    fn i64(&mut self) -> Result<i64, RestartError> {
        Ok(i64::from_le_bytes(
            self.take(8, "a bigint")?.try_into().expect("8 bytes"),
        ))
    }
    fn f64(&mut self) -> Result<f64, RestartError> {
        Ok(f64::from_le_bytes(
            self.take(8, "a double")?.try_into().expect("8 bytes"),
        ))
    }
    fn count(&mut self, what: &'static str, limit: usize) -> Result<usize, RestartError> {
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
    fn string(&mut self) -> Result<String, RestartError> {
        let n = self.count("string length", 1 << 16)?;
        let at = self.at;
        let raw = self.take(n, "a string")?;
        let raw = raw.strip_suffix(&[0]).unwrap_or(raw);
        String::from_utf8(raw.to_vec()).map_err(|_| RestartError::NotText {
            file: self.name.to_string(),
            offset: at,
        })
    }
    fn doubles(&mut self, n: usize) -> Result<Vec<f64>, RestartError> {
        let raw = self.take(8 * n, "doubles")?;
        Ok(raw
            .chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().expect("8 bytes")))
            .collect())
    }
}

fn as_int(d: f64) -> i64 {
    d.to_bits() as i64
}

fn from_int(i: i64) -> f64 {
    f64::from_bits(i as u64)
}

/// Decode the atom records of `n` doubles.
fn records(
    buf: &[f64],
    nfix: usize,
    name: &str,
    out: &mut Vec<AtomRecord>,
) -> Result<(), RestartError> {
    let mut m = 0;
    while m < buf.len() {
        let len = buf[m] as usize;
        if !(17..=buf.len() - m).contains(&len) || buf[m].fract() != 0.0 {
            return Err(RestartError::RecordLength {
                file: name.to_string(),
                record: out.len() + 1,
                length: buf[m],
            });
        }
        let r = &buf[m..m + len];
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

    /// Section 5, the fixes' global states and the list of per-atom states; gives the
    /// per-atom count.
    fn read_fixes(&mut self, r: &mut Reader) -> Result<usize, RestartError> {
        let nglobal = r.count("count of fixes with global state", 4096)?;
        for _ in 0..nglobal {
            let id = r.string()?;
            let style = r.string()?;
            let n = r.count("fix state size", 1 << 30)?;
            let state = r.take(n, "fix state")?.to_vec();
            self.global_fixes.push(GlobalFix { id, style, state });
        }
        let nperatom = r.count("count of fixes with per-atom state", 4096)?;
        for _ in 0..nperatom {
            let id = r.string()?;
            let style = r.string()?;
            let maxsize = r.i32()?;
            self.peratom_fixes.push(PeratomFix { id, style, maxsize });
        }
        Ok(nperatom)
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
                for _ in 0..nprocs {
                    let n = r.count("atom chunk size", usize::MAX >> 4)?;
                    let buf = r.doubles(n)?;
                    records(&buf, nperatom, r.name, &mut self.atoms)?;
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
                    let buf = c.doubles(n)?;
                    records(&buf, nperatom, &pname, &mut self.atoms)?;
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
        let int = |b: &mut Vec<u8>, i: i32| b.extend_from_slice(&i.to_le_bytes());
        let string = |b: &mut Vec<u8>, s: &str| {
            b.extend_from_slice(&((s.len() + 1) as i32).to_le_bytes());
            b.extend_from_slice(s.as_bytes());
            b.push(0);
        };
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
        int(b, self.global_fixes.len() as i32);
        for f in &self.global_fixes {
            string(b, &f.id);
            string(b, &f.style);
            int(b, f.state.len() as i32);
            b.extend_from_slice(&f.state);
        }
        int(b, self.peratom_fixes.len() as i32);
        for f in &self.peratom_fixes {
            string(b, &f.id);
            string(b, &f.style);
            int(b, f.maxsize);
        }
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

fn open_error(path: &str, source: std::io::Error) -> RestartError {
    RestartError::Open {
        path: path.to_string(),
        source,
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

/// The version string regolith writes: LIGGGHTS parses major.minor from its third word.
pub const VERSION: &str = concat!(
    "Version LIGGGHTS-PUBLIC 3.8.0 (written by regolith ",
    env!("CARGO_PKG_VERSION"),
    ")"
);

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

fn set_header(r: &mut Restart, f: i32, v: Value) {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn image_flags_round_trip() {
        for im in [[0, 0, 0], [-1, 0, 0], [3, -2, 1], [-511, 511, -7]] {
            assert_eq!(unpack_image(pack_image(im)), im);
        }
        assert_eq!(pack_image([0, 0, 0]), 512 | (512 << 10) | (512 << 20));
    }

    #[test]
    fn truncated_and_foreign_files_are_typed_errors() {
        let r = fresh_header(&Domain::default(), 1, "si");
        let bytes = r.to_bytes();
        // the version string's length word starts at byte 4
        let e = Restart::parse(&bytes[..6], "cut", None).unwrap_err();
        assert!(
            matches!(
                &e,
                RestartError::Truncated {
                    file,
                    offset: 4,
                    reading: "an int",
                    size: 6,
                } if file == "cut"
            ),
            "{e:?}"
        );
        assert_eq!(
            e.to_string(),
            "cut: truncated at byte 4 (reading an int, file has 6 bytes)"
        );
        // the last word is the atom chunk's count
        let n = bytes.len();
        let e = Restart::parse(&bytes[..n - 2], "cut", None).unwrap_err();
        assert!(
            matches!(e, RestartError::Truncated { offset, size, .. } if offset == n - 4 && size == n - 2),
            "{e:?}"
        );
        let e = Restart::parse(&99i32.to_le_bytes(), "odd", None).unwrap_err();
        assert!(
            matches!(
                e,
                RestartError::UnknownFlag {
                    offset: 0,
                    flag: 99,
                    ..
                }
            ),
            "{e:?}"
        );
        let e = Restart::parse(b"LammpS RestartT\0\0", "new", None).unwrap_err();
        assert!(matches!(e, RestartError::NewerLammps { .. }), "{e:?}");
        assert!(!e.is_unsupported());
        let mut tri = r.clone();
        tri.header.push((flag::XY, Value::Double(0.0)));
        let e = Restart::parse(&tri.to_bytes(), "tri", None).unwrap_err();
        assert!(e.is_unsupported(), "{e:?}");
        assert_eq!(e.to_string(), "tri: triclinic box: not supported yet");
        let e = read("/nonexistent/regolith.restart").unwrap_err();
        assert!(matches!(e, RestartError::Open { .. }), "{e:?}");
    }

    #[test]
    fn deleted_groups_leave_empty_slots_and_no_trailing_ones() {
        let mut r = fresh_header(&Domain::default(), 1, "si");
        r.groups = vec![Some("all".into()), None, Some("bed".into()), None, None];
        r.ngroup = 2;
        let back = Restart::parse(&r.to_bytes(), "test", None).unwrap();
        assert_eq!(back.ngroup, 2);
        assert_eq!(
            back.groups,
            vec![Some("all".into()), None, Some("bed".into())]
        );
    }
}
