//! Time integration of spheres (`fix nve/sphere`): velocity Verlet for translation and
//! rotation in LIGGGHTS's order of operations, plus uniform body forces (`fix gravity`).
//! Every update is element-wise, so results do not depend on the thread count.

use crate::util::team::{stage_chunks, Shards};

use crate::engine::error::EngineError;
use crate::engine::particles::Particles;

/// Below this many particles the per-particle stages stay on one thread (the fork-join cost
/// is larger than the work); either way every particle is updated alike. The pair pass
/// shares out its blocks of 1 024 particles from two blocks on: the stages over a particle
/// share the same split, so its data stay with one core from stage to stage.
pub const PARALLEL_PARTICLES: usize = 1024;

/// Particles per parallel chunk.
const CHUNK: usize = 1024;

/// Particles whose kick factors are computed together (a stack buffer each).
const SUB: usize = 64;

/// The half-kick factors of up to [`SUB`] particles: `lin[k] = dtf / m` (s/kg) and
/// `rot[k] = dtfrotate / (r^2 m)` (s/(kg m^2)), the divisions LIGGGHTS's nve/sphere makes,
/// several per instruction where the processor allows.
#[inline(always)]
fn kick_factors(
    m: &[f64],
    r: &[f64],
    (dtf, dtfrotate): (f64, f64),
    lin: &mut [f64],
    rot: &mut [f64],
) {
    #[cfg(target_arch = "x86_64")]
    if crate::engine::contact::real::lanes_supported() {
        // SAFETY: the processor has AVX2 (checked at run time)
        unsafe { kick_factors_avx2(m, r, (dtf, dtfrotate), lin, rot) };
        return;
    }
    kick_factors_plain(m, r, (dtf, dtfrotate), lin, rot);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn kick_factors_avx2(
    m: &[f64],
    r: &[f64],
    dt: (f64, f64),
    lin: &mut [f64],
    rot: &mut [f64],
) {
    kick_factors_plain(m, r, dt, lin, rot);
}

#[inline(always)]
fn kick_factors_plain(
    m: &[f64],
    r: &[f64],
    (dtf, dtfrotate): (f64, f64),
    lin: &mut [f64],
    rot: &mut [f64],
) {
    for (((l, q), &m), &r) in lin.iter_mut().zip(rot.iter_mut()).zip(m).zip(r) {
        *l = dtf / (m * 1.0);
        *q = dtfrotate / (r * r * m);
    }
}

/// Positions (m), velocities (m/s) and angular velocities (rad/s) of some particles.
type Motion<'a> = (&'a mut [[f64; 3]], &'a mut [[f64; 3]], &'a mut [[f64; 3]]);

/// Up to [`SUB`] particles, all in the group: v += lin f and omega += rot torque, then (with
/// `drift` = Some(dt)) x += dt v. The same operations per component as the particle-by-particle
/// loops, done over the flattened arrays, several components per instruction where the
/// processor allows.
#[inline(always)]
fn kick_drift_all(
    (x, v, w): Motion<'_>,
    (f, t): (&[[f64; 3]], &[[f64; 3]]),
    (lin, rot): (&[f64], &[f64]),
    drift: Option<f64>,
) {
    #[cfg(target_arch = "x86_64")]
    if crate::engine::contact::real::lanes_supported() {
        // SAFETY: the processor has AVX2 (checked at run time)
        unsafe { kick_drift_all_avx2((x, v, w), (f, t), (lin, rot), drift) };
        return;
    }
    kick_drift_all_plain((x, v, w), (f, t), (lin, rot), drift);
}

