//! Why a LIGGGHTS restart file cannot be read or written, as data: the file, the byte offset
//! and what was expected or found. `Display` gives the message regolith prints.

use thiserror::Error;

/// A restart file that cannot be read or written.
#[derive(Debug, Error)]
pub enum RestartError {
    /// The file cannot be opened, read or written.
    #[error("Cannot open restart file {path}: {source}")]
    Open {
        /// The file as named.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// The file ends before a value it promises.
    #[error("{file}: truncated at byte {offset} (reading {reading}, file has {size} bytes)")]
    Truncated {
        /// The file (with the processor file, for a `%` restart).
        file: String,
        /// Byte offset where the value starts.
        offset: usize,
        /// The value being read (`an int`, `a string`, ...).
        reading: &'static str,
        /// The file's length (bytes).
        size: usize,
    },
    /// A count or length outside what any LIGGGHTS file holds.
    #[error("{file}: byte {offset}: {what} {value} is not plausible")]
    Implausible {
        /// The file.
        file: String,
        /// Byte offset of the count.
        offset: usize,
        /// What the count counts (`string length`, `group count`, ...).
        what: &'static str,
        /// The count found.
        value: i32,
    },
    /// A string whose bytes are not UTF-8.
    #[error("{file}: byte {offset}: a string that is not text")]
    NotText {
        /// The file.
        file: String,
        /// Byte offset of the string's bytes.
        offset: usize,
    },
    /// An atom record too short or too long for the chunk.
    #[error("{file}: atom record {record} has length {length} (expected at least 17 values for atom_style granular)")]
    RecordLength {
        /// The file.
        file: String,
        /// The record's number (1-based).
        record: usize,
        /// The length word as stored.
        length: f64,
    },
    /// A per-atom fix block running past the end of its atom's record.
    #[error("{file}: atom {atom}: per-atom block {fix} of fix {fix} overruns the record")]
    FixBlockOverrun {
        /// The file.
        file: String,
        /// The atom's ID.
        atom: i64,
        /// The per-atom fix (1-based).
        fix: usize,
    },
    /// Values of a record that no per-atom fix block claims.
    #[error("{file}: atom {atom}: {count} values left over after the per-atom fix blocks")]
    LeftOver {
        /// The file.
        file: String,
        /// The atom's ID.
        atom: i64,
        /// How many values are left.
        count: usize,
    },
    /// The restart format of newer LAMMPS versions.
    #[error("{file}: a restart file of a newer LAMMPS (magic 'LammpS RestartT'); regolith reads LIGGGHTS 3.x restart files")]
    NewerLammps {
        /// The file.
        file: String,
    },
    /// A file written on a big-endian machine.
    #[error("{file}: big-endian restart file (written on a machine of the other byte order); regolith reads little-endian files")]
    BigEndian {
        /// The file.
        file: String,
    },
    /// A header flag LIGGGHTS 3.x does not write.
    #[error(
        "{file}: byte {offset}: unknown header flag {flag} (not a LIGGGHTS 3.x restart file?)"
    )]
    UnknownFlag {
        /// The file.
        file: String,
        /// Byte offset of the flag.
        offset: usize,
        /// The flag.
        flag: i32,
    },
    /// A triclinic box (valid LIGGGHTS, not run by regolith yet).
    #[error("{file}: triclinic box: not supported yet")]
    Triclinic {
        /// The file.
        file: String,
    },
    /// A file of another program or of LIGGGHTS before 3.x.
    #[error("{file}: written by '{version}'; regolith reads restart files of LIGGGHTS 3.x")]
    Version {
        /// The file.
        file: String,
        /// The version string of the header.
        version: String,
    },
    /// An atom style other than granular or sphere.
    #[error("{file}: atom_style {style}: regolith reads granular and sphere restarts")]
    AtomStyle {
        /// The file.
        file: String,
        /// The atom style of the header.
        style: String,
    },
    /// Bonds, angles, dihedrals or impropers counted in the header.
    #[error("{file}: molecular topology (bonds, angles, ...): not supported")]
    Molecular {
        /// The file.
        file: String,
    },
    /// A header without the version string.
    #[error("{file}: no version in the header: not a LIGGGHTS restart file")]
    NoVersion {
        /// The file.
        file: String,
    },
    /// More group slots than LIGGGHTS's 32.
    #[error("{file}: more group slots than LIGGGHTS has")]
    TooManyGroups {
        /// The file.
        file: String,
    },
    /// A type-array flag other than masses.
    #[error("{file}: byte {offset}: invalid flag {flag} in the type arrays")]
    TypeArrayFlag {
        /// The file.
        file: String,
        /// Byte offset of the flag.
        offset: usize,
        /// The flag.
        flag: i32,
    },
    /// A pair style other than `gran`.
    #[error("{file}: pair style {style}: not supported (regolith reads pair_style gran)")]
    PairStyle {
        /// The file.
        file: String,
        /// The pair style.
        style: String,
    },
    /// So many atom types that the pair settings' size overflows.
    #[error("{file}: {ntypes} atom types: pair settings of impossible size")]
    PairSize {
        /// The file.
        file: String,
        /// The atom-type count of the header.
        ntypes: usize,
    },
    /// A bond, angle, dihedral or improper style.
    #[error(
        "{file}: byte {offset}: bond/angle/dihedral/improper style (flag {flag}): not supported"
    )]
    TopologyStyle {
        /// The file.
        file: String,
        /// Byte offset of the flag.
        offset: usize,
        /// The flag.
        flag: i32,
    },
    /// Bytes after the last atom chunk.
    #[error("{file}: {count} bytes after the last atom chunk")]
    Trailing {
        /// The file.
        file: String,
        /// How many bytes follow.
        count: usize,
    },
    /// The header's atom count disagrees with the records.
    #[error("{file}: the header counts {header} atoms but the file holds {found}")]
    AtomCount {
        /// The file.
        file: String,
        /// The header's count (-1 without one).
        header: i64,
        /// The records read.
        found: usize,
    },
    /// Values the file holds that no simulation can start from (a box that is not one, ...).
    #[error("{path}: {reason}")]
    Values {
        /// The file.
        path: String,
        /// What is wrong.
        reason: crate::io::restart_values::RestartValueError,
    },
}

impl RestartError {
    /// Whether the file is valid LIGGGHTS that regolith does not read yet.
    pub fn is_unsupported(&self) -> bool {
        matches!(self, RestartError::Triclinic { .. })
    }
}
