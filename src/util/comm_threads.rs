//! [`Comm`] between threads of one process: N ranks are N threads joined by channels, one
//! first-in-first-out channel per ordered pair of ranks. Every rank makes the same calls in
//! the same order (as under MPI), so each message is matched by its channel's order alone.
//! Used to test the domain decomposition without MPI; reductions combine the ranks' values
//! in rank order, so every rank gets the same bits.

use std::sync::mpsc::{channel, Receiver, Sender};

use crate::util::comm::{Comm, Reduce};

/// One rank of a [`ThreadRanks`] run.
pub struct ThreadComm {
    rank: usize,
    /// Senders to every rank (this one included), by rank.
    to: Vec<Sender<Vec<u8>>>,
    /// Receivers from every rank (this one included), by rank.
    from: Vec<Receiver<Vec<u8>>>,
}

/// Runs a function on N ranks, each a thread with its own [`ThreadComm`].
pub struct ThreadRanks;

impl ThreadRanks {
    /// Run `work` on `n` ranks (threads) and return each rank's result, in rank order. A
    /// panic on any rank is passed on once every rank has stopped.
    pub fn run<T: Send>(n: usize, work: impl Fn(&ThreadComm) -> T + Sync) -> Vec<T> {
        ThreadRanks::run_owned(n, |c| work(&c))
    }

    /// As [`ThreadRanks::run`], each rank given its [`ThreadComm`] to keep (e.g. to hand
    /// to a simulation).
    pub fn run_owned<T: Send>(n: usize, work: impl Fn(ThreadComm) -> T + Sync) -> Vec<T> {
        // channel a -> b: its sender goes to rank a, its receiver to rank b
        let n = n.max(1);
        let mut senders: Vec<Vec<Sender<Vec<u8>>>> = (0..n).map(|_| Vec::new()).collect();
        let mut receivers: Vec<Vec<Receiver<Vec<u8>>>> = (0..n).map(|_| Vec::new()).collect();
        for receiver in receivers.iter_mut() {
            for sender in senders.iter_mut() {
                let (tx, rx) = channel();
                sender.push(tx);
                receiver.push(rx);
            }
        }
        let comms: Vec<ThreadComm> = senders
            .into_iter()
            .zip(receivers)
            .enumerate()
            .map(|(rank, (to, from))| ThreadComm { rank, to, from })
            .collect();
        let work = &work;
        std::thread::scope(|s| {
            let handles: Vec<_> = comms
                .into_iter()
                .map(|c| s.spawn(move || work(c)))
                .collect();
            let results: Vec<_> = handles.into_iter().map(|h| h.join()).collect();
            results
                .into_iter()
                .map(|r| r.unwrap_or_else(|e| std::panic::resume_unwind(e)))
                .collect()
        })
    }
}

impl ThreadComm {
    fn send(&self, to: usize, bytes: Vec<u8>) {
        // a rank that has stopped (it panicked) is reported by the receiving side
        let _ = self.to[to].send(bytes);
    }

    fn recv(&self, from: usize) -> Vec<u8> {
        match self.from[from].recv() {
            Ok(b) => b,
            Err(_) => panic!("rank {from} stopped before sending to rank {}", self.rank),
        }
    }

    /// Every rank's bytes, in rank order, on every rank.
    fn all_gather(&self, bytes: &[u8]) -> Vec<Vec<u8>> {
        for r in 0..self.size() {
            if r != self.rank {
                self.send(r, bytes.to_vec());
            }
        }
        (0..self.size())
            .map(|r| {
                if r == self.rank {
                    bytes.to_vec()
                } else {
                    self.recv(r)
                }
            })
            .collect()
    }
}

fn combine(a: f64, b: f64, op: Reduce) -> f64 {
    match op {
        Reduce::Sum => a + b,
        Reduce::Max => a.max(b),
        Reduce::Min => a.min(b),
    }
}

impl Comm for ThreadComm {
    fn rank(&self) -> usize {
        self.rank
    }
    fn size(&self) -> usize {
        self.to.len()
    }
    fn barrier(&self) {
        self.all_gather(&[]);
    }
    fn all_reduce_f64(&self, values: &mut [f64], op: Reduce) {
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_le_bytes()).collect();
        let all = self.all_gather(&bytes);
        for (k, v) in values.iter_mut().enumerate() {
            let at = |b: &Vec<u8>| {
                let mut w = [0u8; 8];
                w.copy_from_slice(&b[8 * k..8 * k + 8]);
                f64::from_le_bytes(w)
            };
            *v = all[1..]
                .iter()
                .fold(at(&all[0]), |acc, b| combine(acc, at(b), op));
        }
    }
    fn all_reduce_i64(&self, value: i64, op: Reduce) -> i64 {
        let all = self.all_gather(&value.to_le_bytes());
        let vals = all.iter().map(|b| {
            let mut w = [0u8; 8];
            w.copy_from_slice(&b[..8]);
            i64::from_le_bytes(w)
        });
        match op {
            Reduce::Sum => vals.sum(),
            Reduce::Max => vals.max().unwrap_or(value),
            Reduce::Min => vals.min().unwrap_or(value),
        }
    }
    fn broadcast_bytes(&self, root: usize, bytes: &mut Vec<u8>) {
        if self.rank == root {
            for r in (0..self.size()).filter(|&r| r != root) {
                self.send(r, bytes.clone());
            }
        } else {
            *bytes = self.recv(root);
        }
    }
    fn gather_bytes(&self, bytes: &[u8]) -> Option<Vec<Vec<u8>>> {
        if self.rank != 0 {
            self.send(0, bytes.to_vec());
            return None;
        }
        let mut all = vec![bytes.to_vec()];
        all.extend((1..self.size()).map(|r| self.recv(r)));
        Some(all)
    }
    fn send_recv_bytes(&self, to: usize, from: usize, bytes: &[u8]) -> Vec<u8> {
        self.send(to, bytes.to_vec());
        self.recv(from)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collectives_and_swaps_over_four_threads() {
        let out = ThreadRanks::run(4, |c| {
            let r = c.rank();
            let mut v = [r as f64 + 0.5, -(r as f64)];
            c.all_reduce_f64(&mut v, Reduce::Sum);
            let max = c.all_reduce_i64(r as i64 * 3, Reduce::Max);
            let mut b = if r == 2 { b"root".to_vec() } else { Vec::new() };
            c.broadcast_bytes(2, &mut b);
            let g = c.gather_bytes(&[r as u8]);
            // a ring: send up, receive from below
            let got = c.send_recv_bytes((r + 1) % 4, (r + 3) % 4, &[r as u8; 2]);
            let own = c.send_recv_bytes(r, r, b"me");
            c.barrier();
            (v, max, b, g, got, own)
        });
        for (r, (v, max, b, g, got, own)) in out.into_iter().enumerate() {
            assert_eq!(v, [8.0, -6.0]);
            assert_eq!(max, 9);
            assert_eq!(b, b"root");
            assert_eq!(g.is_some(), r == 0);
            if let Some(g) = g {
                assert_eq!(g, vec![vec![0], vec![1], vec![2], vec![3]]);
            }
            assert_eq!(got, vec![((r + 3) % 4) as u8; 2]);
            assert_eq!(own, b"me");
        }
    }

    #[test]
    fn one_thread_is_one_rank() {
        assert_eq!(ThreadRanks::run(1, |c| (c.rank(), c.size())), vec![(0, 1)]);
    }
}
