//! Granular walls: the primitive wall shapes of `fix wall/gran` and their force loop,
//! monomorphised per contact model like the pair loop.

use super::*;
use crate::engine::contact::{CoeffLanes, WallLanes};

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
    pub(super) fn surface_velocity(&self, shear: Option<(usize, f64)>, pos: [f64; 3]) -> [f64; 3] {
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
    pub(super) fn resolve(&self, pos: [f64; 3], r: f64) -> (f64, [f64; 3]) {
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

impl Primitive {
    /// LIGGGHTS's neighbour-list test of a particle at `pos` of radius `r` (length) with
    /// `threshold` (length): a plane within `r + threshold` of the centre; for a cylinder
    /// LIGGGHTS's test, which lets nearly every particle in.
    pub fn near(&self, pos: [f64; 3], r: f64, threshold: f64) -> bool {
        let reach = r + threshold;
        match *self {
            Primitive::Plane { axis, position } => (pos[axis] - position).abs() <= reach,
            Primitive::Cylinder {
                axis,
                radius,
                c1,
                c2,
            } => {
                let dy = pos[(axis + 1) % 3] - c1;
                let dz = pos[(axis + 2) % 3] - c2;
                let dist = (dy * dy + dz * dz).sqrt() - radius;
                reach < dist || -reach < dist
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
    /// `store`: the wall's contacts as `fix multicontact/halfspace` gathered them (walls of
    /// `surface multicontact` only).
    #[allow(clippy::too_many_arguments)]
    fn compute(
        &mut self,
        p: &mut Particles,
        group: u32,
        history: &mut [f64],
        dt: f64,
        update: bool,
        list: (u64, f64),
        store: Option<&super::multicontact_store::WallStore>,
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
    /// Each near particle's force and torque this step (None: apart), kept between steps.
    results: Vec<Option<([f64; 3], [f64; 3])>>,
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
        _store: Option<&super::multicontact_store::WallStore>,
    ) {
        let w = self.model.history_len();
        if self.near_build != Some(list.0) {
            // refresh the wall's neighbour list; particles off it are apart: their history
            // is reset (found by a scan, so particles reordered since the last list build
            // are treated alike)
            self.near.clear();
            for i in 0..p.len() {
                if p.mask[i] & group != 0 && self.shape.resolve(p.x[i], p.radius[i]).0 < list.1 {
                    self.near.push(i as u32);
                }
            }
            if w > 0 {
                let mut next = self.near.iter().peekable();
                for (i, h) in history.chunks_mut(w).enumerate().take(p.len()) {
                    if next.peek().is_some_and(|&&k| k as usize == i) {
                        next.next();
                    } else if h.iter().any(|v| *v != 0.0) {
                        h.fill(0.0);
                    }
                }
            }
            self.near_build = Some(list.0);
        }
        // each particle near the wall is its own contact: computed on the engine's
        // threads when there are many, each writing only its own force and history
        let mut results = std::mem::take(&mut self.results);
        let this = &*self;
        let near = &this.near;
        results.clear();
        results.resize(near.len(), None);
        let hist = SharedSlice(history.as_mut_ptr(), history.len());
        let step = WallStep { dt, update, w };
        // a fast-path team splits even a few hundred contacts; rayon only many
        let many = near.len() >= 256 && crate::util::team::is_active();
        if many || crate::engine::integrate::parallel(near.len()) {
            let out = crate::util::team::Shards::new(&mut results);
            let parts = &*p;
            crate::util::team::stage_chunks(near.len(), WALL_CHUNK, true, |_, r| {
                // SAFETY: the chunks of a stage are disjoint
                let out = unsafe { out.range(r.clone()) };
                // SAFETY: `near` holds distinct indices, so each chunk writes its own
                // particles' pieces of the history
                unsafe { this.contacts(parts, &near[r], out, hist, step) };
            });
        } else {
            // SAFETY: as above, on one thread
            unsafe { this.contacts(p, near, &mut results, hist, step) };
        }
        for (&i, r) in self.near.iter().zip(&results) {
            if let Some((f, t)) = r {
                let i = i as usize;
                for d in 0..3 {
                    p.f[i][d] += f[d];
                    p.torque[i][d] += t[d];
                }
            }
        }
        self.results = results;
    }
}

/// Four lanes from a function of the lane number.
#[inline(always)]
fn lane(f: impl Fn(usize) -> f64) -> F64x4 {
    F64x4([f(0), f(1), f(2), f(3)])
}

/// What every contact of one wall pass shares.
#[derive(Clone, Copy)]
struct WallStep {
    /// Time step (s).
    dt: f64,
    /// Advance and store history.
    update: bool,
    /// History doubles per particle.
    w: usize,
}

/// Particles resolved against the wall at a time, before their touching ones are computed.
const WALL_CHUNK: usize = 128;

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> WallGran<N, T, C, R> {
    /// The contacts of the particles `ids` with the wall: each one's force and torque into
    /// `out` (None: apart, its history reset), touching ones four at a time where the
    /// processor has the vector unit (the same values, bit for bit).
    ///
    /// # Safety
    /// `ids` are distinct, and no other thread touches their pieces of `hist`.
    unsafe fn contacts(
        &self,
        p: &Particles,
        ids: &[u32],
        out: &mut [Option<([f64; 3], [f64; 3])>],
        hist: SharedSlice,
        step: WallStep,
    ) {
        let w = step.w;
        let lanes = crate::engine::contact::real::lanes_supported() && w <= batch::MAX_HISTORY;
        for (ids, out) in ids.chunks(WALL_CHUNK).zip(out.chunks_mut(WALL_CHUNK)) {
            // resolve every particle; the apart ones are done here
            let mut touching = [(0usize, 0.0f64, [0.0f64; 3]); WALL_CHUNK];
            let mut n = 0;
            for (k, (&i, o)) in ids.iter().zip(out.iter_mut()).enumerate() {
                let i = i as usize;
                let (gap, to_wall) = self.shape.resolve(p.x[i], p.radius[i]);
                // a NaN gap is no contact
                if gap <= 0.0 {
                    touching[n] = (k, gap, to_wall);
                    n += 1;
                } else {
                    // apart: the history is reset (written only if it holds something)
                    // SAFETY: the caller's guarantee
                    let h = unsafe { hist.piece(i * w, w) };
                    if h.iter().any(|v| *v != 0.0) {
                        h.fill(0.0);
                    }
                    *o = None;
                }
            }
            let touching = &touching[..n];
            // (elsewhere than x86-64 every touching particle goes one at a time below)
            let quads = if lanes && cfg!(target_arch = "x86_64") {
                n / LANES
            } else {
                0
            };
            #[cfg(target_arch = "x86_64")]
            for q in touching.chunks_exact(LANES).take(quads) {
                let q: &[_; LANES] = q.try_into().expect("four lanes");
                // SAFETY: the processor has AVX2 (checked above); the caller's guarantee
                unsafe { self.four_avx2(p, ids, q, out, hist, step) };
            }
            for &(k, gap, to_wall) in &touching[LANES * quads..] {
                let i = ids[k] as usize;
                let input = WallInput {
                    x: p.x[i],
                    gap,
                    to_wall,
                    radius: p.radius[i],
                    mass: p.mass[i],
                    v: p.v[i],
                    omega: p.omega[i],
                    v_wall: self.shape.surface_velocity(self.shear, p.x[i]),
                    dt: step.dt,
                    update_history: step.update,
                    coeffs: self.material.pair(p.kind[i] as usize, self.wall_type),
                };
                // SAFETY: the caller's guarantee
                let res = self
                    .model
                    .wall_force(&input, unsafe { hist.piece(i * w, w) });
                out[k] = res.touching.then_some((res.f, res.t));
            }
        }
    }

    /// Four touching particles of [`Self::contacts`] (`quad`: their places in `ids` with
    /// gap and vector to the wall) in one lane batch.
    ///
    /// # Safety
    /// The processor has AVX2; as [`Self::contacts`].
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn four_avx2(
        &self,
        p: &Particles,
        ids: &[u32],
        quad: &[(usize, f64, [f64; 3]); LANES],
        out: &mut [Option<([f64; 3], [f64; 3])>],
        hist: SharedSlice,
        step: WallStep,
    ) {
        let w = step.w;
        let i = [
            ids[quad[0].0] as usize,
            ids[quad[1].0] as usize,
            ids[quad[2].0] as usize,
            ids[quad[3].0] as usize,
        ];
        let vec3 = |a: &[[f64; 3]]| {
            [
                lane(|k| a[i[k]][0]),
                lane(|k| a[i[k]][1]),
                lane(|k| a[i[k]][2]),
            ]
        };
        let v_wall: [[f64; 3]; LANES] = [
            self.shape.surface_velocity(self.shear, p.x[i[0]]),
            self.shape.surface_velocity(self.shear, p.x[i[1]]),
            self.shape.surface_velocity(self.shear, p.x[i[2]]),
            self.shape.surface_velocity(self.shear, p.x[i[3]]),
        ];
        let input = WallLanes {
            gap: lane(|k| quad[k].1),
            to_wall: [
                lane(|k| quad[k].2[0]),
                lane(|k| quad[k].2[1]),
                lane(|k| quad[k].2[2]),
            ],
            radius: lane(|k| p.radius[i[k]]),
            mass: lane(|k| p.mass[i[k]]),
            v: vec3(&p.v),
            omega: vec3(&p.omega),
            v_wall: [
                lane(|k| v_wall[k][0]),
                lane(|k| v_wall[k][1]),
                lane(|k| v_wall[k][2]),
            ],
            dt: step.dt,
            update_history: step.update,
        };
        let pair = |k: usize| self.material.pair(p.kind[i[k]] as usize, self.wall_type);
        let coeffs = CoeffLanes([pair(0), pair(1), pair(2), pair(3)]);
        // SAFETY: the caller's guarantee (distinct particles, their own pieces)
        let pieces = unsafe {
            [
                hist.piece(i[0] * w, w),
                hist.piece(i[1] * w, w),
                hist.piece(i[2] * w, w),
                hist.piece(i[3] * w, w),
            ]
        };
        let mut h = [F64x4::default(); batch::MAX_HISTORY];
        for (d, slot) in h.iter_mut().enumerate().take(w) {
            *slot = lane(|k| pieces[k][d]);
        }
        let (f, t) = self.model.wall_force_lanes(&input, &coeffs, &mut h[..w]);
        for (k, piece) in pieces.into_iter().enumerate() {
            for (d, v) in piece.iter_mut().enumerate() {
                *v = h[d].0[k];
            }
            out[quad[k].0] = Some((
                [f[0].0[k], f[1].0[k], f[2].0[k]],
                [t[0].0[k], t[1].0[k], t[2].0[k]],
            ));
        }
    }
}

/// A slice shared between threads that write disjoint pieces of it.
#[derive(Clone, Copy)]
pub(super) struct SharedSlice(*mut f64, usize);

// SAFETY: used only where every thread writes its own, disjoint piece (see `piece`).
unsafe impl Send for SharedSlice {}

unsafe impl Sync for SharedSlice {}

impl SharedSlice {
    /// The piece `start..start + len`.
    ///
    /// # Safety
    /// No other live reference may overlap the piece.
    #[allow(clippy::mut_from_ref)]
    unsafe fn piece(&self, start: usize, len: usize) -> &mut [f64] {
        assert!(start + len <= self.1);
        std::slice::from_raw_parts_mut(self.0.add(start), len)
    }
}

/// Build the wall interaction for a selection, monomorphised once per run.
pub fn build_wall(
    sel: &Selection,
    input: &MaterialInput,
    wall_type: usize,
    shape: Primitive,
    shear: Option<(usize, f64)>,
) -> Result<Box<dyn WallInteraction>, crate::engine::error::EngineError> {
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
                results: Vec::new(),
            })
        }
    }
    Ok(model.dispatch(Make(material, wall_type, shape, shear)))
}
