//! The order in which a pair pass adds its contributions to the particles' sums.

use super::Pair;

/// For each particle, the list entries it takes part in, in list order: entries where it is
/// the second particle (`as_second`), then its own block of entries as the first. A list
/// grouped by the first particle (ascending) with the second above it gives each particle
/// exactly the order a sequential pass over the list adds its forces in.
#[derive(Debug, Clone, Default)]
pub struct Incidence {
    /// Start of each particle's block of entries as first particle (n + 1 values).
    pub first: Vec<u32>,
    /// Start of each particle's entries as second particle in `second` (n + 1 values).
    pub second_start: Vec<u32>,
    /// Entries by second particle, ascending within each particle.
    pub second: Vec<u32>,
}

/// How a pair pass adds its contributions to the particles' forces and torques.
#[derive(Debug, Clone, Default)]
pub enum SumOrder {
    /// One pass in list order (the exact path's sums, LIGGGHTS's round-off).
    #[default]
    ListOrder,
    /// In parallel, each particle's contributions gathered in list order (the exact path on
    /// several threads: the same sums as `ListOrder`).
    Gathered(Incidence),
    /// The fast path: fixed blocks of [`BLOCK_PARTICLES`] particles each add their own list
    /// entries' contributions (blocks in parallel), then contributions to other blocks'
    /// particles are added in block order. The same sums for any thread count. Holds where
    /// each block starts in the list ([`block_starts`]).
    Blocks(Vec<u32>),
}

/// Particles per block of the fast path's sums (fixed, so sums do not depend on threads).
pub const BLOCK_PARTICLES: usize = 1024;

/// Where each block of [`BLOCK_PARTICLES`] particles starts in `pairs` (one more value than
/// blocks, the last `pairs.len()`), or None if the list is not grouped by ascending first
/// particle.
pub fn block_starts(pairs: &[Pair], n: usize) -> Option<Vec<u32>> {
    if pairs.windows(2).any(|w| w[1].i < w[0].i) || pairs.iter().any(|p| p.i as usize >= n) {
        return None;
    }
    let blocks = n.div_ceil(BLOCK_PARTICLES).max(1);
    let mut starts = Vec::with_capacity(blocks + 1);
    let mut e = 0;
    for b in 0..blocks {
        let lo = (b * BLOCK_PARTICLES) as u32;
        while e < pairs.len() && pairs[e].i < lo {
            e += 1;
        }
        starts.push(e as u32);
    }
    starts.push(pairs.len() as u32);
    Some(starts)
}

impl Incidence {
    /// The incidence of `pairs` over `n` particles, or None if the list is not grouped by
    /// ascending first particle with the second particle above the first.
    pub fn new(pairs: &[Pair], n: usize) -> Option<Incidence> {
        if pairs.windows(2).any(|w| w[1].i < w[0].i) || pairs.iter().any(|p| p.j <= p.i) {
            return None;
        }
        let mut inc = Incidence {
            first: vec![0; n + 1],
            second_start: vec![0; n + 1],
            second: vec![0; pairs.len()],
        };
        for p in pairs {
            inc.first[p.i as usize + 1] += 1;
            inc.second_start[p.j as usize + 1] += 1;
        }
        for k in 0..n {
            inc.first[k + 1] += inc.first[k];
            inc.second_start[k + 1] += inc.second_start[k];
        }
        let mut fill = inc.second_start.clone();
        for (k, p) in pairs.iter().enumerate() {
            inc.second[fill[p.j as usize] as usize] = k as u32;
            fill[p.j as usize] += 1;
        }
        Some(inc)
    }
}
