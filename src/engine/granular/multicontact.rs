//! `pair_style gran ... surface multicontact` with `fix multicontact/halfspace`: the pair
//! loop of the multiple-contact model ([`crate::engine::contact::multicontact`]).
//!
//! Each force evaluation first does what LIGGGHTS's fix does in `pre_force`: every particle
//! of the fix's group gathers, in atom order, the contact surfaces and normal forces of its
//! listed pairs from their history (the pair's other particle gets the mirrored entry), then
//! turns the forces into radius changes. The pair loop then visits every listed pair in list
//! order: i's and j's radii for this pair are their radii plus their changes at this
//! contact, touching pairs run the dry sub-models in LIGGGHTS's order (the surface model's
//! kinematics are `surface default`'s; i's own radius stays unchanged there, as LIGGGHTS
//! passes it), and pairs within twice the changed radius sum reset the dry history and
//! store their radii. Contributions are added as each pair is done, as LIGGGHTS adds them,
//! so the sums are the same on either engine path.

use crate::engine::contact::multicontact::{
    pair_surfaces, radius_changes, Entry, HalfSpace, CONTACT_DISTANCE_FACTOR, PAIR_HISTORY,
};
use crate::engine::contact::{
    CohesionModel, ContactKernel, ContactModel, Material, NormalModel, RollingModel,
    TangentialModel,
};
use crate::engine::error::EngineError;
use crate::engine::neighbor::{Mirrored, Pair, SumOrder};
use crate::engine::particles::Particles;
use crate::engine::sim::{PairContact, PairInteraction};

use super::multicontact_store::WallStore;
use super::{add6, half_virial, model_and_material, touching_contact, Selection};

/// What the fix `multicontact/halfspace` gives the pair style.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MulticontactInput {
    /// `geometric_prefactor` (gamma, dimensionless).
    pub prefactor: f64,
    /// Group bits of the fix (only its particles gather their contacts).
    pub group: u32,
}

/// The multiple-contact pair interaction over a dry model `ContactModel<N, T, C, R>`.
pub struct PairMulti<N, T, C, R> {
    /// The dry sub-models.
    model: ContactModel<N, T, C, R>,
    /// Per-type-pair coefficients.
    material: Material,
    /// Group bits of frozen particles.
    frozen: u32,
    /// The fix's group.
    group: u32,
    /// The half-space constants per atom type (index type - 1).
    halfspace: Vec<HalfSpace>,
    /// Per particle, its contacts of this evaluation: (partner ID, entry), LIGGGHTS's
    /// `multicontactData_` partners in the order they were added.
    partners: Vec<Vec<(i64, Entry)>>,
    /// One particle's entries while its radius changes are worked out (kept between
    /// particles and steps, so the pass allocates nothing).
    scratch: Vec<Entry>,
    /// The walls' gathered contacts (primitive walls and meshes in wall order), each
    /// particle's after its pair contacts.
    walls: Vec<WallStore>,
    /// Touching pairs at the last evaluation.
    touching: usize,
    /// The largest overlap of the last evaluation: (ratio to the smaller radius, i, j).
    worst: Option<(f64, u32, u32)>,
}

