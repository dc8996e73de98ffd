//! `fix property/atom/tracer` and `compute nparticles/tracer/region`: particles marked when
//! they are inside a region (once at a step, or from a step on), and counts and masses of
//! all and of marked particles inside another region, as LIGGGHTS 3.8.0 computes them.
//!
//! The marker is the per-atom property named by the fix ID (1 marked, 0 not). A count
//! with `reset_marker yes` un-marks what it counted; the compute is read through a shared
//! reference, so it records the atom IDs and they are un-marked before the next step (its
//! values within the step are the same either way).

use std::sync::atomic::{AtomicI64, Ordering};
use std::sync::Mutex;

use crate::engine::particles::Particles;
use crate::engine::region::Regions;

/// When particles are marked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkerStyle {
    /// `dirac`: those inside the region at the first check at or after the mark step.
    Dirac,
    /// `heaviside`: those inside the region at any check from the mark step on.
    Heaviside,
    /// `none`: no marking.
    None,
}

/// One `fix property/atom/tracer region_mark R mark_step S [marker_style ...]
/// [check_mark_every N]`.
#[derive(Debug)]
pub struct Tracer {
    /// The marking region (index).
    pub region: usize,
    /// The mark step.
    pub step: i64,
    /// When particles are marked.
    pub style: MarkerStyle,
    /// Check every this many steps.
    pub every: i64,
    /// A Dirac mark has not happened yet.
    pub first_mark: bool,
    /// Name of the per-atom marker (the fix ID).
    pub marker: String,
    /// Particles marked so far.
    pub marked: i64,
    /// `marked` when the global scalar was last read.
    pub marked_read: AtomicI64,
}

impl Tracer {
    /// LIGGGHTS's `end_of_step`: mark the group's particles inside the region.
    pub fn mark(&mut self, p: &mut Particles, group: u32, regions: &Regions, step: i64) {
        if step < self.step
            || self.style == MarkerStyle::None
            || (self.style == MarkerStyle::Dirac && !self.first_mark)
        {
            return;
        }
        let k = p.extra_index(&self.marker, 1);
        let mut marked = 0;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let m = &mut p.extra[k].data[i];
            if (*m - 1.0).abs() >= 1e-5 && regions.matches(self.region, p.x[i]) {
                *m = 1.0;
                marked += 1;
            }
        }
        self.marked += marked;
        self.first_mark = false;
    }

    /// `f_ID`: particles marked since the value was last read.
    pub fn scalar(&self) -> f64 {
        let last = self.marked_read.swap(self.marked, Ordering::Relaxed);
        (self.marked - last) as f64
    }

    /// The marker of each particle (1 marked, 0 not), in particle order.
    pub fn markers(&self, p: &Particles) -> Vec<f64> {
        p.extra
            .iter()
            .find(|e| e.name == self.marker && e.width == 1)
            .map_or_else(|| vec![0.0; p.len()], |e| e.data.clone())
    }
}

/// `compute nparticles/tracer/region region_count R tracer T [periodic DIM IMAGE]
/// [reset_marker yes|no]`.
#[derive(Debug)]
pub struct TracerCount {
    /// The counting region (index).
    pub region: usize,
    /// The tracer fix ID (its marker array has this name).
    pub tracer: String,
    /// `periodic DIM IMAGE`: only particles in this periodic image along DIM (None: all).
    pub image: Option<(usize, Option<i32>)>,
    /// `reset_marker yes`: un-mark counted particles.
    pub reset: bool,
    /// IDs of particles counted since the last step, to un-mark.
    pub pending: Mutex<Vec<i64>>,
}

impl Clone for TracerCount {
    fn clone(&self) -> Self {
        TracerCount {
            region: self.region,
            tracer: self.tracer.clone(),
            image: self.image,
            reset: self.reset,
            pending: Mutex::new(self.pending.lock().map(|v| v.clone()).unwrap_or_default()),
        }
    }
}

impl PartialEq for TracerCount {
    fn eq(&self, other: &Self) -> bool {
        (self.region, &self.tracer, self.image, self.reset)
            == (other.region, &other.tracer, other.image, other.reset)
    }
}

impl TracerCount {
    /// Total count, marked count, total mass, marked mass inside the region among `group`
    /// (1, 1, mass, mass).
    pub fn values(&self, p: &Particles, group: u32, regions: &Regions) -> [f64; 4] {
        let marker = p
            .extra
            .iter()
            .find(|e| e.name == self.tracer && e.width == 1);
        let (mut n, mut n_marked, mut m, mut m_marked) = (0.0, 0.0, 0.0, 0.0);
        let mut counted = Vec::new();
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            if let Some((dim, Some(image))) = self.image {
                if p.image[i][dim] != image {
                    continue;
                }
            }
            if !regions.matches(self.region, p.x[i]) {
                continue;
            }
            n += 1.0;
            m += p.mass[i];
            let is_marked = marker.is_some_and(|e| (e.data[i] - 1.0).abs() < 1e-5);
            if is_marked {
                n_marked += 1.0;
                m_marked += p.mass[i];
                if self.reset {
                    counted.push(p.id[i]);
                }
            }
        }
        if !counted.is_empty() {
            self.pending
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .extend(counted);
        }
        [n, n_marked, m, m_marked]
    }

    /// Un-mark the particles counted since the last call.
    pub fn apply_resets(&mut self, p: &mut Particles) {
        let pending = self.pending.get_mut().unwrap_or_else(|e| e.into_inner());
        if pending.is_empty() {
            return;
        }
        pending.sort_unstable();
        if let Some(k) = p
            .extra
            .iter()
            .position(|e| e.name == self.tracer && e.width == 1)
        {
            for i in 0..p.len() {
                if pending.binary_search(&p.id[i]).is_ok() {
                    p.extra[k].data[i] = 0.0;
                }
            }
        }
        pending.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dirac_marks_once_and_counts_reset_the_marks() {
        let mut regions = Regions::default();
        let ctx = crate::engine::region::RegionContext {
            bounds: None,
            lattice: None,
        };
        regions
            .define(
                &["r", "block", "0", "1", "0", "1", "0", "1", "units", "box"],
                ctx,
            )
            .unwrap();
        let mut p = Particles::default();
        p.push(1, 1, [0.5, 0.5, 0.5], 0.01, 1000.0);
        p.push(2, 1, [1.5, 0.5, 0.5], 0.01, 1000.0);
        let mut t = Tracer {
            region: 0,
            step: 10,
            style: MarkerStyle::Dirac,
            every: 1,
            first_mark: true,
            marker: "tr".into(),
            marked: 0,
            marked_read: AtomicI64::new(0),
        };
        t.mark(&mut p, 1, &regions, 5);
        assert_eq!(t.marked, 0);
        t.mark(&mut p, 1, &regions, 10);
        p.x[1] = [0.5, 0.2, 0.5];
        t.mark(&mut p, 1, &regions, 11);
        assert_eq!((t.marked, t.scalar(), t.scalar()), (1, 1.0, 0.0));
        let mut c = TracerCount {
            region: 0,
            tracer: "tr".into(),
            image: None,
            reset: true,
            pending: Mutex::new(Vec::new()),
        };
        assert_eq!(c.values(&p, 1, &regions)[..2], [2.0, 1.0]);
        c.apply_resets(&mut p);
        assert_eq!(c.values(&p, 1, &regions)[..2], [2.0, 0.0]);
    }
}
