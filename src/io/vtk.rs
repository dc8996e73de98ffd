//! `dump custom/vtk` in the legacy VTK layout Debian's LIGGGHTS 3.8.0 writes (VTK 5.1,
//! ASCII polydata): positions as `float` points, one vertex per atom, and the other columns
//! as point-data fields in LIGGGHTS's fixed attribute order, x/y/z triples merged into
//! vectors (`v`, `f`, `omega`, ...), three consecutive `c_ID[n]` columns merged into
//! `c_ID[n-m]`, duplicates dropped. Values: `%g` for floats, `%.11g` for doubles, `%d` for
//! integers, nine per line. Each snapshot also gets a `_boundingBox` rectilinear grid file.

use std::io::Write;

use crate::state::domain::Domain;
use crate::util::format::{g, g_precision};

/// One point-data field: its name, whether it is integer, and the dump columns (indices
/// into the dump's column list) that make its components.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// Field name as written (`id`, `v`, `c_s[1-3]`, a variable's name without `v_`).
    pub name: String,
    /// Written as `int` (else `double`).
    pub integer: bool,
    /// Column index per component (1 or 3).
    pub columns: Vec<usize>,
}

/// Position of a built-in attribute in LIGGGHTS's ordering (x, y, z are 0..2; references
/// to computes, fixes and variables come after every built-in, in the order given).
fn rank(name: &str) -> Option<usize> {
    const ORDER: &[&str] = &[
        "x", "y", "z", "", "id", "mol", "type", "element", "mass", "xs", "ys", "zs", "", "", "",
        "xu", "yu", "zu", "", "", "", "xsu", "ysu", "zsu", "", "", "", "ix", "iy", "iz", "vx",
        "vy", "vz", "fx", "fy", "fz", "q", "mux", "muy", "muz", "mu", "radius", "diameter",
        "omegax", "omegay", "omegaz", "angmomx", "angmomy", "angmomz", "tqx", "tqy", "tqz", "spin",
        "eradius", "ervel", "erforce", "density", "rho", "p",
    ];
    ORDER.iter().position(|&o| !o.is_empty() && o == name)
}

/// Ranks at which a built-in x/y/z triple starts.
const VECTOR_STARTS: &[&str] = &[
    "xs", "xu", "xsu", "ix", "vx", "fx", "mux", "omegax", "angmomx", "tqx",
];

/// Rank past every built-in: references are keyed `REFERENCES + position`.
const REFERENCES: usize = 1000;

/// The fields of a dump with the given column keywords, in LIGGGHTS's order.
pub fn fields(names: &[String]) -> Vec<Field> {
    // key -> (name, column); a later duplicate of a built-in replaces nothing
    let mut keyed: std::collections::BTreeMap<usize, (String, usize)> = Default::default();
    for (k, n) in names.iter().enumerate() {
        let key = match rank(n) {
            Some(r) => r,
            None => REFERENCES + k,
        };
        keyed.entry(key).or_insert_with(|| (n.clone(), k));
    }
    let mut out = Vec::new();
    let keys: Vec<usize> = keyed.keys().copied().collect();
    let mut skip = std::collections::BTreeSet::new();
    for &key in &keys {
        if key <= 2 || skip.contains(&key) {
            continue; // positions are the points
        }
        let (name, col) = keyed[&key].clone();
        if key < REFERENCES {
            if VECTOR_STARTS.contains(&name.as_str())
                && keyed.contains_key(&(key + 1))
                && keyed.contains_key(&(key + 2))
            {
                skip.insert(key + 1);
                skip.insert(key + 2);
                let short = name[..name.find('x').unwrap_or(name.len())].to_string();
                out.push(Field {
                    name: short,
                    integer: name == "ix",
                    columns: vec![col, keyed[&(key + 1)].1, keyed[&(key + 2)].1],
                });
                continue;
            }
            out.push(Field {
                integer: matches!(name.as_str(), "id" | "mol" | "type" | "ix" | "iy" | "iz"),
                name,
                columns: vec![col],
            });
            continue;
        }
        // references: variables lose their prefix; bracketed triples with one stem merge
        if let Some(var) = name.strip_prefix("v_") {
            out.push(Field {
                name: var.to_string(),
                integer: false,
                columns: vec![col],
            });
            continue;
        }
        let stem = |s: &str| s.len().checked_sub(3).map(|l| s[..l].to_string());
        let bracketed = name.ends_with(']');
        let next = |d: usize| keyed.get(&(key + d)).map(|(n, c)| (n.clone(), *c));
        if let (true, Some((n1, c1)), Some((n2, c2))) = (bracketed, next(1), next(2)) {
            let s = stem(&name);
            let same = |other: &str| {
                s.as_ref()
                    .is_some_and(|s| other.len() >= s.len() && other.starts_with(s.as_str()))
            };
            if same(&n1) && same(&n2) {
                let last = n2
                    .rsplit_once('[')
                    .map(|(_, r)| r.trim_end_matches(']').to_string())
                    .unwrap_or_default();
                skip.insert(key + 1);
                skip.insert(key + 2);
                out.push(Field {
                    name: format!("{}-{last}]", &name[..name.len() - 1]),
                    integer: false,
                    columns: vec![col, c1, c2],
                });
                continue;
            }
        }
        out.push(Field {
            name,
            integer: false,
            columns: vec![col],
        });
    }
    out
}

