//! `fix wall/gran ... surface multicontact primitive ...`: a primitive wall's contacts under
//! the multiple-contact model ([`crate::engine::contact::multicontact_wall`]), in LIGGGHTS
//! 3.8.0's order.
//!
//! The wall keeps its own list of the particles within the skin of it, rebuilt with the
//! pair list (particles off it keep their history untouched, `fix multicontact/halfspace`
//! still reads it). For each listed particle of the wall's group: its radius at this wall
//! is its radius plus the change the half-space step found in the wall's store
//! ([`WallStore`]), scanned only while the particle is within half the skin of the wall;
//! the wall is resolved with that radius. Touching, the sub-models run with the changed
//! radius and the surface values follow; apart by less than the unchanged radius, the
//! surface sits at the changed radius and the other models' `surfacesClose` runs; farther,
//! the whole history is reset.

use super::multicontact_store::WallStore;
use super::wall::{Primitive, WallInteraction};
use super::*;
use crate::engine::contact::multicontact_wall::{apart, touching, WALL_HISTORY, WALL_REACH};

/// A primitive wall of the multiple-contact model (the wall has infinite mass).
pub struct WallMulti<N, T, C, R> {
    /// The dry sub-models.
    model: ContactModel<N, T, C, R>,
    /// Coefficients (the wall has atom type `wall_type`).
    material: Material,
    /// The wall's atom type.
    wall_type: usize,
    /// The wall's shape.
    shape: Primitive,
    /// `shear dim vshear` (dimension, m/s) if the wall surface moves.
    shear: Option<(usize, f64)>,
    /// Contacts resolved farther than this (m, LIGGGHTS's `cutneighmax`) are skipped.
    cutneighmax: f64,
    /// Particles listed at the last list build (LIGGGHTS's primitive wall neighbour list).
    near: Vec<u32>,
    /// The pair-list build `near` belongs to.
    near_build: Option<u64>,
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> WallInteraction
    for WallMulti<N, T, C, R>
{
    fn history_width(&self) -> usize {
        WALL_HISTORY + self.model.history_len()
    }

    fn compute(
        &mut self,
        p: &mut Particles,
        group: u32,
        history: &mut [f64],
        dt: f64,
        update: bool,
        list: (u64, f64),
        store: Option<&WallStore>,
    ) {
        let skin = list.1;
        if self.near_build != Some(list.0) {
            self.near.clear();
            for i in 0..p.len() {
                if self.shape.near(p.x[i], p.radius[i], skin) {
                    self.near.push(i as u32);
                }
            }
            self.near_build = Some(list.0);
        }
        let w = self.history_width();
        for k in 0..self.near.len() {
            let i = self.near[k] as usize;
            if i >= p.len() || p.mask[i] & group == 0 {
                continue;
            }
            let h = &mut history[i * w..(i + 1) * w];
            if let Some((f, t)) = self.contact(p, i, h, dt, update, skin, store) {
                for d in 0..3 {
                    p.f[i][d] += f[d];
                    p.torque[i][d] += t[d];
                }
            }
        }
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> WallMulti<N, T, C, R> {
    /// One listed particle `i` with its history `h`: the force and torque on it when it
    /// touches the wall.
    #[allow(clippy::too_many_arguments)]
    fn contact(
        &self,
        p: &Particles,
        i: usize,
        h: &mut [f64],
        dt: f64,
        update: bool,
        skin: f64,
        store: Option<&WallStore>,
    ) -> Option<([f64; 3], [f64; 3])> {
        let r = p.radius[i];
        // the store is scanned over the slot the particle would reserve now
        let scan = usize::from(self.shape.near(p.x[i], r, 0.5 * skin));
        let radius = r + store.and_then(|s| s.change(i, 1, scan)).unwrap_or(0.0);
        let (gap, to_wall) = self.shape.resolve(p.x[i], radius);
        if gap > self.cutneighmax {
            return None;
        }
        // a NaN gap resets the history, as LIGGGHTS's comparisons do
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(gap <= 0.0 || gap < WALL_REACH * r) {
            h.fill(0.0);
            return None;
        }
        let (hs, hm) = h.split_at_mut(WALL_HISTORY);
        if gap > 0.0 {
            if update {
                apart(hs, to_wall, radius);
            }
            self.model.surfaces_close(hm);
            return None;
        }
        let input = WallInput {
            x: p.x[i],
            gap,
            to_wall,
            radius,
            mass: p.mass[i],
            v: p.v[i],
            omega: p.omega[i],
            v_wall: self.shape.surface_velocity(self.shear, p.x[i]),
            dt,
            update_history: update,
            coeffs: self.material.pair(p.kind[i] as usize, self.wall_type),
        };
        let out = self.model.wall_force(&input, hm);
        if update {
            touching(hs, to_wall, out.f, out.en);
        }
        Some((out.f, out.t))
    }
}

/// Build a primitive wall of the multiple-contact model: `sel` with `surface multicontact`,
/// its dry rest monomorphised as [`build_wall`] does; `cutneighmax` (m) as LIGGGHTS's.
pub fn build_wall_multicontact(
    sel: &Selection,
    input: &MaterialInput,
    wall: (usize, Primitive, Option<(usize, f64)>),
    cutneighmax: f64,
) -> Result<Box<dyn WallInteraction>, EngineError> {
    let mut dry = sel.clone();
    dry.surface = "default".into();
    let (model, material) = model_and_material(&dry, input)?;
    struct Make(Material, (usize, Primitive, Option<(usize, f64)>), f64);
    impl ContactKernel for Make {
        type Output = Box<dyn WallInteraction>;
        fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
            self,
            m: &ContactModel<N, T, C, R>,
        ) -> Self::Output {
            Box::new(WallMulti {
                model: *m,
                material: self.0,
                wall_type: self.1 .0,
                shape: self.1 .1,
                shear: self.1 .2,
                cutneighmax: self.2,
                near: Vec::new(),
                near_build: None,
            })
        }
    }
    Ok(model.dispatch(Make(material, wall, cutneighmax)))
}
