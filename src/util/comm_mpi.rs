//! [`Comm`] over MPI (the `mpi` feature): the world communicator of `mpirun`.

use mpi::collective::SystemOperation;
use mpi::traits::*;

use crate::util::comm::{Comm, Reduce};

/// The MPI world; MPI is finalised when this is dropped.
pub struct MpiComm {
    world: mpi::topology::SimpleCommunicator,
    _universe: mpi::environment::Universe,
}

impl MpiComm {
    /// Initialise MPI (None if it was initialised before).
    pub fn init() -> Option<MpiComm> {
        let universe = mpi::initialize()?;
        Some(MpiComm {
            world: universe.world(),
            _universe: universe,
        })
    }
}

fn op(r: Reduce) -> SystemOperation {
    match r {
        Reduce::Sum => SystemOperation::sum(),
        Reduce::Max => SystemOperation::max(),
        Reduce::Min => SystemOperation::min(),
    }
}

impl Comm for MpiComm {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }
    fn size(&self) -> usize {
        self.world.size() as usize
    }
    fn barrier(&self) {
        self.world.barrier();
    }
    fn all_reduce_f64(&self, values: &mut [f64], r: Reduce) {
        let send = values.to_vec();
        self.world.all_reduce_into(&send[..], values, op(r));
    }
    fn all_reduce_i64(&self, value: i64, r: Reduce) -> i64 {
        let mut out = 0i64;
        self.world.all_reduce_into(&value, &mut out, op(r));
        out
    }
    fn broadcast_bytes(&self, root: usize, bytes: &mut Vec<u8>) {
        let root = self.world.process_at_rank(root as i32);
        let mut len = bytes.len() as u64;
        root.broadcast_into(&mut len);
        bytes.resize(len as usize, 0);
        // Open MPI refuses a broadcast of an empty buffer (every rank knows the length)
        if len > 0 {
            root.broadcast_into(&mut bytes[..]);
        }
    }
    fn gather_bytes(&self, bytes: &[u8]) -> Option<Vec<Vec<u8>>> {
        if self.rank() != 0 {
            self.world.process_at_rank(0).send(bytes);
            return None;
        }
        let mut all = vec![bytes.to_vec()];
        for r in 1..self.world.size() {
            all.push(self.world.process_at_rank(r).receive_vec::<u8>().0);
        }
        Some(all)
    }
    fn send_recv_bytes(&self, to: usize, from: usize, bytes: &[u8]) -> Vec<u8> {
        let dest = self.world.process_at_rank(to as i32);
        let src = self.world.process_at_rank(from as i32);
        // the length first, so the receiver can size its buffer
        let len = bytes.len() as u64;
        let mut n = 0u64;
        mpi::point_to_point::send_receive_into(&len, &dest, &mut n, &src);
        let mut out = vec![0u8; n as usize];
        mpi::point_to_point::send_receive_into(bytes, &dest, &mut out[..], &src);
        out
    }
    fn send_recv_f64(&self, to: usize, from: usize, out: &[f64], into: &mut [f64]) {
        let dest = self.world.process_at_rank(to as i32);
        let src = self.world.process_at_rank(from as i32);
        mpi::point_to_point::send_receive_into(out, &dest, into, &src);
    }
}

/// [`MpiComm`] handed to the thread that runs a deck: MPI is called from one thread at a
/// time (the run's), never from two at once.
pub struct SendComm(pub MpiComm);

// SAFETY: the communicator is moved to the run and used by one thread at a time
unsafe impl Send for SendComm {}

impl Comm for SendComm {
    fn rank(&self) -> usize {
        self.0.rank()
    }
    fn size(&self) -> usize {
        self.0.size()
    }
    fn barrier(&self) {
        self.0.barrier()
    }
    fn all_reduce_f64(&self, values: &mut [f64], r: Reduce) {
        self.0.all_reduce_f64(values, r)
    }
    fn all_reduce_i64(&self, value: i64, r: Reduce) -> i64 {
        self.0.all_reduce_i64(value, r)
    }
    fn broadcast_bytes(&self, root: usize, bytes: &mut Vec<u8>) {
        self.0.broadcast_bytes(root, bytes)
    }
    fn gather_bytes(&self, bytes: &[u8]) -> Option<Vec<Vec<u8>>> {
        self.0.gather_bytes(bytes)
    }
    fn send_recv_bytes(&self, to: usize, from: usize, bytes: &[u8]) -> Vec<u8> {
        self.0.send_recv_bytes(to, from, bytes)
    }
    fn send_recv_f64(&self, to: usize, from: usize, out: &[f64], into: &mut [f64]) {
        self.0.send_recv_f64(to, from, out, into)
    }
}
