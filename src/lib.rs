//! regolith: a soft-sphere discrete-element solver that runs LIGGGHTS 3.8.0 decks unchanged.
//!
//! The crate is organised as the path a deck takes: [`script`] reads and expands the input
//! language, [`commands`] maps every LIGGGHTS command and style name onto what regolith does
//! with it, [`session`] runs or checks a whole deck, and [`error`] carries the file/line
//! diagnostics every layer reports.

pub mod analyze;
pub mod bench;
pub mod cli;
pub mod commands;
pub mod engine;
pub mod error;
pub mod io;
pub mod lang;
pub mod launch;
pub mod progress;
pub mod script;
pub mod session;
pub mod state;
pub mod sweep;
pub mod tool_error;
pub mod util;
