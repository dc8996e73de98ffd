//! The granular contact force of LIGGGHTS 3.8.0's `pair_style gran` and `fix wall/gran`,
//! composed from sub-models: a surface model ([`surface`]), a normal model ([`normal`]), a
//! cohesion model ([`cohesion`]), a tangential model ([`tangential`]) and a rolling model
//! ([`rolling`]), called in that order on one [`Contact`] exactly as LIGGGHTS's
//! `ContactModel::surfacesIntersect` calls them, with per-type-pair coefficients from
//! [`material`].
//!
//! The force loops over pairs and primitive walls are in [`crate::engine::granular`]; they
//! wrap one [`ContactModel`] per run (see [`ContactKernel`]).
//!
//! The arithmetic reproduces LIGGGHTS operation by operation (same formulas, same
//! association, same order of accumulation into the force and torque sums), so forces agree
//! bit for bit with the Debian build (see the golden tests). Vectors are plain `[f64; 3]`
//! rather than nalgebra types: every sum and product is written out in LIGGGHTS's order,
//! which nalgebra's dot/cross/norm do not promise, and the engine's particle arrays are
//! `[f64; 3]` already, so no conversion is needed.
//!
//! [`ContactModel`] is generic over the four sub-models, so each combination compiles to
//! one inlined kernel without dynamic dispatch or allocation; [`AnyContactModel`] maps a
//! parsed `pair_style gran` selection onto one of the monomorphised combinations once per
//! run and falls back to run-time enums ([`DynContactModel`]) for any other combination.
//!
//! History per contact is `[normal (N::HISTORY_LEN), tangential (T::HISTORY_LEN), rolling
//! (R::HISTORY_LEN)]`, the order LIGGGHTS registers it (deltaMax of hooke/hysteresis, then
//! shearx..z, then r_torquex..z_old).

// Component loops index several arrays the way LIGGGHTS writes them out per component, and
// negated comparisons keep LIGGGHTS's behaviour for NaN.
#![allow(
    clippy::needless_range_loop,
    clippy::manual_range_contains,
    clippy::neg_cmp_op_on_partial_ord
)]

pub mod cohesion;
#[cfg(test)]
mod golden;
pub mod material;
pub mod normal;
pub mod real;
pub mod rolling;
pub mod surface;
pub mod tangential;

use std::f64::consts::PI;

pub use cohesion::{AnyCohesion, CohesionModel, NoCohesion, Sjkr, Sjkr2};
pub use material::{CoeffLanes, Coeffs, Material, MaterialInput, PairCoeffs, Property, UnitStyle};
pub use normal::{
    AnyNormal, Hertz, HertzStiffness, Hooke, HookeHysteresis, HookeStiffness, NormalModel,
};
pub use real::{F64x4, Real, LANES};
pub use rolling::{AnyRolling, Cdt, Epsd, Epsd2, Epsd3, NoRolling, RollingModel};
pub use surface::{DefaultSurface, SurfaceModel};
pub use tangential::{
    AnyTangential, History, HistoryTotalCap, NoHistory, NoTangential, TangentialModel,
};

/// A 3-vector in SI units (m, m/s, rad/s, N or N m depending on the field).
pub type Vec3 = [f64; 3];

/// One touching contact as the sub-models see it (LIGGGHTS's `SurfacesIntersectData`
/// together with the two `ForceData` sums). For a wall, j is the wall.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Contact<S = f64> {
    /// The contact is with a wall (no particle j; reff = radi, meff = mi).
    pub is_wall: bool,
    /// Radius of i (m).
    pub radi: S,
    /// Radius of j (m; 0 for walls).
    pub radj: S,
    /// radi + radj for pairs, radi for walls (m).
    pub radsum: S,
    /// Centre distance, or centre-wall distance (m).
    pub r: S,
    /// 1 / r (1/m).
    pub rinv: S,
    /// x_i - x_j, or from the wall contact point to the centre of i (m).
    pub delta: [S; 3],
    /// Unit normal delta / r, pointing from j (or the wall) to i.
    pub en: [S; 3],
    /// Overlap (m); for walls the geometry's value until the surface model recomputes it.
    pub deltan: S,
    /// Mass of i (kg).
    pub mi: S,
    /// Mass of j (kg; 0 for walls).
    pub mj: S,
    /// Effective mass used for damping (kg).
    pub meff: S,
    /// Velocity of i (m/s).
    pub vi: [S; 3],
    /// Velocity of j or of the wall (m/s).
    pub vj: [S; 3],
    /// Angular velocity of i (rad/s).
    pub omegai: [S; 3],
    /// Angular velocity of j (rad/s; 0 for walls).
    pub omegaj: [S; 3],
    /// Time step (s).
    pub dt: S,
    /// Advance and store history (LIGGGHTS's `computeflag && shearupdate`; false in setup).
    pub update_history: bool,
    /// Normal relative velocity (vi - vj) . en (m/s, negative when approaching).
    pub vn: S,
    /// Tangential relative velocity of the surfaces at the contact point (m/s).
    pub vtr: [S; 3],
    /// Surface model's rotational term (rad/s), used by rolling models at walls.
    pub wr: [S; 3],
    /// Lever arm of i: radi - deltan/2 (m).
    pub cri: S,
    /// Lever arm of j: radj - deltan/2 (m).
    pub crj: S,
    /// Normal force magnitude `Fn` (N, positive repulsive), set by the normal model and
    /// reduced by cohesion with `tangential_reduce`.
    pub normal_force: S,
    /// Normal stiffness (N/m).
    pub kn: S,
    /// Tangential stiffness (N/m).
    pub kt: S,
    /// Normal damping coefficient (kg/s).
    pub gamman: S,
    /// Tangential damping coefficient (kg/s).
    pub gammat: S,
    /// Force on i (N).
    pub fi: [S; 3],
    /// Force on j (N).
    pub fj: [S; 3],
    /// Torque on i (N m).
    pub ti: [S; 3],
    /// Torque on j (N m).
    pub tj: [S; 3],
    /// Tangential force on i set by the tangential model (N).
    pub ft: [S; 3],
    /// Rolling torque subtracted from i by the rolling model (N m).
    pub r_torque: [S; 3],
}

/// A particle pair, as the pair loop sees it. Particle j is the image that is closest
/// (x_j already shifted by the periodic offset); if only the separation is known, pass it as
/// `xi` with `xj = [0; 3]` (exact, but the reported contact point is then relative).
#[derive(Debug, Clone, Copy)]
pub struct PairInput<'a> {
    /// Position of i (m).
    pub xi: Vec3,
    /// Position of j (m).
    pub xj: Vec3,
    /// Radius of i (m).
    pub radi: f64,
    /// Radius of j (m).
    pub radj: f64,
    /// Mass of i (kg); the real mass even if i is frozen (rolling inertia uses it).
    pub mi: f64,
    /// Mass of j (kg).
    pub mj: f64,
    /// i is frozen (`fix freeze`): infinite mass for damping, meff = mj.
    pub frozen_i: bool,
    /// j is frozen: meff = mi (checked after i, so both frozen gives mi, as LIGGGHTS).
    pub frozen_j: bool,
    /// Velocity of i (m/s).
    pub vi: Vec3,
    /// Velocity of j (m/s).
    pub vj: Vec3,
    /// Angular velocity of i (rad/s).
    pub omegai: Vec3,
    /// Angular velocity of j (rad/s).
    pub omegaj: Vec3,
    /// Time step (s).
    pub dt: f64,
    /// Advance and store history (false during setup, like LIGGGHTS's `shearupdate`).
    pub update_history: bool,
    /// Coefficients of the type pair (itype, jtype).
    pub coeffs: &'a PairCoeffs,
}

