//! The analysis computes of researchers' decks still dispatched by kind: `rdf`, `slice` and
//! `pressure` (LIGGGHTS 3.8.0's compute_slice.cpp, compute_pressure.cpp): their global
//! outputs and values.

use crate::engine::computes::{Compute, ComputeKind};
use crate::engine::error::EngineError;
use crate::engine::sim::{Simulation, VariableSource};

/// `compute slice Nstart Nstop Nskip input`: every Nskip-th element of a global vector or
/// array column, from Nstart up to (not including) Nstop.
#[derive(Debug, Clone, PartialEq)]
pub struct Slice {
    /// First element (1-based).
    pub start: usize,
    /// Elements up to this one (exclusive).
    pub stop: usize,
    /// Step between elements.
    pub skip: usize,
    /// `c_ID` or `c_ID[I]`: the compute and its array column (None: its vector).
    pub compute: Option<(String, Option<usize>)>,
    /// `f_ID` or `f_ID[I]`: the fix and its array column.
    pub fix: Option<(String, Option<usize>)>,
}

impl Slice {
    /// Length of the sliced vector, as LIGGGHTS sizes it: (Nstop - Nstart) / Nskip.
    pub fn len(&self) -> usize {
        (self.stop - self.start) / self.skip
    }

    /// Whether the slice is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// `compute pressure temp-ID [ke] [pair] [virial] ...`: the pressure tensor of the kinetic
/// part (from the temperature compute) and the pair virial.
#[derive(Debug, Clone, PartialEq)]
pub struct Pressure {
    /// ID of the temperature compute.
    pub temp: String,
    /// Include the kinetic part.
    pub ke: bool,
    /// Include the pair virial.
    pub pair: bool,
}

/// Whether the compute reads the pair virial (it is tallied on the steps output reads).
pub fn reads_virial(c: &Compute) -> bool {
    matches!(&c.kind, ComputeKind::Pressure(p) if p.pair)
}

/// Whether a compute of this kind has a global scalar (kinds `computes` does not cover).
pub fn has_scalar(kind: &ComputeKind) -> bool {
    matches!(kind, ComputeKind::Pressure(_))
}

/// Length of the global vector of the kinds of this file (0: none).
pub fn vector_len(kind: &ComputeKind) -> usize {
    match kind {
        ComputeKind::Pressure(_) | ComputeKind::Temp => 6,
        ComputeKind::Slice(s) => s.len(),
        _ => 0,
    }
}

/// (rows, columns) of the compute's global array, if it has one.
pub fn array_size(c: &Compute) -> Option<(usize, usize)> {
    match &c.kind {
        ComputeKind::Rdf(r) => Some((r.nbin, r.columns())),
        _ => None,
    }
}

/// The compute's global array, row-major, and its number of columns.
pub fn global_array(c: &Compute, sim: &Simulation) -> Result<(Vec<f64>, usize), EngineError> {
    match &c.kind {
        ComputeKind::Rdf(r) => Ok((r.array(sim, c.group)?, r.columns())),
        _ => Err(format!(
            "Compute {} ({}) does not calculate a global array",
            c.id, c.style
        )
        .into()),
    }
}

/// Global scalar of `pressure` (pressure).
pub fn scalar(
    c: &Compute,
    sim: &Simulation,
    vars: &mut dyn VariableSource,
) -> Result<f64, EngineError> {
    match &c.kind {
        ComputeKind::Pressure(pr) => {
            let n = sim.dimension as usize;
            let virial = virial(sim, pr)?;
            let mut sum = 0.0;
            if pr.ke {
                let t = find_temp(sim, &pr.temp)?;
                let (_, dof, boltz) = crate::engine::temperature::temperature_parts(sim, t);
                sum = dof * boltz * t.scalar(sim, vars)?;
            }
            for v in &virial[..n] {
                sum += v;
            }
            Ok(sum / n as f64 * inverse_volume(sim))
        }
        _ => Err(format!("Compute {} ({}) does not calculate a scalar", c.id, c.style).into()),
    }
}

/// Element `index` (1-based) of the global vector of the kinds of this file.
pub fn vector(
    c: &Compute,
    index: usize,
    sim: &Simulation,
    vars: &mut dyn VariableSource,
) -> Result<f64, EngineError> {
    let k = index - 1;
    match &c.kind {
        ComputeKind::Temp => Ok(ke_tensor(sim, c.group)[k]),
        ComputeKind::Pressure(pr) => {
            let mut v = virial(sim, pr)?;
            if pr.ke {
                let t = find_temp(sim, &pr.temp)?;
                let ke = ke_tensor(sim, t.group);
                for (a, b) in v.iter_mut().zip(ke) {
                    *a += b;
                }
            }
            if sim.dimension == 2 && matches!(k, 2 | 4 | 5) {
                return Ok(0.0);
            }
            Ok(v[k] * inverse_volume(sim))
        }
        ComputeKind::Slice(s) => slice_element(s, k, sim, vars),
        _ => Err(format!("Compute {} ({}) has no global vector", c.id, c.style).into()),
    }
}

/// Element `k` (0-based) of a slice.
fn slice_element(
    s: &Slice,
    k: usize,
    sim: &Simulation,
    vars: &mut dyn VariableSource,
) -> Result<f64, EngineError> {
    let at = s.start + k * s.skip; // 1-based element of the source
    if let Some((id, col)) = &s.compute {
        let c = sim
            .computes
            .iter()
            .find(|c| &c.id == id)
            .ok_or_else(|| format!("Compute ID {id} for compute slice does not exist"))?;
        return match col {
            None => c.vector(at, sim, vars),
            Some(col) => {
                let (values, cols) = global_array(c, sim)?;
                Ok(values[(at - 1) * cols + col - 1])
            }
        };
    }
    let (id, col) = s.fix.as_ref().expect("a slice has a compute or a fix");
    let freq = crate::engine::global_values::fix_global_freq(sim, id);
    if freq == 0 {
        return Err(crate::engine::global_values::zero_freq(id));
    }
    if sim.step % freq != 0 {
        return Err("Fix used in compute slice not computed at compatible time".into());
    }
    match col {
        None => sim.fix_value(id, Some(at)),
        Some(col) => {
            let at_fix = sim.fixes.iter().find_map(|f| match &f.kind {
                crate::engine::fixes::FixKind::AveTime(a) if &f.id == id => Some(a),
                _ => None,
            });
            Ok(at_fix.and_then(|a| a.array(at, *col)).unwrap_or(0.0))
        }
    }
}

/// The temperature compute `id` of a compute pressure.
fn find_temp<'a>(sim: &'a Simulation, id: &str) -> Result<&'a Compute, EngineError> {
    sim.computes
        .iter()
        .find(|c| c.id == id && matches!(c.kind, ComputeKind::Temp))
        .ok_or_else(|| "Could not find compute pressure temperature ID".into())
}

