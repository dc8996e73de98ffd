//! The command registry: every command and style name LIGGGHTS 3.8.0 knows, and what regolith
//! does with each. Script-language commands are executed by the interpreter
//! ([`crate::script::interp`]); everything else arrives here as a [`CommandLine`].

pub mod args;
pub mod balance;
pub mod change_box;
pub mod compute;
pub mod compute_modify;
pub mod diverged;
pub mod dump;
pub mod error;
pub mod fix;
pub mod fix_modify;
pub mod fix_modify_servo;
pub mod fix_state;
pub mod group_functions;
pub mod group_variable;
pub mod logs;
pub mod material_check;
pub mod names;
pub mod out_of_scope;
pub mod processors;
pub mod ranks;
pub mod read_dump;
pub mod region_tet;
pub mod registry;
pub mod replicate;
pub mod set;
pub mod sim_run;
pub mod sim_setup;
pub mod specs;
pub mod style_table;
pub mod suggest;
pub mod system_init;
pub mod velocity_vars;
pub mod write_dump;

use crate::engine::error::EngineError;
use crate::engine::sim::Simulation;
use crate::error::{Diagnostic, Location};
use crate::io::output::Output;
use crate::lang::line::Word;
use crate::lang::system::{Mode, System};
use crate::lang::variables::Variables;

pub use args::Args;
pub use error::{At, CommandError};
pub use registry::validate_names;

/// What a command handler may touch.
pub struct Ctx<'a> {
    /// The simulation.
    pub sim: &'a mut Simulation,
    /// Files and mode.
    pub sys: &'a mut System,
    /// Screen and log.
    pub out: &'a mut Output,
    /// The deck's variables (for commands that evaluate them while running).
    pub vars: &'a mut Variables,
}

impl Ctx<'_> {
    /// Evaluate variable region radii before regions are matched: at most once per step, or
    /// unconditionally (`definition`) when a region is defined.
    pub fn reshape_regions(&mut self, definition: bool) -> std::result::Result<(), EngineError> {
        if self.sys.mode != Mode::Run || self.sim.regions.list.iter().all(|r| !r.is_dynamic()) {
            return Ok(());
        }
        let step = (!definition).then_some(self.sim.step);
        let mut regions = std::mem::take(&mut self.sim.regions);
        let result = {
            let mut scope = crate::lang::scope::Scope::new(self.vars, self.sys, self.sim);
            regions.reshape(step, &mut |name| {
                scope
                    .equal_variable(name)
                    .map_err(|e| EngineError::Invalid(e.to_string()))
            })
        };
        self.sim.regions = regions;
        result
    }

    /// Print an informational line to screen and log (not in check mode).
    pub fn say(&mut self, text: &str) {
        if self.sys.mode == Mode::Run {
            self.out.both(text);
        }
    }
}

/// One command after substitution and word splitting.
#[derive(Debug, Clone)]
pub struct CommandLine {
    /// The words, the command name first.
    pub words: Vec<Word>,
    /// The line as executed (comment removed, variables substituted).
    pub text: String,
    /// Where it came from.
    pub location: Location,
}

impl CommandLine {
    /// The command's name.
    pub fn name(&self) -> &str {
        &self.words[0].text
    }

    /// Argument `i` (0-based, after the name).
    pub fn arg(&self, i: usize) -> Option<&str> {
        self.words.get(i + 1).map(|w| w.text.as_str())
    }

    /// Number of arguments after the name.
    pub fn nargs(&self) -> usize {
        self.words.len() - 1
    }

    /// Byte range of argument `i` in [`CommandLine::text`] (the last word if `i` is past the end).
    pub fn span(&self, i: usize) -> (usize, usize) {
        let w = self
            .words
            .get(i.saturating_add(1))
            .unwrap_or_else(|| self.words.last().expect("a command has a name"));
        (w.start, w.end)
    }
}

/// Everything below the script language. Until the simulation engine lands it knows which
/// commands exist and reports the ones it cannot run yet.
pub struct Engine {
    /// The simulation the commands build and run.
    pub sim: Simulation,
    /// Check mode only: an unsupported command was skipped, so the engine state no longer
    /// matches what LIGGGHTS would have; later commands are only name-checked.
    pub diverged: bool,
}

impl Default for Engine {
    fn default() -> Self {
        Engine::new()
    }
}

impl Engine {
    /// An engine with no box and LIGGGHTS's default settings.
    pub fn new() -> Engine {
        let mut sim = Simulation::default();
        // LIGGGHTS's computes of every deck (its Output constructor makes them)
        sim.computes = vec![
            crate::commands::compute::thermo_temp(),
            crate::commands::compute::thermo_kin_eng(),
        ];
        Engine {
            sim,
            diverged: false,
        }
    }

