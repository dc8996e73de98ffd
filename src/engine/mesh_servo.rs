//! `fix mesh/surface/stress/servo`: a mesh wall driven along an axis by a controller until
//! the force on it reaches a target, as LIGGGHTS 3.8.0's servo mesh module does it.
//!
//! Each step (`initial_integrate`) the centre of mass moves by `dt vcm` and the nodes are
//! placed at their positions at the run's setup plus the total displacement since then;
//! the stress module's reference point follows the centre. After the forces
//! (`final_integrate`, once the stress module has summed the total force) the controller
//! sets the velocity of the next step: a PID controller on the force along the axis, or
//! with `mode auto` a proportional controller whose gain depends on the error and on
//! whether particles are near the mesh. The velocity is limited to `vel_max` (and the
//! integral term reset when it is, the "anti-wind-up"); every node moves with it.

use crate::engine::mesh::TriMesh;

type V3 = [f64; 3];

/// LIGGGHTS's smallest radius when there are no particles (length).
const NO_PARTICLES_RADIUS: f64 = 1_000_000.;

/// The controller of one servo mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshServo {
    /// Centre of mass (length); the stress module's reference point.
    pub xcm: V3,
    /// Centre of mass at the run's setup (length).
    pub xcm_orig: V3,
    /// Velocity of the mesh (length/time): the controller's output.
    pub vcm: V3,
    /// Unit direction of the controlled motion (zero if `axis` was not given).
    pub axis: V3,
    /// Set point: minus `target_val` (force), as LIGGGHTS keeps it (0 without one).
    pub set_point: f64,
    /// `target_val v_name`: the equal-style variable giving the target force (force),
    /// evaluated at each step's controller.
    pub set_point_var: Option<String>,
    /// `vel_max` (length/time).
    pub vel_max: f64,
    /// `kp`, `ki`, `kd`.
    pub gains: [f64; 3],
    /// `mode auto`: the gain-scheduled proportional controller.
    pub auto: bool,
    /// `ratio`: the auto mode's speed near particles, in smallest radii per step.
    pub ratio: f64,
    /// Whether the mesh moves (`fix_modify servo/integrate start|stop`).
    pub integrate: bool,
    /// The auto mode's speed near particles, `ratio r_min / dt`, set at each run's setup
    /// (length/time).
    pub vel_min: f64,
    /// Error of the last step (force, or relative in auto mode).
    pub err: f64,
    /// Time integral of the error (force time).
    pub sum_err: f64,
    /// Force along the axis at the last step (force).
    pub old_pv: f64,
    /// Nodes at the run's setup (length).
    pub nodes_orig: Vec<[V3; 3]>,
}

impl MeshServo {
    /// A servo at rest at `com` moving along `axis` (normalised here as LIGGGHTS does).
    pub fn new(com: V3, axis: V3, target: f64, vel_max: f64) -> MeshServo {
        let norm = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
        let inv = if norm == 0. { 0. } else { 1. / norm };
        MeshServo {
            xcm: com,
            xcm_orig: com,
            vcm: [0.0; 3],
            axis: [axis[0] * inv, axis[1] * inv, axis[2] * inv],
            set_point: -target,
            set_point_var: None,
            vel_max,
            gains: [0.01, 0., 0.],
            auto: false,
            ratio: 0.,
            integrate: true,
            vel_min: 0.,
            err: 0.,
            sum_err: 0.,
            old_pv: 0.,
            nodes_orig: Vec::new(),
        }
    }

    /// A run's setup: the current nodes and centre become the origin of the displacement;
    /// the auto mode's speed near particles from the smallest particle radius (`None`: no
    /// particles) and the time step.
    pub fn setup(&mut self, mesh: &TriMesh, r_min: Option<f64>, dt: f64) {
        self.xcm_orig = self.xcm;
        self.nodes_orig = mesh.nodes.clone();
        self.vel_min = self.ratio * r_min.unwrap_or(NO_PARTICLES_RADIUS) / dt;
    }

    /// Move the centre by `dt vcm` and place the nodes at their setup positions plus the
    /// displacement since the setup (centroids as LIGGGHTS sums them).
    pub fn initial_integrate(&mut self, mesh: &mut TriMesh, dt: f64) {
        if !self.integrate {
            return;
        }
        for k in 0..3 {
            self.xcm[k] += dt * self.vcm[k];
        }
        let total = [
            self.xcm[0] - self.xcm_orig[0],
            self.xcm[1] - self.xcm_orig[1],
            self.xcm[2] - self.xcm_orig[2],
        ];
        if self.nodes_orig.len() != mesh.nodes.len() {
            self.nodes_orig = mesh.nodes.clone();
        }
        for (t, orig) in self.nodes_orig.iter().enumerate() {
            let mut c = [0.0; 3];
            for (j, o) in orig.iter().enumerate() {
                let node = [o[0] + total[0], o[1] + total[1], o[2] + total[2]];
                mesh.nodes[t][j] = node;
                c = [node[0] + c[0], node[1] + c[1], node[2] + c[2]];
            }
            let inv = 1. / 3.;
            mesh.center[t] = [inv * c[0], inv * c[1], inv * c[2]];
        }
    }

