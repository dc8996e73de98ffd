//! `fix mesh/surface/stress`: forces, stresses and Finnie wear on a mesh's triangles, as
//! LIGGGHTS 3.8.0's stress module keeps them (docs/notes/mesh_output.md, section 1).
//!
//! Each mesh wall contact adds the force on the wall (minus the force the contact put on the
//! particle) to its triangle and to the mesh's total force and torque; with `wear finnie`
//! it adds the Finnie wear increment. At the end of a step the wear of the step is added to
//! the accumulated wear, and the normal and shear stresses are formed from the triangle
//! forces. Forces and step wear are cleared before each step's forces (and at a run's setup).

type V3 = [f64; 3];

/// One contact's contribution, recorded by the mesh wall force loop.
#[derive(Debug, Clone, Copy)]
pub struct StressContact {
    /// Triangle index.
    pub tri: u32,
    /// Particle index.
    pub particle: usize,
    /// Force the contact put on the particle, as a difference of accumulated sums (force).
    pub force: V3,
    /// From the particle centre to the closest point of the triangle (length).
    pub to_wall: V3,
    /// Wall velocity at the contact (length/time).
    pub v_wall: V3,
}

/// The stress module of one mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshStress {
    /// `stress on|off`: track forces and stresses.
    pub stress: bool,
    /// `wear finnie`: track Finnie wear.
    pub wear_on: bool,
    /// `reference_point` for the total torque (length).
    pub reference: V3,
    /// Force on each triangle this step (force).
    pub f: Vec<V3>,
    /// Normal stress of each triangle at the end of the last step (force/area).
    pub sigma_n: Vec<f64>,
    /// Shear stress of each triangle at the end of the last step (force/area).
    pub sigma_t: Vec<f64>,
    /// Accumulated wear of each triangle (with k = 1: energy/area).
    pub wear: Vec<f64>,
    /// Wear of the running step.
    pub wear_step: Vec<f64>,
    /// Total force on the mesh this step (force).
    pub f_total: V3,
    /// Total torque about the reference point this step (force·length).
    pub torque_total: V3,
    /// `k_finnie` per (mesh type, particle type), 0-based, from `property/global`.
    pub k_finnie: Vec<Vec<f64>>,
    /// The totals of the previous step (force, torque), read until this step's are complete.
    pub old_totals: (V3, V3),
    /// This step's totals are complete (set at the end of a step, cleared before forces).
    pub updated: bool,
    /// Neighbour bin (z, y, x) of each particle at the last list build, shared by every
    /// stress mesh: LIGGGHTS lists a triangle's particles bin by bin (x outermost) and sums
    /// the forces and wear on the mesh in that order.
    pub bins: std::sync::Arc<Vec<[i64; 3]>>,
}

impl MeshStress {
    /// The module for a mesh of `n` triangles.
    pub fn new(n: usize, stress: bool, wear_on: bool, reference: V3) -> MeshStress {
        MeshStress {
            stress,
            wear_on,
            reference,
            f: vec![[0.0; 3]; n],
            sigma_n: vec![0.0; n],
            sigma_t: vec![0.0; n],
            wear: vec![0.0; n],
            wear_step: vec![0.0; n],
            f_total: [0.0; 3],
            torque_total: [0.0; 3],
            k_finnie: Vec::new(),
            old_totals: ([0.0; 3], [0.0; 3]),
            updated: false,
            bins: Default::default(),
        }
    }

    /// Before a step's forces: clear triangle forces, step wear and the totals.
    pub fn pre_force(&mut self) {
        self.clear_triangles();
        if self.stress {
            self.old_totals = (self.f_total, self.torque_total);
            self.f_total = [0.0; 3];
            self.torque_total = [0.0; 3];
            self.updated = false;
        }
    }

    /// `f_ID[i]`, i = 1..9: total force on the mesh, torque about the reference point, the
    /// reference point (LIGGGHTS returns the previous step's totals until this step's are
    /// complete, and 0 with `stress off`).
    pub fn value(&self, i: usize) -> Option<f64> {
        let (f, t) = if self.updated {
            (self.f_total, self.torque_total)
        } else {
            self.old_totals
        };
        match i {
            1..=3 => Some(f[i - 1]),
            4..=6 => Some(t[i - 4]),
            7..=9 => Some(self.reference[i - 7]),
            _ => None,
        }
    }

