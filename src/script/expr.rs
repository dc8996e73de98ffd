//! Equal- and atom-style formulas, parsed and evaluated as LIGGGHTS 3.8.0 does.
//!
//! Grammar and rules follow LIGGGHTS's `Variable::evaluate`: operators by precedence
//! `||` < `&&` < `== !=` < `< <= > >=` < `+ -` < `* / %` < `^` < unary `- !`, all binary
//! operators left-associative (so `2^3^2` is 64 and `-2^2` is 4); `/0`, `%0` and `^0` are
//! errors; a bare word is, in this order, `c_`/`f_`/`v_` reference, function call, atom value
//! `x[N]`, per-atom vector, the constant `PI`, or a thermo keyword. A formula is parsed once
//! into a tree and evaluated left to right, so random draws happen in LIGGGHTS's order.

use crate::script::random::RanMars;
use crate::script::variables::c_atof;

/// Error from parsing or evaluating an expression; `offset` is a byte offset into the text.
#[derive(Debug, Clone, PartialEq)]
pub struct ExprError {
    /// What went wrong, in LIGGGHTS's words where it has them.
    pub message: String,
    /// Byte offset into the expression text where the problem was found.
    pub offset: usize,
}

fn err<T>(message: impl Into<String>, offset: usize) -> Result<T, ExprError> {
    Err(ExprError {
        message: message.into(),
        offset,
    })
}

const SYNTAX: &str = "Invalid syntax in variable formula";
const BAD_FUNCTION: &str = "Invalid math function in variable formula";

/// What a formula can ask of the world. Lookups return `Err(message)` when not available.
pub trait ExprContext {
    /// `v_name` (index None) or `v_name[N]`; `atom` is the atom being evaluated in atom style.
    fn variable(
        &mut self,
        name: &str,
        index: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, String>;
    /// A thermo keyword (`step`, `time`, `atoms`, ...).
    fn thermo(&mut self, name: &str) -> Result<f64, String>;
    /// `c_ID`, `c_ID[i]`, `c_ID[i][j]`; `atom` set inside atom-style formulas.
    fn compute(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, String>;
    /// `f_ID`, `f_ID[i]`, `f_ID[i][j]`, same conventions.
    fn fix(
        &mut self,
        id: &str,
        i: Option<usize>,
        j: Option<usize>,
        atom: Option<usize>,
    ) -> Result<f64, String>;
    /// Group functions `count(g)`, `xcm(g,x)`, `bound(g,zmax,region)` ...; raw argument words.
    fn group_function(&mut self, name: &str, args: &[String]) -> Result<f64, String>;
    /// Special functions `sum() min() max() ave() trap() gmask() rmask() grmask() next()`.
    fn special_function(
        &mut self,
        name: &str,
        args: &[String],
        atom: Option<usize>,
    ) -> Result<f64, String>;
    /// Per-atom keyword (`x`, `vx`, `mass`, `r`, ...) of local atom `atom`.
    fn atom_value(&mut self, name: &str, atom: usize) -> Result<f64, String>;
    /// `x[N]`: per-atom keyword of the atom whose ID is `id`.
    fn atom_value_by_id(&mut self, name: &str, id: usize) -> Result<f64, String>;
    /// Whether the simulation box exists (most lookups need it).
    fn box_exists(&self) -> bool;
    /// The current timestep.
    fn timestep(&self) -> i64;
    /// First and last step of the run in progress (None between runs).
    fn run_bounds(&self) -> Option<(i64, i64)>;
    /// The time-step size (time units).
    fn dt(&self) -> f64;
    /// The generator behind `random()`/`normal()`, made from `seed` on first use.
    fn rng(&mut self, seed: i32, per_atom: bool) -> Result<&mut RanMars, String>;
}

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

/// Operator-stack entries: binary operators and the two prefix operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum StackOp {
    Bin(Op, usize),
    Neg,
    Not,
}

fn precedence(op: StackOp) -> u8 {
    match op {
        StackOp::Neg | StackOp::Not => 8,
        StackOp::Bin(op, _) => match op {
            Op::Or => 1,
            Op::And => 2,
            Op::Eq | Op::Ne => 3,
            Op::Lt | Op::Le | Op::Gt | Op::Ge => 4,
            Op::Add | Op::Sub => 5,
            Op::Mul | Op::Div | Op::Mod => 6,
            Op::Pow => 7,
        },
    }
}

/// Math functions of LIGGGHTS 3.8.0.
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
    fn from_name(name: &str) -> Option<(Math, usize)> {
        use Math::*;
        Some(match name {
            "sqrt" => (Sqrt, 1),
            "exp" => (Exp, 1),
            "ln" => (Ln, 1),
            "log" => (Log, 1),
            "abs" => (Abs, 1),
            "sin" => (Sin, 1),
            "cos" => (Cos, 1),
            "tan" => (Tan, 1),
            "asin" => (Asin, 1),
            "acos" => (Acos, 1),
            "atan" => (Atan, 1),
            "atan2" => (Atan2, 2),
            "random" => (Random, 3),
            "normal" => (Normal, 3),
            "ceil" => (Ceil, 1),
            "floor" => (Floor, 1),
            "round" => (Round, 1),
            "ramp" => (Ramp, 2),
            "stagger" => (Stagger, 2),
            "logfreq" => (Logfreq, 3),
            "stride" => (Stride, 3),
            "vdisplace" => (Vdisplace, 2),
            "swiggle" => (Swiggle, 3),
            "cwiggle" => (Cwiggle, 3),
            _ => return None,
        })
    }
}

