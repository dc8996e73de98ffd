//! `region ID mesh/tet file F scale S move DX DY DZ rotate AX AY AZ`: a region made of the
//! tetrahedra of a legacy ASCII VTK unstructured grid, read as LIGGGHTS reads it (each point
//! moved, then scaled, then rotated; only cells of type 10 kept) and tested as LIGGGHTS tests
//! it (a point is inside when it lies strictly inside one of the tetrahedra).

/// The tetrahedra of a `mesh/tet` region (lengths in box units).
#[derive(Debug, Clone, PartialEq)]
pub struct TetMesh {
    /// The four nodes of each tetrahedron, ordered to give a positive volume (length).
    pub tets: Vec<[[f64; 3]; 4]>,
    /// Lowest node coordinates (length).
    pub lo: [f64; 3],
    /// Highest node coordinates (length).
    pub hi: [f64; 3],
}

/// What reading a mesh file reports besides the mesh: LIGGGHTS's notes and warnings.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadNotes {
    /// Blank lines skipped (one note each).
    pub empty_lines: usize,
    /// Cells other than tetrahedra were dropped.
    pub other_cells: bool,
}

/// Six times the signed volume of the tetrahedron (v0, v1, v2, v3), divided by six as
/// LIGGGHTS computes it (length^3).
fn volume(v0: [f64; 3], v1: [f64; 3], v2: [f64; 3], v3: [f64; 3]) -> f64 {
    let a = [v3[0] - v1[0], v3[1] - v1[1], v3[2] - v1[2]];
    let b = [v2[0] - v1[0], v2[1] - v1[1], v2[2] - v1[2]];
    let c = [v0[0] - v1[0], v0[1] - v1[1], v0[2] - v1[2]];
    let cp = [
        a[1] * b[2] - a[2] * b[1],
        -a[0] * b[2] + a[2] * b[0],
        a[0] * b[1] - a[1] * b[0],
    ];
    (cp[0] * c[0] + cp[1] * c[1] + cp[2] * c[2]) / 6.0
}

/// The signed volume of the tetrahedron (v0, v1, v2, v3) as LIGGGHTS computes it (length^3).
pub fn signed_volume(v0: [f64; 3], v1: [f64; 3], v2: [f64; 3], v3: [f64; 3]) -> f64 {
    volume(v0, v1, v2, v3)
}

/// Where the mesh goes: `move` offsets added before `scale`, then `rotate` angles (degrees)
/// about x, y and z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Scale factor.
    pub scale: f64,
    /// Offset added to every point before scaling (length).
    pub offset: [f64; 3],
    /// Rotation angles about x, y, z (degrees).
    pub rotate: [f64; 3],
}

impl Placement {
    fn apply(&self, p: [f64; 3]) -> [f64; 3] {
        let v: [f64; 3] = std::array::from_fn(|j| (p[j] + self.offset[j]) * self.scale);
        let [px, py, pz] = self.rotate.map(|a| a * std::f64::consts::PI / 180.0);
        let (cx, sx, cy, sy, cz, sz) = (px.cos(), px.sin(), py.cos(), py.sin(), pz.cos(), pz.sin());
        [
            v[0] * cy * cz + v[1] * (cz * sx * sy - cx * sz) + v[2] * (cx * cz * sy + sx * sz),
            v[0] * cy * sz + v[2] * (-cz * sx + cx * sy * sz) + v[1] * (cx * cz + sx * sy * sz),
            v[2] * cx * cy + v[1] * cy * sx - v[0] * sy,
        ]
    }
}

