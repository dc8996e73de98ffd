use super::*;

fn hertz_coeffs(e: f64) -> PairCoeffs {
    let input = MaterialInput {
        ntypes: 1,
        youngs_modulus: Some(vec![1e7]),
        poissons_ratio: Some(vec![0.3]),
        coefficient_restitution: Some(vec![e]),
        coefficient_friction: Some(vec![0.5]),
        characteristic_velocity: Some(1.0),
        ..MaterialInput::default()
    };
    let req = [
        (Property::Yeff, "t"),
        (Property::Geff, "t"),
        (Property::BetaEff, "t"),
        (Property::CharVel, "t"),
        (Property::CoeffFrict, "t"),
    ];
    *Material::new(&input, &req).unwrap().pair(1, 1)
}

/// Head-on collision of two equal spheres integrated with velocity Verlet; returns the
/// ratio of separation to approach speed.
fn rebound<N: NormalModel>(normal: N, e: f64) -> f64 {
    let model = ContactModel::new(normal, History, NoCohesion, NoRolling);
    let coeffs = hertz_coeffs(e);
    let (r, rho) = (0.005, 2500.0);
    let m = 4.0 * PI / 3.0 * r * r * r * rho;
    let v0 = 1.0;
    let mut x = [-r - 1e-7, r + 1e-7];
    let mut v = [v0 / 2.0, -v0 / 2.0];
    let dt = 2e-8;
    let mut h = [0.0; 3];
    let force = |x: &[f64; 2], v: &[f64; 2], h: &mut [f64; 3]| {
        let p = PairInput {
            xi: [x[0], 0.0, 0.0],
            xj: [x[1], 0.0, 0.0],
            radi: r,
            radj: r,
            mi: m,
            mj: m,
            frozen_i: false,
            frozen_j: false,
            vi: [v[0], 0.0, 0.0],
            vj: [v[1], 0.0, 0.0],
            omegai: [0.0; 3],
            omegaj: [0.0; 3],
            dt,
            update_history: true,
            coeffs: &coeffs,
        };
        model.pair_force(&p, h)
    };
    let mut f = force(&x, &v, &mut h).fi[0];
    let mut touched = false;
    for _ in 0..10_000_000 {
        v[0] += 0.5 * dt * f / m;
        v[1] -= 0.5 * dt * f / m;
        x[0] += dt * v[0];
        x[1] += dt * v[1];
        let out = force(&x, &v, &mut h);
        f = out.fi[0];
        v[0] += 0.5 * dt * f / m;
        v[1] -= 0.5 * dt * f / m;
        touched |= out.touching;
        if touched && !out.touching {
            break;
        }
    }
    (v[1] - v[0]) / v0
}

#[test]
fn restitution_of_a_head_on_collision_equals_e() {
    for e in [0.3, 0.5, 0.9] {
        let hz = rebound(Hertz::default(), e);
        assert!((hz - e).abs() < 1e-3, "hertz e={e}: {hz}");
        let hk = rebound(Hooke::default(), e);
        assert!((hk - e).abs() < 1e-3, "hooke e={e}: {hk}");
    }
}

fn oblique(coeffs: &PairCoeffs) -> PairInput<'_> {
    PairInput {
        xi: [0.0, 0.0, 0.0],
        xj: [0.0195, 0.001, -0.0005],
        radi: 0.01,
        radj: 0.01,
        mi: 0.01,
        mj: 0.012,
        frozen_i: false,
        frozen_j: false,
        vi: [0.2, 0.1, 0.0],
        vj: [-0.1, 0.0, 0.3],
        omegai: [1.0, 2.0, 3.0],
        omegaj: [-2.0, 0.5, 1.0],
        dt: 1e-5,
        update_history: true,
        coeffs,
    }
}

#[test]
fn dyn_fallback_equals_the_monomorphised_kernel() {
    let coeffs = hertz_coeffs(0.6);
    let sel = ModelSelection::parse(&["model", "hertz", "tangential", "history"]).unwrap();
    let any = AnyContactModel::new(&sel).unwrap();
    assert!(matches!(any, AnyContactModel::HertzHistory(_)));
    let (n, t, c, r) = sel.sub_models().unwrap();
    let dynm = ContactModel::new(n, t, c, r);
    let p = oblique(&coeffs);
    let (mut h1, mut h2) = ([0.0; 3], [0.0; 6]);
    for _ in 0..5 {
        let a = any.pair_force(&p, &mut h1);
        let b = dynm.pair_force(&p, &mut h2);
        assert_eq!(a, b);
        assert_eq!(h1[..], h2[..3]);
    }
    assert_eq!(any.history_len(), 3);
}