/// Group functions (their arguments are names, not formulas).
pub const GROUP_FUNCTIONS: &[&str] = &[
    "angmom", "bound", "charge", "count", "fcm", "gyration", "inertia", "ke", "mass", "omega",
    "torque", "vcm", "xcm",
];

/// Special functions (arguments are references such as `c_ID`).
pub const SPECIAL_FUNCTIONS: &[&str] = &[
    "ave", "gmask", "grmask", "max", "min", "next", "rmask", "sum", "trap",
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
    Not(Box<Node>),
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

/// Position of the `)` matching the `(` at `open`, allowing nesting.
fn matching_paren(s: &[u8], open: usize) -> Option<usize> {
    let mut level = 0;
    for (i, &c) in s.iter().enumerate().skip(open + 1) {
        match c {
            b'(' => level += 1,
            b')' if level > 0 => level -= 1,
            b')' => return Some(i),
            _ => {}
        }
    }
    None
}

/// `[N]` at `start`: a positive integer of digits only. Returns (N, index after `]`).
fn bracket_index(s: &[u8], start: usize) -> Result<(usize, usize), ExprError> {
    let mut i = start + 1;
    while i < s.len() && s[i] != b']' {
        if !s[i].is_ascii_digit() {
            return err("Non digit character between brackets in variable", i);
        }
        i += 1;
    }
    if i >= s.len() {
        return err("Mismatched brackets in variable", start);
    }
    if i == start + 1 {
        return err("Empty brackets in variable", start);
    }
    let digits = std::str::from_utf8(&s[start + 1..i]).unwrap_or("0");
    let n: usize = digits.parse().unwrap_or(usize::MAX);
    if n == 0 {
        return err("Index between variable brackets must be positive", start);
    }
    Ok((n, i + 1))
}

/// Split function contents at top-level commas into at most three pieces, as LIGGGHTS
/// does (everything after the second comma is the third piece). Offsets are kept.
fn split_args(contents: &str, base: usize) -> Vec<(String, usize)> {
    let b = contents.as_bytes();
    let mut pieces = Vec::new();
    let mut level = 0i32;
    let mut start = 0;
    for (i, &c) in b.iter().enumerate() {
        match c {
            b'(' => level += 1,
            b')' => level -= 1,
            b',' if level == 0 && pieces.len() < 2 => {
                pieces.push((contents[start..i].to_string(), base + start));
                start = i + 1;
            }
            _ => {}
        }
    }
    pieces.push((contents[start..].to_string(), base + start));
    pieces
}

/// Split group/special function contents at every top-level comma.
fn split_all(contents: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut level = 0i32;
    let mut cur = String::new();
    for c in contents.chars() {
        match c {
            '(' => level += 1,
            ')' => level -= 1,
            ',' if level == 0 => {
                out.push(std::mem::take(&mut cur).trim().to_string());
                continue;
            }
            _ => {}
        }
        cur.push(c);
    }
    out.push(cur.trim().to_string());
    out
}

struct Parser<'a> {
    text: &'a str,
    base: usize,
}

