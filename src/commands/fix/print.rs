//! `fix print`: a line of text every N steps.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP print N "text" [file F | append F] [screen yes|no] [title T]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
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
                if ctx.sys.mode == crate::lang::system::Mode::Run {
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
    Ok(FixKind::Print(crate::engine::fixes::PrintFix {
        every,
        text,
        screen,
        file,
    }))
}