#[test]
fn newton_third_law_and_frozen_meff() {
    let coeffs = hertz_coeffs(0.6);
    let model = ContactModel::new(Hertz::default(), History, Sjkr::default(), NoRolling);
    let mut p = oblique(&coeffs);
    let out = model.pair_force(&p, &mut [0.0; 3]);
    for d in 0..3 {
        assert_eq!(out.fj[d], -out.fi[d]);
    }
    // frozen j behaves as infinite mass: meff = mi, so more damping than mi mj/(mi+mj)
    p.frozen_j = true;
    let frozen = model.pair_force(&p, &mut [0.0; 3]);
    assert!(frozen.normal_force != out.normal_force);
    p.frozen_j = false;
    p.mj = 1e30;
    let heavy = model.pair_force(&p, &mut [0.0; 3]);
    assert!((heavy.normal_force - frozen.normal_force).abs() < 1e-12 * frozen.normal_force.abs());
    // apart: nothing, and the history is kept
    let mut h = [1.0, 2.0, 3.0];
    p.xj = [0.03, 0.0, 0.0];
    let apart = model.pair_force(&p, &mut h);
    assert!(!apart.touching && apart.fi == [0.0; 3]);
    assert_eq!(h, [1.0, 2.0, 3.0]);
    model.surfaces_close(&mut h);
    assert_eq!(h, [0.0; 3]);
}

#[test]
fn wall_matches_a_pair_with_an_infinitely_large_partner() {
    // a sphere on the plane z = 0 vs the same sphere on a huge frozen sphere
    let coeffs = hertz_coeffs(0.6);
    let model = ContactModel::new(Hertz::default(), History, NoCohesion, NoRolling);
    let x = [0.1, 0.2, 0.0099];
    let (gap, to_wall) = plane_contact(2, 0.0, &x, 0.01);
    assert!((gap + 1e-4).abs() < 1e-15);
    let w = WallInput {
        x,
        gap,
        to_wall,
        radius: 0.01,
        mass: 0.01,
        v: [0.1, 0.0, -0.2],
        omega: [0.0, 0.0, 0.0],
        v_wall: [0.0; 3],
        dt: 1e-5,
        update_history: true,
        coeffs: &coeffs,
    };
    let mut h = [0.0; 3];
    let out = model.wall_force(&w, &mut h);
    assert!(out.touching);
    let big = 1e6;
    let p = PairInput {
        xi: x,
        xj: [0.1, 0.2, -big + 1e-4 - 1e-4],
        radi: 0.01,
        radj: big,
        mi: 0.01,
        mj: 1.0,
        frozen_i: false,
        frozen_j: true,
        vi: w.v,
        vj: [0.0; 3],
        omegai: [0.0; 3],
        omegaj: [0.0; 3],
        dt: 1e-5,
        update_history: true,
        coeffs: &coeffs,
    };
    let mut hp = [0.0; 3];
    let po = model.pair_force(&p, &mut hp);
    // R* -> R for an infinite partner: forces agree to the size ratio
    for d in 0..3 {
        assert!(
            (po.fi[d] - out.f[d]).abs() < 1e-6 * out.f[2].abs(),
            "{:?} {:?}",
            po.fi,
            out.f
        );
    }
    assert_eq!(out.contact_point, [0.1, 0.2, 0.0]);
    // leaving the wall resets the history
    let mut w2 = w;
    w2.x = [0.1, 0.2, 0.02];
    let (g2, t2) = plane_contact(2, 0.0, &w2.x, 0.01);
    w2.gap = g2;
    w2.to_wall = t2;
    assert!(!model.wall_force(&w2, &mut h).touching);
    assert_eq!(h, [0.0; 3]);
}