impl Parser<'_> {
    fn parse(&self) -> Result<Node, ExprError> {
        let s = self.text.as_bytes();
        let mut args: Vec<Node> = Vec::new();
        let mut ops: Vec<StackOp> = Vec::new();
        let mut expect_arg = true;
        let mut i = 0;
        loop {
            let at = self.base + i;
            let c = s.get(i).copied().unwrap_or(0);
            if c != 0 && is_c_space(c) {
                i += 1;
            } else if c == b'(' {
                if !expect_arg {
                    return err(SYNTAX, at);
                }
                expect_arg = false;
                let Some(close) = matching_paren(s, i) else {
                    return err(SYNTAX, at);
                };
                let inner = Parser {
                    text: &self.text[i + 1..close],
                    base: at + 1,
                };
                args.push(inner.parse()?);
                i = close + 1;
            } else if c.is_ascii_digit() || c == b'.' {
                if !expect_arg {
                    return err(SYNTAX, at);
                }
                expect_arg = false;
                let start = i;
                while i < s.len() && (s[i].is_ascii_digit() || s[i] == b'.') {
                    i += 1;
                }
                if i < s.len() && (s[i] == b'e' || s[i] == b'E') {
                    i += 1;
                    if i < s.len() && (s[i] == b'+' || s[i] == b'-') {
                        i += 1;
                    }
                    while i < s.len() && s[i].is_ascii_digit() {
                        i += 1;
                    }
                }
                args.push(Node::Num(c_atof(&self.text[start..i])));
            } else if c.is_ascii_alphabetic() {
                if !expect_arg {
                    return err(SYNTAX, at);
                }
                expect_arg = false;
                let start = i;
                while i < s.len() && (s[i].is_ascii_alphanumeric() || s[i] == b'_') {
                    i += 1;
                }
                let (node, next) = self.word(&self.text[start..i], i, at)?;
                args.push(node);
                i = next;
            } else if c == 0 || b"+-*/^<>=!&|%".contains(&c) {
                let two = s.get(i + 1).copied().unwrap_or(0);
                let (op, len) = match c {
                    0 => (None, 0),
                    b'+' => (Some(StackOp::Bin(Op::Add, at)), 1),
                    b'-' => (Some(StackOp::Bin(Op::Sub, at)), 1),
                    b'*' => (Some(StackOp::Bin(Op::Mul, at)), 1),
                    b'/' => (Some(StackOp::Bin(Op::Div, at)), 1),
                    b'%' => (Some(StackOp::Bin(Op::Mod, at)), 1),
                    b'^' => (Some(StackOp::Bin(Op::Pow, at)), 1),
                    b'=' if two == b'=' => (Some(StackOp::Bin(Op::Eq, at)), 2),
                    b'!' if two == b'=' => (Some(StackOp::Bin(Op::Ne, at)), 2),
                    b'!' => (Some(StackOp::Not), 1),
                    b'<' if two == b'=' => (Some(StackOp::Bin(Op::Le, at)), 2),
                    b'<' => (Some(StackOp::Bin(Op::Lt, at)), 1),
                    b'>' if two == b'=' => (Some(StackOp::Bin(Op::Ge, at)), 2),
                    b'>' => (Some(StackOp::Bin(Op::Gt, at)), 1),
                    b'&' if two == b'&' => (Some(StackOp::Bin(Op::And, at)), 2),
                    b'|' if two == b'|' => (Some(StackOp::Bin(Op::Or, at)), 2),
                    _ => return err(SYNTAX, at),
                };
                i += len;
                if expect_arg {
                    match op {
                        Some(StackOp::Bin(Op::Sub, _)) => {
                            ops.push(StackOp::Neg);
                            continue;
                        }
                        Some(StackOp::Not) => {
                            ops.push(StackOp::Not);
                            continue;
                        }
                        _ => return err(SYNTAX, at),
                    }
                }
                if op == Some(StackOp::Not) {
                    return err(SYNTAX, at);
                }
                expect_arg = true;
                let level = op.map_or(0, precedence);
                while let Some(&top) = ops.last() {
                    if precedence(top) < level {
                        break;
                    }
                    ops.pop();
                    reduce(&mut args, top, at)?;
                }
                match op {
                    None => break,
                    Some(op) => ops.push(op),
                }
            } else {
                return err(SYNTAX, at);
            }
        }
        if !ops.is_empty() || args.len() != 1 {
            return err(SYNTAX, self.base + self.text.len());
        }
        Ok(args.pop().expect("one argument"))
    }

    /// A word at `next` (byte after it) in the text: reference, function, atom value, ...
    fn word(&self, word: &str, mut next: usize, at: usize) -> Result<(Node, usize), ExprError> {
        let s = self.text.as_bytes();
        let brackets =
            |next: &mut usize, max: usize| -> Result<(Option<usize>, Option<usize>), ExprError> {
                let mut found = (None, None);
                if s.get(*next) == Some(&b'[') {
                    let (n, after) = bracket_index(s, *next)?;
                    found.0 = Some(n);
                    *next = after;
                    if max == 2 && s.get(*next) == Some(&b'[') {
                        let (m, after) = bracket_index(s, *next)?;
                        found.1 = Some(m);
                        *next = after;
                    }
                }
                Ok(found)
            };
        if let Some(id) = word.strip_prefix("c_") {
            let (i, j) = brackets(&mut next, 2)?;
            return Ok((Node::Compute(id.to_string(), i, j, at), next));
        }
        if let Some(id) = word.strip_prefix("f_") {
            let (i, j) = brackets(&mut next, 2)?;
            return Ok((Node::Fix(id.to_string(), i, j, at), next));
        }
        if let Some(name) = word.strip_prefix("v_") {
            let (i, _) = brackets(&mut next, 1)?;
            return Ok((Node::Var(name.to_string(), i, at), next));
        }
        match s.get(next) {
            Some(b'(') => {
                let Some(close) = matching_paren(s, next) else {
                    return err(SYNTAX, at);
                };
                let contents = &self.text[next + 1..close];
                let node = if let Some((f, want)) = Math::from_name(word) {
                    let pieces = split_args(contents, self.base + next + 1);
                    if pieces.len() != want {
                        return err(BAD_FUNCTION, at);
                    }
                    let mut nodes = Vec::with_capacity(want);
                    for (text, base) in &pieces {
                        nodes.push(Parser { text, base: *base }.parse()?);
                    }
                    Node::Math(f, nodes, at)
                } else if GROUP_FUNCTIONS.contains(&word) {
                    Node::Group(word.to_string(), split_all(contents), at)
                } else if SPECIAL_FUNCTIONS.contains(&word) {
                    Node::Special(word.to_string(), split_all(contents), at)
                } else {
                    return err(
                        "Invalid math/group/special function in variable formula",
                        at,
                    );
                };
                Ok((node, close + 1))
            }
            Some(b'[') => {
                let (id, after) = bracket_index(s, next)?;
                Ok((Node::AtomById(word.to_string(), id, at), after))
            }
            _ if ATOM_KEYWORDS.contains(&word) => {
                Ok((Node::AtomVector(word.to_string(), at), next))
            }
            _ if word == "PI" => Ok((Node::Num(std::f64::consts::PI), next)),
            _ => Ok((Node::Thermo(word.to_string(), at), next)),
        }
    }
}

