//! Shared set-up of the domain-decomposition tests: the box, particles and cases.

#![allow(dead_code)]

use regolith::engine::decomp::Halo;

/// The box (length).
pub const LO: [f64; 3] = [-0.5, 0.0, 0.1];
pub const HI: [f64; 3] = [0.7, 0.9, 0.6];

/// A small deterministic generator (xorshift), the same on every rank.
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// One test set-up: grid, periodic flags, pair rule.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// Ranks along x, y, z.
    pub procs: [usize; 3],
    /// Periodic directions.
    pub periodic: [bool; 3],
    /// Some(cut): pairs closer than cut; None: granular (closer than ri + rj + SKIN).
    pub cut: Option<f64>,
    /// Number of particles.
    pub n: usize,
    /// Seed of the particles.
    pub seed: u64,
}

/// Neighbour skin (length).
pub const SKIN: f64 = 0.01;

impl Case {
    /// The ghost reach of the case.
    pub fn halo(&self) -> Halo {
        match self.cut {
            Some(c) => Halo::plain(c),
            None => Halo::granular(2.0 * 0.05 + SKIN, SKIN),
        }
    }
    /// The pair reach of two radii (length).
    pub fn reach(&self, ra: f64, rb: f64) -> f64 {
        self.cut.unwrap_or(ra + rb + SKIN)
    }
}

/// The particles of a case (ID, position, radius), before and after one displacement of
/// less than half a sub-domain per axis, the same for any grid (wrapped into periodic
/// directions, reflected at the faces of the others).
pub fn particles(case: &Case) -> (Vec<[f64; 3]>, Vec<[f64; 3]>, Vec<f64>) {
    let mut rng = Rng(case
        .seed
        .wrapping_mul(2654435761)
        .wrapping_add(88172645463325252));
    let mut start = Vec::new();
    let mut moved = Vec::new();
    let mut radius = Vec::new();
    for _ in 0..case.n {
        let x: [f64; 3] = [0, 1, 2].map(|d| LO[d] + (HI[d] - LO[d]) * rng.unit());
        let mut y = x;
        for d in 0..3 {
            // the narrowest sub-domain of the grids tested (4 ranks on an axis)
            let width = (HI[d] - LO[d]) / 4.0;
            y[d] += (rng.unit() - 0.5) * 0.8 * width;
            let len = HI[d] - LO[d];
            if case.periodic[d] {
                if y[d] < LO[d] {
                    y[d] += len;
                } else if y[d] >= HI[d] {
                    y[d] -= len;
                }
            } else {
                // reflected at the faces
                if y[d] < LO[d] {
                    y[d] = 2.0 * LO[d] - y[d];
                } else if y[d] >= HI[d] {
                    y[d] = 2.0 * HI[d] - y[d] - 1e-12;
                }
            }
        }
        start.push(x);
        moved.push(y);
        radius.push(0.02 + 0.03 * rng.unit());
    }
    (start, moved, radius)
}
