//! `write_dump GROUP STYLE FILE [ARGS...] [modify DUMP_MODIFY_ARGS...]`: one snapshot now, as
//! LIGGGHTS writes it (a temporary dump `WRITE_DUMP` of the style, its `dump_modify`
//! settings, written once at the current step and deleted).

use crate::commands::CommandError;
use crate::commands::{Args, CommandLine, Ctx};
use crate::lang::line::Word;

type Result = std::result::Result<(), CommandError>;

/// The temporary dump's ID (LIGGGHTS's).
const ID: &str = "WRITE_DUMP";

/// A command line of `name` followed by `words` (each pointing at the span of the original
/// word it stands for, so that errors point into the `write_dump` line).
fn line(a: &Args, name: &str, words: &[(String, usize)]) -> CommandLine {
    let head = &a.cmd.words[0];
    let mut out = vec![Word {
        text: name.to_string(),
        start: head.start,
        end: head.end,
    }];
    for (text, original) in words {
        let (start, end) = if *original == usize::MAX {
            (head.start, head.end)
        } else {
            a.cmd.span(*original)
        };
        out.push(Word {
            text: text.clone(),
            start,
            end,
        });
    }
    CommandLine {
        words: out,
        text: a.cmd.text.clone(),
        location: a.cmd.location.clone(),
    }
}

/// `write_dump`.
pub fn write_dump(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(
        3..=usize::MAX,
        "write_dump GROUP STYLE FILE [ARGS...] [modify KEYWORD VALUE ...]",
    )?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Write_dump command before simulation box is defined"));
    }
    let modify = (0..a.len())
        .find(|&i| a.word(i) == Ok("modify"))
        .unwrap_or(a.len());
    // dump WRITE_DUMP GROUP STYLE N FILE ARGS... (LIGGGHTS passes N = 0 and writes once)
    let mut dump_words = vec![
        (ID.to_string(), usize::MAX),
        (a.word(0)?.to_string(), 0),
        (a.word(1)?.to_string(), 1),
        ("1".to_string(), usize::MAX),
    ];
    for i in 2..modify {
        dump_words.push((a.word(i)?.to_string(), i));
    }
    let dump_line = line(a, "dump", &dump_words);
    if ctx.sim.dumps.iter().any(|d| d.id == ID) {
        return Err(a.error(0, "Reuse of dump ID"));
    }
    super::sim_run::dump(&Args { cmd: &dump_line }, ctx)
        .map_err(|e| CommandError::Reported(e.into_diagnostic(&dump_line)))?;
    let result = write_now(a, ctx, modify);
    // the temporary dump goes whatever happened
    if let Some(k) = ctx.sim.dumps.iter().position(|d| d.id == ID) {
        ctx.sim.dumps.remove(k);
    }
    result
}

fn write_now(a: &Args, ctx: &mut Ctx, modify: usize) -> Result {
    if modify < a.len() {
        let mut words = vec![(ID.to_string(), usize::MAX)];
        for i in modify + 1..a.len() {
            words.push((a.word(i)?.to_string(), i));
        }
        if words.len() < 3 {
            return Err(a.error(modify, "Illegal dump_modify command"));
        }
        let modify_line = line(a, "dump_modify", &words);
        super::sim_run::dump_modify(&Args { cmd: &modify_line }, ctx)
            .map_err(|e| CommandError::Reported(e.into_diagnostic(&modify_line)))?;
    }
    if ctx.sys.mode != crate::lang::system::Mode::Run {
        return Ok(());
    }
    let k = ctx
        .sim
        .dumps
        .iter()
        .position(|d| d.id == ID)
        .expect("added above");
    // on several ranks rank 0 alone evaluates and writes the snapshot, as in a run (every
    // rank holds the whole set between runs)
    let written = if ctx.sim.writes_files() {
        let mut vars = crate::lang::scope::RunVariables::new(&mut *ctx.vars, &mut *ctx.sys);
        ctx.sim
            .write_single_dump(k, &mut vars)
            .map_err(|e| e.to_string())
    } else {
        Ok(())
    };
    let name = a.word(2)?;
    ctx.sim
        .agree_on_file(written, name)
        .map_err(|m| a.error(2, &m))
}