/// What one listed pair gives: forces on i and j, torques on i and j (N, N m) and the
/// overlap ratio, when touching.
type Touch = ([[f64; 3]; 4], f64);

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairMulti<N, T, C, R> {
    /// The radius change particle `i` has at its contact with the particle of ID `partner`
    /// (the first such entry, as LIGGGHTS looks it up; 0 without one).
    fn change(&self, i: usize, partner: i64) -> f64 {
        self.partners
            .get(i)
            .and_then(|l| l.iter().find(|e| e.0 == partner))
            .map_or(0.0, |e| e.1[3])
    }

    /// LIGGGHTS's `pre_force` of the fix: gather every group particle's contacts from the
    /// pair history, then turn their forces into radius changes.
    fn gather(&mut self, p: &Particles, pairs: &[Pair], history: &[f64]) {
        let n = p.len();
        let width = self.history_width();
        self.partners.resize_with(n, Vec::new);
        self.partners.truncate(n);
        for l in &mut self.partners {
            l.clear();
        }
        // LIGGGHTS walks its atoms in order and each atom's own list entries
        let mut order: Vec<u32> = (0..pairs.len() as u32).collect();
        order.sort_by_key(|&k| pairs[k as usize].i);
        for &k in &order {
            let pair = &pairs[k as usize];
            let (i, j) = (pair.i as usize, pair.j as usize);
            if p.mask[i] & self.group == 0 {
                continue;
            }
            let hs = &self.halfspace[p.kind[i] as usize - 1];
            let f_eps = hs.force_eps(p.radius[i]);
            let xij = std::array::from_fn(|d| p.x[j][d] + pair.shift[d] - p.x[i][d]);
            let h = &history[k as usize * width..k as usize * width + PAIR_HISTORY];
            let (ij, ji) = pair_surfaces(xij, h, f_eps);
            let f = h[2];
            self.partners[i].push((p.id[j], [ij[0], ij[1], ij[2], f]));
            self.partners[j].push((p.id[i], [ji[0], ji[1], ji[2], f]));
        }
        for i in 0..n {
            if p.mask[i] & self.group == 0 {
                continue;
            }
            let hs = self.halfspace[p.kind[i] as usize - 1];
            let r = p.radius[i];
            let entries = &mut self.scratch;
            entries.clear();
            entries.extend(self.partners[i].iter().map(|e| e.1));
            for s in &self.walls {
                entries.extend(s.slots(i).map(|k| s.entry(k)));
            }
            radius_changes(entries, &hs, r, hs.force_eps(r));
            let n = self.partners[i].len();
            for (e, v) in self.partners[i].iter_mut().zip(entries.iter()) {
                e.1 = *v;
            }
            let mut at = n;
            for s in &mut self.walls {
                for k in s.slots(i) {
                    s.set_change(k, entries[at][3]);
                    at += 1;
                }
            }
        }
    }

    /// One listed pair; `h` its history.
    #[inline]
    fn pair(
        &self,
        p: &Particles,
        pair: &Pair,
        h: &mut [f64],
        dt: f64,
        update: bool,
    ) -> Option<Touch> {
        let (i, j) = (pair.i as usize, pair.j as usize);
        let xi = p.x[i];
        let xj = std::array::from_fn::<f64, 3, _>(|d| p.x[j][d] + pair.shift[d]);
        let delx = xi[0] - xj[0];
        let dely = xi[1] - xj[1];
        let delz = xi[2] - xj[2];
        let rsq = delx * delx + dely * dely + delz * delz;
        let radi = p.radius[i] + self.change(i, p.id[j]);
        let radj = p.radius[j] + self.change(j, p.id[i]);
        let radsum = radi + radj;
        let (hs, hm) = h.split_at_mut(PAIR_HISTORY);
        if rsq < radsum * radsum {
            let r = rsq.sqrt();
            // LIGGGHTS passes i's unchanged radius to the sub-models
            let radii = (p.radius[i], radj, radsum);
            let (delta, ij) = ([delx, dely, delz], (i, j));
            let mut c = touching_contact(p, ij, delta, r, radii, self.frozen, dt, update);
            if update {
                hs[0] = c.radi;
                hs[1] = c.radj;
            }
            let m = self.material.pair(p.kind[i] as usize, p.kind[j] as usize);
            self.model.intersect(&mut c, m, hm);
            if update {
                hs[2] = (c.fi[0] * c.en[0] + c.fi[1] * c.en[1] + c.fi[2] * c.en[2]).abs();
            }
            let ratio = c.deltan / p.radius[i].min(p.radius[j]);
            return Some(([c.fi, c.fj, c.ti, c.tj], ratio));
        }
        let reach = CONTACT_DISTANCE_FACTOR * CONTACT_DISTANCE_FACTOR;
        if rsq < reach * radsum * radsum {
            if update {
                hs[0] = p.radius[i];
                hs[1] = radj;
                hs[2] = 0.0;
            }
            self.model.surfaces_close(hm);
        }
        None
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairInteraction
    for PairMulti<N, T, C, R>
{
    fn history_width(&self) -> usize {
        PAIR_HISTORY + self.model.history_len()
    }

    fn history_flips(&self) -> Vec<bool> {
        let mut v = vec![false; PAIR_HISTORY];
        v.extend(self.model.history_flips());
        v
    }

    fn contact_count(&self) -> usize {
        self.touching
    }

    fn worst_overlap(&self) -> Option<(f64, u32, u32)> {
        self.worst
    }

    fn contact_distance_factor(&self) -> f64 {
        CONTACT_DISTANCE_FACTOR
    }

    fn multicontact_walls(&mut self) -> Option<&mut Vec<WallStore>> {
        Some(&mut self.walls)
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
        let mut out = Vec::new();
        let mut h = vec![0.0; width];
        for (k, pair) in pairs.iter().enumerate() {
            h.copy_from_slice(&history[k * width..(k + 1) * width]);
            if let Some((f, _)) = self.pair(p, pair, &mut h, dt, false) {
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
        mut virial: Option<&mut [[f64; 6]]>,
        _order: &SumOrder,
        _mirrored: Option<Mirrored<'_>>,
    ) {
        self.gather(p, pairs, history);
        // the pair style sets the sums (see PairInteraction::compute)
        p.clear_forces();
        let width = self.history_width();
        let mut f = std::mem::take(&mut p.f);
        let mut torque = std::mem::take(&mut p.torque);
        let mut touching = 0;
        let mut worst: Option<(f64, u32, u32)> = None;
        for (k, pair) in pairs.iter().enumerate() {
            let h = &mut history[k * width..(k + 1) * width];
            let Some((r, ratio)) = self.pair(p, pair, h, dt, update) else {
                continue;
            };
            touching += 1;
            if worst.is_none_or(|w| ratio > w.0) {
                worst = Some((ratio, pair.i, pair.j));
            }
            let (i, j) = (pair.i as usize, pair.j as usize);
            if let Some(w) = virial.as_deref_mut() {
                let half = half_virial(&p.x, pair, r[0]);
                add6(&mut w[i], &half);
                add6(&mut w[j], &half);
            }
            for d in 0..3 {
                f[i][d] += r[0][d];
                torque[i][d] += r[2][d];
            }
            for d in 0..3 {
                f[j][d] += r[1][d];
                torque[j][d] += r[3][d];
            }
        }
        p.f = f;
        p.torque = torque;
        self.touching = touching;
        self.worst = worst;
    }
}

/// Build the multiple-contact pair interaction: `sel` with `surface multicontact`, its dry
/// rest monomorphised as [`super::build`] does; Young's moduli and Poisson ratios per type
/// from the materials.
pub fn build_multicontact(
    sel: &Selection,
    input: &crate::engine::contact::MaterialInput,
    frozen: u32,
    mc: MulticontactInput,
) -> Result<Box<dyn PairInteraction>, EngineError> {
    let mut dry = sel.clone();
    dry.surface = "default".into();
    let (model, material) = model_and_material(&dry, input)?;
    let missing = |name: &str| -> EngineError {
        format!("Could not locate a fix/property storing value(s) for {name} as requested by multicontact/halfspace.").into()
    };
    let y = input
        .youngs_modulus
        .as_ref()
        .ok_or_else(|| missing("youngsModulus"))?;
    let nu = input
        .poissons_ratio
        .as_ref()
        .ok_or_else(|| missing("poissonsRatio"))?;
    let halfspace: Vec<HalfSpace> = (0..input.ntypes)
        .map(|t| HalfSpace::new(y[t], nu[t], mc.prefactor))
        .collect();
    struct Make(Material, u32, MulticontactInput, Vec<HalfSpace>);
    impl ContactKernel for Make {
        type Output = Box<dyn PairInteraction>;
        fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
            self,
            m: &ContactModel<N, T, C, R>,
        ) -> Self::Output {
            Box::new(PairMulti {
                model: *m,
                material: self.0,
                frozen: self.1,
                group: self.2.group,
                halfspace: self.3,
                partners: Vec::new(),
                scratch: Vec::new(),
                walls: Vec::new(),
                touching: 0,
                worst: None,
            })
        }
    }
    Ok(model.dispatch(Make(material, frozen, mc, halfspace)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::contact::MaterialInput;

    /// Three spheres of radius 1 mm on the x axis, the middle one pressed by both others.
    fn setup() -> (Box<dyn PairInteraction>, Particles, Vec<Pair>) {
        let sel = Selection::parse(&["model", "hertz", "tangential", "history"]).unwrap();
        let input = MaterialInput {
            ntypes: 1,
            youngs_modulus: Some(vec![5e6]),
            poissons_ratio: Some(vec![0.3]),
            coefficient_restitution: Some(vec![0.5]),
            coefficient_friction: Some(vec![0.5]),
            ..MaterialInput::default()
        };
        let mc = MulticontactInput {
            prefactor: 1.125,
            group: 1,
        };
        let model = build_multicontact(&sel, &input, 0, mc).unwrap();
        let mut p = Particles::default();
        p.push(1, 1, [-0.00195, 0.0, 0.0], 0.001, 2500.0);
        p.push(2, 1, [0.0, 0.0, 0.0], 0.001, 2500.0);
        p.push(3, 1, [0.00195, 0.0, 0.0], 0.001, 2500.0);
        let pairs = [(0, 1), (1, 2)]
            .map(|(i, j)| Pair {
                i,
                j,
                shift: [0.0; 3],
            })
            .to_vec();
        (model, p, pairs)
    }

    #[test]
    fn the_history_keeps_radii_and_normal_force_and_the_next_step_feels_them() {
        let (mut model, mut p, pairs) = setup();
        assert_eq!(model.history_width(), 6);
        assert_eq!(model.contact_distance_factor(), 2.0);
        let mut h = vec![0.0; 12];
        model.compute(
            &mut p,
            &pairs,
            &mut h,
            1e-6,
            true,
            None,
            &SumOrder::default(),
            None,
        );
        // no force stored yet: no radius change, plain Hertz at 0.05 mm overlap
        assert_eq!(h[0], 0.001);
        assert_eq!(h[1], 0.001);
        let f_first = p.f[0][0];
        assert!(f_first < 0.0);
        assert_eq!(h[2], -f_first, "fn is the normal force on i");
        // the middle sphere pressed at +x gets pushed out at -x and vice versa: both contacts
        // of the middle sphere grow, the outer ones (one contact each) do not
        model.compute(
            &mut p,
            &pairs,
            &mut h,
            1e-6,
            true,
            None,
            &SumOrder::default(),
            None,
        );
        let grown = h[1];
        assert!(grown > 0.001, "{grown}");
        assert_eq!(h[0], 0.001, "i's own radius is stored unchanged");
        assert!(
            p.f[0][0] < f_first,
            "the larger contact radius pushes harder"
        );
        assert!(p.f[2][0] > -f_first);
        // LIGGGHTS gives the models i's unchanged radius: the middle sphere's change enters
        // Hertz's effective radius where it is j (pair 1-2) but not where it is i (pair 2-3)
        assert!(p.f[2][0] < -p.f[0][0], "{:?}", p.f);
    }

    #[test]
    fn pairs_apart_within_twice_the_radius_sum_store_their_radii() {
        let (mut model, mut p, pairs) = setup();
        p.x[2][0] = 0.0035;
        let mut h = vec![0.0; 12];
        h[9] = 1e-9;
        model.compute(
            &mut p,
            &pairs,
            &mut h,
            1e-6,
            true,
            None,
            &SumOrder::default(),
            None,
        );
        assert_eq!(&h[6..9], &[0.001, 0.001, 0.0]);
        assert_eq!(h[9], 0.0, "the tangential history is reset apart");
        assert_eq!(p.f[2], [0.0; 3]);
    }
}
