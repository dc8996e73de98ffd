//! `fix move/mesh`: prescribed motion of a mesh.

use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixStyle;
use crate::engine::mesh_motion::{unit_axis, Motion};

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "move/mesh",
    "fix ID GROUP move/mesh mesh MESH linear|wiggle|rotate|riggle|viblin|vibrot ...",
    &[],
    "prescribed mesh motion",
);

/// `fix ID group move/mesh mesh MESH STYLE args...` (linear, wiggle, rotate, riggle, viblin,
/// vibrot), with LIGGGHTS's messages.
pub fn build(a: &Args, ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    use crate::engine::mesh_motion::MoveMesh;
    if a.len() < 6 {
        return Err(a.error(
            2,
            "Illegal fix move/mesh command, you need to specify a mesh",
        ));
    }
    if a.word(3)? != "mesh" {
        return Err(a.error(3, "Illegal fix move/mesh command, expecting keyword 'mesh'"));
    }
    let mesh = a.word(4)?.to_string();
    let Some(m) = crate::engine::fixes::mesh_named(&ctx.sim.fixes, &mesh) else {
        return Err(a.error(4, "Illegal fix move/mesh command, illegal mesh ID provided"));
    };
    if m.surface_vel.is_some() {
        return Err(a.error(4, "Illegal fix move/mesh command, cannot apply move to a mesh using keywords 'velocity' or 'angular_velocity'"));
    }
    let words = MotionWords {
        a,
        style: a.word(5)?,
        narg: a.len() - 5,
    };
    let (motion, reference) = words.motion()?;
    words.warn_excess(ctx, &motion);
    Ok(Box::new(MoveMesh {
        mesh,
        motion,
        time: 0.0,
        reference,
    }))
}

/// (words read, per mode: amplitude, phase, angular frequency)
type Modes = (usize, Vec<(f64, f64, f64)>);

/// The motion words of `fix move/mesh` from the style (word 5) on. LIGGGHTS counts the
/// style word as argument 0 of the motion's own list.
struct MotionWords<'c> {
    a: &'c Args<'c>,
    style: &'c str,
    narg: usize,
}