/// Writes values with `format`, each followed by a blank, a line break after every ninth,
/// and a line break at the end (VTK's legacy array layout).
pub(crate) fn write_array(
    out: &mut impl Write,
    count: usize,
    mut value: impl FnMut(usize) -> String,
) -> std::io::Result<()> {
    for k in 0..count {
        write!(out, "{} ", value(k))?;
        if (k + 1) % 9 == 0 {
            writeln!(out)?;
        }
    }
    writeln!(out)
}

/// One snapshot of `atoms` (particle indices). `position(i)` gives atom i's coordinates,
/// `value(column, i)` the value of a dump column.
pub fn write_particles(
    out: &mut impl Write,
    atoms: &[usize],
    fields: &[Field],
    position: impl Fn(usize) -> [f64; 3],
    value: impl Fn(usize, usize) -> f64,
) -> std::io::Result<()> {
    let n = atoms.len();
    writeln!(
        out,
        "# vtk DataFile Version 5.1\nGenerated by LIGGGHTS\nASCII\nDATASET POLYDATA\nPOINTS {n} float"
    )?;
    write_array(out, 3 * n, |k| {
        g(position(atoms[k / 3])[k % 3] as f32 as f64)
    })?;
    if n == 0 {
        // VTK writes no cells and no point data for an empty set (LIGGGHTS before insertion)
        return Ok(());
    }
    writeln!(out, "VERTICES {} {n}\nOFFSETS vtktypeint64", n + 1)?;
    write_array(out, n + 1, |k| k.to_string())?;
    writeln!(out, "CONNECTIVITY vtktypeint64")?;
    write_array(out, n, |k| k.to_string())?;
    writeln!(out, "POINT_DATA {n}\nFIELD FieldData {}", fields.len())?;
    for f in fields {
        let width = f.columns.len();
        let kind = if f.integer { "int" } else { "double" };
        writeln!(out, "{} {width} {n} {kind}", f.name)?;
        write_array(out, width * n, |k| {
            let v = value(f.columns[k % width], atoms[k / width]);
            if f.integer {
                (v as i64).to_string()
            } else {
                g_precision(v, 11)
            }
        })?;
    }
    Ok(())
}

/// One snapshot as a binary legacy file (`dump_modify binary yes`): the ASCII file's lines,
/// each array's values big-endian (points as floats, offsets and connectivity as 8-byte
/// integers, fields as ints or doubles) followed by a line break, as VTK 9.1 writes them.
pub fn write_particles_binary(
    out: &mut impl Write,
    atoms: &[usize],
    fields: &[Field],
    position: impl Fn(usize) -> [f64; 3],
    value: impl Fn(usize, usize) -> f64,
) -> std::io::Result<()> {
    let n = atoms.len();
    let mut b = Vec::with_capacity(256 + 12 * n + 16 * (n + 1));
    b.extend_from_slice(
        format!("# vtk DataFile Version 5.1\nGenerated by LIGGGHTS\nBINARY\nDATASET POLYDATA\nPOINTS {n} float\n")
            .as_bytes(),
    );
    for &i in atoms {
        for x in position(i) {
            b.extend_from_slice(&(x as f32).to_be_bytes());
        }
    }
    if n == 0 {
        // as the ASCII file: no cells and no point data for an empty set
        b.push(b'\n');
        return out.write_all(&b);
    }
    b.extend_from_slice(format!("\nVERTICES {} {n}\nOFFSETS vtktypeint64\n", n + 1).as_bytes());
    for k in 0..=n as i64 {
        b.extend_from_slice(&k.to_be_bytes());
    }
    b.extend_from_slice(b"\nCONNECTIVITY vtktypeint64\n");
    for k in 0..n as i64 {
        b.extend_from_slice(&k.to_be_bytes());
    }
    b.extend_from_slice(format!("\nPOINT_DATA {n}\nFIELD FieldData {}\n", fields.len()).as_bytes());
    for f in fields {
        let width = f.columns.len();
        let kind = if f.integer { "int" } else { "double" };
        b.extend_from_slice(format!("{} {width} {n} {kind}\n", f.name).as_bytes());
        for &i in atoms {
            for &c in &f.columns {
                let v = value(c, i);
                if f.integer {
                    b.extend_from_slice(&(v as i32).to_be_bytes());
                } else {
                    b.extend_from_slice(&v.to_be_bytes());
                }
            }
        }
        b.push(b'\n');
    }
    out.write_all(&b)
}