/// Pop the operands of `op` from `args` and push the combined node.
fn reduce(args: &mut Vec<Node>, op: StackOp, at: usize) -> Result<(), ExprError> {
    let Some(right) = args.pop() else {
        return err(SYNTAX, at);
    };
    let node = match op {
        StackOp::Neg => Node::Neg(Box::new(right)),
        StackOp::Not => Node::Not(Box::new(right)),
        StackOp::Bin(op, pos) => {
            let Some(left) = args.pop() else {
                return err(SYNTAX, at);
            };
            Node::Bin(op, Box::new(left), Box::new(right), pos)
        }
    };
    args.push(node);
    Ok(())
}

fn truth(b: bool) -> f64 {
    if b {
        1.0
    } else {
        0.0
    }
}

/// LIGGGHTS's rounding: halves go up (`round(-2.5)` is -2).
fn round_half_up(a: f64) -> f64 {
    if a - a.floor() >= 0.5 {
        a.ceil()
    } else {
        a.floor()
    }
}

impl Expr {
    /// Parse a formula.
    pub fn parse(text: &str) -> Result<Expr, ExprError> {
        Ok(Expr {
            root: Parser { text, base: 0 }.parse()?,
        })
    }

    /// Evaluate as equal style (`atom` None) or for one atom (`atom` = local index).
    pub fn eval(&self, ctx: &mut dyn ExprContext, atom: Option<usize>) -> Result<f64, ExprError> {
        eval(&self.root, ctx, atom)
    }

    /// True if the formula refers to per-atom quantities (then only atom style can use it).
    pub fn is_per_atom(&self) -> bool {
        fn walk(n: &Node) -> bool {
            match n {
                Node::AtomVector(..) => true,
                Node::Neg(a) | Node::Not(a) => walk(a),
                Node::Bin(_, a, b, _) => walk(a) || walk(b),
                Node::Math(_, args, _) => args.iter().any(walk),
                _ => false,
            }
        }
        walk(&self.root)
    }
}

fn lookup(r: Result<f64, String>, at: usize) -> Result<f64, ExprError> {
    r.map_err(|message| ExprError {
        message,
        offset: at,
    })
}