impl MotionWords<'_> {
    /// The command word of the motion's argument `k`.
    fn at(&self, k: usize) -> usize {
        5 + k
    }

    /// At least `n` motion arguments.
    fn need(&self, n: usize) -> Result<(), CommandError> {
        if self.narg < n {
            Err(self.a.error(
                5,
                format!("Not enough arguments for movement type {}", self.style),
            ))
        } else {
            Ok(())
        }
    }

    /// Motion argument `k` is the keyword `w`.
    fn keyword(&self, k: usize, w: &str) -> Result<(), CommandError> {
        if self.a.word(self.at(k))? != w {
            Err(self.a.error(self.at(k), format!("Expected keyword '{w}'")))
        } else {
            Ok(())
        }
    }

    /// Motion arguments `k..k + 3` as a vector.
    fn vec3(&self, k: usize) -> Result<[f64; 3], CommandError> {
        let a = self.a;
        Ok([
            a.real(self.at(k))?,
            a.real(self.at(k + 1))?,
            a.real(self.at(k + 2))?,
        ])
    }

    /// Motion argument `k` as a period, given as the angular frequency 2 pi / period.
    fn omega(&self, k: usize) -> Result<f64, CommandError> {
        Ok(2.0 * std::f64::consts::PI / self.a.real(self.at(k))?)
    }

    /// `order N amplitude C... phase P... period T...` from motion argument `order_at`.
    fn modes(&self, order_at: usize) -> Result<Modes, CommandError> {
        let (a, style, narg) = (self.a, self.style, self.narg);
        self.keyword(order_at, "order")?;
        let n = a.int(self.at(order_at + 1))?;
        if !(1..=30).contains(&n) {
            return Err(a.error(
                self.at(order_at + 1),
                "order can be at most 30 and must be greater 0",
            ));
        }
        let n = n as usize;
        // LIGGGHTS checks for two lists only and reads the periods after them
        if narg < order_at + 5 + 2 * n {
            return Err(a.error(5, format!("Not enough arguments for movement type {style}")));
        }
        if narg < order_at + 5 + 3 * n {
            return Err(a.error(
                5,
                format!("Not enough arguments for movement type {style} (LIGGGHTS reads the periods past the end of the command and crashes)"),
            ));
        }
        self.keyword(order_at + 2, "amplitude")?;
        self.keyword(order_at + 3 + n, "phase")?;
        self.keyword(order_at + 4 + 2 * n, "period")?;
        let mut out = Vec::with_capacity(n);
        for j in 0..n {
            let c = a.real(self.at(order_at + 3 + j))?;
            let phase = a.real(self.at(order_at + 4 + n + j))?;
            let omega = self.omega(order_at + 5 + 2 * n + j)?;
            out.push((c, phase, omega));
        }
        Ok((n, out))
    }

    /// The motion, and the reference point of `rotate` (length).
    fn motion(&self) -> Result<(Motion, Option<[f64; 3]>), CommandError> {
        let (a, style) = (self.a, self.style);
        Ok(match style {
            "linear" => {
                self.need(4)?;
                (Motion::Linear(self.vec3(1)?), None)
            }
            "wiggle" => {
                self.need(7)?;
                self.keyword(1, "amplitude")?;
                self.keyword(5, "period")?;
                let m = Motion::Wiggle {
                    amplitude: self.vec3(2)?,
                    omega: self.omega(6)?,
                };
                (m, None)
            }
            "rotate" => {
                self.need(11)?;
                self.keyword(1, "origin")?;
                self.keyword(5, "axis")?;
                self.keyword(9, "period")?;
                let m = Motion::Rotate {
                    axis: unit_axis(self.vec3(6)?),
                    omega: self.omega(10)?,
                };
                (m, Some(self.vec3(2)?))
            }
            "riggle" => {
                self.need(13)?;
                self.keyword(1, "origin")?;
                self.keyword(5, "axis")?;
                self.keyword(9, "period")?;
                self.keyword(11, "amplitude")?;
                let m = Motion::Riggle {
                    origin: self.vec3(2)?,
                    axis: unit_axis(self.vec3(6)?),
                    omega: self.omega(10)?,
                    alpha: (std::f64::consts::PI * a.real(self.at(12))?) / 180.0,
                };
                (m, None)
            }
            "viblin" => {
                self.need(7)?;
                self.keyword(1, "axis")?;
                let axis = unit_axis(self.vec3(2)?);
                let (_, modes) = self.modes(5)?;
                (Motion::Viblin { axis, modes }, None)
            }
            "vibrot" => {
                self.need(11)?;
                self.keyword(1, "origin")?;
                self.keyword(5, "axis")?;
                let origin = self.vec3(2)?;
                let axis = unit_axis(self.vec3(6)?);
                let (_, modes) = self.modes(9)?;
                (
                    Motion::Vibrot {
                        origin,
                        axis,
                        modes,
                    },
                    None,
                )
            }
            "linear/variable" | "rotate/variable" => {
                return Err(a.unsupported(5, &format!("fix move/mesh {style}")))
            }
            _ => {
                return Err(a.error(5, "Mesh movement type not available").with_help(
                    "fix move/mesh knows linear, linear/variable, wiggle, rotate, rotate/variable, riggle, viblin and vibrot",
                ))
            }
        })
    }

    /// LIGGGHTS's excess-argument warnings (viblin's names the wiggle style).
    fn warn_excess(&self, ctx: &mut Ctx, motion: &Motion) {
        let (style, narg) = (self.style, self.narg);
        let mut warn = |n: usize| {
            if narg > n {
                ctx.say(&format!("WARNING: Movement type {style} requires only {n} arguments, excess arguments will be ignored\n"));
            }
        };
        match motion {
            Motion::Linear(_) => warn(4),
            Motion::Wiggle { .. } => warn(7),
            Motion::Rotate { .. } => warn(11),
            Motion::Riggle { .. } => warn(13),
            Motion::Viblin { modes, .. } => {
                let n = modes.len();
                if narg > 10 + 2 * n {
                    ctx.say("WARNING: Movement type wiggle requires only (10 + 2*$order) arguments, excess arguments will be ignored (./src/mesh_mover_linear.cpp:303)\n");
                }
            }
            Motion::Vibrot { modes, .. } => {
                let n = modes.len();
                if narg > 14 + 2 * n {
                    ctx.say("WARNING: Movement type vibrot requires only (14 + 2*$order) arguments, excess arguments will be ignored (./src/mesh_mover_rotation.cpp:347)\n");
                }
            }
        }
    }
}