/// The box as a binary legacy rectilinear grid (big-endian doubles).
pub fn write_bounding_box_binary(out: &mut impl Write, domain: &Domain) -> std::io::Result<()> {
    let mut b = b"# vtk DataFile Version 5.1\nGenerated by LIGGGHTS\nBINARY\nDATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2\n".to_vec();
    for (d, axis) in ["X", "Y", "Z"].iter().enumerate() {
        b.extend_from_slice(format!("{axis}_COORDINATES 2 double\n").as_bytes());
        b.extend_from_slice(&domain.lo[d].to_be_bytes());
        b.extend_from_slice(&domain.hi[d].to_be_bytes());
        b.push(b'\n');
    }
    out.write_all(&b)
}

/// The box as a 2 x 2 x 2 rectilinear grid (the `_boundingBox` file).
pub fn write_bounding_box(out: &mut impl Write, domain: &Domain) -> std::io::Result<()> {
    writeln!(
        out,
        "# vtk DataFile Version 5.1\nGenerated by LIGGGHTS\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 2"
    )?;
    for (d, axis) in ["X", "Y", "Z"].iter().enumerate() {
        writeln!(out, "{axis}_COORDINATES 2 double")?;
        write_array(out, 2, |k| {
            g_precision(if k == 0 { domain.lo[d] } else { domain.hi[d] }, 11)
        })?;
    }
    Ok(())
}

/// The VTK file flavours a dump name can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flavor {
    /// `.vtk`: legacy ASCII, byte-identical to LIGGGHTS's.
    Legacy,
    /// `.vtp`: XML polydata (ASCII).
    PolyData,
    /// `.vtu`: XML unstructured grid of vertex cells (ASCII).
    Unstructured,
}