fn eval(node: &Node, ctx: &mut dyn ExprContext, atom: Option<usize>) -> Result<f64, ExprError> {
    Ok(match node {
        Node::Num(v) => *v,
        Node::Neg(a) => -eval(a, ctx, atom)?,
        Node::Not(a) => truth(eval(a, ctx, atom)? == 0.0),
        Node::Bin(op, a, b, at) => {
            let x = eval(a, ctx, atom)?;
            let y = eval(b, ctx, atom)?;
            match op {
                Op::Add => x + y,
                Op::Sub => x - y,
                Op::Mul => x * y,
                Op::Div if y == 0.0 => return err("Divide by 0 in variable formula", *at),
                Op::Div => x / y,
                Op::Mod if y == 0.0 => return err("Modulo 0 in variable formula", *at),
                Op::Mod => x % y,
                Op::Pow if y == 0.0 => return err("Power by 0 in variable formula", *at),
                Op::Pow => x.powf(y),
                Op::Eq => truth(x == y),
                Op::Ne => truth(x != y),
                Op::Lt => truth(x < y),
                Op::Le => truth(x <= y),
                Op::Gt => truth(x > y),
                Op::Ge => truth(x >= y),
                Op::And => truth(x != 0.0 && y != 0.0),
                Op::Or => truth(x != 0.0 || y != 0.0),
            }
        }
        Node::Math(f, args, at) => {
            let mut v = [0.0; 3];
            for (slot, a) in v.iter_mut().zip(args) {
                *slot = eval(a, ctx, atom)?;
            }
            math(*f, v, ctx, atom, *at)?
        }
        Node::Group(name, args, at) => lookup(ctx.group_function(name, args), *at)?,
        Node::Special(name, args, at) => lookup(ctx.special_function(name, args, atom), *at)?,
        Node::Compute(id, i, j, at) => {
            if !ctx.box_exists() {
                return err("Variable evaluation before simulation box is defined", *at);
            }
            lookup(ctx.compute(id, *i, *j, atom), *at)?
        }
        Node::Fix(id, i, j, at) => {
            if !ctx.box_exists() {
                return err("Variable evaluation before simulation box is defined", *at);
            }
            lookup(ctx.fix(id, *i, *j, atom), *at)?
        }
        Node::Var(name, index, at) => lookup(ctx.variable(name, *index, atom), *at)?,
        Node::AtomById(name, id, at) => {
            if !ctx.box_exists() {
                return err("Variable evaluation before simulation box is defined", *at);
            }
            lookup(ctx.atom_value_by_id(name, *id), *at)?
        }
        Node::AtomVector(name, at) => {
            if !ctx.box_exists() {
                return err("Variable evaluation before simulation box is defined", *at);
            }
            match atom {
                None => return err("Atom vector in equal-style variable formula", *at),
                Some(a) => lookup(ctx.atom_value(name, a), *at)?,
            }
        }
        Node::Thermo(name, at) => {
            if !ctx.box_exists() {
                return err("Variable evaluation before simulation box is defined", *at);
            }
            lookup(ctx.thermo(name), *at)?
        }
    })
}

