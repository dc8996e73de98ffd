//! C `printf`-compatible formatting of numbers.
//!
//! LIGGGHTS prints every number through C's `printf` family (`%.15g` for `${var}`, `%.20g`
//! for `$(expr)`, `%g` in dumps, `%14.8g` in thermo lines), and users hand it format strings
//! through `dump_modify format` and friends. To reproduce its output byte for byte we parse
//! such format strings ourselves, accept only conversions that are safe for the argument we
//! pass, and let the C library do the digit generation for each conversion.

use std::ffi::CString;

/// One `%...` conversion of a C format string.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Conversion {
    /// The full specification text, e.g. `%-14.8g`.
    pub spec: String,
    /// The conversion character (`g`, `e`, `f`, `d`, ...).
    pub kind: char,
}

impl Conversion {
    /// True for the floating-point conversions (`e E f F g G a A`).
    pub fn is_float(&self) -> bool {
        matches!(self.kind, 'e' | 'E' | 'f' | 'F' | 'g' | 'G' | 'a' | 'A')
    }
}

/// A piece of a parsed format string.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Piece {
    /// Literal text (with `%%` already turned into `%`).
    Text(String),
    /// A conversion consuming one argument.
    Convert(Conversion),
}

/// A C format string regolith cannot print with.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum FormatError {
    /// The text ends inside a conversion (its byte offset).
    #[error("format ends inside the conversion starting at byte {0}")]
    Unfinished(usize),
    /// A conversion letter C's printf has but numbers do not use (letter, byte offset).
    #[error("unsupported conversion '%{0}' at byte {1} (expected one of d i u x X o e E f F g G)")]
    Conversion(char, usize),
    /// One value, two conversions.
    #[error("format '{0}' has more than one conversion")]
    TwoConversions(String),
    /// No conversion at all.
    #[error("format '{0}' has no conversion")]
    NoConversion(String),
}

/// The message alone, for callers that still report errors as text.
impl From<FormatError> for String {
    fn from(e: FormatError) -> String {
        e.to_string()
    }
}

/// A parsed C format string such as `"%d %d %20.15g"`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CFormat {
    /// Literal text and conversions in order.
    pub pieces: Vec<Piece>,
}

impl CFormat {
    /// Parse `text`; errors name the offending conversion.
    pub fn parse(text: &str) -> Result<CFormat, FormatError> {
        let mut pieces = Vec::new();
        let mut literal = String::new();
        let mut chars = text.char_indices().peekable();
        while let Some((start, c)) = chars.next() {
            if c != '%' {
                literal.push(c);
                continue;
            }
            if let Some(&(_, '%')) = chars.peek() {
                chars.next();
                literal.push('%');
                continue;
            }
            let mut spec = String::from("%");
            while let Some(&(_, f)) = chars.peek() {
                if matches!(f, '-' | '+' | ' ' | '#' | '0') {
                    spec.push(f);
                    chars.next();
                } else {
                    break;
                }
            }
            take_digits(&mut chars, &mut spec);
            if let Some(&(_, '.')) = chars.peek() {
                spec.push('.');
                chars.next();
                take_digits(&mut chars, &mut spec);
            }
            // length modifiers LIGGGHTS users write (%ld, %lg, %lld) carry no meaning for us
            while let Some(&(_, l)) = chars.peek() {
                if l == 'l' || l == 'h' {
                    chars.next();
                } else {
                    break;
                }
            }
            let Some((_, kind)) = chars.next() else {
                return Err(FormatError::Unfinished(start));
            };
            if !matches!(
                kind,
                'd' | 'i' | 'u' | 'x' | 'X' | 'o' | 'e' | 'E' | 'f' | 'F' | 'g' | 'G' | 'a' | 'A'
            ) {
                return Err(FormatError::Conversion(kind, start));
            }
            spec.push(kind);
            if !literal.is_empty() {
                pieces.push(Piece::Text(std::mem::take(&mut literal)));
            }
            pieces.push(Piece::Convert(Conversion { spec, kind }));
        }
        if !literal.is_empty() {
            pieces.push(Piece::Text(literal));
        }
        Ok(CFormat { pieces })
    }

    /// The conversions, in order.
    pub fn conversions(&self) -> impl Iterator<Item = &Conversion> {
        self.pieces.iter().filter_map(|p| match p {
            Piece::Convert(c) => Some(c),
            Piece::Text(_) => None,
        })
    }
}

