//! What stops one of regolith's own commands (`sweep`, `bench`, `analyze`'s figures, the
//! command line's accelerator switches): typed here, printed once by `main`.

use std::path::{Path, PathBuf};

use thiserror::Error;

/// Why a command of regolith's own could not do its work.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ToolError {
    /// An option or argument that cannot be used: the option and what it expects.
    #[error("{0}")]
    Usage(String),
    /// A file or folder that cannot be read or written.
    #[error("{}: {why}", path.display())]
    File {
        /// The file or folder.
        path: PathBuf,
        /// The system's reason.
        why: String,
    },
    /// A file or log that does not hold what was expected of it.
    #[error("{0}")]
    Content(String),
    /// A figure that could not be drawn.
    #[error("{0}")]
    Plot(String),
    /// A program (regolith, LIGGGHTS) that could not be started or did not finish its run.
    #[error("{0}")]
    Run(String),
}

impl ToolError {
    /// The refusal of the file system at `path`, for `map_err`.
    pub fn file(path: &Path) -> impl FnOnce(std::io::Error) -> ToolError + '_ {
        move |e| ToolError::File {
            path: path.to_path_buf(),
            why: e.to_string(),
        }
    }

    /// An option or argument that cannot be used.
    pub fn usage(message: impl Into<String>) -> ToolError {
        ToolError::Usage(message.into())
    }

    /// A file or log that does not hold what was expected.
    pub fn content(message: impl Into<String>) -> ToolError {
        ToolError::Content(message.into())
    }
}

/// An analysis or figure that failed: a file it could not write names the file.
impl From<crate::analyze::AnalyzeError> for ToolError {
    fn from(e: crate::analyze::AnalyzeError) -> ToolError {
        match e {
            crate::analyze::AnalyzeError::Write { path, message } => ToolError::File {
                path: PathBuf::from(path),
                why: message,
            },
            other => ToolError::Content(other.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_error_names_the_file_and_the_reason() {
        let e = std::fs::read_to_string("/nonexistent/regolith/x.csv")
            .map_err(ToolError::file(Path::new("/nonexistent/regolith/x.csv")))
            .unwrap_err();
        let text = e.to_string();
        assert!(text.starts_with("/nonexistent/regolith/x.csv: "), "{text}");
        assert!(text.contains("No such file"), "{text}");
    }
}
