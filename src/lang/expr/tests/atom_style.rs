//! Atom-style formulas: per-atom values against LIGGGHTS, columns against the walk.

#![allow(clippy::excessive_precision, clippy::approx_constant)]

use super::*;
use crate::lang::error::ExprErrorKind;

/// Per-atom values of an atom-style formula for the two atoms (fresh world each time,
/// as liggghts was run once per formula).
fn per_atom(formula: &str, w: &mut World) -> Result<Vec<f64>, ExprErrorKind> {
    let e = Expr::parse_atom(formula, w).map_err(|e| e.kind)?;
    e.eval_atoms(w, 2).map_err(|e| e.kind)
}

/// [`per_atom`] evaluated atom by atom.
fn per_atom_walk(formula: &str, w: &mut World) -> Result<Vec<f64>, ExprErrorKind> {
    let e = Expr::parse_atom(formula, w).map_err(|e| e.kind)?;
    (0..2)
        .map(|a| e.eval(w, Some(a)).map_err(|e| e.kind))
        .collect()
}

#[test]
fn whole_columns_equal_the_atom_by_atom_walk() {
    for formula in [
        "x*x+2.5*x-1/(x+0.3)",
        "-x^3%0.07",
        "sqrt(x)*cos(2*x)+atan2(x,0.2)-round(10*x)+floor(x)+ceil(x)",
        "(x>0.2)&&(x<0.5)||(id==1)",
        "swiggle(0,1,2)+x",
        "1/(x-0.1)",
        "sqrt(x-0.2)",
        "ln(x-0.1)+log(x)",
        "asin(x*3)",
        "x^(x-0.1)",
        "mass*vx+r*density",
    ] {
        let (mut a, mut b) = (world(), world());
        a.run = Some((0, 10));
        b.run = Some((0, 10));
        let col = per_atom(formula, &mut a);
        let walk = per_atom_walk(formula, &mut b);
        match (&col, &walk) {
            (Ok(x), Ok(y)) => assert!(
                x.iter().zip(y).all(|(p, q)| p.to_bits() == q.to_bits()),
                "{formula}: {x:?} vs {y:?}"
            ),
            _ => assert_eq!(col, walk, "{formula}"),
        }
    }
}

#[test]
fn atom_style_as_liggghts() {
    // liggghts: two granular atoms at x = 0.1 and 0.4, "variable s atom FORMULA",
    // dumped as "id v_s" with %.17g during "run 0" (S = 15485863)
    let cases: &[(&str, [f64; 2])] = &[
        ("x", [0.10000000000000001, 0.40000000000000002]),
        ("id*2", [2.0, 4.0]),
        ("x[2]", [0.40000000000000002, 0.40000000000000002]),
        ("step", [0.0, 0.0]),
        ("PI", [3.1415926535897931, 3.1415926535897931]),
        ("gmask(all)", [1.0, 1.0]),
        ("random(0,1,S)", [0.86316907405853271, 0.65642291307449341]),
        ("normal(0,1,S)", [0.38324647910204879, 0.88978824275827484]),
        (
            "-random(0,1,S)",
            [-0.86316907405853271, -0.65642291307449341],
        ),
        // right operand first for / % ^
        (
            "random(0,1,S)/random(1,2,S)",
            [0.35231526876120284, 0.24990537925862819],
        ),
        (
            "random(0,1,S)%random(2,3,S)",
            [0.65642291307449341, 0.47164058685302734],
        ),
        (
            "random(0,1,S)^random(2,3,S)",
            [0.2996167684341281, 0.11418923293787246],
        ),
        // left operand first for the others
        (
            "random(0,1,S)-random(0,2,S)",
            [-0.4496767520904541, -0.056004524230957031],
        ),
        (
            "random(0,1,S)+random(0,2,S)",
            [2.1760149002075195, 1.8305578231811523],
        ),
        (
            "random(0,1,S)*random(0,2,S)",
            [1.1332079161386304, 0.83695135931884579],
        ),
        ("random(0,1,S)>=random(0,1,S)", [1.0, 1.0]),
        ("random(0,1,S)<random(0,1,S)", [0.0, 0.0]),
        // && and || short-circuit
        (
            "random(0,1,S) - (x<0.2 && random(0,1,S)<2)",
            [-0.13683092594146729, 0.88727664947509766],
        ),
        (
            "random(0,1,S) - (x<0.2 || random(0,1,S)<2)",
            [-0.13683092594146729, -0.34357708692550659],
        ),
        // atan2's arguments are evaluated right to left
        (
            "atan2(random(0,1,S),random(0,1,S))",
            [0.65017470889489115, 0.48857552091690432],
        ),
        // round() evaluates its argument three times
        (
            "round(random(0,2,S))*10+random(0,1,S)",
            [20.471640586853027, 10.388184249401093],
        ),
        (
            "random(random(0,1,S),random(5,6,S),S)",
            [5.1161112804242634, 4.7766567494516963],
        ),
        (
            "normal(random(0,1,S),1,S)",
            [1.6497417787037096, 0.78934110913404643],
        ),
        (
            "ramp(random(0,1,S),random(0,2,S))",
            [0.86316907405853271, 0.88727664947509766],
        ),
        ("random(0,1,S)*0+1", [1.0, 1.0]),
        // `a ! b` is `!a` in atom style
        ("x ! 1", [0.0, 0.0]),
        ("0 ! 5", [1.0, 1.0]),
        ("0 ! x", [1.0, 1.0]),
        ("2 + 0 ! 5", [3.0, 3.0]),
        ("(x ! 3) + 1", [1.0, 1.0]),
        ("x < 0.2 ! 1", [0.0, 0.0]),
    ];
    for (formula, want) in cases {
        let mut w = world();
        w.run = Some((0, 0));
        let got = per_atom(&formula.replace('S', &S.to_string()), &mut w)
            .unwrap_or_else(|e| panic!("{formula}: {e}"));
        assert_eq!(got, want.to_vec(), "{formula}");
    }
}

