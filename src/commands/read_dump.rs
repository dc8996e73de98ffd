//! `read_dump FILE NSTEP FIELD ... [KEYWORD VALUE ...]`: LIGGGHTS 3.8.0's read_dump with its
//! native reader (text files of `dump atom` / `dump custom`, plain or `.gz`). The snapshot of
//! step NSTEP overwrites the fields of the particles whose IDs it lists (`replace`), may
//! delete the others (`trim`) or all (`purge`), may take the snapshot's box (`box`), and the
//! step count becomes NSTEP.

use crate::commands::{Args, CommandError, Ctx};
use crate::lang::system::Mode;

type Result<T = ()> = std::result::Result<T, CommandError>;

const ILLEGAL: &str = "Illegal read_dump command";

/// A per-atom field read_dump can take from a snapshot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Field {
    Id,
    Type,
    /// A coordinate (0, 1, 2 for x, y, z; length).
    X(usize),
    /// A velocity component (length/time).
    V(usize),
    /// An angular velocity component (1/time).
    Omega(usize),
    /// A force component (force).
    F(usize),
    /// An image count.
    Image(usize),
    Radius,
    Mass,
    Density,
}

/// The word of each field and the column label LIGGGHTS looks for.
const FIELDS: &[(&str, Field)] = &[
    ("x", Field::X(0)),
    ("y", Field::X(1)),
    ("z", Field::X(2)),
    ("vx", Field::V(0)),
    ("vy", Field::V(1)),
    ("vz", Field::V(2)),
    ("omegax", Field::Omega(0)),
    ("omegay", Field::Omega(1)),
    ("omegaz", Field::Omega(2)),
    ("radius", Field::Radius),
    ("mass", Field::Mass),
    ("density", Field::Density),
    ("ix", Field::Image(0)),
    ("iy", Field::Image(1)),
    ("iz", Field::Image(2)),
    ("fx", Field::F(0)),
    ("fy", Field::F(1)),
    ("fz", Field::F(2)),
];

/// The parsed command.
#[derive(Debug, Clone)]
struct Options {
    fields: Vec<Field>,
    boxflag: bool,
    replace: bool,
    purge: bool,
    trim: bool,
    add: bool,
}

/// Fields and keywords in LIGGGHTS's order of checks and with its messages.
fn parse(a: &Args, ctx: &Ctx) -> Result<Options> {
    let (fields, i) = field_list(a)?;
    check_fields(a, ctx, &fields)?;
    let mut o = Options {
        fields,
        boxflag: true,
        replace: true,
        purge: false,
        trim: false,
        add: false,
    };
    let (format, i) = keywords(a, i, &mut o)?;
    if o.purge && (o.replace || o.trim) {
        return Err(a.error(0, "If read_dump purges it cannot replace or trim"));
    }
    match format {
        "native" => {}
        "xyz" => return Err(a.unsupported(i - 1, "read_dump format xyz")),
        _ => return Err(a.error(i - 1, "Invalid dump reader style")),
    }
    // words after `format native` go to the native reader, which ignores them
    if o.add {
        return Err(a.unsupported(0, "read_dump add yes (new particles from a snapshot)"));
    }
    Ok(o)
}

/// The fields from word 2 on (the ID and type always read first) and the first word after
/// them.
fn field_list(a: &Args) -> Result<(Vec<Field>, usize)> {
    let mut fields = vec![Field::Id, Field::Type];
    let mut i = 2;
    while i < a.len() {
        let w = a.word(i)?;
        if w == "q" {
            // atom_style granular has no charge
            return Err(a.error(i, "Read dump of atom property that isn't allocated"));
        }
        match FIELDS.iter().find(|(name, _)| *name == w) {
            Some((_, f)) => fields.push(*f),
            None => break,
        }
        i += 1;
    }
    Ok((fields, i))
}

/// LIGGGHTS's checks of the fields: the radius among them, no z in 2d, none twice.
fn check_fields(a: &Args, ctx: &Ctx, fields: &[Field]) -> Result<()> {
    if !fields.contains(&Field::Radius) {
        return Err(a.error(
            a.len().saturating_sub(1),
            "read_dump: the radius field is required to be read",
        ));
    }
    if ctx.sim.dimension == 2
        && fields
            .iter()
            .any(|f| matches!(f, Field::X(2) | Field::V(2) | Field::Image(2)))
    {
        return Err(a.error(0, ILLEGAL));
    }
    for (k, f) in fields.iter().enumerate() {
        if fields[k + 1..].contains(f) {
            return Err(a.error(0, "Duplicate fields in read_dump command"));
        }
    }
    Ok(())
}

