//! Formula errors as LIGGGHTS reports them: messages, their order, offsets and variants.

use super::*;

#[test]
fn errors_as_liggghts() {
    let cases: &[(&str, &str)] = &[
        ("2^0", "Power by 0 in variable formula"),
        ("1/0", "Divide by 0 in variable formula"),
        ("5%0", "Modulo 0 in variable formula"),
        ("sqrt(-1)", "Sqrt of negative value in variable formula"),
        ("ln(0)", "Log of zero/negative value in variable formula"),
        ("log(-0)", "Log of zero/negative value in variable formula"),
        ("asin(2)", "Arcsin of invalid value in variable formula"),
        ("acos(-1.5)", "Arccos of invalid value in variable formula"),
        ("sqrt(1,2)", BAD_MATH),
        ("sqrt()", SYNTAX),
        ("atan2(1,2,3,4)", SYNTAX),
        ("foo(1)", BAD_NAME),
        (
            "ramp(0,1)",
            "Cannot use ramp in variable formula between runs",
        ),
        (
            "vdisplace(0,1)",
            "Cannot use vdisplace in variable formula between runs",
        ),
        (
            "swiggle(1,2,0)",
            "Cannot use swiggle in variable formula between runs",
        ),
        (
            "cwiggle(1,2,3)",
            "Cannot use cwiggle in variable formula between runs",
        ),
        ("normal(0,-1,15485863)", BAD_MATH),
        ("normal(0,-1,0)", BAD_MATH),
        ("random(0,1,0)", BAD_MATH),
        ("random(0,1,-5)", BAD_MATH),
        ("random(0,1,1e10)", BAD_MATH),
        ("random(0,1,1e308*10-1e308*10)", BAD_MATH),
        ("stagger(10,10)", BAD_MATH),
        ("stagger(1e308*10-1e308*10,1)", BAD_MATH),
        ("logfreq(1,3,3)", BAD_MATH),
        ("stride(5,1,1)", BAD_MATH),
        ("stride(1,5,0)", BAD_MATH),
        ("1 ! 2", SYNTAX),
        ("3 = 3", SYNTAX),
        ("1 & 1", SYNTAX),
        ("1 +", SYNTAX),
        ("", SYNTAX),
        ("(1", SYNTAX),
        ("2 3", SYNTAX),
        ("1 $", SYNTAX),
        ("x", "Atom vector in equal-style variable formula"),
        (
            "gmask(all)",
            "Gmask function in equal-style variable formula",
        ),
        ("rmask(r)", "Rmask function in equal-style variable formula"),
        (
            "grmask(all,r)",
            "Grmask function in equal-style variable formula",
        ),
        ("pi", "Invalid thermo keyword in variable formula"),
        ("sqrt (4)", "Invalid thermo keyword in variable formula"),
        ("x[0]", "Index between variable brackets must be positive"),
        (
            "x[4294967296]",
            "Index between variable brackets must be positive",
        ),
        ("x[a]", "Non digit character between brackets in variable"),
        ("x[1", "Mismatched brackets in variable"),
        ("(x[1)", "Mismatched brackets in variable"),
        ("x[]", "Empty brackets in variable"),
        ("v_a[1]", "Mismatched variable in variable formula"),
        ("c_nope", "Invalid compute ID in variable formula"),
        ("v_nope", "Invalid variable name in variable formula"),
        ("f_nope", "Invalid fix ID in variable formula"),
        ("count( all)", "Group ID in variable formula does not exist"),
        ("xcm(all, x)", "Invalid group function in variable formula"),
        ("foo[1]", "Invalid atom vector in variable formula"),
    ];
    for (formula, want) in cases {
        assert_eq!(fails(formula), *want, "{formula}");
    }
}

