//! Reading numbers and indices from command words exactly as LIGGGHTS does
//! (`force->numeric`, `force->inumeric`, `force->bounds`, C's `atof`), with its error messages.

/// A word that is not the number or index LIGGGHTS expects there (its own words).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum NumberError {
    /// Not made of the characters of a real number.
    #[error("Expected floating point parameter in input script or data file, got '{0}'")]
    NotReal(String),
    /// A real number beyond a double.
    #[error("Floating point parameter '{0}' is out of range (largest: 1.79769e+308)")]
    RealOutOfRange(String),
    /// Not made of the characters of an integer.
    #[error("Expected integer parameter in input script or data file, got '{0}'")]
    NotInteger(String),
    /// An integer beyond what regolith counts in (about 9.2e18).
    #[error("Integer parameter '{0}' is out of range (it must be below 9.2e18)")]
    IntegerOutOfRange(String),
    /// A type index or range (`N`, `*`, `*N`, `N*`, `M*N`) outside 1..=N.
    #[error("Numeric index {0} is out of bounds")]
    IndexOutOfBounds(String),
}

/// The message alone, for callers that still report errors as text.
impl From<NumberError> for String {
    fn from(e: NumberError) -> String {
        e.to_string()
    }
}

/// LIGGGHTS's `numeric`: only digits, signs, `.`, `e`, `E` are allowed; the value is C `atof`.
pub fn numeric(word: &str) -> Result<f64, NumberError> {
    let ok = !word.is_empty()
        && word
            .bytes()
            .all(|b| b.is_ascii_digit() || matches!(b, b'-' | b'+' | b'.' | b'e' | b'E'));
    if !ok {
        return Err(NumberError::NotReal(word.to_string()));
    }
    let x = c_atof(word);
    if x.is_infinite() {
        return Err(NumberError::RealOutOfRange(word.to_string()));
    }
    Ok(x)
}

/// LIGGGHTS's `inumeric`: only digits and a sign are allowed; the value is C `atoi`.
pub fn inumeric(word: &str) -> Result<i64, NumberError> {
    let ok = !word.is_empty()
        && word
            .bytes()
            .all(|b| b.is_ascii_digit() || b == b'-' || b == b'+');
    if !ok {
        return Err(NumberError::NotInteger(word.to_string()));
    }
    let x = c_atof(word);
    // an i64 holds up to about 9.2e18; beyond it `as` would quietly saturate
    if x.is_nan() || x.abs() >= 9.2e18 {
        return Err(NumberError::IntegerOutOfRange(word.to_string()));
    }
    Ok(x as i64)
}

/// A leading integer as C's `atoi` reads it after leading blanks (0 when there is none).
pub fn c_atoi(w: &str) -> i64 {
    let t = w.trim_start_matches(is_c_space);
    let (sign, digits) = match t.as_bytes().first() {
        Some(b'-') => (-1, &t[1..]),
        Some(b'+') => (1, &t[1..]),
        _ => (1, t),
    };
    let end = digits
        .bytes()
        .position(|b| !b.is_ascii_digit())
        .unwrap_or(digits.len());
    sign * digits[..end].parse::<i64>().unwrap_or(0)
}

/// The blanks C's `isspace` knows (space, tab, newline, vertical tab, form feed, return).
pub fn is_c_space(c: char) -> bool {
    matches!(c, ' ' | '\t' | '\n' | '\u{0b}' | '\u{0c}' | '\r')
}

/// C's `atof`: the longest numeric prefix after leading blanks, 0 if there is none.
pub fn c_atof(text: &str) -> f64 {
    let t = text.trim_start_matches(is_c_space);
    let b = t.as_bytes();
    let mut end = 0;
    let mut best = 0;
    if end < b.len() && (b[end] == b'+' || b[end] == b'-') {
        end += 1;
    }
    let lower = t.to_ascii_lowercase();
    for special in ["infinity", "inf", "nan"] {
        if lower[end..].starts_with(special) {
            let v = if special == "nan" {
                f64::NAN
            } else {
                f64::INFINITY
            };
            return if b.first() == Some(&b'-') { -v } else { v };
        }
    }
    let mut digits = 0;
    while end < b.len() && b[end].is_ascii_digit() {
        end += 1;
        digits += 1;
    }
    if end < b.len() && b[end] == b'.' {
        end += 1;
        while end < b.len() && b[end].is_ascii_digit() {
            end += 1;
            digits += 1;
        }
    }
    if digits > 0 {
        best = end;
        if end < b.len() && (b[end] == b'e' || b[end] == b'E') {
            let mut e = end + 1;
            if e < b.len() && (b[e] == b'+' || b[e] == b'-') {
                e += 1;
            }
            let start = e;
            while e < b.len() && b[e].is_ascii_digit() {
                e += 1;
            }
            if e > start {
                best = e;
            }
        }
    }
    t[..best].parse::<f64>().unwrap_or(0.0)
}

