//! The servo keywords of `fix mesh/surface/stress/servo` (after the mesh's and the stress
//! module's keywords, as LIGGGHTS parses its mesh modules in turn).

use crate::commands::{Args, CommandError, Ctx};
use crate::engine::mesh_servo::MeshServo;

/// The servo keywords as given (LIGGGHTS's defaults: kp 0.01, ki 0, kd 0).
#[derive(Debug, Clone, Default)]
pub struct ServoArgs {
    /// `com x y z` (length).
    com: Option<[f64; 3]>,
    /// `ctrlPV force` was given.
    force: bool,
    /// `axis x y z`.
    axis: [f64; 3],
    /// `target_val` (force).
    target: Option<f64>,
    /// `target_val v_name`: the equal-style variable giving the target (force).
    target_var: Option<String>,
    /// `vel_max` (length/time).
    vel_max: Option<f64>,
    /// `kp`, `ki`, `kd` when given.
    gains: [Option<f64>; 3],
    /// `mode auto`.
    auto: bool,
    /// `ratio`.
    ratio: f64,
}

/// The servo module's keywords.
pub const KEYWORDS: &[&str] = &[
    "com",
    "ctrlPV",
    "vel_max",
    "target_val",
    "axis",
    "kp",
    "ki",
    "kd",
    "mode",
    "ratio",
];

impl ServoArgs {
    /// Parse the servo keyword at argument `i`; the number of words it takes.
    pub fn parse(&mut self, a: &Args, i: usize) -> Result<usize, CommandError> {
        let need = |n: usize, what: &str| {
            if i + n >= a.len() {
                Err(a.error(i, format!("not enough arguments for '{what}'")))
            } else {
                Ok(())
            }
        };
        let w = a.word(i)?;
        match w {
            "com" | "axis" => {
                need(3, w)?;
                let v = [a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?];
                if w == "com" {
                    self.com = Some(v);
                } else {
                    self.axis = v;
                }
                Ok(4)
            }
            "ctrlPV" => {
                need(1, w)?;
                match a.word(i + 1)? {
                    "force" => self.force = true,
                    "torque" => {
                        return Err(
                            a.unsupported(i + 1, "fix mesh/surface/stress/servo ctrlPV torque")
                        )
                    }
                    _ => {
                        return Err(a.error(
                            i + 1,
                            "only 'force', 'torque' are valid arguments for ctrlPV",
                        ))
                    }
                }
                Ok(2)
            }
            "vel_max" => {
                need(1, w)?;
                let v = a.real(i + 1)?;
                if v <= 0. {
                    return Err(a.error(i + 1, "vel_max > 0 required"));
                }
                self.vel_max = Some(v);
                Ok(2)
            }
            "target_val" => {
                need(1, w)?;
                if let Some(name) = a.word(i + 1)?.strip_prefix("v_") {
                    // checked at each run's init, as LIGGGHTS checks it
                    self.target_var = Some(name.to_string());
                    self.target = None;
                    return Ok(2);
                }
                let v = a.real(i + 1)?;
                if v == 0. {
                    return Err(a.error(
                        i + 1,
                        "'target_val' (desired force/torque) has to be != 0.0",
                    ));
                }
                self.target = Some(v);
                self.target_var = None;
                Ok(2)
            }
            "kp" | "ki" | "kd" => {
                if i + 1 >= a.len() {
                    return Err(a.error(i, "not enough arguments"));
                }
                let k = ["kp", "ki", "kd"].iter().position(|k| *k == w).unwrap_or(0);
                self.gains[k] = Some(a.real(i + 1)?);
                Ok(2)
            }
            "mode" => {
                if i + 1 >= a.len() {
                    return Err(a.error(i, "not enough arguments"));
                }
                if a.word(i + 1)? != "auto" {
                    return Err(a.error(i + 1, "mode supports only auto"));
                }
                self.auto = true;
                Ok(2)
            }
            "ratio" => {
                if i + 1 >= a.len() {
                    return Err(a.error(i, "not enough arguments"));
                }
                self.ratio = a.real(i + 1)?;
                Ok(2)
            }
            _ => Err(a.keyword_error(i, KEYWORDS)),
        }
    }

    /// The servo, after LIGGGHTS's checks of its settings (`at`: the style's argument).
    pub fn build(&self, a: &Args, at: usize) -> Result<MeshServo, CommandError> {
        if !self.force {
            return Err(a.error(
                at,
                "Bad registration of upcoming move. (please define 'ctrlPV' for the mesh)",
            ));
        }
        let com = self
            .com
            .ok_or_else(|| a.error(at, "please define 'com' for the mesh"))?;
        let vel_max = self
            .vel_max
            .ok_or_else(|| a.error(at, "please define 'vel_max' for the mesh"))?;
        // without target_val LIGGGHTS's set point is 0 and its servo never moves
        let target = self.target.unwrap_or(0.);
        let mut s = MeshServo::new(com, self.axis, target, vel_max);
        s.set_point_var = self.target_var.clone();
        for (g, given) in s.gains.iter_mut().zip(self.gains) {
            if let Some(v) = given {
                *g = v;
            }
        }
        s.auto = self.auto;
        s.ratio = self.ratio;
        if s.auto {
            if s.ratio == 0. {
                return Err(a.error(
                    at,
                    "please define 'ratio' for the mesh, since you use the auto mode",
                ));
            }
        } else {
            if s.gains.iter().any(|g| *g < 0.) {
                return Err(a.error(at, "kp, ki, and kd >= 0 required."));
            }
            if s.gains.iter().all(|g| *g == 0.) {
                return Err(a.error(
                    at,
                    "kp, ki, and kd are zero. Please set a valid configuration",
                ));
            }
        }
        Ok(s)
    }
}

/// A run's init: each servo's variable set point names an equal-style variable, as
/// LIGGGHTS's servo module checks it.
pub fn check_variables(ctx: &Ctx) -> Result<(), crate::engine::error::EngineError> {
    for f in &ctx.sim.fixes {
        let Some(name) = (f.kind.mesh())
            .and_then(|m| m.servo.as_ref())
            .and_then(|s| s.set_point_var.as_deref())
        else {
            continue;
        };
        match ctx.vars.get(name).map(|v| v.style) {
            None => {
                return Err(format!(
                    "Fix mesh/surface/stress/servo (id {}): Variable name does not exist",
                    f.id
                )
                .into())
            }
            Some(crate::lang::variables::Style::Equal) => {}
            Some(_) => {
                return Err(format!(
                    "Fix mesh/surface/stress/servo (id {}): Variable is invalid style",
                    f.id
                )
                .into())
            }
        }
    }
    Ok(())
}
