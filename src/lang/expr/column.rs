//! Atom-style formulas evaluated a whole column at a time, giving the values the
//! atom-by-atom walk gives.

use super::*;

/// Values of a formula piece for all atoms: one number for every atom, or one per atom.
pub(super) enum Column {
    Same(f64),
    Each(Vec<f64>),
}

impl Column {
    pub(super) fn into_vec(self, n: usize) -> Vec<f64> {
        match self {
            Column::Same(v) => vec![v; n],
            Column::Each(v) => v,
        }
    }

    pub(super) fn at(&self, i: usize) -> f64 {
        match self {
            Column::Same(v) => *v,
            Column::Each(v) => v[i],
        }
    }

    /// `f` applied to each value (to the one value if it is the same for all).
    pub(super) fn map(
        self,
        f: impl Fn(f64) -> Result<f64, ExprError>,
    ) -> Result<Column, ExprError> {
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
pub(super) fn columnar(node: &Node) -> bool {
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
/// any value would be one). The result takes the place of one of the operands' values.
pub(super) fn binary_column(
    op: Op,
    x: Column,
    y: Column,
    n: usize,
    at: usize,
) -> Result<Vec<f64>, ExprError> {
    let zero_divisor = match &y {
        Column::Same(q) => *q == 0.0,
        Column::Each(b) => b[..n].contains(&0.0),
    };
    if matches!(op, Op::Div | Op::Mod | Op::Pow) && zero_divisor {
        return binary(op, 1.0, 0.0, at).map(|_| Vec::new());
    }
    fn zip(x: Column, y: Column, n: usize, f: impl Fn(f64, f64) -> f64) -> Vec<f64> {
        match (x, y) {
            (Column::Each(mut a), Column::Each(b)) => {
                for (p, &q) in a.iter_mut().zip(&b) {
                    *p = f(*p, q);
                }
                a
            }
            (Column::Each(mut a), Column::Same(q)) => {
                for p in a.iter_mut() {
                    *p = f(*p, q);
                }
                a
            }
            (Column::Same(p), Column::Each(mut b)) => {
                for q in b.iter_mut() {
                    *q = f(p, *q);
                }
                b
            }
            (Column::Same(p), Column::Same(q)) => vec![f(p, q); n],
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
pub(super) fn plain_math(f: Math) -> Option<fn(f64) -> Option<f64>> {
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

/// Replace each value by `g` of it (NaN where `g` gives none); false if `g` gave none for
/// some value.
#[inline(always)]
fn apply_each(values: &mut [f64], g: impl Fn(f64) -> Option<f64>) -> bool {
    let mut valid = true;
    for x in values.iter_mut() {
        let y = g(*x);
        valid &= y.is_some();
        *x = y.unwrap_or(f64::NAN);
    }
    valid
}

/// A formula piece for all `n` atoms; any error (the walk then reports it as LIGGGHTS).
pub(super) fn eval_column(
    node: &Node,
    ctx: &mut dyn ExprContext,
    n: usize,
) -> Result<Column, ExprError> {
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
                (x, y) => Column::Each(binary_column(*op, x, y, n, *at)?),
            }
        }
        Node::Math(f, args, at) => {
            // the walk turns swiggle() into cwiggle() for atoms
            let f = if *f == Math::Swiggle {
                Math::Cwiggle
            } else {
                *f
            };
            let mut cols = args
                .iter()
                .map(|a| eval_column(a, ctx, n))
                .collect::<Result<Vec<Column>, ExprError>>()?;
            if cols.iter().all(|c| matches!(c, Column::Same(_))) {
                let v: Vec<f64> = cols.iter().map(|c| c.at(0)).collect();
                Column::Same(math(f, &v, ctx, *at)?)
            } else if let (1, Some(g)) = (cols.len(), plain_math(f)) {
                // one argument, no step or time: a tight loop, in place
                let mut values = cols.pop().expect("one argument").into_vec(n);
                // the same function inlined (a loop the compiler can vectorise) for the
                // commonest one, through its pointer otherwise
                let valid = match f {
                    Math::Sqrt => {
                        apply_each(&mut values, |a| if a < 0.0 { None } else { Some(a.sqrt()) })
                    }
                    _ => apply_each(&mut values, g),
                };
                if !valid {
                    return err(ExprErrorKind::NotColumnar, *at);
                }
                Column::Each(values)
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