/// Four particle pairs side by side, one per lane, as the batched pair loop gathers them
/// (the fields of [`PairInput`]; j already shifted to the image nearest i).
#[derive(Debug, Clone, Copy)]
pub struct PairLanes {
    /// Positions of i (m).
    pub xi: [F64x4; 3],
    /// Positions of j (m).
    pub xj: [F64x4; 3],
    /// Radii of i (m).
    pub radi: F64x4,
    /// Radii of j (m).
    pub radj: F64x4,
    /// Masses of i (kg).
    pub mi: F64x4,
    /// Masses of j (kg).
    pub mj: F64x4,
    /// i is frozen (infinite mass in the damping).
    pub frozen_i: real::M4,
    /// j is frozen.
    pub frozen_j: real::M4,
    /// Velocities of i (m/s).
    pub vi: [F64x4; 3],
    /// Velocities of j (m/s).
    pub vj: [F64x4; 3],
    /// Angular velocities of i (rad/s).
    pub omegai: [F64x4; 3],
    /// Angular velocities of j (rad/s).
    pub omegaj: [F64x4; 3],
    /// Time step (s).
    pub dt: f64,
    /// Advance and store history (false during setup).
    pub update_history: bool,
}

/// What four touching pairs contribute, one per lane (see [`PairOutput`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct PairLanesOutput {
    /// Forces on i (N).
    pub fi: [F64x4; 3],
    /// Forces on j (N).
    pub fj: [F64x4; 3],
    /// Torques on i (N m).
    pub ti: [F64x4; 3],
    /// Torques on j (N m).
    pub tj: [F64x4; 3],
    /// Overlaps (m).
    pub deltan: F64x4,
}

/// What one pair contributes (all zero and `touching == false` if the spheres do not
/// overlap; the history is then left alone).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairOutput {
    /// The spheres overlap (rsq < (radi + radj)^2).
    pub touching: bool,
    /// Force on i (N).
    pub fi: Vec3,
    /// Force on j (N).
    pub fj: Vec3,
    /// Torque on i (N m).
    pub ti: Vec3,
    /// Torque on j (N m).
    pub tj: Vec3,
    /// Normal force magnitude Fn after limitForce and tangential_reduce (N).
    pub normal_force: f64,
    /// Tangential force on i (N).
    pub ft: Vec3,
    /// Overlap radi + radj - r (m).
    pub deltan: f64,
    /// Unit normal from j to i.
    pub en: Vec3,
}

/// The per-contact values `compute pair/gran/local` reports, computed as it computes them.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairLocal {
    /// `force`: force on i (N).
    pub force: Vec3,
    /// `force_normal`: its projection on (x_j - x_i)/|x_j - x_i| (N).
    pub force_normal: Vec3,
    /// `force_tangential`: force minus its normal projection (N).
    pub force_tangential: Vec3,
    /// `torque`: torque on i (N m).
    pub torque: Vec3,
    /// `torque_normal` (N m).
    pub torque_normal: Vec3,
    /// `torque_tangential` (N m).
    pub torque_tangential: Vec3,
    /// `contactArea`: the sjkr lens area (m^2).
    pub contact_area: f64,
    /// `delta`: overlap (m).
    pub delta: f64,
    /// `contactPoint`: (x_i R_j + x_j R_i) / (R_i + R_j) (m).
    pub contact_point: Vec3,
}

/// Projection of `v` on the unit vector `n` and the remainder, as LIGGGHTS's compute does.
#[inline]
pub fn split(v: Vec3, n: Vec3) -> (Vec3, Vec3) {
    let mag = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
    let vn = [n[0] * mag, n[1] * mag, n[2] * mag];
    (vn, [v[0] - vn[0], v[1] - vn[1], v[2] - vn[2]])
}

impl PairOutput {
    /// The values `compute pair/gran/local` would report for this contact.
    pub fn local(&self, p: &PairInput) -> PairLocal {
        let mut n = [p.xj[0] - p.xi[0], p.xj[1] - p.xi[1], p.xj[2] - p.xi[2]];
        let norm = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        let inv = if norm == 0. { 0. } else { 1. / norm };
        for x in n.iter_mut() {
            *x *= inv;
        }
        let (force_normal, force_tangential) = split(self.fi, n);
        let (torque_normal, torque_tangential) = split(self.ti, n);
        let del = [p.xi[0] - p.xj[0], p.xi[1] - p.xj[1], p.xi[2] - p.xj[2]];
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        let r = rsq.sqrt();
        let (ri, rj) = (p.radi, p.radj);
        let contact_area =
            -PI / 4.0 * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj)) / rsq;
        let mut cp = [0.0; 3];
        for d in 0..3 {
            cp[d] = (p.xi[d] * rj + p.xj[d] * ri) / (ri + rj);
        }
        PairLocal {
            force: self.fi,
            force_normal,
            force_tangential,
            torque: self.ti,
            torque_normal,
            torque_tangential,
            contact_area,
            delta: ri + rj - r,
            contact_point: cp,
        }
    }
}

/// A particle near a primitive wall (`fix wall/gran ... primitive`); the wall has infinite
/// mass and the wall's atom type selects the coefficients.
#[derive(Debug, Clone, Copy)]
pub struct WallInput<'a> {
    /// Position of the particle (m).
    pub x: Vec3,
    /// The wall geometry's signed gap: distance to the wall minus the radius (m, negative
    /// when overlapping), as LIGGGHTS's `resolveContact` returns it (see [`plane_contact`]).
    pub gap: f64,
    /// Vector from the centre to the closest wall point, as `resolveContact` returns it (m).
    pub to_wall: Vec3,
    /// Radius (m).
    pub radius: f64,
    /// Mass (kg; the body mass for rigid clumps); meff = mass.
    pub mass: f64,
    /// Velocity (m/s).
    pub v: Vec3,
    /// Angular velocity (rad/s).
    pub omega: Vec3,
    /// Velocity of the wall at the contact (m/s; `shear` walls).
    pub v_wall: Vec3,
    /// Time step (s).
    pub dt: f64,
    /// Advance and store history (false during setup).
    pub update_history: bool,
    /// Coefficients of the type pair (particle type, wall type).
    pub coeffs: &'a PairCoeffs,
}

/// What one wall contact contributes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WallOutput {
    /// The particle touches the wall (gap <= 0).
    pub touching: bool,
    /// Force on the particle (N).
    pub f: Vec3,
    /// Torque on the particle (N m).
    pub t: Vec3,
    /// Normal force magnitude Fn (N).
    pub normal_force: f64,
    /// Tangential force (N).
    pub ft: Vec3,
    /// Overlap (m).
    pub deltan: f64,
    /// Unit normal from the wall to the particle.
    pub en: Vec3,
    /// Contact point on the wall, x - delta (m), as `compute wall/gran/local` reports it.
    pub contact_point: Vec3,
}

/// LIGGGHTS's contact of a sphere with the plane `x[axis] = position` (`xplane`, `yplane`,
/// `zplane`): returns (gap, to_wall) for [`WallInput`].
#[inline]
pub fn plane_contact(axis: usize, position: f64, x: &Vec3, radius: f64) -> (f64, Vec3) {
    let mut to_wall = [0.0; 3];
    let pos = x[axis];
    to_wall[axis] = position - pos;
    let gap = if pos > position {
        pos - position - radius
    } else {
        position - pos - radius
    };
    (gap, to_wall)
}

/// A contact model: one sub-model of each family, combined in LIGGGHTS's order
/// (surface, normal, cohesion, tangential, rolling).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactModel<N, T, C, R> {
    /// Normal model.
    pub normal: N,
    /// Tangential model.
    pub tangential: T,
    /// Cohesion model.
    pub cohesion: C,
    /// Rolling model.
    pub rolling: R,
}

