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
pub mod easo;
#[cfg(test)]
mod golden;
pub mod material;
pub mod multicontact;
pub mod multicontact_wall;
pub mod normal;
pub mod real;
pub mod rolling;
mod selection;
pub mod surface;
pub mod tangential;
pub mod whitelist;

use std::f64::consts::PI;

pub use cohesion::{AnyCohesion, CohesionModel, NoCohesion, Sjkr, Sjkr2};
pub use material::{
    CoeffLanes, CoeffWideLanes, Coeffs, Material, MaterialInput, PairCoeffs, Property, UnitStyle,
};
pub use normal::{
    AnyNormal, Hertz, HertzStiffness, Hooke, HookeHysteresis, HookeStiffness, NormalModel,
};
pub use real::{F64x4, F64x8, Real, LANES, WIDE_LANES};
pub use rolling::{AnyRolling, Cdt, Epsd, Epsd2, Epsd3, NoRolling, RollingModel};
pub use selection::{ModelError, ModelOptions, ModelSelection};
pub use surface::{DefaultSurface, SurfaceModel};
pub use tangential::{
    AnyTangential, History, HistoryTotalCap, NoHistory, NoTangential, TangentialModel,
};

/// A 3-vector in SI units (m, m/s, rad/s, N or N m depending on the field).
pub type Vec3 = [f64; 3];

/// One touching contact as the sub-models see it (LIGGGHTS's `SurfacesIntersectData`
/// together with the two `ForceData` sums). For a wall, j is the wall.
#[derive(Debug, Clone, Copy, PartialEq)]
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

impl<S: Copy + Default> Default for Contact<S> {
    /// All zeros (written out and inlined: on builds without link-time optimisation the
    /// derived one stayed a call inside the pair kernel's loop).
    #[inline(always)]
    fn default() -> Self {
        let z = S::default();
        let v = [z; 3];
        Contact {
            is_wall: false,
            radi: z,
            radj: z,
            radsum: z,
            r: z,
            rinv: z,
            delta: v,
            en: v,
            deltan: z,
            mi: z,
            mj: z,
            meff: z,
            vi: v,
            vj: v,
            omegai: v,
            omegaj: v,
            dt: z,
            update_history: false,
            vn: z,
            vtr: v,
            wr: v,
            cri: z,
            crj: z,
            normal_force: z,
            kn: z,
            kt: z,
            gamman: z,
            gammat: z,
            fi: v,
            fj: v,
            ti: v,
            tj: v,
            ft: v,
            r_torque: v,
        }
    }
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

/// Particle pairs side by side, one per lane of `S` ([`F64x4`] or [`real::F64x8`]), as the
/// batched pair loop gathers them (the fields of [`PairInput`]; j already shifted to the
/// image nearest i).
#[derive(Debug, Clone, Copy)]
pub struct PairLanes<S: Real = F64x4> {
    /// Positions of i (m).
    pub xi: [S; 3],
    /// Positions of j (m).
    pub xj: [S; 3],
    /// Radii of i (m).
    pub radi: S,
    /// Radii of j (m).
    pub radj: S,
    /// Masses of i (kg).
    pub mi: S,
    /// Masses of j (kg).
    pub mj: S,
    /// i is frozen (infinite mass in the damping).
    pub frozen_i: S::Mask,
    /// j is frozen.
    pub frozen_j: S::Mask,
    /// Velocities of i (m/s).
    pub vi: [S; 3],
    /// Velocities of j (m/s).
    pub vj: [S; 3],
    /// Angular velocities of i (rad/s).
    pub omegai: [S; 3],
    /// Angular velocities of j (rad/s).
    pub omegaj: [S; 3],
    /// Time step (s).
    pub dt: f64,
    /// Advance and store history (false during setup).
    pub update_history: bool,
}

/// Four particles touching one wall at once, one per lane (the fields of [`WallInput`]
/// that the force needs; every lane's gap is <= 0).
#[derive(Debug, Clone, Copy)]
pub struct WallLanes {
    /// Signed gaps, distance to the wall minus the radius (m, <= 0).
    pub gap: F64x4,
    /// Vectors from the centres to the closest wall points (m).
    pub to_wall: [F64x4; 3],
    /// Radii (m).
    pub radius: F64x4,
    /// Masses (kg); meff = mass.
    pub mass: F64x4,
    /// Velocities (m/s).
    pub v: [F64x4; 3],
    /// Angular velocities (rad/s).
    pub omega: [F64x4; 3],
    /// Velocities of the wall at the contacts (m/s).
    pub v_wall: [F64x4; 3],
    /// Time step (s).
    pub dt: f64,
    /// Advance and store history (false during setup).
    pub update_history: bool,
}

/// What a batch of touching pairs contributes, one per lane of `S` (see [`PairOutput`]).
#[derive(Debug, Clone, Copy, Default)]
pub struct PairLanesOutput<S = F64x4> {
    /// Forces on i (N).
    pub fi: [S; 3],
    /// Forces on j (N).
    pub fj: [S; 3],
    /// Torques on i (N m).
    pub ti: [S; 3],
    /// Torques on j (N m).
    pub tj: [S; 3],
    /// Overlaps (m).
    pub deltan: S,
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

