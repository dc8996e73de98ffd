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
//!
//! The parts: `format` (flags, value types, encodings), `header` (section 1), `read` and
//! `write` (the byte streams, sections 2-4 and 6), `fixes` (section 5).

mod fixes;
mod format;
mod header;
mod read;
mod write;

pub use crate::io::restart_error::RestartError;
pub use fixes::{GlobalFix, PeratomFix};
pub use format::{flag, pack_image, unpack_image, Value, VERSION};
pub use header::fresh_header;
pub use read::{read, read_bed};
pub use write::{write, write_bed, write_processor_files};

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::state::domain::Domain;

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
