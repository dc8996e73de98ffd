//! `fix move/mesh`: prescribed motion of a mesh's nodes (linear, wiggle, rotate, riggle,
//! viblin, vibrot), as LIGGGHTS 3.8.0 integrates it (docs/notes/move_mesh.md).
//!
//! Every style is incremental: each step the nodes are translated by `dt V` or rotated by
//! `dt w` about an axis, with `V` or `w` evaluated at the mover's own clock after the step
//! (`time += dt`, from the fix's creation). The first mover of a mesh zeroes the node
//! velocities each step; every mover then adds its own. Later movers act on nodes already
//! moved this step, and `rotate` centres travel with the translations and rotations of the
//! movers before them (and their own).

use crate::engine::mesh::{quat_rotate, rotation_quaternion, TriMesh};

type V3 = [f64; 3];

/// The motion of one `fix move/mesh`.
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// `linear Vx Vy Vz`: constant velocity (length/time).
    Linear(V3),
    /// `wiggle amplitude A period T`: velocity `A ω cos(ω t)` (A length, ω = 2π/T 1/time).
    Wiggle { amplitude: V3, omega: f64 },
    /// `rotate origin P axis a period T`: constant angular rate ω = 2π/T (1/time) about
    /// the unit axis through the moving reference point.
    Rotate { axis: V3, omega: f64 },
    /// `riggle origin P axis a period T amplitude deg`: angular rate `ω α cos(ω t)` about
    /// the fixed origin (α radians).
    Riggle {
        origin: V3,
        axis: V3,
        omega: f64,
        alpha: f64,
    },
    /// `viblin axis a order n amplitude C.. phase φ.. period T..`: velocity
    /// `-Σ C ω sin(ω t + φ)` along the unit axis (C length).
    Viblin {
        axis: V3,
        modes: Vec<(f64, f64, f64)>,
    },
    /// `vibrot origin P axis a order n amplitude C.. phase φ.. period T..`: angular rate
    /// `-Σ C ω sin(ω t + φ)` about the fixed origin (C radians).
    Vibrot {
        origin: V3,
        axis: V3,
        modes: Vec<(f64, f64, f64)>,
    },
}

/// One `fix move/mesh`.
#[derive(Debug, Clone, PartialEq)]
pub struct MoveMesh {
    /// The `fix mesh/surface` it moves.
    pub mesh: String,
    /// How it moves.
    pub motion: Motion,
    /// Its clock (time since the fix was created).
    pub time: f64,
    /// The rotation centre of `rotate` (length), carried along by translations and
    /// rotations of this and earlier movers.
    pub reference: Option<V3>,
}

/// What one mover did in a step, for the reference points of the movers after it.
pub enum Displacement {
    /// Translated by this vector (length).
    Translation(V3),
    /// Rotated by `angle` (radians) about the once-normalised `axis` through `centre`.
    Rotation { angle: f64, axis: V3, centre: V3 },
}

impl MoveMesh {
    /// Advance the clock by `dt`, move `mesh` and add this motion's node velocities to
    /// `v` (length/time).
    pub fn step(&mut self, mesh: &mut TriMesh, v: &mut [[V3; 3]], dt: f64) -> Displacement {
        self.time += dt;
        let t = self.time;
        let translation = |mesh: &mut TriMesh, v: &mut [[V3; 3]], vel: V3| {
            let dx = vel.map(|c| dt * c);
            mesh.translate(dx);
            for tri in v.iter_mut() {
                for node in tri.iter_mut() {
                    *node = [node[0] + vel[0], node[1] + vel[1], node[2] + vel[2]];
                }
            }
            Displacement::Translation(dx)
        };
        let rotation = |mesh: &mut TriMesh, v: &mut [[V3; 3]], w: f64, axis: V3, centre: V3| {
            let angle = w * dt;
            mesh.rotate(angle, axis, centre);
            let om = axis.map(|a| w * a);
            for (tri, nodes) in v.iter_mut().zip(&mesh.nodes) {
                for (node_v, x) in tri.iter_mut().zip(nodes) {
                    let r = [x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]];
                    let c = [
                        om[1] * r[2] - om[2] * r[1],
                        om[2] * r[0] - om[0] * r[2],
                        om[0] * r[1] - om[1] * r[0],
                    ];
                    *node_v = [node_v[0] + c[0], node_v[1] + c[1], node_v[2] + c[2]];
                }
            }
            Displacement::Rotation {
                angle,
                axis,
                centre,
            }
        };
        let vib = |modes: &[(f64, f64, f64)]| {
            let mut s = 0.0;
            for &(c, phase, omega) in modes {
                s -= (c * omega) * (omega * t + phase).sin();
            }
            s
        };
        match &self.motion {
            Motion::Linear(vel) => translation(mesh, v, *vel),
            Motion::Wiggle { amplitude, omega } => {
                let s = omega * (omega * t).cos();
                translation(mesh, v, amplitude.map(|a| s * a))
            }
            Motion::Viblin { axis, modes } => {
                let s = vib(modes);
                translation(mesh, v, axis.map(|a| s * a))
            }
            Motion::Rotate { axis, omega } => {
                let centre = self.reference.expect("rotate has a reference point");
                rotation(mesh, v, *omega, *axis, centre)
            }
            Motion::Riggle {
                origin,
                axis,
                omega,
                alpha,
            } => {
                let w = (omega * alpha) * (omega * t).cos();
                rotation(mesh, v, w, *axis, *origin)
            }
            Motion::Vibrot {
                origin,
                axis,
                modes,
            } => {
                let w = vib(modes);
                rotation(mesh, v, w, *axis, *origin)
            }
        }
    }

    /// Carry this mover's reference point along with a displacement of its mesh.
    pub fn follow(&mut self, d: &Displacement) {
        if let Some(r) = self.reference.as_mut() {
            follow_point(r, d);
        }
    }
}