impl Flavor {
    /// The flavour of a file name (None: not a VTK name regolith writes).
    pub fn of(name: &str) -> Option<Flavor> {
        if name.ends_with(".vtk") {
            Some(Flavor::Legacy)
        } else if name.ends_with(".vtp") {
            Some(Flavor::PolyData)
        } else if name.ends_with(".vtu") {
            Some(Flavor::Unstructured)
        } else if name.ends_with(".pvtp") {
            // a parallel master file: its one piece holds the polydata
            Some(Flavor::PolyData)
        } else if name.ends_with(".pvtu") {
            Some(Flavor::Unstructured)
        } else {
            None
        }
    }
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// One snapshot as an XML file (`.vtp` polydata or `.vtu` unstructured grid) in the layout
/// LIGGGHTS 3.8.0 writes through VTK 9.1: the legacy file's fields with their ranges, numbers
/// in VTK's shortest round-trip form, single-precision points, one vertex cell per particle.
pub fn write_particles_xml<W: Write>(
    out: &mut W,
    flavor: Flavor,
    binary: bool,
    atoms: &[usize],
    fields: &[Field],
    position: impl Fn(usize) -> [f64; 3],
    value: impl Fn(usize, usize) -> f64,
) -> std::io::Result<()> {
    use crate::io::local_vtk_xml::{data_array, shortest, Encoding};
    let n = atoms.len();
    let enc = |bytes: Vec<u8>| {
        if binary {
            Encoding::Binary(bytes)
        } else {
            Encoding::Ascii
        }
    };
    let (kind, piece) = match flavor {
        Flavor::Unstructured => (
            "UnstructuredGrid",
            format!("<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\">"),
        ),
        _ => (
            "PolyData",
            format!(
                "<Piece NumberOfPoints=\"{n}\" NumberOfVerts=\"{n}\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">"
            ),
        ),
    };
    writeln!(
        out,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{kind}\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n  <{kind}>\n    {piece}\n      <PointData>"
    )?;
    for f in fields {
        let width = f.columns.len();
        let numbers: Vec<f64> = (0..width * n)
            .map(|k| {
                let v = value(f.columns[k % width], atoms[k / width]);
                if f.integer {
                    v as i32 as f64
                } else {
                    v
                }
            })
            .collect();
        let text: Vec<String> = numbers
            .iter()
            .map(|&v| {
                if f.integer {
                    (v as i64).to_string()
                } else {
                    shortest(v)
                }
            })
            .collect();
        let t = if f.integer { "Int32" } else { "Float64" };
        let raw = if f.integer {
            numbers
                .iter()
                .flat_map(|&v| (v as i32).to_le_bytes())
                .collect()
        } else {
            numbers.iter().flat_map(|&v| v.to_le_bytes()).collect()
        };
        data_array(
            out,
            t,
            &xml_escape(&f.name),
            width,
            &text,
            &numbers,
            &enc(raw),
        )?;
    }
    writeln!(
        out,
        "      </PointData>\n      <CellData>\n      </CellData>\n      <Points>"
    )?;
    let points: Vec<f64> = (0..3 * n)
        .map(|k| position(atoms[k / 3])[k % 3] as f32 as f64)
        .collect();
    let text: Vec<String> = points.iter().map(|&v| shortest(v)).collect();
    let raw = points
        .iter()
        .flat_map(|&v| (v as f32).to_le_bytes())
        .collect();
    data_array(out, "Float32", "Points", 3, &text, &points, &enc(raw))?;
    writeln!(out, "      </Points>")?;
    let ints = |out: &mut W, kind: &str, name: &str, values: &[u64]| -> std::io::Result<()> {
        let text: Vec<String> = values.iter().map(u64::to_string).collect();
        let numbers: Vec<f64> = values.iter().map(|&v| v as f64).collect();
        let raw = if kind == "UInt8" {
            values.iter().map(|&v| v as u8).collect()
        } else {
            values
                .iter()
                .flat_map(|&v| (v as i64).to_le_bytes())
                .collect()
        };
        data_array(out, kind, name, 1, &text, &numbers, &enc(raw))
    };
    let connectivity: Vec<u64> = (0..n as u64).collect();
    let offsets: Vec<u64> = (1..=n as u64).collect();
    let sections: &[(&str, bool)] = match flavor {
        Flavor::Unstructured => &[("Cells", true)],
        _ => &[
            ("Verts", true),
            ("Lines", false),
            ("Strips", false),
            ("Polys", false),
        ],
    };
    for &(section, vertices) in sections {
        writeln!(out, "      <{section}>")?;
        let (c, o) = if vertices {
            (&connectivity[..], &offsets[..])
        } else {
            (&[][..], &[][..])
        };
        ints(out, "Int64", "connectivity", c)?;
        ints(out, "Int64", "offsets", o)?;
        if flavor == Flavor::Unstructured {
            ints(out, "UInt8", "types", &vec![1; n])?;
        }
        writeln!(out, "      </{section}>")?;
    }
    writeln!(out, "    </Piece>\n  </{kind}>\n</VTKFile>")
}

/// The box as an XML rectilinear grid (`.vtr`, and the `.pvtr` of parallel dumps), in VTK
/// 9.1's layout as LIGGGHTS writes it; VTK names the coordinate arrays after their memory
/// addresses (`Array 0x...`), regolith names them x, y, z.
pub fn write_bounding_box_xml(
    out: &mut impl Write,
    domain: &Domain,
    binary: bool,
) -> std::io::Result<()> {
    use crate::io::local_vtk_xml::shortest;
    writeln!(
        out,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"RectilinearGrid\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n  <RectilinearGrid WholeExtent=\"0 1 0 1 0 1\">\n  <Piece Extent=\"0 1 0 1 0 1\">\n    <PointData>\n    </PointData>\n    <CellData>\n    </CellData>\n    <Coordinates>"
    )?;
    for (d, axis) in ["x", "y", "z"].iter().enumerate() {
        let (lo, hi) = (domain.lo[d], domain.hi[d]);
        let (format, values) = if binary {
            let mut block = 16u32.to_le_bytes().to_vec();
            block.extend_from_slice(&lo.to_le_bytes());
            block.extend_from_slice(&hi.to_le_bytes());
            ("binary", crate::io::local_vtk_xml::base64(&block))
        } else {
            ("ascii", format!("{} {}", shortest(lo), shortest(hi)))
        };
        writeln!(
            out,
            "      <DataArray type=\"Float64\" Name=\"{axis}\" format=\"{format}\" RangeMin=\"{}\" RangeMax=\"{}\">\n        {values}\n      </DataArray>",
            shortest(lo.min(hi)),
            shortest(lo.max(hi)),
        )?;
    }
    writeln!(
        out,
        "    </Coordinates>\n  </Piece>\n  </RectilinearGrid>\n</VTKFile>"
    )
}

/// File name of the bounding-box companion of dump file `name` at a (padded) step:
/// `d*.vtk` gives `dboundingBox_<step>.vtk`, `single.vtk` gives `single_boundingBox.vtk`;
/// XML dumps get a `.vtr` box.
pub fn bounding_box_name(name: &str, step_text: &str) -> String {
    let legacy = bounding_box_name_legacy(name, step_text);
    if is_parallel(name) {
        // LIGGGHTS names the box of a parallel dump `.pvtr` (its content a serial grid)
        return format!("{}.pvtr", &legacy[..legacy.len() - 5]);
    }
    match Flavor::of(name) {
        Some(Flavor::PolyData) | Some(Flavor::Unstructured) => {
            format!("{}.vtr", &legacy[..legacy.len() - 4])
        }
        _ => legacy,
    }
}

/// Whether `name` is a parallel VTK master file (`.pvtp`, `.pvtu`): LIGGGHTS writes the
/// master and one piece per process (regolith: one piece, see [`piece_name`]).
pub fn is_parallel(name: &str) -> bool {
    name.ends_with(".pvtp") || name.ends_with(".pvtu")
}

/// The file of the (only) piece of parallel master file `name`: `d10.pvtp` gives
/// `d10_0.vtp`, as LIGGGHTS numbers the pieces by process.
pub fn piece_name(name: &str) -> String {
    let (stem, ext) = name.split_at(name.len() - 5);
    format!("{stem}_0.{}", &ext[2..])
}

/// The parallel master file of a one-piece XML dump, as VTK 9.1's parallel writers write
/// it for LIGGGHTS: the piece's point-data arrays and points declared by type, name and
/// component count, then the piece's file name (`source`, without its folder).
pub fn parallel_master(piece: &str, source: &str, flavor: Flavor) -> String {
    let kind = match flavor {
        Flavor::Unstructured => "PUnstructuredGrid",
        _ => "PPolyData",
    };
    let mut out = format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{kind}\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n  <{kind} GhostLevel=\"0\">\n"
    );
    // the piece's PointData and Points sections, each array's declaration
    let mut section: Option<&str> = None;
    for line in piece.lines().map(str::trim) {
        match line {
            "<PointData>" => {
                section = Some("PPointData");
                out.push_str("    <PPointData>\n");
            }
            "<Points>" => {
                section = Some("PPoints");
                out.push_str("    <PPoints>\n");
            }
            "</PointData>" | "</Points>" => {
                if let Some(tag) = section.take() {
                    out.push_str(&format!("    </{tag}>\n"));
                }
            }
            l if section.is_some() && l.starts_with("<DataArray ") => {
                let attr = |key: &str| {
                    let pat = format!(" {key}=\"");
                    l.find(&pat).map(|k| {
                        let rest = &l[k + pat.len()..];
                        rest[..rest.find('"').unwrap_or(rest.len())].to_string()
                    })
                };
                let mut decl = format!(
                    "      <PDataArray type=\"{}\" Name=\"{}\"",
                    attr("type").unwrap_or_default(),
                    attr("Name").unwrap_or_default()
                );
                if let Some(n) = attr("NumberOfComponents") {
                    decl.push_str(&format!(" NumberOfComponents=\"{n}\""));
                }
                decl.push_str("/>\n");
                out.push_str(&decl);
            }
            _ => {}
        }
    }
    out.push_str(&format!(
        "    <Piece Source=\"{}\"/>\n  </{kind}>\n</VTKFile>\n",
        xml_escape(source)
    ));
    out
}

