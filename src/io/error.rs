//! Why a file regolith reads or writes (an STL mesh, a data file, a dump read back, a dump's
//! columns, a conversion) cannot be used, as data: the file, the line and what was expected
//! or found. `Display` gives the message regolith prints. Restart files have their own
//! [`crate::io::restart_error::RestartError`].

use thiserror::Error;

/// `path:line` of a text file (1-based line).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Line {
    /// The file as named.
    pub path: String,
    /// 1-based line number.
    pub line: usize,
}

impl std::fmt::Display for Line {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.path, self.line)
    }
}

/// An STL mesh that cannot be read or used as a wall.
#[derive(Debug, Error)]
pub enum StlError {
    /// The file cannot be opened or read.
    #[error("Cannot open mesh file {path}: {source}")]
    Open {
        /// The file as named.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// A `vertex` line with fewer than three numbers.
    #[error("{at}: a vertex needs three coordinates")]
    ShortVertex {
        /// Where.
        at: Line,
    },
    /// A coordinate that is not a number.
    #[error("{at}: '{word}' is not a coordinate")]
    Coordinate {
        /// Where.
        at: Line,
        /// The word found.
        word: String,
    },
    /// A facet with other than three vertices.
    #[error("{at}: facet {facet} has {vertices} vertices (STL facets are triangles)")]
    NotTriangle {
        /// Where its `endloop` is.
        at: Line,
        /// The facet (1-based).
        facet: usize,
        /// Its vertex count.
        vertices: usize,
    },
    /// The text ends between `outer loop` and `endloop`.
    #[error("{path}: the file ends inside facet {facet}")]
    EndsInFacet {
        /// The file.
        path: String,
        /// The facet (1-based).
        facet: usize,
    },
    /// An ASCII file with bytes that are not UTF-8.
    #[error("{path}: an ASCII STL file with bytes that are not text")]
    NotText {
        /// The file.
        path: String,
    },
    /// Too short for a binary STL header.
    #[error("{path}: neither ASCII STL nor a binary STL (only {size} bytes)")]
    TooShort {
        /// The file.
        path: String,
        /// Its length (bytes).
        size: usize,
    },
    /// A binary STL whose length disagrees with its triangle count.
    #[error("{path}: binary STL header counts {triangles} triangles ({expected} bytes) but the file has {size} bytes")]
    BinarySize {
        /// The file.
        path: String,
        /// The header's triangle count.
        triangles: usize,
        /// The length that count implies (bytes).
        expected: usize,
        /// The file's length (bytes).
        size: usize,
    },
    /// The binary STL reader refused the file.
    #[error("{path}: {source}")]
    Binary {
        /// The file.
        path: String,
        /// What the reader said.
        source: std::io::Error,
    },
    /// No triangles at all.
    #[error("{path}: the mesh has no triangles")]
    Empty {
        /// The file.
        path: String,
    },
    /// A triangle of (nearly) zero area.
    #[error("{path}: triangle {triangle} is degenerate (area {area:e} for an edge of {longest:e}): vertices {vertices:?}")]
    Degenerate {
        /// The file.
        path: String,
        /// The triangle (1-based).
        triangle: usize,
        /// Its area (length^2).
        area: f64,
        /// Its longest edge (length).
        longest: f64,
        /// Its vertices (length).
        vertices: crate::io::stl::Triangle,
    },
    /// A mesh far larger than the box: probably millimetres in a metre deck.
    #[error("{path}: the mesh is {extent:e} across but the box only {size:e}: wrong length unit? (use scale, e.g. scale 0.001 for millimetres)")]
    WrongUnit {
        /// The file.
        path: String,
        /// The mesh's largest extent (length).
        extent: f64,
        /// The box's size (length).
        size: f64,
    },
}

/// A data file (`read_data`, `regolith convert`) that cannot be read.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DataError {
    /// A word that is not of the expected form.
    #[error("{at}: expected {what}, found '{found}'")]
    Expected {
        /// Where.
        at: Line,
        /// What was expected (`an atom count`, `a diameter`, ...).
        what: &'static str,
        /// The word found.
        found: String,
    },
    /// A number that is `nan`, `inf` or beyond a double.
    #[error("{at}: expected {what}, found '{found}' (not a finite number)")]
    NotFinite {
        /// Where.
        at: Line,
        /// What was expected.
        what: &'static str,
        /// The word found.
        found: String,
    },
    /// A triclinic box (valid LIGGGHTS, not run by regolith yet).
    #[error("{at}: triclinic boxes are not supported yet")]
    Triclinic {
        /// Where.
        at: Line,
    },
    /// Bonds, angles and the like, which atom_style granular has not.
    #[error("{at}: '{text}': molecular data is not supported by atom_style granular")]
    Molecular {
        /// Where.
        at: Line,
        /// The header line.
        text: String,
    },
    /// A header line that is missing (`N atoms`, `N atom types`, `xlo xhi`, ...).
    #[error("{path}: no '{line}' line in the header")]
    MissingHeader {
        /// The file.
        path: String,
        /// The line's form.
        line: &'static str,
    },
    /// Bounds that make no box.
    #[error("{path}: box bounds {lo} {hi} are not a box")]
    NotABox {
        /// The file.
        path: String,
        /// Lower bound (length).
        lo: f64,
        /// Upper bound (length).
        hi: f64,
    },
    /// A section with fewer lines than atoms.
    #[error("{path}: {section} section ends after {read} of {atoms} atoms")]
    SectionEnds {
        /// The file.
        path: String,
        /// `Atoms` or `Velocities`.
        section: &'static str,
        /// Lines read.
        read: usize,
        /// Atoms the header counts.
        atoms: usize,
    },
    /// An `Atoms` line of the wrong length.
    #[error("{at}: expected 'id type diameter density x y z [ix iy iz]' (7 or 10 values), found {found}")]
    AtomColumns {
        /// Where.
        at: Line,
        /// Values found.
        found: usize,
    },
    /// A `Velocities` line of the wrong length.
    #[error("{at}: expected 'id vx vy vz omegax omegay omegaz', found {found} values")]
    VelocityColumns {
        /// Where.
        at: Line,
        /// Values found.
        found: usize,
    },
    /// An atom type outside 1..ntypes.
    #[error("{at}: atom type {kind} outside 1..{ntypes}")]
    TypeRange {
        /// Where.
        at: Line,
        /// The type found.
        kind: u32,
        /// The header's type count.
        ntypes: u32,
    },
    /// A negative diameter or a density that is not positive.
    #[error("{at}: diameter must be >= 0 and density > 0")]
    BadSize {
        /// Where.
        at: Line,
    },
    /// A sphere no simulation can hold (the engine's reason).
    #[error("{at}: atom {id}: {reason}")]
    Sphere {
        /// Where.
        at: Line,
        /// The atom's ID.
        id: i64,
        /// Which value is out of range and what is allowed.
        reason: crate::state::limits::LimitError,
    },
    /// An atom ID given twice.
    #[error("{at}: atom ID {id} appears twice")]
    DuplicateId {
        /// Where.
        at: Line,
        /// The atom ID.
        id: i64,
    },
    /// A velocity of an atom the Atoms section has not (yet).
    #[error("{at}: velocity of atom {id}, which the Atoms section lacks (Atoms must come first)")]
    VelocityWithoutAtom {
        /// Where.
        at: Line,
        /// The atom ID.
        id: i64,
    },
    /// A section other than Atoms and Velocities.
    #[error("{at}: section '{section}' is not supported yet (granular data files have Atoms and Velocities)")]
    UnsupportedSection {
        /// Where.
        at: Line,
        /// The section's name.
        section: String,
    },
    /// Atoms counted in the header but no Atoms section.
    #[error("{path}: the header promises {atoms} atoms but there is no Atoms section")]
    NoAtoms {
        /// The file.
        path: String,
        /// Atoms the header counts.
        atoms: usize,
    },
}

