//! `pair_style gran ... cohesion easo/capillary/viscous`: the pair loop of wet particles.
//!
//! A dry contact model (normal, tangential, rolling) with LIGGGHTS 3.8.0's liquid bridge
//! ([`Easo`]) in the cohesion slot: its bridge flag is stored after the normal model's
//! history and before the tangential one. Every listed pair is visited in list order:
//! touching pairs run the sub-models in LIGGGHTS's order with the bridge between the normal
//! and tangential models; pairs apart but within the contact distance
//! (`factor (Ri + Rj)`, factor [`Easo::contact_distance_factor`]) reset the dry models'
//! history and keep, act through or break their bridge, a broken bridge adding its liquid
//! to the two particles' `liquidFlux`. Contributions are added to the particles as each
//! pair is done, as LIGGGHTS's pair loop adds them, so sums are the same for any thread
//! count and on either engine path.

// Component loops index several arrays the way LIGGGHTS writes them out per component.
#![allow(clippy::needless_range_loop)]

use crate::engine::contact::easo::{Close, Easo, Gap, Motion, WetPair};
use crate::engine::contact::{
    CohesionModel, ContactKernel, ContactModel, DefaultSurface, Material, NormalModel, PairCoeffs,
    RollingModel, SurfaceModel, TangentialModel,
};
use crate::engine::error::EngineError;
use crate::engine::neighbor::{Mirrored, Pair, SumOrder};
use crate::engine::particles::Particles;
use crate::engine::sim::{PairContact, PairInteraction};

use super::{add6, half_virial, model_and_material, touching_contact, Selection};

/// Name (fix ID) of the per-atom liquid content (LIGGGHTS's units: the film volume is
/// `4/3 1000 pi R^3` times it).
pub const LIQUID_CONTENT: &str = "surfaceLiquidContent";
/// Name of the per-atom liquid flux (content per second).
pub const LIQUID_FLUX: &str = "liquidFlux";
/// Name of the per-atom liquid source (content per second).
pub const LIQUID_SOURCE: &str = "liquidSource";

/// The wet part of a model: the bridge's coefficients and the contact angles.
#[derive(Debug, Clone, PartialEq)]
pub struct WetInput {
    /// The global coefficients.
    pub easo: Easo,
    /// `contactAngle` per atom type (degrees, index type - 1).
    pub contact_angle: Vec<f64>,
}

/// The wet pair interaction over a dry model `ContactModel<N, T, C, R>` (C is `cohesion
/// off`).
pub struct PairWet<N, T, C, R> {
    /// The dry sub-models.
    model: ContactModel<N, T, C, R>,
    /// Per-type-pair coefficients.
    material: Material,
    /// The bridge.
    easo: Easo,
    /// Effective contact angle per type pair (row-major, index (ti - 1) ntypes + tj - 1).
    angle: Vec<f64>,
    /// Number of atom types.
    ntypes: usize,
    /// Group bits of frozen particles.
    frozen: u32,
    /// Touching pairs at the last evaluation.
    touching: usize,
    /// The largest overlap of the last evaluation: (ratio to the smaller radius, i, j).
    worst: Option<(f64, u32, u32)>,
}

/// What one listed pair gives.
enum Outcome {
    /// Nothing (apart, or a bridge without force).
    None,
    /// Forces on i and j, torques on i and j (N, N m); the overlap ratio when touching.
    Force([[f64; 3]; 4], Option<f64>),
    /// The bridge broke: liquid fluxes into i and j (1/s).
    Flux(f64, f64),
}

