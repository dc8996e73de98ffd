//! Reading a formula: operators and their precedence, math function names, brackets, and
//! the parser that evaluates while it reads (equal style) or builds a tree (atom style).

use super::*;

/// Binary operators.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Op {
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
    pub(super) fn precedence(self) -> u8 {
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
pub(super) enum Pending {
    Bin(Op, usize),
    Neg,
    Not(usize),
}

impl Pending {
    pub(super) fn precedence(self) -> u8 {
        match self {
            Pending::Bin(op, _) => op.precedence(),
            Pending::Neg | Pending::Not(_) => 8,
        }
    }
}

/// The operator at `i` (None for end of text), its length, or Err for `=`, `&`, `|` alone.
pub(super) fn operator_at(bytes: &[u8], i: usize) -> Result<(Option<Pending>, usize), ()> {
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
pub(super) enum Math {
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
    pub(super) fn from_name(name: &str) -> Option<Math> {
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

    pub(super) fn arity(self) -> usize {
        use Math::*;
        match self {
            Atan2 | Ramp | Stagger | Vdisplace => 2,
            Random | Normal | Logfreq | Stride | Swiggle | Cwiggle => 3,
            _ => 1,
        }
    }

    /// The name used in "Cannot use NAME in variable formula between runs", for the
    /// functions that need a run in progress.
    pub(super) fn needs_run(self) -> Option<&'static str> {
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
pub(super) fn mask_function(name: &str) -> Option<&'static str> {
    match name {
        "gmask" => Some("Gmask"),
        "rmask" => Some("Rmask"),
        "grmask" => Some("Grmask"),
        _ => None,
    }
}

/// Position of the `)` matching the `(` at `open`, allowing nesting; None if unmatched.
pub(super) fn matching_paren(bytes: &[u8], open: usize) -> Option<usize> {
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
pub(super) fn split_pieces(bytes: &[u8], start: usize, end: usize) -> Vec<(usize, usize)> {
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
pub(super) fn bracket_index(bytes: &[u8], open: usize) -> Result<(usize, usize), ExprError> {
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
pub(super) enum Mode<'c> {
    /// Build the tree only.
    Syntax,
    /// Equal style: compute every piece as soon as it is complete.
    Equal(&'c mut dyn ExprContext),
    /// Atom style: fetch global values now, keep per-atom pieces as a tree.
    Atom(&'c mut dyn ExprContext),
}

pub(super) struct Parser<'t, 'c> {
    pub(super) text: &'t str,
    pub(super) mode: Mode<'c>,
    pub(super) nesting: usize,
}

/// A parsed piece and the depth of its tree.
pub(super) type Item = (Node, usize);

impl Parser<'_, '_> {
    /// Parse `start..end` as one formula (LIGGGHTS calls `evaluate` once per level of
    /// parentheses and per function argument).
    pub(super) fn level(&mut self, start: usize, end: usize) -> Result<Item, ExprError> {
        if self.nesting >= MAX_NESTING {
            return err(TOO_DEEP, start);
        }
        self.nesting += 1;
        let result = self.level_inner(start, end);
        self.nesting -= 1;
        result
    }

    pub(super) fn level_inner(&mut self, start: usize, end: usize) -> Result<Item, ExprError> {
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
    pub(super) fn reduce(
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
    pub(super) fn need_box(&self, at: usize) -> Result<(), ExprError> {
        match &self.mode {
            Mode::Equal(ctx) | Mode::Atom(ctx) if !ctx.box_exists() => err(NO_BOX, at),
            _ => Ok(()),
        }
    }

    /// The word at `from..to` and what follows it. Returns the item and the next position.
    pub(super) fn word(
        &mut self,
        bytes: &[u8],
        from: usize,
        to: usize,
    ) -> Result<(Item, usize), ExprError> {
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
    pub(super) fn function(
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
    pub(super) fn settle(
        &mut self,
        node: Node,
        depth: usize,
        at: usize,
    ) -> Result<Item, ExprError> {
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
