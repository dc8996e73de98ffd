//! Starting under an MPI launcher (`mpirun -np N regolith ...`). A build without the `mpi`
//! feature stops at once when the launcher started more than one rank; a build with it
//! initialises MPI and learns the ranks (a run on more than one is refused for now, after the
//! deck's processor grid is reported as LIGGGHTS reports it).

use crate::util::comm::{self, Ranks};

/// The ranks of this run; with MPI, the communicator too (MPI ends when this is dropped).
pub struct Launch {
    /// The ranks.
    pub ranks: Ranks,
    #[cfg(feature = "mpi")]
    _comm: Option<crate::util::comm_mpi::MpiComm>,
}

/// Look at how this process was started: Err(message) if it cannot run as started.
pub fn start() -> Result<Launch, String> {
    start_with(|k| std::env::var(k).ok())
}

/// As [`start`], the environment read through `var`.
#[cfg(not(feature = "mpi"))]
pub fn start_with(var: impl Fn(&str) -> Option<String>) -> Result<Launch, String> {
    match comm::launcher_size(&var) {
        Some(n) if n > 1 => Err(comm::no_mpi_message(n)),
        _ => Ok(Launch {
            ranks: Ranks::default(),
        }),
    }
}

/// As [`start`], the environment read through `var`.
#[cfg(feature = "mpi")]
pub fn start_with(var: impl Fn(&str) -> Option<String>) -> Result<Launch, String> {
    use crate::util::comm::Comm;
    if comm::launcher_size(&var).is_none() {
        return Ok(Launch {
            ranks: Ranks::default(),
            _comm: None,
        });
    }
    let c = crate::util::comm_mpi::MpiComm::init()
        .ok_or_else(|| "MPI could not be initialised".to_string())?;
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