    /// Forces and torques of a batch of touching particle pairs at once (lane k is the pair
    /// [`Self::pair_force`] would compute from the k-th inputs, bit for bit); `history`
    /// holds each lane's values (`history_len()` entries).
    #[inline(always)]
    pub fn pair_force_lanes<S: Real>(
        &self,
        p: &PairLanes<S>,
        m: &impl Coeffs<S>,
        history: &mut [S],
    ) -> PairLanesOutput<S> {
        let delx = p.xi[0] - p.xj[0];
        let dely = p.xi[1] - p.xj[1];
        let delz = p.xi[2] - p.xj[2];
        let rsq = delx * delx + dely * dely + delz * delz;
        let radsum = p.radi + p.radj;
        let r = rsq.sqrt();
        let rinv = S::splat(1.0) / r;
        let en = [delx * rinv, dely * rinv, delz * rinv];
        let mut meff = p.mi * p.mj / (p.mi + p.mj);
        meff = S::select(p.frozen_i, p.mj, meff);
        meff = S::select(p.frozen_j, p.mi, meff);
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
            dt: S::splat(p.dt),
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
        let mut c = wall_contact(
            (w.gap, w.to_wall, w.radius, w.mass),
            (w.v, w.omega, w.v_wall),
            w.dt,
            w.update_history,
        );
        let delta = c.delta;
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

    /// Forces (N) and torques (N m) of a wall on four touching particles at once: lane k
    /// is what [`Self::wall_force`] computes from the k-th inputs, bit for bit; `history`
    /// holds each lane's values for this wall (`history_len()` entries).
    #[inline(always)]
    pub fn wall_force_lanes(
        &self,
        w: &WallLanes,
        m: &impl Coeffs<F64x4>,
        history: &mut [F64x4],
    ) -> ([F64x4; 3], [F64x4; 3]) {
        let mut c = wall_contact(
            (w.gap, w.to_wall, w.radius, w.mass),
            (w.v, w.omega, w.v_wall),
            F64x4::splat(w.dt),
            w.update_history,
        );
        self.intersect(&mut c, m, history);
        (c.fi, c.ti)
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

/// A particle touching a wall before any sub-model runs, for one particle or four lanes:
/// from its gap and vector to the wall (m), radius (m) and mass (kg, meff = mass), its
/// velocity, spin and the wall's velocity (m/s, rad/s), and the step (s).
#[inline(always)]
fn wall_contact<S: Real>(
    (gap, to_wall, radius, mass): (S, [S; 3], S, S),
    (v, omega, v_wall): ([S; 3], [S; 3], [S; 3]),
    dt: S,
    update_history: bool,
) -> Contact<S> {
    let deltan = -gap;
    let delta = [-to_wall[0], -to_wall[1], -to_wall[2]];
    let r = radius - deltan;
    let rinv = S::splat(1.0) / r;
    let en = [delta[0] * rinv, delta[1] * rinv, delta[2] * rinv];
    Contact {
        is_wall: true,
        radi: radius,
        radsum: radius,
        r,
        rinv,
        delta,
        en,
        deltan,
        mi: mass,
        meff: mass,
        vi: v,
        vj: v_wall,
        omegai: omega,
        dt,
        update_history,
        ..Contact::default()
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
mod tests;
