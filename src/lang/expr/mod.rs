//! Equal- and atom-style formulas, parsed and evaluated as LIGGGHTS 3.8.0 does.
//!
//! Grammar (LIGGGHTS's `Variable::evaluate`): numbers (`2`, `.5`, `5.`, `1e-5`, read with C
//! `atof`), parentheses, the constant `PI`, references `c_ID`, `c_ID[i]`, `c_ID[i][j]`,
//! `f_ID...`, `v_name`, `v_name[i]`, math functions, group functions, special functions,
//! atom values `x[N]`, per-atom keywords (`x`, `vx`, `mass`, ...) and thermo keywords.
//! Operators by increasing precedence: `||`, `&&`, `== !=`, `< <= > >=`, `+ -`, `* / %`,
//! `^`, prefix `-` and `!`; every binary operator is left-associative, so `2^3^2` is 64 and
//! `-2^2` is 4. Dividing by zero, `%` by zero and raising to the power zero are errors.
//!
//! A bare word followed by `(` is a math, group or special function (in that order); one
//! followed by `[` is an atom value; then come the per-atom keywords, `PI`, and last the
//! thermo keywords.
//!
//! Three ways in, mirroring what LIGGGHTS does:
//! * [`evaluate`]: equal style. LIGGGHTS computes while it reads, so every lookup and every
//!   operator happens at the moment LIGGGHTS does it; errors come in LIGGGHTS's order.
//! * [`Expr::parse_atom`] then [`Expr::eval`] with `Some(atom)`: atom style. Global values
//!   are fetched once while reading, constant parts are folded, and what is left is
//!   evaluated atom by atom with the quirks of LIGGGHTS's per-atom tree walker.
//! * [`Expr::parse`]: syntax only, for checking or evaluating a formula later.
//!
//! [`evaluate_boolean`] is the separate, numbers-only evaluator of the `if` command.

use crate::util::numbers::c_atof;
use crate::util::random::RanMars;

pub use crate::lang::error::{ExprErrorKind, VariableError};

mod boolean;
mod column;
mod eval;
mod parse;

use boolean::*;
use column::*;
use eval::*;
use parse::*;

/// Error from parsing or evaluating an expression: what is wrong and where.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{kind}")]
pub struct ExprError {
    /// What went wrong; its text is LIGGGHTS's where it has one.
    pub kind: ExprErrorKind,
    /// Byte offset into the expression text of the token that caused the error.
    pub offset: usize,
}

impl ExprError {
    /// Whether only a real run can know the formula's value (check mode).
    pub fn is_known_when_run(&self) -> bool {
        matches!(
            self.kind,
            ExprErrorKind::Lookup(VariableError::KnownWhenRun)
        )
    }
}

impl From<ExprError> for VariableError {
    /// A formula's error as the error of the variable holding it (the position is dropped).
    fn from(e: ExprError) -> VariableError {
        match e.kind {
            ExprErrorKind::Lookup(v) => v,
            other => VariableError::Formula(Box::new(other)),
        }
    }
}

/// A number written in a formula; one too large for a double (`1e400`) is an error naming it,
/// not infinity.
fn literal(word: &str, offset: usize) -> Result<f64, ExprError> {
    let x = c_atof(word);
    if x.is_infinite() {
        return err(ExprErrorKind::OutOfRange(word.to_string()), offset);
    }
    Ok(x)
}

fn err<T>(kind: ExprErrorKind, offset: usize) -> Result<T, ExprError> {
    Err(ExprError { kind, offset })
}

/// Attach an offset to a context lookup's error.
fn lookup(r: Result<f64, VariableError>, offset: usize) -> Result<f64, ExprError> {
    r.map_err(|e| ExprError {
        kind: e.into(),
        offset,
    })
}