#[test]
fn atom_style_errors_as_liggghts() {
    let cases: &[(&str, &str)] = &[
        ("!x", SYNTAX),
        ("1+!x", SYNTAX),
        ("!0", SYNTAX),
        ("x^0", "Power by 0 in variable formula"),
        ("1/0", "Divide by 0 in variable formula"),
        ("x/0", "Divide by 0 in variable formula"),
        ("sqrt(-1)", "Sqrt of negative value in variable formula"),
        ("sqrt(-x)", "Sqrt of negative value in variable formula"),
    ];
    for (formula, want) in cases {
        let mut w = world();
        w.run = Some((0, 0));
        assert_eq!(
            per_atom(formula, &mut w).unwrap_err().to_string(),
            *want,
            "{formula}"
        );
    }
    // run-only functions are refused while reading, even where unused
    let mut w = world();
    assert_eq!(
        per_atom("x + 0*ramp(0,1)", &mut w).unwrap_err().to_string(),
        "Cannot use ramp in variable formula between runs"
    );
}

#[test]
fn atom_style_swiggle_is_cwiggle() {
    // liggghts, timestep 0.25, "run 2", dump every step: at step 1 the atom-style
    // swiggle(1,2,3) prints 1.2679491924311226 (cwiggle's value), equal style prints 2
    let mut w = world();
    w.step = 1;
    w.run = Some((0, 2));
    w.dt = 0.25;
    assert_eq!(
        per_atom("swiggle(1,2,3)", &mut w).unwrap(),
        [1.2679491924311226; 2]
    );
    assert_eq!(
        per_atom("x*0+swiggle(1,2,3)", &mut w).unwrap(),
        [1.2679491924311226; 2]
    );
    assert_eq!(evaluate("swiggle(1,2,3)", &mut w).unwrap(), 2.0);
    let e = Expr::parse("swiggle(1,2,3)").unwrap();
    assert_eq!(e.eval(&mut w, Some(0)).unwrap(), 1.2679491924311226);
}

#[test]
fn atom_style_reads_globals_once() {
    let mut w = world();
    let e = Expr::parse_atom("x*v_a + step + count(all)", &mut w).unwrap();
    assert_eq!(w.lookups, ["v_a", "step", "count(all)"]);
    assert_eq!(e.eval(&mut w, Some(1)).unwrap(), 0.8 + 2.0);
    assert_eq!(w.lookups.len(), 3);
    assert!(e.is_per_atom());
    assert!(!Expr::parse("1+v_a").unwrap().is_per_atom());
    assert!(Expr::parse("gmask(all)*2").unwrap().is_per_atom());
    // the seed of the first random() met while folding makes the generator
    let mut w = world();
    Expr::parse_atom("random(0,1,32452843)/random(0,1,15485863)", &mut w).unwrap();
    let mut want = RanMars::new(32452843).unwrap();
    assert_eq!(w.atom_rng.as_mut().unwrap().uniform(), want.uniform());
}
