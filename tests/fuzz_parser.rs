//! Random and mutated decks thrown at the whole front end (line reader, substitution, word
//! splitting, variables, expressions, control flow, name registry) in check mode: whatever
//! the input, regolith reports problems and never panics or hangs.

use proptest::prelude::*;
use regolith::script::interp::Source;
use regolith::session::check_deck;

/// Decks that exercise every part of the language, to be mutated.
const SEEDS: &[&str] = &[
    "variable a index 1 2 3\nlabel loop\nprint \"a=${a} $(v_a*2) $a\"\nnext a\njump SELF loop\n",
    "variable x equal \"2^3^2 + sqrt(16) - -1 && !0 || 3 % 2\"\nif \"${x} > 70\" then \"print big\" elif \"${x} < 0\" \"print neg\" else \"print small\"\n",
    "variable i loop 3 pad\nvariable s string \"hello #not a comment\"\nprint '${s} $i' append out.txt screen no\nshell mkdir post\n",
    "atom_style granular\nboundary p p f\nregion reg block 0 1 0 1 0 1 units box\ncreate_box 1 reg\nfix m all property/global youngsModulus peratomtype 5e6\npair_style gran model hertz tangential history cohesion sjkr rolling_friction epsd\npair_coeff * *\n",
    "variable f file data.txt\nvariable e getenv HOME\nvariable u uloop 2\nprint \"${f} ${e} &\n continued\"\nquit\n",
    "include in.missing\njump other.deck label\nlabel\nnext\nvariable\nprint\nif\necho loud\nlog\n",
];

fn check(text: &str) {
    let _ = check_deck(
        Source::from_text("fuzz.deck", text, false),
        &Default::default(),
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn random_text_never_panics(text in "[ -~\\t\\n&$#{}()\"'\\\\]{0,200}") {
        check(&text);
    }

    #[test]
    fn random_unicode_never_panics(text in "\\PC{0,120}") {
        check(&text);
    }

    #[test]
    fn mutated_decks_never_panic(
        seed in 0..SEEDS.len(),
        edits in prop::collection::vec((any::<usize>(), any::<u8>(), 0u8..3), 1..12),
    ) {
        let mut bytes = SEEDS[seed].as_bytes().to_vec();
        for (pos, byte, op) in edits {
            if bytes.is_empty() { break; }
            let i = pos % bytes.len();
            match op {
                0 => bytes[i] = byte,
                1 => { bytes.remove(i); }
                _ => bytes.insert(i, byte),
            }
        }
        check(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn random_formulas_never_panic(expr in "[0-9a-z_+*/%^()<>=!&|.,\\[\\] -]{0,60}") {
        check(&format!("variable v equal \"{expr}\"\nprint \"${{v}} $({expr})\"\n"));
    }
}
