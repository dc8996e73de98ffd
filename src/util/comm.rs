//! Communication between the processes of one run: a small trait with a single-process
//! implementation (always built) and an MPI one (only with the `mpi` feature, in
//! [`crate::util::comm_mpi`]). Also how regolith tells it was started by an MPI launcher.

/// How an all-reduce combines the ranks' values.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reduce {
    /// The sum over ranks.
    Sum,
    /// The largest value over ranks.
    Max,
    /// The smallest value over ranks.
    Min,
}

/// What the processes of one run can say to each other.
pub trait Comm {
    /// This process's rank (0-based).
    fn rank(&self) -> usize;
    /// Number of ranks.
    fn size(&self) -> usize;
    /// Wait until every rank arrives here.
    fn barrier(&self);
    /// Combine `values` element by element over all ranks; every rank gets the result.
    fn all_reduce_f64(&self, values: &mut [f64], op: Reduce);
    /// Combine one integer over all ranks; every rank gets the result.
    fn all_reduce_i64(&self, value: i64, op: Reduce) -> i64;
    /// Rank `root`'s bytes, on every rank (`bytes` is replaced on the others).
    fn broadcast_bytes(&self, root: usize, bytes: &mut Vec<u8>);
    /// Every rank's bytes, in rank order, on rank 0 (None on the others).
    fn gather_bytes(&self, bytes: &[u8]) -> Option<Vec<Vec<u8>>>;
    /// One swap with neighbours: send `bytes` to rank `to` and return the bytes rank `from`
    /// sent to this rank in the same swap (`to` and `from` may be this rank itself). Every
    /// rank calls it in the same order, as MPI's sendrecv.
    fn send_recv_bytes(&self, to: usize, from: usize, bytes: &[u8]) -> Vec<u8>;
    /// A swap of doubles whose counts both sides know (`into.len()` is what rank `from`
    /// sends): `out` to rank `to`, `into` filled from rank `from`, with no length message.
    fn send_recv_f64(&self, to: usize, from: usize, out: &[f64], into: &mut [f64]) {
        let bytes: Vec<u8> = out.iter().flat_map(|v| v.to_le_bytes()).collect();
        let got = self.send_recv_bytes(to, from, &bytes);
        for (v, b) in into.iter_mut().zip(got.chunks_exact(8)) {
            *v = f64::from_le_bytes(b.try_into().unwrap_or([0; 8]));
        }
    }
}

impl<C: Comm + ?Sized> Comm for Box<C> {
    fn rank(&self) -> usize {
        (**self).rank()
    }
    fn size(&self) -> usize {
        (**self).size()
    }
    fn barrier(&self) {
        (**self).barrier()
    }
    fn all_reduce_f64(&self, values: &mut [f64], op: Reduce) {
        (**self).all_reduce_f64(values, op)
    }
    fn all_reduce_i64(&self, value: i64, op: Reduce) -> i64 {
        (**self).all_reduce_i64(value, op)
    }
    fn broadcast_bytes(&self, root: usize, bytes: &mut Vec<u8>) {
        (**self).broadcast_bytes(root, bytes)
    }
    fn gather_bytes(&self, bytes: &[u8]) -> Option<Vec<Vec<u8>>> {
        (**self).gather_bytes(bytes)
    }
    fn send_recv_bytes(&self, to: usize, from: usize, bytes: &[u8]) -> Vec<u8> {
        (**self).send_recv_bytes(to, from, bytes)
    }
    fn send_recv_f64(&self, to: usize, from: usize, out: &[f64], into: &mut [f64]) {
        (**self).send_recv_f64(to, from, out, into)
    }
}

/// The communicator a run on several ranks uses (MPI's world, or threads in tests).
pub type RankComm = Box<dyn Comm + Send>;

/// One process: every collective is the identity.
#[derive(Debug, Clone, Copy, Default)]
pub struct Single;

impl Comm for Single {
    fn rank(&self) -> usize {
        0
    }
    fn size(&self) -> usize {
        1
    }
    fn barrier(&self) {}
    fn all_reduce_f64(&self, _values: &mut [f64], _op: Reduce) {}
    fn all_reduce_i64(&self, value: i64, _op: Reduce) -> i64 {
        value
    }
    fn broadcast_bytes(&self, _root: usize, _bytes: &mut Vec<u8>) {}
    fn gather_bytes(&self, bytes: &[u8]) -> Option<Vec<Vec<u8>>> {
        Some(vec![bytes.to_vec()])
    }
    fn send_recv_bytes(&self, _to: usize, _from: usize, bytes: &[u8]) -> Vec<u8> {
        bytes.to_vec()
    }
}