/// Carry a point that moves with a mesh (LIGGGHTS's `frame_general` mesh properties: a
/// mover's rotation centre, the stress module's `reference_point`) along with a
/// displacement of the mesh (length).
pub fn follow_point(r: &mut V3, d: &Displacement) {
    match d {
        Displacement::Translation(dx) => *r = [r[0] + dx[0], r[1] + dx[1], r[2] + dx[2]],
        Displacement::Rotation {
            angle,
            axis,
            centre,
        } => {
            let tmp = [r[0] - centre[0], r[1] - centre[1], r[2] - centre[2]];
            let t2 = tmp[0] * tmp[0] + tmp[1] * tmp[1] + tmp[2] * tmp[2];
            let r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
            if t2 > 1e-20 * r2 {
                let q = rotation_quaternion(*angle, *axis);
                let p = quat_rotate(q, tmp);
                *r = [p[0] + centre[0], p[1] + centre[1], p[2] + centre[2]];
            }
        }
    }
}

/// A unit axis as LIGGGHTS normalises it at parse time (a zero axis stays zero).
pub fn unit_axis(a: V3) -> V3 {
    let s = ((a[0] * a[0] + a[1] * a[1]) + a[2] * a[2]).sqrt();
    let inv = if s == 0.0 { 0.0 } else { 1.0 / s };
    a.map(|c| c * inv)
}

impl crate::engine::fixes::FixStyle for MoveMesh {
    fn name(&self) -> &str {
        "move/mesh"
    }

    /// Its mesh moves in [`crate::engine::fixes::move_meshes`], in `initial_integrate`.
    fn reads_computes(&self) -> bool {
        true
    }

    /// Its clock (time).
    fn restart_state(&self) -> Option<Vec<u8>> {
        Some(crate::engine::restart_fixes::to_bytes(&[self.time]))
    }

    /// The clock from the file; the mesh took its moved nodes from the file.
    fn restore_state(&mut self, state: &[u8]) -> Result<(), crate::engine::fixes::RestoreError> {
        let d = crate::engine::restart_fixes::doubles(state);
        self.time = *d
            .first()
            .ok_or_else(|| crate::engine::fixes::RestoreError::Malformed("empty".into()))?;
        Ok(())
    }

    fn array_unsupported(&self) -> bool {
        true
    }

    fn refuses_thermo(&self) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::mesh::MeshSettings;

    fn tri() -> TriMesh {
        TriMesh::new(
            &[[[0.1, 0.2, 0.3], [0.7, 0.1, 0.25], [0.3, 0.8, 0.35]]],
            MeshSettings::default(),
        )
    }

    fn run(movers: &mut [MoveMesh], steps: usize) -> ([V3; 3], V3) {
        let mut m = tri();
        let mut v = vec![[[0.0; 3]; 3]];
        for _ in 0..steps {
            v = vec![[[0.0; 3]; 3]];
            for k in 0..movers.len() {
                let d = movers[k].step(&mut m, &mut v, 0.001);
                for later in movers[k..].iter_mut() {
                    later.follow(&d);
                }
            }
        }
        (m.nodes[0], v[0][0])
    }

