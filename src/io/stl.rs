//! STL triangle meshes for `fix mesh/surface`: ASCII files are parsed here in double
//! precision (LIGGGHTS reads ASCII coordinates as doubles; the `stl_io` crate stores f32),
//! binary files through `stl_io`. Loaded meshes are checked for what breaks a DEM wall:
//! degenerate triangles, edges shared by more than two triangles, and sizes that suggest
//! the wrong length unit. Errors name the file and the triangle (1-based).

use crate::io::error::Line;
pub use crate::io::error::StlError;

/// A triangle: three vertices (length).
pub type Triangle = [[f64; 3]; 3];

/// One transformation of `fix mesh/surface`, applied in the order given.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshOp {
    /// `scale f`: multiply every coordinate.
    Scale(f64),
    /// `move dx dy dz` (length).
    Move([f64; 3]),
    /// `rotate axis ax ay az angle deg`: about the axis through the origin.
    Rotate {
        /// The axis (any length).
        axis: [f64; 3],
        /// The angle (degrees).
        degrees: f64,
    },
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// The unit normal of a triangle (right-hand rule over its vertex order), computed as
/// LIGGGHTS does: the cross product of the first two unit edge vectors, normalised.
pub fn normal(t: &Triangle) -> [f64; 3] {
    let unit = |a: [f64; 3]| {
        let l = norm(a);
        a.map(|c| c / l)
    };
    let n = cross(unit(sub(t[1], t[0])), unit(sub(t[2], t[1])));
    let l = norm(n);
    if l > 0.0 {
        [n[0] / l, n[1] / l, n[2] / l]
    } else {
        [0.0; 3]
    }
}

/// Parse an ASCII STL text; `name` labels errors. Also returns each triangle's ID as
/// LIGGGHTS numbers them for `element_exclusion_list`: the line of its `facet` keyword.
fn parse_ascii(text: &str, name: &str) -> Result<(Vec<Triangle>, Vec<usize>), StlError> {
    let mut out = Vec::new();
    let mut ids = Vec::new();
    let mut facet_line = 0;
    let mut current: Vec<[f64; 3]> = Vec::new();
    for (n, line) in text.lines().enumerate() {
        // LIGGGHTS strips `#` comments from STL lines as from deck lines
        let line = line.split('#').next().unwrap_or("");
        let mut w = line.split_whitespace();
        let at = || Line {
            path: name.to_string(),
            line: n + 1,
        };
        match w.next() {
            Some("facet") => facet_line = n + 1,
            Some("vertex") => {
                let mut v = [0.0; 3];
                for c in v.iter_mut() {
                    let word = w.next().ok_or_else(|| StlError::ShortVertex { at: at() })?;
                    *c = word.parse().map_err(|_| StlError::Coordinate {
                        at: at(),
                        word: word.to_string(),
                    })?;
                }
                current.push(v);
            }
            Some("endloop") => {
                if current.len() != 3 {
                    return Err(StlError::NotTriangle {
                        at: at(),
                        facet: out.len() + 1,
                        vertices: current.len(),
                    });
                }
                out.push([current[0], current[1], current[2]]);
                ids.push(facet_line);
                current.clear();
            }
            _ => {}
        }
    }
    if !current.is_empty() {
        return Err(StlError::EndsInFacet {
            path: name.to_string(),
            facet: out.len() + 1,
        });
    }
    Ok((out, ids))
}

/// Read an STL file (ASCII or binary).
pub fn read(path: &str) -> Result<Vec<Triangle>, StlError> {
    read_with_ids(path).map(|(t, _, _)| t)
}

