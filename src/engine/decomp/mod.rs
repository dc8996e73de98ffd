//! Domain decomposition for runs on several ranks (LIGGGHTS's brick decomposition): each
//! rank owns the particles in its sub-domain of the box, keeps copies (ghosts) of the
//! particles within the ghost cutoff of it, refreshes them every step and sends the
//! forces computed on ghosts back to their owners. Written over [`crate::util::comm::Comm`],
//! so the same code runs on one process, under MPI, or on threads in tests. Not yet used by
//! runs: a run on more than one rank is still refused.

pub mod borders;
pub mod decomposition;
pub mod forward;
pub mod migrate;
pub mod pack;

pub use borders::{borders, GhostPlan, Halo, Swap};
pub use decomposition::Decomposition;
pub use forward::{canonical_sum, forward, reverse, reverse_contributions, Contribution};
pub use migrate::migrate;
pub use pack::{DecompError, PartnerHistory};