/// The yes/no keywords from word `i` into `o`, up to and including `format`: the reader
/// format (`native` by default) and the first word after the keywords.
fn keywords<'a>(a: &'a Args, mut i: usize, o: &mut Options) -> Result<(&'a str, usize)> {
    while i < a.len() {
        let key = a.word(i)?;
        if !matches!(
            key,
            "box"
                | "replace"
                | "purge"
                | "trim"
                | "add"
                | "label"
                | "scaled"
                | "wrapped"
                | "format"
        ) {
            return Err(a.error(i, ILLEGAL));
        }
        if i + 2 > a.len() || (key == "label" && i + 3 > a.len()) {
            return Err(a.error(i, ILLEGAL));
        }
        if key == "format" {
            return Ok((a.word(i + 1)?, i + 2));
        }
        if key == "label" {
            // LIGGGHTS 3.8.0 looks the field up among labels that are all still unset, so
            // every label keyword is illegal there
            return Err(a.error(i, ILLEGAL));
        }
        let yes = match a.word(i + 1)? {
            "yes" => true,
            "no" => false,
            _ => return Err(a.error(i + 1, ILLEGAL)),
        };
        match key {
            "box" => o.boxflag = yes,
            "replace" => o.replace = yes,
            "purge" => o.purge = yes,
            "trim" => o.trim = yes,
            "add" => o.add = yes,
            // the native reader takes scaling and wrapping from the column labels; these
            // only matter for columns named by label
            _ => {}
        }
        i += 2;
    }
    Ok(("native", i))
}

/// The snapshot read_dump asked for: its box (length), whether its coordinates are scaled
/// and wrapped, and one row of values per atom in the order of the fields.
#[derive(Debug)]
struct Snapshot {
    lo: [f64; 3],
    hi: [f64; 3],
    scaled: bool,
    wrapped: bool,
    rows: Vec<Vec<f64>>,
}

/// LIGGGHTS's `atof`: the longest leading number, 0 when there is none.
fn atof(w: &str) -> f64 {
    let mut end = w.len();
    while end > 0 {
        if let Ok(v) = w[..end].parse::<f64>() {
            return v;
        }
        end -= 1;
        while end > 0 && !w.is_char_boundary(end) {
            end -= 1;
        }
    }
    0.0
}

/// The leading integer of a line (`sscanf %ld`), -1 when there is none.
fn leading_int(line: &str) -> i64 {
    let t = line.trim_start();
    let n = t
        .char_indices()
        .take_while(|(k, c)| c.is_ascii_digit() || (*k == 0 && (*c == '-' || *c == '+')))
        .count();
    t[..n].parse().unwrap_or(-1)
}

/// Why a native dump file does not give the snapshot asked for, in LIGGGHTS's words.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
enum SnapshotError {
    /// A snapshot does not start with its `ITEM: TIMESTEP` line.
    #[error("Dump file is incorrectly formatted")]
    Formatted,
    /// No snapshot of the step asked for.
    #[error("Dump file does not contain requested snapshot")]
    Missing,
    /// A triclinic box in the file.
    #[error("Read_dump triclinic status does not match simulation")]
    Triclinic,
    /// A field without its column.
    #[error("Read_dump field not found in dump file")]
    FieldNotFound,
    /// Coordinate columns of mixed kinds (`x` and `ys`, ...).
    #[error("Read_dump xyz fields do not have consistent scaling/wrapping")]
    MixedCoordinates,
}

/// Find the snapshot of step `nstep` in the text of a native dump file and read its
/// columns for `fields`.
fn find_snapshot(
    text: &str,
    nstep: i64,
    fields: &[Field],
) -> std::result::Result<Snapshot, SnapshotError> {
    let mut lines = text.lines();
    loop {
        let Some(head) = lines.next() else {
            return Err(SnapshotError::Missing);
        };
        if !head.starts_with("ITEM: TIMESTEP") {
            return Err(SnapshotError::Formatted);
        }
        let step = leading_int(lines.next().unwrap_or(""));
        lines.next();
        let natoms = leading_int(lines.next().unwrap_or("")).max(0) as usize;
        if step >= nstep {
            if step != nstep {
                return Err(SnapshotError::Missing);
            }
            return read_body(&mut lines, natoms, fields);
        }
        for _ in 0..5 + natoms {
            lines.next();
        }
    }
}