/// The environment variables MPI launchers set to the number of ranks (Open MPI, MPICH's
/// and Slurm's PMI).
pub const SIZE_VARIABLES: &[&str] = &["OMPI_COMM_WORLD_SIZE", "PMI_SIZE"];

/// The number of ranks an MPI launcher started, read from its environment variables
/// (`var` looks one up): None when none is set; PMIx alone gives no size, only this
/// process's rank (`PMIX_RANK`), so a rank above 0 means at least two.
pub fn launcher_size(var: impl Fn(&str) -> Option<String>) -> Option<usize> {
    for name in SIZE_VARIABLES {
        if let Some(n) = var(name).and_then(|v| v.trim().parse::<usize>().ok()) {
            return Some(n);
        }
    }
    var("PMIX_RANK")
        .and_then(|v| v.trim().parse::<usize>().ok())
        .map(|r| if r > 0 { r + 1 } else { 1 })
}

/// This process's rank as the MPI launcher's environment variables give it (0 if none).
pub fn launcher_rank(var: impl Fn(&str) -> Option<String>) -> usize {
    ["OMPI_COMM_WORLD_RANK", "PMI_RANK", "PMIX_RANK"]
        .iter()
        .find_map(|name| var(name).and_then(|v| v.trim().parse::<usize>().ok()))
        .unwrap_or(0)
}

/// The ranks of a run: how many, which one this process is, and how many share its node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Ranks {
    /// Number of ranks (1 without an MPI launcher).
    pub size: usize,
    /// This process's rank.
    pub rank: usize,
    /// Ranks on the node (LIGGGHTS's `numa` grid: those named as the first node name).
    pub per_node: usize,
}

impl Default for Ranks {
    fn default() -> Self {
        Ranks {
            size: 1,
            rank: 0,
            per_node: 1,
        }
    }
}

/// The message of a build without MPI started on `n` ranks.
pub fn no_mpi_message(n: usize) -> String {
    format!(
        "this regolith was built without MPI, but was started as one of {n} MPI ranks; \
         run it as one process (without mpirun), or build it with MPI: \
         cargo build --release --features mpi (needs an MPI library such as OpenMPI and libclang)"
    )
}

/// The message with which a run on more than one rank is refused.
pub const MANY_RANKS: &str = "runs on more than one MPI rank";

/// This machine's name, as MPI reports a processor's name (empty if unknown).
pub fn host_name() -> String {
    let mut buf = [0u8; 256];
    // SAFETY: the buffer is writable for its whole length, which is passed with it
    let rc = unsafe { libc::gethostname(buf.as_mut_ptr().cast(), buf.len()) };
    if rc != 0 {
        return String::new();
    }
    let end = buf.iter().position(|&b| b == 0).unwrap_or(buf.len());
    String::from_utf8_lossy(&buf[..end]).into_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn single_process_collectives_are_the_identity() {
        let c = Single;
        assert_eq!((c.rank(), c.size()), (0, 1));
        c.barrier();
        let mut v = [1.5, -2.0];
        c.all_reduce_f64(&mut v, Reduce::Max);
        assert_eq!(v, [1.5, -2.0]);
        assert_eq!(c.all_reduce_i64(7, Reduce::Sum), 7);
        let mut b = b"abc".to_vec();
        c.broadcast_bytes(0, &mut b);
        assert_eq!(b, b"abc");
        assert_eq!(c.gather_bytes(b"xy"), Some(vec![b"xy".to_vec()]));
        assert_eq!(c.send_recv_bytes(0, 0, b"swap"), b"swap".to_vec());
    }

    #[test]
    fn launcher_size_reads_open_mpi_pmi_and_pmix() {
        let env = |pairs: &'static [(&'static str, &'static str)]| {
            move |k: &str| {
                pairs
                    .iter()
                    .find(|(n, _)| *n == k)
                    .map(|(_, v)| v.to_string())
            }
        };
        assert_eq!(launcher_size(env(&[])), None);
        assert_eq!(
            launcher_size(env(&[("OMPI_COMM_WORLD_SIZE", "4")])),
            Some(4)
        );
        assert_eq!(launcher_size(env(&[("PMI_SIZE", "2")])), Some(2));
        assert_eq!(launcher_size(env(&[("PMIX_RANK", "3")])), Some(4));
        assert_eq!(launcher_size(env(&[("PMIX_RANK", "0")])), Some(1));
        assert_eq!(launcher_size(env(&[("OMPI_COMM_WORLD_SIZE", "x")])), None);
    }
}
