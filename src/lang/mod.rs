//! The pieces of the LIGGGHTS input language that commands use as well as the interpreter:
//! lines, words and `$` substitution, variables of every style, equal- and atom-style
//! formulas, what a formula can see of the engine, and the files, folder and environment a
//! deck reads (with an in-memory overlay for check mode).

pub mod error;
pub mod expr;
pub mod line;
pub mod scope;
pub mod system;
pub mod variables;

/// Commands the interpreter executes itself (the script language).
pub const SCRIPT_COMMANDS: &[&str] = &[
    "clear",
    "echo",
    "if",
    "include",
    "jump",
    "label",
    "log",
    "next",
    "partition",
    "print",
    "quit",
    "shell",
    "variable",
];

/// The text substituted in check mode for a value only a real run can know.
pub const UNKNOWN_VALUE: &str = "?unknown?";
