// expected values are copied digit for digit from LIGGGHTS's %.17g output (PI included)
#![allow(clippy::excessive_precision, clippy::approx_constant)]

use super::*;

// the messages, to check that each error still reads as LIGGGHTS's
const SYNTAX: &str = "Invalid syntax in variable formula";
const BAD_MATH: &str = "Invalid math function in variable formula";
const BAD_NAME: &str = "Invalid math/group/special function in variable formula";
const NO_BOX: &str = "Variable evaluation before simulation box is defined";
const BOOLEAN: &str = "Invalid Boolean syntax in if command";
const TOO_DEEP: &str = "Variable formula is nested too deeply";

const S: i32 = 15485863;

/// A small world: variable `a` = 2, compute `x` (c_x = 7, c_x[i] = 7 + i), fix `y`
/// (8), two atoms at x = 0.1 and 0.4 (IDs 1 and 2), group `all`, one random generator
/// per style (prime seeds required, as in LIGGGHTS).
struct World {
    equal_rng: Option<RanMars>,
    atom_rng: Option<RanMars>,
    step: i64,
    run: Option<(i64, i64)>,
    dt: f64,
    has_box: bool,
    lookups: Vec<String>,
}

fn world() -> World {
    World {
        equal_rng: None,
        atom_rng: None,
        step: 0,
        run: None,
        dt: 1e-8,
        has_box: true,
        lookups: Vec::new(),
    }
}

const XS: [f64; 2] = [0.1, 0.4];

impl ExprContext for World {
    fn variable(
        &mut self,
        name: &str,
        index: Option<usize>,
        _: Option<usize>,
    ) -> Result<f64, VariableError> {
        self.lookups.push(format!("v_{name}"));
        match (name, index) {
            ("a", None) => Ok(2.0),
            ("a", Some(_)) => Err("Mismatched variable in variable formula".into()),
            ("later", None) => Err(VariableError::KnownWhenRun),
            _ => Err("Invalid variable name in variable formula".into()),
        }
    }
    fn thermo(&mut self, name: &str) -> Result<f64, VariableError> {
        self.lookups.push(name.to_string());
        match name {
            "step" => Ok(self.step as f64),
            "atoms" => Ok(2.0),
            "dt" => Ok(self.dt),
            _ => Err("Invalid thermo keyword in variable formula".into()),
        }
    }
    fn compute(
        &mut self,
        id: &str,
        i: Option<usize>,
        _: Option<usize>,
        _: Option<usize>,
    ) -> Result<f64, VariableError> {
        self.lookups.push(format!("c_{id}"));
        match id {
            "x" => Ok(7.0 + i.unwrap_or(0) as f64),
            _ => Err("Invalid compute ID in variable formula".into()),
        }
    }
    fn fix(
        &mut self,
        id: &str,
        _: Option<usize>,
        _: Option<usize>,
        _: Option<usize>,
    ) -> Result<f64, VariableError> {
        match id {
            "y" => Ok(8.0),
            _ => Err("Invalid fix ID in variable formula".into()),
        }
    }
    fn group_function(&mut self, name: &str, args: &[String]) -> Result<f64, VariableError> {
        self.lookups.push(format!("{name}({})", args.join(",")));
        if args.first().map(String::as_str) != Some("all") {
            return Err("Group ID in variable formula does not exist".into());
        }
        match (name, args.len()) {
            ("count", 1) => Ok(2.0),
            ("xcm", 2) if args[1] == "x" => Ok(0.25),
            _ => Err("Invalid group function in variable formula".into()),
        }
    }
    fn special_function(
        &mut self,
        name: &str,
        args: &[String],
        atom: Option<usize>,
    ) -> Result<f64, VariableError> {
        match (name, atom) {
            ("gmask", Some(_)) if args == ["all"] => Ok(1.0),
            ("sum", None) if args == ["c_x"] => Ok(21.0),
            _ => Err("Invalid special function in variable formula".into()),
        }
    }
    fn atom_value(&mut self, name: &str, atom: usize) -> Result<f64, VariableError> {
        match name {
            "x" => Ok(XS[atom]),
            "id" => Ok(atom as f64 + 1.0),
            _ => Ok(0.0),
        }
    }
    fn atom_value_by_id(&mut self, name: &str, id: usize) -> Result<f64, VariableError> {
        match (name, id) {
            ("x", 1 | 2) => Ok(XS[id - 1]),
            ("x", _) => Ok(0.0),
            _ => Err("Invalid atom vector in variable formula".into()),
        }
    }
    fn box_exists(&self) -> bool {
        self.has_box
    }
    fn timestep(&self) -> i64 {
        self.step
    }
    fn run_bounds(&self) -> Option<(i64, i64)> {
        self.run
    }
    fn dt(&self) -> f64 {
        self.dt
    }
    fn rng(&mut self, seed: i32, per_atom: bool) -> Result<&mut RanMars, VariableError> {
        let slot = if per_atom {
            &mut self.atom_rng
        } else {
            &mut self.equal_rng
        };
        if slot.is_none() {
            crate::util::random::check_seed(i64::from(seed))?;
            *slot = Some(RanMars::new(seed)?);
        }
        Ok(slot.as_mut().expect("just made"))
    }
}

fn ev(text: &str) -> f64 {
    evaluate(text, &mut world()).unwrap_or_else(|e| panic!("{text}: {e:?}"))
}

fn fails(text: &str) -> String {
    evaluate(text, &mut world()).unwrap_err().to_string()
}

fn fails_without_box(text: &str) -> String {
    let mut w = world();
    w.has_box = false;
    evaluate(text, &mut w).unwrap_err().to_string()
}

/// What LIGGGHTS prints for `${a}` (%.15g), to compare with its output.
fn g15(x: f64) -> String {
    crate::util::format::g_precision(x, 15)
}

// Every expected value below is what Debian's liggghts 3.8.0 printed for
//   variable a equal "FORMULA"
//   print "R=${a}"
// (or the ERROR line it stopped with), unless a comment says otherwise.

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

/// Per-atom values of an atom-style formula for the two atoms (fresh world each time,
/// as liggghts was run once per formula).
fn per_atom(formula: &str, w: &mut World) -> Result<Vec<f64>, String> {
    let e = Expr::parse_atom(formula, w).map_err(|e| e.to_string())?;
    e.eval_atoms(w, 2).map_err(|e| e.to_string())
}

fn per_atom_walk(formula: &str, w: &mut World) -> Result<Vec<f64>, String> {
    let e = Expr::parse_atom(formula, w).map_err(|e| e.to_string())?;
    (0..2)
        .map(|a| e.eval(w, Some(a)).map_err(|e| e.to_string()))
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
        assert_eq!(per_atom(formula, &mut w).unwrap_err(), *want, "{formula}");
    }
    // run-only functions are refused while reading, even where unused
    let mut w = world();
    assert_eq!(
        per_atom("x + 0*ramp(0,1)", &mut w).unwrap_err(),
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