    /// The controller after the forces: the next step's velocity from the total force on
    /// the mesh `f_total` (force) and whether particles are near it (`near`: entries in
    /// the mesh's contact lists).
    pub fn final_integrate(&mut self, f_total: V3, near: usize, dt: f64) {
        if !self.integrate {
            return;
        }
        let a = self.axis;
        let pv = f_total[0] * a[0] + f_total[1] * a[1] + f_total[2] * a[2];
        // a set point of 0 (no target_val) leaves the inverse at 0: the mesh stays
        let sp_inv = if self.set_point == 0. {
            0.
        } else {
            1. / self.set_point.abs()
        };
        let [kp, ki, kd] = self.gains;
        if self.auto {
            self.err = (self.set_point - pv) * sp_inv;
            let (err_low, err_high, scale) = (0.9, 1.0, 0.1);
            let e = self.err.abs();
            let gain = if near == 0 {
                self.vel_max
            } else if e <= err_low {
                scale * self.vel_min
            } else if e >= err_high {
                self.vel_min
            } else {
                scale * self.vel_min
                    + ((1. - scale) * self.vel_min) * (e - err_low) / (err_high - err_low)
            };
            let s = -gain * self.err;
            self.vcm = [s * a[0], s * a[1], s * a[2]];
        } else {
            self.err = self.set_point - pv;
            self.sum_err += self.err * dt;
            let dfdt = -(pv - self.old_pv) / dt;
            let s = -self.vel_max * (self.err * kp + self.sum_err * ki + dfdt * kd) * sp_inv;
            self.vcm = [s * a[0], s * a[1], s * a[2]];
            self.old_pv = pv;
        }
        self.limit(near);
    }

    /// Saturate the velocity at `vel_max` (auto mode near particles: its slow speed); on
    /// saturation with an integral term, reset the error integral to the value that gives
    /// the limit (LIGGGHTS's anti-wind-up).
    fn limit(&mut self, near: usize) {
        let v = self.vcm;
        let mag = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let max = if self.auto && near > 0 {
            self.vel_min
        } else {
            self.vel_max
        };
        if mag > max && mag != 0. {
            let factor = max / mag;
            self.vcm = [factor * v[0], factor * v[1], factor * v[2]];
            let [kp, ki, _] = self.gains;
            if ki > 0. {
                let a = self.axis;
                let out = self.vcm[0] * a[0] + self.vcm[1] * a[1] + self.vcm[2] * a[2];
                let sign = f64::from(i8::from(0. < out) - i8::from(out < 0.));
                self.sum_err = (-sign * self.set_point - self.err * kp) / ki;
            }
        }
    }

    /// `f_ID[10..12]` of the mesh fix: the centre of mass (length).
    pub fn value(&self, i: usize) -> Option<f64> {
        (10..=12).contains(&i).then(|| self.xcm[i - 10])
    }
}

/// Put the contacts of one stress mesh in the order LIGGGHTS's wall loop meets them:
/// triangle by triangle, each triangle's particles by neighbour bin (x, then y, then z) and
/// index (`bins`: each particle's bin as (z, y, x)).
pub fn order_contacts(
    contacts: &mut [crate::engine::mesh_stress::StressContact],
    bins: &[[i64; 3]],
) {
    contacts.sort_by_key(|c| {
        let b = bins.get(c.particle).copied().unwrap_or([0; 3]);
        (c.tri, b[2], b[1], b[0], c.particle)
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saturates_at_vel_max_and_moves_the_nodes_by_the_total_displacement() {
        let tri = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
        let mut mesh = TriMesh::new(&[tri], Default::default());
        let mut s = MeshServo::new([0.0, 0.0, 1.0], [0.0, 0.0, 2.0], -10.0, 0.5);
        s.gains = [5.0, 0.0, 0.0];
        s.setup(&mesh, Some(0.001), 1e-3);
        // no force yet: full speed towards -z
        s.final_integrate([0.0; 3], 0, 1e-3);
        assert_eq!(s.vcm, [0.0, 0.0, -0.5]);
        s.initial_integrate(&mut mesh, 1e-3);
        assert_eq!(s.xcm[2], 1.0 - 0.5e-3);
        assert_eq!(mesh.nodes[0][1], [1.0, 0.0, 1.0 - 0.5e-3]);
        // a force past the target reverses the motion, proportionally below saturation
        s.final_integrate([0.0, 0.0, 10.2], 1, 1e-3);
        assert!((s.vcm[2] - 0.5 * 5.0 * 0.2 / 10.0).abs() < 1e-15);
        assert_eq!(s.value(12), Some(s.xcm[2]));
    }

    #[test]
    fn anti_windup_resets_the_integral_when_saturated() {
        let mut s = MeshServo::new([0.0; 3], [0.0, 0.0, 1.0], -1.0, 0.1);
        s.gains = [1.0, 100.0, 0.0];
        s.final_integrate([0.0; 3], 0, 1e-3);
        assert_eq!(s.vcm[2], -0.1);
        // sum_err so that kp err + ki sum_err gives the set point: -(-1) - 1 = 0
        assert_eq!(s.sum_err, 0.0);
    }
}
