//! What a formula sees while it is evaluated: the deck's variables, the files and
//! environment, and the engine's state (thermo values, computes, fixes, groups, atoms).

use std::collections::HashMap;
use std::rc::Rc;

use crate::engine::error::EngineError;
use crate::engine::sim::{Simulation, VariableSource};
use crate::lang::error::VariableError;
use crate::lang::expr::{self, Expr, ExprContext, RefKind};
use crate::lang::system::{Mode, System};
use crate::lang::variables::{Style, Value, Variables};
use crate::util::format::g_precision;
use crate::util::numbers::c_atof;
use crate::util::random::{check_seed, RanMars};

/// An evaluation context borrowing the interpreter's parts.
pub struct Scope<'a> {
    /// The deck's variables (and the formula random-number generators).
    pub vars: &'a mut Variables,
    /// Files and environment.
    pub sys: &'a mut System,
    /// The simulation's state.
    pub sim: &'a Simulation,
    active: Vec<String>,
    /// Per-atom vectors evaluated during this scope (atom-style variables `v_name`,
    /// per-atom computes `c_ID`), so a formula reading them for every atom evaluates each
    /// once.
    per_atom: HashMap<String, Rc<Vec<f64>>>,
}

impl<'a> Scope<'a> {
    /// A scope over the interpreter's variables, system and simulation.
    pub fn new(vars: &'a mut Variables, sys: &'a mut System, sim: &'a Simulation) -> Scope<'a> {
        Scope {
            vars,
            sys,
            sim,
            active: Vec::new(),
            per_atom: HashMap::new(),
        }
    }

    /// The values of atom-style variable `name` for every particle (particle order).
    pub fn atom_variable(&mut self, name: &str) -> Result<Rc<Vec<f64>>, VariableError> {
        let key = format!("v_{name}");
        if let Some(v) = self.per_atom.get(&key) {
            return Ok(v.clone());
        }
        let formula = match self.vars.get(name) {
            None => return Err(VariableError::NoSuchVariable(name.to_string())),
            Some(v) if v.style != Style::Atom => {
                return Err(VariableError::WrongStyle {
                    name: name.to_string(),
                    wanted: "atom",
                })
            }
            Some(_) => self.vars.atom_formula(name).expect("atom style"),
        };
        if self.active.iter().any(|a| a == name) {
            return Err(VariableError::Circular);
        }
        self.active.push(name.to_string());
        let result = (|| -> Result<Vec<f64>, VariableError> {
            let e = Expr::parse_atom(&formula, self)?;
            let n = self.sim.particles.len();
            Ok(e.eval_atoms(self, n)?)
        })();
        self.active.pop();
        let values = Rc::new(result?);
        self.per_atom.insert(key, values.clone());
        Ok(values)
    }

    /// The per-atom values of compute `id` (cached for this scope) and its column.
    fn atom_compute(
        &mut self,
        id: &str,
        i: Option<usize>,
    ) -> Result<(Rc<Vec<f64>>, usize, usize), VariableError> {
        let c = self
            .sim
            .computes
            .iter()
            .find(|c| c.id == id)
            .ok_or("Invalid compute ID in variable formula")?;
        let col = crate::engine::computes::column_of(c, i)?;
        let cols = c.per_atom_columns();
        let key = format!("c_{id}");
        if let Some(v) = self.per_atom.get(&key) {
            return Ok((v.clone(), cols, col));
        }
        let sim = self.sim;
        let data = Rc::new(c.per_atom(sim, self)?.values);
        self.per_atom.insert(key, data.clone());
        Ok((data, cols, col))
    }

    /// An equal-style variable's value as LIGGGHTS's `compute_equal` gives it (no text
    /// round trip).
    pub fn equal_variable(&mut self, name: &str) -> Result<f64, VariableError> {
        match self.vars.get(name) {
            None => return Err(VariableError::NoSuchVariable(name.to_string())),
            Some(v) if matches!(v.style, Style::Atom | Style::AtomFile) => {
                return Err(VariableError::WrongStyle {
                    name: name.to_string(),
                    wanted: "equal",
                })
            }
            _ => {}
        }
        match self.vars.retrieve(name, self.sys) {
            None => Err(VariableError::Invalid(format!(
                "Variable {name}: invalid evaluation"
            ))),
            Some(Value::Text(t)) => Ok(c_atof(&t)),
            Some(Value::Formula(f)) => {
                if self.active.iter().any(|a| a == name) {
                    return Err(VariableError::Circular);
                }
                self.active.push(name.to_string());
                let r = expr::evaluate(&f, self).map_err(VariableError::from);
                self.active.pop();
                r
            }
        }
    }

    /// What to answer when a formula asks for state the engine does not have yet: in check
    /// mode "unknown" (a real run might have it), else LIGGGHTS's own message.
    fn no_state(&self, error: VariableError) -> VariableError {
        match self.sys.mode {
            Mode::Check => VariableError::KnownWhenRun,
            Mode::Run => error,
        }
    }
}

impl ExprContext for Scope<'_> {
    fn variable(
        &mut self,
        name: &str,
        index: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, VariableError> {
        let Some(var) = self.vars.get(name) else {
            return Err("Invalid variable name in variable formula".into());
        };
        if self.active.iter().any(|a| a == name) {
            return Err(VariableError::Circular);
        }
        match (var.style, index) {
            (Style::Atom | Style::AtomFile, None) if atom.is_none() => {
                Err("Atom-style variable in equal-style variable formula".into())
            }
            (Style::Atom, None) => {
                let i = atom.expect("checked above");
                if self.sys.mode == Mode::Check {
                    return Err(VariableError::KnownWhenRun);
                }
                Ok(self.atom_variable(name)?[i])
            }
            (Style::Atom, Some(id)) => {
                if self.sys.mode == Mode::Check {
                    return Err(VariableError::KnownWhenRun);
                }
                let p = &self.sim.particles;
                let i =
                    p.id.iter()
                        .position(|&t| t == id as i64)
                        .ok_or("Variable atom ID is not currently defined")?;
                Ok(self.atom_variable(name)?[i])
            }
            (Style::AtomFile, _) => Err(self.no_state(VariableError::Unsupported(
                "atomfile-style variables".into(),
            ))),
            (_, Some(_)) => Err("Mismatched variable in variable formula".into()),
            (_, None) => match self.vars.retrieve(name, self.sys) {
                None => Err("Invalid variable evaluation in variable formula".into()),
                Some(Value::Text(t)) => Ok(c_atof(&t)),
                Some(Value::Formula(f)) => {
                    self.active.push(name.to_string());
                    let result = expr::evaluate(&f, self).map_err(VariableError::from);
                    self.active.pop();
                    // LIGGGHTS hands the value over as %.15g text read back with atof
                    result.map(|x| c_atof(&g_precision(x, 15)))
                }
            },
        }
    }

    fn thermo(&mut self, name: &str) -> Result<f64, VariableError> {
        if !crate::engine::thermo::THERMO_KEYWORDS.contains(&name) {
            return Err("Invalid thermo keyword in variable formula".into());
        }
        if self.sys.mode == Mode::Check {
            return Err(VariableError::KnownWhenRun);
        }
        let sim = self.sim;
        // LIGGGHTS's rules for keywords that need thermo's computes or a run
        if matches!(name, "ke" | "erotate") && !sim.thermo.fields.iter().any(|f| f.keyword == name)
        {
            return Err(
                format!("Thermo keyword in variable requires thermo to use/init {name}").into(),
            );
        }
        let timed = [
            "elapsed",
            "elaplong",
            "cpu",
            "cu",
            "tpcpu",
            "spcpu",
            "cpuremain",
        ];
        if sim.run_bounds.is_none() && timed.contains(&name) {
            return Err("This variable thermo keyword cannot be used between runs".into());
        }
        sim.thermo_value(name, self).ok_or_else(|| {
            VariableError::Unsupported(format!("thermo keyword {name} in a formula"))
        })
    }

    fn compute(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, VariableError> {
        if self.sys.mode == Mode::Check {
            return Err(VariableError::KnownWhenRun);
        }
        if j.is_some() {
            return Err(VariableError::Unsupported(format!("c_{id}[i][j]")));
        }
        if let Some(a) = atom {
            let is_per_atom = self
                .sim
                .computes
                .iter()
                .any(|c| c.id == id && c.per_atom_columns() > 0);
            if is_per_atom {
                let (data, cols, col) = self.atom_compute(id, i)?;
                return Ok(data[a * cols + col]);
            }
        }
        if !self.sim.computes.iter().any(|c| c.id == id) {
            return Err("Invalid compute ID in variable formula".into());
        }
        let sim = self.sim;
        Ok(sim.compute_value(id, i, self)?)
    }

    fn fix(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, VariableError> {
        if self.sys.mode == Mode::Check {
            return Err(VariableError::KnownWhenRun);
        }
        if !self.sim.fixes.iter().any(|f| f.id == id) {
            return Err("Invalid fix ID in variable formula".into());
        }
        if let (Some(i), Some(j)) = (i, j) {
            if atom.is_none() {
                return Ok(self.sim.fix_array_value(id, i, j)?);
            }
            return Err(VariableError::Unsupported(format!("f_{id}[i][j]")));
        }
        // LIGGGHTS's variables read a fix's global scalar before its per-atom vector
        let scalar_first = i.is_none()
            && self.sim.fixes.iter().any(|f| {
                f.id == id
                    && matches!(&f.kind, crate::engine::fixes::FixKind::Style(s) if s.scalar_before_per_atom())
            });
        let per_atom = !scalar_first && crate::engine::fix_columns::column(self.sim, id, i).is_ok();
        match atom {
            Some(a) if per_atom => {
                let key = format!("f_{id}[{}]", i.unwrap_or(0));
                let data = match self.per_atom.get(&key) {
                    Some(v) => v.clone(),
                    None => {
                        let (data, col) = crate::engine::fix_columns::per_atom(self.sim, id, i)?;
                        let column: Vec<f64> = (0..self.sim.particles.len())
                            .map(|k| data.get(k, col))
                            .collect();
                        let column = Rc::new(column);
                        self.per_atom.insert(key, column.clone());
                        column
                    }
                };
                Ok(data[a])
            }
            None if per_atom => Err("Per-atom fix in equal-style variable formula".into()),
            _ => Ok(self.sim.fix_value(id, i)?),
        }
    }

    fn group_function(&mut self, name: &str, args: &[String]) -> Result<f64, VariableError> {
        Ok(self.sim.group_function(name, args, self.sys.mode)?)
    }

    fn special_function(
        &mut self,
        _: &str,
        _: &[String],
        _: Option<usize>,
    ) -> Result<f64, VariableError> {
        Err(self.no_state("Invalid special function in variable formula".into()))
    }

    fn atom_value(&mut self, name: &str, atom: usize) -> Result<f64, VariableError> {
        if self.sys.mode == Mode::Check || atom >= self.sim.particles.len() {
            return Err(
                self.no_state("Variable evaluation before simulation box is defined".into())
            );
        }
        Ok(crate::engine::computes::atom_keyword(
            &self.sim.particles,
            name,
            atom,
        )?)
    }

    fn atom_column(&mut self, name: &str, n: usize) -> Result<Vec<f64>, VariableError> {
        if self.sys.mode == Mode::Check || n > self.sim.particles.len() {
            return Err(
                self.no_state("Variable evaluation before simulation box is defined".into())
            );
        }
        let p = &self.sim.particles;
        let axis = |c: u8| (c - b'x') as usize;
        let b = name.as_bytes();
        let pick = |v: &[[f64; 3]], d: usize| v[..n].iter().map(|x| x[d]).collect();
        Ok(match name {
            "id" => p.id[..n].iter().map(|&t| t as f64).collect(),
            "type" => p.kind[..n].iter().map(|&t| t as f64).collect(),
            "mass" => p.mass[..n].to_vec(),
            "r" => p.radius[..n].to_vec(),
            "density" => p.density[..n].to_vec(),
            "x" | "y" | "z" => pick(&p.x, axis(b[0])),
            "vx" | "vy" | "vz" => pick(&p.v, axis(b[1])),
            "fx" | "fy" | "fz" => pick(&p.f, axis(b[1])),
            "omegax" | "omegay" | "omegaz" => pick(&p.omega, axis(b[5])),
            "tqx" | "tqy" | "tqz" => pick(&p.torque, axis(b[2])),
            _ => return (0..n).map(|i| self.atom_value(name, i)).collect(),
        })
    }

    fn variable_column(
        &mut self,
        name: &str,
        index: Option<usize>,
        n: usize,
    ) -> Result<Vec<f64>, VariableError> {
        let per_atom = self
            .vars
            .get(name)
            .is_some_and(|v| v.style == Style::Atom && index.is_none());
        if !per_atom || self.sys.mode == Mode::Check || self.active.iter().any(|a| a == name) {
            return (0..n)
                .map(|i| self.variable(name, index, Some(i)))
                .collect();
        }
        let values = self.atom_variable(name)?;
        if values.len() < n {
            return Err("Variable evaluation before simulation box is defined".into());
        }
        Ok(values[..n].to_vec())
    }

    fn compute_column(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        n: usize,
    ) -> Result<Vec<f64>, VariableError> {
        let is_per_atom = self
            .sim
            .computes
            .iter()
            .any(|c| c.id == id && c.per_atom_columns() > 0);
        if self.sys.mode == Mode::Check || j.is_some() || !is_per_atom {
            return (0..n).map(|a| self.compute(id, i, j, Some(a))).collect();
        }
        let (data, cols, col) = self.atom_compute(id, i)?;
        if data.len() < n * cols {
            return Err("Compute used in variable between runs is not current".into());
        }
        Ok((0..n).map(|a| data[a * cols + col]).collect())
    }

    fn atom_value_by_id(&mut self, name: &str, id: usize) -> Result<f64, VariableError> {
        if self.sys.mode == Mode::Check {
            return Err(VariableError::KnownWhenRun);
        }
        Ok(self.sim.atom_value_by_id(name, id)?)
    }

    fn box_exists(&self) -> bool {
        // in check mode the box never exists; formulas needing it are "unknown", not errors
        self.sys.mode == Mode::Check || self.sim.domain.exists
    }

    fn timestep(&self) -> i64 {
        self.sim.step
    }

    fn run_bounds(&self) -> Option<(i64, i64)> {
        self.sim.run_bounds
    }

    fn dt(&self) -> f64 {
        self.sim.dt
    }

    fn rng(&mut self, seed: i32, per_atom: bool) -> Result<&mut RanMars, VariableError> {
        let tolerant = self.sim.seed_tolerant;
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

    fn is_per_atom_ref(
        &mut self,
        kind: RefKind,
        name: &str,
        i: Option<usize>,
        _j: Option<usize>,
    ) -> bool {
        match kind {
            RefKind::Variable => self
                .vars
                .get(name)
                .is_some_and(|v| matches!(v.style, Style::Atom | Style::AtomFile)),
            RefKind::Compute => self
                .sim
                .computes
                .iter()
                .any(|c| c.id == name && c.per_atom_columns() > 0),
            RefKind::Fix => crate::engine::fix_columns::column(self.sim, name, i).is_ok(),
        }
    }
}

impl VariableSource for Scope<'_> {
    fn equal(&mut self, _sim: &Simulation, name: &str) -> Result<f64, EngineError> {
        Ok(self.equal_variable(name)?)
    }

    fn atom(&mut self, _sim: &Simulation, name: &str) -> Result<Vec<f64>, EngineError> {
        Ok(self.atom_variable(name)?.as_ref().clone())
    }
}

/// The deck's variables as a running simulation reads them (thermo `v_` columns, dump
/// `v_` columns, fixes and computes with variable inputs): each request evaluates in a
/// fresh [`Scope`] over the simulation's current state.
pub struct RunVariables<'a> {
    /// The deck's variables.
    pub vars: &'a mut Variables,
    /// Files and environment.
    pub sys: &'a mut System,
    /// Per-atom values kept between requests while the caller holds the particles still
    /// (see [`VariableSource::hold`]).
    held: Option<HashMap<String, Rc<Vec<f64>>>>,
}

impl<'a> RunVariables<'a> {
    /// The deck's variables over a running simulation, each request in a fresh scope.
    pub fn new(vars: &'a mut Variables, sys: &'a mut System) -> RunVariables<'a> {
        RunVariables {
            vars,
            sys,
            held: None,
        }
    }

    /// `f` in a scope over `sim` that starts from the per-atom values held so far and, while
    /// holding, keeps what it evaluated for the next request.
    fn in_scope<R>(&mut self, sim: &Simulation, f: impl FnOnce(&mut Scope) -> R) -> R {
        let mut scope = Scope::new(self.vars, self.sys, sim);
        if let Some(held) = self.held.as_mut() {
            scope.per_atom = std::mem::take(held);
        }
        let result = f(&mut scope);
        if let Some(held) = self.held.as_mut() {
            *held = std::mem::take(&mut scope.per_atom);
        }
        result
    }
}

/// Whether every formula of the deck gives the same values when evaluated twice over the
/// same particles: no random draws (each evaluation draws anew) and no region masks (a
/// dynamic region may move between two requests).
fn formulas_repeatable(vars: &Variables) -> bool {
    vars.names().into_iter().all(|name| {
        let formula = vars.get(name).and_then(|v| v.formula()).unwrap_or("");
        !(formula.contains("random") || formula.contains("normal") || formula.contains("mask"))
    })
}

impl VariableSource for RunVariables<'_> {
    fn substitute(&mut self, sim: &Simulation, text: &str) -> Result<String, EngineError> {
        use crate::lang::line::SubstitutionError;
        let vars = &mut *self.vars;
        let sys = &mut *self.sys;
        crate::lang::line::substitute(
            text,
            |r| match r {
                crate::lang::line::VarRef::Named(name) => match vars.retrieve(name, sys) {
                    None => Err(SubstitutionError::Undefined),
                    Some(Value::Text(t)) => Ok(t),
                    Some(Value::Formula(f)) => {
                        let mut scope = Scope::new(vars, sys, sim);
                        Ok(g_precision(expr::evaluate(&f, &mut scope)?, 15))
                    }
                },
                crate::lang::line::VarRef::Immediate(e) => {
                    let mut scope = Scope::new(vars, sys, sim);
                    Ok(g_precision(expr::evaluate(e, &mut scope)?, 20))
                }
            },
            |_| {},
        )
        .map_err(|e| EngineError::Invalid(e.message))
    }

    fn equal(&mut self, sim: &Simulation, name: &str) -> Result<f64, EngineError> {
        Ok(self.in_scope(sim, |scope| scope.equal_variable(name))?)
    }

    fn atom(&mut self, sim: &Simulation, name: &str) -> Result<Vec<f64>, EngineError> {
        let values = self.in_scope(sim, |scope| scope.atom_variable(name))?;
        Ok(values.as_ref().clone())
    }

    fn hold(&mut self, on: bool) {
        self.held = (on && formulas_repeatable(self.vars)).then(HashMap::new);
    }
}