#[test]
fn local_output_splits_force_and_torque() {
    let coeffs = hertz_coeffs(0.6);
    let model = ContactModel::new(Hertz::default(), History, NoCohesion, NoRolling);
    let p = oblique(&coeffs);
    let mut h = [0.0; 3];
    model.pair_force(&p, &mut h);
    let out = model.pair_force(&p, &mut h);
    let l = out.local(&p);
    for d in 0..3 {
        assert!((l.force_normal[d] + l.force_tangential[d] - out.fi[d]).abs() < 1e-15);
        assert!((l.force_normal[d] - out.normal_force * out.en[d]).abs() < 1e-9);
    }
    assert!((l.delta - out.deltan).abs() < 1e-18);
    assert!(l.contact_area > 0.0);
    assert!((l.contact_point[0] - 0.0195 / 2.0).abs() < 1e-15);
}

#[test]
fn selection_parsing_and_messages() {
    let sel = ModelSelection::parse(&[
        "model",
        "hertz",
        "tangential",
        "history",
        "cohesion",
        "sjkr",
        "rolling_friction",
        "epsd",
        "tangential_reduce",
        "on",
        "torsionTorque",
        "on",
        "limitForce",
        "on",
    ])
    .unwrap();
    assert!(sel.options.tangential_reduce && sel.options.torsion_torque && sel.options.limit_force);
    assert!(sel.options.tangential_damping);
    let any = AnyContactModel::new(&sel).unwrap();
    assert!(matches!(any, AnyContactModel::HertzHistorySjkrEpsd(_)));
    assert_eq!(any.history_len(), 6);
    assert_eq!(
        any.properties(),
        vec![
            (Property::Yeff, "model hertz"),
            (Property::Geff, "model hertz"),
            (Property::BetaEff, "model hertz"),
            (Property::CohEnergyDens, "cohesion_model sjkr"),
            (Property::CoeffFrict, "tangential_model history"),
            (Property::CoeffRollFrict, "rolling_model epsd"),
            (Property::CoeffRollVisc, "rolling_model epsd"),
        ]
    );
    let sel =
        ModelSelection::parse(&["model", "hertz", "tangential", "history_total_cap"]).unwrap();
    assert!(matches!(
        AnyContactModel::new(&sel).unwrap(),
        AnyContactModel::HertzTotalCap(_)
    ));
    // a combination without its own variant still works through the fallback
    let sel = ModelSelection::parse(&[
        "model",
        "hooke/stiffness",
        "tangential",
        "no_history",
        "rolling_friction",
        "epsd3",
    ])
    .unwrap();
    let any = AnyContactModel::new(&sel).unwrap();
    assert!(!any.is_monomorphised());
    assert_eq!(any.history_len(), 3);
    // LIGGGHTS's messages
    assert_eq!(
        ModelSelection::parse(&["model", "hertzz"])
            .unwrap_err()
            .to_string(),
        "Invalid model specified (check for typos and enable at least one model)"
    );
    assert_eq!(
        ModelSelection::parse(&["tangential", "off"])
            .unwrap_err()
            .to_string(),
        "Invalid model specified (check for typos and enable at least one model)"
    );
    assert_eq!(
        ModelSelection::parse(&["model", "hertz", "tangential_reduce", "on"])
            .unwrap_err()
            .to_string(),
        "Unknown argument or wrong keyword order: 'tangential_reduce'"
    );
    assert_eq!(
        ModelSelection::parse(&["model", "hertz", "limitForce", "yes"])
            .unwrap_err()
            .to_string(),
        "while parsing 'limitForce' argument: unknown option or wrong keyword order: 'yes'"
    );
    // keywords after the settings are not model keywords
    assert!(ModelSelection::parse(&[
        "model",
        "hertz",
        "limitForce",
        "on",
        "tangential",
        "history"
    ])
    .is_err());
    assert!(AnyContactModel::new(&ModelSelection::parse(&["model", "luding"]).unwrap()).is_err());
    // easo/capillary/viscous takes tangential_reduce (as LIGGGHTS does); no composed model
    // holds it: the pair loop runs it around the dry model (granular::wet)
    let wet = ModelSelection::parse(&[
        "model",
        "hertz",
        "tangential",
        "history",
        "cohesion",
        "easo/capillary/viscous",
        "tangential_reduce",
        "on",
    ])
    .unwrap();
    assert_eq!(
        AnyContactModel::new(&wet).unwrap_err().to_string(),
        "cohesion easo/capillary/viscous is not supported by regolith"
    );
    assert!(ModelSelection::parse(&["model", "hertz", "heating_normal_hertz", "off"]).is_ok());
    assert!(ModelSelection::parse(&["model", "hertz", "heating_normal_hertz", "on"]).is_err());
}

