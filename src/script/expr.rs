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

pub use crate::script::error::{ExprErrorKind, VariableError};

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

/// Binary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Op {
    Or,
    And,
    Eq,
    Ne,
    Lt,
    Le,
    Gt,
    Ge,
    Add,
    Sub,
    Mul,
    Div,
    Mod,
    Pow,
}

impl Op {
    fn precedence(self) -> u8 {
        match self {
            Op::Or => 1,
            Op::And => 2,
            Op::Eq | Op::Ne => 3,
            Op::Lt | Op::Le | Op::Gt | Op::Ge => 4,
            Op::Add | Op::Sub => 5,
            Op::Mul | Op::Div | Op::Mod => 6,
            Op::Pow => 7,
        }
    }
}

/// Pending operators: binary ones and the two prefix ones, with their byte offsets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Pending {
    Bin(Op, usize),
    Neg,
    Not(usize),
}

impl Pending {
    fn precedence(self) -> u8 {
        match self {
            Pending::Bin(op, _) => op.precedence(),
            Pending::Neg | Pending::Not(_) => 8,
        }
    }
}

/// The operator at `i` (None for end of text), its length, or Err for `=`, `&`, `|` alone.
fn operator_at(bytes: &[u8], i: usize) -> Result<(Option<Pending>, usize), ()> {
    let c = bytes.get(i).copied().unwrap_or(0);
    let doubled = bytes.get(i + 1).copied().unwrap_or(0);
    let bin = |op| Some(Pending::Bin(op, i));
    Ok(match c {
        0 => (None, 0),
        b'+' => (bin(Op::Add), 1),
        b'-' => (bin(Op::Sub), 1),
        b'*' => (bin(Op::Mul), 1),
        b'/' => (bin(Op::Div), 1),
        b'%' => (bin(Op::Mod), 1),
        b'^' => (bin(Op::Pow), 1),
        b'=' if doubled == b'=' => (bin(Op::Eq), 2),
        b'!' if doubled == b'=' => (bin(Op::Ne), 2),
        b'!' => (Some(Pending::Not(i)), 1),
        b'<' if doubled == b'=' => (bin(Op::Le), 2),
        b'<' => (bin(Op::Lt), 1),
        b'>' if doubled == b'=' => (bin(Op::Ge), 2),
        b'>' => (bin(Op::Gt), 1),
        b'&' if doubled == b'&' => (bin(Op::And), 2),
        b'|' if doubled == b'|' => (bin(Op::Or), 2),
        _ => return Err(()),
    })
}

/// Math functions and their argument counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Math {
    Sqrt,
    Exp,
    Ln,
    Log,
    Abs,
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Atan2,
    Random,
    Normal,
    Ceil,
    Floor,
    Round,
    Ramp,
    Stagger,
    Logfreq,
    Stride,
    Vdisplace,
    Swiggle,
    Cwiggle,
}

impl Math {
    fn from_name(name: &str) -> Option<Math> {
        use Math::*;
        Some(match name {
            "sqrt" => Sqrt,
            "exp" => Exp,
            "ln" => Ln,
            "log" => Log,
            "abs" => Abs,
            "sin" => Sin,
            "cos" => Cos,
            "tan" => Tan,
            "asin" => Asin,
            "acos" => Acos,
            "atan" => Atan,
            "atan2" => Atan2,
            "random" => Random,
            "normal" => Normal,
            "ceil" => Ceil,
            "floor" => Floor,
            "round" => Round,
            "ramp" => Ramp,
            "stagger" => Stagger,
            "logfreq" => Logfreq,
            "stride" => Stride,
            "vdisplace" => Vdisplace,
            "swiggle" => Swiggle,
            "cwiggle" => Cwiggle,
            _ => return None,
        })
    }

    fn arity(self) -> usize {
        use Math::*;
        match self {
            Atan2 | Ramp | Stagger | Vdisplace => 2,
            Random | Normal | Logfreq | Stride | Swiggle | Cwiggle => 3,
            _ => 1,
        }
    }

    /// The name used in "Cannot use NAME in variable formula between runs", for the
    /// functions that need a run in progress.
    fn needs_run(self) -> Option<&'static str> {
        match self {
            Math::Ramp => Some("ramp"),
            Math::Vdisplace => Some("vdisplace"),
            Math::Swiggle => Some("swiggle"),
            Math::Cwiggle => Some("cwiggle"),
            _ => None,
        }
    }
}

/// The mask special functions: per-atom only; their equal-style error names them.
fn mask_function(name: &str) -> Option<&'static str> {
    match name {
        "gmask" => Some("Gmask"),
        "rmask" => Some("Rmask"),
        "grmask" => Some("Grmask"),
        _ => None,
    }
}

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

/// Position of the `)` matching the `(` at `open`, allowing nesting; None if unmatched.
fn matching_paren(bytes: &[u8], open: usize) -> Option<usize> {
    let mut level = 0usize;
    for (i, &c) in bytes.iter().enumerate().skip(open + 1) {
        match c {
            0 => return None,
            b'(' => level += 1,
            b')' if level > 0 => level -= 1,
            b')' => return Some(i),
            _ => {}
        }
    }
    None
}

/// Split `start..end` at its first two top-level commas (later commas stay in the third
/// piece, as LIGGGHTS's `find_next_comma` use does). Returns byte ranges.
fn split_pieces(bytes: &[u8], start: usize, end: usize) -> Vec<(usize, usize)> {
    let mut pieces = Vec::with_capacity(3);
    let mut level = 0i64;
    let mut from = start;
    for (i, &c) in bytes.iter().enumerate().take(end).skip(start) {
        match c {
            b'(' => level += 1,
            b')' => level -= 1,
            b',' if level == 0 && pieces.len() < 2 => {
                pieces.push((from, i));
                from = i + 1;
            }
            _ => {}
        }
    }
    pieces.push((from, end));
    pieces
}

/// `[N]` at `open`: digits only, as C `atoi` reads them (saturating `strtol` cut to `int`),
/// and not zero. Returns (N, position after `]`).
fn bracket_index(bytes: &[u8], open: usize) -> Result<(usize, usize), ExprError> {
    let mut i = open + 1;
    let mut value: i64 = 0;
    while let Some(&c) = bytes.get(i) {
        if c == b']' || c == 0 {
            break;
        }
        if !c.is_ascii_digit() {
            return err(ExprErrorKind::NonDigitIndex, i);
        }
        value = value.saturating_mul(10).saturating_add(i64::from(c - b'0'));
        i += 1;
    }
    if bytes.get(i) != Some(&b']') {
        return err(ExprErrorKind::MismatchedBrackets, open);
    }
    if i == open + 1 {
        return err(ExprErrorKind::EmptyBrackets, open);
    }
    let index = value as i32;
    if index == 0 {
        return err(ExprErrorKind::IndexNotPositive, open);
    }
    // a negative index (from int overflow) becomes huge and is out of range for the context
    Ok((index as isize as usize, i + 1))
}

