//! `regolith convert IN OUT`: between LIGGGHTS restart files, data files, text dumps and
//! legacy VTK. Restart and data files become a [`Bed`] (particles, box, step), which is
//! written as a data file, a dump (text or gzip) or VTK; a dump converts snapshot by snapshot
//! to VTK. Formats come from the file names or `--from`/`--to`.

use crate::io::dump::Layout;
pub use crate::io::error::ConvertError;
use crate::state::domain::{parse_boundary, Domain};
use crate::state::particles::Particles;

/// File formats `convert` knows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// LIGGGHTS binary restart.
    Restart,
    /// LAMMPS/LIGGGHTS data file.
    Data,
    /// Text dump (`dump custom`), gzip when the name ends in `.gz`.
    Dump,
    /// Legacy VTK polydata.
    Vtk,
}

impl Format {
    /// Parse a `--from`/`--to` word.
    pub fn parse(word: &str) -> Result<Format, ConvertError> {
        match word {
            "restart" => Ok(Format::Restart),
            "data" => Ok(Format::Data),
            "dump" => Ok(Format::Dump),
            "vtk" => Ok(Format::Vtk),
            _ => Err(ConvertError::UnknownFormat(word.to_string())),
        }
    }

    /// The format a file name implies, if any.
    pub fn of_name(name: &str) -> Option<Format> {
        let n = name.strip_suffix(".gz").unwrap_or(name);
        let ext = n.rsplit_once('.').map(|(_, e)| e).unwrap_or("");
        let base = n.rsplit('/').next().unwrap_or(n);
        match ext {
            "restart" | "rst" | "bin" => Some(Format::Restart),
            "data" | "lmp" => Some(Format::Data),
            "dump" | "lammpstrj" | "txt" | "liggghts" => Some(Format::Dump),
            "vtk" => Some(Format::Vtk),
            _ if base.starts_with("restart") => Some(Format::Restart),
            _ if base.starts_with("data") => Some(Format::Data),
            _ if base.starts_with("dump") => Some(Format::Dump),
            _ => None,
        }
    }
}

/// A bed read from a restart or data file.
#[derive(Debug, Clone, Default)]
pub struct Bed {
    /// The particles.
    pub particles: Particles,
    /// Box and boundaries.
    pub domain: Domain,
    /// Number of atom types.
    pub ntypes: u32,
    /// Timestep count.
    pub step: i64,
    /// Everything else a restart file held, to write it back unchanged where possible.
    pub restart: Option<crate::io::restart::Restart>,
}

/// Options of a conversion.
#[derive(Debug, Clone, Default)]
pub struct ConvertOptions {
    /// Input format (None: from the name).
    pub from: Option<Format>,
    /// Output format (None: from the name).
    pub to: Option<Format>,
    /// Boundary letters for a data file's box (data files carry none), e.g. `p p f`.
    pub boundary: Option<String>,
}

fn format_of(
    name: &str,
    given: Option<Format>,
    which: &'static str,
) -> Result<Format, ConvertError> {
    given
        .or_else(|| Format::of_name(name))
        .ok_or_else(|| ConvertError::FormatOfName {
            name: name.to_string(),
            which,
        })
}

/// Read a data file as a bed.
pub fn read_data_bed(path: &str, boundary: Option<&str>) -> Result<Bed, ConvertError> {
    let text = crate::io::diff::read_text(path)?;
    let data = crate::io::data::parse(&text, path)?;
    let mut domain = Domain::default();
    if let Some(b) = boundary {
        let words: Vec<&str> = b.split_whitespace().collect();
        domain.boundary = parse_boundary(&words).map_err(ConvertError::Boundary)?;
    }
    domain.create(data.lo, data.hi);
    let mut p = Particles::default();
    for a in &data.atoms {
        p.push(a.id, a.kind, a.x, 0.5 * a.diameter, a.density);
        let i = p.len() - 1;
        p.image[i] = a.image;
        p.v[i] = a.v;
        p.omega[i] = a.omega;
        if a.diameter == 0.0 {
            p.mass[i] = a.density;
        }
    }
    Ok(Bed {
        particles: p,
        domain,
        ntypes: data.ntypes,
        step: 0,
        restart: None,
    })
}

/// The columns a bed is dumped with.
const BED_COLUMNS: &[&str] = &[
    "id", "type", "x", "y", "z", "ix", "iy", "iz", "vx", "vy", "vz", "omegax", "omegay", "omegaz",
    "radius", "mass", "density",
];

/// Write a bed as a text dump (full precision), gzip for `.gz` names.
fn write_bed_dump(bed: &Bed, path: &str) -> Result<(), ConvertError> {
    let mut layout = Layout::new(BED_COLUMNS)?;
    let fmt: Vec<&str> = BED_COLUMNS
        .iter()
        .map(|c| {
            if matches!(*c, "id" | "type" | "ix" | "iy" | "iz") {
                "%d"
            } else {
                "%.17g"
            }
        })
        .collect();
    layout.set_format(&fmt.join(" "))?;
    layout.sort_by_id = true;
    let mut text = Vec::new();
    layout
        .write_snapshot(
            &mut text,
            bed.step,
            &bed.particles,
            u32::MAX,
            &bed.domain,
            |_, _| 0.0,
        )
        .map_err(ConvertError::Encode)?;
    write_maybe_gzip(path, &text)
}

