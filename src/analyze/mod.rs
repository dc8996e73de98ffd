//! `regolith analyze`: the studies' post-processing, from dumps to numbers, CSV tables and
//! PNG figures.
//!
//! - [`chain`]: the struck chain of beads (peak force per particle, arrival times, wave speed
//!   c_w, and over a sweep of impact speeds c_w against v_im with its power-law exponent);
//! - [`channel`]: the lunar channel (sensor grid of 0.5 cm cells, wave arrival, wave and
//!   solitary speeds, bed height and dilation, initial overlap against depth);
//! - [`ring`]: the radial blast (inner/outer radius of the disturbed surface, compaction
//!   front, corrugation amplitude, azimuthal force spectrum).
//!
//! Every analysis reads text dumps (plain or gzip, one file or a `*` series) written by
//! regolith or LIGGGHTS, in SI units; times are step x dt.

pub mod args;
pub mod chain;
pub mod chain_cli;
pub mod chain_report;
pub mod channel;
pub mod channel_cli;
pub mod channel_panels;
pub mod channel_report;
pub mod fit;
pub mod overlap;
pub mod plot;
pub mod ring;
pub mod ring_cli;
pub mod ring_report;
pub mod run;
pub mod sensor;
pub mod series;
pub mod table;

use thiserror::Error;

/// What can stop an analysis.
#[derive(Debug, Error)]
pub enum AnalyzeError {
    /// A dump or log could not be read or parsed.
    #[error("{0}")]
    Read(String),
    /// A column the analysis needs is not in the dump.
    #[error("step {step}: no column {wanted} (the dump has: {have})")]
    MissingColumn {
        /// The snapshot's step.
        step: i64,
        /// The names tried.
        wanted: String,
        /// The columns present.
        have: String,
    },
    /// The data do not allow the measurement (too few points, no wave arrival, ...).
    #[error("{0}")]
    Fit(String),
    /// The options are inconsistent.
    #[error("{0}")]
    Usage(String),
    /// Writing a table or figure failed.
    #[error("{path}: {message}")]
    Write {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
    /// Running the deck failed.
    #[error("{0}")]
    Run(String),
}

/// The time step (s) of the last `timestep` command echoed in a LIGGGHTS or regolith log.
pub fn dt_from_log(text: &str) -> Option<f64> {
    text.lines().rev().find_map(|l| {
        let mut w = l.split_whitespace();
        (w.next() == Some("timestep"))
            .then(|| w.next()?.parse::<f64>().ok())
            .flatten()
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn dt_from_an_echoed_log() {
        let log = "variable dt equal 1e-6\ntimestep ${dt}\ntimestep        1e-06\nrun 10\n";
        assert_eq!(super::dt_from_log(log), Some(1e-6));
        assert_eq!(super::dt_from_log("run 1\n"), None);
    }
}