/// Move up to three ASCII digits from `chars` onto `spec` (a width or a precision).
fn take_digits(chars: &mut std::iter::Peekable<std::str::CharIndices<'_>>, spec: &mut String) {
    let mut n = 0;
    while let Some(&(_, d)) = chars.peek() {
        if d.is_ascii_digit() && n < 3 {
            spec.push(d);
            chars.next();
            n += 1;
        } else {
            break;
        }
    }
}

/// Format one value with one conversion spec (`%g`, `%8d`, ...), as C's `printf` would.
/// Integer conversions receive the value truncated toward zero.
pub fn format_one(conv: &Conversion, value: f64) -> String {
    let mut out = String::new();
    push_one(&mut out, conv, value);
    out
}

/// [`format_one`] appended to `out` (no allocation for the usual short numbers).
pub fn push_one(out: &mut String, conv: &Conversion, value: f64) {
    if conv.is_float() {
        push_c_f64(out, &conv.spec, value);
    } else {
        // integers go through a 64-bit conversion so %d of large ids stays exact
        let spec = format!("{}ll{}", &conv.spec[..conv.spec.len() - 1], conv.kind);
        out.push_str(&c_format_i64(&spec, value as i64));
    }
}

/// `value` through a whole `printf` format of at most one conversion appended to `out`:
/// its text as it is, the conversion as [`push_one`] (without one, only the text).
pub fn push_element(out: &mut String, fmt: &CFormat, value: f64) {
    for piece in &fmt.pieces {
        match piece {
            Piece::Text(t) => out.push_str(t),
            Piece::Convert(c) => push_one(out, c, value),
        }
    }
}

/// `%g` of `value` appended to `out`, as dumps print floats (no allocation).
pub fn push_g(out: &mut String, value: f64) {
    push_c_f64(out, "%g", value);
}

/// `sprintf(spec, value)` appended to `out`; `spec` must hold exactly one float conversion.
/// Short specs and results go through buffers on the stack.
fn push_c_f64(out: &mut String, spec: &str, value: f64) {
    if let Some((width, precision)) = plain_g(spec) {
        if push_g_digits(out, value, width, precision) {
            return;
        }
    }
    let mut fmt = [0u8; 40];
    if spec.len() >= fmt.len() || spec.contains('\0') {
        out.push_str(&c_format_f64(spec, value));
        return;
    }
    fmt[..spec.len()].copy_from_slice(spec.as_bytes());
    let mut buf = [0u8; 64];
    // SAFETY: fmt is NUL-terminated and holds exactly one floating conversion (checked by
    // CFormat::parse or the callers) and we pass exactly one double; snprintf never writes
    // past buf.len().
    let n = unsafe {
        libc::snprintf(
            buf.as_mut_ptr() as *mut libc::c_char,
            buf.len(),
            fmt.as_ptr() as *const libc::c_char,
            value,
        )
    };
    let n = n.max(0) as usize;
    match std::str::from_utf8(&buf[..n.min(buf.len())]) {
        Ok(text) if n < buf.len() => out.push_str(text),
        _ => out.push_str(&c_format_f64(spec, value)),
    }
}

/// Width and precision of a spec `%g`, `%.Pg`, `%Wg` or `%W.Pg` (no flags, no length
/// modifier), the dumps' and thermo's usual conversions; None for any other spec.
fn plain_g(spec: &str) -> Option<(usize, usize)> {
    let body = spec.strip_prefix('%')?.strip_suffix('g')?;
    let (width, precision) = match body.split_once('.') {
        Some((w, p)) => (w, Some(p)),
        None => (body, None),
    };
    let digits = |t: &str| t.len() <= 2 && t.bytes().all(|b| b.is_ascii_digit());
    // a leading 0 is the zero-padding flag, not a width
    if !digits(width) || width.starts_with('0') {
        return None;
    }
    let width = width.parse().unwrap_or(0);
    let precision = match precision {
        None => 6,
        Some(p) if digits(p) => p.parse().unwrap_or(0),
        Some(_) => return None,
    };
    Some((width, precision))
}