/// The run-time composed model, for combinations that are not monomorphised.
pub type DynContactModel = ContactModel<AnyNormal, AnyTangential, AnyCohesion, AnyRolling>;

impl<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>
    ContactModel<N, T, C, R>
{
    /// Doubles of history per contact the type reserves (tangential, then rolling; the
    /// normal and cohesion models regolith implements keep none, which is checked here).
    pub const HISTORY_LEN: usize = {
        assert!(C::HISTORY_LEN == 0);
        N::HISTORY_LEN + T::HISTORY_LEN + R::HISTORY_LEN
    };

    /// Combine four sub-models.
    pub fn new(normal: N, tangential: T, cohesion: C, rolling: R) -> Self {
        ContactModel {
            normal,
            tangential,
            cohesion,
            rolling,
        }
    }

    /// Doubles of history per contact this instance uses (normal, tangential, then rolling,
    /// LIGGGHTS's order).
    #[inline(always)]
    pub fn history_len(&self) -> usize {
        self.normal.history_len() + self.tangential.history_len() + self.rolling.history_len()
    }

    /// For each history value, whether it changes sign when the pair is seen from its other
    /// particle: the normal model says; tangential shear and rolling torques are vectors.
    pub fn history_flips(&self) -> Vec<bool> {
        let mut v = self.normal.history_flips().to_vec();
        v.resize(self.history_len(), true);
        v
    }

    /// The coefficients the sub-models need, in LIGGGHTS's `connectToProperties` order
    /// (normal, cohesion, tangential, rolling), for [`Material::new`].
    pub fn properties(&self) -> Vec<(Property, &'static str)> {
        let mut out = Vec::new();
        self.normal.properties(&mut out);
        self.cohesion.properties(&mut out);
        self.tangential.properties(&mut out);
        self.rolling.properties(&mut out);
        out
    }

    /// Run the sub-models on a prepared contact (one, or a batch of four), history split
    /// normal | tangential | rolling.
    #[inline(always)]
    pub fn intersect<S: Real>(&self, c: &mut Contact<S>, m: &impl Coeffs<S>, history: &mut [S]) {
        DefaultSurface.surfaces_intersect(c);
        let (hn, history) = history.split_at_mut(self.normal.history_len());
        self.normal.surfaces_intersect(c, m, hn);
        self.cohesion.surfaces_intersect(c, m);
        let (ht, hr) = history.split_at_mut(self.tangential.history_len());
        self.tangential.surfaces_intersect(c, m, ht);
        self.rolling.surfaces_intersect(c, m, hr);
    }

    /// Force and torques of one particle pair; `history` is the pair's stored values
    /// (at least `history_len()` doubles). Not touching: zero output, history untouched
    /// (LIGGGHTS keeps it until the next neighbour-list build drops the pair; call
    /// [`Self::surfaces_close`] to reset it where LIGGGHTS's `surfacesClose` would).
    #[inline(always)]
    pub fn pair_force(&self, p: &PairInput, history: &mut [f64]) -> PairOutput {
        let delx = p.xi[0] - p.xj[0];
        let dely = p.xi[1] - p.xj[1];
        let delz = p.xi[2] - p.xj[2];
        let rsq = delx * delx + dely * dely + delz * delz;
        let radsum = p.radi + p.radj;
        if !(rsq < radsum * radsum) {
            return PairOutput::default();
        }
        let r = rsq.sqrt();
        let rinv = 1.0 / r;
        let en = [delx * rinv, dely * rinv, delz * rinv];
        // a frozen particle has infinite mass: the other one's mass is the effective mass
        let mut meff = p.mi * p.mj / (p.mi + p.mj);
        if p.frozen_i {
            meff = p.mj;
        }
        if p.frozen_j {
            meff = p.mi;
        }
        let mut c = Contact {
            is_wall: false,
            radi: p.radi,
            radj: p.radj,
            radsum,
            r,
            rinv,
            delta: [delx, dely, delz],
            en,
            mi: p.mi,
            mj: p.mj,
            meff,
            vi: p.vi,
            vj: p.vj,
            omegai: p.omegai,
            omegaj: p.omegaj,
            dt: p.dt,
            update_history: p.update_history,
            ..Contact::default()
        };
        self.intersect(&mut c, p.coeffs, history);
        PairOutput {
            touching: true,
            fi: c.fi,
            fj: c.fj,
            ti: c.ti,
            tj: c.tj,
            normal_force: c.normal_force,
            ft: c.ft,
            deltan: c.deltan,
            en: c.en,
        }
    }

    /// Forces and torques of four touching particle pairs at once (lane k is the pair
    /// [`Self::pair_force`] would compute from the k-th inputs, bit for bit); `history`
    /// holds each lane's values (`history_len()` entries).
    #[inline(always)]
    pub fn pair_force_lanes(
        &self,
        p: &PairLanes,
        m: &impl Coeffs<F64x4>,
        history: &mut [F64x4],
    ) -> PairLanesOutput {
        let delx = p.xi[0] - p.xj[0];
        let dely = p.xi[1] - p.xj[1];
        let delz = p.xi[2] - p.xj[2];
        let rsq = delx * delx + dely * dely + delz * delz;
        let radsum = p.radi + p.radj;
        let r = rsq.sqrt();
        let rinv = F64x4::splat(1.0) / r;
        let en = [delx * rinv, dely * rinv, delz * rinv];
        let mut meff = p.mi * p.mj / (p.mi + p.mj);
        meff = F64x4::select(p.frozen_i, p.mj, meff);
        meff = F64x4::select(p.frozen_j, p.mi, meff);
        let mut c = Contact {
            is_wall: false,
            radi: p.radi,
            radj: p.radj,
            radsum,
            r,
            rinv,
            delta: [delx, dely, delz],
            en,
            mi: p.mi,
            mj: p.mj,
            meff,
            vi: p.vi,
            vj: p.vj,
            omegai: p.omegai,
            omegaj: p.omegaj,
            dt: F64x4::splat(p.dt),
            update_history: p.update_history,
            ..Contact::default()
        };
        self.intersect(&mut c, m, history);
        PairLanesOutput {
            fi: c.fi,
            fj: c.fj,
            ti: c.ti,
            tj: c.tj,
            deltan: c.deltan,
        }
    }

    /// Force and torque of a primitive wall on one particle; `history` is the particle's
    /// values for this wall. Not touching (gap > 0): zero output and the history is reset,
    /// as `fix wall/gran` does for primitive walls.
    #[inline(always)]
    pub fn wall_force(&self, w: &WallInput, history: &mut [f64]) -> WallOutput {
        if !(w.gap <= 0.0) {
            let n = self.history_len();
            for h in history[..n].iter_mut() {
                *h = 0.0;
            }
            return WallOutput::default();
        }
        let deltan = -w.gap;
        let delta = [-w.to_wall[0], -w.to_wall[1], -w.to_wall[2]];
        let r = w.radius - deltan;
        let rinv = 1.0 / r;
        let en = [delta[0] * rinv, delta[1] * rinv, delta[2] * rinv];
        let mut c = Contact {
            is_wall: true,
            radi: w.radius,
            radsum: w.radius,
            r,
            rinv,
            delta,
            en,
            deltan,
            mi: w.mass,
            meff: w.mass,
            vi: w.v,
            vj: w.v_wall,
            omegai: w.omega,
            dt: w.dt,
            update_history: w.update_history,
            ..Contact::default()
        };
        self.intersect(&mut c, w.coeffs, history);
        WallOutput {
            touching: true,
            f: c.fi,
            t: c.ti,
            normal_force: c.normal_force,
            ft: c.ft,
            deltan: c.deltan,
            en: c.en,
            contact_point: [w.x[0] - delta[0], w.x[1] - delta[1], w.x[2] - delta[2]],
        }
    }

    /// LIGGGHTS's `surfacesClose`: the surfaces no longer touch but are within the contact
    /// distance; resets the tangential and rolling history.
    #[inline]
    pub fn surfaces_close<S: Real>(&self, history: &mut [S]) {
        let (hn, history) = history.split_at_mut(self.normal.history_len());
        self.normal.surfaces_close(hn);
        let (ht, hr) = history.split_at_mut(self.tangential.history_len());
        self.tangential.surfaces_close(ht);
        self.rolling.surfaces_close(hr);
    }
}