/// Index of the per-atom array `name` (one column), if the particles hold it.
fn array(p: &Particles, name: &str) -> Option<usize> {
    p.extra.iter().position(|e| e.name == name && e.width == 1)
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairWet<N, T, C, R> {
    /// One listed pair; `h` its history, `liquid` the contents of i and j.
    #[inline]
    fn pair(
        &self,
        p: &Particles,
        pair: &Pair,
        h: &mut [f64],
        liquid: (f64, f64),
        dt: f64,
        update: bool,
    ) -> Outcome {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let xi = p.x[i];
        let xj = [
            p.x[j][0] + pair.shift[0],
            p.x[j][1] + pair.shift[1],
            p.x[j][2] + pair.shift[2],
        ];
        let (radi, radj) = (p.radius[i], p.radius[j]);
        let delx = xi[0] - xj[0];
        let dely = xi[1] - xj[1];
        let delz = xi[2] - xj[2];
        let rsq = delx * delx + dely * dely + delz * delz;
        let radsum = radi + radj;
        let (ti, tj) = (p.kind[i] as usize, p.kind[j] as usize);
        let wet = WetPair {
            is_wall: false,
            radi,
            radj,
            radsum,
            liquid_i: liquid.0,
            liquid_j: liquid.1,
            contact_angle: self.angle[(ti - 1) * self.ntypes + tj - 1],
            area_ratio: 1.0,
        };
        let nlen = self.model.normal.history_len();
        let tlen = self.model.tangential.history_len();
        let factor = self.easo.contact_distance_factor();
        if rsq < radsum * radsum {
            let r = rsq.sqrt();
            let radii = (radi, radj, radsum);
            let (delta, ij) = ([delx, dely, delz], (i, j));
            let mut c = touching_contact(p, ij, delta, r, radii, self.frozen, dt, update);
            let m: &PairCoeffs = self.material.pair(ti, tj);
            DefaultSurface.surfaces_intersect(&mut c);
            let (hn, rest) = h.split_at_mut(nlen);
            self.model.normal.surfaces_intersect(&mut c, m, hn);
            let (hc, rest) = rest.split_at_mut(1);
            let motion = Motion {
                en: c.en,
                vn: c.vn,
                vtr: c.vtr,
                cri: c.cri,
                crj: c.crj,
            };
            if let Some(w) = self.easo.intersect(&wet, &motion, &mut hc[0]) {
                if self.easo.tangential_reduce {
                    c.normal_force += w.normal;
                }
                for d in 0..3 {
                    c.fi[d] += w.f[d];
                    c.ti[d] += w.ti[d];
                    c.fj[d] -= w.f[d];
                    c.tj[d] += w.tj[d];
                }
            }
            let (ht, hr) = rest.split_at_mut(tlen);
            self.model.tangential.surfaces_intersect(&mut c, m, ht);
            self.model.rolling.surfaces_intersect(&mut c, m, hr);
            let ratio = c.deltan / radi.min(radj);
            return Outcome::Force([c.fi, c.fj, c.ti, c.tj], Some(ratio));
        }
        // a NaN distance is no contact
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if !(rsq < factor * factor * radsum * radsum) {
            return Outcome::None;
        }
        let (hn, rest) = h.split_at_mut(nlen);
        self.model.normal.surfaces_close(hn);
        let (hc, rest) = rest.split_at_mut(1);
        let (ht, hr) = rest.split_at_mut(tlen);
        self.model.tangential.surfaces_close(ht);
        self.model.rolling.surfaces_close(hr);
        let gap = Gap {
            delta: [delx, dely, delz],
            rsq,
            vi: p.v[i],
            vj: p.v[j],
            omegai: p.omega[i],
            omegaj: p.omega[j],
            dt,
        };
        match self.easo.close(&wet, &gap, &mut hc[0]) {
            Close::Dry | Close::Holds(None) => Outcome::None,
            Close::Holds(Some(w)) => {
                let fj = [-w.f[0], -w.f[1], -w.f[2]];
                Outcome::Force([w.f, fj, w.ti, w.tj], None)
            }
            Close::Breaks { flux_i, flux_j } => Outcome::Flux(flux_i, flux_j),
        }
    }

    /// Every listed pair in list order, each one's contributions added to `sums` as it is
    /// done.
    fn pass(
        &mut self,
        p: &Particles,
        pairs: &[Pair],
        history: &mut [f64],
        (dt, update): (f64, bool),
        sums: &mut Sums<'_>,
    ) {
        let width = self.history_width();
        let content = array(p, LIQUID_CONTENT).map(|k| &p.extra[k].data);
        let mut touching = 0;
        let mut worst: Option<(f64, u32, u32)> = None;
        for (k, pair) in pairs.iter().enumerate() {
            let (i, j) = (pair.i as usize, pair.j as usize);
            let liquid = content.map_or((0.0, 0.0), |c| (c[i], c[j]));
            let h = &mut history[k * width..(k + 1) * width];
            match self.pair(p, pair, h, liquid, dt, update) {
                Outcome::None => {}
                Outcome::Force(f, ratio) => {
                    if let Some(r) = ratio {
                        touching += 1;
                        if worst.is_none_or(|w| r > w.0) {
                            worst = Some((r, pair.i, pair.j));
                        }
                    }
                    sums.add(&p.x, pair, &f);
                }
                Outcome::Flux(a, b) => {
                    if !sums.flux.is_empty() {
                        sums.flux[i] += a;
                        sums.flux[j] += b;
                    }
                }
            }
        }
        self.touching = touching;
        self.worst = worst;
    }
}

/// Where a pass adds its contributions: forces (N), torques (N m), virials (N m, on steps
/// that tally them) and liquid fluxes (1/s; empty without the array).
struct Sums<'a> {
    f: &'a mut [[f64; 3]],
    torque: &'a mut [[f64; 3]],
    virial: Option<&'a mut [[f64; 6]]>,
    flux: &'a mut [f64],
}

