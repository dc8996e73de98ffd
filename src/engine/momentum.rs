//! The inertia tensor and angular velocity of a group, as LAMMPS's Group computes them (for
//! `fix momentum angular`, `velocity ... rot yes` and the group functions).

/// Add a particle of mass `m` (mass) at arm `d` (length) from the centre of mass to the
/// inertia tensor `t` (mass*length^2): its diagonal and upper triangle, in LIGGGHTS's order.
#[inline]
pub fn add_inertia(t: &mut [[f64; 3]; 3], [dx, dy, dz]: [f64; 3], m: f64) {
    t[0][0] += m * (dy * dy + dz * dz);
    t[1][1] += m * (dx * dx + dz * dz);
    t[2][2] += m * (dx * dx + dy * dy);
    t[0][1] -= m * dx * dy;
    t[1][2] -= m * dy * dz;
    t[0][2] -= m * dx * dz;
}

/// Copy the upper triangle of the inertia tensor `t` to its lower one (it is symmetric).
#[inline]
pub fn mirror_inertia(t: &mut [[f64; 3]; 3]) {
    t[1][0] = t[0][1];
    t[2][1] = t[1][2];
    t[2][0] = t[0][2];
}

/// The angular velocity (1/time) of angular momentum `l` with inertia tensor `t`, through
/// the adjugate and determinant as LAMMPS's Group::omega computes it.
/// The angular velocity (rad/s) of angular momentum `l` (kg m^2/s) about inertia tensor `t`
/// (kg m^2), through the adjugate divided by the determinant when it is positive (as LIGGGHTS
/// does for `fix momentum angular` and `velocity ... rot yes`).
pub fn omega(l: [f64; 3], t: [[f64; 3]; 3]) -> [f64; 3] {
    let mut inv = [[0.0; 3]; 3];
    inv[0][0] = t[1][1] * t[2][2] - t[1][2] * t[2][1];
    inv[0][1] = -(t[0][1] * t[2][2] - t[0][2] * t[2][1]);
    inv[0][2] = t[0][1] * t[1][2] - t[0][2] * t[1][1];
    inv[1][0] = -(t[1][0] * t[2][2] - t[1][2] * t[2][0]);
    inv[1][1] = t[0][0] * t[2][2] - t[0][2] * t[2][0];
    inv[1][2] = -(t[0][0] * t[1][2] - t[0][2] * t[1][0]);
    inv[2][0] = t[1][0] * t[2][1] - t[1][1] * t[2][0];
    inv[2][1] = -(t[0][0] * t[2][1] - t[0][1] * t[2][0]);
    inv[2][2] = t[0][0] * t[1][1] - t[0][1] * t[1][0];
    let det =
        t[0][0] * t[1][1] * t[2][2] + t[0][1] * t[1][2] * t[2][0] + t[0][2] * t[1][0] * t[2][1]
            - t[0][0] * t[1][2] * t[2][1]
            - t[0][1] * t[1][0] * t[2][2]
            - t[2][0] * t[1][1] * t[0][2];
    if det > 0.0 {
        for row in &mut inv {
            for c in row.iter_mut() {
                *c /= det;
            }
        }
    }
    [0, 1, 2].map(|r| inv[r][0] * l[0] + inv[r][1] * l[1] + inv[r][2] * l[2])
}

/// Total mass of the particles of `group` (kg), summed in particle order.
pub fn group_mass(p: &crate::engine::particles::Particles, group: u32) -> f64 {
    let mut m = 0.0;
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            m += p.mass[i];
        }
    }
    m
}