/// Code generic over the sub-models, run by [`AnyContactModel::dispatch`] with the concrete
/// model type, so a whole pair loop is monomorphised once per combination.
pub trait ContactKernel {
    /// What the kernel returns.
    type Output;
    /// Run with the concrete model.
    fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
        self,
        model: &ContactModel<N, T, C, R>,
    ) -> Self::Output;
}

/// The on/off settings `pair_style gran` and `fix wall/gran` accept after the model names.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModelOptions {
    /// `tangential_damping` (default on; normal models).
    pub tangential_damping: bool,
    /// `limitForce` (default off; normal models).
    pub limit_force: bool,
    /// `absolute_damping` (default off; hooke/stiffness).
    pub absolute_damping: bool,
    /// `viscous` (default off; hooke).
    pub viscous: bool,
    /// `ktToKnUser` (default off; hooke).
    pub kt_to_kn: bool,
    /// `tangential_reduce` (default off; sjkr, sjkr2).
    pub tangential_reduce: bool,
    /// `torsionTorque` (default off; cdt, epsd, epsd2, epsd3).
    pub torsion_torque: bool,
    /// The run is 2d (`dimension 2`; not a keyword): epsd/epsd3 inertia factor 1.5.
    pub two_d: bool,
}

impl Default for ModelOptions {
    fn default() -> Self {
        ModelOptions {
            tangential_damping: true,
            limit_force: false,
            absolute_damping: false,
            viscous: false,
            kt_to_kn: false,
            tangential_reduce: false,
            torsion_torque: false,
            two_d: false,
        }
    }
}

/// Why a contact model selection is refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ModelError {
    /// Invalid in LIGGGHTS too; the message is LIGGGHTS's.
    #[error("{0}")]
    Invalid(String),
    /// Valid LIGGGHTS that regolith does not run: the model or setting as the deck names it
    /// (`model luding`, `'heating_normal_hertz on'`).
    #[error("{0} is not supported by regolith")]
    Unsupported(String),
}

/// A parsed `model ... tangential ... cohesion ... rolling_friction ... surface ...`
/// selection with its settings.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelSelection {
    /// Normal model name (`off` if no `model` keyword).
    pub normal: String,
    /// Tangential model name (`off` by default).
    pub tangential: String,
    /// Cohesion model name (`off` by default).
    pub cohesion: String,
    /// Rolling model name (`off` by default).
    pub rolling: String,
    /// Surface model name (`default` by default).
    pub surface: String,
    /// Settings.
    pub options: ModelOptions,
}

const NORMAL_NAMES: &[&str] = &[
    "off",
    "hertz",
    "hooke",
    "hertz/stiffness",
    "hooke/stiffness",
    "hooke/hysteresis",
    "edinburgh",
    "edinburgh/stiffness",
    "luding",
    "thornton_ning",
];
const TANGENTIAL_NAMES: &[&str] = &[
    "off",
    "no_history",
    "history",
    "tan_luding",
    "history_total_cap",
];
const COHESION_NAMES: &[&str] = &[
    "off",
    "sjkr",
    "sjkr2",
    "easo/capillary/viscous",
    "washino/capillary/viscous",
];
const ROLLING_NAMES: &[&str] = &["off", "cdt", "epsd", "epsd2", "epsd3", "luding"];
const SURFACE_NAMES: &[&str] = &["default", "multicontact", "superquadric"];

/// LIGGGHTS's message for an unknown or empty model selection.
const INVALID_MODEL: &str =
    "Invalid model specified (check for typos and enable at least one model)";

impl Default for ModelSelection {
    fn default() -> Self {
        ModelSelection {
            normal: "off".into(),
            tangential: "off".into(),
            cohesion: "off".into(),
            rolling: "off".into(),
            surface: "default".into(),
            options: ModelOptions::default(),
        }
    }
}

impl ModelSelection {
    /// Consume the model keywords at the start of `args` in LIGGGHTS's fixed order
    /// (`model`, `tangential`, `cohesion`, `rolling_friction`, `surface`); returns the
    /// selection and the number of arguments consumed.
    pub fn select(args: &[&str]) -> Result<(ModelSelection, usize), String> {
        let mut sel = ModelSelection::default();
        let mut k = 0;
        let steps: [(&str, &[&str]); 5] = [
            ("model", NORMAL_NAMES),
            ("tangential", TANGENTIAL_NAMES),
            ("cohesion", COHESION_NAMES),
            ("rolling_friction", ROLLING_NAMES),
            ("surface", SURFACE_NAMES),
        ];
        for (i, (kw, names)) in steps.iter().enumerate() {
            if args.len() - k > 1 && args[k] == *kw {
                let name = args[k + 1];
                if !names.contains(&name) {
                    return Err(INVALID_MODEL.into());
                }
                let slot = match i {
                    0 => &mut sel.normal,
                    1 => &mut sel.tangential,
                    2 => &mut sel.cohesion,
                    3 => &mut sel.rolling,
                    _ => &mut sel.surface,
                };
                *slot = name.to_string();
                k += 2;
            }
        }
        if sel.normal == "off"
            && sel.tangential == "off"
            && sel.cohesion == "off"
            && sel.rolling == "off"
        {
            return Err(INVALID_MODEL.into());
        }
        Ok((sel, k))
    }

    /// The on/off settings the selected sub-models register, with whether regolith
    /// implements the `on` value.
    fn settings(&self) -> Vec<(&'static str, bool)> {
        let mut s = vec![
            ("computeElasticPotential", false),
            ("computeDissipatedEnergy", false),
        ];
        match self.normal.as_str() {
            "hertz" => s.extend([
                ("tangential_damping", true),
                ("limitForce", true),
                ("heating_normal_hertz", false),
                ("heating_tracking", false),
                ("disableNormalWhenBonded", false),
            ]),
            "hooke" => s.extend([
                ("viscous", true),
                ("tangential_damping", true),
                ("limitForce", true),
                ("ktToKnUser", true),
                ("heating_normal_hooke", false),
                ("heating_tracking", false),
                ("disableNormalWhenBonded", false),
            ]),
            // LIGGGHTS registers hooke's settings but its hysteresis force ignores limitForce
            // and ktToKnUser: regolith refuses `on` rather than ignore it
            "hooke/hysteresis" => s.extend([
                ("viscous", true),
                ("tangential_damping", true),
                ("limitForce", false),
                ("ktToKnUser", false),
                ("heating_normal_hooke", false),
                ("heating_tracking", false),
                ("disableNormalWhenBonded", false),
            ]),
            "hertz/stiffness" => s.extend([("tangential_damping", true), ("limitForce", true)]),
            "hooke/stiffness" => s.extend([
                ("tangential_damping", true),
                ("absolute_damping", true),
                ("limitForce", true),
            ]),
            _ => {}
        }
        match self.tangential.as_str() {
            "no_history" => s.push(("disableTangentialWhenBonded", false)),
            "history" | "history_total_cap" => s.extend([
                ("heating_tangential_history", false),
                ("heating_tracking", false),
            ]),
            _ => {}
        }
        if matches!(self.cohesion.as_str(), "sjkr" | "sjkr2") {
            s.push(("tangential_reduce", true));
        }
        if matches!(self.rolling.as_str(), "cdt" | "epsd" | "epsd2" | "epsd3") {
            s.push(("torsionTorque", true));
        }
        s
    }

