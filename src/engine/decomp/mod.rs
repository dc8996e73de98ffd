//! Domain decomposition for runs on several ranks (LIGGGHTS's brick decomposition): each
//! rank owns the particles in its sub-domain of the box, keeps copies (ghosts) of the
//! particles within the ghost cutoff of it, refreshes them every step and sends the
//! forces computed on ghosts back to their owners. Written over [`crate::util::comm::Comm`],
//! so the same code runs on one process, under MPI, or on threads in tests. Runs on more
//! than one rank use it (`engine::sim` ranks module) with LIGGGHTS's granular `newton off`
//! pairs, so they need no reverse communication.
//!
//! A step on several ranks: wrap positions into the periodic box, write the pair list's
//! contact history into the particles' partner lists ([`PartnerHistory::from_pairs`]),
//! [`migrate`], [`borders`], build the neighbour list over owned particles and ghosts,
//! take the history back ([`PartnerHistory::to_pairs`]); then each step [`forward`],
//! compute forces, and [`reverse`] (or [`reverse_contributions`] and [`canonical_sum`] for
//! the same bits on any rank count).

pub mod balance;
pub mod borders;
pub mod decomposition;
pub mod forward;
pub mod history;
pub mod migrate;
pub mod pack;

pub use borders::{borders, GhostPlan, Halo, Swap};
pub use decomposition::{global_extent, Decomposition};
pub use forward::{
    canonical_sum, forward, forward_with, reverse, reverse_contributions, Contribution, SwapBuffers,
};
pub use migrate::{migrate, migrate_anywhere};
pub use pack::{DecompError, PartnerHistory};