/// Read an STL file with each triangle's ID as LIGGGHTS numbers them (ASCII: the line of
/// its `facet` keyword; binary: its position from 1) and whether the file was ASCII.
pub fn read_with_ids(path: &str) -> Result<(Vec<Triangle>, Vec<usize>, bool), StlError> {
    let file = || path.to_string();
    let bytes = std::fs::read(path).map_err(|source| StlError::Open {
        path: file(),
        source,
    })?;
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(512)]).to_string();
    // LIGGGHTS reads a file as binary only when its first line is not blank, not a `#`
    // comment and does not start with `solid`
    let first = head.lines().next().unwrap_or("");
    let commented = first.split('#').next().unwrap_or("").trim().is_empty() && !bytes.is_empty();
    let significant: String = head
        .lines()
        .map(|l| l.split('#').next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    let ascii = (commented && head.lines().count() > 1 && std::str::from_utf8(&bytes).is_ok())
        || (significant.trim_start().starts_with("solid") && head.contains("facet"));
    let (triangles, ids) = if ascii {
        let text = String::from_utf8(bytes).map_err(|_| StlError::NotText { path: file() })?;
        parse_ascii(&text, path)?
    } else {
        if bytes.len() < 84 {
            return Err(StlError::TooShort {
                path: file(),
                size: bytes.len(),
            });
        }
        let n = u32::from_le_bytes(bytes[80..84].try_into().expect("4 bytes")) as usize;
        if bytes.len() != 84 + 50 * n {
            return Err(StlError::BinarySize {
                path: file(),
                triangles: n,
                expected: 84 + 50 * n,
                size: bytes.len(),
            });
        }
        let mut cursor = std::io::Cursor::new(bytes);
        let mesh = stl_io::read_stl(&mut cursor).map_err(|source| StlError::Binary {
            path: file(),
            source,
        })?;
        let t: Vec<Triangle> = mesh
            .faces
            .iter()
            .map(|f| f.vertices.map(|k| mesh.vertices[k].0.map(|c| c as f64)))
            .collect();
        let ids = (1..=t.len()).collect();
        (t, ids)
    };
    if triangles.is_empty() {
        return Err(StlError::Empty { path: file() });
    }
    Ok((triangles, ids, ascii))
}

/// The triangles `fix mesh/surface ... element_exclusion_list read` keeps: LIGGGHTS walks the
/// sorted list along the file, skipping a triangle whose ID is the entry it points at and
/// only then moving on (in ASCII files also past repeated entries), so an entry no triangle
/// has stops the walk there.
pub fn exclude(
    triangles: Vec<Triangle>,
    ids: &[usize],
    list: &[i64],
    ascii: bool,
) -> Vec<Triangle> {
    let mut i = 0;
    let mut kept = Vec::with_capacity(triangles.len());
    for (t, &id) in triangles.into_iter().zip(ids) {
        if !list.is_empty() && id as i64 == list[i] {
            if i + 1 < list.len() {
                i += 1;
                while ascii && list[i - 1] == list[i] && i + 1 < list.len() {
                    i += 1;
                }
            }
        } else {
            kept.push(t);
        }
    }
    kept
}

/// Apply the transformations in order.
pub fn transform(triangles: &mut [Triangle], ops: &[MeshOp]) {
    for op in ops {
        for t in triangles.iter_mut() {
            for v in t.iter_mut() {
                *v = match op {
                    MeshOp::Scale(f) => v.map(|c| c * f),
                    MeshOp::Move(d) => [v[0] + d[0], v[1] + d[1], v[2] + d[2]],
                    MeshOp::Rotate { axis, degrees } => rotate(*v, *axis, *degrees),
                };
            }
        }
    }
}

/// Hamilton product of two quaternions (w, x, y, z), in LAMMPS's term order.
fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + b[0] * a[1] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] + b[0] * a[2] + a[3] * b[1] - a[1] * b[3],
        a[0] * b[3] + b[0] * a[3] + a[1] * b[2] - a[2] * b[1],
    ]
}