fn bounding_box_name_legacy(name: &str, step_text: &str) -> String {
    if name.contains('*') {
        return name.replace('*', &format!("boundingBox_{step_text}"));
    }
    let file_start = name.rfind('/').map_or(0, |k| k + 1);
    match name[file_start..].rfind('.') {
        Some(dot) => {
            let dot = file_start + dot;
            format!("{}_boundingBox{}", &name[..dot], &name[dot..])
        }
        None => format!("{name}_boundingBox"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(s: &str) -> Vec<String> {
        s.split_whitespace().map(str::to_string).collect()
    }

    #[test]
    fn fields_follow_liggghts_order_and_merge_vectors() {
        // the tutorials' column list, with a compute triple and a variable
        let f = fields(&names(
            "id type type x y z ix iy iz vx vy vz fx fy fz omegax omegay omegaz radius c_s[1] c_s[2] c_s[3] c_s[4] v_k mass",
        ));
        let got: Vec<(&str, usize)> = f
            .iter()
            .map(|f| (f.name.as_str(), f.columns.len()))
            .collect();
        assert_eq!(
            got,
            vec![
                ("id", 1),
                ("type", 1),
                ("mass", 1),
                ("i", 3),
                ("v", 3),
                ("f", 3),
                ("radius", 1),
                ("omega", 3),
                ("c_s[1-3]", 3),
                ("c_s[4]", 1),
                ("k", 1)
            ]
        );
        assert!(f[3].integer && !f[4].integer);
        // incomplete triples stay scalar, id still comes first
        let f = fields(&names("vx fx id"));
        let got: Vec<&str> = f.iter().map(|f| f.name.as_str()).collect();
        assert_eq!(got, vec!["id", "vx", "fx"]);
    }

    #[test]
    fn layout_matches_liggghts_bytes() {
        // Debian LIGGGHTS, dump custom/vtk ... id vx fx of two atoms
        let f = fields(&names("vx fx id"));
        let x = [[0.499995, 0.499994, 0.5], [0.55002, 0.520012, 0.5]];
        let vals = [
            [-0.2017150924, -3896.8263952, 1.0],
            [0.48928728984, 3896.8263952, 2.0],
        ];
        let mut out = Vec::new();
        write_particles(&mut out, &[0, 1], &f, |i| x[i], |c, i| vals[i][c]).unwrap();
        let want = "# vtk DataFile Version 5.1\nGenerated by LIGGGHTS\nASCII\nDATASET POLYDATA\n\
POINTS 2 float\n0.499995 0.499994 0.5 0.55002 0.520012 0.5 \nVERTICES 3 2\n\
OFFSETS vtktypeint64\n0 1 2 \nCONNECTIVITY vtktypeint64\n0 1 \nPOINT_DATA 2\n\
FIELD FieldData 3\nid 1 2 int\n1 2 \nvx 1 2 double\n-0.2017150924 0.48928728984 \n\
fx 1 2 double\n-3896.8263952 3896.8263952 \n";
        assert_eq!(String::from_utf8(out).unwrap(), want);
    }

    #[test]
    fn parallel_names_and_master() {
        assert_eq!(piece_name("post/d10.pvtp"), "post/d10_0.vtp");
        assert_eq!(piece_name("atoms.pvtu"), "atoms_0.vtu");
        assert_eq!(
            bounding_box_name("post/d*.pvtp", "10"),
            "post/dboundingBox_10.pvtr"
        );
        assert_eq!(
            bounding_box_name("atoms.pvtu", "10"),
            "atoms_boundingBox.pvtr"
        );
        let piece = "<PointData>\n<DataArray type=\"Int32\" Name=\"id\" format=\"ascii\">\n1\n</DataArray>\n\
            <DataArray type=\"Float64\" Name=\"v\" NumberOfComponents=\"3\" format=\"ascii\">\n</DataArray>\n</PointData>\n\
            <CellData>\n</CellData>\n<Points>\n<DataArray type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n</DataArray>\n</Points>\n";
        assert_eq!(
            parallel_master(piece, "d10_0.vtp", Flavor::PolyData),
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"PPolyData\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n  <PPolyData GhostLevel=\"0\">\n    <PPointData>\n      <PDataArray type=\"Int32\" Name=\"id\"/>\n      <PDataArray type=\"Float64\" Name=\"v\" NumberOfComponents=\"3\"/>\n    </PPointData>\n    <PPoints>\n      <PDataArray type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\"/>\n    </PPoints>\n    <Piece Source=\"d10_0.vtp\"/>\n  </PPolyData>\n</VTKFile>\n"
        );
    }

    #[test]
    fn bounding_box_names() {
        assert_eq!(
            bounding_box_name("post/d*.vtk", "00010"),
            "post/dboundingBox_00010.vtk"
        );
        assert_eq!(
            bounding_box_name("post/single.vtk", "10"),
            "post/single_boundingBox.vtk"
        );
    }
}
