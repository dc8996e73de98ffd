//! `fix print`: a line of text, the deck's variables substituted, every N steps
//! (`end_of_step`).

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStep, FixStyle, StepInputs};
use crate::util::comm::Comm;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "print",
    "fix ID GROUP print N TEXT",
    &[
        kw("file", &[arg("F", Value::File)], "write to this file"),
        kw("append", &[arg("F", Value::File)], "append to this file"),
        kw("screen", &[arg("yes|no", YES_NO)], "print to the screen"),
        kw("title", &[arg("T", Value::Word)], "first line of the file"),
    ],
    "print a text every N steps",
);

/// `fix print`: a line with variables substituted every `every` steps.
pub struct Print {
    /// Print every this many steps.
    every: i64,
    /// The text, `$` references still in it.
    text: String,
    /// Also print to screen and log.
    screen: bool,
    /// The output file, if any.
    file: Option<std::io::BufWriter<std::fs::File>>,
}

impl Print {
    /// Write one substituted line where the fix sends it.
    fn emit(&mut self, line: &str, out: &mut dyn FnMut(&str)) -> Result<(), EngineError> {
        use std::io::Write;
        if self.screen {
            out(&format!("{line}\n"));
        }
        if let Some(f) = self.file.as_mut() {
            writeln!(f, "{line}")
                .and_then(|_| f.flush())
                .map_err(|e| format!("fix print: {e}"))?;
        }
        Ok(())
    }
}

impl FixStyle for Print {
    fn name(&self) -> &str {
        "print"
    }

    fn reads_computes(&self) -> bool {
        true
    }

    fn outputs_at(&self, step: i64) -> bool {
        step % self.every == 0
    }

    fn end_of_step_output(
        &mut self,
        _at: &FixStep,
        inputs: &mut dyn StepInputs,
        out: &mut dyn FnMut(&str),
    ) -> Result<(), EngineError> {
        let line = inputs.substitute(&self.text)?;
        self.emit(&line, out)
    }
}

/// `fix ID GROUP print N "text" [file F | append F] [screen yes|no] [title T]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let FixDef { id, .. } = *fix;
    a.count(
        5..=usize::MAX,
        "fix ID GROUP print N \"text\" [file F] [screen yes|no] [title T]",
    )?;
    let every = a.int(3)?;
    if every <= 0 {
        return Err(a.error(3, "Illegal fix print command"));
    }
    let text = a.word(4)?.to_string();
    let (mut screen, mut file, mut title) = (true, None, None);
    let mut i = 5;
    while i < a.len() {
        match a.word(i)? {
            kw @ ("file" | "append") => {
                let name = a.word(i + 1)?;
                // on several MPI ranks rank 0 alone writes the file (as LIGGGHTS's proc 0)
                let rank = ctx.sim.comm.as_ref().map_or(0, |c| c.rank());
                if ctx.sys.mode == crate::lang::system::Mode::Run && rank == 0 {
                    let f = std::fs::OpenOptions::new()
                        .create(true)
                        .write(true)
                        .append(kw == "append")
                        .truncate(kw == "file")
                        .open(name)
                        .map_err(|_| {
                            a.file_error(i + 1, format!("Cannot open fix print file {name}"))
                        })?;
                    file = Some(std::io::BufWriter::new(f));
                }
            }
            "screen" => screen = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "title" => title = Some(a.word(i + 1)?.to_string()),
            _ => return Err(a.error(i, "Illegal fix print command")),
        }
        i += 2;
    }
    if let Some(f) = file.as_mut() {
        use std::io::Write;
        let head = match title.as_deref() {
            Some("none") => None,
            Some(t) => Some(t.to_string()),
            None => Some(format!("# Fix print output for fix {id}")),
        };
        if let Some(h) = head {
            writeln!(f, "{h}")
                .and_then(|_| f.flush())
                .map_err(|e| a.error(0, format!("fix print: {e}")))?;
        }
    }
    Ok(Box::new(Print {
        every,
        text,
        screen,
        file,
    }))
}