    fn linear() -> MoveMesh {
        MoveMesh {
            mesh: "cad".into(),
            motion: Motion::Linear([0.5, -0.25, 0.125]),
            time: 0.0,
            reference: None,
        }
    }

    fn rotate() -> MoveMesh {
        MoveMesh {
            mesh: "cad".into(),
            motion: Motion::Rotate {
                axis: unit_axis([1.0, 2.0, 3.0]),
                omega: 2.0 * std::f64::consts::PI / 0.05,
            },
            time: 0.0,
            reference: Some([0.2, 0.3, 0.1]),
        }
    }

    /// Node coordinates after 5 steps as LIGGGHTS 3.8.0 writes them to its restart file
    /// (docs/notes/move_mesh.md §7.2).
    #[test]
    #[allow(clippy::excessive_precision)] // LIGGGHTS's 17-digit output, kept as it printed
    fn nodes_match_liggghts_after_five_steps() {
        let (n, v) = run(&mut [linear()], 5);
        assert_eq!(
            n[0],
            [
                0.10250000000000001,
                0.19875000000000001,
                0.30062499999999992
            ]
        );
        assert_eq!(
            n[1],
            [
                0.70249999999999968,
                0.098750000000000004,
                0.25062499999999993
            ]
        );
        assert_eq!(v, [0.5, -0.25, 0.125]);
        let (n, _) = run(&mut [rotate()], 5);
        assert_eq!(
            n[0],
            [
                0.23315534509403077,
                0.14873717826511754,
                0.28979009945857803
            ]
        );
        assert_eq!(
            n[2],
            [
                0.14904652296102558,
                0.76283718807079781,
                0.42509303363245954
            ]
        );
        let wiggle = MoveMesh {
            mesh: "cad".into(),
            motion: Motion::Wiggle {
                amplitude: [0.05, 0.02, -0.03],
                omega: 2.0 * std::f64::consts::PI / 0.007,
            },
            time: 0.0,
            reference: None,
        };
        let (n, _) = run(&mut [wiggle], 5);
        assert_eq!(
            n[0],
            [
                0.027137948075752198,
                0.17085517923030091,
                0.34371723115454877
            ]
        );
        // a rotation after a translation turns about the carried centre; before it, about
        // the fixed one
        let (n, _) = run(&mut [linear(), rotate()], 5);
        assert_eq!(
            n[0],
            [
                0.23565534509403077,
                0.14748717826511754,
                0.29041509945857796
            ]
        );
        let (n, _) = run(&mut [rotate(), linear()], 5);
        assert_eq!(
            n[0],
            [
                0.23587208393907361,
                0.14800774129841229,
                0.28999581115470047
            ]
        );
    }

    #[test]
    #[allow(clippy::excessive_precision)] // LIGGGHTS's 17-digit output, kept as it printed
    fn vibrations_and_riggle_match_liggghts() {
        let two_pi = 2.0 * std::f64::consts::PI;
        let riggle = MoveMesh {
            mesh: "cad".into(),
            motion: Motion::Riggle {
                origin: [0.2, 0.3, 0.1],
                axis: unit_axis([1.0, -1.0, 0.5]),
                omega: two_pi / 0.009,
                alpha: (std::f64::consts::PI * 20.0) / 180.0,
            },
            time: 0.0,
            reference: None,
        };
        let (n, _) = run(&mut [riggle], 5);
        assert_eq!(
            n[0],
            [
                0.14316822960937331,
                0.26066609535562213,
                0.33499573149249762
            ]
        );
        let viblin = MoveMesh {
            mesh: "cad".into(),
            motion: Motion::Viblin {
                axis: unit_axis([1.0, 1.0, 0.0]),
                modes: vec![(0.01, 0.3, two_pi / 0.004), (0.02, 1.1, two_pi / 0.011)],
            },
            time: 0.0,
            reference: None,
        };
        let (n, _) = run(&mut [viblin], 5);
        assert_eq!(
            n[0],
            [
                0.080246141501149587,
                0.18024614150114959,
                0.29999999999999999
            ]
        );
        let vibrot = MoveMesh {
            mesh: "cad".into(),
            motion: Motion::Vibrot {
                origin: [0.2, 0.3, 0.1],
                axis: unit_axis([0.0, 0.0, 1.0]),
                modes: vec![(0.1, 0.5, two_pi / 0.01), (0.2, 0.0, two_pi / 0.02)],
            },
            time: 0.0,
            reference: None,
        };
        let (n, _) = run(&mut [vibrot], 5);
        assert_eq!(
            n[0],
            [
                0.070642904030312287,
                0.2428445827389128,
                0.29999999999999993
            ]
        );
    }
}