const SYNTAX: ExprErrorKind = ExprErrorKind::Syntax;
const BAD_MATH: ExprErrorKind = ExprErrorKind::BadMath;
const BAD_NAME: ExprErrorKind = ExprErrorKind::UnknownFunction;
const NO_BOX: ExprErrorKind = ExprErrorKind::NoBox;
const BOOLEAN: ExprErrorKind = ExprErrorKind::Boolean;
const TOO_DEEP: ExprErrorKind = ExprErrorKind::TooDeep;

/// Deepest parse tree accepted (keeps recursion far from the stack limit).
const MAX_DEPTH: usize = 1000;
/// Deepest nesting of parentheses and function arguments accepted.
const MAX_NESTING: usize = 200;

/// Which kind of reference a formula makes with a `c_`, `f_` or `v_` prefix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RefKind {
    /// `c_ID...`
    Compute,
    /// `f_ID...`
    Fix,
    /// `v_name...`
    Variable,
}

/// What a formula can ask of the world. Lookups return `Err` when not available.
pub trait ExprContext {
    /// `v_name` (index None) or `v_name[N]`; `atom` is the atom being evaluated in atom style.
    /// The context evaluates the variable (recursively, guarding against cycles).
    fn variable(
        &mut self,
        name: &str,
        index: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, VariableError>;
    /// A thermo keyword (`step`, `time`, `atoms`, ...); unknown words give
    /// "Invalid thermo keyword in variable formula".
    fn thermo(&mut self, name: &str) -> Result<f64, VariableError>;
    /// `c_ID`, `c_ID[i]`, `c_ID[i][j]`; `atom` set inside atom-style formulas.
    fn compute(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, VariableError>;
    /// `f_ID`, `f_ID[i]`, `f_ID[i][j]`, same conventions.
    fn fix(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, VariableError>;
    /// Group functions `count(g)`, `xcm(g,x)`, `bound(g,zmax,region)` ...: the raw text
    /// between the parentheses split at the first two top-level commas (untrimmed, so
    /// `count( all)` names group " all" and fails as in LIGGGHTS).
    fn group_function(&mut self, name: &str, args: &[String]) -> Result<f64, VariableError>;
    /// Special functions `sum() min() max() ave() trap() next()` (atom None) and, in atom
    /// style only, `gmask() rmask() grmask()` for one atom; raw arguments as above.
    fn special_function(
        &mut self,
        name: &str,
        args: &[String],
        atom: Option<usize>,
    ) -> Result<f64, VariableError>;
    /// Per-atom keyword (`x`, `vx`, `mass`, `r`, ...) of local atom `atom`.
    fn atom_value(&mut self, name: &str, atom: usize) -> Result<f64, VariableError>;
    /// The keyword `name` of the first `n` atoms at once (the default asks atom by atom).
    fn atom_column(&mut self, name: &str, n: usize) -> Result<Vec<f64>, VariableError> {
        (0..n).map(|i| self.atom_value(name, i)).collect()
    }
    /// A per-atom `v_name` for the first `n` atoms at once (the default asks atom by atom).
    fn variable_column(
        &mut self,
        name: &str,
        index: Option<usize>,
        n: usize,
    ) -> Result<Vec<f64>, VariableError> {
        (0..n)
            .map(|i| self.variable(name, index, Some(i)))
            .collect()
    }
    /// A per-atom `c_ID[i]` for the first `n` atoms at once (the default asks atom by atom).
    fn compute_column(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        n: usize,
    ) -> Result<Vec<f64>, VariableError> {
        (0..n).map(|a| self.compute(id, i, j, Some(a))).collect()
    }
    /// `x[N]`: keyword `name` (any word) of the atom whose ID is `id`.
    fn atom_value_by_id(&mut self, name: &str, id: usize) -> Result<f64, VariableError>;
    /// Whether the simulation box exists (most lookups need it).
    fn box_exists(&self) -> bool;
    /// The current timestep.
    fn timestep(&self) -> i64;
    /// First and last step of the run in progress (None between runs).
    fn run_bounds(&self) -> Option<(i64, i64)>;
    /// The time-step size (time units).
    fn dt(&self) -> f64;
    /// The generator behind `random()`/`normal()` (one for equal style, one for atom style),
    /// made from `seed` on first use and returned unchanged afterwards whatever the seed.
    fn rng(&mut self, seed: i32, per_atom: bool) -> Result<&mut RanMars, VariableError>;
    /// Whether a `c_`/`f_`/`v_` reference names per-atom data (one value per atom, looked up
    /// for each atom) rather than one number (looked up once when an atom-style formula is
    /// read, as LIGGGHTS does). Contexts with per-atom computes, fixes or atom-style
    /// variables must say so; the default treats every reference as one number.
    fn is_per_atom_ref(
        &mut self,
        kind: RefKind,
        name: &str,
        i: Option<usize>,
        j: Option<usize>,
    ) -> bool {
        let _ = (kind, name, i, j);
        false
    }
}

/// The math functions of LIGGGHTS 3.8.0 (arguments are formulas).
pub const MATH_FUNCTIONS: &[&str] = &[
    "sqrt",
    "exp",
    "ln",
    "log",
    "abs",
    "sin",
    "cos",
    "tan",
    "asin",
    "acos",
    "atan",
    "atan2",
    "random",
    "normal",
    "ceil",
    "floor",
    "round",
    "ramp",
    "stagger",
    "logfreq",
    "stride",
    "vdisplace",
    "swiggle",
    "cwiggle",
];

/// Group functions (arguments are group, dimension and region names).
pub const GROUP_FUNCTIONS: &[&str] = &[
    "count", "mass", "charge", "xcm", "vcm", "fcm", "bound", "gyration", "ke", "angmom", "torque",
    "inertia", "omega", "countMS",
];

/// Special functions (arguments are references such as `c_ID` or names).
pub const SPECIAL_FUNCTIONS: &[&str] = &[
    "sum", "min", "max", "ave", "trap", "gmask", "rmask", "grmask", "next",
];

/// Per-atom keywords a formula may name (LIGGGHTS's `is_atom_vector` for granular atoms).
pub const ATOM_KEYWORDS: &[&str] = &[
    "id", "mass", "type", "x", "y", "z", "vx", "vy", "vz", "fx", "fy", "fz", "omegax", "omegay",
    "omegaz", "tqx", "tqy", "tqz", "r", "density",
];

#[derive(Debug, Clone, PartialEq)]
enum Node {
    Num(f64),
    Neg(Box<Node>),
    Not(Box<Node>, usize),
    /// Atom style's `a ! b`: LIGGGHTS's tree builder takes `!` as binary there and the
    /// result is `!a`, `b` never being looked at.
    NotLeft(Box<Node>, Box<Node>),
    Bin(Op, Box<Node>, Box<Node>, usize),
    Math(Math, Vec<Node>, usize),
    Group(String, Vec<String>, usize),
    Special(String, Vec<String>, usize),
    Compute(String, Option<usize>, Option<usize>, usize),
    Fix(String, Option<usize>, Option<usize>, usize),
    Var(String, Option<usize>, usize),
    AtomById(String, usize, usize),
    AtomVector(String, usize),
    Thermo(String, usize),
}

/// A parsed formula (parse once, evaluate many times).
#[derive(Debug, Clone, PartialEq)]
pub struct Expr {
    root: Node,
}

fn is_c_space(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | 0x0b | 0x0c | b'\r')
}

fn truth(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}

/// C's `static_cast<int>` of a double on x86: truncation, and INT_MIN for NaN or values
/// out of range.
fn c_int(x: f64) -> i32 {
    if x.is_nan() || x >= 2147483648.0 || x <= -2147483649.0 {
        i32::MIN
    } else {
        x as i32
    }
}

/// LIGGGHTS's rounding: `x - floor(x) >= 0.5` rounds up, so halves go towards +infinity.
fn round_half_up(a: f64) -> f64 {
    if a - a.floor() >= 0.5 {
        a.ceil()
    } else {
        a.floor()
    }
}

impl Expr {
    /// Parse a formula for later evaluation (syntax only; nothing is looked up).
    pub fn parse(text: &str) -> Result<Expr, ExprError> {
        let mut parser = Parser {
            text,
            mode: Mode::Syntax,
            nesting: 0,
        };
        let (root, _) = parser.level(0, text.len())?;
        Ok(Expr { root })
    }

    /// Read an atom-style formula the way LIGGGHTS does each time it evaluates one: global
    /// values (thermo keywords, group functions, global computes, fixes and variables) are
    /// fetched now and in formula order, constant parts are computed, the per-atom random
    /// generator is made; then call [`Expr::eval`] with `Some(atom)` for each atom.
    pub fn parse_atom(text: &str, ctx: &mut dyn ExprContext) -> Result<Expr, ExprError> {
        let root = {
            let mut parser = Parser {
                text,
                mode: Mode::Atom(&mut *ctx),
                nesting: 0,
            };
            parser.level(0, text.len())?.0
        };
        Ok(Expr {
            root: collapse(root, ctx)?,
        })
    }

    /// Evaluate as equal style (`atom` None) or for one atom (`atom` = local index), with
    /// LIGGGHTS's per-atom evaluation order in the latter case.
    pub fn eval(&self, ctx: &mut dyn ExprContext, atom: Option<usize>) -> Result<f64, ExprError> {
        eval_node(&self.root, ctx, atom)
    }

    /// Evaluate an atom-style formula for the first `n` atoms. Formulas without random
    /// draws or mask functions are computed a whole column at a time (each value with the
    /// operations of the atom-by-atom walk, so bit for bit the same); should any value fail,
    /// or the formula need the atom-by-atom order, the walk runs and reports as LIGGGHTS.
    pub fn eval_atoms(&self, ctx: &mut dyn ExprContext, n: usize) -> Result<Vec<f64>, ExprError> {
        if columnar(&self.root) {
            if let Ok(col) = eval_column(&self.root, ctx, n) {
                return Ok(col.into_vec(n));
            }
        }
        (0..n)
            .map(|i| eval_node(&self.root, ctx, Some(i)))
            .collect()
    }

    /// True if the formula names per-atom keywords (`x`, `mass`, ...) or mask functions,
    /// so that only atom style can evaluate it. (`c_`/`f_`/`v_` references may be per-atom
    /// too; only the context knows.)
    pub fn is_per_atom(&self) -> bool {
        fn walk(n: &Node) -> bool {
            match n {
                Node::AtomVector(..) => true,
                Node::Special(name, ..) => mask_function(name).is_some(),
                Node::Neg(a) | Node::Not(a, _) => walk(a),
                Node::NotLeft(a, b) | Node::Bin(_, a, b, _) => walk(a) || walk(b),
                Node::Math(_, args, _) => args.iter().any(walk),
                _ => false,
            }
        }
        walk(&self.root)
    }
}

/// Evaluate an equal-style formula as LIGGGHTS does: reading and computing in one pass, so
/// lookups, random draws and errors happen in LIGGGHTS's order.
pub fn evaluate(text: &str, ctx: &mut dyn ExprContext) -> Result<f64, ExprError> {
    let mut parser = Parser {
        text,
        mode: Mode::Equal(ctx),
        nesting: 0,
    };
    let (node, _) = parser.level(0, text.len())?;
    match node {
        Node::Num(v) => Ok(v),
        other => match parser.mode {
            Mode::Equal(ctx) => eval_node(&other, ctx, None),
            _ => err(SYNTAX, 0),
        },
    }
}

/// The condition of an `if` command, as LIGGGHTS 3.8.0 evaluates it: numbers (which may
/// start with `-`), parentheses, comparisons, `&&`, `||` and `!` only, no words and no
/// arithmetic (so no string comparisons either); 1.0 means true, 0.0 false.
pub fn evaluate_boolean(text: &str) -> Result<f64, ExprError> {
    boolean_level(text, 0, text.len(), 0)
}

#[cfg(test)]
mod tests;
