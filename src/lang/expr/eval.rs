//! Evaluating a parsed formula: folding its global parts, the operators and math
//! functions as LIGGGHTS computes them, and the atom-by-atom tree walk.

use super::*;

/// What LIGGGHTS does with a freshly read piece of an atom-style formula: global values
/// are looked up at once, run-only functions are checked, per-atom pieces are kept.
pub(super) fn atom_leaf(node: Node, ctx: &mut dyn ExprContext) -> Result<Node, ExprError> {
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
pub(super) fn generator(
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
pub(super) fn collapse(node: Node, ctx: &mut dyn ExprContext) -> Result<Node, ExprError> {
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
pub(super) fn binary(op: Op, x: f64, y: f64, at: usize) -> Result<f64, ExprError> {
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
pub(super) fn math(
    f: Math,
    v: &[f64],
    ctx: &mut dyn ExprContext,
    at: usize,
) -> Result<f64, ExprError> {
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
        Stagger => stagger(step, a, b, at)?,
        Logfreq => logfreq(step, [a, b, c], at)?,
        Stride => stride(step, [a, b, c], at)?,
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

/// `stagger(N1,N2)`: the next step after `step` on the pattern N2, N1, N1+N2, 2*N1, ...
/// (LIGGGHTS's C int arithmetic).
fn stagger(step: i64, a: f64, b: f64, at: usize) -> Result<f64, ExprError> {
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
    Ok(f64::from(next))
}

/// `logfreq(N1,N2,N3)`: the next step after `step` with N2 steps per factor N3 from N1 on.
fn logfreq(step: i64, [a, b, c]: [f64; 3], at: usize) -> Result<f64, ExprError> {
    let (n1, n2, n3) = (
        i64::from(c_int(a)),
        i64::from(c_int(b)),
        i64::from(c_int(c)),
    );
    if n1 <= 0 || n2 <= 0 || n3 <= 0 || n2 >= n3 {
        return err(BAD_MATH, at);
    }
    if step < n1 {
        return Ok(n1 as f64);
    }
    // 64-bit here: LIGGGHTS's int arithmetic overflows beyond step 2^31 / n3
    let mut lower = n1;
    while let Some(up) = n3.checked_mul(lower).filter(|&up| step >= up) {
        lower = up;
    }
    let multiple = step / lower;
    Ok(if multiple < n2 {
        ((multiple + 1) * lower) as f64
    } else {
        (lower * n3) as f64
    })
}

/// `stride(N1,N2,N3)`: the next step after `step` from N1 to N2 every N3 steps (9e18
/// past N2; LIGGGHTS's C int arithmetic).
fn stride(step: i64, [a, b, c]: [f64; 3], at: usize) -> Result<f64, ExprError> {
    let (n1, n2, n3) = (c_int(a), c_int(b), c_int(c));
    if n1 < 0 || n2 < 0 || n3 <= 0 || n1 > n2 {
        return err(BAD_MATH, at);
    }
    Ok(if step < i64::from(n1) {
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
    })
}

/// The argument `k` of a math node (always present: the parser checked the count).
pub(super) fn nth(args: &[Node], k: usize, at: usize) -> Result<&Node, ExprError> {
    args.get(k).ok_or(ExprError {
        kind: BAD_MATH,
        offset: at,
    })
}

/// Evaluate a tree: equal style (`atom` None) left to right, or atom style for one atom
/// with the evaluation order of LIGGGHTS's per-atom tree walker.
pub(super) fn eval_node(
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

pub(super) fn eval_math(
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