impl Sums<'_> {
    /// Add one pair's forces and torques `r` (on i, on j, torque on i, torque on j) as
    /// LIGGGHTS does: i, then j.
    #[inline]
    fn add(&mut self, x: &[[f64; 3]], pair: &Pair, r: &[[f64; 3]; 4]) {
        let (i, j) = (pair.i as usize, pair.j as usize);
        if let Some(w) = self.virial.as_deref_mut() {
            let half = half_virial(x, pair, r[0]);
            add6(&mut w[i], &half);
            add6(&mut w[j], &half);
        }
        for d in 0..3 {
            self.f[i][d] += r[0][d];
            self.torque[i][d] += r[2][d];
        }
        for d in 0..3 {
            self.f[j][d] += r[1][d];
            self.torque[j][d] += r[3][d];
        }
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairInteraction
    for PairWet<N, T, C, R>
{
    fn history_width(&self) -> usize {
        self.model.history_len() + 1
    }

    fn history_flips(&self) -> Vec<bool> {
        let mut v = self.model.normal.history_flips().to_vec();
        v.push(false);
        v.resize(self.history_width(), true);
        v
    }

    fn contact_count(&self) -> usize {
        self.touching
    }

    fn worst_overlap(&self) -> Option<(f64, u32, u32)> {
        self.worst
    }

    fn contact_distance_factor(&self) -> f64 {
        self.easo.contact_distance_factor()
    }

    fn contacts(
        &self,
        p: &Particles,
        pairs: &[Pair],
        history: &[f64],
        dt: f64,
        _ghost: (&[[f64; 3]], &[[f64; 3]]),
    ) -> Vec<PairContact> {
        let width = self.history_width();
        let content = array(p, LIQUID_CONTENT).map(|k| &p.extra[k].data);
        let mut out = Vec::new();
        let mut h = vec![0.0; width];
        for (k, pair) in pairs.iter().enumerate() {
            let (i, j) = (pair.i as usize, pair.j as usize);
            h.copy_from_slice(&history[k * width..(k + 1) * width]);
            let liquid = content.map_or((0.0, 0.0), |c| (c[i], c[j]));
            if let Outcome::Force(f, Some(_)) = self.pair(p, pair, &mut h, liquid, dt, false) {
                out.push((k, f[0], f[2], f[1], f[3]));
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
        virial: Option<&mut [[f64; 6]]>,
        _order: &SumOrder,
        _mirrored: Option<Mirrored<'_>>,
    ) {
        // the pair style sets the sums (see PairInteraction::compute)
        p.clear_forces();
        let kf = array(p, LIQUID_FLUX);
        let mut flux = kf.map_or_else(Vec::new, |k| std::mem::take(&mut p.extra[k].data));
        let mut f = std::mem::take(&mut p.f);
        let mut torque = std::mem::take(&mut p.torque);
        let mut sums = Sums {
            f: &mut f,
            torque: &mut torque,
            virial,
            flux: &mut flux,
        };
        self.pass(p, pairs, history, (dt, update), &mut sums);
        p.f = f;
        p.torque = torque;
        if let Some(k) = kf {
            p.extra[k].data = flux;
        }
    }
}

/// Build the wet pair interaction: `sel` with cohesion `easo/capillary/viscous`, the dry
/// rest of it monomorphised as [`super::build`] does.
pub fn build_wet(
    sel: &Selection,
    input: &crate::engine::contact::MaterialInput,
    frozen: u32,
    wet: &WetInput,
) -> Result<Box<dyn PairInteraction>, EngineError> {
    let dry = crate::engine::wet::dry(sel);
    let (model, material) = model_and_material(&dry, input)?;
    let n = wet.contact_angle.len();
    let mut angle = vec![0.0; n * n];
    for a in 0..n {
        for b in 0..n {
            angle[a * n + b] = crate::engine::contact::easo::effective_contact_angle(
                wet.contact_angle[a],
                wet.contact_angle[b],
            );
        }
    }
    let mut easo = wet.easo;
    easo.tangential_reduce = sel.options.tangential_reduce;
    struct Make(Material, u32, Easo, Vec<f64>, usize);
    impl ContactKernel for Make {
        type Output = Box<dyn PairInteraction>;
        fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
            self,
            m: &ContactModel<N, T, C, R>,
        ) -> Self::Output {
            Box::new(PairWet {
                model: *m,
                material: self.0,
                easo: self.2,
                angle: self.3,
                ntypes: self.4,
                frozen: self.1,
                touching: 0,
                worst: None,
            })
        }
    }
    Ok(model.dispatch(Make(material, frozen, easo, angle, n)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::contact::MaterialInput;
    use crate::engine::heat::add_property;

    /// Two wet spheres (radii 1 mm and 0.8 mm, content 0.05) on the x axis, `gap` apart.
    fn setup(gap: f64) -> (Box<dyn PairInteraction>, Particles, Vec<Pair>) {
        let sel = Selection::parse(&[
            "model",
            "hertz",
            "tangential",
            "history",
            "cohesion",
            "easo/capillary/viscous",
        ])
        .unwrap();
        let input = MaterialInput {
            ntypes: 1,
            youngs_modulus: Some(vec![5e6]),
            poissons_ratio: Some(vec![0.3]),
            coefficient_restitution: Some(vec![0.5]),
            coefficient_friction: Some(vec![0.5]),
            ..MaterialInput::default()
        };
        let wet = WetInput {
            easo: Easo {
                surface_tension: 0.072,
                fluid_viscosity: 0.01,
                min_separation: 1.01,
                max_separation: 1.1,
                tangential_reduce: false,
            },
            contact_angle: vec![20.0],
        };
        let model = build_wet(&sel, &input, 0, &wet).unwrap();
        let mut p = Particles::default();
        p.push(1, 1, [0.0; 3], 0.001, 2500.0);
        p.push(2, 1, [0.0018 + gap, 0.0, 0.0], 0.0008, 2500.0);
        add_property(&mut p, LIQUID_CONTENT, &[0.05]);
        add_property(&mut p, LIQUID_FLUX, &[0.0]);
        let pairs = vec![Pair {
            i: 0,
            j: 1,
            shift: [0.0; 3],
        }];
        (model, p, pairs)
    }

    fn step(
        model: &mut Box<dyn PairInteraction>,
        p: &mut Particles,
        pairs: &[Pair],
        h: &mut [f64],
    ) {
        p.f = vec![[0.0; 3]; 2];
        p.torque = vec![[0.0; 3]; 2];
        model.compute(p, pairs, h, 1e-6, true, None, &SumOrder::default(), None);
    }

    #[test]
    fn a_bridge_forms_at_contact_holds_across_a_gap_and_breaks_past_its_limit() {
        // hertz keeps no history: [flag, shear x3]
        let (mut model, mut p, pairs) = setup(-1e-6);
        assert_eq!(model.history_width(), 4);
        assert!(model.contact_distance_factor() > 1.2);
        let mut h = vec![0.0; 4];
        step(&mut model, &mut p, &pairs, &mut h);
        assert_eq!(h[0], 1.0, "the bridge forms on contact");
        // apart by 0.1 mm (below the 0.18 mm limit): it holds and pulls the two together
        p.x[1][0] = 0.0018 + 1e-4;
        h[1] = 1e-9;
        step(&mut model, &mut p, &pairs, &mut h);
        assert_eq!(h[0], 1.0);
        assert_eq!(h[1], 0.0, "the tangential history is reset apart");
        assert!(p.f[0][0] > 0.0 && p.f[1][0] < 0.0, "{:?}", p.f);
        assert_eq!(p.f[0][0], -p.f[1][0]);
        let k = p.extra.iter().position(|e| e.name == LIQUID_FLUX).unwrap();
        assert_eq!(p.extra[k].data, vec![0.0, 0.0]);
        // beyond (maxSeparationDistanceRatio - 1)(Ri + Rj): it breaks, no force, the liquid
        // moves to the larger sphere by volume
        p.x[1][0] = 0.0018 + 2e-4;
        step(&mut model, &mut p, &pairs, &mut h);
        assert_eq!(h[0], 0.0);
        assert_eq!(p.f, vec![[0.0; 3]; 2]);
        let flux = &p.extra[k].data;
        assert!(flux[0] > 0.0 && flux[1] < 0.0, "{flux:?}");
        // the liquid is conserved: film volumes scale as R^3
        let (v0, v1) = (flux[0] * 1e-9, flux[1] * 0.512e-9);
        assert!((v0 + v1).abs() < 1e-12 * v0.abs(), "{v0} {v1}");
        // broken: no force when it comes back within reach without touching
        p.x[1][0] = 0.0018 + 1e-4;
        step(&mut model, &mut p, &pairs, &mut h);
        assert_eq!(p.f, vec![[0.0; 3]; 2]);
    }

    #[test]
    fn dry_spheres_apart_feel_no_bridge() {
        let (mut model, mut p, pairs) = setup(1e-4);
        let mut h = vec![0.0; 4];
        step(&mut model, &mut p, &pairs, &mut h);
        assert_eq!(h[0], 0.0);
        assert_eq!(p.f, vec![[0.0; 3]; 2]);
    }
}
