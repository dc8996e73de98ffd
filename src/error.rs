//! Diagnostics: every problem regolith reports names a file, a line, the offending word and
//! what was expected, and maps onto a stable process exit status.

use std::fmt;

/// Process exit statuses, stable across releases (documented in README.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExitStatus {
    /// The deck ran (or checked) cleanly.
    Success = 0,
    /// The deck is invalid or failed while running (LIGGGHTS's `ERROR:` cases).
    DeckError = 1,
    /// The command line itself was wrong.
    Usage = 2,
    /// The deck is valid LIGGGHTS but uses something regolith does not support yet.
    Unsupported = 3,
}

/// Where in the input a diagnostic points: file name as given, 1-based line number.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The script's name as the user gave it (`-` for standard input).
    pub file: String,
    /// 1-based line number of the first physical line of the command.
    pub line: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.file, self.line)
    }
}

/// How bad a diagnostic is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Severity {
    /// Invalid input: LIGGGHTS would stop here too.
    Error,
    /// Valid LIGGGHTS that regolith does not support yet.
    Unsupported,
    /// Worth saying, not fatal.
    Warning,
}

/// One reported problem. It is one pointer wide (its parts live on the heap), so the
/// `Result`s that carry it stay small; its parts read as fields through [`Report`].
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnostic(Box<Report>);

/// The parts of a [`Diagnostic`].
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Error, unsupported feature or warning.
    pub severity: Severity,
    /// The message; for errors LIGGGHTS also raises, its own wording comes first.
    pub message: String,
    /// Script file and line, when the problem comes from a script.
    pub location: Option<Location>,
    /// The command line as executed (after `$` substitution).
    pub source: Option<String>,
    /// Byte range of the offending word inside `source`.
    pub span: Option<(usize, usize)>,
    /// What was expected, nearest valid names, or how to fix it.
    pub help: Option<String>,
}

impl std::ops::Deref for Diagnostic {
    type Target = Report;
    fn deref(&self) -> &Report {
        &self.0
    }
}

impl std::ops::DerefMut for Diagnostic {
    fn deref_mut(&mut self) -> &mut Report {
        &mut self.0
    }
}

impl From<Report> for Diagnostic {
    fn from(report: Report) -> Diagnostic {
        Diagnostic(Box::new(report))
    }
}

impl Diagnostic {
    /// A plain error with a message and nothing else yet.
    pub fn error(message: impl Into<String>) -> Diagnostic {
        Diagnostic::from(Report {
            severity: Severity::Error,
            message: message.into(),
            location: None,
            source: None,
            span: None,
            help: None,
        })
    }

    /// A "not supported yet" report for a valid LIGGGHTS feature.
    pub fn unsupported(what: impl Into<String>) -> Diagnostic {
        let mut d = Diagnostic::error(format!("{}: not supported yet", what.into()));
        d.severity = Severity::Unsupported;
        d
    }

    /// A warning.
    pub fn warning(message: impl Into<String>) -> Diagnostic {
        let mut d = Diagnostic::error(message);
        d.severity = Severity::Warning;
        d
    }

    /// Attach what was expected or the nearest names.
    pub fn with_help(mut self, help: impl Into<String>) -> Diagnostic {
        let help = help.into();
        if !help.is_empty() {
            self.help = Some(help);
        }
        self
    }

    /// Attach the command text and the byte range of the offending word.
    pub fn with_source(mut self, source: &str, span: Option<(usize, usize)>) -> Diagnostic {
        if self.source.is_none() {
            self.source = Some(source.to_string());
            self.span = span;
        }
        self
    }

    /// Attach a location unless one is already set (the innermost location wins).
    pub fn at(mut self, location: &Location) -> Diagnostic {
        if self.location.is_none() {
            self.location = Some(location.clone());
        }
        self
    }

    /// The exit status this diagnostic leads to.
    pub fn exit_status(&self) -> ExitStatus {
        match self.severity {
            Severity::Unsupported => ExitStatus::Unsupported,
            _ => ExitStatus::DeckError,
        }
    }

    /// One line: `file:line: message (help)`, as `regolith check` lists problems.
    pub fn one_line(&self) -> String {
        let mut s = String::new();
        if let Some(loc) = &self.location {
            s.push_str(&format!("{loc}: "));
        }
        if self.severity == Severity::Warning {
            s.push_str("warning: ");
        }
        s.push_str(&self.message);
        if let Some(h) = &self.help {
            s.push_str(&format!(" ({h})"));
        }
        s
    }

    /// The full report: LIGGGHTS-style first line, then location, source with a caret, help.
    pub fn render(&self) -> String {
        let head = match self.severity {
            Severity::Error => "ERROR",
            Severity::Unsupported => "ERROR (regolith)",
            Severity::Warning => "WARNING",
        };
        let mut out = format!("{head}: {}\n", self.message);
        if let Some(loc) = &self.location {
            out.push_str(&format!("  --> {loc}\n"));
            if let Some(src) = &self.source {
                let number = loc.line.to_string();
                let pad = " ".repeat(number.len());
                let shown = src.replace('\t', " ");
                out.push_str(&format!(" {pad} |\n {number} | {shown}\n"));
                if let Some((a, b)) = self.span {
                    let a = a.min(shown.len());
                    let b = b.clamp(a, shown.len());
                    let lead = shown.get(..a).map(|t| t.chars().count()).unwrap_or(a);
                    let width = shown
                        .get(a..b)
                        .map(|t| t.chars().count())
                        .unwrap_or(1)
                        .max(1);
                    out.push_str(&format!(
                        " {pad} | {}{}\n",
                        " ".repeat(lead),
                        "^".repeat(width)
                    ));
                }
            }
        }
        if let Some(h) = &self.help {
            out.push_str(&format!("  = {h}\n"));
        }
        out
    }
}

impl fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.one_line())
    }
}

impl std::error::Error for Diagnostic {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_location_caret_and_help() {
        let d = Diagnostic::error("Invalid fix style")
            .with_source("fix 1 all insert/strem", Some((10, 22)))
            .at(&Location {
                file: "in.deck".into(),
                line: 7,
            })
            .with_help("did you mean 'insert/stream'?");
        let text = d.render();
        assert!(text.starts_with("ERROR: Invalid fix style\n  --> in.deck:7\n"));
        assert!(text.contains("\n   |           ^^^^^^^^^^^^\n"), "{text}");
        assert_eq!(
            d.one_line(),
            "in.deck:7: Invalid fix style (did you mean 'insert/stream'?)"
        );
        assert_eq!(d.exit_status(), ExitStatus::DeckError);
        assert_eq!(
            Diagnostic::unsupported("fix insert/stream").exit_status(),
            ExitStatus::Unsupported
        );
    }
}
