//! Granular contacts (`pair_style gran`), composed from sub-models chosen once per run:
//! a normal model ([`normal`]) and a tangential model ([`tangential`]). Each combination is
//! a separate monomorphised kernel, so a deck without history stores none and runs no
//! history code. The arithmetic follows LIGGGHTS 3.8.0 operation by operation.

pub mod cohesion;
pub mod material;
pub mod normal;
pub mod rolling;
pub mod tangential;

use rayon::prelude::*;

use crate::engine::neighbor::Pair;
use crate::engine::particles::Particles;
use crate::engine::sim::PairInteraction;
use cohesion::CohesionModel;
use material::Material;
use normal::NormalModel;
use rolling::RollingModel;
use tangential::TangentialModel;

/// One touching pair as the sub-models see it (LIGGGHTS's `SurfacesIntersectData`).
#[derive(Debug, Clone, Default)]
pub struct Contact {
    /// Types of the two particles (1-based).
    pub itype: usize,
    /// Type of the second particle.
    pub jtype: usize,
    /// Unit normal pointing from j to i.
    pub en: [f64; 3],
    /// Separation x_i - x_j (length).
    pub delta: [f64; 3],
    /// Overlap (length).
    pub deltan: f64,
    /// Effective radius (length).
    pub reff: f64,
    /// Effective mass (mass).
    pub meff: f64,
    /// Normal relative velocity (length/time, positive when separating).
    pub vn: f64,
    /// Tangential relative velocity at the contact point (length/time).
    pub vtr: [f64; 3],
    /// Lever arms from the centres to the contact point (length).
    pub cri: f64,
    /// Lever arm of particle j.
    pub crj: f64,
    /// Normal force magnitude set by the normal model (force).
    pub fn_total: f64,
    /// Normal stiffness (force/length).
    pub kn: f64,
    /// Tangential stiffness (force/length).
    pub kt: f64,
    /// Normal damping coefficient (force time/length).
    pub gamman: f64,
    /// Tangential damping coefficient.
    pub gammat: f64,
    /// Force on i (force).
    pub fi: [f64; 3],
    /// Force on j.
    pub fj: [f64; 3],
    /// Torque on i (force length).
    pub ti: [f64; 3],
    /// Torque on j.
    pub tj: [f64; 3],
    /// Radii (length).
    pub radi: f64,
    /// Radius of j (length).
    pub radj: f64,
    /// Centre distance (length).
    pub r: f64,
    /// Masses (mass).
    pub mi: f64,
    /// Mass of j.
    pub mj: f64,
    /// A wall contact (no particle j).
    pub wall: bool,
    /// Surface-model angular velocity term (1/time), used by rolling models at walls.
    pub wr: [f64; 3],
    /// omega_i - omega_j (1/time).
    pub wrel: [f64; 3],
}

/// A granular pair interaction composed of normal `N`, tangential `T`, cohesion `C` and
/// rolling `R` sub-models.
pub struct PairGran<N, T, C, R> {
    /// Normal model.
    pub normal: N,
    /// Tangential model.
    pub tangential: T,
    /// Cohesion model.
    pub cohesion: C,
    /// Rolling-friction model.
    pub rolling: R,
    /// Per-type-pair coefficients.
    pub material: Material,
    /// Group bits of frozen particles (infinite mass in contacts).
    pub frozen: u32,
    /// Per-pair results of the current step (reused between steps).
    pub results: Vec<PairResult>,
    /// The largest overlap of the last evaluation: (ratio to the smaller radius, i, j).
    pub worst: Option<(f64, u32, u32)>,
}

/// What one listed pair contributes: forces and torques on both particles.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairResult {
    /// The particles touch.
    pub touching: bool,
    /// Force on i (force).
    pub fi: [f64; 3],
    /// Force on j.
    pub fj: [f64; 3],
    /// Torque on i (force length).
    pub ti: [f64; 3],
    /// Torque on j.
    pub tj: [f64; 3],
    /// Overlap as a fraction of the smaller radius (for the blow-up guard).
    pub overlap_ratio: f64,
}

