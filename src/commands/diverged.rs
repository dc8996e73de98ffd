//! `check` after an unsupported command: the dry run skipped it, so its state (atoms, fixes,
//! computes, groups) no longer matches LIGGGHTS's and errors about that state may be
//! artefacts. Errors that follow from a command's own words or files alone are still real.

use crate::error::Diagnostic;

/// Words of LIGGGHTS's messages about a command's own arguments or files (seeds that are not
/// large primes, files that cannot be read, illegal keywords and numbers, unknown models).
const OWN_WORDS: &[&str] = &[
    "random seed",
    "Seed ",
    "Invalid seed",
    "Cannot open",
    "No such file",
    "restart file",
    "Illegal ",
    "Expected ",
    "is not a number",
    "Expected integer",
    "Expected floating point",
    "unknown keyword",
    "out of range",
    "Invalid model",
    "Unknown argument",
    "wrong keyword order",
    "required for SI units",
    "required for CGS units",
    "poissonsRatio",
    "invalid weight",
];

/// Whether `d` depends only on its own command (reported even after an unsupported command).
pub fn stands_alone(d: &Diagnostic) -> bool {
    OWN_WORDS.iter().any(|w| d.message.contains(w))
}