mod props {
    use super::*;
    use proptest::prelude::*;

    const NORMALS: [&str; 4] = ["hertz", "hooke", "hertz/stiffness", "hooke/stiffness"];
    const TANGENTIALS: [&str; 4] = ["off", "no_history", "history", "history_total_cap"];
    const COHESIONS: [&str; 3] = ["off", "sjkr", "sjkr2"];
    const ROLLINGS: [&str; 5] = ["off", "cdt", "epsd", "epsd2", "epsd3"];

    fn coeffs() -> PairCoeffs {
        PairCoeffs {
            yeff: 5e7,
            geff: 2e7,
            betaeff: -0.4,
            coeff_rest_log: -1.2,
            char_vel: 1.0,
            coeff_frict: 0.4,
            cohesion_energy_density: 1e5,
            coeff_roll_frict: 0.05,
            coeff_roll_visc: 0.2,
            rolling_stiffness: 2.0,
            kn: 1e4,
            kt: 5e3,
            gamman: 40.0,
            gammat: 20.0,
            ..PairCoeffs::default()
        }
    }

    proptest! {
        #[test]
        fn third_law_and_coulomb_bound(
            n in 0usize..4, t in 0usize..4, c in 0usize..3, r in 0usize..5,
            dir in prop::array::uniform3(-1.0f64..1.0),
            overlap in 1e-6f64..1e-3,
            vi in prop::array::uniform3(-1.0f64..1.0),
            wi in prop::array::uniform3(-30.0f64..30.0),
            wj in prop::array::uniform3(-30.0f64..30.0),
            steps in 1usize..20,
        ) {
            let norm = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
            prop_assume!(norm > 0.1);
            let sel = ModelSelection::parse(&[
                "model", NORMALS[n], "tangential", TANGENTIALS[t],
                "cohesion", COHESIONS[c], "rolling_friction", ROLLINGS[r],
            ]).unwrap();
            let model = AnyContactModel::new(&sel).unwrap();
            let co = coeffs();
            let dist = 0.021 - overlap;
            let p = PairInput {
                xi: [dist * dir[0] / norm, dist * dir[1] / norm, dist * dir[2] / norm],
                xj: [0.0; 3],
                radi: 0.01, radj: 0.011, mi: 0.01, mj: 0.013,
                frozen_i: false, frozen_j: false,
                vi, vj: [0.0; 3], omegai: wi, omegaj: wj,
                dt: 1e-5, update_history: true, coeffs: &co,
            };
            let mut h = vec![0.0; model.history_len()];
            for _ in 0..steps {
                let out = model.pair_force(&p, &mut h);
                prop_assert!(out.touching);
                for d in 0..3 {
                    prop_assert_eq!(out.fj[d], -out.fi[d]);
                }
                let ft = (out.ft[0] * out.ft[0] + out.ft[1] * out.ft[1] + out.ft[2] * out.ft[2]).sqrt();
                let limit = 0.4 * out.normal_force.abs();
                if TANGENTIALS[t] == "history_total_cap" || TANGENTIALS[t] == "no_history" {
                    prop_assert!(ft <= limit * (1.0 + 1e-12) + 1e-300, "{} > {}", ft, limit);
                }
                // the tangential force lies in the tangent plane
                let dot = out.ft[0] * out.en[0] + out.ft[1] * out.en[1] + out.ft[2] * out.en[2];
                prop_assert!(dot.abs() <= 1e-9 * (ft + 1e-12));
            }
        }
    }
}