/// Why a tetrahedral mesh file cannot be read (LIGGGHTS's messages).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum TetMeshError {
    /// The second line is not `ASCII`.
    #[error("Expecting ASCII VTK mesh file, cannot continue")]
    NotAscii,
    /// The dataset is not an unstructured grid.
    #[error("Expecting ASCII VTK unstructured grid mesh file, cannot continue")]
    NotUnstructuredGrid,
    /// A section (`POINTS`, `CELLS`, `CELL_TYPES`) missing where it belongs.
    #[error("Expecting '{0}' section in ASCII VTK mesh file, cannot continue")]
    Section(&'static str),
    /// A `POINTS` line whose values are not whole points.
    #[error("Expecting 3 values for each point in 'POINTS' section of ASCII VTK mesh file, cannot continue")]
    PointValues,
    /// A cell naming a point the file does not have.
    #[error("VTK mesh file: cell {cell} names point {point} of {points}")]
    CellPoint {
        /// The cell (from 0).
        cell: usize,
        /// The point it names.
        point: i64,
        /// Points in the file.
        points: usize,
    },
    /// `CELL_TYPES` counts other cells than `CELLS`.
    #[error("Inconsistency in 'CELL_TYPES' section in ASCII VTK mesh file, cannot continue")]
    CellTypes,
    /// A placed node outside the simulation box.
    #[error("VTK mesh file is incompatible with simulation box: One or more vertices outside simulation box")]
    OutsideBox,
    /// A tetrahedron with negative volume in both node orders.
    #[error("Fatal error: RegTetMesh::add_tet: vol < 0")]
    NegativeVolume,
    /// No cells at all.
    #[error("VTK mesh file containing no tet cell - cannnot continue")]
    NoCells,
}

/// The words of a line before its comment (a `#` outside quotes; the VTK header line is
/// one).
fn words_of(raw: &str) -> Vec<&str> {
    let mut quote = None;
    let cut = raw
        .char_indices()
        .find(|&(_, c)| {
            match quote {
                Some(q) if c == q => quote = None,
                None if c == '"' || c == '\'' => quote = Some(c),
                None => return c == '#',
                _ => {}
            }
            false
        })
        .map_or(raw.len(), |(k, _)| k);
    raw[..cut].split_whitespace().collect()
}

/// A legacy VTK file read line by line (non-empty lines counted from 1): the header, then
/// the `POINTS`, `CELLS` and `CELL_TYPES` sections in turn.
struct VtkReader<'a> {
    place: &'a Placement,
    inside_box: &'a dyn Fn([f64; 3]) -> bool,
    notes: ReadNotes,
    /// The placed points read so far (length).
    points: Vec<[f64; 3]>,
    /// Points the `POINTS` line announces.
    npoints: usize,
    /// The cells read so far (None: not four nodes, or not a tetrahedron).
    cells: Vec<Option<[usize; 4]>>,
    /// Cells the `CELLS` line announces.
    ncells: usize,
    points_done: bool,
    cells_done: bool,
    last_point_line: usize,
    last_cell_line: usize,
    /// Cell types read so far.
    types_seen: usize,
    /// A placed point lies outside the box.
    outside: bool,
    /// The current line (non-empty lines from 1).
    line_no: usize,
}

