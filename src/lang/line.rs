//! Turning script text into commands: `&` continuation, `#` comments, `$` substitution and
//! word splitting, each exactly as LIGGGHTS 3.8.0 does it.

/// A reference found by `$` substitution.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum VarRef<'a> {
    /// `$x` or `${name}`: the variable's current text.
    Named(&'a str),
    /// `$(expr)`: an immediate equal-style evaluation, printed with `%.20g`.
    Immediate(&'a str),
}

/// Why a `$` reference has no value.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SubstitutionError {
    /// The named variable does not exist.
    #[error("Substitution for illegal variable")]
    Undefined,
    /// Its formula (a named equal-style variable or `$(expr)`) could not be evaluated.
    #[error(transparent)]
    Formula(#[from] crate::lang::expr::ExprError),
}

/// A lexical problem with a byte offset into the text being processed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LexError {
    /// LIGGGHTS's message for this problem.
    pub message: String,
    /// Byte range in the processed text.
    pub span: (usize, usize),
}

/// One word of a command, with its byte range in the (substituted) line; quotes removed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Word {
    /// The word's text without surrounding quotes.
    pub text: String,
    /// Byte offset of the word's first character (the opening quote, if quoted).
    pub start: usize,
    /// Byte offset one past the word's last character (the closing quote, if quoted).
    pub end: usize,
}

/// Read the next logical line from `lines` starting at index `*pos`.
///
/// A line whose last non-blank character is `&` is joined with the next line: the `&` and
/// the blanks after it are dropped, blanks before it are kept. Trailing blanks are removed
/// from the result. Returns the 0-based index of the first physical line used.
pub fn next_logical_line(lines: &[String], pos: &mut usize) -> Option<(String, usize)> {
    if *pos >= lines.len() {
        return None;
    }
    let first = *pos;
    let mut text = String::new();
    while *pos < lines.len() {
        let raw = &lines[*pos];
        *pos += 1;
        let trimmed = raw.trim_end_matches(is_c_space);
        if let Some(body) = trimmed.strip_suffix('&') {
            text.push_str(body);
            if *pos >= lines.len() {
                // LIGGGHTS keeps the dangling '&' when the file ends right after it
                text.push('&');
            }
            continue;
        }
        text.push_str(trimmed);
        break;
    }
    Some((text, first))
}

pub use crate::util::numbers::is_c_space;

/// Cut a `#` comment off, unless the `#` is inside single or double quotes.
pub fn strip_comment(text: &str) -> &str {
    let mut quote: Option<char> = None;
    for (i, c) in text.char_indices() {
        if c == '#' && quote.is_none() {
            return &text[..i];
        }
        if Some(c) == quote {
            quote = None;
        } else if c == '"' || c == '\'' {
            quote = Some(c);
        }
    }
    text
}