/// Each lane of [`ContactModel::wall_force_lanes`] is [`ContactModel::wall_force`] of its
/// own inputs, force, torque and updated history bit for bit, over several steps.
fn wall_lanes_equal_one_at_a_time<N, T, C, R>(model: ContactModel<N, T, C, R>)
where
    N: NormalModel,
    T: TangentialModel,
    C: CohesionModel,
    R: RollingModel,
{
    let input = MaterialInput {
        ntypes: 1,
        youngs_modulus: Some(vec![5e6]),
        poissons_ratio: Some(vec![0.25]),
        coefficient_restitution: Some(vec![0.5]),
        coefficient_friction: Some(vec![0.6]),
        coefficient_rolling_friction: Some(vec![0.3]),
        coefficient_rolling_viscous_damping: Some(vec![1.5]),
        cohesion_energy_density: Some(vec![2e3]),
        ..MaterialInput::default()
    };
    let material = Material::new(&input, &model.properties()).unwrap();
    let coeffs = *material.pair(1, 1);
    let lanes_coeffs = CoeffLanes([&coeffs; LANES]);
    let width = model.history_len();
    let mut rng = crate::util::random::RanPark::new(8191).unwrap();
    let mut u = |lo: f64, hi: f64| lo + (hi - lo) * rng.uniform();
    let mut one = vec![0.0; LANES * width];
    let mut four = vec![F64x4::default(); width];
    for step in 0..6 {
        let inputs: [WallInput; LANES] = std::array::from_fn(|_| {
            let radius = u(0.8e-3, 1.5e-3);
            let x = [u(-1.0, 1.0), u(-1.0, 1.0), radius - u(1e-7, 2e-5)];
            let (gap, to_wall) = plane_contact(2, 0.0, &x, radius);
            WallInput {
                x,
                gap,
                to_wall,
                radius,
                mass: u(1e-5, 3e-5),
                v: [u(-0.3, 0.3), u(-0.3, 0.3), u(-0.3, 0.1)],
                omega: [u(-50.0, 50.0), u(-50.0, 50.0), u(-50.0, 50.0)],
                v_wall: [u(-0.1, 0.1), 0.0, 0.0],
                dt: 1e-6,
                update_history: step > 0,
                coeffs: &coeffs,
            }
        });
        let lanes = WallLanes {
            gap: F64x4(inputs.map(|w| w.gap)),
            to_wall: std::array::from_fn(|d| F64x4(inputs.map(|w| w.to_wall[d]))),
            radius: F64x4(inputs.map(|w| w.radius)),
            mass: F64x4(inputs.map(|w| w.mass)),
            v: std::array::from_fn(|d| F64x4(inputs.map(|w| w.v[d]))),
            omega: std::array::from_fn(|d| F64x4(inputs.map(|w| w.omega[d]))),
            v_wall: std::array::from_fn(|d| F64x4(inputs.map(|w| w.v_wall[d]))),
            dt: 1e-6,
            update_history: step > 0,
        };
        let (f, t) = model.wall_force_lanes(&lanes, &lanes_coeffs, &mut four);
        for (k, w) in inputs.iter().enumerate() {
            let h = &mut one[k * width..(k + 1) * width];
            let out = model.wall_force(w, h);
            assert!(out.touching);
            for d in 0..3 {
                assert_eq!(
                    out.f[d].to_bits(),
                    f[d].0[k].to_bits(),
                    "force {d} lane {k}"
                );
                assert_eq!(
                    out.t[d].to_bits(),
                    t[d].0[k].to_bits(),
                    "torque {d} lane {k}"
                );
            }
            for (s, slot) in four.iter().enumerate() {
                assert_eq!(h[s].to_bits(), slot.0[k].to_bits(), "history {s} lane {k}");
            }
            assert!(out.f[2] != 0.0);
        }
    }
    // the tangential history was built up (the test compares more than zeros)
    if width > 0 {
        assert!(one.iter().any(|h| *h != 0.0));
    }
}

#[test]
fn a_wall_four_particles_at_a_time_equals_one_at_a_time() {
    let hertz = Hertz::default();
    wall_lanes_equal_one_at_a_time(ContactModel::new(hertz, History, NoCohesion, NoRolling));
    wall_lanes_equal_one_at_a_time(ContactModel::new(
        hertz,
        History,
        NoCohesion,
        Cdt {
            torsion_torque: false,
        },
    ));
    wall_lanes_equal_one_at_a_time(ContactModel::new(
        hertz,
        History,
        Sjkr::default(),
        Epsd::default(),
    ));
}
