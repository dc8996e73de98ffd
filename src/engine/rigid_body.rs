//! Rigid-body motion of a multisphere clump as LIGGGHTS 3.8.0's `fix multisphere` integrates
//! it: velocity Verlet on the centre of mass, the angular momentum kicked by the torque, and
//! the orientation quaternion advanced by a Richardson iteration (a full step and two half
//! steps of dq/dt = w q / 2, combined and normalised). The operations and their order follow
//! LIGGGHTS's, so that the arithmetic agrees with it to the bit.

/// A unit quaternion (w, x, y, z).
pub type Quat = [f64; 4];
/// A vector (units per use).
pub type Vec3 = [f64; 3];

fn normalize(q: &mut Quat) {
    let n = 1.0 / (q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]).sqrt();
    for c in q.iter_mut() {
        *c *= n;
    }
}

/// The product of the pure quaternion (0, a) and q.
fn vec_times_quat(a: &Vec3, q: &Quat) -> Quat {
    [
        -a[0] * q[1] - a[1] * q[2] - a[2] * q[3],
        q[0] * a[0] + a[1] * q[3] - a[2] * q[2],
        q[0] * a[1] + a[2] * q[1] - a[0] * q[3],
        q[0] * a[2] + a[0] * q[2] - a[1] * q[1],
    ]
}

/// The rotation matrix of a unit quaternion.
fn rotation(q: &Quat) -> [[f64; 3]; 3] {
    let (w2, i2, j2, k2) = (q[0] * q[0], q[1] * q[1], q[2] * q[2], q[3] * q[3]);
    let ij = 2.0 * q[1] * q[2];
    let ik = 2.0 * q[1] * q[3];
    let jk = 2.0 * q[2] * q[3];
    let iw = 2.0 * q[1] * q[0];
    let jw = 2.0 * q[2] * q[0];
    let kw = 2.0 * q[3] * q[0];
    [
        [w2 + i2 - j2 - k2, ij - kw, jw + ik],
        [ij + kw, w2 - i2 + j2 - k2, jk - iw],
        [ik - jw, jk + iw, w2 - i2 - j2 + k2],
    ]
}

/// The quaternion of the rotation taking the unit axes to `ex`, `ey`, `ez`.
pub fn axes_to_quat(ex: &Vec3, ey: &Vec3, ez: &Vec3) -> Quat {
    let q0sq = 0.25 * (ex[0] + ey[1] + ez[2] + 1.0);
    let q1sq = q0sq - 0.5 * (ey[1] + ez[2]);
    let q2sq = q0sq - 0.5 * (ex[0] + ez[2]);
    let q3sq = q0sq - 0.5 * (ex[0] + ey[1]);
    let mut q = [0.0; 4];
    if q0sq >= 0.25 {
        q[0] = q0sq.sqrt();
        q[1] = (ey[2] - ez[1]) / (4.0 * q[0]);
        q[2] = (ez[0] - ex[2]) / (4.0 * q[0]);
        q[3] = (ex[1] - ey[0]) / (4.0 * q[0]);
    } else if q1sq >= 0.25 {
        q[1] = q1sq.sqrt();
        q[0] = (ey[2] - ez[1]) / (4.0 * q[1]);
        q[2] = (ey[0] + ex[1]) / (4.0 * q[1]);
        q[3] = (ex[2] + ez[0]) / (4.0 * q[1]);
    } else if q2sq >= 0.25 {
        q[2] = q2sq.sqrt();
        q[0] = (ez[0] - ex[2]) / (4.0 * q[2]);
        q[1] = (ey[0] + ex[1]) / (4.0 * q[2]);
        q[3] = (ez[1] + ey[2]) / (4.0 * q[2]);
    } else if q3sq >= 0.25 {
        q[3] = q3sq.sqrt();
        q[0] = (ex[1] - ey[0]) / (4.0 * q[3]);
        q[1] = (ez[0] + ex[2]) / (4.0 * q[3]);
        q[2] = (ez[1] + ey[2]) / (4.0 * q[3]);
    }
    normalize(&mut q);
    q
}