/// Exact powers of ten as doubles (10^0 ..= 10^22).
const POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The `p` (at most 9) correctly rounded significant digits of `a > 0` into `digits`, and
/// the decimal exponent, from one correctly rounded scaling by an exact power of ten: the
/// scaled value (below 10^9) is then within 1.2e-7 of the exact one, so its rounding is
/// the exact value's unless it lies within 1e-6 of a tie, which is left to
/// [`exact_digits`] (None), as are zero and values whose scaling needs a power beyond 10^22.
fn scaled_digits(a: f64, p: usize, digits: &mut [u8; 41]) -> Option<i32> {
    if p > 9 || a == 0.0 || !a.is_normal() {
        return None;
    }
    let (lo, hi) = (POWERS_OF_TEN[p - 1], POWERS_OF_TEN[p]);
    let mut exponent = a.log10().floor() as i32;
    let mut scaled = 0.0;
    for _ in 0..3 {
        let k = p as i32 - 1 - exponent;
        let power = *POWERS_OF_TEN.get(k.unsigned_abs() as usize)?;
        // one correctly rounded operation either way
        scaled = if k >= 0 { a * power } else { a / power };
        if scaled < lo {
            exponent -= 1;
        } else if scaled >= hi {
            exponent += 1;
        } else {
            break;
        }
    }
    if !(lo..hi).contains(&scaled) {
        return None;
    }
    let whole = scaled.floor();
    let fraction = scaled - whole;
    if (fraction - 0.5).abs() < 1e-6 {
        return None;
    }
    let mut rounded = whole as u64 + u64::from(fraction > 0.5);
    if rounded as f64 >= hi {
        rounded /= 10;
        exponent += 1;
    }
    for slot in digits[..p].iter_mut().rev() {
        *slot = b'0' + (rounded % 10) as u8;
        rounded /= 10;
    }
    Some(exponent)
}

/// The `p` significant digits of `a >= 0` into `digits` and the decimal exponent, from the
/// correctly rounded exponent formatting of Rust's standard library.
fn exact_digits(a: f64, p: usize, digits: &mut [u8; 41]) -> Option<i32> {
    use std::fmt::Write;
    let mut text = StackText {
        buf: [0; 48],
        len: 0,
    };
    write!(text, "{:.*e}", p - 1, a).ok()?;
    let text = &text.buf[..text.len];
    let e_at = text.iter().position(|&b| b == b'e')?;
    let exponent: i32 = std::str::from_utf8(&text[e_at + 1..]).ok()?.parse().ok()?;
    let mut n = 0;
    for &b in text[..e_at].iter().filter(|b| b.is_ascii_digit()) {
        *digits.get_mut(n)? = b;
        n += 1;
    }
    (n == p).then_some(exponent)
}

/// A fixed buffer on the stack that `write!` fills (false once it is full).
struct StackText {
    buf: [u8; 48],
    len: usize,
}

impl std::fmt::Write for StackText {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        let end = self.len + s.len();
        if end > self.buf.len() {
            return Err(std::fmt::Error);
        }
        self.buf[self.len..end].copy_from_slice(s.as_bytes());
        self.len = end;
        Ok(())
    }
}

/// C's `%W.Pg` of a finite `value` appended to `out`, from the correctly rounded decimal
/// digits Rust's exponent formatting gives (C's printf rounds the exact binary value to
/// nearest, ties to even, as Rust does): false, with nothing written, for values it leaves
/// to the C library (infinities, NaN, more than 40 significant digits).
fn push_g_digits(out: &mut String, value: f64, width: usize, precision: usize) -> bool {
    let p = precision.max(1);
    if !value.is_finite() || p > 40 {
        return false;
    }
    // the P significant digits (ASCII, without the point) and the decimal exponent
    let mut digits = [0u8; 41];
    let exponent = match scaled_digits(value.abs(), p, &mut digits) {
        Some(x) => x,
        None => match exact_digits(value.abs(), p, &mut digits) {
            Some(x) => x,
            None => return false,
        },
    };
    let mut body = [0u8; 64];
    let mut len = 0;
    let mut put = |b: u8| {
        body[len] = b;
        len += 1;
    };
    if value.is_sign_negative() {
        put(b'-');
    }
    if exponent < -4 || exponent >= p as i32 {
        // d.ddd (trailing zeros dropped) then e+XX with at least two exponent digits
        let kept = digits[1..p]
            .iter()
            .rposition(|&d| d != b'0')
            .map_or(0, |k| k + 1);
        put(digits[0]);
        if kept > 0 {
            put(b'.');
            digits[1..=kept].iter().for_each(|&d| put(d));
        }
        put(b'e');
        put(if exponent < 0 { b'-' } else { b'+' });
        let x = exponent.unsigned_abs();
        if x >= 100 {
            put(b'0' + (x / 100) as u8);
        }
        put(b'0' + (x / 10 % 10) as u8);
        put(b'0' + (x % 10) as u8);
    } else {
        // fixed: the same digits around the point, trailing zeros of the fraction dropped
        let kept = digits[..p]
            .iter()
            .rposition(|&d| d != b'0')
            .map_or(0, |k| k + 1);
        if exponent >= 0 {
            let int = exponent as usize + 1;
            digits[..int].iter().for_each(|&d| put(d));
            if kept > int {
                put(b'.');
                digits[int..kept].iter().for_each(|&d| put(d));
            }
        } else {
            put(b'0');
            if kept > 0 {
                put(b'.');
                (1..-exponent).for_each(|_| put(b'0'));
                digits[..kept].iter().for_each(|&d| put(d));
            }
        }
    }
    for _ in len..width {
        out.push(' ');
    }
    // every byte written above is ASCII
    out.push_str(std::str::from_utf8(&body[..len]).unwrap_or_default());
    true
}