/// Replace every `$x`, `${name}` and `$(expr)` outside quotes with its value.
///
/// `lookup` returns the text for a reference or an error message. After each substitution
/// `progress` receives the partly substituted line (text so far plus the untouched rest), as
/// LIGGGHTS echoes it. Quote tracking follows LIGGGHTS: each `"` toggles the double-quote
/// state and each `'` the single-quote state, independently.
pub fn substitute(
    text: &str,
    mut lookup: impl FnMut(VarRef<'_>) -> Result<String, SubstitutionError>,
    mut progress: impl FnMut(&str),
) -> Result<String, LexError> {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut in_double = false;
    let mut in_single = false;
    let mut i = 0;
    while i < bytes.len() {
        let c = bytes[i];
        if c == b'$' && !in_double && !in_single {
            let (reference, beyond) = match bytes.get(i + 1) {
                Some(b'{') => {
                    let Some(close) = text[i + 2..].find('}') else {
                        return Err(LexError {
                            message: "Invalid variable name".into(),
                            span: (i, text.len()),
                        });
                    };
                    (VarRef::Named(&text[i + 2..i + 2 + close]), i + 3 + close)
                }
                Some(b'(') => {
                    let mut depth = 0i32;
                    let mut j = i + 2;
                    let mut close = None;
                    while j < bytes.len() {
                        match bytes[j] {
                            b'(' => depth += 1,
                            b')' if depth == 0 => {
                                close = Some(j);
                                break;
                            }
                            b')' => depth -= 1,
                            _ => {}
                        }
                        j += 1;
                    }
                    let Some(close) = close else {
                        return Err(LexError {
                            message: "Invalid immediate variable".into(),
                            span: (i, text.len()),
                        });
                    };
                    (VarRef::Immediate(&text[i + 2..close]), close + 1)
                }
                Some(_) => {
                    let len = text[i + 1..].chars().next().map_or(1, char::len_utf8);
                    (VarRef::Named(&text[i + 1..i + 1 + len]), i + 1 + len)
                }
                None => (VarRef::Named(""), i + 1),
            };
            let value = lookup(reference).map_err(|e| LexError {
                message: e.to_string(),
                span: (i, beyond),
            })?;
            out.push_str(&value);
            i = beyond;
            progress(&format!("{out}{}", &text[i..]));
            continue;
        }
        if c == b'"' {
            in_double = !in_double;
        } else if c == b'\'' {
            in_single = !in_single;
        }
        let len = text[i..].chars().next().map_or(1, char::len_utf8);
        out.push_str(&text[i..i + len]);
        i += len;
    }
    Ok(out)
}

/// Split a command line into words as LIGGGHTS does.
///
/// Words are separated by blanks. A word that starts with `"` or `'` runs to the next same
/// quote, which must be followed by a blank or the end of the line; the quotes are removed.
pub fn split_words(text: &str) -> Result<Vec<Word>, LexError> {
    let mut words = Vec::new();
    let bytes = text.as_bytes();
    let mut i = 0;
    loop {
        while i < bytes.len() && is_c_space(bytes[i] as char) {
            i += 1;
        }
        if i >= bytes.len() {
            return Ok(words);
        }
        let start = i;
        let c = bytes[i];
        if c == b'"' || c == b'\'' {
            let Some(rel) = text[i + 1..].find(c as char) else {
                return Err(LexError {
                    message: "Unbalanced quotes in input line".into(),
                    span: (start, text.len()),
                });
            };
            let close = i + 1 + rel;
            if let Some(&after) = bytes.get(close + 1) {
                if !is_c_space(after as char) {
                    return Err(LexError {
                        message: "Input line quote not followed by whitespace".into(),
                        span: (close, close + 1),
                    });
                }
            }
            words.push(Word {
                text: text[i + 1..close].to_string(),
                start,
                end: close + 1,
            });
            i = close + 2;
        } else {
            while i < bytes.len() && !is_c_space(bytes[i] as char) {
                i += 1;
            }
            words.push(Word {
                text: text[start..i].to_string(),
                start,
                end: i,
            });
            i += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(v: &[&str]) -> Vec<String> {
        v.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn continuation_joins_lines_like_liggghts() {
        let l = lines(&["a b &  ", "c&", "d   ", "e"]);
        let mut pos = 0;
        assert_eq!(
            next_logical_line(&l, &mut pos),
            Some(("a b cd".to_string(), 0))
        );
        assert_eq!(next_logical_line(&l, &mut pos), Some(("e".to_string(), 3)));
        assert_eq!(next_logical_line(&l, &mut pos), None);
    }

    #[test]
    fn comments_respect_quotes() {
        assert_eq!(strip_comment("print 'a # b' # c"), "print 'a # b' ");
        // LIGGGHTS quirk: a quote of the other kind inside quotes takes over, so this
        // comment survives (liggghts then fails with "Illegal print command")
        assert_eq!(strip_comment("x \"it's\" # c"), "x \"it's\" # c");
    }

    #[test]
    fn substitution_forms() {
        let look = |r: VarRef<'_>| match r {
            VarRef::Named("a") => Ok("1".to_string()),
            VarRef::Named("long") => Ok("22".to_string()),
            VarRef::Immediate(e) => Ok(format!("<{e}>")),
            _ => Err(SubstitutionError::Undefined),
        };
        let mut seen = Vec::new();
        let out = substitute("x $a ${long} $(f(1)+2) '$a'", look, |p| {
            seen.push(p.to_string())
        });
        assert_eq!(out.unwrap(), "x 1 22 <f(1)+2> '$a'");
        assert_eq!(seen[0], "x 1 ${long} $(f(1)+2) '$a'");
        assert_eq!(seen.len(), 3);
        let undefined = substitute("$b", look, |_| {}).unwrap_err();
        assert_eq!(undefined.span, (0, 2));
        assert_eq!(undefined.message, "Substitution for illegal variable");
        assert!(substitute("${a", look, |_| {}).is_err());
        assert!(substitute("$(1", look, |_| {}).is_err());
        assert!(substitute("$", look, |_| {}).is_err());
    }

    #[test]
    fn words_and_quotes() {
        let w = split_words("print \"a b\" 'c'  d").unwrap();
        let t: Vec<_> = w.iter().map(|w| w.text.as_str()).collect();
        assert_eq!(t, ["print", "a b", "c", "d"]);
        assert_eq!((w[1].start, w[1].end), (6, 11));
        assert_eq!(
            split_words("print \"a\"b").unwrap_err().message,
            "Input line quote not followed by whitespace"
        );
        assert_eq!(
            split_words("print \"a").unwrap_err().message,
            "Unbalanced quotes in input line"
        );
        assert!(split_words("   ").unwrap().is_empty());
    }
}
