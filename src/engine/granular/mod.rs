//! The granular force loops of `pair_style gran` (over the neighbour list) and `fix
//! wall/gran` primitives (over particles). The contact mechanics live in
//! [`crate::engine::contact`]; here a selected [`ContactModel`] is wrapped once per run into
//! a loop monomorphised for its sub-models, so the hot loop has no dynamic dispatch and
//! stores exactly the history the model needs.

use rayon::prelude::*;

use crate::engine::contact::{
    AnyContactModel, CohesionModel, ContactKernel, ContactModel, Material, MaterialInput,
    NormalModel, PairInput, RollingModel, TangentialModel, WallInput,
};
use crate::engine::neighbor::Pair;
use crate::engine::particles::Particles;
use crate::engine::sim::PairInteraction;

pub use crate::engine::contact::ModelSelection as Selection;

/// A granular pair interaction: the contact model and its per-type-pair coefficients.
pub struct PairGran<N, T, C, R> {
    /// The composed contact model.
    pub model: ContactModel<N, T, C, R>,
    /// Per-type-pair coefficients.
    pub material: Material,
    /// Group bits of frozen particles (infinite mass in contacts).
    pub frozen: u32,
    /// Per-pair results of the current step (reused between steps).
    pub results: Vec<PairResult>,
    /// The largest overlap of the last evaluation: (ratio to the smaller radius, i, j).
    pub worst: Option<(f64, u32, u32)>,
}

/// What one listed pair contributes: forces (N) and torques (N m) on both particles.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairResult {
    /// The particles touch.
    pub touching: bool,
    /// Force on i (N).
    pub fi: [f64; 3],
    /// Force on j (N).
    pub fj: [f64; 3],
    /// Torque on i (N m).
    pub ti: [f64; 3],
    /// Torque on j (N m).
    pub tj: [f64; 3],
    /// Overlap as a fraction of the smaller radius (for the blow-up guard).
    pub overlap_ratio: f64,
}