/// Below this many listed pairs the contact loop stays on one thread.
const PARALLEL_PAIRS: usize = 2048;

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
        let xj = [
            p.x[j][0] + pair.shift[0],
            p.x[j][1] + pair.shift[1],
            p.x[j][2] + pair.shift[2],
        ];
        let delx = p.x[i][0] - xj[0];
        let dely = p.x[i][1] - xj[1];
        let delz = p.x[i][2] - xj[2];
        let rsq = delx * delx + dely * dely + delz * delz;
        let (radi, radj) = (p.radius[i], p.radius[j]);
        let radsum = radi + radj;
        if rsq >= radsum * radsum {
            return PairResult::default();
        }
        let r = rsq.sqrt();
        let rinv = 1.0 / r;
        let (mi, mj) = (p.mass[i], p.mass[j]);
        let mut meff = mi * mj / (mi + mj);
        if p.mask[i] & self.frozen != 0 {
            meff = mj;
        }
        if p.mask[j] & self.frozen != 0 {
            meff = mi;
        }
        let mut c = Contact {
            itype: p.kind[i] as usize,
            jtype: p.kind[j] as usize,
            en: [delx * rinv, dely * rinv, delz * rinv],
            delta: [delx, dely, delz],
            reff: radi * radj / (radi + radj),
            meff,
            radi,
            radj,
            r,
            mi,
            mj,
            ..Contact::default()
        };
        surface(&mut c, p, i, j, radi, radj, radsum, r, rinv);
        self.normal.force(&mut c, &self.material);
        self.cohesion.force(&mut c, &self.material);
        let (ht, hr) = h.split_at_mut(T::HISTORY);
        self.tangential
            .force(&mut c, &self.material, ht, dt, update);
        self.rolling.torque(&mut c, &self.material, hr, dt, update);
        PairResult {
            touching: true,
            fi: c.fi,
            fj: c.fj,
            ti: c.ti,
            tj: c.tj,
            overlap_ratio: c.deltan / radi.min(radj),
        }
    }
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> PairInteraction
    for PairGran<N, T, C, R>
{
    fn history_width(&self) -> usize {
        T::HISTORY + R::HISTORY
    }

    fn worst_overlap(&self) -> Option<(f64, u32, u32)> {
        self.worst
    }

    fn compute(
        &mut self,
        p: &mut Particles,
        pairs: &[Pair],
        history: &mut [f64],
        dt: f64,
        update: bool,
    ) {
        let width = T::HISTORY + R::HISTORY;
        self.worst = None;
        if pairs.len() < PARALLEL_PAIRS || rayon::current_num_threads() == 1 {
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
                    add_pair(p, pair, &res);
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
                add_pair(p, pair, res);
                self.note_overlap(pair, res.overlap_ratio);
            }
        }
        self.results = results;
    }
}

/// Add one pair's forces and torques to its two particles.
#[inline(always)]
fn add_pair(p: &mut Particles, pair: &Pair, res: &PairResult) {
    let (i, j) = (pair.i as usize, pair.j as usize);
    for d in 0..3 {
        p.f[i][d] += 1.0 * res.fi[d];
        p.torque[i][d] += 1.0 * res.ti[d];
    }
    for d in 0..3 {
        p.f[j][d] += 1.0 * res.fj[d];
        p.torque[j][d] += 1.0 * res.tj[d];
    }
}

/// The default surface model: relative velocities at the contact point and lever arms.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn surface(
    c: &mut Contact,
    p: &Particles,
    i: usize,
    j: usize,
    radi: f64,
    radj: f64,
    radsum: f64,
    r: f64,
    rinv: f64,
) {
    let [enx, eny, enz] = c.en;
    let vr1 = p.v[i][0] - p.v[j][0];
    let vr2 = p.v[i][1] - p.v[j][1];
    let vr3 = p.v[i][2] - p.v[j][2];
    let vn = vr1 * enx + vr2 * eny + vr3 * enz;
    let vt1 = vr1 - vn * enx;
    let vt2 = vr2 - vn * eny;
    let vt3 = vr3 - vn * enz;
    let deltan = radsum - r;
    let [dx, dy, dz] = c.delta;
    let cri = radi - 0.5 * deltan;
    let crj = radj - 0.5 * deltan;
    let (wi, wj) = (p.omega[i], p.omega[j]);
    let wr1 = (cri * wi[0] + crj * wj[0]) * rinv;
    let wr2 = (cri * wi[1] + crj * wj[1]) * rinv;
    let wr3 = (cri * wi[2] + crj * wj[2]) * rinv;
    c.vtr = [
        vt1 - (dz * wr2 - dy * wr3),
        vt2 - (dx * wr3 - dz * wr1),
        vt3 - (dy * wr1 - dx * wr2),
    ];
    c.vn = vn;
    c.deltan = deltan;
    c.cri = cri;
    c.crj = crj;
    c.wr = [wr1, wr2, wr3];
    c.wrel = [wi[0] - wj[0], wi[1] - wj[1], wi[2] - wj[2]];
}

