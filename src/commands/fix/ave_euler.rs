//! `fix ave/euler` and `fix ave/euler/stress` (one style in LIGGGHTS 3.8.0): cell averages
//! of velocity, radius, volume fraction and stress every N steps, read by `dump euler/vtk`
//! and, between runs, as `f_ID[i][j]` (cell i; j = centre x y z, volume fraction, velocity
//! x y z). Defining it adds LIGGGHTS's `compute stress_faveu all stress/atom pair`.

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, Value};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::ave_euler::EulerGrid;
use crate::engine::computes::Compute;
use crate::engine::error::EngineError;
use crate::engine::fixes::{FixStep, FixStyle};
use crate::engine::particles::Particles;

/// The keywords both styles take after the obligatory ones.
const KEYWORDS: &[crate::commands::specs::Keyword] = &[kw(
    "basevolume_region",
    &[arg("REGION", Value::Id("region"))],
    "correct cell volumes by a region's share (not supported yet)",
)];

/// The declared signature of `ave/euler`.
pub const SPEC: Spec = style(
    "fix",
    "ave/euler",
    "fix ID GROUP ave/euler nevery N cell_size_relative C parallel yes|no",
    KEYWORDS,
    "cell averages (velocity, radius, volume fraction, stress) every N steps on cells C max contact distances wide; dump euler/vtk, f_ID[i][1..7] between runs",
);

/// The declared signature of `ave/euler/stress` (the same fix in LIGGGHTS 3.8.0).
pub const STRESS: Spec = style(
    "fix",
    "ave/euler/stress",
    "fix ID GROUP ave/euler/stress nevery N cell_size_relative C parallel yes|no",
    KEYWORDS,
    "the same cell averages as fix ave/euler",
);

/// The ID of the stress compute the fix adds, as LIGGGHTS names it.
pub const STRESS_COMPUTE: &str = "stress_faveu";

/// One `fix ave/euler`.
#[derive(Debug, Clone)]
pub struct AveEuler {
    /// The style name as written.
    pub style: String,
    /// Average every this many steps.
    pub every: i64,
    /// Cell size in largest contact distances.
    pub relative: f64,
    /// `parallel yes`: LIGGGHTS's per-process grids (pressure not recomputed after scaling).
    pub parallel: bool,
    /// The grid and its last averages.
    pub grid: EulerGrid,
    /// Velocities after the forces of an averaging step, before the second half-kick (what
    /// LIGGGHTS's ghost atoms carry at its end).
    pub ghost_v: Vec<[f64; 3]>,
}

impl AveEuler {
    /// Bins and averages with the step's virial.
    fn evaluate(&mut self, p: &Particles, at: &FixStep) {
        let (lo, hi) = (at.domain.lo, at.domain.hi);
        self.grid.setup_bins(lo, hi, self.relative, at.contact);
        let stress: Vec<[f64; 6]> = at.virial.iter().map(|w| w.map(|x| -(0.0 + x))).collect();
        self.grid.average(
            p,
            at.group,
            &stress,
            &self.ghost_v,
            at.domain,
            self.parallel,
        );
    }
}

impl FixStyle for AveEuler {
    fn name(&self) -> &str {
        &self.style
    }

    fn setup_values(&mut self, p: &Particles, at: &FixStep) {
        self.ghost_v.clear();
        self.evaluate(p, at);
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        if at.step % self.every == 0 {
            self.ghost_v.clone_from(&p.v);
        }
    }

    fn end_of_step(&mut self, p: &mut Particles, at: &FixStep) {
        if at.step % self.every == 0 {
            self.evaluate(p, at);
        }
    }

    fn wants_virial(&self, step: i64) -> bool {
        step % self.every == 0
    }

    fn array_value(&self, i: usize, j: usize, in_run: bool) -> Option<Result<f64, EngineError>> {
        if in_run {
            return Some(Err(EngineError::Unsupported(format!(
                "fix {} values during a run (LIGGGHTS 3.8.0 divides by the \
                 fix's zero output interval there and crashes); read them between runs",
                self.style
            ))));
        }
        if !(1..=7).contains(&j) || i == 0 {
            return Some(Err(EngineError::Invalid(
                "Variable formula fix array is accessed out-of-range".into(),
            )));
        }
        Some(Ok(self.grid.array(i - 1, j - 1)))
    }
}

/// `fix ID GROUP ave/euler nevery N cell_size_relative C parallel yes|no
/// [basevolume_region R]`, with LIGGGHTS's errors; adds the stress compute.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let own = |m: &str| format!("Fix {} (id {}): {m}", fix.style, fix.id);
    if a.len() < 6 {
        return Err(a.error(2, "Illegal fix ave/pic command"));
    }
    let expect = |i: usize, word: &str| -> Result<(), CommandError> {
        if i >= a.len() || a.word(i)? != word {
            let at = i.min(a.len() - 1);
            return Err(a.error(at, own(&format!("expecting keyword '{word}'"))));
        }
        Ok(())
    };
    expect(3, "nevery")?;
    let every = a.int32(4)?;
    if every < 1 {
        return Err(a.error(4, own("'nevery' > 0 required")));
    }
    expect(5, "cell_size_relative")?;
    let relative = a.real(6)?;
    if relative < 1.0 {
        return Err(a.error(6, own("'cell_size_relative' > 1 required")));
    }
    expect(7, "parallel")?;
    let parallel = match a.word(8)? {
        "yes" => true,
        "no" => false,
        _ => return Err(a.error(8, own("expecting 'yes' or 'no' after 'parallel'"))),
    };
    let i = 9;
    if i < a.len() {
        match a.word(i)? {
            "basevolume_region" => {
                let id = a.word(i + 1)?;
                if ctx.sim.regions.find(id).is_none() {
                    return Err(a.error(i + 1, own("region ID does not exist")));
                }
                return Err(a.unsupported(i, &format!("fix {} basevolume_region", fix.style)));
            }
            w => {
                return Err(a.error(
                    i,
                    own(&format!("unknown keyword or wrong keyword order: {w}")),
                ))
            }
        }
    }
    if ctx.sim.computes.iter().any(|c| c.id == STRESS_COMPUTE) {
        return Err(a.error(0, "Reuse of compute ID"));
    }
    ctx.sim.computes.push(Compute {
        id: STRESS_COMPUTE.into(),
        style: "stress/atom".into(),
        group: ctx.sim.group_bit("all").unwrap_or(1),
        calc: Box::new(crate::commands::compute::StressAtom {
            ke: false,
            pair: true,
        }),
    });
    Ok(Box::new(AveEuler {
        style: fix.style.to_string(),
        every,
        relative,
        parallel,
        grid: EulerGrid::default(),
        ghost_v: Vec::new(),
    }))
}
