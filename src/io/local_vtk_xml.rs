//! `dump local/gran/vtk` to a `.vtp` (polydata) or `.vtu` (unstructured grid) file: the
//! contact network of [`crate::io::local_vtk`] in the ASCII XML layout Debian's LIGGGHTS 3.8.0
//! writes through VTK 9.1: both ends of each contact as `Float32` points, one line cell per
//! contact, the same cell-data arrays as the legacy file, six values a line, numbers in
//! VTK's shortest round-trip form, each array's range (of the magnitudes for vectors) in its
//! header and, for vectors, again with 11 digits as VTK's `L2_NORM_RANGE` key.

use std::io::Write;

use crate::io::local_vtk::ContactLayout;
use crate::util::format::g_precision;

/// Which XML dataset the file holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum XmlKind {
    /// `.vtp`: polydata with line cells.
    PolyData,
    /// `.vtu`: an unstructured grid of line cells (VTK cell type 3).
    Unstructured,
}

impl XmlKind {
    /// The XML flavour a dump file name asks for (`None`: the legacy `.vtk` layout).
    pub fn of_file(name: &str) -> Option<XmlKind> {
        if name.ends_with(".vtp") {
            Some(XmlKind::PolyData)
        } else if name.ends_with(".vtu") {
            Some(XmlKind::Unstructured)
        } else {
            None
        }
    }
}

/// `v` as VTK 9.1 writes a double (double-conversion's shortest round-trip digits in the
/// ECMAScript layout: plain decimals from 1e-6 up to 1e21, else `d.ddde±N`).
pub fn shortest(v: f64) -> String {
    if v == 0.0 {
        return "0".to_string();
    }
    if !v.is_finite() {
        return if v.is_nan() {
            "NaN"
        } else if v > 0.0 {
            "Infinity"
        } else {
            "-Infinity"
        }
        .to_string();
    }
    // the shortest digit count; of the numbers with that many digits the nearest, a tie
    // going to the even digit as double-conversion rounds (Rust's shortest form rounds it up)
    let short = format!("{:e}", v.abs());
    let count = short.split('e').next().unwrap_or("").replace('.', "").len();
    let sci = format!("{:.*e}", count.saturating_sub(1), v.abs());
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let digits: String = mantissa.chars().filter(|c| *c != '.').collect();
    let k = digits.len() as i32;
    let n = exp + 1; // the decimal point sits after n digits
    let body = if k <= n && n <= 21 {
        format!("{digits}{}", "0".repeat((n - k) as usize))
    } else if 0 < n && n <= 21 {
        format!("{}.{}", &digits[..n as usize], &digits[n as usize..])
    } else if -6 < n && n <= 0 {
        format!("0.{}{digits}", "0".repeat((-n) as usize))
    } else {
        let sign = if n - 1 < 0 { '-' } else { '+' };
        let tail = if k > 1 {
            format!(".{}", &digits[1..])
        } else {
            String::new()
        };
        format!("{}{tail}e{sign}{}", &digits[..1], (n - 1).abs())
    };
    if v < 0.0 {
        format!("-{body}")
    } else {
        body
    }
}

/// How a `DataArray`'s values are written.
pub(crate) enum Encoding {
    /// The formatted values, six a line.
    Ascii,
    /// `format="binary"`: these raw little-endian bytes after their byte count (a 4-byte
    /// integer), base64 on one line.
    Binary(Vec<u8>),
}