/// The contact sub-models and options a `pair_style gran` line selects.
#[derive(Debug, Clone, PartialEq)]
pub struct Selection {
    /// Normal model name.
    pub model: String,
    /// Tangential model name.
    pub tangential: String,
    /// `tangential_damping` (default on).
    pub tangential_damping: bool,
    /// `limitForce` (default off).
    pub limit_force: bool,
    /// Cohesion model name (`off` for none).
    pub cohesion: String,
    /// Rolling-friction model name (`off` for none).
    pub rolling: String,
    /// sjkr `tangential_reduce` (default off).
    pub tangential_reduce: bool,
    /// cdt/epsd `torsionTorque` (default off).
    pub torsion_torque: bool,
}

/// Build the monomorphised interaction for a selection: one kernel per combination of
/// sub-models, chosen here once per run.
pub fn build(
    sel: &Selection,
    material: Material,
    frozen: u32,
) -> Result<Box<dyn PairInteraction>, String> {
    macro_rules! pair {
        ($n:expr, $t:expr, $c:expr, $r:expr) => {{
            check_models(&$n, &$c, &$r, &material)?;
            Box::new(PairGran {
                normal: $n,
                tangential: $t,
                cohesion: $c,
                rolling: $r,
                material,
                frozen,
                results: Vec::new(),
                worst: None,
            }) as Box<dyn PairInteraction>
        }};
    }
    dispatch!(sel, pair)
}

/// Checks each sub-model makes of the material tables.
fn check_models<N: NormalModel, C: CohesionModel, R: RollingModel>(
    _: &N,
    _: &C,
    _: &R,
    m: &Material,
) -> Result<(), String> {
    N::check(m)?;
    C::check(m)?;
    R::check(m)
}

/// Expand `$make!(normal, tangential, cohesion, rolling)` for the selected combination: one
/// monomorphised kernel per combination, chosen here once per run.
macro_rules! dispatch {
    ($sel:expr, $make:ident) => {{
        match $sel.model.as_str() {
            "hertz" => {
                let n = normal::Hertz {
                    tangential_damping: $sel.tangential_damping,
                    limit_force: $sel.limit_force,
                };
                dispatch_rest!($sel, $make, n)
            }
            "hooke" => {
                let n = normal::Hooke {
                    tangential_damping: $sel.tangential_damping,
                    limit_force: $sel.limit_force,
                };
                dispatch_rest!($sel, $make, n)
            }
            m => Err(format!("model {m}: not supported yet")),
        }
    }};
}
use dispatch;

/// The tangential, cohesion and rolling part of [`dispatch`].
macro_rules! dispatch_rest {
    ($sel:expr, $make:ident, $n:expr) => {{
        let sjkr = cohesion::Sjkr {
            tangential_reduce: $sel.tangential_reduce,
        };
        let cdt = rolling::Cdt {
            torsion: $sel.torsion_torque,
        };
        let epsd = rolling::Epsd {
            torsion: $sel.torsion_torque,
        };
        use cohesion::NoCohesion as NoC;
        use rolling::NoRolling as NoR;
        use tangential::{History as H, HistoryTotalCap as HC, NoHistory as NH};
        Ok(
            match (
                $sel.tangential.as_str(),
                $sel.cohesion.as_str(),
                $sel.rolling.as_str(),
            ) {
                ("history", "off", "off") => $make!($n, H, NoC, NoR),
                ("history", "off", "cdt") => $make!($n, H, NoC, cdt),
                ("history", "off", "epsd") => $make!($n, H, NoC, epsd),
                ("history", "sjkr", "off") => $make!($n, H, sjkr, NoR),
                ("history", "sjkr", "cdt") => $make!($n, H, sjkr, cdt),
                ("history", "sjkr", "epsd") => $make!($n, H, sjkr, epsd),
                ("history_total_cap", "off", "off") => $make!($n, HC, NoC, NoR),
                ("history_total_cap", "sjkr", "epsd") => $make!($n, HC, sjkr, epsd),
                ("history_total_cap", "off", "epsd") => $make!($n, HC, NoC, epsd),
                ("history_total_cap", "off", "cdt") => $make!($n, HC, NoC, cdt),
                ("no_history", "off", "off") => $make!($n, NH, NoC, NoR),
                ("no_history", "off", "cdt") => $make!($n, NH, NoC, cdt),
                ("no_history", "sjkr", "off") => $make!($n, NH, sjkr, NoR),
                ("no_history", "sjkr", "cdt") => $make!($n, NH, sjkr, cdt),
                (t, c, r) => {
                    return Err(format!(
                        "tangential {t} cohesion {c} rolling_friction {r}: not supported yet"
                    ))
                }
            },
        )
    }};
}
use dispatch_rest;

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
    /// Add wall forces to particles of `group`; `history` is per particle.
    fn compute(
        &mut self,
        p: &mut Particles,
        group: u32,
        history: &mut [f64],
        dt: f64,
        update: bool,
    );
}

