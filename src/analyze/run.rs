//! `--run DECK`: run a deck (in regolith, or Debian's LIGGGHTS with `--liggghts`) from its own
//! folder, as LIGGGHTS decks expect, before analysing the dumps it writes.

use std::path::{Path, PathBuf};
use std::process::Command;

use super::AnalyzeError;

/// A deck to run before the analysis.
#[derive(Debug, Clone, PartialEq)]
pub struct RunRequest {
    /// The deck file.
    pub deck: PathBuf,
    /// `-var NAME VALUE` pairs.
    pub vars: Vec<(String, String)>,
    /// Run `liggghts` instead of this program.
    pub liggghts: bool,
}

impl RunRequest {
    /// The deck's folder (where it runs and writes its `post/` files).
    pub fn folder(&self) -> PathBuf {
        self.deck
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf)
    }

    /// The log file the run writes (`log.liggghts` in the deck's folder).
    pub fn log(&self) -> PathBuf {
        self.folder().join("log.liggghts")
    }

    /// Run the deck to completion with the screen output discarded (the log has it; Debian's
    /// LIGGGHTS 3.8.0 crashes in `fix insert/pack` under `-screen none`); Err if it cannot
    /// start or exits with a failure.
    pub fn run(&self) -> Result<(), AnalyzeError> {
        let file = self
            .deck
            .file_name()
            .ok_or_else(|| AnalyzeError::Usage(format!("{}: not a file", self.deck.display())))?;
        let program = if self.liggghts {
            PathBuf::from("liggghts")
        } else {
            std::env::current_exe().map_err(|e| AnalyzeError::Run(e.to_string()))?
        };
        let mut cmd = Command::new(&program);
        cmd.current_dir(self.folder()).arg("-in").arg(file).args([
            "-log",
            "log.liggghts",
            "-screen",
            "none",
        ]);
        for (name, value) in &self.vars {
            cmd.args(["-var", name, value]);
        }
        let status = cmd
            .status()
            .map_err(|e| AnalyzeError::Run(format!("cannot start {}: {e}", program.display())))?;
        if !status.success() {
            return Err(AnalyzeError::Run(format!(
                "{} failed ({status}); see {}",
                self.deck.display(),
                self.log().display()
            )));
        }
        Ok(())
    }
}

/// The time step: `dt` if given, else the last `timestep` in the log file.
pub fn resolve_dt(dt: Option<f64>, log: Option<&Path>) -> Result<f64, AnalyzeError> {
    if let Some(dt) = dt {
        return Ok(dt);
    }
    let Some(log) = log else {
        return Err(AnalyzeError::Usage(
            "the time step is needed to turn steps into seconds: give --dt SECONDS or --log LOGFILE"
                .into(),
        ));
    };
    let text = std::fs::read_to_string(log)
        .map_err(|e| AnalyzeError::Read(format!("{}: {e}", log.display())))?;
    super::dt_from_log(&text).ok_or_else(|| {
        AnalyzeError::Read(format!(
            "{}: no echoed `timestep` command; give --dt",
            log.display()
        ))
    })
}
