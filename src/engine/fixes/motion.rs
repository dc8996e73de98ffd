//! `fix move`: prescribed motion of a group of particles (linear, wiggle, rotate, or from
//! variables), the free components integrated.

use std::collections::HashMap;

use super::{FixStep, FixStyle, ForceValue, PerAtomShape};
use crate::engine::domain::Domain;
use crate::engine::particles::Particles;
use crate::engine::restart_fixes::to_bytes;

/// Prescribed motion of `fix move` (length and time units).
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// `linear vx vy vz`: constant velocity; None components are integrated freely.
    Linear([Option<f64>; 3]),
    /// `wiggle Ax Ay Az period`: x = x0 + A sin(2 pi t / period).
    Wiggle {
        /// Amplitudes (length); None components are integrated.
        amplitude: [Option<f64>; 3],
        /// 2 pi / period (1/time).
        omega: f64,
    },
    /// `rotate Px Py Pz Rx Ry Rz period`: rotation about the axis through P along R.
    Rotate {
        /// A point on the axis (length).
        point: [f64; 3],
        /// Unit vector along the axis.
        axis: [f64; 3],
        /// 2 pi / period (1/time).
        omega: f64,
    },
    /// `variable dx dy dz vx vy vz`: displacements from the start position and velocities
    /// from equal- or atom-style variables (NULL: not given).
    Variable {
        /// Displacement variables (length).
        displace: [ForceValue; 3],
        /// Velocity variables (length/time).
        velocity: [ForceValue; 3],
    },
}

/// A `fix move`: the motion, where each atom started (unwrapped) and the start step.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// The motion.
    pub motion: Motion,
    /// Unwrapped start positions by atom ID.
    pub origin: HashMap<i64, [f64; 3]>,
    /// The step the fix was defined at (its time origin).
    pub start_step: i64,
    /// `move variable`: this step's displacement and velocity values per local atom.
    pub resolved: Vec<[Option<f64>; 6]>,
}