/// A primitive plane wall composed of the same sub-models as pairs.
pub struct WallGran<N, T, C, R> {
    /// Normal model.
    pub normal: N,
    /// Tangential model.
    pub tangential: T,
    /// Cohesion model.
    pub cohesion: C,
    /// Rolling-friction model.
    pub rolling: R,
    /// Coefficients (the wall has atom type `wall_type`).
    pub material: Material,
    /// The wall's atom type.
    pub wall_type: usize,
    /// The wall's shape.
    pub plane: Primitive,
}

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel> WallInteraction
    for WallGran<N, T, C, R>
{
    fn history_width(&self) -> usize {
        T::HISTORY + R::HISTORY
    }

    fn compute(
        &mut self,
        p: &mut Particles,
        group: u32,
        history: &mut [f64],
        dt: f64,
        update: bool,
    ) {
        let w = T::HISTORY + R::HISTORY;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let radi = p.radius[i];
            // LIGGGHTS's primitive contact: gap (negative = overlap) and centre-to-wall vector
            let (gap, towards) = self.plane.resolve(p.x[i], radi);
            let h = &mut history[i * w..(i + 1) * w];
            if gap > 0.0 {
                if h.iter().any(|v| *v != 0.0) {
                    h.iter_mut().for_each(|v| *v = 0.0);
                }
                continue;
            }
            let passed_deltan = -gap;
            let delta = [-towards[0], -towards[1], -towards[2]];
            let r = radi - passed_deltan;
            let rinv = 1.0 / r;
            let mut c = Contact {
                itype: p.kind[i] as usize,
                jtype: self.wall_type,
                en: [delta[0] * rinv, delta[1] * rinv, delta[2] * rinv],
                delta,
                reff: radi,
                meff: p.mass[i],
                radi,
                r,
                mi: p.mass[i],
                wall: true,
                ..Contact::default()
            };
            // the default surface model for a wall (wall at rest)
            let [enx, eny, enz] = c.en;
            let v = p.v[i];
            let vn = v[0] * enx + v[1] * eny + v[2] * enz;
            let vt = [v[0] - vn * enx, v[1] - vn * eny, v[2] - vn * enz];
            let deltan = radi - r;
            let cr = radi - 0.5 * passed_deltan;
            let om = p.omega[i];
            let wr = [cr * om[0] * rinv, cr * om[1] * rinv, cr * om[2] * rinv];
            let [dx, dy, dz] = delta;
            c.vtr = [
                vt[0] - (dz * wr[1] - dy * wr[2]),
                vt[1] - (dx * wr[2] - dz * wr[0]),
                vt[2] - (dy * wr[0] - dx * wr[1]),
            ];
            c.vn = vn;
            c.deltan = deltan;
            c.cri = cr;
            c.wr = wr;
            self.normal.force(&mut c, &self.material);
            self.cohesion.force(&mut c, &self.material);
            let (ht, hr) = h.split_at_mut(T::HISTORY);
            self.tangential
                .force(&mut c, &self.material, ht, dt, update);
            self.rolling.torque(&mut c, &self.material, hr, dt, update);
            for d in 0..3 {
                p.f[i][d] += c.fi[d];
                p.torque[i][d] += c.ti[d];
            }
        }
    }
}

/// Build the monomorphised wall interaction for a selection.
pub fn build_wall(
    sel: &Selection,
    material: Material,
    wall_type: usize,
    plane: Primitive,
) -> Result<Box<dyn WallInteraction>, String> {
    macro_rules! wall {
        ($n:expr, $t:expr, $c:expr, $r:expr) => {{
            check_models(&$n, &$c, &$r, &material)?;
            Box::new(WallGran {
                normal: $n,
                tangential: $t,
                cohesion: $c,
                rolling: $r,
                material,
                wall_type,
                plane,
            }) as Box<dyn WallInteraction>
        }};
    }
    dispatch!(sel, wall)
}
