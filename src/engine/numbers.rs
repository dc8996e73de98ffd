//! Reading numbers from command arguments exactly as LIGGGHTS does (`force->numeric`,
//! `force->inumeric`), with its error messages.

use crate::script::variables::c_atof;

/// LIGGGHTS's `numeric`: only digits, signs, `.`, `e`, `E` are allowed; the value is C `atof`.
pub fn numeric(word: &str) -> Result<f64, String> {
    let ok = !word.is_empty()
        && word
            .bytes()
            .all(|b| b.is_ascii_digit() || matches!(b, b'-' | b'+' | b'.' | b'e' | b'E'));
    if !ok {
        return Err(format!(
            "Expected floating point parameter in input script or data file, got '{word}'"
        ));
    }
    let x = c_atof(word);
    if x.is_infinite() {
        return Err(format!(
            "Floating point parameter '{word}' is out of range (largest: 1.79769e+308)"
        ));
    }
    Ok(x)
}

/// LIGGGHTS's `inumeric`: only digits and a sign are allowed; the value is C `atoi`.
pub fn inumeric(word: &str) -> Result<i64, String> {
    let ok = !word.is_empty()
        && word
            .bytes()
            .all(|b| b.is_ascii_digit() || b == b'-' || b == b'+');
    if !ok {
        return Err(format!(
            "Expected integer parameter in input script or data file, got '{word}'"
        ));
    }
    let x = c_atof(word);
    // an i64 holds up to about 9.2e18; beyond it `as` would quietly saturate
    if x.is_nan() || x.abs() >= 9.2e18 {
        return Err(format!(
            "Integer parameter '{word}' is out of range (it must be below 9.2e18)"
        ));
    }
    Ok(x as i64)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert!(e.contains("'1e400'") && e.contains("out of range"), "{e}");
        assert!(numeric("-1e400").is_err());
        assert_eq!(numeric("1e-400").unwrap(), 0.0);
        assert!(numeric("1.7e308").is_ok());
        let e = inumeric("99999999999999999999").unwrap_err();
        assert!(e.contains("'99999999999999999999'"), "{e}");
        assert_eq!(
            inumeric("-9000000000000000000").unwrap(),
            -9_000_000_000_000_000_000
        );
    }
}