/// `sprintf(spec, value)` for a double; `spec` must hold exactly one float conversion.
fn c_format_f64(spec: &str, value: f64) -> String {
    let fmt = CString::new(spec).expect("format spec has no NUL");
    let mut buf = vec![0u8; 64];
    loop {
        // SAFETY: fmt holds exactly one floating conversion (checked by CFormat::parse or the
        // callers below) and we pass exactly one double; snprintf never writes past buf.len().
        let n = unsafe {
            libc::snprintf(
                buf.as_mut_ptr() as *mut libc::c_char,
                buf.len(),
                fmt.as_ptr(),
                value,
            )
        };
        let n = n.max(0) as usize;
        if n < buf.len() {
            buf.truncate(n);
            return String::from_utf8_lossy(&buf).into_owned();
        }
        buf.resize(n + 1, 0);
    }
}

/// `sprintf(spec, value)` for a 64-bit integer; `spec` must hold exactly one `ll` conversion.
fn c_format_i64(spec: &str, value: i64) -> String {
    let fmt = CString::new(spec).expect("format spec has no NUL");
    let mut buf = vec![0u8; 32];
    loop {
        // SAFETY: fmt holds exactly one `ll` integer conversion and we pass one c_longlong.
        let n = unsafe {
            libc::snprintf(
                buf.as_mut_ptr() as *mut libc::c_char,
                buf.len(),
                fmt.as_ptr(),
                value as libc::c_longlong,
            )
        };
        let n = n.max(0) as usize;
        if n < buf.len() {
            buf.truncate(n);
            return String::from_utf8_lossy(&buf).into_owned();
        }
        buf.resize(n + 1, 0);
    }
}

/// `%.Ng` formatting, e.g. `g_precision(1.0/3.0, 15)` gives `0.333333333333333`.
pub fn g_precision(value: f64, precision: usize) -> String {
    let mut out = String::new();
    push_c_f64(&mut out, &format!("%.{}g", precision.min(99)), value);
    out
}

/// `%g` formatting (6 significant digits), as dumps print floats.
pub fn g(value: f64) -> String {
    let mut out = String::new();
    push_g(&mut out, value);
    out
}

