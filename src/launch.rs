//! Starting under an MPI launcher (`mpirun -np N regolith ...`). A build without the `mpi`
//! feature stops at once when the launcher started more than one rank; a build with it
//! initialises MPI and learns the ranks, and hands the communicator to the run.

use crate::util::comm::{self, Ranks};

/// The ranks of this run; with MPI, the communicator too (MPI ends when this is dropped).
pub struct Launch {
    /// The ranks.
    pub ranks: Ranks,
    #[cfg(feature = "mpi")]
    _comm: Option<crate::util::comm_mpi::MpiComm>,
}

impl Launch {
    /// The communicator of a run on more than one rank, handed to the run (None on one
    /// process or without MPI).
    pub fn take_comm(&mut self) -> Option<comm::RankComm> {
        #[cfg(feature = "mpi")]
        if self.ranks.size > 1 {
            return self
                ._comm
                .take()
                .map(|c| Box::new(crate::util::comm_mpi::SendComm(c)) as comm::RankComm);
        }
        None
    }
}

/// Why this process cannot run as it was started.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LaunchError {
    /// A build without MPI started by an MPI launcher on more than one rank (the ranks).
    #[error("{}", comm::no_mpi_message(*.0))]
    NoMpi(usize),
    /// The MPI library did not start.
    #[error("MPI could not be initialised")]
    MpiInit,
}

/// Look at how this process was started.
pub fn start() -> Result<Launch, LaunchError> {
    start_with(|k| std::env::var(k).ok())
}

/// As [`start`], the environment read through `var`.
#[cfg(not(feature = "mpi"))]
pub fn start_with(var: impl Fn(&str) -> Option<String>) -> Result<Launch, LaunchError> {
    match comm::launcher_size(&var) {
        Some(n) if n > 1 => Err(LaunchError::NoMpi(n)),
        _ => Ok(Launch {
            ranks: Ranks::default(),
        }),
    }
}

/// As [`start`], the environment read through `var`.
#[cfg(feature = "mpi")]
pub fn start_with(var: impl Fn(&str) -> Option<String>) -> Result<Launch, LaunchError> {
    use crate::util::comm::Comm;
    if comm::launcher_size(&var).is_none() {
        return Ok(Launch {
            ranks: Ranks::default(),
            _comm: None,
        });
    }
    let c = crate::util::comm_mpi::MpiComm::init().ok_or(LaunchError::MpiInit)?;
    // ranks per node as LIGGGHTS's numa grid counts them: those named as the first name
    let names = c.gather_bytes(comm::host_name().as_bytes());
    let mut per_node = names
        .map(|all| {
            let first = all.iter().min().cloned().unwrap_or_default();
            all.iter().filter(|n| **n == first).count()
        })
        .unwrap_or(0)
        .to_le_bytes()
        .to_vec();
    c.broadcast_bytes(0, &mut per_node);
    let per_node = usize::from_le_bytes(per_node.try_into().unwrap_or_default()).max(1);
    Ok(Launch {
        ranks: Ranks {
            size: c.size(),
            rank: c.rank(),
            per_node,
        },
        _comm: Some(c),
    })
}

#[cfg(all(test, not(feature = "mpi")))]
mod tests {
    use super::*;

    #[test]
    fn a_build_without_mpi_refuses_more_than_one_rank() {
        let env =
            |n: &'static str| move |k: &str| (k == "OMPI_COMM_WORLD_SIZE").then(|| n.to_string());
        let e = start_with(env("3")).err().expect("refused");
        assert_eq!(e, LaunchError::NoMpi(3));
        assert!(e.to_string().contains("one of 3 MPI ranks"), "{e}");
        assert_eq!(start_with(env("1")).map(|l| l.ranks.size).ok(), Some(1));
    }
}
