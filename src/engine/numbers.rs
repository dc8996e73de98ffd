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
    Ok(c_atof(word))
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
    Ok(c_atof(word) as i64)
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
    }
}