impl DataError {
    /// Whether the file is valid LIGGGHTS that regolith does not read yet.
    pub fn is_unsupported(&self) -> bool {
        matches!(
            self,
            DataError::Triclinic { .. } | DataError::UnsupportedSection { .. }
        )
    }
}

/// A text file that cannot be read (`regolith diff`, `analyze`, gzip data files).
#[derive(Debug, Error)]
pub enum TextError {
    /// The file cannot be opened or read.
    #[error("{path}: {source}")]
    Open {
        /// The file as named.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// A `.gz` file whose data does not decompress.
    #[error("{path}: corrupted gzip data ({source})")]
    Gzip {
        /// The file.
        path: String,
        /// What the decompressor said.
        source: std::io::Error,
    },
    /// Neither UTF-8 text nor gzip.
    #[error("{path}: not a text file (nor gzip)")]
    NotText {
        /// The file.
        path: String,
    },
}

/// A `dump custom` column list or `dump_modify format` refused.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ColumnError {
    /// A column keyword `dump custom` does not have.
    #[error("Invalid attribute {0} in dump custom command")]
    Attribute(String),
    /// A format element that is not a C conversion.
    #[error(transparent)]
    Format(#[from] crate::util::format::FormatError),
    /// A format element without a conversion.
    /// A format element with more than a conversion.
    #[error("format element '{0}' has more than one conversion")]
    NotSingle(String),
    /// Fewer conversions than columns.
    #[error("Dump_modify format string is too short")]
    TooShort,
}

/// A text dump or VTK particle file read back (`regolith diff`, `convert`, `analyze`) that
/// cannot be parsed.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum DumpReadError {
    /// A dump that stops inside a snapshot.
    #[error("dump ends early: expected {expected}")]
    DumpEnds {
        /// What should come next.
        expected: &'static str,
    },
    /// A VTK file that stops inside a section.
    #[error("file ends early: expected {expected}")]
    FileEnds {
        /// What should come next.
        expected: &'static str,
    },
    /// A VTK file that stops inside a block it skips.
    #[error("file ends early")]
    FileEndsInBlock,
    /// A line or word not of the expected form.
    #[error("line {line}: expected {expected}, found '{found}'")]
    Expected {
        /// 1-based line.
        line: usize,
        /// What was expected.
        expected: &'static str,
        /// What was found.
        found: String,
    },
    /// A value that does not read as what it should be.
    #[error("line {line}: bad {what} '{found}'")]
    Bad {
        /// 1-based line.
        line: usize,
        /// `timestep`, `atom count` or `box bounds`.
        what: &'static str,
        /// The line.
        found: String,
    },
    /// The `ITEM: ATOMS` (or `ITEM: ENTRIES`) line is missing.
    #[error("line {line}: expected '{item}'")]
    MissingItem {
        /// 1-based line.
        line: usize,
        /// The item line expected.
        item: &'static str,
    },
    /// A per-atom dump without an `id` column.
    #[error("dump has no id column")]
    NoIdColumn,
    /// A row with a word that is not a number.
    #[error("line {line}: non-numeric value in '{text}'")]
    NonNumeric {
        /// 1-based line.
        line: usize,
        /// The row.
        text: String,
    },
    /// A row with another value count than columns.
    #[error("line {line}: {values} values for {columns} columns")]
    RowLength {
        /// 1-based line.
        line: usize,
        /// Values in the row.
        values: usize,
        /// Columns of the snapshot.
        columns: usize,
    },
    /// A key column for ordering `dump local` entries that the snapshot lacks.
    #[error("step {step}: no key column {column}")]
    NoKeyColumn {
        /// The snapshot's step.
        step: i64,
        /// The column.
        column: String,
    },
    /// A binary VTK file.
    #[error("line {line}: binary VTK files are not supported")]
    BinaryVtk {
        /// 1-based line.
        line: usize,
    },
    /// POINT_DATA counting other points than POINTS.
    #[error("line {line}: POINT_DATA {count} does not match POINTS")]
    PointData {
        /// 1-based line.
        line: usize,
        /// The POINT_DATA count.
        count: usize,
    },
    /// A VTK keyword regolith does not read.
    #[error("line {line}: unexpected '{word}'")]
    Unexpected {
        /// 1-based line.
        line: usize,
        /// The word.
        word: String,
    },
    /// A VTK file without an `id` array.
    #[error("VTK file has no id array")]
    NoIdArray,
    /// A VTK file without POINTS.
    #[error("VTK file has no POINTS")]
    NoPoints,
}

