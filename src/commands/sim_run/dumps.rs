//! `dump`, `dump_modify` and `undump`.

use super::*;
use crate::engine::sim::Dump;

/// `dump ID GROUP STYLE N FILE ...`: the style's own file builds the dump (see
/// [`crate::commands::dump`]).
pub(in crate::commands) fn dump(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(5..=usize::MAX, "dump ID GROUP custom N FILE columns...")?;
    let (id, group, style) = (a.word(0)?, a.word(1)?, a.word(2)?);
    let bit = ctx
        .sim
        .group_bit(group)
        .ok_or_else(|| a.error(1, "Could not find dump group ID"))?;
    if ctx.sim.dumps.iter().any(|d| d.id == id) {
        return Err(a.error(0, "Reuse of dump ID"));
    }
    let every = a.int(3)?;
    if every <= 0 {
        return Err(a.error(3, "Illegal dump command"));
    }
    let file = a.word(4)?;
    let row = crate::commands::dump::TABLE.row_for(a, "dump")?;
    let def = crate::commands::dump::DumpDef {
        id,
        group,
        bit,
        style,
        every,
        file,
    };
    let (layout, dump_style) = (row.build)(a, ctx, &def)?;
    ctx.sim.dumps.push(Dump {
        id: id.to_string(),
        group: bit,
        every,
        file: ctx.sys.resolve(file).to_string_lossy().into_owned(),
        layout,
        last_written: None,
        handle: None,
        first: false,
        pad: 0,
        style: dump_style,
    });
    Ok(())
}

/// Every `dump_modify` keyword LIGGGHTS 3.8.0 knows (Dump's own, its sort buffer's, and
/// those of its custom, VTK, xyz, local and image dumps); any other is its "Illegal
/// dump_modify command".
const LIGGGHTS_KEYWORDS: &[&str] = &[
    "append",
    "buffer",
    "every",
    "fileper",
    "first",
    "flush",
    "format",
    "nfile",
    "pad",
    "sort",
    "region",
    "label",
    "element",
    "thresh",
    "binary",
    "compressor",
    "acolor",
    "adiam",
    "amap",
    "backcolor",
    "bcolor",
    "bdiam",
    "boxcolor",
    "color",
];

/// `dump_modify ID KEYWORD VALUE ...`: the settings every dump has, and the keywords the
/// dump's style takes.
pub(in crate::commands) fn dump_modify(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(3..=usize::MAX, "dump_modify ID keyword value ...")?;
    let id = a.word(0)?;
    let k = ctx
        .sim
        .dumps
        .iter()
        .position(|d| d.id == id)
        .ok_or_else(|| a.error(0, "Could not find dump_modify ID"))?;
    // LIGGGHTS takes any format string here and checks it when the run starts: a bad one
    // is reported after the other keywords (whose errors LIGGGHTS raises first)
    let mut bad_format = None;
    let mut i = 1;
    while i < a.len() {
        let dump = &mut ctx.sim.dumps[k];
        match a.word(i)? {
            "sort" => match a.word(i + 1)? {
                "id" => dump.layout.sort_by_id = true,
                "off" => dump.layout.sort_by_id = false,
                _ => return Err(a.unsupported(i + 1, "dump_modify sort by column")),
            },
            // `none` goes back to the default formats
            "format" if a.word(i + 1)? == "none" => dump.layout.format = None,
            "format" => {
                if let Err(m) = dump.layout.set_format(a.word(i + 1)?) {
                    bad_format.get_or_insert(a.error(i + 1, &m));
                }
            }
            "first" => dump.first = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "pad" => {
                let n = a.int(i + 1)?;
                if n < 0 {
                    return Err(a.error(i + 1, "Illegal dump_modify command"));
                }
                dump.pad = n as usize;
            }
            "every" => {
                let n = a.int(i + 1)?;
                if n <= 0 {
                    return Err(a.error(i + 1, "Illegal dump_modify command"));
                }
                dump.every = n;
            }
            "flush" => {
                a.word_in(i + 1, &["yes", "no"])?;
            }
            "element" => {
                let n = ctx.sim.ntypes as usize;
                if i + n >= a.len() {
                    return Err(a.error(i, "Dump modify element names do not match atom types"));
                }
                let names: Vec<String> = (i + 1..=i + n)
                    .map(|k| a.word(k).map(str::to_string))
                    .collect::<std::result::Result<_, _>>()?;
                if let Some(e) = ctx.sim.dumps[k].style.elements() {
                    *e = names;
                }
                i += n + 1;
                continue;
            }
            "binary" if dump.style.takes_binary() == Some(true) => {
                dump.layout.binary = a.word_in(i + 1, &["yes", "no"])? == "yes";
            }
            // LIGGGHTS's text dumps take no `binary` keyword (a `.bin` file name makes
            // `dump custom` binary)
            "binary" if dump.style.takes_binary() == Some(false) => {
                return Err(a
                    .error(i, "Illegal dump_modify command")
                    .with_help("dump custom writes LAMMPS's binary format to a file named *.bin"));
            }
            // a value where a keyword belongs (`format float %.10g`, the newer LAMMPS syntax)
            other if !other.starts_with(|c: char| c.is_ascii_alphabetic()) => {
                return Err(a.error(i, "Illegal dump_modify command"));
            }
            other if LIGGGHTS_KEYWORDS.contains(&other) => {
                return Err(a.unsupported(i, &format!("dump_modify {other}")))
            }
            // a keyword of newer LIGGGHTS versions or of LAMMPS (`domainfile` of
            // LIGGGHTS-PFM's VTK dumps)
            _ => return Err(a.error(i, "Illegal dump_modify command")),
        }
        i += 2;
    }
    bad_format.map_or(Ok(()), Err)
}

/// `undump ID`.
pub(super) fn undump(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "undump ID")?;
    remove_by_id(&mut ctx.sim.dumps, |d| &d.id, a, "Could not find undump ID")
}