fn write_maybe_gzip(path: &str, text: &[u8]) -> Result<(), ConvertError> {
    use std::io::Write;
    let bytes = if path.ends_with(".gz") {
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
        enc.write_all(text).map_err(ConvertError::Encode)?;
        enc.finish().map_err(ConvertError::Encode)?
    } else {
        text.to_vec()
    };
    write(path, &bytes)
}

/// Write a file atomically; errors name it.
fn write(path: &str, bytes: &[u8]) -> Result<(), ConvertError> {
    crate::io::write_atomically(path, bytes).map_err(|source| ConvertError::Write {
        path: path.to_string(),
        source,
    })
}

/// Write a bed as legacy VTK (with its `_boundingBox` file).
fn write_bed_vtk(bed: &Bed, path: &str) -> Result<(), ConvertError> {
    let names: Vec<String> = BED_COLUMNS.iter().map(|s| s.to_string()).collect();
    let layout = Layout::new(BED_COLUMNS)?;
    let fields = crate::io::vtk::fields(&names);
    let p = &bed.particles;
    let mut atoms: Vec<usize> = (0..p.len()).collect();
    atoms.sort_by_key(|&i| p.id[i]);
    let mut text = Vec::new();
    crate::io::vtk::write_particles(
        &mut text,
        &atoms,
        &fields,
        |i| p.x[i],
        |c, i| layout.columns[c].value(p, &bed.domain, i),
    )
    .map_err(ConvertError::Encode)?;
    let mut bbox = Vec::new();
    crate::io::vtk::write_bounding_box(&mut bbox, &bed.domain).map_err(ConvertError::Encode)?;
    let step = bed.step.to_string();
    let name = path.replace('*', &step);
    write(&name, &text)?;
    let box_name = crate::io::vtk::bounding_box_name(path, &step);
    write(&box_name, &bbox)
}

/// Convert each snapshot of a dump to VTK: `*` in the output name becomes the step (needed
/// when the dump has more than one snapshot).
fn dump_to_vtk(input: &str, output: &str) -> Result<usize, ConvertError> {
    let text = crate::io::diff::read_text(input)?;
    let snaps = crate::io::dump_compare::parse(&text).map_err(|source| ConvertError::Dump {
        input: input.to_string(),
        source,
    })?;
    if snaps.is_empty() {
        return Err(ConvertError::NoSnapshot(input.to_string()));
    }
    if snaps.len() > 1 && !output.contains('*') {
        return Err(ConvertError::NeedStar {
            input: input.to_string(),
            snapshots: snaps.len(),
            output: output.to_string(),
        });
    }
    for s in &snaps {
        let fields = crate::io::vtk::fields(&s.columns);
        let col = |n: &str| s.columns.iter().position(|c| c == n);
        let (Some(cx), Some(cy), Some(cz)) = (col("x"), col("y"), col("z")) else {
            return Err(ConvertError::NoPositions {
                input: input.to_string(),
                step: s.step,
                columns: s.columns.join(" "),
            });
        };
        let rows: Vec<&Vec<f64>> = s.rows.values().collect();
        let atoms: Vec<usize> = (0..rows.len()).collect();
        let mut out = Vec::new();
        crate::io::vtk::write_particles(
            &mut out,
            &atoms,
            &fields,
            |i| [rows[i][cx], rows[i][cy], rows[i][cz]],
            |c, i| rows[i][c],
        )
        .map_err(ConvertError::Encode)?;
        let step = s.step.to_string();
        let name = output.replace('*', &step);
        write(&name, &out)?;
        let mut domain = Domain::default();
        domain.create(
            [s.bounds[0][0], s.bounds[1][0], s.bounds[2][0]],
            [s.bounds[0][1], s.bounds[1][1], s.bounds[2][1]],
        );
        let mut bbox = Vec::new();
        crate::io::vtk::write_bounding_box(&mut bbox, &domain).map_err(ConvertError::Encode)?;
        let box_name = crate::io::vtk::bounding_box_name(output, &step);
        write(&box_name, &bbox)?;
    }
    Ok(snaps.len())
}

/// Run a conversion; returns a one-line summary.
pub fn convert(input: &str, output: &str, opts: &ConvertOptions) -> Result<String, ConvertError> {
    let from = format_of(input, opts.from, "from")?;
    let to = format_of(output, opts.to, "to")?;
    if from == Format::Dump {
        return match to {
            Format::Vtk => {
                let n = dump_to_vtk(input, output)?;
                Ok(format!("{input} -> {output}: {n} snapshot(s) as VTK"))
            }
            _ => Err(ConvertError::DumpOnlyToVtk(input.to_string())),
        };
    }
    let bed = match from {
        Format::Restart => crate::io::restart::read_bed(input)?,
        Format::Data => read_data_bed(input, opts.boundary.as_deref())?,
        Format::Vtk => return Err(ConvertError::VtkInput(input.to_string())),
        Format::Dump => unreachable!("handled above"),
    };
    match to {
        Format::Data => {
            let text = crate::io::data::write(
                &bed.particles,
                &bed.domain,
                bed.ntypes,
                bed.step,
                concat!("regolith ", env!("CARGO_PKG_VERSION")),
            );
            write(output, text.as_bytes())?
        }
        Format::Dump => write_bed_dump(&bed, output)?,
        Format::Vtk => write_bed_vtk(&bed, output)?,
        Format::Restart => crate::io::restart::write_bed(&bed, output)?,
    }
    Ok(format!(
        "{input} -> {output}: {} atoms, step {}",
        bed.particles.len(),
        bed.step
    ))
}