/// Format `value` with an arbitrary single-conversion C spec such as `%14.8g` or `%8d`.
pub fn with_spec(spec: &str, value: f64) -> Result<String, FormatError> {
    let fmt = CFormat::parse(spec)?;
    let mut out = String::new();
    let mut used = 0;
    for piece in &fmt.pieces {
        match piece {
            Piece::Text(t) => out.push_str(t),
            Piece::Convert(c) => {
                used += 1;
                if used > 1 {
                    return Err(FormatError::TwoConversions(spec.to_string()));
                }
                out.push_str(&format_one(c, value));
            }
        }
    }
    if used == 0 {
        return Err(FormatError::NoConversion(spec.to_string()));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_c_printf() {
        assert_eq!(g_precision(1.0 / 3.0, 15), "0.333333333333333");
        assert_eq!(g_precision(1.0 / 3.0, 20), "0.33333333333333331483");
        assert_eq!(g_precision(-0.02064 - 1e-5, 15), "-0.02065");
        assert_eq!(g(-0.0), "-0");
        assert_eq!(g(1e20), "1e+20");
        assert_eq!(with_spec("%14.8g", 2.5).unwrap(), "           2.5");
        assert_eq!(with_spec("%8d", 42.0).unwrap(), "      42");
        assert_eq!(with_spec("%05d", 7.9).unwrap(), "00007");
        assert_eq!(g_precision(f64::INFINITY, 15), "inf");
        // results longer than the stack buffer
        assert_eq!(
            with_spec("%.40f", 0.5).unwrap(),
            format!("0.5{}", "0".repeat(39))
        );
        assert_eq!(with_spec("%f", 1e70).unwrap().len(), 71 + 7);
        let mut line = String::from("x ");
        push_g(&mut line, 2.0 / 3.0);
        assert_eq!(line, "x 0.666667");
    }

    /// C's own `snprintf` of one double (the reference for the digits path).
    fn c_reference(spec: &str, value: f64) -> String {
        c_format_f64(spec, value)
    }

    #[test]
    fn g_digits_match_the_c_library() {
        let specs = [
            "%g", "%.1g", "%.2g", "%.3g", "%.8g", "%.10g", "%.15g", "%.16g", "%.17g", "%.20g",
            "%.0g", "%14.8g", "%20.17g", "%12g", "%.25g", "%3.2g",
        ];
        // values at ties and rounding edges, powers of ten, extremes, subnormals, zeros
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            1.5,
            2.5,
            0.125,
            0.375,
            1e-4,
            9.99995e-5,
            1e-5,
            99999.95,
            999999.5,
            9999995.0,
            1e15,
            1e16,
            1e17,
            1e21,
            1e22,
            1e-300,
            5e-324,
            2.2250738585072014e-308,
            1.7976931348623157e308,
            123456.5,
            1234567.5,
            0.00012345,
            1.0 / 3.0,
            2.0 / 3.0,
        ];
        for e in -30..30 {
            for m in [1.0, 2.5, 5.0, 9.5, 9.95, 9.995, 9.9999995, 1.25, 7.0] {
                values.push(m * 10f64.powi(e));
            }
        }
        // pseudo-random doubles over the whole range and near one (a fixed stream)
        let mut state = 0x9e37_79b9_7f4a_7c15u64;
        for k in 0..20_000 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let v = if k % 2 == 0 {
                f64::from_bits(state)
            } else {
                (state >> 11) as f64 / (1u64 << 53) as f64 * 10f64.powi((k % 40) - 20)
            };
            if v.is_finite() {
                values.push(v);
            }
        }
        // decimal ties of six and eight digits (1234565e-9 and the like), near and at
        // which the scaled digits defer to the exact ones
        for k in 0..4_000u64 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let digits = (state % 9_000_000 + 1_000_000) as f64 * 10.0 + 5.0;
            values.push(digits * 10f64.powi((k % 30) as i32 - 20));
            values.push(digits * 100.0 + 50.0);
        }
        for &v in &values {
            for value in [v, -v] {
                for spec in specs {
                    let mut fast = String::new();
                    push_c_f64(&mut fast, spec, value);
                    assert_eq!(fast, c_reference(spec, value), "{spec} of {value:e}");
                }
            }
        }
    }

    #[test]
    fn only_plain_g_specs_take_the_digits_path() {
        assert_eq!(plain_g("%g"), Some((0, 6)));
        assert_eq!(plain_g("%14.8g"), Some((14, 8)));
        assert_eq!(plain_g("%.0g"), Some((0, 0)));
        for other in [
            "%-14.8g", "%014g", "%+g", "%#g", "%G", "%e", "%.8f", "%lg", "%123g",
        ] {
            assert_eq!(plain_g(other), None, "{other}");
        }
    }

    #[test]
    fn rejects_unsafe_conversions() {
        assert!(CFormat::parse("%s").is_err());
        assert!(CFormat::parse("%n").is_err());
        assert!(CFormat::parse("%").is_err());
        assert!(with_spec("%g %g", 1.0).is_err());
        let f = CFormat::parse("%d %lg 100%%").unwrap();
        assert_eq!(f.conversions().count(), 2);
    }
}
