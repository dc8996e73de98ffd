//! The numbers-only evaluator of the `if` command.

use super::*;

pub(super) fn boolean_level(
    text: &str,
    start: usize,
    end: usize,
    nesting: usize,
) -> Result<f64, ExprError> {
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