impl VtkReader<'_> {
    /// Take one line of the file.
    fn line(&mut self, raw: &str) -> Result<(), TetMeshError> {
        let words = words_of(raw);
        if words.is_empty() {
            self.notes.empty_lines += 1;
            return Ok(());
        }
        self.line_no += 1;
        let line_no = self.line_no;
        if line_no <= 4 {
            return self.header(&words);
        }
        if !self.points_done {
            return self.point_line(&words);
        }
        if line_no == self.last_point_line + 1 {
            if words[0] != "CELLS" {
                return Err(TetMeshError::Section("CELLS"));
            }
            self.ncells = words
                .get(1)
                .map_or(0, |w| crate::util::numbers::c_atoi(w))
                .max(0) as usize;
            if self.ncells == 0 {
                self.cells_done = true;
                self.last_cell_line = line_no;
            }
            return Ok(());
        }
        if !self.cells_done {
            return self.cell_line(&words);
        }
        if line_no == self.last_cell_line + 1 {
            if words[0] != "CELL_TYPES" {
                return Err(TetMeshError::Section("CELL_TYPES"));
            }
            if words.get(1).map_or(0, |w| crate::util::numbers::c_atoi(w)) != self.ncells as i64 {
                return Err(TetMeshError::CellTypes);
            }
            return Ok(());
        }
        if line_no <= self.last_cell_line + 1 + self.ncells && self.types_seen < self.cells.len() {
            if words[0] != "10" {
                self.cells[self.types_seen] = None;
                self.notes.other_cells = true;
            }
            self.types_seen += 1;
        }
        Ok(())
    }

    /// Lines 1 to 4: title, `ASCII`, `DATASET UNSTRUCTURED_GRID`, `POINTS N`.
    fn header(&mut self, words: &[&str]) -> Result<(), TetMeshError> {
        match self.line_no {
            2 if words[0] != "ASCII" => Err(TetMeshError::NotAscii),
            3 if words[0] != "DATASET" || words.get(1) != Some(&"UNSTRUCTURED_GRID") => {
                Err(TetMeshError::NotUnstructuredGrid)
            }
            4 => {
                if words[0] != "POINTS" {
                    return Err(TetMeshError::Section("POINTS"));
                }
                self.npoints = words
                    .get(1)
                    .map_or(0, |w| crate::util::numbers::c_atoi(w))
                    .max(0) as usize;
                if self.npoints == 0 {
                    self.points_done = true;
                    self.last_point_line = self.line_no;
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }

    /// A line of points (whole points only), each placed and tested against the box.
    fn point_line(&mut self, words: &[&str]) -> Result<(), TetMeshError> {
        if !words.len().is_multiple_of(3) {
            return Err(TetMeshError::PointValues);
        }
        for c in words.chunks(3) {
            let mut p = [0.0; 3];
            for (k, w) in c.iter().enumerate() {
                p[k] = crate::util::numbers::numeric(w).unwrap_or(0.0);
            }
            let q = self.place.apply(p);
            if !(self.inside_box)(q) {
                self.outside = true;
            }
            self.points.push(q);
        }
        if self.points.len() >= self.npoints {
            self.points_done = true;
            self.last_point_line = self.line_no;
        }
        Ok(())
    }

    /// A cell line: four nodes (a count and four point indices) make a candidate
    /// tetrahedron.
    fn cell_line(&mut self, words: &[&str]) -> Result<(), TetMeshError> {
        let cell = if words.len() == 5 {
            let mut c = [0usize; 4];
            for k in 0..4 {
                let n = crate::util::numbers::c_atoi(words[1 + k]);
                if n < 0 || n as usize >= self.npoints.min(self.points.len()) {
                    return Err(TetMeshError::CellPoint {
                        cell: self.cells.len(),
                        point: n,
                        points: self.npoints,
                    });
                }
                c[k] = n as usize;
            }
            Some(c)
        } else {
            None
        };
        self.cells.push(cell);
        if self.cells.len() == self.ncells {
            self.cells_done = true;
            self.last_cell_line = self.line_no;
        }
        Ok(())
    }

    /// The mesh from the lines read: the tetrahedra ordered to a positive volume, and
    /// their bounds.
    fn finish(self) -> Result<(TetMesh, ReadNotes), TetMeshError> {
        if self.outside {
            return Err(TetMeshError::OutsideBox);
        }
        // cells whose type was never read count as tetrahedra when they have four nodes
        let points = &self.points;
        let mut tets = Vec::new();
        for c in self.cells.iter().flatten() {
            let mut n = c.map(|k| points[k]);
            if volume(n[0], n[1], n[2], n[3]) < 0.0 {
                n.swap(0, 3);
            }
            if volume(n[0], n[1], n[2], n[3]) < 0.0 {
                return Err(TetMeshError::NegativeVolume);
            }
            tets.push(n);
        }
        if self.ncells == 0 {
            return Err(TetMeshError::NoCells);
        }
        let mut lo = [crate::engine::region::BIG; 3];
        let mut hi = [-crate::engine::region::BIG; 3];
        for t in &tets {
            for n in t {
                for d in 0..3 {
                    lo[d] = lo[d].min(n[d]);
                    hi[d] = hi[d].max(n[d]);
                }
            }
        }
        Ok((TetMesh { tets, lo, hi }, self.notes))
    }
}

/// Read a legacy ASCII VTK unstructured grid. `inside_box` tells whether a placed point lies
/// in the simulation box (LIGGGHTS refuses meshes that stick out).
pub fn read(
    text: &str,
    place: &Placement,
    inside_box: &dyn Fn([f64; 3]) -> bool,
) -> Result<(TetMesh, ReadNotes), TetMeshError> {
    let mut reader = VtkReader {
        place,
        inside_box,
        notes: ReadNotes::default(),
        points: Vec::new(),
        npoints: 0,
        cells: Vec::new(),
        ncells: 0,
        points_done: false,
        cells_done: false,
        last_point_line: 0,
        last_cell_line: 0,
        types_seen: 0,
        outside: false,
        line_no: 0,
    };
    for raw in text.lines() {
        reader.line(raw)?;
    }
    reader.finish()
}

impl TetMesh {
    /// Whether `x` lies strictly inside one of the tetrahedra (within the nodes' bounds).
    pub fn inside(&self, x: [f64; 3]) -> bool {
        if (0..3).any(|d| x[d] < self.lo[d] || x[d] > self.hi[d]) {
            return false;
        }
        self.tets.iter().any(|n| {
            volume(n[0], n[1], n[2], x) > 0.0
                && volume(n[0], n[1], x, n[3]) > 0.0
                && volume(n[0], x, n[2], n[3]) > 0.0
                && volume(x, n[1], n[2], n[3]) > 0.0
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CUBE_CORNER: &str = "# vtk DataFile Version 2.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n\
        POINTS 5 double\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n5 5 5\n\nCELLS 2 8\n4 0 1 3 2\n2 0 4\n\
        CELL_TYPES 2\n10\n3\n";

    fn place() -> Placement {
        Placement {
            scale: 1.0,
            offset: [0.0; 3],
            rotate: [0.0; 3],
        }
    }

    #[test]
    fn reads_tetrahedra_and_tests_points_strictly_inside() {
        let (m, notes) = read(CUBE_CORNER, &place(), &|_| true).unwrap();
        assert_eq!(m.tets.len(), 1);
        // the comment line and the blank line
        assert_eq!(notes.empty_lines, 2);
        assert!(notes.other_cells);
        assert!(m.inside([0.1, 0.1, 0.1]));
        assert!(!m.inside([0.5, 0.5, 0.5]));
        // on a face: not inside (LIGGGHTS's strict test)
        assert!(!m.inside([0.0, 0.2, 0.2]));
    }

    #[test]
    fn moves_then_scales_and_refuses_points_outside_the_box() {
        let p = Placement {
            scale: 2.0,
            offset: [1.0, 0.0, 0.0],
            rotate: [0.0; 3],
        };
        let (m, _) = read(CUBE_CORNER, &p, &|_| true).unwrap();
        assert_eq!(m.lo, [2.0, 0.0, 0.0]);
        assert_eq!(m.hi, [4.0, 2.0, 2.0]);
        let e = read(CUBE_CORNER, &p, &|x| x[0] < 3.0).unwrap_err();
        assert_eq!(e, TetMeshError::OutsideBox);
        assert!(e.to_string().contains("outside simulation box"), "{e}");
        let e = read("x\nBINARY\n", &place(), &|_| true).unwrap_err();
        assert_eq!(e, TetMeshError::NotAscii);
        assert_eq!(
            e.to_string(),
            "Expecting ASCII VTK mesh file, cannot continue"
        );
    }
}
