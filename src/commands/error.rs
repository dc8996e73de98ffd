//! What can go wrong in a command, as data: one variant per kind of problem, each naming the
//! word it points at. The command boundary ([`crate::commands::Engine::execute`]) turns it
//! into a [`Diagnostic`] with the file, the line and a caret under that word, once.

use crate::commands::{registry, CommandLine};
use crate::error::{Diagnostic, Severity};
use thiserror::Error;

/// Which part of the command a problem points at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum At {
    /// Argument `i` (0-based, after the command name; past the end: the last word).
    Arg(usize),
    /// The command's name.
    Name,
    /// The command name through its style word (`fix ID GROUP style`).
    Feature,
    /// No word in particular: the report carries no caret of its own (the interpreter puts
    /// one under the command's name when it runs the line).
    Line,
}

/// A problem with one command.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CommandError {
    /// A name LIGGGHTS 3.8.0 does not have; `help` names the nearest ones.
    #[error("{message}")]
    UnknownName {
        /// LIGGGHTS's own message.
        message: String,
        /// The misspelt word.
        at: At,
        /// Nearest valid names, or what the word is not.
        help: String,
    },
    /// An argument that is missing, extra or not of the form the command takes.
    #[error("{message}")]
    BadArgument {
        /// LIGGGHTS's own message.
        message: String,
        /// The offending word.
        at: At,
        /// What was expected (`expected: fix ID GROUP STYLE ...`, `missing argument 4`).
        expected: String,
    },
    /// A value LIGGGHTS refuses, in its own words.
    #[error("{message}")]
    InvalidValue {
        /// LIGGGHTS's own message.
        message: String,
        /// The offending word.
        at: At,
        /// How to fix it, if there is more to say.
        help: Option<String>,
    },
    /// A file that cannot be opened, read or written.
    #[error("{message}")]
    File {
        /// What went wrong, naming the file.
        message: String,
        /// The word naming the file.
        at: At,
        /// How to fix it, if there is more to say.
        help: Option<String>,
    },
    /// Valid LIGGGHTS that regolith does not run yet.
    #[error("{feature}: not supported yet")]
    Unsupported {
        /// The feature, as the deck names it (`fix insert/rate/region`).
        feature: String,
        /// The word naming it.
        at: At,
        /// What to do instead, if anything.
        help: Option<String>,
    },
    /// Valid LIGGGHTS that regolith will not run (CFD coupling, SPH), and why.
    #[error("{feature}: {reason}")]
    OutOfScope {
        /// The feature, as the deck names it.
        feature: String,
        /// The word naming it.
        at: At,
        /// Why regolith does not run it.
        reason: String,
        /// Where to run it instead.
        help: String,
    },
    /// A problem already reported in full, with its own location (e.g. at the `fix
    /// property/global` line that set a value `run` refuses).
    #[error("{0}")]
    Reported(Diagnostic),
}

impl CommandError {
    /// An unsupported feature, pointed at argument `i`.
    pub fn unsupported(feature: impl Into<String>, at: At) -> CommandError {
        CommandError::Unsupported {
            feature: feature.into(),
            at,
            help: None,
        }
    }

    /// Add how to fix it (the expected form, for a bad argument).
    pub fn with_help(mut self, text: impl Into<String>) -> CommandError {
        let text = text.into();
        if text.is_empty() {
            return self;
        }
        match &mut self {
            CommandError::UnknownName { help, .. } | CommandError::OutOfScope { help, .. } => {
                *help = text
            }
            CommandError::BadArgument { expected, .. } => *expected = text,
            CommandError::InvalidValue { help, .. }
            | CommandError::File { help, .. }
            | CommandError::Unsupported { help, .. } => *help = Some(text),
            CommandError::Reported(d) => d.help = Some(text),
        }
        self
    }

    /// What was expected, the nearest names, or how to fix it, if anything.
    pub fn help(&self) -> Option<&str> {
        match self {
            CommandError::UnknownName { help, .. } | CommandError::OutOfScope { help, .. } => {
                Some(help)
            }
            CommandError::BadArgument { expected, .. } => Some(expected),
            CommandError::InvalidValue { help, .. }
            | CommandError::File { help, .. }
            | CommandError::Unsupported { help, .. } => help.as_deref(),
            CommandError::Reported(d) => d.help.as_deref(),
        }
    }

    /// How bad it is: unsupported and out-of-scope features are not deck errors.
    pub fn severity(&self) -> Severity {
        match self {
            CommandError::Unsupported { .. } | CommandError::OutOfScope { .. } => {
                Severity::Unsupported
            }
            CommandError::Reported(d) => d.severity,
            _ => Severity::Error,
        }
    }

    /// The report of this problem in `cmd`, with a caret under the word it points at.
    pub fn into_diagnostic(self, cmd: &CommandLine) -> Diagnostic {
        let severity = self.severity();
        let message = self.to_string();
        let (at, help) = match self {
            CommandError::Reported(d) => return d,
            CommandError::UnknownName { at, help, .. } => (at, Some(help)),
            CommandError::BadArgument { at, expected, .. } => (at, Some(expected)),
            CommandError::InvalidValue { at, help, .. }
            | CommandError::File { at, help, .. }
            | CommandError::Unsupported { at, help, .. } => (at, help),
            CommandError::OutOfScope { at, help, .. } => (at, Some(help)),
        };
        let mut d = Diagnostic::error(message);
        d.severity = severity;
        let d = match at {
            At::Arg(i) => d.with_source(&cmd.text, Some(cmd.span(i))),
            At::Name => d.with_source(&cmd.text, Some((cmd.words[0].start, cmd.words[0].end))),
            At::Feature => d.with_source(&cmd.text, Some(registry::feature_span(cmd))),
            At::Line => d,
        };
        d.with_help(help.unwrap_or_default())
    }
}

impl From<Diagnostic> for CommandError {
    fn from(d: Diagnostic) -> CommandError {
        CommandError::Reported(d)
    }
}
