//! Global vectors and arrays of computes and fixes, as `fix ave/time ... mode vector` reads
//! them: their sizes when a deck names them, and their values when the fix samples.

use crate::engine::computes::Compute;
use crate::engine::error::EngineError;
use crate::engine::fixes::{AveInput, AveTime, FixKind};
use crate::engine::sim::{Simulation, VariableSource};

/// What a compute or fix offers as global output, as LIGGGHTS's flags say.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GlobalShape {
    /// It has a global scalar.
    pub scalar: bool,
    /// Length of its global vector (0: none).
    pub vector: usize,
    /// (rows, columns) of its global array, if it has one.
    pub array: Option<(usize, usize)>,
}

impl Compute {
    /// The compute's global outputs.
    pub fn shape(&self) -> GlobalShape {
        GlobalShape {
            scalar: self.style().has_scalar(),
            vector: self.vector_len(),
            array: self.array_size(),
        }
    }

    /// The compute's whole global vector.
    pub fn global_vector(
        &self,
        sim: &Simulation,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<f64>, EngineError> {
        (1..=self.vector_len())
            .map(|i| self.vector(i, sim, vars))
            .collect()
    }
}

/// The global outputs of the fix `id` (None if there is no such fix).
pub fn fix_shape(sim: &Simulation, id: &str) -> Option<GlobalShape> {
    let fix = sim.fixes.iter().find(|f| f.id == id)?;
    if let Some(at) = fix.kind.style_as::<AveTime>() {
        return Some(GlobalShape {
            scalar: at.value(None).is_some(),
            vector: at.vector_len(),
            array: at.array_size(),
        });
    }
    // the other fixes' vectors are as long as their elements answer
    let vector = (1..=64)
        .take_while(|&i| sim.fix_value(id, Some(i)).is_ok())
        .count();
    Some(GlobalShape {
        scalar: sim.fix_value(id, None).is_ok(),
        vector,
        array: None,
    })
}

/// The error for reading, during a run, a fix whose output interval is 0 (`fix diam/max`):
/// LIGGGHTS 3.8.0 divides the step by that interval there and crashes.
pub fn zero_freq(id: &str) -> EngineError {
    EngineError::Unsupported(format!(
        "f_{id} during a run (LIGGGHTS 3.8.0 divides by the fix's zero output interval there \
         and crashes); read it between runs"
    ))
}

/// How often the fix `id` computes its global values (steps), for LIGGGHTS's
/// "not computed at compatible time" check.
pub fn fix_global_freq(sim: &Simulation, id: &str) -> i64 {
    match sim.fixes.iter().find(|f| f.id == id).map(|f| &f.kind) {
        Some(FixKind::Style(s)) => s.global_freq(),
        _ => 1,
    }
}

impl Simulation {
    /// The values `fix ave/time` `at` samples now: one per input in scalar mode, `rows`
    /// rows of one value per input (row-major) in vector mode.
    pub(crate) fn ave_time_values(
        &self,
        at: &AveTime,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<f64>, EngineError> {
        let Some(rows) = at.rows else {
            return at
                .inputs
                .iter()
                .map(|input| self.ave_input(input, vars))
                .collect();
        };
        let n = at.inputs.len();
        let mut out = vec![0.0; rows * n];
        // a compute's array is evaluated once per sample, as LIGGGHTS's invoked flags do
        let mut arrays: Vec<(&str, Vec<f64>, usize)> = Vec::new();
        for (j, input) in at.inputs.iter().enumerate() {
            let column: Vec<f64> = match input {
                AveInput::Compute(id, None) => self.find_compute(id)?.global_vector(self, vars)?,
                AveInput::Compute(id, Some(col)) => {
                    if !arrays.iter().any(|(a, _, _)| a == id) {
                        let c = self.find_compute(id)?;
                        let (values, cols) = c.global_array(self)?;
                        arrays.push((id, values, cols));
                    }
                    let (_, values, cols) = arrays
                        .iter()
                        .find(|(a, _, _)| a == id)
                        .expect("just evaluated");
                    (0..rows).map(|r| values[r * cols + col - 1]).collect()
                }
                AveInput::Fix(id, None) => (1..=rows)
                    .map(|r| self.fix_value(id, Some(r)))
                    .collect::<Result<_, _>>()?,
                AveInput::Fix(id, Some(col)) => {
                    let array = self
                        .fixes
                        .iter()
                        .find(|f| f.id == *id)
                        .and_then(|f| f.kind.style_as::<AveTime>());
                    let array = array.ok_or_else(|| format!("Could not find fix ID {id}"))?;
                    (1..=rows)
                        .map(|r| array.array(r, *col).unwrap_or(0.0))
                        .collect()
                }
                AveInput::Variable(name) => {
                    return Err(format!(
                        "Fix ave/time cannot use variable with vector mode (v_{name})"
                    )
                    .into())
                }
            };
            if column.len() != rows {
                return Err("Fix ave/time columns are inconsistent lengths".into());
            }
            for (r, v) in column.into_iter().enumerate() {
                out[r * n + j] = v;
            }
        }
        Ok(out)
    }

    /// The compute `id`.
    fn find_compute(&self, id: &str) -> Result<&Compute, EngineError> {
        self.computes
            .iter()
            .find(|c| c.id == id)
            .ok_or_else(|| format!("Compute ID {id} for fix ave/time does not exist").into())
    }
}

/// Whether the global vector (`column` None) or array of the compute is extensive (1),
/// intensive (0) or mixed (-1), as LIGGGHTS flags it; None where regolith does not know.
pub fn compute_ext(sim: &Simulation, c: &Compute, column: Option<usize>) -> Option<i8> {
    c.style().extensive(sim, column)
}

/// As [`compute_ext`], for a fix's global vector or array (fix ave/time only).
pub fn fix_ext(sim: &Simulation, id: &str, column: Option<usize>) -> Option<i8> {
    let at = sim
        .fixes
        .iter()
        .find(|f| f.id == id)?
        .kind
        .style_as::<AveTime>()?;
    if at.rows.is_none() {
        return (column.is_none() && at.inputs.len() > 1).then_some(-1);
    }
    let mut ext = None;
    for inp in &at.inputs {
        let e = input_ext(sim, inp)?;
        if ext.is_some_and(|x| x != e) {
            return Some(-1);
        }
        ext = Some(e);
    }
    ext
}

/// Whether `f_ID` (index None) or `f_ID[i]` is extensive, as LIGGGHTS's thermo output
/// reads the fix's extscalar, extvector and extlist for `thermo_modify norm yes`.
pub fn fix_extensive(sim: &Simulation, id: &str, index: Option<usize>) -> bool {
    let Some(fix) = sim.fixes.iter().find(|f| f.id == id) else {
        return false;
    };
    let FixKind::Style(style) = &fix.kind else {
        return false;
    };
    let Some(at) = fix.kind.style_as::<AveTime>() else {
        return style.extensive(index);
    };
    if at.rows.is_some() {
        return fix_ext(sim, id, None) == Some(1);
    }
    // scalar mode: the scalar of a single input, or the flag of input i
    let k = index.map_or(Some(0), |i| i.checked_sub(1));
    match k.and_then(|k| at.inputs.get(k)) {
        Some(AveInput::Compute(cid, col)) => sim
            .computes
            .iter()
            .find(|c| &c.id == cid)
            .is_some_and(|c| match col {
                None => c.style().extensive_scalar(),
                Some(_) => c.style().extensive(sim, None) == Some(1),
            }),
        Some(AveInput::Fix(fid, col)) => fix_extensive(sim, fid, *col),
        _ => false,
    }
}

/// The extensive flag of one vector-mode `fix ave/time` input.
pub fn input_ext(sim: &Simulation, input: &AveInput) -> Option<i8> {
    match input {
        AveInput::Compute(id, col) => {
            compute_ext(sim, sim.computes.iter().find(|c| &c.id == id)?, *col)
        }
        AveInput::Fix(id, col) => fix_ext(sim, id, *col),
        AveInput::Variable(_) => Some(0),
    }
}
