//! `fix multisphere`: the rigid clumps of a run, as LIGGGHTS 3.8.0 holds and moves them.
//! Each member sphere is an ordinary particle carrying its body's tag (the dump's `mol`) and
//! its body-frame offset in two per-particle arrays; the bodies hold mass, principal
//! moments, centre of mass, orientation, velocity and angular momentum. Per step: the body
//! is integrated in `initial_integrate` and its members placed (`set_xv`); the body sums are
//! zeroed before the forces; in `final_integrate` the members' forces and torques are summed
//! to the body, the body's weight added, the body kicked and its members' velocities set
//! (`set_v`). The operations follow LIGGGHTS's order so that the arithmetic agrees to the bit.

use crate::engine::domain::Domain;
use crate::engine::error::EngineError;
use crate::engine::multisphere::ClumpTemplate;
use crate::engine::particles::Particles;
use crate::engine::rigid_body::{Body, Vec3};
pub use crate::state::bodies::{body_array, body_tags, is_member, BODY_ARRAY};

/// Name of the per-particle array holding the body-frame offset (length).
pub const DISPLACE_ARRAY: &str = "multisphere_displace";

/// The state of `fix multisphere`: its bodies in creation order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Clumps {
    /// The bodies.
    pub bodies: Vec<Body>,
    /// Member spheres per body.
    pub nrigid: Vec<usize>,
    /// Bounding-sphere radius per body (length).
    pub r_bound: Vec<f64>,
    /// Centre of the bounding sphere per body, from the centre of mass in body coordinates
    /// (length).
    pub xb_body: Vec<Vec3>,
    /// Largest body tag ever given (tags are never reused).
    pub max_tag: i64,
    /// The step being integrated and whether the deck has a `fix insert/stream` (set in
    /// `initial_integrate`, used in `final_integrate`).
    pub stepping: (i64, bool),
}

/// The two per-particle arrays (body tag, offset), created on first use: particles that
/// exist already, and ones added later by other means, get the tag -1.
fn arrays(p: &mut Particles) -> (usize, usize) {
    let b = match body_array(p) {
        Some(b) => b,
        None => {
            let b = p.extra_index(BODY_ARRAY, 1);
            p.extra[b].data.fill(-1.0);
            p.extra[b].fill = vec![-1.0];
            b
        }
    };
    let d = p.extra_index(DISPLACE_ARRAY, 3);
    (b, d)
}

impl Clumps {
    /// The index of the body with `tag`.
    fn index(&self, tag: f64) -> Option<usize> {
        if tag < 0.0 {
            return None;
        }
        let t = tag as i64;
        // tags are given in increasing order, so a binary search finds them
        self.bodies.binary_search_by_key(&t, |b| b.tag).ok()
    }

    /// Translational kinetic energy of all bodies, 0.5 sum m vcm^2 (energy).
    pub fn kinetic_energy(&self) -> f64 {
        let mut ke = 0.0;
        for b in &self.bodies {
            let v = b.vcm;
            ke += b.mass * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        }
        0.5 * ke
    }

    /// Inserts one clump of template `t` with its centre of mass at `xcm`, principal axes
    /// `axes` (the template's if None), velocity `v` (length/time) and angular velocity
    /// `omega` (1/time): one
    /// particle per sphere with IDs from `first_id`, type and density of the template and
    /// the body's mass, in group `group` (bits, besides `all`). The members are placed from
    /// the body as LIGGGHTS's `add_body_finalize` does.
    #[allow(clippy::too_many_arguments)]
    pub fn insert(
        &mut self,
        p: &mut Particles,
        t: &ClumpTemplate,
        axes: Option<[Vec3; 3]>,
        first_id: i64,
        xcm: Vec3,
        v: Vec3,
        omega: Vec3,
        group: u32,
        domain: &Domain,
    ) {
        let (ba, da) = arrays(p);
        self.max_tag += 1;
        let tag = self.max_tag;
        let body = Body::new(
            tag,
            t.mass,
            t.density,
            t.principal,
            xcm,
            v,
            omega,
            axes.unwrap_or(t.axes),
            t.spec.fflag,
            t.spec.tflag,
        );
        for (j, (d, &r)) in t.displace.iter().zip(&t.radii).enumerate() {
            let off = body.offset(d);
            let x = [xcm[0] + off[0], xcm[1] + off[1], xcm[2] + off[2]];
            p.push(first_id + j as i64, t.spec.atom_type, x, r, t.density);
            let i = p.len() - 1;
            p.mass[i] = t.mass;
            p.mask[i] |= group;
            p.extra[ba].data[i] = tag as f64;
            p.extra[da].data[3 * i..3 * i + 3].copy_from_slice(d);
        }
        self.bodies.push(body);
        self.nrigid.push(t.displace.len());
        self.r_bound.push(t.r_bound);
        self.xb_body.push(t.x_bound_body);
        let start = p.len() - t.displace.len();
        self.set_xv(p, domain, start);
    }

