//! Granular walls: the primitive wall shapes of `fix wall/gran` and their force loop,
//! monomorphised per contact model like the pair loop.

use super::*;

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
        let (x, v, omega, radius, mass, kind) = (&p.x, &p.v, &p.omega, &p.radius, &p.mass, &p.kind);
        let contact = |i: usize, h: &mut [f64]| -> Option<([f64; 3], [f64; 3])> {
            let (gap, to_wall) = this.shape.resolve(x[i], radius[i]);
            // a NaN gap is no contact
            #[allow(clippy::neg_cmp_op_on_partial_ord)]
            if !(gap <= 0.0) {
                // apart: the history is reset (written only if it holds something)
                if h.iter().any(|v| *v != 0.0) {
                    h.iter_mut().for_each(|v| *v = 0.0);
                }
                return None;
            }
            let input = WallInput {
                x: x[i],
                gap,
                to_wall,
                radius: radius[i],
                mass: mass[i],
                v: v[i],
                omega: omega[i],
                v_wall: this.shape.surface_velocity(this.shear, x[i]),
                dt,
                update_history: update,
                coeffs: this.material.pair(kind[i] as usize, this.wall_type),
            };
            let out = this.model.wall_force(&input, h);
            out.touching.then_some((out.f, out.t))
        };
        let near = &this.near;
        results.clear();
        results.resize(near.len(), None);
        // a fast-path team splits even a few hundred contacts; rayon only many
        let many = near.len() >= 256 && crate::util::team::is_active();
        if many || crate::engine::integrate::parallel(near.len()) {
            let hist = SharedSlice(history.as_mut_ptr(), history.len());
            let out = crate::util::team::Shards::new(&mut results);
            crate::util::team::stage_chunks(near.len(), 128, true, |_, r| {
                // SAFETY: the chunks of a stage are disjoint
                let out = unsafe { out.range(r.clone()) };
                for (o, &i) in out.iter_mut().zip(&near[r]) {
                    let i = i as usize;
                    // SAFETY: `near` holds distinct indices, so each call writes its own
                    // disjoint w-wide piece of the history
                    *o = contact(i, unsafe { hist.piece(i * w, w) });
                }
            });
        } else {
            for (o, &i) in results.iter_mut().zip(near) {
                let i = i as usize;
                *o = contact(i, &mut history[i * w..(i + 1) * w]);
            }
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
