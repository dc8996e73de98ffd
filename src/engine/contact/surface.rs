//! Surface models: the kinematics of a contact (relative normal and tangential velocity at
//! the contact point, lever arms), computed before any force model runs. Only LIGGGHTS's
//! `surface default` (spheres) exists in regolith.

use super::real::Real;
use super::Contact;

/// A surface model fills the kinematic fields of a [`Contact`]: `vn`, `vtr`, `wr`, `cri`,
/// `crj` and the recomputed `deltan`.
pub trait SurfaceModel: Send + Sync {
    /// Compute the contact kinematics from positions, radii and velocities.
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>);
}

/// `surface default`: spheres; the contact point lies half the overlap inside each surface.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DefaultSurface;

impl SurfaceModel for DefaultSurface {
    #[inline(always)]
    fn surfaces_intersect<S: Real>(&self, c: &mut Contact<S>) {
        let [enx, eny, enz] = c.en;
        // relative velocity of the centres, split into normal and tangential parts
        let vr1 = c.vi[0] - c.vj[0];
        let vr2 = c.vi[1] - c.vj[1];
        let vr3 = c.vi[2] - c.vj[2];
        let vn = vr1 * enx + vr2 * eny + vr3 * enz;
        let vt1 = vr1 - vn * enx;
        let vt2 = vr2 - vn * eny;
        let vt3 = vr3 - vn * enz;
        // the overlap is recomputed from the centre distance (for walls too)
        let deltan = c.radsum - c.r;
        let [dx, dy, dz] = c.delta;
        let rinv = c.rinv;
        let (wr1, wr2, wr3);
        if c.is_wall {
            // the lever arm uses the overlap the wall geometry passed in, not the recomputed one
            let cr = c.radi - S::splat(0.5) * c.deltan;
            wr1 = cr * c.omegai[0] * rinv;
            wr2 = cr * c.omegai[1] * rinv;
            wr3 = cr * c.omegai[2] * rinv;
            c.cri = cr;
        } else {
            let cri = c.radi - S::splat(0.5) * deltan;
            let crj = c.radj - S::splat(0.5) * deltan;
            wr1 = (cri * c.omegai[0] + crj * c.omegaj[0]) * rinv;
            wr2 = (cri * c.omegai[1] + crj * c.omegaj[1]) * rinv;
            wr3 = (cri * c.omegai[2] + crj * c.omegaj[2]) * rinv;
            c.cri = cri;
            c.crj = crj;
        }
        // tangential velocity of the surfaces at the contact point
        c.vtr = [
            vt1 - (dz * wr2 - dy * wr3),
            vt2 - (dx * wr3 - dz * wr1),
            vt3 - (dy * wr1 - dx * wr2),
        ];
        c.vn = vn;
        c.deltan = deltan;
        c.wr = [wr1, wr2, wr3];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sliding_and_rolling_kinematics() {
        // two equal spheres along x, i spinning about z: the contact point of i moves in +y
        let mut c = Contact {
            radi: 1.0,
            radj: 1.0,
            radsum: 2.0,
            r: 1.9,
            rinv: 1.0 / 1.9,
            delta: [1.9, 0.0, 0.0],
            en: [1.0, 0.0, 0.0],
            vi: [-0.3, 0.2, 0.0],
            omegai: [0.0, 0.0, 2.0],
            ..Contact::default()
        };
        DefaultSurface.surfaces_intersect(&mut c);
        assert!((c.deltan - 0.1).abs() < 1e-15);
        assert_eq!(c.vn, -0.3);
        assert!((c.cri - 0.95).abs() < 1e-15);
        // the contact point of i (at -cri en from i) moves with omega x (-cri en) = -2 cri y
        // relative to j (at rest): vtr = 0.2 - 2*0.95 = -1.7 in y
        assert!((c.vtr[1] - (0.2 - 2.0 * 0.95)).abs() < 1e-14, "{:?}", c.vtr);
        assert_eq!(c.vtr[0], 0.0);
        assert_eq!(c.vtr[2], 0.0);
    }
}