    /// Members' positions, velocities and angular velocities from their bodies (particles
    /// from `start` on): x = xcm + axes displace (in the atom's periodic image), v = vcm +
    /// omega x (axes displace).
    pub fn set_xv(&self, p: &mut Particles, domain: &Domain, start: usize) {
        let (Some(ba), Some(da)) = (
            body_array(p),
            p.extra.iter().position(|e| e.name == DISPLACE_ARRAY),
        ) else {
            return;
        };
        let len = [0, 1, 2].map(|d| domain.length(d));
        for i in start..p.len() {
            let Some(k) = self.index(p.extra[ba].data[i]) else {
                continue;
            };
            let b = &self.bodies[k];
            let e = &p.extra[da].data[3 * i..3 * i + 3];
            let d = b.offset(&[e[0], e[1], e[2]]);
            p.v[i] = b.velocity_at(&d);
            for c in 0..3 {
                p.x[i][c] = d[c] + (b.xcm[c] - p.image[i][c] as f64 * len[c]);
            }
            p.omega[i] = b.omega;
        }
    }

    /// Members' velocities and angular velocities from their bodies.
    pub fn set_v(&self, p: &mut Particles) {
        let (Some(ba), Some(da)) = (
            body_array(p),
            p.extra.iter().position(|e| e.name == DISPLACE_ARRAY),
        ) else {
            return;
        };
        for i in 0..p.len() {
            let Some(k) = self.index(p.extra[ba].data[i]) else {
                continue;
            };
            let b = &self.bodies[k];
            let e = &p.extra[da].data[3 * i..3 * i + 3];
            let d = b.offset(&[e[0], e[1], e[2]]);
            p.v[i] = b.velocity_at(&d);
            p.omega[i] = b.omega;
        }
    }

    /// `initial_integrate`: kick, drift and rotate every body, then place its members.
    /// Bodies still on their way from an insertion face (before their release step, with
    /// a `fix insert/stream` in the deck) only move at the stream velocity.
    pub fn initial_integrate(
        &mut self,
        p: &mut Particles,
        dt: f64,
        domain: &Domain,
        step: i64,
        has_stream: bool,
    ) {
        self.stepping = (step, has_stream);
        for b in &mut self.bodies {
            if b.streaming(step, has_stream) {
                b.stream_step(dt);
            } else {
                b.initial_integrate(dt);
            }
        }
        self.set_xv(p, domain, 0);
    }

    /// `pre_force`: zero the bodies' force and torque sums.
    pub fn reset_forces(&mut self) {
        for b in &mut self.bodies {
            b.fcm = [0.0; 3];
            b.torque = [0.0; 3];
        }
    }

    /// `calc_force`: add every member's force and torque (about the centre of mass, from
    /// its unwrapped position) to its body, then the body's weight `mass * gravity`.
    pub fn calc_force(&mut self, p: &Particles, domain: &Domain, gravity: Option<Vec3>) {
        if let Some(ba) = body_array(p) {
            let len = [0, 1, 2].map(|d| domain.length(d));
            for i in 0..p.len() {
                let Some(k) = self.index(p.extra[ba].data[i]) else {
                    continue;
                };
                let b = &mut self.bodies[k];
                let u = [0, 1, 2].map(|c| p.x[i][c] + p.image[i][c] as f64 * len[c]);
                let d = [u[0] - b.xcm[0], u[1] - b.xcm[1], u[2] - b.xcm[2]];
                b.add_member_force(&d, &p.f[i], &p.torque[i]);
            }
        }
        if let Some(g) = gravity {
            for b in &mut self.bodies {
                for (f, a) in b.fcm.iter_mut().zip(g) {
                    *f += b.mass * a;
                }
            }
        }
    }