    /// Apply `keyword on|off` settings (any order), with LIGGGHTS's messages for unknown
    /// keywords and values; `on` for an energy/heating/bond option regolith lacks is
    /// [`ModelError::Unsupported`] (the other settings still apply).
    pub fn apply_settings(&mut self, args: &[&str]) -> Result<(), ModelError> {
        let known = self.settings();
        let mut unsupported: Option<&str> = None;
        let mut k = 0;
        while k < args.len() {
            let kw = args[k];
            let Some(&(_, supported)) = known.iter().find(|(n, _)| *n == kw) else {
                return Err(ModelError::Invalid(format!(
                    "Unknown argument or wrong keyword order: '{kw}'"
                )));
            };
            let val = args.get(k + 1).copied().unwrap_or("");
            let on = match val {
                "on" => true,
                "off" => false,
                _ => {
                    return Err(ModelError::Invalid(format!(
                    "while parsing '{kw}' argument: unknown option or wrong keyword order: '{val}'"
                )))
                }
            };
            if on && !supported {
                // the rest still applies: the caller reports this one as unsupported
                unsupported.get_or_insert(kw);
                k += 2;
                continue;
            }
            let o = &mut self.options;
            match kw {
                "tangential_damping" => o.tangential_damping = on,
                "limitForce" => o.limit_force = on,
                "absolute_damping" => o.absolute_damping = on,
                "viscous" => o.viscous = on,
                "ktToKnUser" => o.kt_to_kn = on,
                "tangential_reduce" => o.tangential_reduce = on,
                "torsionTorque" => o.torsion_torque = on,
                _ => {}
            }
            k += 2;
        }
        match unsupported {
            Some(kw) => Err(ModelError::Unsupported(format!("'{kw} on'"))),
            None => Ok(()),
        }
    }

    /// Parse a whole `pair_style gran` argument list (after `gran`): model keywords, then
    /// settings.
    pub fn parse(args: &[&str]) -> Result<ModelSelection, ModelError> {
        let (mut sel, k) = ModelSelection::select(args).map_err(ModelError::Invalid)?;
        sel.apply_settings(&args[k..])?;
        Ok(sel)
    }

    /// The run-time sub-models of this selection.
    pub fn sub_models(
        &self,
    ) -> Result<(AnyNormal, AnyTangential, AnyCohesion, AnyRolling), ModelError> {
        let o = self.options;
        let unsupported =
            |kind: &str, name: &str| ModelError::Unsupported(format!("{kind} {name}"));
        let normal = match self.normal.as_str() {
            "hertz" => AnyNormal::Hertz(Hertz {
                tangential_damping: o.tangential_damping,
                limit_force: o.limit_force,
            }),
            "hooke" => AnyNormal::Hooke(Hooke {
                tangential_damping: o.tangential_damping,
                limit_force: o.limit_force,
                viscous: o.viscous,
                kt_to_kn: o.kt_to_kn,
            }),
            "hertz/stiffness" => AnyNormal::HertzStiffness(HertzStiffness {
                tangential_damping: o.tangential_damping,
                limit_force: o.limit_force,
            }),
            "hooke/stiffness" => AnyNormal::HookeStiffness(HookeStiffness {
                tangential_damping: o.tangential_damping,
                absolute_damping: o.absolute_damping,
                limit_force: o.limit_force,
            }),
            "hooke/hysteresis" => AnyNormal::HookeHysteresis(HookeHysteresis {
                hooke: Hooke {
                    tangential_damping: o.tangential_damping,
                    limit_force: false,
                    viscous: o.viscous,
                    kt_to_kn: false,
                },
            }),
            n => return Err(unsupported("model", n)),
        };
        let tangential = match self.tangential.as_str() {
            "off" => AnyTangential::Off(NoTangential),
            "no_history" => AnyTangential::NoHistory(NoHistory),
            "history" => AnyTangential::History(History),
            "history_total_cap" => AnyTangential::TotalCap(HistoryTotalCap),
            n => return Err(unsupported("tangential", n)),
        };
        let cohesion = match self.cohesion.as_str() {
            "off" => AnyCohesion::Off(NoCohesion),
            "sjkr" => AnyCohesion::Sjkr(Sjkr {
                tangential_reduce: o.tangential_reduce,
            }),
            "sjkr2" => AnyCohesion::Sjkr2(Sjkr2 {
                tangential_reduce: o.tangential_reduce,
            }),
            n => return Err(unsupported("cohesion", n)),
        };
        let rolling = match self.rolling.as_str() {
            "off" => AnyRolling::Off(NoRolling),
            "cdt" => AnyRolling::Cdt(Cdt {
                torsion_torque: o.torsion_torque,
            }),
            "epsd" => AnyRolling::Epsd(Epsd {
                torsion_torque: o.torsion_torque,
                two_d: o.two_d,
            }),
            "epsd2" => AnyRolling::Epsd2(Epsd2 {
                torsion_torque: o.torsion_torque,
            }),
            "epsd3" => AnyRolling::Epsd3(Epsd3 {
                torsion_torque: o.torsion_torque,
                two_d: o.two_d,
            }),
            n => return Err(unsupported("rolling_friction", n)),
        };
        if self.surface != "default" {
            return Err(unsupported("surface", &self.surface));
        }
        Ok((normal, tangential, cohesion, rolling))
    }
}