/// The rotated unit axes of a unit quaternion.
pub fn quat_to_axes(q: &Quat) -> [Vec3; 3] {
    [
        [
            q[0] * q[0] + q[1] * q[1] - q[2] * q[2] - q[3] * q[3],
            2.0 * (q[1] * q[2] + q[0] * q[3]),
            2.0 * (q[1] * q[3] - q[0] * q[2]),
        ],
        [
            2.0 * (q[1] * q[2] - q[0] * q[3]),
            q[0] * q[0] - q[1] * q[1] + q[2] * q[2] - q[3] * q[3],
            2.0 * (q[2] * q[3] + q[0] * q[1]),
        ],
        [
            2.0 * (q[1] * q[3] + q[0] * q[2]),
            2.0 * (q[2] * q[3] - q[0] * q[1]),
            q[0] * q[0] - q[1] * q[1] - q[2] * q[2] + q[3] * q[3],
        ],
    ]
}

/// Angular velocity (1/time) from angular momentum and principal moments along `axes`
/// (a zero moment gives no rotation about its axis).
pub fn angmom_to_omega(m: &Vec3, axes: &[Vec3; 3], moments: &Vec3) -> Vec3 {
    let mut wb = [0.0; 3];
    for k in 0..3 {
        let a = &axes[k];
        wb[k] = if moments[k] == 0.0 {
            0.0
        } else {
            (m[0] * a[0] + m[1] * a[1] + m[2] * a[2]) / moments[k]
        };
    }
    let (ex, ey, ez) = (&axes[0], &axes[1], &axes[2]);
    [
        wb[0] * ex[0] + wb[1] * ey[0] + wb[2] * ez[0],
        wb[0] * ex[1] + wb[1] * ey[1] + wb[2] * ez[1],
        wb[0] * ex[2] + wb[1] * ey[2] + wb[2] * ez[2],
    ]
}

/// Angular momentum (mass*length^2/time) from angular velocity and principal moments.
pub fn omega_to_angmom(w: &Vec3, axes: &[Vec3; 3], moments: &Vec3) -> Vec3 {
    let mut mb = [0.0; 3];
    for k in 0..3 {
        let a = &axes[k];
        mb[k] = (w[0] * a[0] + w[1] * a[1] + w[2] * a[2]) * moments[k];
    }
    let (ex, ey, ez) = (&axes[0], &axes[1], &axes[2]);
    [
        mb[0] * ex[0] + mb[1] * ey[0] + mb[2] * ez[0],
        mb[0] * ex[1] + mb[1] * ey[1] + mb[2] * ez[1],
        mb[0] * ex[2] + mb[1] * ey[2] + mb[2] * ez[2],
    ]
}

/// Angular velocity from angular momentum and an orientation quaternion.
fn angmom_quat_to_omega(m: &Vec3, q: &Quat, moments: &Vec3) -> Vec3 {
    let r = rotation(q);
    let mut wb = [
        r[0][0] * m[0] + r[1][0] * m[1] + r[2][0] * m[2],
        r[0][1] * m[0] + r[1][1] * m[1] + r[2][1] * m[2],
        r[0][2] * m[0] + r[1][2] * m[1] + r[2][2] * m[2],
    ];
    for k in 0..3 {
        if moments[k] == 0.0 {
            wb[k] = 0.0;
        } else {
            wb[k] /= moments[k];
        }
    }
    [
        r[0][0] * wb[0] + r[0][1] * wb[1] + r[0][2] * wb[2],
        r[1][0] * wb[0] + r[1][1] * wb[1] + r[1][2] * wb[2],
        r[2][0] * wb[0] + r[2][1] * wb[1] + r[2][2] * wb[2],
    ]
}

/// Advances `q` by `2 dtq` with Richardson's iteration; `w` is updated to the angular velocity
/// at the half step.
pub fn richardson(q: &mut Quat, m: &Vec3, w: &mut Vec3, moments: &Vec3, dtq: f64) {
    let wq = vec_times_quat(w, q);
    let mut full = [0.0; 4];
    let mut half = [0.0; 4];
    for k in 0..4 {
        full[k] = q[k] + dtq * wq[k];
    }
    normalize(&mut full);
    for k in 0..4 {
        half[k] = q[k] + 0.5 * dtq * wq[k];
    }
    normalize(&mut half);
    *w = angmom_quat_to_omega(m, &half, moments);
    let wq = vec_times_quat(w, &half);
    for k in 0..4 {
        half[k] += 0.5 * dtq * wq[k];
    }
    normalize(&mut half);
    for k in 0..4 {
        q[k] = 2.0 * half[k] - full[k];
    }
    normalize(q);
}