    /// At a run's setup: clear triangle forces and step wear (the totals keep adding).
    pub fn clear_triangles(&mut self) {
        self.f.iter_mut().for_each(|f| *f = [0.0; 3]);
        self.wear_step.iter_mut().for_each(|w| *w = 0.0);
    }

    /// Add one contact: `x`, `v` the particle's position and (half-step) velocity,
    /// `normal` and `area` the triangle's, `mesh_type` and `particle_type` 1-based.
    #[allow(clippy::too_many_arguments)]
    pub fn add(
        &mut self,
        c: &StressContact,
        x: V3,
        v: V3,
        normal: V3,
        area: f64,
        mesh_type: usize,
        particle_type: usize,
        dt: f64,
    ) {
        let t = c.tri as usize;
        let w = c.force.map(|f| -f);
        let point = [
            x[0] + c.to_wall[0],
            x[1] + c.to_wall[1],
            x[2] + c.to_wall[2],
        ];
        if self.stress {
            self.f[t] = [
                self.f[t][0] + w[0],
                self.f[t][1] + w[1],
                self.f[t][2] + w[2],
            ];
            self.f_total = [
                self.f_total[0] + w[0],
                self.f_total[1] + w[1],
                self.f_total[2] + w[2],
            ];
            let r = [
                point[0] - self.reference[0],
                point[1] - self.reference[1],
                point[2] - self.reference[2],
            ];
            let tq = cross(r, w);
            self.torque_total = [
                self.torque_total[0] + tq[0],
                self.torque_total[1] + tq[1],
                self.torque_total[2] + tq[2],
            ];
        }
        if !self.wear_on {
            return;
        }
        let d = [point[0] - x[0], point[1] - x[1], point[2] - x[2]];
        let v_rel = [v[0] - c.v_wall[0], v[1] - c.v_wall[1], v[2] - c.v_wall[2]];
        if dot(d, v_rel) < 0.0 {
            return;
        }
        let v_mag = mag(v_rel);
        if 0.0000001 > v_mag {
            return;
        }
        let sin_g = (dot(v_rel, normal).abs() / v_mag).min(1.0);
        let cos_g = (mag(cross(v_rel, normal)).abs() / v_mag).min(1.0);
        let mut e = if cos_g < 1e-4 || 3. * sin_g > cos_g {
            0.33333 * cos_g * cos_g
        } else {
            2. * sin_g * cos_g - 3. * sin_g * sin_g
        };
        let k = self
            .k_finnie
            .get(mesh_type - 1)
            .and_then(|row| row.get(particle_type - 1))
            .copied()
            .unwrap_or(0.0);
        e *= 2. * k * v_mag * mag(w);
        self.wear_step[t] += e * dt / area;
    }

    /// The first triangle whose accumulated wear or stress is not finite (an overflow, as
    /// from a `k_finnie` of 1e308), if any.
    pub fn first_non_finite(&self) -> Option<usize> {
        (0..self.wear.len()).find(|&t| {
            !(self.wear[t].is_finite()
                && self.sigma_n.get(t).is_none_or(|s| s.is_finite())
                && self.sigma_t.get(t).is_none_or(|s| s.is_finite()))
        })
    }

    /// End of a step: add the step's wear, and form the stresses from the triangle forces
    /// (`normals` unit, `areas` in length²).
    pub fn end_of_step(&mut self, normals: &[V3], areas: &[f64]) {
        if self.wear_on {
            for (w, s) in self.wear.iter_mut().zip(self.wear_step.iter_mut()) {
                *w += *s;
                *s = 0.0;
            }
        }
        if self.stress {
            self.updated = true;
            for t in 0..self.f.len() {
                let n = normals[t];
                let inv = 1. / areas[t];
                let sn = dot(self.f[t], n);
                let tang = [
                    self.f[t][0] - n[0] * sn,
                    self.f[t][1] - n[1] * sn,
                    self.f[t][2] - n[2] * sn,
                ];
                // abs as "negate if negative": a -0 stays -0
                let abs = |x: f64| if x < 0.0 { -x } else { x };
                self.sigma_n[t] = abs(sn) * inv;
                self.sigma_t[t] = abs(mag(tang)) * inv;
            }
        }
    }
}

#[inline]
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
fn mag(a: V3) -> f64 {
    dot(a, a).sqrt()
}