/// The box, column labels and atom lines after a snapshot's atom count.
fn read_body<'t>(
    lines: &mut impl Iterator<Item = &'t str>,
    natoms: usize,
    fields: &[Field],
) -> std::result::Result<Snapshot, SnapshotError> {
    let bounds = lines.next().unwrap_or("");
    if bounds.get(17..18) == Some("x") {
        return Err(SnapshotError::Triclinic);
    }
    let (mut lo, mut hi) = ([0.0; 3], [0.0; 3]);
    for d in 0..3 {
        let mut w = lines.next().unwrap_or("").split_whitespace();
        lo[d] = w.next().map_or(0.0, atof);
        hi[d] = w.next().map_or(0.0, atof);
    }
    let header = lines.next().unwrap_or("");
    let labels: Vec<&str> = header
        .get("ITEM: ATOMS ".len()..)
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let find = |name: &str| labels.iter().position(|l| *l == name);
    let mut index = Vec::new();
    // UNSET, then (scaled, wrapped) of the first coordinate column found
    let mut coord: Vec<(bool, bool)> = Vec::new();
    for f in fields {
        let name = match f {
            Field::Id => "id".to_string(),
            Field::Type => "type".to_string(),
            Field::X(d) => {
                let axis = ["x", "y", "z"][*d];
                let pick = if let Some(k) = find(axis) {
                    Some((k, (false, true)))
                } else {
                    let kinds = [
                        ("s", (true, true)),
                        ("u", (false, false)),
                        ("su", (true, false)),
                    ];
                    kinds
                        .iter()
                        .filter_map(|(s, flags)| find(&format!("{axis}{s}")).map(|k| (k, *flags)))
                        .min_by_key(|(k, _)| *k)
                };
                match pick {
                    Some((k, flags)) => {
                        index.push(k);
                        coord.push(flags);
                        continue;
                    }
                    None => return Err(SnapshotError::FieldNotFound),
                }
            }
            other => {
                let (name, _) = FIELDS
                    .iter()
                    .find(|(_, g)| g == other)
                    .ok_or(SnapshotError::FieldNotFound)?;
                (*name).to_string()
            }
        };
        index.push(find(&name).ok_or(SnapshotError::FieldNotFound)?);
    }
    if coord.iter().any(|c| *c != coord[0]) {
        return Err(SnapshotError::MixedCoordinates);
    }
    let (scaled, wrapped) = coord.first().copied().unwrap_or((false, false));
    let mut rows = Vec::with_capacity(natoms);
    for _ in 0..natoms {
        let words: Vec<&str> = lines.next().unwrap_or("").split_whitespace().collect();
        rows.push(
            index
                .iter()
                .map(|&k| words.get(k).map_or(0.0, |w| atof(w)))
                .collect(),
        );
    }
    Ok(Snapshot {
        lo,
        hi,
        scaled,
        wrapped,
        rows,
    })
}

/// `read_dump FILE NSTEP FIELD ... [box|replace|purge|trim|add|scaled|wrapped yes|no]
/// [format native]`.
pub fn read_dump(a: &Args, ctx: &mut Ctx) -> Result {
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Read_dump command before simulation box is defined"));
    }
    if a.len() < 2 {
        return Err(a
            .error(a.len().saturating_sub(1), ILLEGAL)
            .with_help("read_dump FILE NSTEP FIELD ... [KEYWORD VALUE ...]"));
    }
    let name = a.word(0)?;
    let nstep = leading_int(a.word(1)?).max(0);
    let o = parse(a, ctx)?;
    if ctx.sys.mode == Mode::Check {
        // the file is usually written by the run itself: a dry run only moves the step
        ctx.sim.reset_timestep(nstep);
        return Ok(());
    }
    if name.contains('*') {
        return Err(a.unsupported(0, "read_dump of several files (a * in the file name)"));
    }
    ctx.out.screen("Scanning dump file ...\n");
    let text = if name.ends_with(".gz") {
        crate::io::diff::read_text(&ctx.sys.resolve(name).to_string_lossy())
            .map_err(|e| e.to_string())
    } else {
        ctx.sys.read(name).map_err(|e| e.to_string())
    }
    .map_err(|m| a.file_error(0, format!("Cannot open file {name}: {m}")))?;
    let snap = find_snapshot(&text, nstep, &o.fields).map_err(|e| a.error(0, e.to_string()))?;
    ctx.sim.reset_timestep(nstep);
    ctx.out.screen("Reading snapshot from dump file ...\n");
    let before = ctx.sim.particles.len();
    let counts = apply(ctx, &o, &snap);
    if o.boxflag {
        let dims = if ctx.sim.dimension == 2 { 2 } else { 3 };
        let domain = &mut ctx.sim.domain;
        domain.lo[..dims].copy_from_slice(&snap.lo[..dims]);
        domain.hi[..dims].copy_from_slice(&snap.hi[..dims]);
        domain
            .reset_initial()
            .map_err(|e| a.error(0, e.to_string()))?;
    }
    let sim = &mut *ctx.sim;
    let p = &mut sim.particles;
    for (x, image) in p.x.iter_mut().zip(p.image.iter_mut()) {
        sim.domain.remap(x, image);
    }
    let line = crate::commands::change_box::orthogonal_box_line(sim.domain.lo, sim.domain.hi);
    let after = sim.particles.len();
    ctx.say(&line);
    let [purged, replaced, trimmed] = counts;
    ctx.say(&format!(
        "  {before} atoms before read\n  {} atoms in snapshot\n  {purged} atoms purged\n  \
         {replaced} atoms replaced\n  {trimmed} atoms trimmed\n  0 atoms added\n  {after} atoms after read\n",
        snap.rows.len()
    ));
    Ok(())
}