/// Rotation of `v` about `axis` (through the origin) by `degrees`, as LIGGGHTS rotates
/// meshes: the angle converted with pi = 3.14159265, then q v q* with the unit axis.
fn rotate(v: [f64; 3], axis: [f64; 3], degrees: f64) -> [f64; 3] {
    // LIGGGHTS's own truncated pi: the rotated nodes must match its bit for bit.
    #[allow(clippy::approx_constant)]
    const LIGGGHTS_PI: f64 = 3.14159265;
    let angle = degrees * LIGGGHTS_PI / 180.0;
    let l = norm(axis);
    let n = axis.map(|c| c / l);
    let (s, c) = ((angle * 0.5).sin(), (angle * 0.5).cos());
    let q = [c, n[0] * s, n[1] * s, n[2] * s];
    let conj = [q[0], -q[1], -q[2], -q[3]];
    let r = quat_mul(quat_mul(q, [0.0, v[0], v[1], v[2]]), conj);
    [r[1], r[2], r[3]]
}

/// Check a mesh for degenerate triangles and a size that suggests the wrong unit next to a
/// box of size `box_size` (length); returns warnings (edges shared by more than two
/// triangles, which LIGGGHTS imports).
pub fn check(
    triangles: &[Triangle],
    name: &str,
    box_size: Option<f64>,
) -> Result<Vec<String>, StlError> {
    let mut warnings = Vec::new();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for (k, t) in triangles.iter().enumerate() {
        let longest = (0..3)
            .map(|e| norm(sub(t[(e + 1) % 3], t[e])))
            .fold(0.0, f64::max);
        let area = 0.5 * norm(cross(sub(t[1], t[0]), sub(t[2], t[0])));
        // a NaN area is degenerate too
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(area > 1e-10 * longest * longest) {
            return Err(StlError::Degenerate {
                path: name.to_string(),
                triangle: k + 1,
                area,
                longest,
                vertices: *t,
            });
        }
        for v in t {
            for d in 0..3 {
                lo[d] = lo[d].min(v[d]);
                hi[d] = hi[d].max(v[d]);
            }
        }
    }
    // edges by exact vertex coordinates (as written in the file)
    let key = |v: [f64; 3]| v.map(f64::to_bits);
    let mut edges: std::collections::HashMap<([u64; 3], [u64; 3]), Vec<usize>> =
        std::collections::HashMap::new();
    for (k, t) in triangles.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (key(t[e]), key(t[(e + 1) % 3]));
            let edge = if a <= b { (a, b) } else { (b, a) };
            edges.entry(edge).or_default().push(k);
        }
    }
    if let Some((_, faces)) = edges
        .iter()
        .filter(|(_, f)| f.len() > 2)
        .min_by_key(|(_, f)| f[0])
    {
        let count = edges.values().filter(|f| f.len() > 2).count();
        warnings.push(format!(
            "{name}: non-manifold mesh: triangles {} share one edge ({count} such edge(s) in all); \
             LIGGGHTS imports it and so does regolith",
            faces.iter().map(|f| (f + 1).to_string()).collect::<Vec<_>>().join(", ")
        ));
    }
    if let Some(size) = box_size.filter(|s| *s > 0.0) {
        let extent = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
        if extent > 100.0 * size {
            return Err(StlError::WrongUnit {
                path: name.to_string(),
                extent,
                size,
            });
        }
    }
    Ok(warnings)
}

