//! Equal-style formulas against LIGGGHTS: precedence, numbers, math, step and reference
//! functions, random streams.

#![allow(clippy::excessive_precision, clippy::approx_constant)]

use super::*;

#[test]
fn precedence_and_associativity() {
    let cases: &[(&str, &str)] = &[
        ("2^3^2", "64"),
        ("-2^2", "4"),
        ("7%3", "1"),
        ("-7%3", "-1"),
        ("5%-3", "2"),
        ("5.5%2", "1.5"),
        ("!1+1", "1"),
        ("2*-3", "-6"),
        ("- -3", "3"),
        ("--3", "3"),
        ("----1", "1"),
        ("!!5", "1"),
        ("1 < 2 == 1", "1"),
        ("3>2>1", "0"),
        ("1+2*3^4", "163"),
        ("1<2+3*4^-5", "1"),
        ("1||2&&3==4<5+6*7^-8", "1"),
        ("1+2+3+4+5+6+7+8+9+10", "55"),
        ("(-2)^3", "-8"),
        ("0^0.5", "0"),
        ("2^0.5", "1.4142135623731"),
    ];
    for (formula, want) in cases {
        assert_eq!(g15(ev(formula)), *want, "{formula}");
    }
}

#[test]
fn numbers_read_like_atof() {
    let cases: &[(&str, &str)] = &[
        ("1e-5", "1e-05"),
        (".5", "0.5"),
        ("5.", "5"),
        ("1.2.3", "1.2"),
        ("1e", "1"),
        ("1e+", "1"),
        ("..5", "0"),
        ("1e308*10", "inf"),
        ("-1e308*10", "-inf"),
        ("1/(1e308*10)", "0"),
        ("0^-1", "inf"),
        ("3%(1e308*10)", "3"),
        ("1e-400", "0"),
    ];
    for (formula, want) in cases {
        assert_eq!(g15(ev(formula)), *want, "{formula}");
    }
    // a literal beyond a double is an error naming it (LIGGGHTS's atof makes it inf)
    for big in ["1e400", "-1e400", "2*1e309"] {
        let e = fails(big);
        assert!(e.contains("1e400") || e.contains("1e309"), "{big}: {e}");
    }
    // liggghts prints -nan for these, and -0 for the signed zeros
    for nan in [
        "1e308*10-1e308*10",
        "(-2)^0.5",
        "sqrt(1e308*10-1e308*10)",
        "(1e308*10)%3",
    ] {
        let v = ev(nan);
        assert!(v.is_nan() && v.is_sign_negative(), "{nan}: {v}");
    }
    for zero in ["-0", "0*-1", "sqrt(-0)", "ceil(-0.5)", "round(-0.5)"] {
        let v = ev(zero);
        assert!(v == 0.0 && v.is_sign_negative(), "{zero}: {v}");
    }
    assert_eq!(ev("(1e308*10-1e308*10)==(1e308*10-1e308*10)"), 0.0);
    assert_eq!(ev("!(1e308*10-1e308*10)"), 0.0);
}

#[test]
fn math_functions() {
    let cases: &[(&str, &str)] = &[
        ("round(-2.5)", "-2"),
        ("round(2.5)", "3"),
        ("round(0.49999999999999994)", "0"),
        ("atan2(1,1)", "0.785398163397448"),
        ("atan2(0,0)", "0"),
        ("atan2(-0,-1)", "-3.14159265358979"),
        ("exp(1)", "2.71828182845905"),
        ("exp(710)", "inf"),
        ("abs(-0)", "0"),
        ("floor(-0.5)", "-1"),
        ("tan(PI/2)", "1.63312393531954e+16"),
        ("cos(PI)", "-1"),
        ("log(10)", "1"),
        ("ln(2)", "0.693147180559945"),
        ("PI", "3.14159265358979"),
        ("stagger(1000,100)", "100"),
        ("stagger(10.9,3.5)", "3"),
        ("logfreq(100,4,10)", "100"),
        ("stride(0,100,10)", "10"),
    ];
    for (formula, want) in cases {
        assert_eq!(g15(ev(formula)), *want, "{formula}");
    }
    assert_eq!(ev("sqrt(16)+abs(-2)+floor(2.7)+ceil(2.1)"), 11.0);
    assert_eq!(ev("log(1000)+ln(exp(2))"), 5.0);
}