/// `regolith diff` (and the readers it shares with `analyze`) refusing its input.
#[derive(Debug, Error)]
pub enum DiffError {
    /// A `--scale` word other than `max` and `rms`.
    #[error("--scale {0}: expected max (the column's largest magnitude in A) or rms (its root mean square in A)")]
    Scale(String),
    /// A `--steps` part that is not `N` or `A:B`.
    #[error("--steps: expected N, A:B or a comma list of them, got '{0}'")]
    Steps(String),
    /// The folder of a `*` name cannot be listed.
    #[error("{pattern}: {source}")]
    Folder {
        /// The name with `*`.
        pattern: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// No file matches a `*` name.
    #[error("{0}: no file matches")]
    NoMatch(String),
    /// A file that cannot be read as text.
    #[error(transparent)]
    Text(#[from] TextError),
    /// A dump or VTK file that does not parse.
    #[error("{file}: {source}")]
    Parse {
        /// The file.
        file: String,
        /// What is wrong in it.
        source: DumpReadError,
    },
    /// A `*` series of logs.
    #[error("{0}: a `*` series must be dumps")]
    SeriesOfLogs(String),
    /// Neither dump, VTK nor log.
    #[error("{0}: neither a text dump (no 'ITEM: TIMESTEP'), a legacy VTK file, nor a log with thermo output (no 'Step' header)")]
    Unknown(String),
    /// A dump compared with a log.
    #[error("{a} and {b}: one is a dump, the other a log")]
    Mixed {
        /// The first file.
        a: String,
        /// The second file.
        b: String,
    },
    /// `dump local` entries that cannot be ordered by the key columns.
    #[error(transparent)]
    Key(#[from] DumpReadError),
}

/// `regolith convert` refusing its input or failing to write.
#[derive(Debug, Error)]
pub enum ConvertError {
    /// A `--from`/`--to` word that names no format.
    #[error("unknown format '{0}': expected restart, data, dump or vtk")]
    UnknownFormat(String),
    /// A file name that implies no format, without `--from`/`--to`.
    #[error("{name}: cannot tell the {which} format from the name; give --{which} restart|data|dump|vtk")]
    FormatOfName {
        /// The file.
        name: String,
        /// `from` or `to`.
        which: &'static str,
    },
    /// A `--boundary` that is not three boundary styles.
    #[error("--boundary: {0}")]
    Boundary(crate::state::domain::BoxError),
    /// A restart file that cannot be read or written.
    #[error(transparent)]
    Restart(#[from] crate::io::restart_error::RestartError),
    /// A data file that cannot be read.
    #[error(transparent)]
    Data(#[from] DataError),
    /// A file that cannot be read as text.
    #[error(transparent)]
    Text(#[from] TextError),
    /// The dump layout of a bed.
    #[error(transparent)]
    Column(#[from] ColumnError),
    /// A text dump that does not parse.
    #[error("{input}: {source}")]
    Dump {
        /// The dump.
        input: String,
        /// What is wrong in it.
        source: DumpReadError,
    },
    /// Output that cannot be written.
    #[error("{path}: {source}")]
    Write {
        /// The file.
        path: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// Output that cannot be formatted or compressed.
    #[error("{0}")]
    Encode(std::io::Error),
    /// A dump without snapshots.
    #[error("{0}: not a text dump: no snapshot (no 'ITEM: TIMESTEP'); nothing was written")]
    NoSnapshot(String),
    /// Several snapshots into one output name.
    #[error(
        "{input} holds {snapshots} snapshots: put a * in the output name ({output}) for the step"
    )]
    NeedStar {
        /// The dump.
        input: String,
        /// Its snapshot count.
        snapshots: usize,
        /// The output name.
        output: String,
    },
    /// A dump snapshot without positions.
    #[error("{input}: step {step}: VTK needs x y z columns (found {columns})")]
    NoPositions {
        /// The dump.
        input: String,
        /// The snapshot's step.
        step: i64,
        /// Its columns, blank-separated.
        columns: String,
    },
    /// A dump into anything but VTK.
    #[error("{0}: a dump converts only to VTK (a dump lacks what restart and data files need)")]
    DumpOnlyToVtk(String),
    /// VTK as input.
    #[error("{0}: VTK files are output only")]
    VtkInput(String),
}

/// The words of a `dump mesh/vtk` (or `mesh/gran/VTK`) command refused.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum MeshDumpError {
    /// `output` as the last word.
    #[error(
        "Dump mesh/vtk: not enough arguments for 'output' (expected face, interpolate or original)"
    )]
    OutputMissing,
    /// `output` followed by another word.
    #[error(
        "Dump mesh/vtk: wrong argument '{0}' for 'output' (expected face, interpolate or original)"
    )]
    OutputMode(String),
    /// A word that is no mesh, keyword or property.
    #[error("Illegal dump mesh/vtk command, unknown keyword or mesh '{word}': expected a mesh/surface fix ID, 'output face|interpolate|original', one of the keywords {} or the name of a per-triangle mesh property", crate::io::mesh_vtk::keyword_list())]
    UnknownWord {
        /// The word.
        word: String,
    },
    /// Nothing to write.
    #[error(
        "Dump mesh/vtk: No dump quantity selected (keywords: {})",
        crate::io::mesh_vtk::keyword_list()
    )]
    NoQuantity,
}
