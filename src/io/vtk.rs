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

fn xml_array(
    out: &mut impl Write,
    kind: &str,
    name: &str,
    components: usize,
    count: usize,
    mut value: impl FnMut(usize) -> String,
) -> std::io::Result<()> {
    let comps = if components > 1 {
        format!(" NumberOfComponents=\"{components}\"")
    } else {
        String::new()
    };
    writeln!(
        out,
        "        <DataArray type=\"{kind}\" Name=\"{}\"{comps} format=\"ascii\">",
        xml_escape(name)
    )?;
    for start in (0..count).step_by(6) {
        let line: Vec<String> = (start..(start + 6).min(count)).map(&mut value).collect();
        writeln!(out, "          {}", line.join(" "))?;
    }
    writeln!(out, "        </DataArray>")
}

/// One snapshot as an XML file (`.vtp` polydata or `.vtu` unstructured grid), the same
/// fields as the legacy file, full double precision.
pub fn write_particles_xml(
    out: &mut impl Write,
    flavor: Flavor,
    atoms: &[usize],
    fields: &[Field],
    position: impl Fn(usize) -> [f64; 3],
    value: impl Fn(usize, usize) -> f64,
) -> std::io::Result<()> {
    let n = atoms.len();
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
        let t = if f.integer { "Int32" } else { "Float64" };
        xml_array(out, t, &f.name, width, width * n, |k| {
            let v = value(f.columns[k % width], atoms[k / width]);
            if f.integer {
                (v as i64).to_string()
            } else {
                g_precision(v, 17)
            }
        })?;
    }
    writeln!(
        out,
        "      </PointData>\n      <CellData>\n      </CellData>\n      <Points>"
    )?;
    xml_array(out, "Float32", "Points", 3, 3 * n, |k| {
        g_precision(position(atoms[k / 3])[k % 3] as f32 as f64, 9)
    })?;
    writeln!(out, "      </Points>")?;
    let section = if flavor == Flavor::Unstructured {
        "Cells"
    } else {
        "Verts"
    };
    writeln!(out, "      <{section}>")?;
    xml_array(out, "Int64", "connectivity", 1, n, |k| k.to_string())?;
    xml_array(out, "Int64", "offsets", 1, n, |k| (k + 1).to_string())?;
    if flavor == Flavor::Unstructured {
        xml_array(out, "UInt8", "types", 1, n, |_| "1".to_string())?;
    }
    writeln!(
        out,
        "      </{section}>\n    </Piece>\n  </{kind}>\n</VTKFile>"
    )
}

/// The box as an XML rectilinear grid (`.vtr`).
pub fn write_bounding_box_xml(out: &mut impl Write, domain: &Domain) -> std::io::Result<()> {
    writeln!(
        out,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"RectilinearGrid\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n  <RectilinearGrid WholeExtent=\"0 1 0 1 0 1\">\n    <Piece Extent=\"0 1 0 1 0 1\">\n      <PointData>\n      </PointData>\n      <CellData>\n      </CellData>\n      <Coordinates>"
    )?;
    for (d, axis) in ["x", "y", "z"].iter().enumerate() {
        xml_array(out, "Float64", axis, 1, 2, |k| {
            g_precision(if k == 0 { domain.lo[d] } else { domain.hi[d] }, 17)
        })?;
    }
    writeln!(
        out,
        "      </Coordinates>\n    </Piece>\n  </RectilinearGrid>\n</VTKFile>"
    )
}

/// File name of the bounding-box companion of dump file `name` at a (padded) step:
/// `d*.vtk` gives `dboundingBox_<step>.vtk`, `single.vtk` gives `single_boundingBox.vtk`;
/// XML dumps get a `.vtr` box.
pub fn bounding_box_name(name: &str, step_text: &str) -> String {
    let legacy = bounding_box_name_legacy(name, step_text);
    match Flavor::of(name) {
        Some(Flavor::PolyData) | Some(Flavor::Unstructured) => {
            format!("{}.vtr", &legacy[..legacy.len() - 4])
        }
        _ => legacy,
    }
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
