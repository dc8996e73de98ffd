//! Files regolith writes and reads: dumps (and, later, logs, restarts and data files).

pub mod dump;
pub mod dump_compare;
