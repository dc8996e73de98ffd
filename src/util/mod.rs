//! The bottom layer, shared by every other: numbers printed exactly as LIGGGHTS's C printf
//! prints them, LIGGGHTS's random-number streams, and numbers read from words as LIGGGHTS reads
//! them. Nothing here knows about decks, commands or the engine.

pub mod comm;
#[cfg(feature = "mpi")]
pub mod comm_mpi;
pub mod comm_threads;
pub mod format;
pub mod huge_pages;
pub mod numbers;
pub mod random;
pub mod team;
pub mod tuner;
