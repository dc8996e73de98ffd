//! The format's constants and encodings: header flags and their value types, the version
//! string regolith writes, image flags as LIGGGHTS packs them, and integers stored bit for
//! bit in the doubles of atom records.

use super::read::Reader;
use super::RestartError;

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
pub(super) type ReadValue = fn(&mut Reader) -> Result<Value, RestartError>;

/// The value type of header flag `f` (None: unknown flag).
pub(super) fn kind_of(f: i32) -> Option<ReadValue> {
    Some(match f {
        0 | 4 | 22 => |r| r.string().map(Value::Text),
        5 | 23 | 25 | 28 | 31 | 34 => |r| r.i64().map(Value::Big),
        1..=3 | 6..=21 | 24 | 26 | 27 | 29 | 30 | 32 | 33 | 35 | 36 => |r| r.i32().map(Value::Int),
        37..=51 => |r| r.f64().map(Value::Double),
        _ => return None,
    })
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

/// The version string regolith writes: LIGGGHTS parses major.minor from its third word.
pub const VERSION: &str = concat!(
    "Version LIGGGHTS-PUBLIC 3.8.0 (written by regolith ",
    env!("CARGO_PKG_VERSION"),
    ")"
);

/// An integer of an atom record, stored bit for bit in a double.
pub(super) fn as_int(d: f64) -> i64 {
    d.to_bits() as i64
}

/// An integer as an atom record stores it, bit for bit in a double.
pub(super) fn from_int(i: i64) -> f64 {
    f64::from_bits(i as u64)
}
