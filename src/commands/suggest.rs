//! Nearest valid names for a misspelled command, style or keyword.
//!
//! Style names are slash-separated words (`insert/stream`, `wall/gran`), commands and keywords
//! underscore-separated ones (`read_restart`). The usual slips are a typo inside a word, a
//! missing, extra or swapped character, `_` for `/`, a dropped separator (`insertstream`), words
//! in the wrong order (`stream/insert`), a word cut short or spelled out (`insert/rate`,
//! `wall/granular`), or the wrong case. The score is a Damerau-Levenshtein edit distance taken
//! over the best of several views of the two names (as written, without separators, with the
//! words sorted, one a prefix of the other), less a little credit for a shared beginning. Only
//! names within a length-dependent threshold, and not much worse than the best one, are offered.

/// Separator characters, all read as `/`.
const SEPARATORS: [char; 4] = ['/', '_', '-', '.'];

/// Words longer than this are not names; nothing is suggested for them (and no quadratic
/// edit distance is run on them).
const MAX_WORD_CHARS: usize = 80;

/// How far (tenths of an edit) behind the best suggestion another must stay to be offered.
const RELATIVE_CUTOFF: u32 = 10;

/// Lower case, with every separator read as `/`.
fn normalise(s: &str) -> String {
    s.chars()
        .map(|c| {
            if SEPARATORS.contains(&c) {
                '/'
            } else {
                c.to_ascii_lowercase()
            }
        })
        .collect()
}

/// The name without separators.
fn squash(s: &str) -> String {
    s.chars().filter(|&c| c != '/').collect()
}

/// The name's words in sorted order.
fn sorted_words(s: &str) -> String {
    let mut words: Vec<&str> = s.split('/').collect();
    words.sort_unstable();
    words.join("/")
}

/// Number of leading characters two strings share.
fn common_prefix(a: &str, b: &str) -> usize {
    a.chars().zip(b.chars()).take_while(|(x, y)| x == y).count()
}

/// Score (in tenths of an edit) for `word` being `candidate` cut short (`insert/rate`,
/// `mesh/surf`, also with one slip: `insert/rates`), lower for a cut at a word boundary, or
/// `candidate` with its last word spelled out (`wall/granular`). None if neither, or if the
/// shorter one is too short to mean anything.
fn truncation(word: &str, candidate: &str) -> Option<u32> {
    let n = word.chars().count();
    if n >= 3 && candidate.chars().count() > n {
        let cut = candidate
            .char_indices()
            .nth(n)
            .map_or(candidate.len(), |(i, _)| i);
        let slips = strsim::damerau_levenshtein(word, &candidate[..cut]) as u32;
        if slips <= 1 {
            let at_boundary = candidate[cut..].starts_with('/') || word.ends_with('/');
            return Some(if at_boundary { 10 } else { 15 } + 10 * slips);
        }
    }
    if candidate.chars().count() >= 3 && word.starts_with(candidate) {
        let extra = &word[candidate.len()..];
        if extra.chars().count() >= 3 && !extra.contains('/') && !candidate.ends_with('/') {
            return Some(20);
        }
    }
    None
}

/// How different `word` is from `candidate`, in tenths of an edit (0 = the same).
fn distance(word: &str, candidate: &str) -> u32 {
    if word == candidate {
        return 0;
    }
    let w = normalise(word);
    let c = normalise(candidate);
    if w == c {
        // only case or separators differ
        return 2;
    }
    let dl = |a: &str, b: &str| 10 * strsim::damerau_levenshtein(a, b).min(1000) as u32;
    let mut best = dl(&w, &c);
    best = best.min(dl(&squash(&w), &squash(&c)) + 5);
    if w.contains('/') || c.contains('/') {
        best = best.min(dl(&sorted_words(&w), &sorted_words(&c)) + 5);
    }
    if let Some(t) = truncation(&w, &c) {
        best = best.min(t);
    }
    // a shared beginning is a strong hint (nve/spher -> nve/sphere), but never makes a
    // different name as good as an exact one
    let prefix = common_prefix(&w, &c).min(5) as u32;
    best.saturating_sub(prefix).max(3)
}