/// Purge, replace and trim as LIGGGHTS does; returns the purged, replaced and trimmed counts.
fn apply(ctx: &mut Ctx, o: &Options, snap: &Snapshot) -> [usize; 3] {
    let p = &mut ctx.sim.particles;
    let mut purged = 0;
    if o.purge {
        purged = p.len();
        p.truncate(0);
    }
    let map: std::collections::HashMap<i64, usize> =
        p.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    let mut seen = vec![false; p.len()];
    let mut replaced = 0;
    let (lo, len) = (snap.lo, [0, 1, 2].map(|d| snap.hi[d] - snap.lo[d]));
    for row in &snap.rows {
        let Some(&m) = map.get(&(row[0] as i32 as i64)) else {
            continue;
        };
        seen[m] = true;
        if !o.replace {
            continue;
        }
        replaced += 1;
        let mut image = p.image[m];
        for (f, &value) in o.fields.iter().zip(row).skip(1) {
            match *f {
                Field::X(d) => {
                    p.x[m][d] = if snap.scaled {
                        value * len[d] + lo[d]
                    } else {
                        value
                    }
                }
                Field::V(d) => p.v[m][d] = value,
                Field::Omega(d) => p.omega[m][d] = value,
                Field::F(d) => p.f[m][d] = value,
                Field::Image(d) => image[d] = value as i32,
                Field::Radius => p.radius[m] = value,
                Field::Mass => p.mass[m] = value,
                Field::Density => p.density[m] = value,
                Field::Id | Field::Type => {}
            }
        }
        if !snap.wrapped {
            image = [0; 3];
        }
        p.image[m] = image;
    }
    let mut trimmed = 0;
    if o.trim {
        let remove: Vec<bool> = seen.iter().map(|s| !s).collect();
        trimmed = remove.iter().filter(|r| **r).count();
        p.remove_filling_from_last(&remove);
    }
    [purged, replaced, trimmed]
}

#[cfg(test)]
mod tests {
    use super::*;

    const DUMP: &str = "ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS ff ff ff\n\
        0 1\n0 2\n0 3\nITEM: ATOMS id type x y z radius\n1 1 0.5 0.25 0.125 0.01\n\
        ITEM: TIMESTEP\n200\nITEM: NUMBER OF ATOMS\n2\nITEM: BOX BOUNDS ff ff ff\n\
        -1 1\n0 2\n0 3\nITEM: ATOMS id type xs ys zs radius\n2 1 0.5 0.25 0.5 0.02\n\
        1 1 0 1 1 0.03\n";

    #[test]
    fn finds_the_step_and_reads_scaled_columns() {
        let fields = [
            Field::Id,
            Field::Type,
            Field::X(0),
            Field::X(1),
            Field::Radius,
        ];
        let s = find_snapshot(DUMP, 200, &fields).unwrap();
        assert!(s.scaled && s.wrapped);
        assert_eq!(s.lo, [-1.0, 0.0, 0.0]);
        assert_eq!(
            s.rows,
            vec![
                vec![2.0, 1.0, 0.5, 0.25, 0.02],
                vec![1.0, 1.0, 0.0, 1.0, 0.03]
            ]
        );
        let e = find_snapshot(DUMP, 150, &fields).unwrap_err();
        assert_eq!(
            e.to_string(),
            "Dump file does not contain requested snapshot"
        );
        let e = find_snapshot(DUMP, 100, &[Field::Id, Field::V(0)]).unwrap_err();
        assert_eq!(e.to_string(), "Read_dump field not found in dump file");
    }
}
