//! What a formula sees while it is evaluated: the deck's variables, the files and
//! environment, and the engine's state (thermo values, computes, fixes, groups, atoms).

use crate::commands::Engine;
use crate::script::expr::{self, ExprContext};
use crate::script::format::g_precision;
use crate::script::random::{check_seed, RanMars};
use crate::script::system::{Mode, System};
use crate::script::variables::{c_atof, Style, Value, Variables};

/// Error text meaning "only a real run can know this" (check mode).
pub const UNKNOWN_QUERY: &str = "\u{0}value known only when the deck runs";

/// An evaluation context borrowing the interpreter's parts.
pub struct Scope<'a> {
    /// The deck's variables (and the formula random-number generators).
    pub vars: &'a mut Variables,
    /// Files and environment.
    pub sys: &'a mut System,
    /// The engine's state.
    pub engine: &'a Engine,
    active: Vec<String>,
}

impl<'a> Scope<'a> {
    /// A scope over the interpreter's variables, system and engine.
    pub fn new(vars: &'a mut Variables, sys: &'a mut System, engine: &'a Engine) -> Scope<'a> {
        Scope {
            vars,
            sys,
            engine,
            active: Vec::new(),
        }
    }

    /// What to answer when a formula asks for state the engine does not have yet: in check
    /// mode "unknown" (a real run might have it), else LIGGGHTS's own message.
    fn no_state(&self, message: &str) -> String {
        match self.sys.mode {
            Mode::Check => UNKNOWN_QUERY.to_string(),
            Mode::Run => message.to_string(),
        }
    }
}

impl ExprContext for Scope<'_> {
    fn variable(
        &mut self,
        name: &str,
        index: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, String> {
        let Some(var) = self.vars.get(name) else {
            return Err("Invalid variable name in variable formula".into());
        };
        if self.active.iter().any(|a| a == name) {
            return Err("Variable has circular dependency".into());
        }
        match (var.style, index) {
            (Style::Atom | Style::AtomFile, None) if atom.is_none() => {
                Err("Atom-style variable in equal-style variable formula".into())
            }
            (Style::Atom | Style::AtomFile, _) => {
                Err(self.no_state("Atom-style variables need atoms"))
            }
            (_, Some(_)) => Err("Mismatched variable in variable formula".into()),
            (_, None) => match self.vars.retrieve(name, self.sys) {
                None => Err("Invalid variable evaluation in variable formula".into()),
                Some(Value::Text(t)) => Ok(c_atof(&t)),
                Some(Value::Formula(f)) => {
                    self.active.push(name.to_string());
                    let result = expr::evaluate(&f, self).map_err(|e| e.message);
                    self.active.pop();
                    // LIGGGHTS hands the value over as %.15g text read back with atof
                    result.map(|x| c_atof(&g_precision(x, 15)))
                }
            },
        }
    }

    fn thermo(&mut self, name: &str) -> Result<f64, String> {
        if !crate::commands::THERMO_KEYWORDS.contains(&name) {
            return Err("Invalid thermo keyword in variable formula".into());
        }
        if self.sys.mode == Mode::Check {
            return Err(UNKNOWN_QUERY.to_string());
        }
        self.engine
            .thermo_value(name)
            .ok_or_else(|| format!("thermo keyword {name} in a formula: not supported yet"))
    }

    fn compute(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, String> {
        if self.sys.mode == Mode::Check {
            return Err(UNKNOWN_QUERY.to_string());
        }
        if j.is_some() || atom.is_some() {
            return Err(format!(
                "c_{id} with array or per-atom access: not supported yet"
            ));
        }
        if !self.engine.sim.computes.iter().any(|c| c.id == id) {
            return Err("Invalid compute ID in variable formula".into());
        }
        self.engine.sim.compute_value(id, i)
    }

    fn fix(
        &mut self,
        _: &str,
        _: Option<usize>,
        _: Option<usize>,
        _: Option<usize>,
    ) -> Result<f64, String> {
        Err(self.no_state("Invalid fix ID in variable formula"))
    }

    fn group_function(&mut self, name: &str, args: &[String]) -> Result<f64, String> {
        self.engine.group_function(name, args, self.sys.mode)
    }

    fn special_function(&mut self, _: &str, _: &[String], _: Option<usize>) -> Result<f64, String> {
        Err(self.no_state("Invalid special function in variable formula"))
    }

    fn atom_value(&mut self, _: &str, _: usize) -> Result<f64, String> {
        Err(self.no_state("Variable evaluation before simulation box is defined"))
    }

    fn atom_value_by_id(&mut self, name: &str, id: usize) -> Result<f64, String> {
        if self.sys.mode == Mode::Check {
            return Err(UNKNOWN_QUERY.to_string());
        }
        self.engine.atom_value_by_id(name, id)
    }

    fn box_exists(&self) -> bool {
        // in check mode the box never exists; formulas needing it are "unknown", not errors
        self.sys.mode == Mode::Check || self.engine.box_exists()
    }

    fn timestep(&self) -> i64 {
        self.engine.sim.step
    }

    fn run_bounds(&self) -> Option<(i64, i64)> {
        self.engine.sim.run_bounds
    }

    fn dt(&self) -> f64 {
        self.engine.sim.dt
    }

    fn rng(&mut self, seed: i32, per_atom: bool) -> Result<&mut RanMars, String> {
        let tolerant = self.engine.sim.seed_tolerant;
        let slot = if per_atom {
            &mut self.vars.random_atom
        } else {
            &mut self.vars.random_equal
        };
        if slot.is_none() {
            if !tolerant {
                check_seed(seed as i64)?;
            }
            *slot = Some(RanMars::new(seed)?);
        }
        Ok(slot.as_mut().expect("just made"))
    }
}
