//! Nearest valid names for a misspelled command, style or keyword.
//!
//! Style names are slash-separated words (`insert/stream`, `wall/gran`), and the usual slips
//! are a typo inside a word, a missing or doubled character, `_` for `/`, a dropped slash, or
//! words in the wrong order. The score combines an edit distance over the whole name with one
//! over its sorted components, so each of those slips lands near the intended name.

/// How different two names are (0 = the same; smaller is nearer).
fn distance(word: &str, candidate: &str) -> f64 {
    let w = normalise(word);
    let c = normalise(candidate);
    if w == c {
        return 0.1;
    }
    let whole = strsim::damerau_levenshtein(&w, &c) as f64;
    let squashed = strsim::damerau_levenshtein(&w.replace('/', ""), &c.replace('/', "")) as f64;
    let reordered = {
        let mut a: Vec<&str> = w.split('/').collect();
        let mut b: Vec<&str> = c.split('/').collect();
        a.sort_unstable();
        b.sort_unstable();
        strsim::damerau_levenshtein(&a.join("/"), &b.join("/")) as f64
    };
    let best = whole.min(squashed + 0.5).min(reordered + 0.5);
    // a shared prefix is a strong hint (nve/spher -> nve/sphere)
    let prefix = w.chars().zip(c.chars()).take_while(|(x, y)| x == y).count() as f64;
    best - 0.1 * prefix.min(5.0)
}

/// Lower case, with `_`, `-` and `.` read as `/`.
fn normalise(s: &str) -> String {
    s.chars()
        .map(|c| match c {
            '_' | '-' | '.' => '/',
            c => c.to_ascii_lowercase(),
        })
        .collect()
}

/// The largest distance still worth suggesting for a word of this length.
fn threshold(word: &str) -> f64 {
    let n = word.chars().count() as f64;
    (n / 3.0).clamp(1.5, 4.0)
}

/// Up to `max` names from `candidates` closest to `word`, nearest first (ties alphabetical).
pub fn nearest<'a>(word: &str, candidates: &[&'a str], max: usize) -> Vec<&'a str> {
    if word.is_empty() {
        return Vec::new();
    }
    let limit = threshold(word);
    let mut scored: Vec<(f64, &'a str)> = candidates
        .iter()
        .map(|&c| (distance(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .collect();
    scored.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(b.1)));
    scored.into_iter().take(max).map(|(_, c)| c).collect()
}

/// `did you mean 'x'?` or `did you mean one of: 'a', 'b', 'c'?`, or None if nothing is close.
pub fn did_you_mean(word: &str, candidates: &[&str]) -> Option<String> {
    match nearest(word, candidates, 3).as_slice() {
        [] => None,
        [one] => Some(format!("did you mean '{one}'?")),
        many => {
            let list: Vec<String> = many.iter().map(|m| format!("'{m}'")).collect();
            Some(format!("did you mean one of: {}?", list.join(", ")))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::names::{COMMANDS, COMPUTE_STYLES, FIX_STYLES};

    fn first(word: &str, list: &[&'static str]) -> Option<&'static str> {
        nearest(word, list, 1).first().copied()
    }

    #[test]
    fn common_slips_find_the_name() {
        assert_eq!(first("stream/insert", FIX_STYLES), Some("insert/stream"));
        assert_eq!(first("insert/strem", FIX_STYLES), Some("insert/stream"));
        assert_eq!(first("insertstream", FIX_STYLES), Some("insert/stream"));
        assert_eq!(first("wall/granular", FIX_STYLES), Some("wall/gran"));
        assert_eq!(first("nve/spher", FIX_STYLES), Some("nve/sphere"));
        assert_eq!(first("stress_atom", COMPUTE_STYLES), Some("stress/atom"));
        assert_eq!(first("pair_styl", COMMANDS), Some("pair_style"));
        assert_eq!(first("variabel", COMMANDS), Some("variable"));
    }

    #[test]
    fn unrelated_words_get_nothing() {
        assert_eq!(did_you_mean("xyzzyplugh", FIX_STYLES), None);
        assert_eq!(did_you_mean("", FIX_STYLES), None);
        assert_eq!(did_you_mean("gravity", &[]), None);
        assert_eq!(did_you_mean("ünïcödé/ß", FIX_STYLES), None);
    }

    #[test]
    fn wording() {
        assert_eq!(
            did_you_mean("gravty", FIX_STYLES).as_deref(),
            Some("did you mean 'gravity'?")
        );
        let many = did_you_mean("ab", &["ab1", "ab2", "ab3", "ab4"]).unwrap();
        assert_eq!(many, "did you mean one of: 'ab1', 'ab2', 'ab3'?");
    }
}