/// The largest distance (tenths) still worth suggesting for a word of this length.
fn threshold(word: &str) -> u32 {
    let n = word.chars().count() as u32;
    (n * 10 / 3).clamp(15, 40)
}

/// Up to `max` names from `candidates` closest to `word`, nearest first (ties alphabetical).
/// Names too far from `word`, or much farther than the nearest one, are left out, so the
/// result may be empty.
pub fn nearest<'a>(word: &str, candidates: &[&'a str], max: usize) -> Vec<&'a str> {
    let chars = word.chars().count();
    if chars == 0 || chars > MAX_WORD_CHARS || max == 0 {
        return Vec::new();
    }
    let limit = threshold(word);
    let mut scored: Vec<(u32, &'a str)> = candidates
        .iter()
        .map(|&c| (distance(word, c), c))
        .filter(|(d, _)| *d <= limit)
        .collect();
    scored.sort_unstable();
    scored.dedup_by(|a, b| a.1 == b.1);
    let Some(&(best, _)) = scored.first() else {
        return Vec::new();
    };
    scored
        .into_iter()
        .take_while(|(d, _)| *d < best + RELATIVE_CUTOFF)
        .take(max)
        .map(|(_, c)| c)
        .collect()
}

/// `did you mean 'x'?` or `did you mean one of: 'a', 'b', 'c'?` (at most three), or None if
/// nothing is close.
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
    use crate::commands::names::{
        COMMANDS, COMPUTE_STYLES, DUMP_STYLES, FIX_STYLES, GRAN_COHESION_MODELS,
        GRAN_NORMAL_MODELS, GRAN_ROLLING_MODELS, GRAN_TANGENTIAL_MODELS, REGION_STYLES,
    };

    fn first(word: &str, list: &[&'static str]) -> Option<&'static str> {
        nearest(word, list, 1).first().copied()
    }

    #[test]
    fn brief_examples() {
        assert_eq!(first("stream/insert", FIX_STYLES), Some("insert/stream"));
        assert_eq!(first("wall/granular", FIX_STYLES), Some("wall/gran"));
        assert_eq!(first("insertstream", FIX_STYLES), Some("insert/stream"));
        assert_eq!(first("nve/spher", FIX_STYLES), Some("nve/sphere"));
        assert_eq!(first("stress_atom", COMPUTE_STYLES), Some("stress/atom"));
    }

    #[test]
    fn common_slips_find_the_name() {
        let cases: &[(&str, &[&str], &str)] = &[
            ("insert/strem", FIX_STYLES, "insert/stream"),
            ("insert/steam", FIX_STYLES, "insert/stream"),
            ("gravty", FIX_STYLES, "gravity"),
            ("Gravity", FIX_STYLES, "gravity"),
            ("gran/wall", FIX_STYLES, "wall/gran"),
            ("wallgran", FIX_STYLES, "wall/gran"),
            ("wall_gran", FIX_STYLES, "wall/gran"),
            ("mesh/surf", FIX_STYLES, "mesh/surface"),
            ("insert/rate", FIX_STYLES, "insert/rate/region"),
            ("insert/rates", FIX_STYLES, "insert/rate/region"),
            ("move/meshes", FIX_STYLES, "move/mesh"),
            ("ave/spacial", FIX_STYLES, "ave/spatial"),
            ("rotate", COMPUTE_STYLES, "erotate"),
            ("nve/sphere/", FIX_STYLES, "nve/sphere"),
            (
                "multisphere/nointegrate",
                FIX_STYLES,
                "multisphere/nointegration",
            ),
            ("property/atom/trace", FIX_STYLES, "property/atom/tracer"),
            (
                "particletemplate/spheres",
                FIX_STYLES,
                "particletemplate/sphere",
            ),
            ("custom_vtk", DUMP_STYLES, "custom/vtk"),
            ("mesh/gran/vtk", DUMP_STYLES, "mesh/gran/VTK"),
            ("atom/stress", COMPUTE_STYLES, "stress/atom"),
            ("cylindre", REGION_STYLES, "cylinder"),
            ("hertz/stifness", GRAN_NORMAL_MODELS, "hertz/stiffness"),
            ("histroy", GRAN_TANGENTIAL_MODELS, "history"),
            ("sjrk", GRAN_COHESION_MODELS, "sjkr"),
            ("pair_styl", COMMANDS, "pair_style"),
            ("style_pair", COMMANDS, "pair_style"),
            ("variabel", COMMANDS, "variable"),
            ("read_restar", COMMANDS, "read_restart"),
            ("thermo_stlye", COMMANDS, "thermo_style"),
            ("writerestart", COMMANDS, "write_restart"),
        ];
        for &(word, list, want) in cases {
            assert_eq!(first(word, list), Some(want), "{word}");
        }
    }

    #[test]
    fn several_equally_near_names() {
        assert_eq!(
            nearest("epsd4", GRAN_ROLLING_MODELS, 5),
            vec!["epsd", "epsd2", "epsd3"]
        );
        assert_eq!(
            nearest("insert", FIX_STYLES, 3),
            vec!["insert/pack", "insert/rate/region", "insert/stream"]
        );
        assert_eq!(
            did_you_mean("insert", FIX_STYLES).as_deref(),
            Some("did you mean one of: 'insert/pack', 'insert/rate/region', 'insert/stream'?")
        );
    }

    #[test]
    fn far_worse_names_are_not_offered() {
        // nve/sph is near too, but clearly worse than nve/sphere
        assert_eq!(nearest("nve/spher", FIX_STYLES, 5), vec!["nve/sphere"]);
        assert_eq!(
            did_you_mean("stream/insert", FIX_STYLES).as_deref(),
            Some("did you mean 'insert/stream'?")
        );
    }

    #[test]
    fn deterministic_order() {
        let a = nearest("ave", FIX_STYLES, 10);
        let b = nearest("ave", FIX_STYLES, 10);
        assert_eq!(a, b);
        let mut reversed: Vec<&str> = FIX_STYLES.to_vec();
        reversed.reverse();
        assert_eq!(nearest("ave", &reversed, 10), a);
        // ties are alphabetical
        assert_eq!(
            nearest("ab", &["ab3", "ab1", "ab2"], 3),
            vec!["ab1", "ab2", "ab3"]
        );
        // duplicates in the candidates are offered once
        assert_eq!(
            nearest("gravty", &["gravity", "gravity"], 3),
            vec!["gravity"]
        );
    }

    #[test]
    fn unrelated_words_get_nothing() {
        assert_eq!(did_you_mean("xyzzyplugh", FIX_STYLES), None);
        assert_eq!(did_you_mean("banana", COMMANDS), None);
        assert_eq!(did_you_mean("q", FIX_STYLES), None);
        assert_eq!(did_you_mean("thermostat/berendsen", FIX_STYLES), None);
    }

    #[test]
    fn edge_cases_do_not_panic() {
        assert_eq!(did_you_mean("", FIX_STYLES), None);
        assert_eq!(did_you_mean("gravity", &[]), None);
        assert!(nearest("gravity", FIX_STYLES, 0).is_empty());
        assert_eq!(did_you_mean("ünïcödé/ß", FIX_STYLES), None);
        assert_eq!(did_you_mean("グラビティ", FIX_STYLES), None);
        assert_eq!(did_you_mean("/", FIX_STYLES), None);
        assert_eq!(did_you_mean("///", FIX_STYLES), None);
        // non-ASCII next to a prefix cut must not split a character
        assert_eq!(first("nveé", FIX_STYLES), Some("nve"));
        assert_eq!(first("gravité", FIX_STYLES), Some("gravity"));
        assert_eq!(nearest("é", &["é/x", "éé"], 3).first(), Some(&"éé"));
        let long = "insert/stream".repeat(1000);
        assert_eq!(did_you_mean(&long, FIX_STYLES), None);
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

    #[test]
    fn exact_names_come_first() {
        assert_eq!(first("nve", FIX_STYLES), Some("nve"));
        assert_eq!(first("ke", COMPUTE_STYLES), Some("ke"));
        assert_eq!(first("run", COMMANDS), Some("run"));
    }
}