/// Base64 (RFC 4648, padded) of `bytes`.
pub(crate) fn base64(bytes: &[u8]) -> String {
    const SYMBOLS: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let word = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(SYMBOLS[((word >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// One `DataArray`: `values` hold `width` components per tuple, already formatted; `numbers`
/// the same values for the range; `encoding` says which of them the file holds.
pub(crate) fn data_array(
    out: &mut impl Write,
    kind: &str,
    name: &str,
    width: usize,
    values: &[String],
    numbers: &[f64],
    encoding: &Encoding,
) -> std::io::Result<()> {
    // an empty array's range is VTK's untouched (1e299, -1e299)
    let mut range = (1e299_f64, -1e299_f64);
    for tuple in numbers.chunks(width) {
        let v = if width == 1 {
            tuple[0]
        } else {
            tuple.iter().fold(0.0, |s, x| s + x * x)
        };
        range = (range.0.min(v), range.1.max(v));
    }
    if width > 1 && !numbers.is_empty() {
        range = (range.0.sqrt(), range.1.sqrt());
    }
    let comps = if width > 1 {
        format!(" NumberOfComponents=\"{width}\"")
    } else {
        String::new()
    };
    let format = match encoding {
        Encoding::Ascii => "ascii",
        Encoding::Binary(_) => "binary",
    };
    writeln!(
        out,
        "        <DataArray type=\"{kind}\" Name=\"{name}\"{comps} format=\"{format}\" RangeMin=\"{}\" RangeMax=\"{}\">",
        shortest(range.0),
        shortest(range.1)
    )?;
    match encoding {
        Encoding::Ascii => {
            for line in values.chunks(6) {
                writeln!(out, "          {}", line.join(" "))?;
            }
        }
        Encoding::Binary(raw) => {
            let mut block = (raw.len() as u32).to_le_bytes().to_vec();
            block.extend_from_slice(raw);
            writeln!(out, "          {}", base64(&block))?;
        }
    }
    if width > 1 {
        writeln!(
            out,
            "          <InformationKey name=\"L2_NORM_RANGE\" location=\"vtkDataArray\" length=\"2\">"
        )?;
        for (i, v) in [range.0, range.1].into_iter().enumerate() {
            writeln!(
                out,
                "            <Value index=\"{i}\">\n              {}\n            </Value>",
                g_precision(v, 11)
            )?;
        }
        writeln!(out, "          </InformationKey>")?;
    }
    writeln!(out, "        </DataArray>")
}

/// An integer `DataArray` of `values` (connectivity, offsets, cell types).
fn int_array(out: &mut impl Write, kind: &str, name: &str, values: &[u64]) -> std::io::Result<()> {
    let text: Vec<String> = values.iter().map(u64::to_string).collect();
    let numbers: Vec<f64> = values.iter().map(|&v| v as f64).collect();
    data_array(out, kind, name, 1, &text, &numbers, &Encoding::Ascii)
}

/// One snapshot: `rows` holds `ncols` values per contact, row-major.
pub fn write_contacts_xml(
    out: &mut impl Write,
    kind: XmlKind,
    layout: &ContactLayout,
    ncols: usize,
    rows: &[f64],
) -> std::io::Result<()> {
    let n = rows.len().checked_div(ncols).unwrap_or(0);
    let at = |r: usize, c: usize| rows[r * ncols + c];
    // single-precision points, written as the doubles they widen to
    let points: Vec<f64> = (layout.points(n, at).into_iter())
        .map(|v| v as f32 as f64)
        .collect();
    let lines = layout.lines(n);
    let (npoints, cells, per) = (points.len() / 3, lines.len(), layout.lines_per_contact());
    let (tag, piece) = match kind {
        XmlKind::PolyData => (
            "PolyData",
            format!(
                "<Piece NumberOfPoints=\"{npoints}\" NumberOfVerts=\"0\" NumberOfLines=\"{cells}\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">"
            ),
        ),
        XmlKind::Unstructured => (
            "UnstructuredGrid",
            format!("<Piece NumberOfPoints=\"{npoints}\" NumberOfCells=\"{cells}\">"),
        ),
    };
    writeln!(
        out,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"{tag}\" version=\"0.1\" byte_order=\"LittleEndian\" header_type=\"UInt32\">\n  <{tag}>\n    {piece}\n      <PointData>\n      </PointData>\n      <CellData>"
    )?;
    for &(name, first, width) in &layout.fields {
        let numbers: Vec<f64> = (0..cells * width)
            .map(|k| at(k / width / per, first + k % width))
            .collect();
        let text: Vec<String> = numbers.iter().map(|&v| shortest(v)).collect();
        data_array(
            out,
            "Float64",
            name,
            width,
            &text,
            &numbers,
            &Encoding::Ascii,
        )?;
    }
    writeln!(out, "      </CellData>\n      <Points>")?;
    let text: Vec<String> = points.iter().map(|&v| shortest(v)).collect();
    data_array(
        out,
        "Float32",
        "Points",
        3,
        &text,
        &points,
        &Encoding::Ascii,
    )?;
    writeln!(out, "      </Points>")?;
    let connectivity: Vec<u64> = lines.iter().flatten().copied().collect();
    let offsets: Vec<u64> = (1..=cells as u64).map(|k| 2 * k).collect();
    let sections: &[(&str, bool)] = match kind {
        XmlKind::PolyData => &[
            ("Verts", false),
            ("Lines", true),
            ("Strips", false),
            ("Polys", false),
        ],
        XmlKind::Unstructured => &[("Cells", true)],
    };
    for &(section, lines) in sections {
        writeln!(out, "      <{section}>")?;
        let (c, o) = if lines {
            (&connectivity[..], &offsets[..])
        } else {
            (&[][..], &[][..])
        };
        int_array(out, "Int64", "connectivity", c)?;
        int_array(out, "Int64", "offsets", o)?;
        if kind == XmlKind::Unstructured {
            int_array(out, "UInt8", "types", &vec![3; cells])?;
        }
        writeln!(out, "      </{section}>")?;
    }
    writeln!(out, "    </Piece>\n  </{tag}>\n</VTKFile>")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_as_vtk_writes_it() {
        // LIGGGHTS's binary id array [1, 2] after its byte count 8
        let block = [8u8, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0];
        assert_eq!(base64(&block), "CAAAAAEAAAACAAAA");
        assert_eq!(base64(&[0, 0, 0, 0]), "AAAAAA==");
        assert_eq!(base64(&[0, 0, 0, 0, 1]), "AAAAAAE=");
    }

    #[test]
    fn numbers_as_vtk_writes_them() {
        assert_eq!(shortest(9.863631902492693e-8), "9.863631902492693e-8");
        assert_eq!(shortest(1.3019902140442167e-6), "0.0000013019902140442167");
        assert_eq!(shortest(-0.0005157046834938228), "-0.0005157046834938228");
        assert_eq!(shortest(56.0), "56");
        assert_eq!(shortest(1e299), "1e+299");
        assert_eq!(shortest(-1e299), "-1e+299");
        assert_eq!(shortest(0.1), "0.1");
        assert_eq!(shortest(123456.5), "123456.5");
        assert_eq!(shortest(1e21), "1e+21");
        assert_eq!(shortest(1e20), "100000000000000000000");
        assert_eq!(shortest(-0.0), "0");
        // a float's exact value halfway between two 17-digit numbers: the even one, as VTK
        assert_eq!(shortest(-0.150_272_37_f32 as f64), "-0.15027236938476562");
    }
}
