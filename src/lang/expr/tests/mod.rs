// expected values are copied digit for digit from LIGGGHTS's %.17g output (PI included)
#![allow(clippy::excessive_precision, clippy::approx_constant)]

use super::*;

mod atom_style;
mod equal;
mod errors;
mod syntax;

// the messages, to check that each error still reads as LIGGGHTS's
const SYNTAX: &str = "Invalid syntax in variable formula";
const BAD_MATH: &str = "Invalid math function in variable formula";
const BAD_NAME: &str = "Invalid math/group/special function in variable formula";
const NO_BOX: &str = "Variable evaluation before simulation box is defined";
const BOOLEAN: &str = "Invalid Boolean syntax in if command";
const TOO_DEEP: &str = "Variable formula is nested too deeply";

const S: i32 = 15485863;

/// A small world: variable `a` = 2, compute `x` (c_x = 7, c_x[i] = 7 + i), fix `y`
/// (8), two atoms at x = 0.1 and 0.4 (IDs 1 and 2), group `all`, one random generator
/// per style (prime seeds required, as in LIGGGHTS).
struct World {
    equal_rng: Option<RanMars>,
    atom_rng: Option<RanMars>,
    step: i64,
    run: Option<(i64, i64)>,
    dt: f64,
    has_box: bool,
    lookups: Vec<String>,
}

fn world() -> World {
    World {
        equal_rng: None,
        atom_rng: None,
        step: 0,
        run: None,
        dt: 1e-8,
        has_box: true,
        lookups: Vec::new(),
    }
}

const XS: [f64; 2] = [0.1, 0.4];

impl ExprContext for World {
    fn variable(
        &mut self,
        name: &str,
        index: Option<usize>,
        _: Option<usize>,
    ) -> Result<f64, VariableError> {
        self.lookups.push(format!("v_{name}"));
        match (name, index) {
            ("a", None) => Ok(2.0),
            ("a", Some(_)) => Err("Mismatched variable in variable formula".into()),
            ("later", None) => Err(VariableError::KnownWhenRun),
            _ => Err("Invalid variable name in variable formula".into()),
        }
    }
    fn thermo(&mut self, name: &str) -> Result<f64, VariableError> {
        self.lookups.push(name.to_string());
        match name {
            "step" => Ok(self.step as f64),
            "atoms" => Ok(2.0),
            "dt" => Ok(self.dt),
            _ => Err("Invalid thermo keyword in variable formula".into()),
        }
    }
    fn compute(
        &mut self,
        id: &str,
        i: Option<usize>,
        _: Option<usize>,
        _: Option<usize>,
    ) -> Result<f64, VariableError> {
        self.lookups.push(format!("c_{id}"));
        match id {
            "x" => Ok(7.0 + i.unwrap_or(0) as f64),
            _ => Err("Invalid compute ID in variable formula".into()),
        }
    }
    fn fix(
        &mut self,
        id: &str,
        _: Option<usize>,
        _: Option<usize>,
        _: Option<usize>,
    ) -> Result<f64, VariableError> {
        match id {
            "y" => Ok(8.0),
            _ => Err("Invalid fix ID in variable formula".into()),
        }
    }
    fn group_function(&mut self, name: &str, args: &[String]) -> Result<f64, VariableError> {
        self.lookups.push(format!("{name}({})", args.join(",")));
        if args.first().map(String::as_str) != Some("all") {
            return Err("Group ID in variable formula does not exist".into());
        }
        match (name, args.len()) {
            ("count", 1) => Ok(2.0),
            ("xcm", 2) if args[1] == "x" => Ok(0.25),
            _ => Err("Invalid group function in variable formula".into()),
        }
    }
    fn special_function(
        &mut self,
        name: &str,
        args: &[String],
        atom: Option<usize>,
    ) -> Result<f64, VariableError> {
        match (name, atom) {
            ("gmask", Some(_)) if args == ["all"] => Ok(1.0),
            ("sum", None) if args == ["c_x"] => Ok(21.0),
            _ => Err("Invalid special function in variable formula".into()),
        }
    }
    fn atom_value(&mut self, name: &str, atom: usize) -> Result<f64, VariableError> {
        match name {
            "x" => Ok(XS[atom]),
            "id" => Ok(atom as f64 + 1.0),
            _ => Ok(0.0),
        }
    }
    fn atom_value_by_id(&mut self, name: &str, id: usize) -> Result<f64, VariableError> {
        match (name, id) {
            ("x", 1 | 2) => Ok(XS[id - 1]),
            ("x", _) => Ok(0.0),
            _ => Err("Invalid atom vector in variable formula".into()),
        }
    }
    fn box_exists(&self) -> bool {
        self.has_box
    }
    fn timestep(&self) -> i64 {
        self.step
    }
    fn run_bounds(&self) -> Option<(i64, i64)> {
        self.run
    }
    fn dt(&self) -> f64 {
        self.dt
    }
    fn rng(&mut self, seed: i32, per_atom: bool) -> Result<&mut RanMars, VariableError> {
        let slot = if per_atom {
            &mut self.atom_rng
        } else {
            &mut self.equal_rng
        };
        if slot.is_none() {
            crate::util::random::check_seed(i64::from(seed))?;
            *slot = Some(RanMars::new(seed)?);
        }
        Ok(slot.as_mut().expect("just made"))
    }
}

fn ev(text: &str) -> f64 {
    evaluate(text, &mut world()).unwrap_or_else(|e| panic!("{text}: {e:?}"))
}

fn fails(text: &str) -> String {
    evaluate(text, &mut world()).unwrap_err().to_string()
}

fn fails_without_box(text: &str) -> String {
    let mut w = world();
    w.has_box = false;
    evaluate(text, &mut w).unwrap_err().to_string()
}

/// What LIGGGHTS prints for `${a}` (%.15g), to compare with its output.
fn g15(x: f64) -> String {
    crate::util::format::g_precision(x, 15)
}

// Every expected value below is what Debian's liggghts 3.8.0 printed for
//   variable a equal "FORMULA"
//   print "R=${a}"
// (or the ERROR line it stopped with), unless a comment says otherwise.