/// One rigid clump: its state in the space frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Body id (LIGGGHTS's body tag, the atoms' `mol`).
    pub tag: i64,
    /// Mass (mass).
    pub mass: f64,
    /// Density (mass/length^3).
    pub density: f64,
    /// Principal moments of inertia (mass*length^2).
    pub moments: Vec3,
    /// Centre of mass (length).
    pub xcm: Vec3,
    /// Centre-of-mass velocity (length/time).
    pub vcm: Vec3,
    /// Angular momentum (mass*length^2/time).
    pub angmom: Vec3,
    /// Angular velocity (1/time).
    pub omega: Vec3,
    /// Orientation.
    pub quat: Quat,
    /// Principal axes in the space frame (unit vectors).
    pub axes: [Vec3; 3],
    /// Total force on the body (force).
    pub fcm: Vec3,
    /// Total torque about the centre of mass (force*length).
    pub torque: Vec3,
    /// Translations that are integrated.
    pub fflag: [bool; 3],
    /// Rotations that are integrated.
    pub tflag: [bool; 3],
    /// Step from which the body is integrated (`fix insert/stream`: it moves at
    /// `v_integrate` before; -1: no such step).
    pub start_step: i64,
    /// Velocity while moving to the release point (length/time).
    pub v_integrate: Vec3,
}