/// [`kick_drift_all_plain`] four particles (twelve components, three registers) at a time:
/// each factor is spread over its particle's three components by a lane permutation, so no
/// spread copy goes through memory (the same multiplications and additions, bit for bit).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn kick_drift_all_avx2(
    (x, v, w): Motion<'_>,
    (f, t): (&[[f64; 3]], &[[f64; 3]]),
    (lin, rot): (&[f64], &[f64]),
    drift: Option<f64>,
) {
    use std::arch::x86_64::*;
    let mut n = lin.len().min(rot.len()).min(v.len()).min(w.len());
    n = n.min(f.len()).min(t.len());
    if drift.is_some() {
        n = n.min(x.len());
    }
    let quads = n / 4;
    {
        let (vp, wp) = (
            v.as_flattened_mut().as_mut_ptr(),
            w.as_flattened_mut().as_mut_ptr(),
        );
        let xp = x.as_flattened_mut().as_mut_ptr();
        let (fp, tp) = (f.as_flattened().as_ptr(), t.as_flattened().as_ptr());
        // factors of particles 0-3 in lane order: (0 0 0 1) (1 1 2 2) (2 3 3 3)
        let spread = |a: __m256d| {
            [
                _mm256_permute4x64_pd::<0x40>(a),
                _mm256_permute4x64_pd::<0xA5>(a),
                _mm256_permute4x64_pd::<0xFE>(a),
            ]
        };
        for q in 0..quads {
            // SAFETY: 4q + 3 < n <= every slice's length (in particles; 12 doubles per quad)
            unsafe {
                let lin = spread(_mm256_loadu_pd(lin.as_ptr().add(4 * q)));
                let rot = spread(_mm256_loadu_pd(rot.as_ptr().add(4 * q)));
                for (g, (l, r)) in lin.into_iter().zip(rot).enumerate() {
                    let k = 12 * q + 4 * g;
                    let vk = _mm256_add_pd(
                        _mm256_loadu_pd(vp.add(k)),
                        _mm256_mul_pd(l, _mm256_loadu_pd(fp.add(k))),
                    );
                    _mm256_storeu_pd(vp.add(k), vk);
                    if let Some(dt) = drift {
                        let xk = _mm256_add_pd(
                            _mm256_loadu_pd(xp.add(k)),
                            _mm256_mul_pd(_mm256_set1_pd(dt), vk),
                        );
                        _mm256_storeu_pd(xp.add(k), xk);
                    }
                    let wk = _mm256_add_pd(
                        _mm256_loadu_pd(wp.add(k)),
                        _mm256_mul_pd(r, _mm256_loadu_pd(tp.add(k))),
                    );
                    _mm256_storeu_pd(wp.add(k), wk);
                }
            }
        }
    }
    // the last particles (fewer than four) one component at a time
    for k in 4 * quads..n {
        for d in 0..3 {
            v[k][d] += lin[k] * f[k][d];
        }
        if let Some(dt) = drift {
            for d in 0..3 {
                x[k][d] += dt * v[k][d];
            }
        }
        for d in 0..3 {
            w[k][d] += rot[k] * t[k][d];
        }
    }
}

#[inline(always)]
fn kick_drift_all_plain(
    (x, v, w): Motion<'_>,
    (f, t): (&[[f64; 3]], &[[f64; 3]]),
    (lin, rot): (&[f64], &[f64]),
    drift: Option<f64>,
) {
    // each particle's factor once per component (no zeroing: only the first n are read)
    let mut lin3 = [std::mem::MaybeUninit::<[f64; 3]>::uninit(); SUB];
    let mut rot3 = [std::mem::MaybeUninit::<[f64; 3]>::uninit(); SUB];
    let n = lin.len().min(rot.len()).min(SUB);
    for ((l3, r3), (&l, &r)) in lin3
        .iter_mut()
        .zip(&mut rot3)
        .zip(lin.iter().zip(rot))
        .take(n)
    {
        l3.write([l, l, l]);
        r3.write([r, r, r]);
    }
    // SAFETY: the first n entries of both were written just above
    let (lin3, rot3): (&[f64], &[f64]) = unsafe {
        (
            std::slice::from_raw_parts(lin3.as_ptr().cast(), 3 * n),
            std::slice::from_raw_parts(rot3.as_ptr().cast(), 3 * n),
        )
    };
    let kick = |v: &mut [[f64; 3]], f: &[[f64; 3]], a: &[f64]| {
        let (v, f) = (v.as_flattened_mut(), f.as_flattened());
        for ((v, &f), &a) in v.iter_mut().zip(f).zip(a) {
            *v += a * f;
        }
    };
    kick(v, f, lin3);
    if let Some(dt) = drift {
        let (x, v) = (x.as_flattened_mut(), v.as_flattened());
        for (x, &v) in x.iter_mut().zip(v) {
            *x += dt * v;
        }
    }
    kick(w, t, rot3);
}

/// Run per-particle work on the engine's threads when there are enough particles.
#[inline]
pub fn parallel(n: usize) -> bool {
    n >= PARALLEL_PARTICLES && rayon::current_num_threads() > 1 && !crate::util::team::held()
}

/// Moment-of-inertia prefactor of a solid sphere (I = 0.4 m r^2).
pub const SPHERE_INERTIA: f64 = 0.4;

/// First half of a velocity-Verlet step for particles whose `mask` has `group` bits:
/// half-kick v and omega with the current force and torque, then drift x by a full `dt`.
pub fn initial_integrate(p: &mut Particles, group: u32, dt: f64) {
    initial_integrate_with(p, group, dt, SPHERE_INERTIA)
}