/// The ASCII STL LIGGGHTS's `dump mesh/stl` writes (`%g` numbers), with the given normals.
pub fn write_ascii(triangles: &[Triangle], normals: &[[f64; 3]]) -> String {
    use crate::util::format::g;
    let mut s = String::from("solid LIGGGHTS_STL_EXPORT\n");
    for (t, n) in triangles.iter().zip(normals) {
        s.push_str(&format!(
            "  facet normal {} {} {}\n    outer loop\n",
            g(n[0]),
            g(n[1]),
            g(n[2])
        ));
        for v in t {
            s.push_str(&format!(
                "      vertex {} {} {}\n",
                g(v[0]),
                g(v[1]),
                g(v[2])
            ));
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    s.push_str("endsolid LIGGGHTS_STL_EXPORT\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    const SQUARE: &str = "solid s\nfacet normal 0 0 -1\n outer loop\n  vertex 0.25 -0.005 -0.02\n  vertex 0.25 -0.045 -0.02\n  vertex 0.21 -0.005 -0.02\n endloop\nendfacet\nfacet normal 0 0 -1\n outer loop\n  vertex 0.25 -0.045 -0.02\n  vertex 0.21 -0.045 -0.02\n  vertex 0.21 -0.005 -0.02\n endloop\nendfacet\nendsolid s\n";

    #[test]
    fn ascii_in_double_precision_and_transforms_in_order() {
        let mut t = parse_ascii(SQUARE, "sq.stl").unwrap().0;
        assert_eq!(t.len(), 2);
        assert_eq!(t[0][2], [0.21, -0.005, -0.02]);
        check(&t, "sq.stl", Some(1.0)).unwrap();
        transform(
            &mut t,
            &[
                MeshOp::Scale(2.0),
                MeshOp::Move([1.0, 0.0, 0.0]),
                MeshOp::Rotate {
                    axis: [0.0, 0.0, 1.0],
                    degrees: 90.0,
                },
            ],
        );
        // (0.21, -0.005) -> (0.42, -0.01) -> (1.42, -0.01) -> (0.01, 1.42)
        let v = t[0][2];
        assert!(
            (v[0] - 0.01).abs() < 1e-8 && (v[1] - 1.42).abs() < 1e-8 && (v[2] + 0.04).abs() < 1e-12,
            "{v:?}"
        );
        assert_eq!(normal(&t[0]), normal(&t[1]));
    }

    #[test]
    fn ascii_after_comment_lines_is_not_binary() {
        let dir = std::env::temp_dir().join(format!("regolith-stl-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("commented.stl");
        std::fs::write(
            &path,
            format!("# exported by a CAD tool\n# units: m\n{SQUARE}"),
        )
        .unwrap();
        let t = read(path.to_str().unwrap()).unwrap();
        assert_eq!(t, parse_ascii(SQUARE, "sq.stl").unwrap().0);
        let _ = std::fs::remove_dir_all(&dir);
    }

    #[test]
    fn broken_meshes_are_named() {
        let flat = SQUARE.replace(
            "vertex 0.21 -0.005 -0.02\n endloop\nendfacet\nfacet",
            "vertex 0.25 -0.025 -0.02\n endloop\nendfacet\nfacet",
        );
        let t = parse_ascii(&flat, "flat.stl").unwrap().0;
        let e = check(&t, "flat.stl", None).unwrap_err();
        assert!(
            matches!(e, StlError::Degenerate { triangle: 1, .. }),
            "{e:?}"
        );
        let e = e.to_string();
        assert!(e.starts_with("flat.stl: triangle 1 is degenerate"), "{e}");
        let t = parse_ascii(SQUARE, "sq.stl").unwrap().0;
        let mut three = t.clone();
        three.push([t[0][1], t[0][2], [0.3, 0.3, 0.3]]); // the shared edge again
                                                         // LIGGGHTS imports a non-manifold mesh: a warning, not an error
        let w = check(&three, "nm.stl", None).unwrap();
        assert!(w[0].contains("triangles 1, 2, 3 share one edge"), "{w:?}");
        let e = check(&t, "mm.stl", Some(0.0001)).unwrap_err();
        assert!(matches!(e, StlError::WrongUnit { .. }), "{e:?}");
        assert!(e.to_string().contains("wrong length unit"), "{e}");
        let e = parse_ascii(
            "solid x\nfacet\nouter loop\nvertex 0 0 0\nvertex 1 0\n",
            "cut.stl",
        )
        .unwrap_err();
        assert!(
            matches!(&e, StlError::ShortVertex { at } if at.line == 5),
            "{e:?}"
        );
        assert!(
            e.to_string()
                .starts_with("cut.stl:5: a vertex needs three coordinates"),
            "{e}"
        );
    }
}