/// How the parser treats what it reads.
enum Mode<'c> {
    /// Build the tree only.
    Syntax,
    /// Equal style: compute every piece as soon as it is complete.
    Equal(&'c mut dyn ExprContext),
    /// Atom style: fetch global values now, keep per-atom pieces as a tree.
    Atom(&'c mut dyn ExprContext),
}

struct Parser<'t, 'c> {
    text: &'t str,
    mode: Mode<'c>,
    nesting: usize,
}

/// A parsed piece and the depth of its tree.
type Item = (Node, usize);

impl Parser<'_, '_> {
    /// Parse `start..end` as one formula (LIGGGHTS calls `evaluate` once per level of
    /// parentheses and per function argument).
    fn level(&mut self, start: usize, end: usize) -> Result<Item, ExprError> {
        if self.nesting >= MAX_NESTING {
            return err(TOO_DEEP, start);
        }
        self.nesting += 1;
        let result = self.level_inner(start, end);
        self.nesting -= 1;
        result
    }

    fn level_inner(&mut self, start: usize, end: usize) -> Result<Item, ExprError> {
        let text = self.text;
        let bytes = &text.as_bytes()[..end];
        let at = |k: usize| bytes.get(k).copied().unwrap_or(0);
        let mut args: Vec<Item> = Vec::new();
        let mut ops: Vec<Pending> = Vec::new();
        let mut expect_arg = true;
        // atom style: LIGGGHTS's tree stack ran dry, the level will end in a syntax error
        let mut broken = false;
        let mut i = start;
        loop {
            let c = at(i);
            if c != 0 && is_c_space(c) {
                i += 1;
            } else if c == b'(' {
                if !expect_arg {
                    return err(SYNTAX, i);
                }
                expect_arg = false;
                let Some(close) = matching_paren(bytes, i) else {
                    return err(SYNTAX, i);
                };
                let item = self.level(i + 1, close)?;
                args.push(item);
                i = close + 1;
            } else if c.is_ascii_digit() || c == b'.' {
                if !expect_arg {
                    return err(SYNTAX, i);
                }
                expect_arg = false;
                let from = i;
                while at(i).is_ascii_digit() || at(i) == b'.' {
                    i += 1;
                }
                if matches!(at(i), b'e' | b'E') {
                    i += 1;
                    if matches!(at(i), b'+' | b'-') {
                        i += 1;
                    }
                    while at(i).is_ascii_digit() {
                        i += 1;
                    }
                }
                args.push((Node::Num(literal(&text[from..i], from)?), 1));
            } else if c.is_ascii_alphabetic() {
                if !expect_arg {
                    return err(SYNTAX, i);
                }
                expect_arg = false;
                let from = i;
                while at(i).is_ascii_alphanumeric() || at(i) == b'_' {
                    i += 1;
                }
                let (item, next) = self.word(bytes, from, i)?;
                args.push(item);
                i = next;
            } else if c == 0 || b"+-*/^<>=!&|%".contains(&c) {
                let Ok((op, len)) = operator_at(bytes, i) else {
                    return err(SYNTAX, i);
                };
                let op_at = i;
                i += len;
                if expect_arg {
                    match op {
                        Some(Pending::Bin(Op::Sub, _)) => {
                            ops.push(Pending::Neg);
                            continue;
                        }
                        Some(Pending::Not(p)) => {
                            ops.push(Pending::Not(p));
                            continue;
                        }
                        _ => return err(SYNTAX, op_at),
                    }
                }
                // a `!` after an operand is pushed like any operator (LIGGGHTS does so)
                expect_arg = true;
                let level = op.map_or(0, Pending::precedence);
                while let Some(&top) = ops.last() {
                    if top.precedence() < level {
                        break;
                    }
                    ops.pop();
                    self.reduce(&mut args, top, &mut broken, op_at)?;
                }
                match op {
                    None => break,
                    Some(op) => ops.push(op),
                }
            } else {
                return err(SYNTAX, i);
            }
        }
        if !ops.is_empty() || broken || args.len() != 1 {
            return err(SYNTAX, end.min(i));
        }
        Ok(args.pop().expect("exactly one operand"))
    }

    /// Combine the operands of `op` on the stack into one node.
    fn reduce(
        &mut self,
        args: &mut Vec<Item>,
        op: Pending,
        broken: &mut bool,
        at: usize,
    ) -> Result<(), ExprError> {
        let atom_style = matches!(self.mode, Mode::Atom(_));
        let mut pop = |args: &mut Vec<Item>| match args.pop() {
            Some(item) => Ok(item),
            None if atom_style => {
                *broken = true;
                Ok((Node::Num(0.0), 1))
            }
            None => err(SYNTAX, at),
        };
        let (node, depth, node_at) = match op {
            Pending::Neg => {
                let (a, d) = pop(args)?;
                (Node::Neg(Box::new(a)), d + 1, at)
            }
            Pending::Not(p) if !atom_style => {
                let (a, d) = pop(args)?;
                (Node::Not(Box::new(a), p), d + 1, p)
            }
            Pending::Not(p) => {
                let (b, db) = pop(args)?;
                let (a, da) = pop(args)?;
                (Node::NotLeft(Box::new(a), Box::new(b)), da.max(db) + 1, p)
            }
            Pending::Bin(op, p) => {
                let (b, db) = pop(args)?;
                let (a, da) = pop(args)?;
                (
                    Node::Bin(op, Box::new(a), Box::new(b), p),
                    da.max(db) + 1,
                    p,
                )
            }
        };
        let item = self.settle(node, depth, node_at)?;
        args.push(item);
        Ok(())
    }

    /// LIGGGHTS checks for the box before it reads brackets after `c_`, `f_` and `x`.
    fn need_box(&self, at: usize) -> Result<(), ExprError> {
        match &self.mode {
            Mode::Equal(ctx) | Mode::Atom(ctx) if !ctx.box_exists() => err(NO_BOX, at),
            _ => Ok(()),
        }
    }

    /// The word at `from..to` and what follows it. Returns the item and the next position.
    fn word(&mut self, bytes: &[u8], from: usize, to: usize) -> Result<(Item, usize), ExprError> {
        let text = self.text;
        let word = &text[from..to];
        let mut next = to;
        let mut brackets = |max: usize| -> Result<(Option<usize>, Option<usize>), ExprError> {
            let mut found = (None, None);
            if bytes.get(next) == Some(&b'[') {
                let (n, after) = bracket_index(bytes, next)?;
                found.0 = Some(n);
                next = after;
                if max == 2 && bytes.get(next) == Some(&b'[') {
                    let (m, after) = bracket_index(bytes, next)?;
                    found.1 = Some(m);
                    next = after;
                }
            }
            Ok(found)
        };
        let node = if let Some(id) = word.strip_prefix("c_") {
            self.need_box(from)?;
            let (i, j) = brackets(2)?;
            Node::Compute(id.to_string(), i, j, from)
        } else if let Some(id) = word.strip_prefix("f_") {
            self.need_box(from)?;
            let (i, j) = brackets(2)?;
            Node::Fix(id.to_string(), i, j, from)
        } else if let Some(name) = word.strip_prefix("v_") {
            let (i, _) = brackets(1)?;
            Node::Var(name.to_string(), i, from)
        } else if bytes.get(to) == Some(&b'(') {
            return self.function(bytes, word, from, to);
        } else if bytes.get(to) == Some(&b'[') {
            self.need_box(from)?;
            let (id, _) = brackets(1)?;
            Node::AtomById(word.to_string(), id.unwrap_or(0), from)
        } else if ATOM_KEYWORDS.contains(&word) {
            Node::AtomVector(word.to_string(), from)
        } else if word == "PI" {
            Node::Num(std::f64::consts::PI)
        } else {
            Node::Thermo(word.to_string(), from)
        };
        Ok((self.settle(node, 1, from)?, next))
    }

    /// `name(...)` with the `(` at `open`.
    fn function(
        &mut self,
        bytes: &[u8],
        name: &str,
        from: usize,
        open: usize,
    ) -> Result<(Item, usize), ExprError> {
        let Some(close) = matching_paren(bytes, open) else {
            return err(SYNTAX, open);
        };
        let text = self.text;
        let pieces = split_pieces(bytes, open + 1, close);
        let raw = || -> Vec<String> {
            pieces
                .iter()
                .map(|&(a, b)| text[a..b].to_string())
                .collect()
        };
        let (node, depth) = if let Some(f) = Math::from_name(name) {
            // every argument is read (and in equal style computed) before the count is checked
            let mut args = Vec::with_capacity(pieces.len());
            let mut depth = 0;
            for &(a, b) in &pieces {
                let (arg, d) = self.level(a, b)?;
                depth = depth.max(d);
                args.push(arg);
            }
            if args.len() != f.arity() {
                return err(BAD_MATH, from);
            }
            (Node::Math(f, args, from), depth + 1)
        } else if GROUP_FUNCTIONS.contains(&name) {
            (Node::Group(name.to_string(), raw(), from), 1)
        } else if SPECIAL_FUNCTIONS.contains(&name) {
            (Node::Special(name.to_string(), raw(), from), 1)
        } else {
            return err(BAD_NAME, from);
        };
        Ok((self.settle(node, depth, from)?, close + 1))
    }

    /// A node is complete: in equal style compute it, in atom style fetch it if global.
    fn settle(&mut self, node: Node, depth: usize, at: usize) -> Result<Item, ExprError> {
        if depth > MAX_DEPTH {
            return err(TOO_DEEP, at);
        }
        match &mut self.mode {
            Mode::Syntax => Ok((node, depth)),
            Mode::Equal(ctx) => Ok((Node::Num(eval_node(&node, &mut **ctx, None)?), 1)),
            Mode::Atom(ctx) => Ok((atom_leaf(node, &mut **ctx)?, depth)),
        }
    }
}

/// What LIGGGHTS does with a freshly read piece of an atom-style formula: global values
/// are looked up at once, run-only functions are checked, per-atom pieces are kept.
fn atom_leaf(node: Node, ctx: &mut dyn ExprContext) -> Result<Node, ExprError> {
    let global = match &node {
        Node::Compute(id, i, j, _) => !ctx.is_per_atom_ref(RefKind::Compute, id, *i, *j),
        Node::Fix(id, i, j, _) => !ctx.is_per_atom_ref(RefKind::Fix, id, *i, *j),
        Node::Var(name, i, _) => !ctx.is_per_atom_ref(RefKind::Variable, name, *i, None),
        Node::Thermo(..) | Node::AtomById(..) | Node::Group(..) => true,
        Node::Special(name, ..) => mask_function(name).is_none(),
        Node::AtomVector(_, at) => {
            if !ctx.box_exists() {
                return err(NO_BOX, *at);
            }
            false
        }
        Node::Math(f, _, at) => {
            if let Some(name) = f.needs_run() {
                if ctx.run_bounds().is_none() {
                    return err(ExprErrorKind::NeedsRun(name), *at);
                }
            }
            false
        }
        _ => false,
    };
    if global {
        return Ok(Node::Num(eval_node(&node, ctx, None)?));
    }
    Ok(match node {
        // LIGGGHTS's tree builder files swiggle() under cwiggle()
        Node::Math(Math::Swiggle, args, at) => Node::Math(Math::Cwiggle, args, at),
        other => other,
    })
}

/// Make sure the formula generator exists; seeds that are not positive integers are
/// LIGGGHTS's "Invalid math function" unless a generator already exists (then the seed
/// is ignored).
fn generator(
    ctx: &mut dyn ExprContext,
    seed: i32,
    per_atom: bool,
    at: usize,
) -> Result<&mut RanMars, ExprError> {
    match ctx.rng(seed, per_atom) {
        Ok(r) => Ok(r),
        Err(_) if seed <= 0 => err(BAD_MATH, at),
        Err(e) => err(e.into(), at),
    }
}

/// LIGGGHTS's one-time folding of an atom-style tree: constant parts become numbers (with
/// their errors), the random generator is made, per-atom parts stay.
fn collapse(node: Node, ctx: &mut dyn ExprContext) -> Result<Node, ExprError> {
    Ok(match node {
        Node::Neg(a) => match collapse(*a, ctx)? {
            Node::Num(v) => Node::Num(-v),
            a => Node::Neg(Box::new(a)),
        },
        // only the left operand is looked at, the right one is left as it is
        Node::NotLeft(a, b) => match collapse(*a, ctx)? {
            Node::Num(v) => Node::Num(truth(v == 0.0)),
            a => Node::NotLeft(Box::new(a), b),
        },
        Node::Bin(op, a, b, at) => {
            let a = collapse(*a, ctx)?;
            let b = collapse(*b, ctx)?;
            match (&a, &b) {
                (Node::Num(x), Node::Num(y)) => Node::Num(binary(op, *x, *y, at)?),
                _ => Node::Bin(op, Box::new(a), Box::new(b), at),
            }
        }
        Node::Math(f @ (Math::Random | Math::Normal), args, at) => {
            let mut folded = Vec::with_capacity(args.len());
            for a in args {
                folded.push(collapse(a, ctx)?);
            }
            if f == Math::Normal {
                if let Some(Node::Num(sigma)) = folded.get(1) {
                    if *sigma < 0.0 {
                        return err(BAD_MATH, at);
                    }
                }
            }
            let seed = match folded.get(2) {
                Some(Node::Num(v)) => c_int(*v),
                _ => 0,
            };
            generator(ctx, seed, true, at)?;
            Node::Math(f, folded, at)
        }
        Node::Math(f, args, at) => {
            let mut folded = Vec::with_capacity(args.len());
            for a in args {
                folded.push(collapse(a, ctx)?);
            }
            let values: Option<Vec<f64>> = folded
                .iter()
                .map(|n| match n {
                    Node::Num(v) => Some(*v),
                    _ => None,
                })
                .collect();
            match values {
                Some(v) => Node::Num(math(f, &v, ctx, at)?),
                None => Node::Math(f, folded, at),
            }
        }
        other => other,
    })
}

/// Apply a binary operator, with LIGGGHTS's three errors.
fn binary(op: Op, x: f64, y: f64, at: usize) -> Result<f64, ExprError> {
    Ok(match op {
        Op::Add => x + y,
        Op::Sub => x - y,
        Op::Mul => x * y,
        Op::Div if y == 0.0 => return err(ExprErrorKind::DivideByZero, at),
        Op::Div => x / y,
        Op::Mod if y == 0.0 => return err(ExprErrorKind::ModuloZero, at),
        Op::Mod => x % y,
        Op::Pow if y == 0.0 => return err(ExprErrorKind::PowerByZero, at),
        Op::Pow => x.powf(y),
        Op::Eq => truth(x == y),
        Op::Ne => truth(x != y),
        Op::Lt => truth(x < y),
        Op::Le => truth(x <= y),
        Op::Gt => truth(x > y),
        Op::Ge => truth(x >= y),
        Op::And => truth(x != 0.0 && y != 0.0),
        Op::Or => truth(x != 0.0 || y != 0.0),
    })
}

/// Apply a math function other than random()/normal() to its argument values.
// explicit comparisons: a NaN argument passes asin/acos's range check in LIGGGHTS
#[allow(clippy::manual_range_contains)]
fn math(f: Math, v: &[f64], ctx: &mut dyn ExprContext, at: usize) -> Result<f64, ExprError> {
    use Math::*;
    let arg = |k: usize| v.get(k).copied().unwrap_or(0.0);
    let (a, b, c) = (arg(0), arg(1), arg(2));
    let run = |ctx: &dyn ExprContext| -> Result<(i64, i64), ExprError> {
        let name = f.needs_run().unwrap_or("");
        ctx.run_bounds().ok_or(ExprError {
            kind: ExprErrorKind::NeedsRun(name),
            offset: at,
        })
    };
    let step = ctx.timestep();
    Ok(match f {
        Sqrt if a < 0.0 => return err(ExprErrorKind::SqrtNegative, at),
        Sqrt => a.sqrt(),
        Exp => a.exp(),
        Ln | Log if a <= 0.0 => return err(ExprErrorKind::LogNonPositive, at),
        Ln => a.ln(),
        Log => a.log10(),
        Abs => a.abs(),
        Sin => a.sin(),
        Cos => a.cos(),
        Tan => a.tan(),
        Asin if a < -1.0 || a > 1.0 => return err(ExprErrorKind::ArcsinRange, at),
        Asin => a.asin(),
        Acos if a < -1.0 || a > 1.0 => return err(ExprErrorKind::ArccosRange, at),
        Acos => a.acos(),
        Atan => a.atan(),
        Atan2 => a.atan2(b),
        Ceil => a.ceil(),
        Floor => a.floor(),
        Round => round_half_up(a),
        Ramp => {
            let (begin, end) = run(ctx)?;
            let mut delta = (step - begin) as f64;
            if delta != 0.0 {
                delta /= (end - begin) as f64;
            }
            a + delta * (b - a)
        }
        Stagger => {
            let (n1, n2) = (c_int(a), c_int(b));
            if n1 <= 0 || n2 <= 0 || n1 <= n2 {
                return err(BAD_MATH, at);
            }
            // LIGGGHTS keeps these in C ints
            let lower = (step / i64::from(n1) * i64::from(n1)) as i32;
            let delta = (step - i64::from(lower)) as i32;
            let next = if delta < n2 {
                lower.wrapping_add(n2)
            } else {
                lower.wrapping_add(n1)
            };
            f64::from(next)
        }
        Logfreq => {
            let (n1, n2, n3) = (
                i64::from(c_int(a)),
                i64::from(c_int(b)),
                i64::from(c_int(c)),
            );
            if n1 <= 0 || n2 <= 0 || n3 <= 0 || n2 >= n3 {
                return err(BAD_MATH, at);
            }
            if step < n1 {
                n1 as f64
            } else {
                // 64-bit here: LIGGGHTS's int arithmetic overflows beyond step 2^31 / n3
                let mut lower = n1;
                while let Some(up) = n3.checked_mul(lower).filter(|&up| step >= up) {
                    lower = up;
                }
                let multiple = step / lower;
                if multiple < n2 {
                    ((multiple + 1) * lower) as f64
                } else {
                    (lower * n3) as f64
                }
            }
        }
        Stride => {
            let (n1, n2, n3) = (c_int(a), c_int(b), c_int(c));
            if n1 < 0 || n2 < 0 || n3 <= 0 || n1 > n2 {
                return err(BAD_MATH, at);
            }
            if step < i64::from(n1) {
                f64::from(n1)
            } else if step < i64::from(n2) {
                let offset = (step - i64::from(n1)) as i32;
                let next = n1
                    .wrapping_add((offset / n3).wrapping_mul(n3))
                    .wrapping_add(n3);
                if next > n2 {
                    9.0e18
                } else {
                    f64::from(next)
                }
            } else {
                9.0e18
            }
        }
        Vdisplace => {
            let (begin, _) = run(ctx)?;
            a + b * (step - begin) as f64 * ctx.dt()
        }
        Swiggle | Cwiggle => {
            let (begin, _) = run(ctx)?;
            if c == 0.0 {
                return err(BAD_MATH, at);
            }
            let omega = 2.0 * std::f64::consts::PI / c;
            let phase = omega * (step - begin) as f64 * ctx.dt();
            if f == Swiggle {
                a + b * phase.sin()
            } else {
                a + b * (1.0 - phase.cos())
            }
        }
        Random | Normal => return err(BAD_MATH, at),
    })
}

/// The argument `k` of a math node (always present: the parser checked the count).
fn nth(args: &[Node], k: usize, at: usize) -> Result<&Node, ExprError> {
    args.get(k).ok_or(ExprError {
        kind: BAD_MATH,
        offset: at,
    })
}

/// Evaluate a tree: equal style (`atom` None) left to right, or atom style for one atom
/// with the evaluation order of LIGGGHTS's per-atom tree walker.
fn eval_node(
    node: &Node,
    ctx: &mut dyn ExprContext,
    atom: Option<usize>,
) -> Result<f64, ExprError> {
    let per_atom = atom.is_some();
    Ok(match node {
        Node::Num(v) => *v,
        Node::Neg(a) => -eval_node(a, ctx, atom)?,
        // LIGGGHTS cannot build a prefix `!` into an atom-style tree
        Node::Not(_, at) if per_atom => return err(SYNTAX, *at),
        Node::Not(a, _) => truth(eval_node(a, ctx, atom)? == 0.0),
        Node::NotLeft(a, _) => truth(eval_node(a, ctx, atom)? == 0.0),
        Node::Bin(op, a, b, at) => match op {
            // per atom: the right operand first, and its check before the left is looked at
            Op::Div | Op::Mod | Op::Pow if per_atom => {
                let y = eval_node(b, ctx, atom)?;
                binary(*op, 1.0, y, *at)?;
                let x = eval_node(a, ctx, atom)?;
                binary(*op, x, y, *at)?
            }
            // per atom: C's short-circuit && and ||
            Op::And if per_atom => {
                truth(eval_node(a, ctx, atom)? != 0.0 && eval_node(b, ctx, atom)? != 0.0)
            }
            Op::Or if per_atom => {
                truth(eval_node(a, ctx, atom)? != 0.0 || eval_node(b, ctx, atom)? != 0.0)
            }
            _ => {
                let x = eval_node(a, ctx, atom)?;
                let y = eval_node(b, ctx, atom)?;
                binary(*op, x, y, *at)?
            }
        },
        Node::Math(f, args, at) => eval_math(*f, args, *at, ctx, atom)?,
        Node::Group(name, args, at) => lookup(ctx.group_function(name, args), *at)?,
        Node::Special(name, args, at) => match mask_function(name) {
            Some(label) if !per_atom => return err(ExprErrorKind::MaskInEqual(label), *at),
            Some(_) => lookup(ctx.special_function(name, args, atom), *at)?,
            None => lookup(ctx.special_function(name, args, None), *at)?,
        },
        Node::Compute(id, i, j, at) => {
            if !ctx.box_exists() {
                return err(NO_BOX, *at);
            }
            lookup(ctx.compute(id, *i, *j, atom), *at)?
        }
        Node::Fix(id, i, j, at) => {
            if !ctx.box_exists() {
                return err(NO_BOX, *at);
            }
            lookup(ctx.fix(id, *i, *j, atom), *at)?
        }
        Node::Var(name, index, at) => lookup(ctx.variable(name, *index, atom), *at)?,
        Node::AtomById(name, id, at) => {
            if !ctx.box_exists() {
                return err(NO_BOX, *at);
            }
            lookup(ctx.atom_value_by_id(name, *id), *at)?
        }
        Node::AtomVector(name, at) => {
            if !ctx.box_exists() {
                return err(NO_BOX, *at);
            }
            match atom {
                None => return err(ExprErrorKind::AtomVectorInEqual, *at),
                Some(a) => lookup(ctx.atom_value(name, a), *at)?,
            }
        }
        Node::Thermo(name, at) => {
            if !ctx.box_exists() {
                return err(NO_BOX, *at);
            }
            lookup(ctx.thermo(name), *at)?
        }
    })
}

fn eval_math(
    f: Math,
    args: &[Node],
    at: usize,
    ctx: &mut dyn ExprContext,
    atom: Option<usize>,
) -> Result<f64, ExprError> {
    let per_atom = atom.is_some();
    match f {
        Math::Random | Math::Normal => {
            let first = eval_node(nth(args, 0, at)?, ctx, atom)?;
            let second = eval_node(nth(args, 1, at)?, ctx, atom)?;
            let seed_node = nth(args, 2, at)?;
            // equal style reads all three arguments; the per-atom walker reads the seed
            // only while there is no generator, which after folding is never
            let seed = match seed_node {
                Node::Num(v) => *v,
                _ => eval_node(seed_node, ctx, atom)?,
            };
            if f == Math::Normal && second < 0.0 {
                return err(BAD_MATH, at);
            }
            let rng = generator(ctx, c_int(seed), per_atom, at)?;
            Ok(if f == Math::Random {
                rng.uniform() * (second - first) + first
            } else {
                first + second * rng.gaussian()
            })
        }
        // LIGGGHTS's per-atom rounding is a macro that evaluates its argument three times:
        // x - floor(x') decides, then ceil or floor of x''
        Math::Round if per_atom => {
            let arg = nth(args, 0, at)?;
            let x = eval_node(arg, ctx, atom)?;
            let x_floor = eval_node(arg, ctx, atom)?.floor();
            let up = x - x_floor >= 0.5;
            let x_last = eval_node(arg, ctx, atom)?;
            Ok(if up { x_last.ceil() } else { x_last.floor() })
        }
        // per atom, C evaluates the two call arguments right to left
        Math::Atan2 if per_atom => {
            let x = eval_node(nth(args, 1, at)?, ctx, atom)?;
            let y = eval_node(nth(args, 0, at)?, ctx, atom)?;
            Ok(y.atan2(x))
        }
        _ => {
            let mut values = [0.0; 3];
            for (slot, a) in values.iter_mut().zip(args) {
                *slot = eval_node(a, ctx, atom)?;
            }
            let f = if per_atom && f == Math::Swiggle {
                Math::Cwiggle
            } else {
                f
            };
            math(f, &values[..args.len().min(3)], ctx, at)
        }
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

/// Values of a formula piece for all atoms: one number for every atom, or one per atom.
enum Column {
    Same(f64),
    Each(Vec<f64>),
}

impl Column {
    fn into_vec(self, n: usize) -> Vec<f64> {
        match self {
            Column::Same(v) => vec![v; n],
            Column::Each(v) => v,
        }
    }

    fn at(&self, i: usize) -> f64 {
        match self {
            Column::Same(v) => *v,
            Column::Each(v) => v[i],
        }
    }

    /// `f` applied to each value (to the one value if it is the same for all).
    fn map(self, f: impl Fn(f64) -> Result<f64, ExprError>) -> Result<Column, ExprError> {
        Ok(match self {
            Column::Same(v) => Column::Same(f(v)?),
            Column::Each(mut v) => {
                for x in v.iter_mut() {
                    *x = f(*x)?;
                }
                Column::Each(v)
            }
        })
    }
}

/// Whether a formula can be computed a column at a time with the walk's values: no random
/// draws (their order is the walk's), no mask functions, no prefix `!` (an error per atom).
fn columnar(node: &Node) -> bool {
    match node {
        Node::Num(_) | Node::AtomVector(..) | Node::Var(..) | Node::Compute(..) => true,
        Node::Neg(a) | Node::NotLeft(a, _) => columnar(a),
        Node::Bin(_, a, b, _) => columnar(a) && columnar(b),
        Node::Math(Math::Random | Math::Normal, ..) => false,
        Node::Math(_, args, _) => args.iter().all(columnar),
        _ => false,
    }
}

/// A binary operator over columns, value by value as [`binary`] computes it (an error if
/// any value would be one).
fn binary_column(
    op: Op,
    x: &Column,
    y: &Column,
    n: usize,
    at: usize,
) -> Result<Vec<f64>, ExprError> {
    if matches!(op, Op::Div | Op::Mod | Op::Pow) && (0..n).any(|i| y.at(i) == 0.0) {
        return binary(op, 1.0, 0.0, at).map(|_| Vec::new());
    }
    fn zip(x: &Column, y: &Column, n: usize, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        match (x, y) {
            (Column::Each(a), Column::Each(b)) => a.iter().zip(b).map(|(&p, &q)| f(p, q)).collect(),
            (Column::Each(a), Column::Same(q)) => a.iter().map(|&p| f(p, *q)).collect(),
            (Column::Same(p), Column::Each(b)) => b.iter().map(|&q| f(*p, q)).collect(),
            (Column::Same(p), Column::Same(q)) => vec![f(*p, *q); n],
        }
    }
    Ok(match op {
        Op::Add => zip(x, y, n, |p, q| p + q),
        Op::Sub => zip(x, y, n, |p, q| p - q),
        Op::Mul => zip(x, y, n, |p, q| p * q),
        Op::Div => zip(x, y, n, |p, q| p / q),
        Op::Mod => zip(x, y, n, |p, q| p % q),
        Op::Pow => zip(x, y, n, f64::powf),
        _ => zip(x, y, n, |p, q| binary(op, p, q, at).unwrap_or(f64::NAN)),
    })
}

/// The one-argument math functions that depend on nothing but their argument, as [`math`]
/// computes them (None where it would give an error).
fn plain_math(f: Math) -> Option<fn(f64) -> Option<f64>> {
    use Math::*;
    // explicit comparisons: a NaN argument passes the range checks, as in `math`
    #[allow(clippy::manual_range_contains, clippy::neg_cmp_op_on_partial_ord)]
    Some(match f {
        Sqrt => |a| (!(a < 0.0)).then(|| a.sqrt()),
        Exp => |a| Some(a.exp()),
        Ln => |a| (!(a <= 0.0)).then(|| a.ln()),
        Log => |a| (!(a <= 0.0)).then(|| a.log10()),
        Abs => |a| Some(a.abs()),
        Sin => |a| Some(a.sin()),
        Cos => |a| Some(a.cos()),
        Tan => |a| Some(a.tan()),
        Asin => |a| (!(a < -1.0 || a > 1.0)).then(|| a.asin()),
        Acos => |a| (!(a < -1.0 || a > 1.0)).then(|| a.acos()),
        Atan => |a| Some(a.atan()),
        Ceil => |a| Some(a.ceil()),
        Floor => |a| Some(a.floor()),
        Round => |a| Some(round_half_up(a)),
        _ => return None,
    })
}

/// A formula piece for all `n` atoms; any error (the walk then reports it as LIGGGHTS).
fn eval_column(node: &Node, ctx: &mut dyn ExprContext, n: usize) -> Result<Column, ExprError> {
    let fail = |e: VariableError| ExprError {
        kind: e.into(),
        offset: 0,
    };
    Ok(match node {
        Node::Num(v) => Column::Same(*v),
        Node::Neg(a) => eval_column(a, ctx, n)?.map(|x| Ok(-x))?,
        Node::NotLeft(a, _) => eval_column(a, ctx, n)?.map(|x| Ok(truth(x == 0.0)))?,
        Node::Bin(op, a, b, at) => {
            let x = eval_column(a, ctx, n)?;
            let y = eval_column(b, ctx, n)?;
            match (x, y) {
                (Column::Same(x), Column::Same(y)) => Column::Same(binary(*op, x, y, *at)?),
                (x, y) => Column::Each(binary_column(*op, &x, &y, n, *at)?),
            }
        }
        Node::Math(f, args, at) => {
            // the walk turns swiggle() into cwiggle() for atoms
            let f = if *f == Math::Swiggle {
                Math::Cwiggle
            } else {
                *f
            };
            let cols = args
                .iter()
                .map(|a| eval_column(a, ctx, n))
                .collect::<Result<Vec<Column>, ExprError>>()?;
            if cols.iter().all(|c| matches!(c, Column::Same(_))) {
                let v: Vec<f64> = cols.iter().map(|c| c.at(0)).collect();
                Column::Same(math(f, &v, ctx, *at)?)
            } else if let (1, Some(g)) = (cols.len(), plain_math(f)) {
                // one argument, no step or time: a tight loop
                let mut out = Vec::with_capacity(n);
                for i in 0..n {
                    out.push(g(cols[0].at(i)).ok_or(ExprError {
                        kind: ExprErrorKind::NotColumnar,
                        offset: *at,
                    })?);
                }
                Column::Each(out)
            } else {
                let mut out = Vec::with_capacity(n);
                let mut v = [0.0; 3];
                for i in 0..n {
                    for (slot, c) in v.iter_mut().zip(&cols) {
                        *slot = c.at(i);
                    }
                    out.push(math(f, &v[..cols.len().min(3)], ctx, *at)?);
                }
                Column::Each(out)
            }
        }
        Node::AtomVector(name, _) => Column::Each(ctx.atom_column(name, n).map_err(fail)?),
        Node::Var(name, index, _) => {
            Column::Each(ctx.variable_column(name, *index, n).map_err(fail)?)
        }
        Node::Compute(id, i, j, _) => {
            Column::Each(ctx.compute_column(id, *i, *j, n).map_err(fail)?)
        }
        _ => return err(ExprErrorKind::NotColumnar, 0),
    })
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

fn boolean_level(text: &str, start: usize, end: usize, nesting: usize) -> Result<f64, ExprError> {
    if nesting >= MAX_NESTING {
        return err(TOO_DEEP, start);
    }
    let bytes = &text.as_bytes()[..end];
    let at = |k: usize| bytes.get(k).copied().unwrap_or(0);
    let mut args: Vec<f64> = Vec::new();
    let mut ops: Vec<Pending> = Vec::new();
    let mut expect_arg = true;
    let mut i = start;
    loop {
        let c = at(i);
        if c != 0 && is_c_space(c) {
            i += 1;
        } else if c == b'(' {
            if !expect_arg {
                return err(BOOLEAN, i);
            }
            expect_arg = false;
            let Some(close) = matching_paren(bytes, i) else {
                return err(SYNTAX, i);
            };
            args.push(boolean_level(text, i + 1, close, nesting + 1)?);
            i = close + 1;
        } else if c.is_ascii_digit() || c == b'.' || c == b'-' {
            if !expect_arg {
                return err(BOOLEAN, i);
            }
            expect_arg = false;
            let from = i;
            i += 1;
            while at(i).is_ascii_digit() || at(i) == b'.' {
                i += 1;
            }
            if matches!(at(i), b'e' | b'E') {
                i += 1;
                if matches!(at(i), b'+' | b'-') {
                    i += 1;
                }
                while at(i).is_ascii_digit() {
                    i += 1;
                }
            }
            args.push(literal(&text[from..i], from)?);
        } else if c == 0 || b"<>=!&|".contains(&c) {
            let Ok((op, len)) = operator_at(bytes, i) else {
                return err(BOOLEAN, i);
            };
            let op_at = i;
            i += len;
            if expect_arg {
                if let Some(Pending::Not(p)) = op {
                    ops.push(Pending::Not(p));
                    continue;
                }
                return err(BOOLEAN, op_at);
            }
            expect_arg = true;
            let level = op.map_or(0, Pending::precedence);
            while let Some(&top) = ops.last() {
                if top.precedence() < level {
                    break;
                }
                ops.pop();
                let Some(y) = args.pop() else {
                    return err(BOOLEAN, op_at);
                };
                let value = match top {
                    Pending::Not(_) | Pending::Neg => truth(y == 0.0),
                    Pending::Bin(op, p) => {
                        let Some(x) = args.pop() else {
                            return err(BOOLEAN, op_at);
                        };
                        binary(op, x, y, p)?
                    }
                };
                args.push(value);
            }
            match op {
                None => break,
                Some(op) => ops.push(op),
            }
        } else {
            return err(BOOLEAN, i);
        }
    }
    if !ops.is_empty() || args.len() != 1 {
        return err(BOOLEAN, end.min(i));
    }
    Ok(args[0])
}

#[cfg(test)]
// expected values are copied digit for digit from LIGGGHTS's %.17g output (PI included)
#[allow(clippy::excessive_precision, clippy::approx_constant)]
mod tests {
    use super::*;

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

    #[test]
    fn precedence_and_associativity() {
        let cases: &[(&str, &str)] = &[
            ("2^3^2", "64"),
            ("-2^2", "4"),
            ("7%3", "1"),
            ("-7%3", "-1"),
            ("5%-3", "2"),
            ("5.5%2", "1.5"),
            ("!1+1", "1"),
            ("2*-3", "-6"),
            ("- -3", "3"),
            ("--3", "3"),
            ("----1", "1"),
            ("!!5", "1"),
            ("1 < 2 == 1", "1"),
            ("3>2>1", "0"),
            ("1+2*3^4", "163"),
            ("1<2+3*4^-5", "1"),
            ("1||2&&3==4<5+6*7^-8", "1"),
            ("1+2+3+4+5+6+7+8+9+10", "55"),
            ("(-2)^3", "-8"),
            ("0^0.5", "0"),
            ("2^0.5", "1.4142135623731"),
        ];
        for (formula, want) in cases {
            assert_eq!(g15(ev(formula)), *want, "{formula}");
        }
    }

    #[test]
    fn numbers_read_like_atof() {
        let cases: &[(&str, &str)] = &[
            ("1e-5", "1e-05"),
            (".5", "0.5"),
            ("5.", "5"),
            ("1.2.3", "1.2"),
            ("1e", "1"),
            ("1e+", "1"),
            ("..5", "0"),
            ("1e308*10", "inf"),
            ("-1e308*10", "-inf"),
            ("1/(1e308*10)", "0"),
            ("0^-1", "inf"),
            ("3%(1e308*10)", "3"),
            ("1e-400", "0"),
        ];
        for (formula, want) in cases {
            assert_eq!(g15(ev(formula)), *want, "{formula}");
        }
        // a literal beyond a double is an error naming it (LIGGGHTS's atof makes it inf)
        for big in ["1e400", "-1e400", "2*1e309"] {
            let e = fails(big);
            assert!(e.contains("1e400") || e.contains("1e309"), "{big}: {e}");
        }
        // liggghts prints -nan for these, and -0 for the signed zeros
        for nan in [
            "1e308*10-1e308*10",
            "(-2)^0.5",
            "sqrt(1e308*10-1e308*10)",
            "(1e308*10)%3",
        ] {
            let v = ev(nan);
            assert!(v.is_nan() && v.is_sign_negative(), "{nan}: {v}");
        }
        for zero in ["-0", "0*-1", "sqrt(-0)", "ceil(-0.5)", "round(-0.5)"] {
            let v = ev(zero);
            assert!(v == 0.0 && v.is_sign_negative(), "{zero}: {v}");
        }
        assert_eq!(ev("(1e308*10-1e308*10)==(1e308*10-1e308*10)"), 0.0);
        assert_eq!(ev("!(1e308*10-1e308*10)"), 0.0);
    }

    #[test]
    fn math_functions() {
        let cases: &[(&str, &str)] = &[
            ("round(-2.5)", "-2"),
            ("round(2.5)", "3"),
            ("round(0.49999999999999994)", "0"),
            ("atan2(1,1)", "0.785398163397448"),
            ("atan2(0,0)", "0"),
            ("atan2(-0,-1)", "-3.14159265358979"),
            ("exp(1)", "2.71828182845905"),
            ("exp(710)", "inf"),
            ("abs(-0)", "0"),
            ("floor(-0.5)", "-1"),
            ("tan(PI/2)", "1.63312393531954e+16"),
            ("cos(PI)", "-1"),
            ("log(10)", "1"),
            ("ln(2)", "0.693147180559945"),
            ("PI", "3.14159265358979"),
            ("stagger(1000,100)", "100"),
            ("stagger(10.9,3.5)", "3"),
            ("logfreq(100,4,10)", "100"),
            ("stride(0,100,10)", "10"),
        ];
        for (formula, want) in cases {
            assert_eq!(g15(ev(formula)), *want, "{formula}");
        }
        assert_eq!(ev("sqrt(16)+abs(-2)+floor(2.7)+ceil(2.1)"), 11.0);
        assert_eq!(ev("log(1000)+ln(exp(2))"), 5.0);
    }

    #[test]
    fn step_functions_during_a_run() {
        // liggghts: two atoms, timestep 0.25, thermo 1 and thermo_modify format float %.17g,
        // thermo_style custom step v_sw v_cw v_rp v_vd v_sg v_lf v_lg v_st with
        //   sw = swiggle(1,2,3)  cw = cwiggle(1,2,3)  rp = ramp(0,10)  vd = vdisplace(1,2)
        //   sg = stagger(10,3)  lf = logfreq(1,2,10)  lg = logfreq(2,3,5)  st = stride(5,20,4)
        // during "run 25"
        let table: &[(i64, [f64; 8])] = &[
            (0, [1.0, 1.0, 0.0, 1.0, 3.0, 1.0, 2.0, 5.0]),
            (
                1,
                [
                    2.0,
                    1.2679491924311226,
                    0.40000000000000002,
                    1.5,
                    3.0,
                    2.0,
                    2.0,
                    5.0,
                ],
            ),
            (
                2,
                [
                    2.7320508075688772,
                    1.9999999999999998,
                    0.80000000000000004,
                    2.0,
                    3.0,
                    10.0,
                    4.0,
                    5.0,
                ],
            ),
            (
                5,
                [
                    2.0000000000000009,
                    4.7320508075688767,
                    2.0,
                    3.5,
                    10.0,
                    10.0,
                    6.0,
                    9.0,
                ],
            ),
            (
                7,
                [
                    5.5511151231257827e-16,
                    4.7320508075688776,
                    2.8000000000000003,
                    4.5,
                    10.0,
                    10.0,
                    10.0,
                    9.0,
                ],
            ),
            (
                10,
                [
                    -0.73205080756887808,
                    2.0000000000000013,
                    4.0,
                    6.0,
                    13.0,
                    20.0,
                    20.0,
                    13.0,
                ],
            ),
            (
                13,
                [
                    1.9999999999999987,
                    1.2679491924311219,
                    5.2000000000000002,
                    7.5,
                    20.0,
                    20.0,
                    20.0,
                    17.0,
                ],
            ),
            (
                17,
                [
                    2.0000000000000027,
                    4.7320508075688759,
                    6.8000000000000007,
                    9.5,
                    20.0,
                    20.0,
                    20.0,
                    9e18,
                ],
            ),
            (
                20,
                [
                    -0.73205080756887564,
                    4.0000000000000027,
                    8.0,
                    11.0,
                    23.0,
                    100.0,
                    30.0,
                    9e18,
                ],
            ),
            (
                23,
                [
                    -2.886579864025407e-15,
                    1.2679491924311244,
                    9.2000000000000011,
                    12.5,
                    30.0,
                    100.0,
                    30.0,
                    9e18,
                ],
            ),
            (
                25,
                [
                    1.9999999999999982,
                    1.2679491924311217,
                    10.0,
                    13.5,
                    30.0,
                    100.0,
                    30.0,
                    9e18,
                ],
            ),
        ];
        let formulas = [
            "swiggle(1,2,3)",
            "cwiggle(1,2,3)",
            "ramp(0,10)",
            "vdisplace(1,2)",
            "stagger(10,3)",
            "logfreq(1,2,10)",
            "logfreq(2,3,5)",
            "stride(5,20,4)",
        ];
        for (step, want) in table {
            let mut w = world();
            w.step = *step;
            w.run = Some((0, 25));
            w.dt = 0.25;
            for (formula, want) in formulas.iter().zip(want) {
                assert_eq!(
                    evaluate(formula, &mut w).unwrap(),
                    *want,
                    "{formula} at {step}"
                );
                let parsed = Expr::parse(formula).unwrap();
                assert_eq!(parsed.eval(&mut w, None).unwrap(), *want);
            }
        }
    }

    #[test]
    fn errors_as_liggghts() {
        let cases: &[(&str, &str)] = &[
            ("2^0", "Power by 0 in variable formula"),
            ("1/0", "Divide by 0 in variable formula"),
            ("5%0", "Modulo 0 in variable formula"),
            ("sqrt(-1)", "Sqrt of negative value in variable formula"),
            ("ln(0)", "Log of zero/negative value in variable formula"),
            ("log(-0)", "Log of zero/negative value in variable formula"),
            ("asin(2)", "Arcsin of invalid value in variable formula"),
            ("acos(-1.5)", "Arccos of invalid value in variable formula"),
            ("sqrt(1,2)", BAD_MATH),
            ("sqrt()", SYNTAX),
            ("atan2(1,2,3,4)", SYNTAX),
            ("foo(1)", BAD_NAME),
            (
                "ramp(0,1)",
                "Cannot use ramp in variable formula between runs",
            ),
            (
                "vdisplace(0,1)",
                "Cannot use vdisplace in variable formula between runs",
            ),
            (
                "swiggle(1,2,0)",
                "Cannot use swiggle in variable formula between runs",
            ),
            (
                "cwiggle(1,2,3)",
                "Cannot use cwiggle in variable formula between runs",
            ),
            ("normal(0,-1,15485863)", BAD_MATH),
            ("normal(0,-1,0)", BAD_MATH),
            ("random(0,1,0)", BAD_MATH),
            ("random(0,1,-5)", BAD_MATH),
            ("random(0,1,1e10)", BAD_MATH),
            ("random(0,1,1e308*10-1e308*10)", BAD_MATH),
            ("stagger(10,10)", BAD_MATH),
            ("stagger(1e308*10-1e308*10,1)", BAD_MATH),
            ("logfreq(1,3,3)", BAD_MATH),
            ("stride(5,1,1)", BAD_MATH),
            ("stride(1,5,0)", BAD_MATH),
            ("1 ! 2", SYNTAX),
            ("3 = 3", SYNTAX),
            ("1 & 1", SYNTAX),
            ("1 +", SYNTAX),
            ("", SYNTAX),
            ("(1", SYNTAX),
            ("2 3", SYNTAX),
            ("1 $", SYNTAX),
            ("x", "Atom vector in equal-style variable formula"),
            (
                "gmask(all)",
                "Gmask function in equal-style variable formula",
            ),
            ("rmask(r)", "Rmask function in equal-style variable formula"),
            (
                "grmask(all,r)",
                "Grmask function in equal-style variable formula",
            ),
            ("pi", "Invalid thermo keyword in variable formula"),
            ("sqrt (4)", "Invalid thermo keyword in variable formula"),
            ("x[0]", "Index between variable brackets must be positive"),
            (
                "x[4294967296]",
                "Index between variable brackets must be positive",
            ),
            ("x[a]", "Non digit character between brackets in variable"),
            ("x[1", "Mismatched brackets in variable"),
            ("(x[1)", "Mismatched brackets in variable"),
            ("x[]", "Empty brackets in variable"),
            ("v_a[1]", "Mismatched variable in variable formula"),
            ("c_nope", "Invalid compute ID in variable formula"),
            ("v_nope", "Invalid variable name in variable formula"),
            ("f_nope", "Invalid fix ID in variable formula"),
            ("count( all)", "Group ID in variable formula does not exist"),
            ("xcm(all, x)", "Invalid group function in variable formula"),
            ("foo[1]", "Invalid atom vector in variable formula"),
        ];
        for (formula, want) in cases {
            assert_eq!(fails(formula), *want, "{formula}");
        }
    }

    #[test]
    fn errors_come_in_liggghts_order() {
        // liggghts computes while it reads: the first problem met wins
        let cases: &[(&str, &str)] = &[
            ("count(all)+foo(1)", BAD_NAME),
            ("1/0 + foo(1)", "Divide by 0 in variable formula"),
            ("v_nope +", "Invalid variable name in variable formula"),
            ("sqrt(-1, 1/0)", "Divide by 0 in variable formula"),
            ("sqrt(1/0, 2)", "Divide by 0 in variable formula"),
            ("1 ! 1/0", "Divide by 0 in variable formula"),
            ("1 ! (2", SYNTAX),
        ];
        for (formula, want) in cases {
            assert_eq!(fails(formula), *want, "{formula}");
        }
        // without a box (liggghts before create_box)
        for formula in ["step", "x", "x[1]", "x[0]", "c_x[0]", "pi", "sqrt (4)"] {
            assert_eq!(fails_without_box(formula), NO_BOX, "{formula}");
        }
        let mut w = world();
        w.has_box = false;
        assert_eq!(
            evaluate("PI+v_a", &mut w).unwrap(),
            std::f64::consts::PI + 2.0
        );
        // lookups happen in formula order
        let mut w = world();
        evaluate("count(all) + v_a*c_x[2] - step", &mut w).unwrap();
        assert_eq!(w.lookups, ["count(all)", "v_a", "c_x", "step"]);
    }

    #[test]
    fn references_and_functions() {
        assert_eq!(ev("v_a*c_x[2]+f_y"), 2.0 * 9.0 + 8.0);
        assert_eq!(ev("x[2]"), 0.4);
        assert_eq!(ev("count(all)"), 2.0);
        assert_eq!(ev("xcm(all,x)"), 0.25);
        assert_eq!(ev("sum(c_x)"), 21.0);
        assert_eq!(ev("atoms"), 2.0);
        // group and special arguments are passed raw, split at the first two commas
        let mut w = world();
        let _ = evaluate("bound(all,xmin, r,  s)", &mut w);
        assert_eq!(w.lookups, ["bound(all,xmin, r,  s)"]);
        assert_eq!(
            Expr::parse("count(all, a)").unwrap().root,
            Node::Group("count".into(), vec!["all".into(), " a".into()], 0)
        );
    }

    #[test]
    fn error_offsets() {
        assert_eq!(evaluate("1 +\n 2 $", &mut world()).unwrap_err().offset, 7);
        assert_eq!(evaluate("2 * (3 / 0)", &mut world()).unwrap_err().offset, 7);
        assert_eq!(
            evaluate("1 + sqrt(-1)", &mut world()).unwrap_err().offset,
            4
        );
        assert_eq!(evaluate("1 + v_nope", &mut world()).unwrap_err().offset, 4);
        assert_eq!(evaluate("x[1a]", &mut world()).unwrap_err().offset, 3);
        assert_eq!(Expr::parse("(1 + )").unwrap_err().offset, 5);
    }

    #[test]
    fn random_stream_matches_liggghts() {
        // print "$(random(0,1,S)) $(random(0,1,0)) $(random(0,1,12345))": once the
        // generator exists its seed argument is ignored, even an invalid one
        let mut w = world();
        let draws: Vec<f64> = ["random(0,1,S)", "random(0,1,0)", "random(0,1,12345)"]
            .iter()
            .map(|f| evaluate(&f.replace('S', &S.to_string()), &mut w).unwrap())
            .collect();
        assert_eq!(
            draws,
            [
                0.86316907405853271484,
                0.6564229130744934082,
                0.88727664947509765625
            ]
        );
        // print "${b}" with b = random(0,1,S) after ten draws of another variable
        // (one generator for all equal-style formulas)
        let mut w = world();
        let f = format!("random(0,1,{S})");
        for _ in 0..10 {
            evaluate(&f, &mut w).unwrap();
        }
        assert_eq!(g15(evaluate(&f, &mut w).unwrap()), "0.273580014705658");
        // random(1,0,S) and normal(1,0,S) as first draws
        assert_eq!(g15(ev(&format!("random(1,0,{S})"))), "0.136830925941467");
        assert_eq!(ev(&format!("normal(1,0,{S})")), 1.0);
        // a non-prime seed is refused when the generator is made
        assert!(fails("random(0,1,12345)").contains("The random seed used was 12345"));
    }

    /// Per-atom values of an atom-style formula for the two atoms (fresh world each time,
    /// as liggghts was run once per formula).
    fn per_atom(formula: &str, w: &mut World) -> Result<Vec<f64>, String> {
        let e = Expr::parse_atom(formula, w).map_err(|e| e.to_string())?;
        e.eval_atoms(w, 2).map_err(|e| e.to_string())
    }

    fn per_atom_walk(formula: &str, w: &mut World) -> Result<Vec<f64>, String> {
        let e = Expr::parse_atom(formula, w).map_err(|e| e.to_string())?;
        (0..2)
            .map(|a| e.eval(w, Some(a)).map_err(|e| e.to_string()))
            .collect()
    }

    #[test]
    fn whole_columns_equal_the_atom_by_atom_walk() {
        for formula in [
            "x*x+2.5*x-1/(x+0.3)",
            "-x^3%0.07",
            "sqrt(x)*cos(2*x)+atan2(x,0.2)-round(10*x)+floor(x)+ceil(x)",
            "(x>0.2)&&(x<0.5)||(id==1)",
            "swiggle(0,1,2)+x",
            "1/(x-0.1)",
            "sqrt(x-0.2)",
            "ln(x-0.1)+log(x)",
            "asin(x*3)",
            "x^(x-0.1)",
            "mass*vx+r*density",
        ] {
            let (mut a, mut b) = (world(), world());
            a.run = Some((0, 10));
            b.run = Some((0, 10));
            let col = per_atom(formula, &mut a);
            let walk = per_atom_walk(formula, &mut b);
            match (&col, &walk) {
                (Ok(x), Ok(y)) => assert!(
                    x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits()),
                    "{formula}: {x:?} vs {y:?}"
                ),
                _ => assert_eq!(col, walk, "{formula}"),
            }
        }
    }

    #[test]
    fn atom_style_as_liggghts() {
        // liggghts: two granular atoms at x = 0.1 and 0.4, "variable s atom FORMULA",
        // dumped as "id v_s" with %.17g during "run 0" (S = 15485863)
        let cases: &[(&str, [f64; 2])] = &[
            ("x", [0.10000000000000001, 0.40000000000000002]),
            ("id*2", [2.0, 4.0]),
            ("x[2]", [0.40000000000000002, 0.40000000000000002]),
            ("step", [0.0, 0.0]),
            ("PI", [3.1415926535897931, 3.1415926535897931]),
            ("gmask(all)", [1.0, 1.0]),
            ("random(0,1,S)", [0.86316907405853271, 0.65642291307449341]),
            ("normal(0,1,S)", [0.38324647910204879, 0.88978824275827484]),
            (
                "-random(0,1,S)",
                [-0.86316907405853271, -0.65642291307449341],
            ),
            // right operand first for / % ^
            (
                "random(0,1,S)/random(1,2,S)",
                [0.35231526876120284, 0.24990537925862819],
            ),
            (
                "random(0,1,S)%random(2,3,S)",
                [0.65642291307449341, 0.47164058685302734],
            ),
            (
                "random(0,1,S)^random(2,3,S)",
                [0.2996167684341281, 0.11418923293787246],
            ),
            // left operand first for the others
            (
                "random(0,1,S)-random(0,2,S)",
                [-0.4496767520904541, -0.056004524230957031],
            ),
            (
                "random(0,1,S)+random(0,2,S)",
                [2.1760149002075195, 1.8305578231811523],
            ),
            (
                "random(0,1,S)*random(0,2,S)",
                [1.1332079161386304, 0.83695135931884579],
            ),
            ("random(0,1,S)>=random(0,1,S)", [1.0, 1.0]),
            ("random(0,1,S)<random(0,1,S)", [0.0, 0.0]),
            // && and || short-circuit
            (
                "random(0,1,S) - (x<0.2 && random(0,1,S)<2)",
                [-0.13683092594146729, 0.88727664947509766],
            ),
            (
                "random(0,1,S) - (x<0.2 || random(0,1,S)<2)",
                [-0.13683092594146729, -0.34357708692550659],
            ),
            // atan2's arguments are evaluated right to left
            (
                "atan2(random(0,1,S),random(0,1,S))",
                [0.65017470889489115, 0.48857552091690432],
            ),
            // round() evaluates its argument three times
            (
                "round(random(0,2,S))*10+random(0,1,S)",
                [20.471640586853027, 10.388184249401093],
            ),
            (
                "random(random(0,1,S),random(5,6,S),S)",
                [5.1161112804242634, 4.7766567494516963],
            ),
            (
                "normal(random(0,1,S),1,S)",
                [1.6497417787037096, 0.78934110913404643],
            ),
            (
                "ramp(random(0,1,S),random(0,2,S))",
                [0.86316907405853271, 0.88727664947509766],
            ),
            ("random(0,1,S)*0+1", [1.0, 1.0]),
            // `a ! b` is `!a` in atom style
            ("x ! 1", [0.0, 0.0]),
            ("0 ! 5", [1.0, 1.0]),
            ("0 ! x", [1.0, 1.0]),
            ("2 + 0 ! 5", [3.0, 3.0]),
            ("(x ! 3) + 1", [1.0, 1.0]),
            ("x < 0.2 ! 1", [0.0, 0.0]),
        ];
        for (formula, want) in cases {
            let mut w = world();
            w.run = Some((0, 0));
            let got = per_atom(&formula.replace('S', &S.to_string()), &mut w)
                .unwrap_or_else(|e| panic!("{formula}: {e}"));
            assert_eq!(got, want.to_vec(), "{formula}");
        }
    }

    #[test]
    fn atom_style_errors_as_liggghts() {
        let cases: &[(&str, &str)] = &[
            ("!x", SYNTAX),
            ("1+!x", SYNTAX),
            ("!0", SYNTAX),
            ("x^0", "Power by 0 in variable formula"),
            ("1/0", "Divide by 0 in variable formula"),
            ("x/0", "Divide by 0 in variable formula"),
            ("sqrt(-1)", "Sqrt of negative value in variable formula"),
            ("sqrt(-x)", "Sqrt of negative value in variable formula"),
        ];
        for (formula, want) in cases {
            let mut w = world();
            w.run = Some((0, 0));
            assert_eq!(per_atom(formula, &mut w).unwrap_err(), *want, "{formula}");
        }
        // run-only functions are refused while reading, even where unused
        let mut w = world();
        assert_eq!(
            per_atom("x + 0*ramp(0,1)", &mut w).unwrap_err(),
            "Cannot use ramp in variable formula between runs"
        );
    }

    #[test]
    fn atom_style_swiggle_is_cwiggle() {
        // liggghts, timestep 0.25, "run 2", dump every step: at step 1 the atom-style
        // swiggle(1,2,3) prints 1.2679491924311226 (cwiggle's value), equal style prints 2
        let mut w = world();
        w.step = 1;
        w.run = Some((0, 2));
        w.dt = 0.25;
        assert_eq!(
            per_atom("swiggle(1,2,3)", &mut w).unwrap(),
            [1.2679491924311226; 2]
        );
        assert_eq!(
            per_atom("x*0+swiggle(1,2,3)", &mut w).unwrap(),
            [1.2679491924311226; 2]
        );
        assert_eq!(evaluate("swiggle(1,2,3)", &mut w).unwrap(), 2.0);
        let e = Expr::parse("swiggle(1,2,3)").unwrap();
        assert_eq!(e.eval(&mut w, Some(0)).unwrap(), 1.2679491924311226);
    }

    #[test]
    fn atom_style_reads_globals_once() {
        let mut w = world();
        let e = Expr::parse_atom("x*v_a + step + count(all)", &mut w).unwrap();
        assert_eq!(w.lookups, ["v_a", "step", "count(all)"]);
        assert_eq!(e.eval(&mut w, Some(1)).unwrap(), 0.8 + 2.0);
        assert_eq!(w.lookups.len(), 3);
        assert!(e.is_per_atom());
        assert!(!Expr::parse("1+v_a").unwrap().is_per_atom());
        assert!(Expr::parse("gmask(all)*2").unwrap().is_per_atom());
        // the seed of the first random() met while folding makes the generator
        let mut w = world();
        Expr::parse_atom("random(0,1,32452843)/random(0,1,15485863)", &mut w).unwrap();
        let mut want = RanMars::new(32452843).unwrap();
        assert_eq!(w.atom_rng.as_mut().unwrap().uniform(), want.uniform());
    }

    #[test]
    fn errors_are_variants_with_positions() {
        let e = evaluate("1 + 2/0", &mut world()).unwrap_err();
        assert_eq!(e.kind, ExprErrorKind::DivideByZero);
        assert_eq!(e.to_string(), "Divide by 0 in variable formula");
        let e = Expr::parse("1 ! 2").unwrap_err();
        assert_eq!((e.kind, e.offset), (ExprErrorKind::Syntax, 5));
        let e = evaluate("2*1e400", &mut world()).unwrap_err();
        assert_eq!(e.kind, ExprErrorKind::OutOfRange("1e400".into()));
        assert_eq!(e.offset, 2);
        let e = evaluate("x[0]", &mut world()).unwrap_err();
        assert_eq!(e.kind, ExprErrorKind::IndexNotPositive);
        // a lookup's own error, unchanged
        let e = evaluate("1 + v_nope", &mut world()).unwrap_err();
        assert_eq!(
            e.kind,
            ExprErrorKind::Lookup(VariableError::Invalid(
                "Invalid variable name in variable formula".into()
            ))
        );
        assert_eq!(e.offset, 4);
        // a value only a run knows is told apart by its variant, not its text
        let e = evaluate("1 + v_later", &mut world()).unwrap_err();
        assert!(e.is_known_when_run(), "{e:?}");
        assert!(!evaluate("1/0", &mut world())
            .unwrap_err()
            .is_known_when_run());
        // a seed LIGGGHTS refuses, typed
        let e = evaluate("random(0,1,12345)", &mut world()).unwrap_err();
        assert!(
            matches!(
                e.kind,
                ExprErrorKind::Lookup(VariableError::Seed(
                    crate::util::random::SeedError::NotPrime(12345)
                ))
            ),
            "{e:?}"
        );
        // a formula's error seen as the variable's: the kind is kept
        let v: VariableError = evaluate("sqrt(-1)", &mut world()).unwrap_err().into();
        assert_eq!(
            v,
            VariableError::Formula(Box::new(ExprErrorKind::SqrtNegative))
        );
        assert_eq!(v.to_string(), "Sqrt of negative value in variable formula");
        // the text of a value only a run knows, crossing a layer that passes text, comes
        // back as the variant
        let v = VariableError::from(String::from(VariableError::KnownWhenRun));
        assert!(v.is_known_when_run());
    }

    #[test]
    fn syntax_only_parse() {
        let e = Expr::parse("x*2 + mass").unwrap();
        assert!(e.is_per_atom());
        assert_eq!(
            e.eval(&mut world(), None).unwrap_err().to_string(),
            "Atom vector in equal-style variable formula"
        );
        assert_eq!(Expr::parse("1 ! 2").unwrap_err().to_string(), SYNTAX);
        assert_eq!(Expr::parse("foo(1)").unwrap_err().to_string(), BAD_NAME);
        let e = Expr::parse("1/0").unwrap();
        assert_eq!(
            e.eval(&mut world(), None).unwrap_err().to_string(),
            "Divide by 0 in variable formula"
        );
    }

    #[test]
    fn boolean_conditions() {
        // liggghts: if "COND" then "print T" else "print F" (T means nonzero)
        let truths: &[(&str, bool)] = &[
            ("2.5 > 1", true),
            ("-1", true),
            ("-", false),
            ("!0", true),
            ("!!0", false),
            ("((1))", true),
            ("1e3 < 999", false),
            ("1 == 1.0", true),
            ("-e5 == 0", true),
            (".", false),
            ("1..2 == 1", true),
            ("1 == 1 == 1", true),
            ("2 || 0 && 0", true),
            ("!1 || 1", true),
            ("-1 >= 0 || (3 == 3 && !0)", true),
        ];
        for (cond, want) in truths {
            assert_eq!(evaluate_boolean(cond).unwrap() != 0.0, *want, "{cond}");
        }
        assert_eq!(evaluate_boolean("-2.5").unwrap(), -2.5);
        for cond in [
            "abc == abc",
            "1 +1",
            "",
            "- 1",
            "1 ! 2",
            "a",
            "0x10",
            ")",
            "()",
            "1 2",
            "1 ! 1/0",
        ] {
            assert_eq!(
                evaluate_boolean(cond).unwrap_err().to_string(),
                BOOLEAN,
                "{cond}"
            );
        }
        assert_eq!(evaluate_boolean("(1").unwrap_err().to_string(), SYNTAX);
        assert_eq!(evaluate_boolean("1 ! (2").unwrap_err().to_string(), SYNTAX);
    }

    #[test]
    fn deep_formulas_do_not_overflow_the_stack() {
        let deep = "(".repeat(5000) + "1" + &")".repeat(5000);
        assert_eq!(fails(&deep), TOO_DEEP);
        assert_eq!(evaluate_boolean(&deep).unwrap_err().to_string(), TOO_DEEP);
        assert_eq!(Expr::parse(&deep).unwrap_err().to_string(), TOO_DEEP);
        let chain = vec!["1"; 5000].join("+");
        assert_eq!(ev(&chain), 5000.0);
        assert_eq!(Expr::parse(&chain).unwrap_err().to_string(), TOO_DEEP);
        let fine = vec!["1"; 900].join("+");
        assert_eq!(
            Expr::parse(&fine)
                .unwrap()
                .eval(&mut world(), None)
                .unwrap(),
            900.0
        );
        // equal style computes as it goes, so long prefix chains are no problem there
        assert_eq!(ev(&("-".repeat(5000) + "1")), 1.0);
        assert_eq!(
            Expr::parse(&("-".repeat(5000) + "1"))
                .unwrap_err()
                .to_string(),
            TOO_DEEP
        );
    }

    #[test]
    fn c_int_is_x86_truncation() {
        assert_eq!(c_int(2.9), 2);
        assert_eq!(c_int(-2.9), -2);
        assert_eq!(c_int(1e10), i32::MIN);
        assert_eq!(c_int(-1e10), i32::MIN);
        assert_eq!(c_int(f64::NAN), i32::MIN);
        assert_eq!(c_int(2147483647.5), i32::MAX);
    }

    use proptest::prelude::*;

    proptest! {
        #[test]
        fn never_panics(text in "\\PC{0,40}") {
            let _ = evaluate(&text, &mut world());
            let _ = evaluate_boolean(&text);
            if let Ok(e) = Expr::parse(&text) {
                let _ = e.eval(&mut world(), None);
                let _ = e.eval(&mut world(), Some(1));
            }
            let mut w = world();
            if let Ok(e) = Expr::parse_atom(&text, &mut w) {
                let _ = e.eval(&mut w, Some(0));
            }
        }

        #[test]
        fn never_panics_on_formula_soup(
            parts in proptest::collection::vec(
                prop_oneof![
                    Just("("), Just(")"), Just("["), Just("]"), Just(","), Just("-"),
                    Just("!"), Just("^"), Just("/"), Just("%"), Just("&&"), Just("||"),
                    Just("=="), Just("<"), Just("1"), Just("0"), Just(".5e3"), Just("x"),
                    Just("v_a"), Just("c_x"), Just("step"), Just("PI"), Just("sqrt"),
                    Just("random"), Just("round"), Just("atan2"), Just("stride"),
                    Just("logfreq"), Just("count"), Just("gmask"), Just(" "), Just("15485863"),
                ],
                0..30,
            )
        ) {
            let text = parts.concat();
            let mut w = world();
            w.run = Some((0, 10));
            w.step = 5;
            let _ = evaluate(&text, &mut w);
            let _ = evaluate_boolean(&text);
            if let Ok(e) = Expr::parse(&text) {
                let _ = e.eval(&mut w, None);
                let _ = e.eval(&mut w, Some(1));
            }
            if let Ok(e) = Expr::parse_atom(&text, &mut w) {
                let _ = e.eval(&mut w, Some(0));
            }
        }
    }
}