#[test]
fn errors_come_in_liggghts_order() {
    // liggghts computes while it reads: the first problem met wins
    let cases: &[(&str, &str)] = &[
        ("count(all)+foo(1)", BAD_NAME),
        ("1/0 + foo(1)", "Divide by 0 in variable formula"),
        ("v_nope +", "Invalid variable name in variable formula"),
        ("sqrt(-1, 1/0)", "Divide by 0 in variable formula"),
        ("sqrt(1/0, 2)", "Divide by 0 in variable formula"),
        ("1 ! 1/0", "Divide by 0 in variable formula"),
        ("1 ! (2", SYNTAX),
    ];
    for (formula, want) in cases {
        assert_eq!(fails(formula), *want, "{formula}");
    }
    // without a box (liggghts before create_box)
    for formula in ["step", "x", "x[1]", "x[0]", "c_x[0]", "pi", "sqrt (4)"] {
        assert_eq!(fails_without_box(formula), NO_BOX, "{formula}");
    }
    let mut w = world();
    w.has_box = false;
    assert_eq!(
        evaluate("PI+v_a", &mut w).unwrap(),
        std::f64::consts::PI + 2.0
    );
    // lookups happen in formula order
    let mut w = world();
    evaluate("count(all) + v_a*c_x[2] - step", &mut w).unwrap();
    assert_eq!(w.lookups, ["count(all)", "v_a", "c_x", "step"]);
}

#[test]
fn error_offsets() {
    assert_eq!(evaluate("1 +\n 2 $", &mut world()).unwrap_err().offset, 7);
    assert_eq!(evaluate("2 * (3 / 0)", &mut world()).unwrap_err().offset, 7);
    assert_eq!(
        evaluate("1 + sqrt(-1)", &mut world()).unwrap_err().offset,
        4
    );
    assert_eq!(evaluate("1 + v_nope", &mut world()).unwrap_err().offset, 4);
    assert_eq!(evaluate("x[1a]", &mut world()).unwrap_err().offset, 3);
    assert_eq!(Expr::parse("(1 + )").unwrap_err().offset, 5);
}

#[test]
fn errors_are_variants_with_positions() {
    let e = evaluate("1 + 2/0", &mut world()).unwrap_err();
    assert_eq!(e.kind, ExprErrorKind::DivideByZero);
    assert_eq!(e.to_string(), "Divide by 0 in variable formula");
    let e = Expr::parse("1 ! 2").unwrap_err();
    assert_eq!((e.kind, e.offset), (ExprErrorKind::Syntax, 5));
    let e = evaluate("2*1e400", &mut world()).unwrap_err();
    assert_eq!(e.kind, ExprErrorKind::OutOfRange("1e400".into()));
    assert_eq!(e.offset, 2);
    let e = evaluate("x[0]", &mut world()).unwrap_err();
    assert_eq!(e.kind, ExprErrorKind::IndexNotPositive);
    // a lookup's own error, unchanged
    let e = evaluate("1 + v_nope", &mut world()).unwrap_err();
    assert_eq!(
        e.kind,
        ExprErrorKind::Lookup(VariableError::Invalid(
            "Invalid variable name in variable formula".into()
        ))
    );
    assert_eq!(e.offset, 4);
    // a value only a run knows is told apart by its variant, not its text
    let e = evaluate("1 + v_later", &mut world()).unwrap_err();
    assert!(e.is_known_when_run(), "{e:?}");
    assert!(!evaluate("1/0", &mut world())
        .unwrap_err()
        .is_known_when_run());
    // a seed LIGGGHTS refuses, typed
    let e = evaluate("random(0,1,12345)", &mut world()).unwrap_err();
    assert!(
        matches!(
            e.kind,
            ExprErrorKind::Lookup(VariableError::Seed(
                crate::util::random::SeedError::NotPrime(12345)
            ))
        ),
        "{e:?}"
    );
    // a formula's error seen as the variable's: the kind is kept
    let v: VariableError = evaluate("sqrt(-1)", &mut world()).unwrap_err().into();
    assert_eq!(
        v,
        VariableError::Formula(Box::new(ExprErrorKind::SqrtNegative))
    );
    assert_eq!(v.to_string(), "Sqrt of negative value in variable formula");
    // a value only a run knows, crossing the engine's error type, comes back as the variant
    let e = crate::engine::error::EngineError::from(VariableError::KnownWhenRun);
    assert!(VariableError::from(e).is_known_when_run());
}