#[test]
fn step_functions_during_a_run() {
    // liggghts: two atoms, timestep 0.25, thermo 1 and thermo_modify format float %.17g,
    // thermo_style custom step v_sw v_cw v_rp v_vd v_sg v_lf v_lg v_st with
    //   sw = swiggle(1,2,3)  cw = cwiggle(1,2,3)  rp = ramp(0,10)  vd = vdisplace(1,2)
    //   sg = stagger(10,3)  lf = logfreq(1,2,10)  lg = logfreq(2,3,5)  st = stride(5,20,4)
    // during "run 25"
    let table: &[(i64, [f64; 8])] = &[
        (0, [1.0, 1.0, 0.0, 1.0, 3.0, 1.0, 2.0, 5.0]),
        (
            1,
            [
                2.0,
                1.2679491924311226,
                0.40000000000000002,
                1.5,
                3.0,
                2.0,
                2.0,
                5.0,
            ],
        ),
        (
            2,
            [
                2.7320508075688772,
                1.9999999999999998,
                0.80000000000000004,
                2.0,
                3.0,
                10.0,
                4.0,
                5.0,
            ],
        ),
        (
            5,
            [
                2.0000000000000009,
                4.7320508075688767,
                2.0,
                3.5,
                10.0,
                10.0,
                6.0,
                9.0,
            ],
        ),
        (
            7,
            [
                5.5511151231257827e-16,
                4.7320508075688776,
                2.8000000000000003,
                4.5,
                10.0,
                10.0,
                10.0,
                9.0,
            ],
        ),
        (
            10,
            [
                -0.73205080756887808,
                2.0000000000000013,
                4.0,
                6.0,
                13.0,
                20.0,
                20.0,
                13.0,
            ],
        ),
        (
            13,
            [
                1.9999999999999987,
                1.2679491924311219,
                5.2000000000000002,
                7.5,
                20.0,
                20.0,
                20.0,
                17.0,
            ],
        ),
        (
            17,
            [
                2.0000000000000027,
                4.7320508075688759,
                6.8000000000000007,
                9.5,
                20.0,
                20.0,
                20.0,
                9e18,
            ],
        ),
        (
            20,
            [
                -0.73205080756887564,
                4.0000000000000027,
                8.0,
                11.0,
                23.0,
                100.0,
                30.0,
                9e18,
            ],
        ),
        (
            23,
            [
                -2.886579864025407e-15,
                1.2679491924311244,
                9.2000000000000011,
                12.5,
                30.0,
                100.0,
                30.0,
                9e18,
            ],
        ),
        (
            25,
            [
                1.9999999999999982,
                1.2679491924311217,
                10.0,
                13.5,
                30.0,
                100.0,
                30.0,
                9e18,
            ],
        ),
    ];
    let formulas = [
        "swiggle(1,2,3)",
        "cwiggle(1,2,3)",
        "ramp(0,10)",
        "vdisplace(1,2)",
        "stagger(10,3)",
        "logfreq(1,2,10)",
        "logfreq(2,3,5)",
        "stride(5,20,4)",
    ];
    for (step, want) in table {
        let mut w = world();
        w.step = *step;
        w.run = Some((0, 25));
        w.dt = 0.25;
        for (formula, want) in formulas.iter().zip(want) {
            assert_eq!(
                evaluate(formula, &mut w).unwrap(),
                *want,
                "{formula} at {step}"
            );
            let parsed = Expr::parse(formula).unwrap();
            assert_eq!(parsed.eval(&mut w, None).unwrap(), *want);
        }
    }
}

#[test]
fn references_and_functions() {
    assert_eq!(ev("v_a*c_x[2]+f_y"), 2.0 * 9.0 + 8.0);
    assert_eq!(ev("x[2]"), 0.4);
    assert_eq!(ev("count(all)"), 2.0);
    assert_eq!(ev("xcm(all,x)"), 0.25);
    assert_eq!(ev("sum(c_x)"), 21.0);
    assert_eq!(ev("atoms"), 2.0);
    // group and special arguments are passed raw, split at the first two commas
    let mut w = world();
    let _ = evaluate("bound(all,xmin, r,  s)", &mut w);
    assert_eq!(w.lookups, ["bound(all,xmin, r,  s)"]);
    assert_eq!(
        Expr::parse("count(all, a)").unwrap().root,
        Node::Group("count".into(), vec!["all".into(), " a".into()], 0)
    );
}

#[test]
fn random_stream_matches_liggghts() {
    // print "$(random(0,1,S)) $(random(0,1,0)) $(random(0,1,12345))": once the
    // generator exists its seed argument is ignored, even an invalid one
    let mut w = world();
    let draws: Vec<f64> = ["random(0,1,S)", "random(0,1,0)", "random(0,1,12345)"]
        .iter()
        .map(|f| evaluate(&f.replace('S', &S.to_string()), &mut w).unwrap())
        .collect();
    assert_eq!(
        draws,
        [
            0.86316907405853271484,
            0.6564229130744934082,
            0.88727664947509765625
        ]
    );
    // print "${b}" with b = random(0,1,S) after ten draws of another variable
    // (one generator for all equal-style formulas)
    let mut w = world();
    let f = format!("random(0,1,{S})");
    for _ in 0..10 {
        evaluate(&f, &mut w).unwrap();
    }
    assert_eq!(g15(evaluate(&f, &mut w).unwrap()), "0.273580014705658");
    // random(1,0,S) and normal(1,0,S) as first draws
    assert_eq!(g15(ev(&format!("random(1,0,{S})"))), "0.136830925941467");
    assert_eq!(ev(&format!("normal(1,0,{S})")), 1.0);
    // a non-prime seed is refused when the generator is made
    assert!(fails("random(0,1,12345)").contains("The random seed used was 12345"));
}