/// [`initial_integrate`] for bodies of moment of inertia `inertia` m r^2 (discs in 2d).
pub fn initial_integrate_with(p: &mut Particles, group: u32, dt: f64, inertia: f64) {
    let dtf = 0.5 * dt;
    let dtfrotate = dtf / inertia;
    let Particles {
        x,
        v,
        omega,
        f,
        torque,
        mass,
        radius,
        mask,
        ..
    } = p;
    let n = x.len();
    // one chunk of particles: zipped slices, so the loop carries no bounds checks
    let sub = |start: usize, x: &mut [[f64; 3]], v: &mut [[f64; 3]], w: &mut [[f64; 3]]| {
        let end = start + x.len();
        let (mut lin, mut rot) = ([0.0; SUB], [0.0; SUB]);
        let (m, r) = (&mass[start..end], &radius[start..end]);
        kick_factors(m, r, (dtf, dtfrotate), &mut lin, &mut rot);
        if mask[start..end].iter().all(|&bits| bits & group != 0) {
            let (f, t) = (&f[start..end], &torque[start..end]);
            let len = end - start;
            kick_drift_all((x, v, w), (f, t), (&lin[..len], &rot[..len]), Some(dt));
            return;
        }
        let cols = f[start..end]
            .iter()
            .zip(&torque[start..end])
            .zip(lin.iter().zip(&rot))
            .zip(&mask[start..end]);
        for (((((f, t), (&dtfm, &dtirotate)), &bits), x), (v, w)) in
            cols.zip(x.iter_mut()).zip(v.iter_mut().zip(w.iter_mut()))
        {
            if bits & group == 0 {
                continue;
            }
            for d in 0..3 {
                v[d] += dtfm * f[d];
            }
            for d in 0..3 {
                x[d] += dt * v[d];
            }
            for d in 0..3 {
                w[d] += dtirotate * t[d];
            }
        }
    };
    let chunk = |start: usize, x: &mut [[f64; 3]], v: &mut [[f64; 3]], w: &mut [[f64; 3]]| {
        let parts = x
            .chunks_mut(SUB)
            .zip(v.chunks_mut(SUB))
            .zip(w.chunks_mut(SUB));
        for (k, ((x, v), w)) in parts.enumerate() {
            sub(start + k * SUB, x, v, w);
        }
    };
    if parallel(n) {
        let (x, v, w) = (Shards::new(x), Shards::new(v), Shards::new(omega));
        stage_chunks(n, CHUNK, true, |_, r| {
            // SAFETY: the chunks of a stage are disjoint
            let (x, v, w) = unsafe { (x.range(r.clone()), v.range(r.clone()), w.range(r.clone())) };
            chunk(r.start, x, v, w)
        });
    } else {
        chunk(0, x, v, omega);
    }
}

/// Second half of a velocity-Verlet step: half-kick v and omega with the new force/torque.
pub fn final_integrate(p: &mut Particles, group: u32, dt: f64) {
    final_integrate_with(p, group, dt, SPHERE_INERTIA)
}

/// [`final_integrate`] for bodies of moment of inertia `inertia` m r^2 (discs in 2d).
pub fn final_integrate_with(p: &mut Particles, group: u32, dt: f64, inertia: f64) {
    let dtf = 0.5 * dt;
    let dtfrotate = dtf / inertia;
    let Particles {
        v,
        omega,
        f,
        torque,
        mass,
        radius,
        mask,
        ..
    } = p;
    let n = v.len();
    let sub = |start: usize, v: &mut [[f64; 3]], w: &mut [[f64; 3]]| {
        let end = start + v.len();
        let (mut lin, mut rot) = ([0.0; SUB], [0.0; SUB]);
        let (m, r) = (&mass[start..end], &radius[start..end]);
        kick_factors(m, r, (dtf, dtfrotate), &mut lin, &mut rot);
        if mask[start..end].iter().all(|&bits| bits & group != 0) {
            let (f, t) = (&f[start..end], &torque[start..end]);
            let len = end - start;
            kick_drift_all((&mut [], v, w), (f, t), (&lin[..len], &rot[..len]), None);
            return;
        }
        let cols = f[start..end]
            .iter()
            .zip(&torque[start..end])
            .zip(lin.iter().zip(&rot))
            .zip(&mask[start..end]);
        for ((((f, t), (&dtfm, &dtirotate)), &bits), (v, w)) in
            cols.zip(v.iter_mut().zip(w.iter_mut()))
        {
            if bits & group == 0 {
                continue;
            }
            for d in 0..3 {
                v[d] += dtfm * f[d];
            }
            for d in 0..3 {
                w[d] += dtirotate * t[d];
            }
        }
    };
    let chunk = |start: usize, v: &mut [[f64; 3]], w: &mut [[f64; 3]]| {
        for (k, (v, w)) in v.chunks_mut(SUB).zip(w.chunks_mut(SUB)).enumerate() {
            sub(start + k * SUB, v, w);
        }
    };
    if parallel(n) {
        let (v, w) = (Shards::new(v), Shards::new(omega));
        stage_chunks(n, CHUNK, true, |_, r| {
            // SAFETY: the chunks of a stage are disjoint
            let (v, w) = unsafe { (v.range(r.clone()), w.range(r.clone())) };
            chunk(r.start, v, w)
        });
    } else {
        chunk(0, v, omega);
    }
}