/// The kinetic energy tensor of compute temp: sum of m v_a v_b over the group, xx yy zz xy
/// xz yz (energy).
fn ke_tensor(sim: &Simulation, group: u32) -> [f64; 6] {
    let p = &sim.particles;
    let mut t = [0.0; 6];
    for i in 0..p.len() {
        if p.mask[i] & group != 0 {
            let (m, v) = (p.mass[i], p.v[i]);
            t[0] += m * v[0] * v[0];
            t[1] += m * v[1] * v[1];
            t[2] += m * v[2] * v[2];
            t[3] += m * v[0] * v[1];
            t[4] += m * v[0] * v[2];
            t[5] += m * v[1] * v[2];
        }
    }
    t
}

/// The pair virial of the last force evaluation, summed over the particles (force length),
/// or zeros without `pair`.
fn virial(sim: &Simulation, pr: &Pressure) -> Result<[f64; 6], EngineError> {
    let mut v = [0.0; 6];
    if !pr.pair || sim.pair.is_none() {
        return Ok(v);
    }
    if sim.virial_step != Some(sim.step) {
        return Err("Virial was not tallied on needed timestep".into());
    }
    for w in &sim.virial {
        for k in 0..6 {
            v[k] += w[k];
        }
    }
    Ok(v)
}

/// 1 / volume of the box (1 / area in 2d; per volume).
fn inverse_volume(sim: &Simulation) -> f64 {
    let d = &sim.domain;
    if sim.dimension == 3 {
        1.0 / (d.length(0) * d.length(1) * d.length(2))
    } else {
        1.0 / (d.length(0) * d.length(1))
    }
}