fn math(
    f: Math,
    v: [f64; 3],
    ctx: &mut dyn ExprContext,
    atom: Option<usize>,
    at: usize,
) -> Result<f64, ExprError> {
    use Math::*;
    let [a, b, c] = v;
    let step = ctx.timestep();
    let between_runs = |what: &str| ExprError {
        message: format!("Cannot use {what} in variable formula between runs"),
        offset: at,
    };
    Ok(match f {
        Sqrt if a < 0.0 => return err("Sqrt of negative value in variable formula", at),
        Sqrt => a.sqrt(),
        Exp => a.exp(),
        Ln | Log if a <= 0.0 => return err("Log of zero/negative value in variable formula", at),
        Ln => a.ln(),
        Log => a.log10(),
        Abs => a.abs(),
        Sin => a.sin(),
        Cos => a.cos(),
        Tan => a.tan(),
        Asin if !(-1.0..=1.0).contains(&a) => {
            return err("Arcsin of invalid value in variable formula", at)
        }
        Asin => a.asin(),
        Acos if !(-1.0..=1.0).contains(&a) => {
            return err("Arccos of invalid value in variable formula", at)
        }
        Acos => a.acos(),
        Atan => a.atan(),
        Atan2 => a.atan2(b),
        Random | Normal => {
            if f == Normal && b < 0.0 {
                return err(BAD_FUNCTION, at);
            }
            let seed = c as i32;
            if seed <= 0 {
                return err(BAD_FUNCTION, at);
            }
            let rng = lookup_rng(ctx.rng(seed, atom.is_some()), at)?;
            if f == Random {
                rng.uniform() * (b - a) + a
            } else {
                a + b * rng.gaussian()
            }
        }
        Ceil => a.ceil(),
        Floor => a.floor(),
        Round => round_half_up(a),
        Ramp => {
            let (begin, end) = ctx.run_bounds().ok_or_else(|| between_runs("ramp"))?;
            let mut delta = (step - begin) as f64;
            if delta != 0.0 {
                delta /= (end - begin) as f64;
            }
            a + delta * (b - a)
        }
        Stagger => {
            let (n1, n2) = (a as i32 as i64, b as i32 as i64);
            if n1 <= 0 || n2 <= 0 || n1 <= n2 {
                return err(BAD_FUNCTION, at);
            }
            let lower = step / n1 * n1;
            if step - lower < n2 {
                (lower + n2) as f64
            } else {
                (lower + n1) as f64
            }
        }
        Logfreq => {
            let (n1, n2, n3) = (a as i32 as i64, b as i32 as i64, c as i32 as i64);
            if n1 <= 0 || n2 <= 0 || n3 <= 0 || n2 >= n3 {
                return err(BAD_FUNCTION, at);
            }
            if step < n1 {
                n1 as f64
            } else {
                let mut lower = n1;
                while step >= n3 * lower {
                    lower *= n3;
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
            let (n1, n2, n3) = (a as i32 as i64, b as i32 as i64, c as i32 as i64);
            if n1 < 0 || n2 < 0 || n3 <= 0 || n1 > n2 {
                return err(BAD_FUNCTION, at);
            }
            if step < n1 {
                n1 as f64
            } else if step < n2 {
                let value = (n1 + (step - n1) / n3 * n3 + n3) as f64;
                if value > n2 as f64 {
                    9.0e18
                } else {
                    value
                }
            } else {
                9.0e18
            }
        }
        Vdisplace => {
            let (begin, _) = ctx.run_bounds().ok_or_else(|| between_runs("vdisplace"))?;
            a + b * (step - begin) as f64 * ctx.dt()
        }
        Swiggle | Cwiggle => {
            let name = if f == Swiggle { "swiggle" } else { "cwiggle" };
            let (begin, _) = ctx.run_bounds().ok_or_else(|| between_runs(name))?;
            if c == 0.0 {
                return err(BAD_FUNCTION, at);
            }
            let omega = 2.0 * std::f64::consts::PI / c;
            let phase = omega * (step - begin) as f64 * ctx.dt();
            if f == Swiggle {
                a + b * phase.sin()
            } else {
                a + b * (1.0 - phase.cos())
            }
        }
    })
}

fn lookup_rng(r: Result<&mut RanMars, String>, at: usize) -> Result<&mut RanMars, ExprError> {
    r.map_err(|message| ExprError {
        message,
        offset: at,
    })
}

/// Parse and evaluate an equal-style formula.
pub fn evaluate(text: &str, ctx: &mut dyn ExprContext) -> Result<f64, ExprError> {
    Expr::parse(text)?.eval(ctx, None)
}

const BOOLEAN: &str = "Invalid Boolean syntax in if command";

/// The condition of an `if` command, as LIGGGHTS 3.8.0 evaluates it: numbers (which may
/// start with `-`), parentheses, comparisons, `&&`, `||` and `!` only; 1.0 means true.
pub fn evaluate_boolean(text: &str) -> Result<f64, ExprError> {
    let s = text.as_bytes();
    let mut args: Vec<f64> = Vec::new();
    let mut ops: Vec<StackOp> = Vec::new();
    let mut expect_arg = true;
    let mut i = 0;
    loop {
        let c = s.get(i).copied().unwrap_or(0);
        if c != 0 && is_c_space(c) {
            i += 1;
        } else if c == b'(' {
            if !expect_arg {
                return err(BOOLEAN, i);
            }
            expect_arg = false;
            let Some(close) = matching_paren(s, i) else {
                return err(SYNTAX, i);
            };
            args.push(
                evaluate_boolean(&text[i + 1..close]).map_err(|e| ExprError {
                    offset: e.offset + i + 1,
                    ..e
                })?,
            );
            i = close + 1;
        } else if c.is_ascii_digit() || c == b'.' || c == b'-' {
            if !expect_arg {
                return err(BOOLEAN, i);
            }
            expect_arg = false;
            let start = i;
            i += 1;
            while i < s.len() && (s[i].is_ascii_digit() || s[i] == b'.') {
                i += 1;
            }
            if i < s.len() && (s[i] == b'e' || s[i] == b'E') {
                i += 1;
                if i < s.len() && (s[i] == b'+' || s[i] == b'-') {
                    i += 1;
                }
                while i < s.len() && s[i].is_ascii_digit() {
                    i += 1;
                }
            }
            args.push(c_atof(&text[start..i]));
        } else if c == 0 || b"<>=!&|".contains(&c) {
            let two = s.get(i + 1).copied().unwrap_or(0);
            let (op, len) = match c {
                0 => (None, 0),
                b'=' if two == b'=' => (Some(StackOp::Bin(Op::Eq, i)), 2),
                b'!' if two == b'=' => (Some(StackOp::Bin(Op::Ne, i)), 2),
                b'!' => (Some(StackOp::Not), 1),
                b'<' if two == b'=' => (Some(StackOp::Bin(Op::Le, i)), 2),
                b'<' => (Some(StackOp::Bin(Op::Lt, i)), 1),
                b'>' if two == b'=' => (Some(StackOp::Bin(Op::Ge, i)), 2),
                b'>' => (Some(StackOp::Bin(Op::Gt, i)), 1),
                b'&' if two == b'&' => (Some(StackOp::Bin(Op::And, i)), 2),
                b'|' if two == b'|' => (Some(StackOp::Bin(Op::Or, i)), 2),
                _ => return err(BOOLEAN, i),
            };
            let at = i;
            i += len;
            if op == Some(StackOp::Not) && expect_arg {
                ops.push(StackOp::Not);
                continue;
            }
            if expect_arg || op == Some(StackOp::Not) {
                return err(BOOLEAN, at);
            }
            expect_arg = true;
            let level = op.map_or(0, precedence);
            while let Some(&top) = ops.last() {
                if precedence(top) < level {
                    break;
                }
                ops.pop();
                let Some(y) = args.pop() else {
                    return err(BOOLEAN, at);
                };
                let value = match top {
                    StackOp::Not => truth(y == 0.0),
                    StackOp::Neg => -y,
                    StackOp::Bin(op, _) => {
                        let Some(x) = args.pop() else {
                            return err(BOOLEAN, at);
                        };
                        match op {
                            Op::Eq => truth(x == y),
                            Op::Ne => truth(x != y),
                            Op::Lt => truth(x < y),
                            Op::Le => truth(x <= y),
                            Op::Gt => truth(x > y),
                            Op::Ge => truth(x >= y),
                            Op::And => truth(x != 0.0 && y != 0.0),
                            Op::Or => truth(x != 0.0 || y != 0.0),
                            _ => return err(BOOLEAN, at),
                        }
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
        return err(BOOLEAN, text.len());
    }
    Ok(args[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A world with no box, step 0 and a couple of variables.
    struct World {
        rng: Option<RanMars>,
        step: i64,
        run: Option<(i64, i64)>,
    }

    impl ExprContext for World {
        fn variable(
            &mut self,
            name: &str,
            _: Option<usize>,
            _: Option<usize>,
        ) -> Result<f64, String> {
            match name {
                "a" => Ok(2.0),
                _ => Err("Invalid variable name in variable formula".into()),
            }
        }
        fn thermo(&mut self, name: &str) -> Result<f64, String> {
            match name {
                "step" => Ok(self.step as f64),
                _ => Err("Invalid thermo keyword in variable formula".into()),
            }
        }
        fn compute(
            &mut self,
            _: &str,
            _: Option<usize>,
            _: Option<usize>,
            _: Option<usize>,
        ) -> Result<f64, String> {
            Ok(7.0)
        }
        fn fix(
            &mut self,
            _: &str,
            _: Option<usize>,
            _: Option<usize>,
            _: Option<usize>,
        ) -> Result<f64, String> {
            Ok(8.0)
        }
        fn group_function(&mut self, name: &str, args: &[String]) -> Result<f64, String> {
            Ok(if name == "count" && args == ["all"] {
                0.0
            } else {
                -1.0
            })
        }
        fn special_function(
            &mut self,
            _: &str,
            _: &[String],
            _: Option<usize>,
        ) -> Result<f64, String> {
            Ok(0.0)
        }
        fn atom_value(&mut self, _: &str, atom: usize) -> Result<f64, String> {
            Ok(atom as f64)
        }
        fn atom_value_by_id(&mut self, _: &str, id: usize) -> Result<f64, String> {
            Ok(10.0 * id as f64)
        }
        fn box_exists(&self) -> bool {
            true
        }
        fn timestep(&self) -> i64 {
            self.step
        }
        fn run_bounds(&self) -> Option<(i64, i64)> {
            self.run
        }
        fn dt(&self) -> f64 {
            0.001
        }
        fn rng(&mut self, seed: i32, _: bool) -> Result<&mut RanMars, String> {
            if self.rng.is_none() {
                self.rng = Some(RanMars::new(seed)?);
            }
            Ok(self.rng.as_mut().unwrap())
        }
    }

    fn world() -> World {
        World {
            rng: None,
            step: 0,
            run: None,
        }
    }

    fn ev(text: &str) -> f64 {
        evaluate(text, &mut world()).unwrap_or_else(|e| panic!("{text}: {e:?}"))
    }

    fn fails(text: &str) -> String {
        evaluate(text, &mut world()).unwrap_err().message
    }

    #[test]
    fn precedence_and_associativity_as_liggghts() {
        // values printed by Debian's liggghts for the same formulas
        assert_eq!(ev("2^3^2"), 64.0);
        assert_eq!(ev("-2^2"), 4.0);
        assert_eq!(ev("7%3"), 1.0);
        assert_eq!(ev("1+2*3-4/2"), 5.0);
        assert_eq!(ev("1 < 2 == 1"), 1.0);
        assert_eq!(ev("!0 && 3 || 0"), 1.0);
        assert_eq!(ev("!1+1"), 1.0);
        assert_eq!(ev("--3"), 3.0);
        assert_eq!(ev("(1+2)*(3+4)"), 21.0);
        assert!((ev(".5+5.+1e-1+2E+1") - 25.6).abs() < 1e-12);
        assert_eq!(ev("PI"), std::f64::consts::PI);
        assert_eq!(ev("v_a*c_x[2]+f_y[1][2]"), 2.0 * 7.0 + 8.0);
        assert_eq!(ev("x[3]"), 30.0);
        assert_eq!(ev("count(all)"), 0.0);
        assert_eq!(ev("step"), 0.0);
    }

    #[test]
    fn functions() {
        assert_eq!(
            ev("sqrt(16)+abs(-2)+floor(2.7)+ceil(2.1)"),
            4.0 + 2.0 + 2.0 + 3.0
        );
        assert_eq!(ev("round(-2.5)"), -2.0);
        assert_eq!(ev("round(2.5)"), 3.0);
        assert_eq!(ev("log(1000)+ln(exp(2))"), 5.0);
        assert_eq!(ev("atan2(1,1)"), std::f64::consts::FRAC_PI_4);
        assert_eq!(ev("stagger(1000,100)"), 100.0);
        assert_eq!(ev("logfreq(100,4,10)"), 100.0);
        assert_eq!(ev("stride(0,100,10)"), 10.0);
        let mut w = World {
            rng: None,
            step: 250,
            run: Some((200, 300)),
        };
        assert_eq!(evaluate("ramp(0,10)", &mut w).unwrap(), 5.0);
        assert_eq!(evaluate("logfreq(10,4,10)", &mut w).unwrap(), 300.0);
        assert!((evaluate("vdisplace(1,2)", &mut w).unwrap() - 1.1).abs() < 1e-12);
    }

    #[test]
    fn random_stream_matches_liggghts() {
        // liggghts: variable r equal random(0,1,15485863), g equal normal(0,1,15485863),
        // print "$(v_r) $(v_r) $(v_g) $(v_g) $(v_r)" (v_ passes values through %.15g)
        let mut w = world();
        let mut next =
            |f: &str| crate::script::format::g_precision(evaluate(f, &mut w).unwrap(), 15);
        assert_eq!(next("random(0,1,15485863)"), "0.863169074058533");
        assert_eq!(next("random(0,1,15485863)"), "0.656422913074493");
        assert_eq!(next("normal(0,1,15485863)"), "-0.0734393293225169");
        assert_eq!(next("normal(0,1,15485863)"), "1.0028887851919");
        assert_eq!(next("random(0,1,15485863)"), "0.917968690395355");
    }

    #[test]
    fn errors_as_liggghts() {
        assert_eq!(fails("1/0"), "Divide by 0 in variable formula");
        assert_eq!(fails("5%0"), "Modulo 0 in variable formula");
        assert_eq!(fails("2^0"), "Power by 0 in variable formula");
        assert_eq!(
            fails("sqrt(-1)"),
            "Sqrt of negative value in variable formula"
        );
        assert_eq!(fails("sqrt(1,2)"), BAD_FUNCTION);
        assert_eq!(
            fails("foo(1)"),
            "Invalid math/group/special function in variable formula"
        );
        assert_eq!(
            fails("ramp(0,1)"),
            "Cannot use ramp in variable formula between runs"
        );
        assert_eq!(fails("1 +"), SYNTAX);
        assert_eq!(fails(""), SYNTAX);
        assert_eq!(fails("(1"), SYNTAX);
        assert_eq!(fails("2 3"), SYNTAX);
        assert_eq!(
            fails("x[0]"),
            "Index between variable brackets must be positive"
        );
        assert_eq!(
            fails("c_a[b]"),
            "Non digit character between brackets in variable"
        );
        assert_eq!(fails("1 = 1"), SYNTAX);
        assert_eq!(fails("x"), "Atom vector in equal-style variable formula");
        assert_eq!(evaluate("1 +\n 2 $", &mut world()).unwrap_err().offset, 7);
    }

    #[test]
    fn atom_style() {
        let e = Expr::parse("x*2 + mass").unwrap();
        assert!(e.is_per_atom());
        assert_eq!(e.eval(&mut world(), Some(3)).unwrap(), 9.0);
        assert!(!Expr::parse("1+v_a").unwrap().is_per_atom());
    }

    #[test]
    fn boolean_conditions() {
        assert_eq!(evaluate_boolean("2.5 > 1").unwrap(), 1.0);
        assert_eq!(evaluate_boolean("-1 >= 0 || (3 == 3 && !0)").unwrap(), 1.0);
        assert_eq!(evaluate_boolean("1e3 < 999").unwrap(), 0.0);
        assert_eq!(evaluate_boolean("abc == abc").unwrap_err().message, BOOLEAN);
        assert_eq!(evaluate_boolean("1 +1").unwrap_err().message, BOOLEAN);
        assert_eq!(evaluate_boolean("").unwrap_err().message, BOOLEAN);
    }

    use proptest::prelude::*;
    proptest! {
        #[test]
        fn never_panics(text in "\\PC{0,40}") {
            let _ = evaluate(&text, &mut world());
            let _ = evaluate_boolean(&text);
        }
    }
}