impl Body {
    /// A body at rest force-wise, with LIGGGHTS's initial quaternion and angular momentum.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        tag: i64,
        mass: f64,
        density: f64,
        moments: Vec3,
        xcm: Vec3,
        vcm: Vec3,
        omega: Vec3,
        axes: [Vec3; 3],
        fflag: [bool; 3],
        tflag: [bool; 3],
    ) -> Body {
        Body {
            tag,
            mass,
            density,
            moments,
            xcm,
            vcm,
            angmom: omega_to_angmom(&omega, &axes, &moments),
            omega,
            quat: axes_to_quat(&axes[0], &axes[1], &axes[2]),
            axes,
            fcm: [0.0; 3],
            torque: [0.0; 3],
            fflag,
            tflag,
            start_step: -1,
            v_integrate: [0.0; 3],
        }
    }

    /// Whether the body is still on its way from an insertion face at `step` (only with a
    /// `fix insert/stream` in the deck, as LIGGGHTS checks).
    pub fn streaming(&self, step: i64, has_stream: bool) -> bool {
        has_stream && step < self.start_step
    }

    /// A full step at the stream velocity, without forces or rotation (time `dt`).
    pub fn stream_step(&mut self, dt: f64) {
        self.vcm = self.v_integrate;
        for k in 0..3 {
            self.xcm[k] += dt * self.vcm[k];
        }
    }

    /// First half of the step: kick with the current force and torque, drift the centre of
    /// mass, rotate. `dt` is the time step (time).
    pub fn initial_integrate(&mut self, dt: f64) {
        self.half_kick(dt);
        for k in 0..3 {
            self.xcm[k] += dt * self.vcm[k];
        }
        self.omega = angmom_to_omega(&self.angmom, &self.axes, &self.moments);
        richardson(
            &mut self.quat,
            &self.angmom,
            &mut self.omega,
            &self.moments,
            0.5 * dt,
        );
        self.axes = quat_to_axes(&self.quat);
    }

    /// Half a step's kick of the velocity and angular momentum (unfixed components) with
    /// the current force and torque; `dt` is the whole time step (time).
    fn half_kick(&mut self, dt: f64) {
        let dtf = 0.5 * dt;
        let dtfm = dtf / self.mass;
        for k in 0..3 {
            if self.fflag[k] {
                self.vcm[k] += dtfm * self.fcm[k];
            }
        }
        for k in 0..3 {
            if self.tflag[k] {
                self.angmom[k] += dtf * self.torque[k];
            }
        }
    }

    /// Second half of the step: kick with the new force and torque.
    pub fn final_integrate(&mut self, dt: f64) {
        self.half_kick(dt);
        self.omega = angmom_to_omega(&self.angmom, &self.axes, &self.moments);
    }

    /// A member sphere's offset from the centre of mass in the space frame (length), from its
    /// body-frame offset.
    pub fn offset(&self, displace: &Vec3) -> Vec3 {
        let (ex, ey, ez) = (&self.axes[0], &self.axes[1], &self.axes[2]);
        [
            ex[0] * displace[0] + ey[0] * displace[1] + ez[0] * displace[2],
            ex[1] * displace[0] + ey[1] * displace[1] + ez[1] * displace[2],
            ex[2] * displace[0] + ey[2] * displace[1] + ez[2] * displace[2],
        ]
    }

    /// A member's velocity (length/time) at space-frame offset `d` from the centre of mass.
    pub fn velocity_at(&self, d: &Vec3) -> Vec3 {
        let w = &self.omega;
        [
            w[1] * d[2] - w[2] * d[1] + self.vcm[0],
            w[2] * d[0] - w[0] * d[2] + self.vcm[1],
            w[0] * d[1] - w[1] * d[0] + self.vcm[2],
        ]
    }

    /// Adds a member's force (force) and torque (force*length) acting at space-frame offset
    /// `d` from the centre of mass.
    pub fn add_member_force(&mut self, d: &Vec3, f: &Vec3, t: &Vec3) {
        for (c, x) in self.fcm.iter_mut().zip(f) {
            *c += x;
        }
        self.torque[0] += d[1] * f[2] - d[2] * f[1] + t[0];
        self.torque[1] += d[2] * f[0] - d[0] * f[2] + t[1];
        self.torque[2] += d[0] * f[1] - d[1] * f[0] + t[2];
    }

    /// Translational kinetic energy (energy).
    pub fn kinetic_energy(&self) -> f64 {
        0.5 * (self.mass
            * (self.vcm[0] * self.vcm[0] + self.vcm[1] * self.vcm[1] + self.vcm[2] * self.vcm[2]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body(omega: Vec3, moments: Vec3) -> Body {
        let axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        Body::new(
            1,
            2.0,
            1000.0,
            moments,
            [0.0; 3],
            [0.5, 0.0, 0.0],
            omega,
            axes,
            [true; 3],
            [true; 3],
        )
    }

    #[test]
    fn free_fall_keeps_the_exact_parabola_and_no_rotation() {
        let mut b = body([0.0; 3], [1.0, 2.0, 3.0]);
        let (dt, g) = (1e-4, -9.81);
        for _ in 0..1000 {
            b.fcm = [0.0, 0.0, b.mass * g];
            b.initial_integrate(dt);
            b.fcm = [0.0, 0.0, b.mass * g];
            b.final_integrate(dt);
        }
        let t = 1000.0 * dt;
        assert!((b.vcm[2] - g * t).abs() < 1e-12);
        assert!((b.xcm[2] - 0.5 * g * t * t).abs() < 1e-10);
        assert!((b.xcm[0] - 0.5 * t).abs() < 1e-12);
        assert_eq!(b.quat, [1.0, 0.0, 0.0, 0.0]);
    }

    #[test]
    fn torque_free_tumbling_conserves_angular_momentum_and_energy() {
        let moments = [1.0, 2.0, 3.0];
        let mut b = body([0.3, 2.0, 0.1], moments);
        let l0 = b.angmom;
        let energy = |b: &Body| {
            let wb = [0, 1, 2].map(|k| {
                let a = &b.axes[k];
                b.omega[0] * a[0] + b.omega[1] * a[1] + b.omega[2] * a[2]
            });
            0.5 * (0..3).map(|k| moments[k] * wb[k] * wb[k]).sum::<f64>()
        };
        let e0 = energy(&b);
        for _ in 0..20000 {
            b.initial_integrate(1e-4);
            b.final_integrate(1e-4);
        }
        // no torque: the space-frame angular momentum is never changed
        assert_eq!(b.angmom, l0);
        assert!(((energy(&b) - e0) / e0).abs() < 1e-6, "{} {e0}", energy(&b));
        let q = b.quat;
        assert!(((q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) - 1.0).abs() < 1e-14);
        // the body has turned (rotation about the intermediate axis is unstable)
        assert!(b.axes[1][1] < 0.99);
    }

    #[test]
    fn member_forces_sum_to_force_and_torque() {
        let mut b = body([0.0; 3], [1.0, 1.0, 1.0]);
        b.add_member_force(&[1.0, 0.0, 0.0], &[0.0, 2.0, 0.0], &[0.0, 0.0, 0.5]);
        b.add_member_force(&[-1.0, 0.0, 0.0], &[0.0, 2.0, 0.0], &[0.0; 3]);
        assert_eq!(b.fcm, [0.0, 4.0, 0.0]);
        assert_eq!(b.torque, [0.0, 0.0, 0.5]);
    }

    #[test]
    fn axes_and_quaternions_convert_both_ways() {
        let mut q = [0.9, 0.1, -0.3, 0.2];
        normalize(&mut q);
        let a = quat_to_axes(&q);
        let back = axes_to_quat(&a[0], &a[1], &a[2]);
        for k in 0..4 {
            assert!((back[k] - q[k]).abs() < 1e-14);
        }
    }
}