/// Declare [`AnyContactModel`] with one variant per monomorphised combination.
macro_rules! any_contact_model {
    ($( $(#[$doc:meta])* $variant:ident: $np:ident($nt:ty), $tp:ident($tt:ty), $cp:ident($ct:ty), $rp:ident($rt:ty); )*) => {
        /// A contact model chosen once per run: one of the monomorphised combinations, or
        /// the run-time fallback [`DynContactModel`] for any other.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum AnyContactModel {
            $( $(#[$doc])* $variant(ContactModel<$nt, $tt, $ct, $rt>), )*
            /// Any other combination, dispatched per sub-model at run time.
            Dyn(DynContactModel),
        }

        impl AnyContactModel {
            /// Pick the monomorphised combination for these sub-models, or the fallback.
            pub fn from_sub_models(n: AnyNormal, t: AnyTangential, c: AnyCohesion, r: AnyRolling) -> Self {
                match (n, t, c, r) {
                    $( (AnyNormal::$np(n), AnyTangential::$tp(t), AnyCohesion::$cp(c), AnyRolling::$rp(r)) =>
                        AnyContactModel::$variant(ContactModel::new(n, t, c, r)), )*
                    (n, t, c, r) => AnyContactModel::Dyn(ContactModel::new(n, t, c, r)),
                }
            }

            /// Run `kernel` with the concrete model type (one `match` per call).
            #[inline]
            pub fn dispatch<K: ContactKernel>(&self, kernel: K) -> K::Output {
                match self {
                    $( AnyContactModel::$variant(m) => kernel.run(m), )*
                    AnyContactModel::Dyn(m) => kernel.run(m),
                }
            }

            /// The combination is one of the monomorphised ones.
            pub fn is_monomorphised(&self) -> bool {
                !matches!(self, AnyContactModel::Dyn(_))
            }
        }
    };
}

any_contact_model! {
    /// hertz, history.
    HertzHistory: Hertz(Hertz), History(History), Off(NoCohesion), Off(NoRolling);
    /// hertz, history, rolling cdt.
    HertzHistoryCdt: Hertz(Hertz), History(History), Off(NoCohesion), Cdt(Cdt);
    /// hertz, history, rolling epsd.
    HertzHistoryEpsd: Hertz(Hertz), History(History), Off(NoCohesion), Epsd(Epsd);
    /// hertz, history, rolling epsd2.
    HertzHistoryEpsd2: Hertz(Hertz), History(History), Off(NoCohesion), Epsd2(Epsd2);
    /// hertz, history, cohesion sjkr.
    HertzHistorySjkr: Hertz(Hertz), History(History), Sjkr(Sjkr), Off(NoRolling);
    /// hertz, history, cohesion sjkr, rolling cdt.
    HertzHistorySjkrCdt: Hertz(Hertz), History(History), Sjkr(Sjkr), Cdt(Cdt);
    /// hertz, history, cohesion sjkr, rolling epsd.
    HertzHistorySjkrEpsd: Hertz(Hertz), History(History), Sjkr(Sjkr), Epsd(Epsd);
    /// hertz, history, cohesion sjkr, rolling epsd2.
    HertzHistorySjkrEpsd2: Hertz(Hertz), History(History), Sjkr(Sjkr), Epsd2(Epsd2);
    /// hertz, history, cohesion sjkr2.
    HertzHistorySjkr2: Hertz(Hertz), History(History), Sjkr2(Sjkr2), Off(NoRolling);
    /// hertz, no_history.
    HertzNoHistory: Hertz(Hertz), NoHistory(NoHistory), Off(NoCohesion), Off(NoRolling);
    /// hertz, tangential off.
    HertzFrictionless: Hertz(Hertz), Off(NoTangential), Off(NoCohesion), Off(NoRolling);
    /// hertz, history_total_cap (regolith extension).
    HertzTotalCap: Hertz(Hertz), TotalCap(HistoryTotalCap), Off(NoCohesion), Off(NoRolling);
    /// hertz, history_total_cap, cohesion sjkr, rolling epsd (the lunar study, corrected).
    HertzTotalCapSjkrEpsd: Hertz(Hertz), TotalCap(HistoryTotalCap), Sjkr(Sjkr), Epsd(Epsd);
    /// hertz, history_total_cap, rolling epsd.
    HertzTotalCapEpsd: Hertz(Hertz), TotalCap(HistoryTotalCap), Off(NoCohesion), Epsd(Epsd);
    /// hertz, history_total_cap, rolling cdt.
    HertzTotalCapCdt: Hertz(Hertz), TotalCap(HistoryTotalCap), Off(NoCohesion), Cdt(Cdt);
    /// hertz, history, rolling epsd3.
    HertzHistoryEpsd3: Hertz(Hertz), History(History), Off(NoCohesion), Epsd3(Epsd3);
    /// hertz, no_history, rolling cdt.
    HertzNoHistoryCdt: Hertz(Hertz), NoHistory(NoHistory), Off(NoCohesion), Cdt(Cdt);
    /// hertz, history_total_cap, rolling epsd2.
    HertzTotalCapEpsd2: Hertz(Hertz), TotalCap(HistoryTotalCap), Off(NoCohesion), Epsd2(Epsd2);
    /// hooke, history.
    HookeHistory: Hooke(Hooke), History(History), Off(NoCohesion), Off(NoRolling);
    /// hooke, no_history.
    HookeNoHistory: Hooke(Hooke), NoHistory(NoHistory), Off(NoCohesion), Off(NoRolling);
    /// hooke/hysteresis, history.
    HookeHysteresisHistory: HookeHysteresis(HookeHysteresis), History(History), Off(NoCohesion), Off(NoRolling);
    /// hertz/stiffness, history.
    HertzStiffnessHistory: HertzStiffness(HertzStiffness), History(History), Off(NoCohesion), Off(NoRolling);
    /// hooke/stiffness, history.
    HookeStiffnessHistory: HookeStiffness(HookeStiffness), History(History), Off(NoCohesion), Off(NoRolling);
    /// hooke/stiffness, no_history.
    HookeStiffnessNoHistory: HookeStiffness(HookeStiffness), NoHistory(NoHistory), Off(NoCohesion), Off(NoRolling);
}

impl AnyContactModel {
    /// Build the model for a parsed selection (error for names regolith lacks).
    pub fn new(sel: &ModelSelection) -> Result<Self, ModelError> {
        let (n, t, c, r) = sel.sub_models()?;
        Ok(AnyContactModel::from_sub_models(n, t, c, r))
    }

    /// Doubles of history per contact.
    pub fn history_len(&self) -> usize {
        struct K;
        impl ContactKernel for K {
            type Output = usize;
            fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
                self,
                m: &ContactModel<N, T, C, R>,
            ) -> usize {
                m.history_len()
            }
        }
        self.dispatch(K)
    }

    /// The coefficients the sub-models need, for [`Material::new`].
    pub fn properties(&self) -> Vec<(Property, &'static str)> {
        struct K;
        impl ContactKernel for K {
            type Output = Vec<(Property, &'static str)>;
            fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
                self,
                m: &ContactModel<N, T, C, R>,
            ) -> Self::Output {
                m.properties()
            }
        }
        self.dispatch(K)
    }

    /// [`ContactModel::pair_force`] through one `match` (prefer [`Self::dispatch`] around
    /// a whole loop).
    pub fn pair_force(&self, p: &PairInput, history: &mut [f64]) -> PairOutput {
        struct K<'a, 'b, 'c>(&'a PairInput<'b>, &'c mut [f64]);
        impl ContactKernel for K<'_, '_, '_> {
            type Output = PairOutput;
            fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
                self,
                m: &ContactModel<N, T, C, R>,
            ) -> PairOutput {
                m.pair_force(self.0, self.1)
            }
        }
        self.dispatch(K(p, history))
    }

    /// [`ContactModel::wall_force`] through one `match`.
    pub fn wall_force(&self, w: &WallInput, history: &mut [f64]) -> WallOutput {
        struct K<'a, 'b, 'c>(&'a WallInput<'b>, &'c mut [f64]);
        impl ContactKernel for K<'_, '_, '_> {
            type Output = WallOutput;
            fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
                self,
                m: &ContactModel<N, T, C, R>,
            ) -> WallOutput {
                m.wall_force(self.0, self.1)
            }
        }
        self.dispatch(K(w, history))
    }

    /// [`ContactModel::surfaces_close`] through one `match`.
    pub fn surfaces_close(&self, history: &mut [f64]) {
        struct K<'c>(&'c mut [f64]);
        impl ContactKernel for K<'_> {
            type Output = ();
            fn run<N: NormalModel, T: TangentialModel, C: CohesionModel, R: RollingModel>(
                self,
                m: &ContactModel<N, T, C, R>,
            ) {
                m.surfaces_close(self.0)
            }
        }
        self.dispatch(K(history))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hertz_coeffs(e: f64) -> PairCoeffs {
        let input = MaterialInput {
            ntypes: 1,
            youngs_modulus: Some(vec![1e7]),
            poissons_ratio: Some(vec![0.3]),
            coefficient_restitution: Some(vec![e]),
            coefficient_friction: Some(vec![0.5]),
            characteristic_velocity: Some(1.0),
            ..MaterialInput::default()
        };
        let req = [
            (Property::Yeff, "t"),
            (Property::Geff, "t"),
            (Property::BetaEff, "t"),
            (Property::CharVel, "t"),
            (Property::CoeffFrict, "t"),
        ];
        *Material::new(&input, &req).unwrap().pair(1, 1)
    }

    /// Head-on collision of two equal spheres integrated with velocity Verlet; returns the
    /// ratio of separation to approach speed.
    fn rebound<N: NormalModel>(normal: N, e: f64) -> f64 {
        let model = ContactModel::new(normal, History, NoCohesion, NoRolling);
        let coeffs = hertz_coeffs(e);
        let (r, rho) = (0.005, 2500.0);
        let m = 4.0 * PI / 3.0 * r * r * r * rho;
        let v0 = 1.0;
        let mut x = [-r - 1e-7, r + 1e-7];
        let mut v = [v0 / 2.0, -v0 / 2.0];
        let dt = 2e-8;
        let mut h = [0.0; 3];
        let force = |x: &[f64; 2], v: &[f64; 2], h: &mut [f64; 3]| {
            let p = PairInput {
                xi: [x[0], 0.0, 0.0],
                xj: [x[1], 0.0, 0.0],
                radi: r,
                radj: r,
                mi: m,
                mj: m,
                frozen_i: false,
                frozen_j: false,
                vi: [v[0], 0.0, 0.0],
                vj: [v[1], 0.0, 0.0],
                omegai: [0.0; 3],
                omegaj: [0.0; 3],
                dt,
                update_history: true,
                coeffs: &coeffs,
            };
            model.pair_force(&p, h)
        };
        let mut f = force(&x, &v, &mut h).fi[0];
        let mut touched = false;
        for _ in 0..10_000_000 {
            v[0] += 0.5 * dt * f / m;
            v[1] -= 0.5 * dt * f / m;
            x[0] += dt * v[0];
            x[1] += dt * v[1];
            let out = force(&x, &v, &mut h);
            f = out.fi[0];
            v[0] += 0.5 * dt * f / m;
            v[1] -= 0.5 * dt * f / m;
            touched |= out.touching;
            if touched && !out.touching {
                break;
            }
        }
        (v[1] - v[0]) / v0
    }

    #[test]
    fn restitution_of_a_head_on_collision_equals_e() {
        for e in [0.3, 0.5, 0.9] {
            let hz = rebound(Hertz::default(), e);
            assert!((hz - e).abs() < 1e-3, "hertz e={e}: {hz}");
            let hk = rebound(Hooke::default(), e);
            assert!((hk - e).abs() < 1e-3, "hooke e={e}: {hk}");
        }
    }

    fn oblique(coeffs: &PairCoeffs) -> PairInput<'_> {
        PairInput {
            xi: [0.0, 0.0, 0.0],
            xj: [0.0195, 0.001, -0.0005],
            radi: 0.01,
            radj: 0.01,
            mi: 0.01,
            mj: 0.012,
            frozen_i: false,
            frozen_j: false,
            vi: [0.2, 0.1, 0.0],
            vj: [-0.1, 0.0, 0.3],
            omegai: [1.0, 2.0, 3.0],
            omegaj: [-2.0, 0.5, 1.0],
            dt: 1e-5,
            update_history: true,
            coeffs,
        }
    }

    #[test]
    fn dyn_fallback_equals_the_monomorphised_kernel() {
        let coeffs = hertz_coeffs(0.6);
        let sel = ModelSelection::parse(&["model", "hertz", "tangential", "history"]).unwrap();
        let any = AnyContactModel::new(&sel).unwrap();
        assert!(matches!(any, AnyContactModel::HertzHistory(_)));
        let (n, t, c, r) = sel.sub_models().unwrap();
        let dynm = ContactModel::new(n, t, c, r);
        let p = oblique(&coeffs);
        let (mut h1, mut h2) = ([0.0; 3], [0.0; 6]);
        for _ in 0..5 {
            let a = any.pair_force(&p, &mut h1);
            let b = dynm.pair_force(&p, &mut h2);
            assert_eq!(a, b);
            assert_eq!(h1[..], h2[..3]);
        }
        assert_eq!(any.history_len(), 3);
    }

    #[test]
    fn newton_third_law_and_frozen_meff() {
        let coeffs = hertz_coeffs(0.6);
        let model = ContactModel::new(Hertz::default(), History, Sjkr::default(), NoRolling);
        let mut p = oblique(&coeffs);
        let out = model.pair_force(&p, &mut [0.0; 3]);
        for d in 0..3 {
            assert_eq!(out.fj[d], -out.fi[d]);
        }
        // frozen j behaves as infinite mass: meff = mi, so more damping than mi mj/(mi+mj)
        p.frozen_j = true;
        let frozen = model.pair_force(&p, &mut [0.0; 3]);
        assert!(frozen.normal_force != out.normal_force);
        p.frozen_j = false;
        p.mj = 1e30;
        let heavy = model.pair_force(&p, &mut [0.0; 3]);
        assert!(
            (heavy.normal_force - frozen.normal_force).abs() < 1e-12 * frozen.normal_force.abs()
        );
        // apart: nothing, and the history is kept
        let mut h = [1.0, 2.0, 3.0];
        p.xj = [0.03, 0.0, 0.0];
        let apart = model.pair_force(&p, &mut h);
        assert!(!apart.touching && apart.fi == [0.0; 3]);
        assert_eq!(h, [1.0, 2.0, 3.0]);
        model.surfaces_close(&mut h);
        assert_eq!(h, [0.0; 3]);
    }

    #[test]
    fn wall_matches_a_pair_with_an_infinitely_large_partner() {
        // a sphere on the plane z = 0 vs the same sphere on a huge frozen sphere
        let coeffs = hertz_coeffs(0.6);
        let model = ContactModel::new(Hertz::default(), History, NoCohesion, NoRolling);
        let x = [0.1, 0.2, 0.0099];
        let (gap, to_wall) = plane_contact(2, 0.0, &x, 0.01);
        assert!((gap + 1e-4).abs() < 1e-15);
        let w = WallInput {
            x,
            gap,
            to_wall,
            radius: 0.01,
            mass: 0.01,
            v: [0.1, 0.0, -0.2],
            omega: [0.0, 0.0, 0.0],
            v_wall: [0.0; 3],
            dt: 1e-5,
            update_history: true,
            coeffs: &coeffs,
        };
        let mut h = [0.0; 3];
        let out = model.wall_force(&w, &mut h);
        assert!(out.touching);
        let big = 1e6;
        let p = PairInput {
            xi: x,
            xj: [0.1, 0.2, -big + 1e-4 - 1e-4],
            radi: 0.01,
            radj: big,
            mi: 0.01,
            mj: 1.0,
            frozen_i: false,
            frozen_j: true,
            vi: w.v,
            vj: [0.0; 3],
            omegai: [0.0; 3],
            omegaj: [0.0; 3],
            dt: 1e-5,
            update_history: true,
            coeffs: &coeffs,
        };
        let mut hp = [0.0; 3];
        let po = model.pair_force(&p, &mut hp);
        // R* -> R for an infinite partner: forces agree to the size ratio
        for d in 0..3 {
            assert!(
                (po.fi[d] - out.f[d]).abs() < 1e-6 * out.f[2].abs(),
                "{:?} {:?}",
                po.fi,
                out.f
            );
        }
        assert_eq!(out.contact_point, [0.1, 0.2, 0.0]);
        // leaving the wall resets the history
        let mut w2 = w;
        w2.x = [0.1, 0.2, 0.02];
        let (g2, t2) = plane_contact(2, 0.0, &w2.x, 0.01);
        w2.gap = g2;
        w2.to_wall = t2;
        assert!(!model.wall_force(&w2, &mut h).touching);
        assert_eq!(h, [0.0; 3]);
    }

    #[test]
    fn local_output_splits_force_and_torque() {
        let coeffs = hertz_coeffs(0.6);
        let model = ContactModel::new(Hertz::default(), History, NoCohesion, NoRolling);
        let p = oblique(&coeffs);
        let mut h = [0.0; 3];
        model.pair_force(&p, &mut h);
        let out = model.pair_force(&p, &mut h);
        let l = out.local(&p);
        for d in 0..3 {
            assert!((l.force_normal[d] + l.force_tangential[d] - out.fi[d]).abs() < 1e-15);
            assert!((l.force_normal[d] - out.normal_force * out.en[d]).abs() < 1e-9);
        }
        assert!((l.delta - out.deltan).abs() < 1e-18);
        assert!(l.contact_area > 0.0);
        assert!((l.contact_point[0] - 0.0195 / 2.0).abs() < 1e-15);
    }

    #[test]
    fn selection_parsing_and_messages() {
        let sel = ModelSelection::parse(&[
            "model",
            "hertz",
            "tangential",
            "history",
            "cohesion",
            "sjkr",
            "rolling_friction",
            "epsd",
            "tangential_reduce",
            "on",
            "torsionTorque",
            "on",
            "limitForce",
            "on",
        ])
        .unwrap();
        assert!(
            sel.options.tangential_reduce && sel.options.torsion_torque && sel.options.limit_force
        );
        assert!(sel.options.tangential_damping);
        let any = AnyContactModel::new(&sel).unwrap();
        assert!(matches!(any, AnyContactModel::HertzHistorySjkrEpsd(_)));
        assert_eq!(any.history_len(), 6);
        assert_eq!(
            any.properties(),
            vec![
                (Property::Yeff, "model hertz"),
                (Property::Geff, "model hertz"),
                (Property::BetaEff, "model hertz"),
                (Property::CohEnergyDens, "cohesion_model sjkr"),
                (Property::CoeffFrict, "tangential_model history"),
                (Property::CoeffRollFrict, "rolling_model epsd"),
                (Property::CoeffRollVisc, "rolling_model epsd"),
            ]
        );
        let sel =
            ModelSelection::parse(&["model", "hertz", "tangential", "history_total_cap"]).unwrap();
        assert!(matches!(
            AnyContactModel::new(&sel).unwrap(),
            AnyContactModel::HertzTotalCap(_)
        ));
        // a combination without its own variant still works through the fallback
        let sel = ModelSelection::parse(&[
            "model",
            "hooke/stiffness",
            "tangential",
            "no_history",
            "rolling_friction",
            "epsd3",
        ])
        .unwrap();
        let any = AnyContactModel::new(&sel).unwrap();
        assert!(!any.is_monomorphised());
        assert_eq!(any.history_len(), 3);
        // LIGGGHTS's messages
        assert_eq!(
            ModelSelection::parse(&["model", "hertzz"])
                .unwrap_err()
                .to_string(),
            "Invalid model specified (check for typos and enable at least one model)"
        );
        assert_eq!(
            ModelSelection::parse(&["tangential", "off"])
                .unwrap_err()
                .to_string(),
            "Invalid model specified (check for typos and enable at least one model)"
        );
        assert_eq!(
            ModelSelection::parse(&["model", "hertz", "tangential_reduce", "on"])
                .unwrap_err()
                .to_string(),
            "Unknown argument or wrong keyword order: 'tangential_reduce'"
        );
        assert_eq!(
            ModelSelection::parse(&["model", "hertz", "limitForce", "yes"])
                .unwrap_err()
                .to_string(),
            "while parsing 'limitForce' argument: unknown option or wrong keyword order: 'yes'"
        );
        // keywords after the settings are not model keywords
        assert!(ModelSelection::parse(&[
            "model",
            "hertz",
            "limitForce",
            "on",
            "tangential",
            "history"
        ])
        .is_err());
        assert!(
            AnyContactModel::new(&ModelSelection::parse(&["model", "luding"]).unwrap()).is_err()
        );
        assert!(ModelSelection::parse(&["model", "hertz", "heating_normal_hertz", "off"]).is_ok());
        assert!(ModelSelection::parse(&["model", "hertz", "heating_normal_hertz", "on"]).is_err());
    }

    mod props {
        use super::*;
        use proptest::prelude::*;

        const NORMALS: [&str; 4] = ["hertz", "hooke", "hertz/stiffness", "hooke/stiffness"];
        const TANGENTIALS: [&str; 4] = ["off", "no_history", "history", "history_total_cap"];
        const COHESIONS: [&str; 3] = ["off", "sjkr", "sjkr2"];
        const ROLLINGS: [&str; 5] = ["off", "cdt", "epsd", "epsd2", "epsd3"];

        fn coeffs() -> PairCoeffs {
            PairCoeffs {
                yeff: 5e7,
                geff: 2e7,
                betaeff: -0.4,
                coeff_rest_log: -1.2,
                char_vel: 1.0,
                coeff_frict: 0.4,
                cohesion_energy_density: 1e5,
                coeff_roll_frict: 0.05,
                coeff_roll_visc: 0.2,
                rolling_stiffness: 2.0,
                kn: 1e4,
                kt: 5e3,
                gamman: 40.0,
                gammat: 20.0,
                ..PairCoeffs::default()
            }
        }

        proptest! {
            #[test]
            fn third_law_and_coulomb_bound(
                n in 0usize..4, t in 0usize..4, c in 0usize..3, r in 0usize..5,
                dir in prop::array::uniform3(-1.0f64..1.0),
                overlap in 1e-6f64..1e-3,
                vi in prop::array::uniform3(-1.0f64..1.0),
                wi in prop::array::uniform3(-30.0f64..30.0),
                wj in prop::array::uniform3(-30.0f64..30.0),
                steps in 1usize..20,
            ) {
                let norm = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
                prop_assume!(norm > 0.1);
                let sel = ModelSelection::parse(&[
                    "model", NORMALS[n], "tangential", TANGENTIALS[t],
                    "cohesion", COHESIONS[c], "rolling_friction", ROLLINGS[r],
                ]).unwrap();
                let model = AnyContactModel::new(&sel).unwrap();
                let co = coeffs();
                let dist = 0.021 - overlap;
                let p = PairInput {
                    xi: [dist * dir[0] / norm, dist * dir[1] / norm, dist * dir[2] / norm],
                    xj: [0.0; 3],
                    radi: 0.01, radj: 0.011, mi: 0.01, mj: 0.013,
                    frozen_i: false, frozen_j: false,
                    vi, vj: [0.0; 3], omegai: wi, omegaj: wj,
                    dt: 1e-5, update_history: true, coeffs: &co,
                };
                let mut h = vec![0.0; model.history_len()];
                for _ in 0..steps {
                    let out = model.pair_force(&p, &mut h);
                    prop_assert!(out.touching);
                    for d in 0..3 {
                        prop_assert_eq!(out.fj[d], -out.fi[d]);
                    }
                    let ft = (out.ft[0] * out.ft[0] + out.ft[1] * out.ft[1] + out.ft[2] * out.ft[2]).sqrt();
                    let limit = 0.4 * out.normal_force.abs();
                    if TANGENTIALS[t] == "history_total_cap" || TANGENTIALS[t] == "no_history" {
                        prop_assert!(ft <= limit * (1.0 + 1e-12) + 1e-300, "{} > {}", ft, limit);
                    }
                    // the tangential force lies in the tangent plane
                    let dot = out.ft[0] * out.en[0] + out.ft[1] * out.en[1] + out.ft[2] * out.en[2];
                    prop_assert!(dot.abs() <= 1e-9 * (ft + 1e-12));
                }
            }
        }
    }
}