/// A uniform acceleration field (`fix gravity MAG vector X Y Z`), acceleration in length/time^2.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gravity {
    /// Acceleration components (length/time^2).
    pub acc: [f64; 3],
    /// Group bits it acts on.
    pub group: u32,
}

impl Gravity {
    /// Gravity of `magnitude` along the direction (dx, dy, dz), normalised as LIGGGHTS does.
    pub fn along(magnitude: f64, dir: [f64; 3], group: u32) -> Result<Gravity, EngineError> {
        let length = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        if length == 0.0 {
            return Err("Gravity direction vector = 0".into());
        }
        Ok(Gravity {
            acc: [
                magnitude * (dir[0] / length),
                magnitude * (dir[1] / length),
                magnitude * (dir[2] / length),
            ],
            group,
        })
    }

    /// Gravity of `magnitude` at the polar angle `theta` and azimuth `phi` (degrees), as
    /// LIGGGHTS's `spherical` and `chute` styles turn them into a direction (`dimension` 2: in
    /// the xy plane, the angle measured from +y).
    pub fn spherical(magnitude: f64, phi: f64, theta: f64, dimension: u32, group: u32) -> Gravity {
        let degree2rad = std::f64::consts::PI / 180.0;
        let dir = if dimension == 3 {
            [
                (degree2rad * theta).sin() * (degree2rad * phi).cos(),
                (degree2rad * theta).sin() * (degree2rad * phi).sin(),
                (degree2rad * theta).cos(),
            ]
        } else {
            [(degree2rad * theta).sin(), (degree2rad * theta).cos(), 0.0]
        };
        Gravity {
            acc: dir.map(|d| magnitude * d),
            group,
        }
    }

    /// Add m g to every particle's force (LIGGGHTS's post_force).
    pub fn apply(&self, p: &mut Particles) {
        // members of multisphere clumps get their weight through their body
        let tags = crate::engine::clumps::body_array(p).map(|k| &p.extra[k].data[..]);
        let (mass, mask) = (&p.mass, &p.mask);
        let add = |i: usize, f: &mut [f64; 3]| {
            if mask[i] & self.group != 0 && !crate::engine::clumps::is_member(tags, i) {
                let m = mass[i] * 1.0;
                for (fd, ad) in f.iter_mut().zip(self.acc) {
                    *fd += m * ad;
                }
            }
        };
        if parallel(p.f.len()) {
            let n = p.f.len();
            let f = Shards::new(&mut p.f);
            stage_chunks(n, CHUNK, true, |_, r| {
                // SAFETY: the chunks of a stage are disjoint
                for (k, f) in unsafe { f.range(r.clone()) }.iter_mut().enumerate() {
                    add(r.start + k, f);
                }
            });
        } else {
            for (i, f) in p.f.iter_mut().enumerate() {
                add(i, f);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_fall_is_exact_for_verlet() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0, 0.0, 1.0], 0.01, 2500.0);
        let g = Gravity::along(9.81, [0.0, 0.0, -2.0], 1).unwrap();
        let dt = 1e-3;
        g.apply(&mut p);
        for _ in 0..1000 {
            initial_integrate(&mut p, 1, dt);
            p.f[0] = [0.0; 3];
            g.apply(&mut p);
            final_integrate(&mut p, 1, dt);
        }
        // velocity Verlet integrates constant acceleration exactly: z = 1 - g t^2 / 2
        assert!((p.x[0][2] - (1.0 - 0.5 * 9.81)).abs() < 1e-9);
        assert!((p.v[0][2] + 9.81).abs() < 1e-9);
    }

    #[test]
    fn torque_spins_up_a_sphere() {
        let mut p = Particles::default();
        p.push(1, 1, [0.0; 3], 0.5, 1.0);
        p.torque[0] = [0.0, 0.0, 2.0];
        initial_integrate(&mut p, 1, 0.1);
        final_integrate(&mut p, 1, 0.1);
        let inertia = 0.4 * p.mass[0] * 0.25;
        assert!((p.omega[0][2] - 2.0 * 0.1 / inertia).abs() < 1e-12);
        assert!(Gravity::along(1.0, [0.0; 3], 1).is_err());
    }
}