/// LIGGGHTS's `force->bounds`: `N`, `*`, `*N`, `N*`, `M*N` within 1..=nmax.
pub fn bounds(text: &str, nmax: i64) -> Result<(i64, i64), NumberError> {
    let bad = || NumberError::IndexOutOfBounds(text.to_string());
    let parse = |s: &str| s.parse::<i64>().map_err(|_| bad());
    let (lo, hi) = match text.split_once('*') {
        None => {
            let n = parse(text)?;
            (n, n)
        }
        Some(("", "")) => (1, nmax),
        Some(("", b)) => (1, parse(b)?),
        Some((a, "")) => (parse(a)?, nmax),
        Some((a, b)) => (parse(a)?, parse(b)?),
    };
    if lo < 1 || hi > nmax || lo > hi {
        return Err(bad());
    }
    Ok((lo, hi))
}

/// C's `atol`: leading white space, an optional sign, then the digits up to the first other
/// character (none: 0); saturating at the `long` range as glibc's `strtol` does.
pub fn atol(text: &str) -> i64 {
    let t = text.trim_start();
    let (negative, t) = match t.as_bytes().first() {
        Some(b'-') => (true, &t[1..]),
        Some(b'+') => (false, &t[1..]),
        _ => (false, t),
    };
    let mut value: i64 = 0;
    for d in t.bytes().take_while(u8::is_ascii_digit) {
        let digit = i64::from(d - b'0');
        value = match value.checked_mul(10).and_then(|v| v.checked_add(digit)) {
            Some(v) => v,
            None => return if negative { i64::MIN } else { i64::MAX },
        };
    }
    if negative {
        -value
    } else {
        value
    }
}

/// `ID` or `ID[N]` of a `c_`/`f_`/`v_` reference body: the ID and the 1-based index.
pub fn split_reference(body: &str) -> Option<(&str, Option<usize>)> {
    match body.split_once('[') {
        Some((id, rest)) => Some((id, Some(rest.strip_suffix(']')?.parse().ok()?))),
        None => Some((body, None)),
    }
}

/// As [`split_reference`], the index read as LIGGGHTS's `atoi` reads it: its leading digits,
/// and a zero or non-number index is no index; None only for a `[` without its `]`.
pub fn split_reference_atoi(body: &str) -> Option<(&str, Option<usize>)> {
    match body.split_once('[') {
        Some((id, rest)) => {
            let inner = rest.strip_suffix(']')?;
            let digits: String = inner.chars().take_while(|c| c.is_ascii_digit()).collect();
            let k = digits.parse::<usize>().unwrap_or(0);
            Some((id, (k != 0).then_some(k)))
        }
        None => Some((body, None)),
    }
}

#[cfg(test)]
mod tests {

    #[test]
    fn atol_reads_as_c_does() {
        assert_eq!(atol("32452843.0"), 32452843);
        assert_eq!(atol("  -17x"), -17);
        assert_eq!(atol("+5"), 5);
        assert_eq!(atol("abc"), 0);
        assert_eq!(atol("1e5"), 1);
        assert_eq!(atol("99999999999999999999"), i64::MAX);
    }

    use super::*;

    #[test]
    fn references_split_as_liggghts_reads_them() {
        assert_eq!(split_reference("c1[2]"), Some(("c1", Some(2))));
        assert_eq!(split_reference("c1[x]"), None);
        assert_eq!(split_reference_atoi("c1[2x]"), Some(("c1", Some(2))));
        assert_eq!(split_reference_atoi("c1[x]"), Some(("c1", None)));
        assert_eq!(split_reference_atoi("c1[0]"), Some(("c1", None)));
        assert_eq!(split_reference_atoi("c1[2"), None);
        assert_eq!(split_reference_atoi("c1"), Some(("c1", None)));
    }

    #[test]
    fn liggghts_number_rules() {
        assert_eq!(numeric("1e-3").unwrap(), 1e-3);
        assert_eq!(numeric("-.5").unwrap(), -0.5);
        assert!(numeric("1.0x").is_err());
        assert!(numeric("").is_err());
        assert!(numeric("INF").is_err());
        assert_eq!(inumeric("-42").unwrap(), -42);
        assert!(inumeric("4.2").is_err());
        // overflow is an error naming the word, never infinity or a saturated integer
        let e = numeric("1e400").unwrap_err();
        let e = e.to_string();
        assert!(e.contains("'1e400'") && e.contains("out of range"), "{e}");
        assert!(numeric("-1e400").is_err());
        assert_eq!(numeric("1e-400").unwrap(), 0.0);
        assert!(numeric("1.7e308").is_ok());
        let e = inumeric("99999999999999999999").unwrap_err().to_string();
        assert!(e.contains("'99999999999999999999'"), "{e}");
        assert_eq!(
            inumeric("-9000000000000000000").unwrap(),
            -9_000_000_000_000_000_000
        );
    }

    #[test]
    fn atof_prefix() {
        assert_eq!(c_atof("  1.5e3xyz"), 1500.0);
        assert_eq!(c_atof("abc"), 0.0);
        assert_eq!(c_atof("-2e"), -2.0);
        assert_eq!(c_atof(".5"), 0.5);
    }
}
