//! Compute styles as modules: [`ComputeStyle`] is what a style may do in LIGGGHTS's phases
//! of a run and what values it offers to thermo, variables, dumps and fixes, each hook a
//! no-op (or offering nothing) unless the style overrides it. The engine reaches the style
//! a [`Compute`](super::Compute) holds through its methods, so every reader of computes
//! (thermo, formulas, dumps, `compute reduce`, `fix ave/...`) takes any style without
//! knowing it.
//!
//! A style is one file under `commands/compute/` (its arguments, its state, this trait) and
//! one row in that folder's table.

use crate::engine::error::EngineError;
use crate::engine::particles::Particles;
use crate::engine::sim::{Simulation, VariableSource};
use crate::state::local_field::LocalField;

/// What a value hook is told: the simulation as it stands and the compute's definition.
#[derive(Clone, Copy)]
pub struct ComputeAt<'a> {
    /// The simulation (particles, box, neighbour lists, fixes, other computes).
    pub sim: &'a Simulation,
    /// The compute ID.
    pub id: &'a str,
    /// Group bits of the compute (particle `i` is in the group when `p.mask[i] & group != 0`).
    pub group: u32,
}

impl ComputeAt<'_> {
    /// Whether particle `i` is in the compute's group.
    pub fn in_group(&self, i: usize) -> bool {
        self.sim.particles.mask[i] & self.group != 0
    }
}

/// How `dump local` reads a local compute's rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LocalRows {
    /// `c_ID` (the first column) or `c_ID[N]`.
    VectorOrArray,
    /// Only `c_ID[N]`: a local array even with one column.
    Array,
}

/// A compute style: the phases it hooks and the values it offers. Every hook has a default
/// that does nothing (or offers nothing), so a style writes only what it does.
pub trait ComputeStyle: Send + std::fmt::Debug {
    /// The style's name as decks write it (`ke`).
    fn name(&self) -> &str;

    /// LIGGGHTS's `init` checks at the start of every run (and of a dry run's `run`): an
    /// error stops the run with LIGGGHTS's message.
    fn init(&self, _sim: &Simulation) -> Result<(), EngineError> {
        Ok(())
    }

    /// At the start of every run, before the setup force evaluation: state the style keeps
    /// for the run (LIGGGHTS's `init`/`setup` bookkeeping); `group` is the compute's group.
    fn setup(&mut self, _p: &Particles, _group: u32) {}

    /// Whether the style has a global scalar (`c_ID` in thermo and formulas).
    fn has_scalar(&self) -> bool {
        false
    }

    /// The global scalar, in the style's units (only called when [`Self::has_scalar`]).
    fn scalar(&self, _at: &ComputeAt, _vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        Err(EngineError::Invalid(format!(
            "compute {} does not calculate a scalar",
            self.name()
        )))
    }

    /// Length of the global vector (`c_ID[N]`; 0: none).
    fn vector_len(&self) -> usize {
        0
    }

    /// Element `index` (1-based, within [`Self::vector_len`]) of the global vector.
    fn vector(
        &self,
        _at: &ComputeAt,
        _index: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        Err(EngineError::Invalid(format!(
            "compute {} does not calculate a global vector",
            self.name()
        )))
    }

    /// (rows, columns) of the global array (`c_ID[I]` read by `fix ave/time` and `compute
    /// slice`), if the style has one.
    fn array_size(&self) -> Option<(usize, usize)> {
        None
    }

    /// The global array, row-major (only called when [`Self::array_size`] is Some).
    fn array(&self, _at: &ComputeAt) -> Result<Vec<f64>, EngineError> {
        Err(EngineError::Invalid(format!(
            "compute {} does not calculate a global array",
            self.name()
        )))
    }

    /// Whether the global vector (`column` None) or an array column is extensive (1),
    /// intensive (0) or mixed (-1), as LIGGGHTS flags it; None where it does not matter.
    /// `sim` holds the other computes and fixes (a style sliced from another reads its
    /// flag).
    fn extensive(&self, _sim: &Simulation, _column: Option<usize>) -> Option<i8> {
        None
    }

    /// Whether the global scalar is extensive (LIGGGHTS's extscalar: `thermo_modify norm yes`
    /// divides it by the atom count).
    fn extensive_scalar(&self) -> bool {
        false
    }

    /// Whether the style is a temperature compute (`compute_modify`'s settings apply to
    /// it, `compute pressure` reads it).
    fn is_temperature(&self) -> bool {
        false
    }

    /// How `dump local` may read the style's local rows (None: it has none).
    fn local_rows(&self) -> Option<LocalRows> {
        None
    }

    /// The local rows now: (columns per row, values row-major).
    fn local(&self, _at: &ComputeAt) -> Result<(usize, Vec<f64>), EngineError> {
        Err(EngineError::Invalid(format!(
            "compute {} does not calculate local values",
            self.name()
        )))
    }

    /// The contact fields of a granular local compute's rows (`dump local/gran/vtk` lays
    /// them out), in column order.
    fn local_fields(&self) -> Option<&[LocalField]> {
        None
    }

    /// Whether the style re-evaluates the pair contacts at output (the force evaluation
    /// then keeps the velocities it ran with).
    fn reads_pair_contacts(&self) -> bool {
        false
    }

    /// The ID of the mesh wall fix whose contacts the style re-evaluates at output (the
    /// fix may not be unfixed while the compute exists).
    fn reads_wall(&self) -> Option<&str> {
        None
    }

    /// Per-atom values per particle (0: the style has none; 1 is read as `c_ID`, more as
    /// `c_ID[1..N]`).
    fn per_atom_columns(&self) -> usize {
        0
    }

    /// The per-atom values into `values` (row-major in particle order, `per_atom_columns`
    /// per particle, zero on entry; particles outside the group stay zero).
    fn per_atom(
        &self,
        _at: &ComputeAt,
        _values: &mut [f64],
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        Ok(())
    }

    /// Whether the style reads the per-atom pair virial (it is then tallied in the force
    /// evaluations of the steps output reads).
    fn reads_virial(&self) -> bool {
        false
    }

    /// Whether the style keeps per-particle state that copies of the particles
    /// (`replicate`) could not take over.
    fn keeps_per_atom_state(&self) -> bool {
        false
    }

    /// At the start of every step and of a run's setup, before anything moves: changes the
    /// style makes to the particles for what its last evaluation counted
    /// (`nparticles/tracer/region reset_marker yes` un-marks them).
    fn before_step(&mut self, _p: &mut Particles) {}
}

impl Simulation {
    /// The `setup` hook of every compute style, in compute order, at a run's start.
    pub(crate) fn setup_compute_styles(&mut self) {
        let p = &self.particles;
        for c in &mut self.computes {
            c.calc.setup(p, c.group);
        }
    }

    /// The `before_step` hook of every compute style, in compute order.
    pub(crate) fn before_step_compute_styles(&mut self) {
        for c in &mut self.computes {
            c.calc.before_step(&mut self.particles);
        }
    }
}