/// Below this many listed pairs the contact loop stays on one thread (the fork-join cost of
/// a parallel pass is larger than the work); `REGOLITH_PARALLEL_PAIRS` overrides it.
fn parallel_pairs() -> usize {
    static LIMIT: std::sync::OnceLock<usize> = std::sync::OnceLock::new();
    *LIMIT.get_or_init(|| {
        std::env::var("REGOLITH_PARALLEL_PAIRS")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(20_000)
    })
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairGran<N, T, C, R> {
    #[inline(always)]
    fn note_overlap(&mut self, pair: &Pair, ratio: f64) {
        if self.worst.is_none_or(|w| ratio > w.0) {
            self.worst = Some((ratio, pair.i, pair.j));
        }
    }

    /// The contribution of one listed pair; `h` is its history.
    #[inline(always)]
    fn pair_result(
        &self,
        p: &Particles,
        pair: &Pair,
        h: &mut [f64],
        dt: f64,
        update: bool,
    ) -> PairResult {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let xi = p.x[i];
        let xj = [
            p.x[j][0] + pair.shift[0],
            p.x[j][1] + pair.shift[1],
            p.x[j][2] + pair.shift[2],
        ];
        let (radi, radj) = (p.radius[i], p.radius[j]);
        // most listed pairs do not touch: leave before loading anything else
        let del = [xi[0] - xj[0], xi[1] - xj[1], xi[2] - xj[2]];
        let radsum = radi + radj;
        if !(del[0] * del[0] + del[1] * del[1] + del[2] * del[2] < radsum * radsum) {
            return PairResult::default();
        }
        let input = PairInput {
            xi,
            xj,
            radi,
            radj,
            mi: p.mass[i],
            mj: p.mass[j],
            frozen_i: p.mask[i] & self.frozen != 0,
            frozen_j: p.mask[j] & self.frozen != 0,
            vi: p.v[i],
            vj: p.v[j],
            omegai: p.omega[i],
            omegaj: p.omega[j],
            dt,
            update_history: update,
            coeffs: self.material.pair(p.kind[i] as usize, p.kind[j] as usize),
        };
        let out = self.model.pair_force(&input, h);
        if !out.touching {
            return PairResult::default();
        }
        PairResult {
            touching: true,
            fi: out.fi,
            fj: out.fj,
            ti: out.ti,
            tj: out.tj,
            overlap_ratio: out.deltan / input.radi.min(input.radj),
        }
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairInteraction
    for PairGran<N, T, C, R>
{
    fn history_width(&self) -> usize {
        self.model.history_len()
    }

    fn history_flips(&self) -> Vec<bool> {
        self.model.history_flips()
    }

    fn worst_overlap(&self) -> Option<(f64, u32, u32)> {
        self.worst
    }

    fn contacts(
        &self,
        p: &Particles,
        pairs: &[Pair],
        history: &[f64],
        dt: f64,
        ghost: (&[[f64; 3]], &[[f64; 3]]),
    ) -> Vec<(usize, [f64; 3], [f64; 3], [f64; 3], [f64; 3])> {
        let width = self.model.history_len();
        let mut h = vec![0.0; width];
        let mut out = Vec::new();
        let mut scratch: Option<Particles> = None;
        for (k, pair) in pairs.iter().enumerate() {
            h.copy_from_slice(&history[k * width..(k + 1) * width]);
            let (i, j) = (pair.i as usize, pair.j as usize);
            let r = if pair.shift != [0.0; 3] && ghost.0.len() == p.len() {
                // the ghost side keeps the velocities of the last force evaluation
                let g = if p.id[i] < p.id[j] { i } else { j };
                let q = scratch.get_or_insert_with(|| p.clone());
                q.v[g] = ghost.0[g];
                q.omega[g] = ghost.1[g];
                let r = self.pair_result(q, pair, &mut h, dt, false);
                q.v[g] = p.v[g];
                q.omega[g] = p.omega[g];
                r
            } else {
                self.pair_result(p, pair, &mut h, dt, false)
            };
            if r.touching {
                out.push((k, r.fi, r.ti, r.fj, r.tj));
            }
        }
        out
    }

    fn compute(
        &mut self,
        p: &mut Particles,
        pairs: &[Pair],
        history: &mut [f64],
        dt: f64,
        update: bool,
        mut virial: Option<&mut [[f64; 6]]>,
    ) {
        let width = self.model.history_len();
        self.worst = None;
        if pairs.len() < parallel_pairs() || rayon::current_num_threads() == 1 {
            // one thread: compute and add each pair in list order (the same sums as below)
            let mut empty: [f64; 0] = [];
            for (k, pair) in pairs.iter().enumerate() {
                let h = if width == 0 {
                    &mut empty[..]
                } else {
                    &mut history[k * width..(k + 1) * width]
                };
                let res = self.pair_result(p, pair, h, dt, update);
                if res.touching {
                    add_pair(p, pair, &res, virial.as_deref_mut());
                    self.note_overlap(pair, res.overlap_ratio);
                }
            }
            return;
        }
        let mut results = std::mem::take(&mut self.results);
        results.clear();
        results.resize(pairs.len(), PairResult::default());
        // contact mechanics per pair are independent: compute them in parallel
        {
            let this = &*self;
            let pr: &Particles = p;
            if width == 0 {
                results
                    .par_iter_mut()
                    .zip(pairs.par_iter())
                    .for_each(|(res, pair)| *res = this.pair_result(pr, pair, &mut [], dt, update));
            } else {
                results
                    .par_iter_mut()
                    .zip(pairs.par_iter())
                    .zip(history.par_chunks_mut(width))
                    .for_each(|((res, pair), h)| *res = this.pair_result(pr, pair, h, dt, update));
            }
        }
        // accumulation in list order: the same sums for any number of threads
        for (res, pair) in results.iter().zip(pairs) {
            if res.touching {
                add_pair(p, pair, res, virial.as_deref_mut());
                self.note_overlap(pair, res.overlap_ratio);
            }
        }
        self.results = results;
    }
}

/// Add one pair's forces and torques to its two particles, and half its virial to each
/// when asked (LIGGGHTS's `ev_tally_xyz` with del = x_i - x_j and F the force on i).
#[inline(always)]
fn add_pair(p: &mut Particles, pair: &Pair, res: &PairResult, virial: Option<&mut [[f64; 6]]>) {
    let (i, j) = (pair.i as usize, pair.j as usize);
    if let Some(w) = virial {
        let del = [
            p.x[i][0] - (p.x[j][0] + pair.shift[0]),
            p.x[i][1] - (p.x[j][1] + pair.shift[1]),
            p.x[i][2] - (p.x[j][2] + pair.shift[2]),
        ];
        let f = res.fi;
        let v = [
            del[0] * f[0],
            del[1] * f[1],
            del[2] * f[2],
            del[0] * f[1],
            del[0] * f[2],
            del[1] * f[2],
        ];
        for k in 0..6 {
            w[i][k] += 0.5 * v[k];
        }
        for k in 0..6 {
            w[j][k] += 0.5 * v[k];
        }
    }
    for d in 0..3 {
        p.f[i][d] += res.fi[d];
        p.torque[i][d] += res.ti[d];
    }
    for d in 0..3 {
        p.f[j][d] += res.fj[d];
        p.torque[j][d] += res.tj[d];
    }
}

/// The model of a selection and its coefficient tables, with LIGGGHTS's material checks.
fn model_and_material(
    sel: &Selection,
    input: &MaterialInput,
) -> Result<(AnyContactModel, Material), String> {
    let model = AnyContactModel::new(sel)?;
    let material = Material::new(input, &model.properties())?;
    Ok((model, material))
}

/// Build the pair interaction for a selection: the loop is monomorphised for the selected
/// sub-models here, once per run.
pub fn build(
    sel: &Selection,
    input: &MaterialInput,
    frozen: u32,
) -> Result<Box<dyn PairInteraction>, String> {
    let (model, material) = model_and_material(sel, input)?;
    struct Make(Material, u32);
    impl ContactKernel for Make {
        type Output = Box<dyn PairInteraction>;
        fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
            self,
            m: &ContactModel<N, T, C, R>,
        ) -> Self::Output {
            Box::new(PairGran {
                model: *m,
                material: self.0,
                frozen: self.1,
                results: Vec::new(),
                worst: None,
            })
        }
    }
    Ok(model.dispatch(Make(material, frozen)))
}

/// A primitive wall (`primitive type T xplane|...|zcylinder ...`), lengths in box units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Primitive {
    /// The plane `x[axis] = position`.
    Plane {
        /// 0, 1 or 2 for xplane, yplane, zplane.
        axis: usize,
        /// Position of the plane.
        position: f64,
    },
    /// An infinite cylinder along `axis` through (c1, c2) in the other two coordinates.
    Cylinder {
        /// 0, 1 or 2 for xcylinder, ycylinder, zcylinder.
        axis: usize,
        /// Radius.
        radius: f64,
        /// Centre coordinate along the axis after `axis` (cyclically).
        c1: f64,
        /// Centre coordinate along the second axis after `axis`.
        c2: f64,
    },
}

impl Primitive {
    /// Velocity of the wall surface seen by a particle at `pos` (m/s) under `shear dim v`,
    /// as LIGGGHTS computes it: a plane, or a cylinder sheared along its axis, translates
    /// along `dim`; a cylinder sheared across its axis turns about it with angular speed
    /// `v`, evaluated at the particle centre's radial vector.
    #[inline(always)]
    fn surface_velocity(&self, shear: Option<(usize, f64)>, pos: [f64; 3]) -> [f64; 3] {
        let mut v_wall = [0.0; 3];
        let Some((dim, v)) = shear else {
            return v_wall;
        };
        match *self {
            Primitive::Cylinder { axis, c1, c2, .. } if dim != axis => {
                let mut w = [0.0; 3];
                w[axis] = v;
                let mut r = [0.0; 3];
                r[(axis + 1) % 3] = pos[(axis + 1) % 3] - c1;
                r[(axis + 2) % 3] = pos[(axis + 2) % 3] - c2;
                [
                    w[1] * r[2] - w[2] * r[1],
                    w[2] * r[0] - w[0] * r[2],
                    w[0] * r[1] - w[1] * r[0],
                ]
            }
            _ => {
                v_wall[dim] = v;
                v_wall
            }
        }
    }

    /// LIGGGHTS's contact resolution: the gap (negative when overlapping) and the vector from
    /// the particle centre towards the wall.
    #[inline(always)]
    fn resolve(&self, pos: [f64; 3], r: f64) -> (f64, [f64; 3]) {
        let mut delta = [0.0; 3];
        match *self {
            Primitive::Plane { axis, position } => {
                delta[axis] = position - pos[axis];
                let gap = if pos[axis] > position {
                    pos[axis] - position - r
                } else {
                    position - pos[axis] - r
                };
                (gap, delta)
            }
            Primitive::Cylinder {
                axis,
                radius,
                c1,
                c2,
            } => {
                let (y, z) = ((axis + 1) % 3, (axis + 2) % 3);
                let dy = pos[y] - c1;
                let dz = pos[z] - c2;
                let dist = (dy * dy + dz * dz).sqrt();
                if dist.abs() < 1e-13 {
                    return (0.0, delta);
                }
                if dist > radius {
                    let fact = (dist - radius) / dist;
                    delta[y] = -dy * fact;
                    delta[z] = -dz * fact;
                    (dist - radius - r, delta)
                } else {
                    let fact = (radius - dist) / dist;
                    delta[y] = dy * fact;
                    delta[z] = dz * fact;
                    (radius - dist - r, delta)
                }
            }
        }
    }
}

/// Wall contacts of particles with a primitive wall (`fix wall/gran ... primitive`).
pub trait WallInteraction: Send {
    /// Doubles of history per particle.
    fn history_width(&self) -> usize;
    /// Add wall forces to particles of `group`; `history` is per particle. `list` is the
    /// neighbour list's build count and skin (length): the wall keeps its own list of the
    /// particles within the skin and refreshes it whenever the pair list was rebuilt.
    fn compute(
        &mut self,
        p: &mut Particles,
        group: u32,
        history: &mut [f64],
        dt: f64,
        update: bool,
        list: (u64, f64),
    );
}

/// A primitive wall with a contact model (the wall has infinite mass).
pub struct WallGran<N, T, C, R> {
    /// The composed contact model.
    pub model: ContactModel<N, T, C, R>,
    /// Coefficients (the wall has atom type `wall_type`).
    pub material: Material,
    /// The wall's atom type.
    pub wall_type: usize,
    /// The wall's shape.
    pub shape: Primitive,
    /// `shear dim vshear` (dimension, m/s) if the wall surface moves.
    pub shear: Option<(usize, f64)>,
    /// Particles closer to the wall than the skin at the last list build.
    pub near: Vec<u32>,
    /// The pair-list build count `near` belongs to.
    pub near_build: Option<u64>,
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> WallInteraction
    for WallGran<N, T, C, R>
{
    fn history_width(&self) -> usize {
        self.model.history_len()
    }

    fn compute(
        &mut self,
        p: &mut Particles,
        group: u32,
        history: &mut [f64],
        dt: f64,
        update: bool,
        list: (u64, f64),
    ) {
        let w = self.model.history_len();
        if self.near_build != Some(list.0) {
            // refresh the wall's neighbour list; particles leaving it are apart: reset them
            let old = std::mem::take(&mut self.near);
            for i in 0..p.len() {
                if p.mask[i] & group != 0 && self.shape.resolve(p.x[i], p.radius[i]).0 < list.1 {
                    self.near.push(i as u32);
                }
            }
            if w > 0 {
                for &i in &old {
                    let i = i as usize;
                    if i < p.len() && self.near.binary_search(&(i as u32)).is_err() {
                        history[i * w..(i + 1) * w]
                            .iter_mut()
                            .for_each(|v| *v = 0.0);
                    }
                }
            }
            self.near_build = Some(list.0);
        }
        for k in 0..self.near.len() {
            let i = self.near[k] as usize;
            let (gap, to_wall) = self.shape.resolve(p.x[i], p.radius[i]);
            let h = &mut history[i * w..(i + 1) * w];
            if !(gap <= 0.0) {
                // apart: the history is reset (written only if it holds something)
                if h.iter().any(|v| *v != 0.0) {
                    h.iter_mut().for_each(|v| *v = 0.0);
                }
                continue;
            }
            let input = WallInput {
                x: p.x[i],
                gap,
                to_wall,
                radius: p.radius[i],
                mass: p.mass[i],
                v: p.v[i],
                omega: p.omega[i],
                v_wall: self.shape.surface_velocity(self.shear, p.x[i]),
                dt,
                update_history: update,
                coeffs: self.material.pair(p.kind[i] as usize, self.wall_type),
            };
            let out = self
                .model
                .wall_force(&input, &mut history[i * w..(i + 1) * w]);
            if out.touching {
                for d in 0..3 {
                    p.f[i][d] += out.f[d];
                    p.torque[i][d] += out.t[d];
                }
            }
        }
    }
}

/// Build the wall interaction for a selection, monomorphised once per run.
pub fn build_wall(
    sel: &Selection,
    input: &MaterialInput,
    wall_type: usize,
    shape: Primitive,
    shear: Option<(usize, f64)>,
) -> Result<Box<dyn WallInteraction>, String> {
    let (model, material) = model_and_material(sel, input)?;
    struct Make(Material, usize, Primitive, Option<(usize, f64)>);
    impl ContactKernel for Make {
        type Output = Box<dyn WallInteraction>;
        fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
            self,
            m: &ContactModel<N, T, C, R>,
        ) -> Self::Output {
            Box::new(WallGran {
                model: *m,
                material: self.0,
                wall_type: self.1,
                shape: self.2,
                shear: self.3,
                near: Vec::new(),
                near_build: None,
            })
        }
    }
    Ok(model.dispatch(Make(material, wall_type, shape, shear)))
}
