//! Parsing alone, Boolean conditions, deep nesting, C conversions and never panicking.

use super::*;

#[test]
fn syntax_only_parse() {
    let e = Expr::parse("x*2 + mass").unwrap();
    assert!(e.is_per_atom());
    assert_eq!(
        e.eval(&mut world(), None).unwrap_err().to_string(),
        "Atom vector in equal-style variable formula"
    );
    assert_eq!(Expr::parse("1 ! 2").unwrap_err().to_string(), SYNTAX);
    assert_eq!(Expr::parse("foo(1)").unwrap_err().to_string(), BAD_NAME);
    let e = Expr::parse("1/0").unwrap();
    assert_eq!(
        e.eval(&mut world(), None).unwrap_err().to_string(),
        "Divide by 0 in variable formula"
    );
}

#[test]
fn boolean_conditions() {
    // liggghts: if "COND" then "print T" else "print F" (T means nonzero)
    let truths: &[(&str, bool)] = &[
        ("2.5 > 1", true),
        ("-1", true),
        ("-", false),
        ("!0", true),
        ("!!0", false),
        ("((1))", true),
        ("1e3 < 999", false),
        ("1 == 1.0", true),
        ("-e5 == 0", true),
        (".", false),
        ("1..2 == 1", true),
        ("1 == 1 == 1", true),
        ("2 || 0 && 0", true),
        ("!1 || 1", true),
        ("-1 >= 0 || (3 == 3 && !0)", true),
    ];
    for (cond, want) in truths {
        assert_eq!(evaluate_boolean(cond).unwrap() != 0.0, *want, "{cond}");
    }
    assert_eq!(evaluate_boolean("-2.5").unwrap(), -2.5);
    for cond in [
        "abc == abc",
        "1 +1",
        "",
        "- 1",
        "1 ! 2",
        "a",
        "0x10",
        ")",
        "()",
        "1 2",
        "1 ! 1/0",
    ] {
        assert_eq!(
            evaluate_boolean(cond).unwrap_err().to_string(),
            BOOLEAN,
            "{cond}"
        );
    }
    assert_eq!(evaluate_boolean("(1").unwrap_err().to_string(), SYNTAX);
    assert_eq!(evaluate_boolean("1 ! (2").unwrap_err().to_string(), SYNTAX);
}

#[test]
fn deep_formulas_do_not_overflow_the_stack() {
    let deep = "(".repeat(5000) + "1" + &")".repeat(5000);
    assert_eq!(fails(&deep), TOO_DEEP);
    assert_eq!(evaluate_boolean(&deep).unwrap_err().to_string(), TOO_DEEP);
    assert_eq!(Expr::parse(&deep).unwrap_err().to_string(), TOO_DEEP);
    let chain = vec!["1"; 5000].join("+");
    assert_eq!(ev(&chain), 5000.0);
    assert_eq!(Expr::parse(&chain).unwrap_err().to_string(), TOO_DEEP);
    let fine = vec!["1"; 900].join("+");
    assert_eq!(
        Expr::parse(&fine)
            .unwrap()
            .eval(&mut world(), None)
            .unwrap(),
        900.0
    );
    // equal style computes as it goes, so long prefix chains are no problem there
    assert_eq!(ev(&("-".repeat(5000) + "1")), 1.0);
    assert_eq!(
        Expr::parse(&("-".repeat(5000) + "1"))
            .unwrap_err()
            .to_string(),
        TOO_DEEP
    );
}

#[test]
fn c_int_is_x86_truncation() {
    assert_eq!(c_int(2.9), 2);
    assert_eq!(c_int(-2.9), -2);
    assert_eq!(c_int(1e10), i32::MIN);
    assert_eq!(c_int(-1e10), i32::MIN);
    assert_eq!(c_int(f64::NAN), i32::MIN);
    assert_eq!(c_int(2147483647.5), i32::MAX);
}

use proptest::prelude::*;

proptest! {
    #[test]
    fn never_panics(text in "\\PC{0,40}") {
        let _ = evaluate(&text, &mut world());
        let _ = evaluate_boolean(&text);
        if let Ok(e) = Expr::parse(&text) {
            let _ = e.eval(&mut world(), None);
            let _ = e.eval(&mut world(), Some(1));
        }
        let mut w = world();
        if let Ok(e) = Expr::parse_atom(&text, &mut w) {
            let _ = e.eval(&mut w, Some(0));
        }
    }

    #[test]
    fn never_panics_on_formula_soup(
        parts in proptest::collection::vec(
            prop_oneof![
                Just("("), Just(")"), Just("["), Just("]"), Just(","), Just("-"),
                Just("!"), Just("^"), Just("/"), Just("%"), Just("&&"), Just("||"),
                Just("=="), Just("<"), Just("1"), Just("0"), Just(".5e3"), Just("x"),
                Just("v_a"), Just("c_x"), Just("step"), Just("PI"), Just("sqrt"),
                Just("random"), Just("round"), Just("atan2"), Just("stride"),
                Just("logfreq"), Just("count"), Just("gmask"), Just(" "), Just("15485863"),
            ],
            0..30,
        )
    ) {
        let text = parts.concat();
        let mut w = world();
        w.run = Some((0, 10));
        w.step = 5;
        let _ = evaluate(&text, &mut w);
        let _ = evaluate_boolean(&text);
        if let Ok(e) = Expr::parse(&text) {
            let _ = e.eval(&mut w, None);
            let _ = e.eval(&mut w, Some(1));
        }
        if let Ok(e) = Expr::parse_atom(&text, &mut w) {
            let _ = e.eval(&mut w, Some(0));
        }
    }
}
