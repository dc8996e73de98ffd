//! Typed access to a command's arguments with errors that point at the offending word.

use crate::commands::error::{At, CommandError};
use crate::commands::suggest::did_you_mean;
use crate::commands::CommandLine;
use crate::engine::error::EngineError;
use crate::util::numbers::{inumeric, numeric};

/// A command's arguments (after the command name).
pub struct Args<'a> {
    /// The command.
    pub cmd: &'a CommandLine,
}

impl<'a> Args<'a> {
    /// Number of arguments.
    pub fn len(&self) -> usize {
        self.cmd.nargs()
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// An invalid value at argument `i`, in LIGGGHTS's words.
    pub fn error(&self, i: usize, message: impl std::fmt::Display) -> CommandError {
        CommandError::InvalidValue {
            message: message.to_string(),
            at: At::Arg(i),
            help: None,
        }
    }

    /// A file named at argument `i` that cannot be opened, read or written.
    pub fn file_error(&self, i: usize, message: impl std::fmt::Display) -> CommandError {
        CommandError::File {
            message: message.to_string(),
            at: At::Arg(i),
            help: None,
        }
    }

    /// A "not supported yet" report pointing at argument `i`.
    pub fn unsupported(&self, i: usize, what: &str) -> CommandError {
        CommandError::unsupported(what, At::Arg(i))
    }

    /// The engine's refusal pointing at argument `i`: invalid input as [`Args::error`], a
    /// feature regolith does not run yet as [`Args::unsupported`].
    pub fn engine_error(&self, i: usize, e: EngineError) -> CommandError {
        match e {
            EngineError::Unsupported(what) => self.unsupported(i, &what),
            other => self.error(i, other.to_string()),
        }
    }

    /// An unknown keyword at `i`, with the nearest of `known`.
    pub fn keyword_error(&self, i: usize, known: &[&str]) -> CommandError {
        let word = self.cmd.arg(i).unwrap_or("");
        let help = did_you_mean(word, known)
            .unwrap_or_else(|| format!("expected one of: {}", known.join(", ")));
        CommandError::UnknownName {
            message: format!(
                "Illegal {} command: unknown keyword '{word}'",
                self.cmd.name()
            ),
            at: At::Arg(i),
            help,
        }
    }

    /// A missing or extra argument, reported at the last word with what was expected.
    fn bad_count(&self, expected: String) -> CommandError {
        CommandError::BadArgument {
            message: format!("Illegal {} command", self.cmd.name()),
            at: At::Arg(self.len().saturating_sub(1)),
            expected,
        }
    }

    /// Check the argument count.
    pub fn count(
        &self,
        range: std::ops::RangeInclusive<usize>,
        usage: &str,
    ) -> Result<(), CommandError> {
        if range.contains(&self.len()) {
            Ok(())
        } else {
            Err(self.bad_count(format!("expected: {usage}")))
        }
    }

    /// Argument `i` as a word.
    pub fn word(&self, i: usize) -> Result<&'a str, CommandError> {
        self.cmd
            .arg(i)
            .ok_or_else(|| self.bad_count(format!("missing argument {}", i + 1)))
    }

    /// Argument `i`, which must be one of `allowed`.
    pub fn word_in(&self, i: usize, allowed: &[&str]) -> Result<&'a str, CommandError> {
        let w = self.word(i)?;
        if allowed.contains(&w) {
            Ok(w)
        } else {
            Err(self.keyword_error(i, allowed))
        }
    }

    /// Argument `i` as a real number (LIGGGHTS's rules).
    pub fn real(&self, i: usize) -> Result<f64, CommandError> {
        let w = self.word(i)?;
        numeric(w).map_err(|m| self.error(i, m))
    }

    /// Argument `i` as an integer (LIGGGHTS's rules).
    pub fn int(&self, i: usize) -> Result<i64, CommandError> {
        let w = self.word(i)?;
        inumeric(w).map_err(|m| self.error(i, m))
    }

    /// Argument `i` as an integer LIGGGHTS keeps in an int (a count): one beyond an int's
    /// range is an error naming the word.
    pub fn int32(&self, i: usize) -> Result<i64, CommandError> {
        let n = self.int(i)?;
        if n > i32::MAX as i64 || n < i32::MIN as i64 {
            let w = self.word(i)?;
            return Err(self.error(
                i,
                format!("Integer parameter '{w}' is out of range (LIGGGHTS counts it in an int, at most {})", i32::MAX),
            ));
        }
        Ok(n)
    }
}