impl Move {
    /// Record the current unwrapped positions of the group's atoms as the origin.
    pub fn new(motion: Motion, p: &Particles, group: u32, domain: &Domain, step: i64) -> Move {
        let mut origin = HashMap::new();
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                let mut x = p.x[i];
                for (d, xd) in x.iter_mut().enumerate() {
                    *xd += p.image[i][d] as f64 * domain.length(d);
                }
                origin.insert(p.id[i], x);
            }
        }
        Move {
            motion,
            origin,
            start_step: step,
            resolved: Vec::new(),
        }
    }

    /// Which components the motion prescribes (the rest are integrated).
    fn prescribed(&self) -> [bool; 3] {
        match &self.motion {
            Motion::Linear(v) => v.map(|c| c.is_some()),
            Motion::Wiggle { amplitude, .. } => amplitude.map(|c| c.is_some()),
            Motion::Rotate { .. } => [true; 3],
            Motion::Variable { displace, velocity } => {
                [0, 1, 2].map(|d| !displace[d].is_null() || !velocity[d].is_null())
            }
        }
    }

    /// `move variable`: x = x0 + dx where dx is given, v = vx where vx is given (with no dx,
    /// x advances by dt vx); components with neither are integrated (LIGGGHTS's order).
    fn variable_integrate(&self, p: &mut Particles, group: u32, dt: f64, domain: &Domain) {
        let dtf = 0.5 * dt;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let xold = p.x[i];
            let x0 = self.origin.get(&p.id[i]).copied().unwrap_or([0.0; 3]);
            let r = self.resolved.get(i).copied().unwrap_or([None; 6]);
            for d in 0..3 {
                match (r[d], r[3 + d]) {
                    (Some(dx), Some(v)) => {
                        p.v[i][d] = v;
                        p.x[i][d] = x0[d] + dx;
                    }
                    (Some(dx), None) => p.x[i][d] = x0[d] + dx,
                    (None, Some(v)) => {
                        p.v[i][d] = v;
                        p.x[i][d] += dt * p.v[i][d];
                    }
                    (None, None) => {
                        p.v[i][d] += dtf / p.mass[i] * p.f[i][d];
                        p.x[i][d] += dt * p.v[i][d];
                    }
                }
            }
            domain.remap_near(&mut p.x[i], &xold);
        }
    }

    /// Prescribe (or integrate) the group's positions and velocities for `step`; positions
    /// set from the unwrapped start point are brought back to the image nearest the old
    /// position, as LIGGGHTS's `remap_near` does.
    fn prescribe(&self, p: &mut Particles, group: u32, step: i64, dt: f64, domain: &Domain) {
        if matches!(self.motion, Motion::Variable { .. }) {
            return self.variable_integrate(p, group, dt, domain);
        }
        let delta = (step - self.start_step) as f64 * dt;
        let dtf = 0.5 * dt;
        if let Motion::Rotate {
            point,
            axis: r,
            omega,
        } = self.motion
        {
            // X = P + C + A cos(wt) + B sin(wt), V = w R x (A cos(wt) + B sin(wt))
            let arg = omega * delta;
            let (sine, cosine) = (arg.sin(), arg.cos());
            for i in 0..p.len() {
                if p.mask[i] & group == 0 {
                    continue;
                }
                let xold = p.x[i];
                let x0 = self.origin.get(&p.id[i]).copied().unwrap_or([0.0; 3]);
                let d = [x0[0] - point[0], x0[1] - point[1], x0[2] - point[2]];
                let ddotr = d[0] * r[0] + d[1] * r[1] + d[2] * r[2];
                let c = [ddotr * r[0], ddotr * r[1], ddotr * r[2]];
                let a = [d[0] - c[0], d[1] - c[1], d[2] - c[2]];
                let b = [
                    r[1] * a[2] - r[2] * a[1],
                    r[2] * a[0] - r[0] * a[2],
                    r[0] * a[1] - r[1] * a[0],
                ];
                let disp = [
                    a[0] * cosine + b[0] * sine,
                    a[1] * cosine + b[1] * sine,
                    a[2] * cosine + b[2] * sine,
                ];
                for k in 0..3 {
                    p.x[i][k] = point[k] + c[k] + disp[k];
                }
                p.v[i] = [
                    omega * (r[1] * disp[2] - r[2] * disp[1]),
                    omega * (r[2] * disp[0] - r[0] * disp[2]),
                    omega * (r[0] * disp[1] - r[1] * disp[0]),
                ];
                p.omega[i] = [omega * r[0], omega * r[1], omega * r[2]];
                domain.remap_near(&mut p.x[i], &xold);
            }
            return;
        }
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let xold = p.x[i];
            let x0 = self.origin.get(&p.id[i]).copied().unwrap_or([0.0; 3]);
            for d in 0..3 {
                let set = match &self.motion {
                    Motion::Linear(v) => v[d].map(|vd| (vd, x0[d] + vd * delta)),
                    Motion::Wiggle { amplitude, omega } => amplitude[d].map(|a| {
                        let arg = omega * delta;
                        (a * omega * arg.cos(), x0[d] + a * arg.sin())
                    }),
                    Motion::Rotate { .. } | Motion::Variable { .. } => {
                        unreachable!("handled above")
                    }
                };
                match set {
                    Some((v, x)) => {
                        p.v[i][d] = v;
                        p.x[i][d] = x;
                    }
                    None => {
                        let dtfm = dtf / p.mass[i];
                        p.v[i][d] += dtfm * p.f[i][d];
                        p.x[i][d] += dt * p.v[i][d];
                    }
                }
            }
            domain.remap_near(&mut p.x[i], &xold);
        }
    }

    fn integrate_free(&self, p: &mut Particles, group: u32, dt: f64) {
        let free = self.prescribed().map(|s| !s);
        let dtf = 0.5 * dt;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            for (d, &free) in free.iter().enumerate() {
                if free {
                    let dtfm = dtf / p.mass[i];
                    p.v[i][d] += dtfm * p.f[i][d];
                }
            }
        }
    }
}

impl FixStyle for Move {
    fn name(&self) -> &str {
        "move"
    }

    fn initial_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        self.prescribe(p, at.group, at.step, at.dt, at.domain);
    }

    fn final_integrate(&mut self, p: &mut Particles, at: &FixStep) {
        self.integrate_free(p, at.group, at.dt);
    }

    /// `move variable` evaluates its variables every step.
    fn reads_computes(&self) -> bool {
        matches!(self.motion, Motion::Variable { .. })
    }

    /// Each atom's unwrapped start position (length; 0 for atoms not in the group then).
    fn per_atom_shape(&self) -> PerAtomShape {
        PerAtomShape::Array(3)
    }

    fn per_atom(&self, p: &Particles) -> Vec<f64> {
        let mut values = Vec::with_capacity(3 * p.len());
        for id in &p.id {
            values.extend(self.origin.get(id).copied().unwrap_or([0.0; 3]));
        }
        values
    }

    /// The time origin (the start step).
    fn restart_state(&self) -> Option<Vec<u8>> {
        Some(to_bytes(&[self.start_step as f64]))
    }

    /// Each atom's start position (LIGGGHTS's `xoriginal`), three values and the count.
    fn restart_per_atom(&self, p: &Particles) -> Option<(i32, Vec<Vec<f64>>)> {
        let rows =
            p.id.iter()
                .map(|id| self.origin.get(id).map_or(vec![0.0; 3], |x| x.to_vec()))
                .collect();
        Some((4, rows))
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn refuses_thermo(&self) -> bool {
        true
    }
}