    /// The `clear` command: forget the simulation, keep the variables and settings.
    pub fn clear(&mut self) {
        // command-line switches survive `clear`
        let (tolerant, zero_e) = (self.sim.seed_tolerant, self.sim.zero_restitution);
        let accel = self.sim.accel.clone();
        let observer = self.sim.observer.take();
        // the ranks of the run survive it too (LIGGGHTS's new Comm keeps its world)
        let (nprocs, per_node) = (self.sim.procs.nprocs, self.sim.procs.procs_per_node);
        let reported = std::mem::take(&mut self.sim.procs.reported);
        *self = Engine::new();
        self.sim.procs.nprocs = nprocs;
        self.sim.procs.procs_per_node = per_node;
        self.sim.procs.reported = reported;
        self.sim.seed_tolerant = tolerant;
        self.sim.zero_restitution = zero_e;
        self.sim.accel = accel;
        self.sim.observer = observer;
    }

    /// Whether `create_box` (or a restart/data file) has defined the simulation box.
    pub fn box_exists(&self) -> bool {
        self.sim.domain.exists
    }

    /// Execute a non-script command.
    pub fn execute(
        &mut self,
        cmd: &CommandLine,
        sys: &mut System,
        vars: &mut Variables,
        out: &mut Output,
    ) -> Result<(), Diagnostic> {
        let check = sys.mode == Mode::Check;
        if let Err(e) = validate_names(cmd) {
            // LIGGGHTS stops at a misspelt name too: the dry run goes on without the command,
            // so errors about the state it would have made (a `pair_coeff` after a refused
            // `pair_style`) are artefacts
            self.diverged |= check;
            return Err(e.into_diagnostic(cmd));
        }
        let args = Args { cmd };
        let mut ctx = Ctx {
            sim: &mut self.sim,
            sys,
            out,
            vars,
        };
        if let Some(run) = registry::handler(cmd.name()) {
            // the one place a command's error becomes a report pointing into its line
            let result = run(&args, &mut ctx)
                .map_err(|e| out_of_scope::explain(cmd, e).into_diagnostic(cmd));
            if let Err(d) = &result {
                if check && d.severity == crate::error::Severity::Unsupported {
                    self.diverged = true;
                } else if check && self.diverged && !diverged::stands_alone(d) {
                    // the dry run's state no longer matches LIGGGHTS's: this error may be an
                    // artefact of something skipped earlier, so only names are held against it
                    return Ok(());
                } else if check {
                    // LIGGGHTS stops here: what follows sees a state it never reaches
                    self.diverged = true;
                }
            }
            return result;
        }
        if check {
            self.diverged = true;
        }
        let unsupported = CommandError::unsupported(registry::feature_name(cmd), At::Feature);
        Err(out_of_scope::explain(cmd, unsupported).into_diagnostic(cmd))
    }

    /// Check a command's names without executing it (supported commands pass).
    pub fn validate_names(&self, cmd: &CommandLine) -> Result<(), Diagnostic> {
        validate_names(cmd).map_err(|e| e.into_diagnostic(cmd))?;
        if registry::is_supported(cmd) {
            return Ok(());
        }
        let unsupported = CommandError::unsupported(registry::feature_name(cmd), At::Line);
        Err(out_of_scope::explain(cmd, unsupported).into_diagnostic(cmd))
    }

    /// True if a `fix property/global` with this variable name exists (the `if property_X` test).
    pub fn has_property_global(&self, name: &str) -> bool {
        self.sim.property(name).is_some()
    }

    /// Group functions of formulas (see [`Simulation::group_function`]).
    pub fn group_function(
        &self,
        name: &str,
        args: &[String],
        mode: Mode,
    ) -> Result<f64, EngineError> {
        self.sim.group_function(name, args, mode)
    }
}

impl Simulation {
    /// A thermo keyword's current value for formulas (None: not a keyword regolith evaluates).
    pub fn thermo_value(
        &self,
        name: &str,
        vars: &mut dyn crate::engine::sim::VariableSource,
    ) -> Option<f64> {
        crate::engine::thermo::keyword_value(name, self, &self.thermo, vars)
    }

    /// Per-atom keyword of the atom with ID `id` (`x[N]` in formulas).
    pub fn atom_value_by_id(&self, name: &str, id: usize) -> Result<f64, EngineError> {
        let p = &self.particles;
        let i =
            p.id.iter()
                .position(|&t| t == id as i64)
                .ok_or("Variable atom ID is not currently defined")?;
        crate::engine::computes::atom_keyword(p, name, i)
    }
}
