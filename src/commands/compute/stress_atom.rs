//! `compute stress/atom`: each particle's stress tensor times its volume, from its motion
//! and the pair virial.

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "stress/atom",
    "compute ID GROUP stress/atom [ke|pair|virial ...]",
    &[],
    "per-particle stress tensor (pressure times volume)",
);

/// `compute stress/atom`: per-particle stress times volume, xx yy zz xy xz yz (pressure
/// volume = force length), with the kinetic and/or pair-virial parts.
#[derive(Debug)]
pub struct StressAtom {
    /// Include -m v_a v_b.
    pub ke: bool,
    /// Include the pair virial -1/2 sum del_a F_b.
    pub pair: bool,
}

impl ComputeStyle for StressAtom {
    fn name(&self) -> &str {
        "stress/atom"
    }

    fn reads_virial(&self) -> bool {
        self.pair
    }

    fn per_atom_columns(&self) -> usize {
        6
    }

    fn per_atom(
        &self,
        at: &ComputeAt,
        values: &mut [f64],
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let sim = at.sim;
        if self.pair && sim.pair.is_some() && sim.virial_step != Some(sim.step) {
            return Err("Per-atom virial was not tallied on needed timestep".into());
        }
        let p = &sim.particles;
        for i in (0..p.len()).filter(|&i| at.in_group(i)) {
            let mut s = [0.0; 6];
            if self.pair {
                if let Some(w) = sim.virial.get(i) {
                    for k in 0..6 {
                        s[k] += w[k];
                    }
                }
            }
            if self.ke {
                let m = 1.0 * p.mass[i];
                let v = p.v[i];
                s[0] += m * v[0] * v[0];
                s[1] += m * v[1] * v[1];
                s[2] += m * v[2] * v[2];
                s[3] += m * v[0] * v[1];
                s[4] += m * v[0] * v[2];
                s[5] += m * v[1] * v[2];
            }
            for k in 0..6 {
                values[i * 6 + k] = -s[k];
            }
        }
        Ok(())
    }
}

/// `compute ID GROUP stress/atom [ke] [pair|virial] [bond angle dihedral improper kspace
/// fix]` (no words: all parts).
pub fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let (mut ke, mut pair) = (a.len() == 3, a.len() == 3);
    for i in 3..a.len() {
        match a.word(i)? {
            "ke" => ke = true,
            "pair" | "virial" => pair = true,
            // no bonds, angles, kspace or virial-contributing fixes exist in a granular run:
            // these parts are zero
            "bond" | "angle" | "dihedral" | "improper" | "kspace" | "fix" => {}
            _ => return Err(a.error(i, "Illegal compute stress/atom command")),
        }
    }
    Ok(Box::new(StressAtom { ke, pair }))
}