    /// `final_integrate` after `calc_force`: kick every body, then set its members'
    /// velocities.
    pub fn final_integrate(&mut self, p: &mut Particles, dt: f64) {
        let (step, has_stream) = self.stepping;
        for b in &mut self.bodies {
            if !b.streaming(step, has_stream) {
                b.final_integrate(dt);
            }
        }
        self.set_v(p);
    }

    /// LIGGGHTS's `calc_n_steps` for a member of body `tag` inserted by `fix insert/stream`
    /// at `step`: the steps until the body's centre of mass crosses the face (reference
    /// point `p_ref`, unit normal `normal`, velocity `v_normal` in length/time, time step
    /// `dt`), fixed at the first member asked; None outside a body.
    pub fn stream_steps(
        &mut self,
        tag: f64,
        step: i64,
        dt: f64,
        p_ref: Vec3,
        normal: Vec3,
        v_normal: Vec3,
    ) -> Option<i64> {
        let k = self.index(tag)?;
        let b = &mut self.bodies[k];
        if b.start_step >= 0 {
            return Some(b.start_step - step);
        }
        let rel = [0, 1, 2].map(|k| p_ref[k] - b.xcm[k]);
        let dist = rel[0] * normal[0] + rel[1] * normal[1] + rel[2] * normal[2];
        let vn =
            (v_normal[0] * v_normal[0] + v_normal[1] * v_normal[1] + v_normal[2] * v_normal[2])
                .sqrt();
        let n = (dist / (vn * dt)) as i32 as i64;
        b.start_step = n + step;
        b.v_integrate = v_normal;
        Some(n)
    }

    /// LIGGGHTS's `release` at a member's release step: the body gets the insertion
    /// velocity (length/time) and angular velocity (1/time; its angular momentum is kept,
    /// so the next step recomputes the angular velocity from it) and is integrated from now.
    pub fn release(&mut self, tag: f64, step: i64, v: Vec3, omega: Vec3) {
        let Some(k) = self.index(tag) else {
            return;
        };
        let b = &mut self.bodies[k];
        if b.start_step >= 0 && step >= b.start_step {
            b.vcm = v;
            b.omega = omega;
            b.start_step = -1;
        }
    }

    /// Bodies that lost a member (an atom left the box): the body is deleted with all its
    /// remaining atoms. Returns the particles to remove (None: nothing to do).
    pub fn lost_members(&mut self, p: &mut Particles) -> Option<Vec<bool>> {
        let ba = body_array(p)?;
        let mut count = vec![0usize; self.bodies.len()];
        for i in 0..p.len() {
            if let Some(k) = self.index(p.extra[ba].data[i]) {
                count[k] += 1;
            }
        }
        let gone: Vec<bool> = (0..self.bodies.len())
            .map(|k| count[k] != self.nrigid[k])
            .collect();
        if !gone.iter().any(|&g| g) {
            return None;
        }
        let remove: Vec<bool> = (0..p.len())
            .map(|i| self.index(p.extra[ba].data[i]).is_some_and(|k| gone[k]))
            .collect();
        let mut k = 0;
        self.bodies.retain(|_| {
            k += 1;
            !gone[k - 1]
        });
        let mut k = 0;
        self.nrigid.retain(|_| {
            k += 1;
            !gone[k - 1]
        });
        let mut k = 0;
        self.r_bound.retain(|_| {
            k += 1;
            !gone[k - 1]
        });
        let mut k = 0;
        self.xb_body.retain(|_| {
            k += 1;
            !gone[k - 1]
        });
        Some(remove)
    }

    /// Per body: the bounding sphere's centre (length; LIGGGHTS's `x_bound`), mass (mass)
    /// and density (mass/length^3).
    pub fn bounds(&self) -> Vec<([f64; 3], f64, f64)> {
        self.bodies
            .iter()
            .zip(&self.xb_body)
            .map(|(b, xb)| {
                let off = b.offset(xb);
                ([0, 1, 2].map(|k| b.xcm[k] + off[k]), b.mass, b.density)
            })
            .collect()
    }

    /// Largest bounding-sphere radius of the bodies (length; 0 without bodies).
    pub fn max_r_bound(&self) -> f64 {
        self.r_bound.iter().copied().fold(0.0, f64::max)
    }
}

/// The simulation's side of `fix multisphere`: the calls in LIGGGHTS's phases.
/// The bodies of the `fix multisphere` among `fixes`, if there is one.
fn clumps_in(fixes: &mut [crate::engine::fixes::Fix]) -> Option<&mut Clumps> {
    fixes.iter_mut().find_map(|f| f.kind.style_as_mut())
}

impl crate::engine::sim::Simulation {
    /// The `fix multisphere` state, if the deck has one.
    pub fn clumps(&self) -> Option<&Clumps> {
        self.fixes.iter().find_map(|f| f.kind.style_as())
    }

    pub(crate) fn clumps_mut(&mut self) -> Option<&mut Clumps> {
        clumps_in(&mut self.fixes)
    }

    /// `pre_force`: the bodies' force sums start from zero.
    pub(crate) fn reset_clump_forces(&mut self) {
        if let Some(ms) = self.clumps_mut() {
            ms.reset_forces();
        }
    }

    /// The setup of `fix multisphere`: the bodies' forces from the setup force evaluation.
    pub(crate) fn setup_clump_forces(&mut self) {
        let gravity = crate::engine::fixes::gravity(&self.fixes);
        if let Some(ms) = clumps_in(&mut self.fixes) {
            ms.calc_force(&self.particles, &self.domain, gravity);
        }
    }

    /// LIGGGHTS's warning at the setup of every run with `fix multisphere`.
    pub(crate) fn say_clump_energy(&self, out: crate::engine::sim::Sink<'_>) {
        if self.clumps().is_some() {
            out("WARNING: Energy calculated for multisphere particles is currently not correct (./src/fix_multisphere.cpp:1312)\n");
        }
    }

    /// Inserts one clump (its members get IDs from `first_id`; `axes`: its drawn
    /// orientation, the template's if None).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn insert_clump(
        &mut self,
        t: &ClumpTemplate,
        axes: Option<[Vec3; 3]>,
        first_id: i64,
        xcm: Vec3,
        v: Vec3,
        omega: Vec3,
        group: u32,
    ) -> Result<(), EngineError> {
        let Some(ms) = clumps_in(&mut self.fixes) else {
            return Err(
                "Multi-sphere particle inserted: You have to use exactly one fix multisphere."
                    .into(),
            );
        };
        ms.insert(
            &mut self.particles,
            t,
            axes,
            first_id,
            xcm,
            v,
            omega,
            group,
            &self.domain,
        );
        Ok(())
    }

    /// Drops the neighbour pairs of two spheres of one body (LIGGGHTS's internal
    /// `neigh_modify exclude molecule`).
    pub(crate) fn exclude_clump_pairs(&mut self) {
        let Some(tags) = body_tags(&self.particles) else {
            return;
        };
        self.list.retain(|pair| {
            let (ti, tj) = (tags[pair.i as usize], tags[pair.j as usize]);
            !(ti >= 0.0 && ti == tj)
        });
    }

    /// Deletes the bodies that lost a member, with their remaining members.
    pub(crate) fn drop_broken_clumps(&mut self) {
        if let Some(ms) = clumps_in(&mut self.fixes) {
            if let Some(remove) = ms.lost_members(&mut self.particles) {
                self.particles.retain_by(&remove);
            }
        }
    }

    /// Restart files do not hold the bodies yet.
    pub(crate) fn refuse_clump_restart(&self) -> Result<(), EngineError> {
        match self.clumps() {
            Some(ms) if !ms.bodies.is_empty() => Err(
                "write_restart with multisphere bodies is not supported yet (the bodies' state is not written)"
                    .into(),
            ),
            _ => Ok(()),
        }
    }
}
