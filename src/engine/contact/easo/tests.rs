use super::*;
use crate::engine::contact::surface::{DefaultSurface, SurfaceModel};
use crate::engine::contact::Contact;

fn easo() -> Easo {
    Easo {
        surface_tension: 0.072,
        fluid_viscosity: 0.001,
        min_separation: 0.01,
        max_separation: 1.1,
        tangential_reduce: false,
    }
}

/// Two equal spheres, R = 1 mm, content 0.01, contact angle 0.
fn equal_pair() -> WetPair {
    WetPair {
        is_wall: false,
        radi: 1e-3,
        radj: 1e-3,
        radsum: 2e-3,
        liquid_i: 0.01,
        liquid_j: 0.01,
        contact_angle: 0.0,
        area_ratio: 1.0,
    }
}

fn close_to(got: f64, want: f64, rel: f64) -> bool {
    (got - want).abs() <= rel * want.abs()
}

// Hand computation (exact 4/3 and 8/15; LIGGGHTS's truncated constants differ by < 1e-9):
// film 4/3 1000 pi R^3 c = 4.18879e-8, bridge V = film (1 - sqrt(3)/2) = 5.611914763e-9,
// V* = V 1e-3 / R^3 = 5.611914763e-3, B = -0.0082 ln V* + 0.48, C = 0.0018 ln V* + 0.078,
// F_cap = -pi sigma sqrt(R R) (e^B + C) = -3.9695082586e-4 N; Stokes -6 pi mu R/2;
// at vn = -0.1 m/s: F_visc = Stokes vn / 0.01 = 9.424777961e-5 N; the tangential factor
// (8/15 ln 100 + 0.9588) Stokes = -3.218458723e-5 kg/s.
#[test]
fn touching_bridge_matches_hand_computed_capillary_and_lubrication() {
    let w = equal_pair();
    let bond = w.bond();
    assert!(close_to(bond.volume, 5.611914763179555e-09, 1e-9));
    let m = Motion {
        en: [1.0, 0.0, 0.0],
        vn: -0.1,
        vtr: [0.0, 0.2, 0.0],
        cri: 0.9e-3,
        crj: 0.9e-3,
    };
    let mut flag = 0.0;
    let f = easo().intersect(&w, &m, &mut flag).unwrap();
    assert_eq!(flag, 1.0);
    let normal = -3.9695082586297265e-4 + 9.424777960769378e-05;
    assert!(close_to(f.normal, normal, 1e-8), "{}", f.normal);
    assert!(close_to(f.f[0], normal, 1e-8));
    let ft = -3.218458722851517e-05 * 0.2;
    assert!(close_to(f.f[1], ft, 1e-7), "{}", f.f[1]);
    assert_eq!(f.f[2], 0.0);
    // torque: -cr (en x Ft) on both particles
    assert!(close_to(f.ti[2], -0.9e-3 * ft, 1e-7));
    assert_eq!(f.ti, f.tj);
}

// At a gap d = 10 um: A = -1.1 V*^-0.53, F_cap = -pi sigma R (e^(A d/R + B) + C)
// = -3.3682682472e-4 N; lubrication at d / R* = 0.02 (above the minimum 0.01):
// vn = 0.05 m/s gives Stokes vn / 0.02 = -2.35619449e-5 N and the tangential factor
// (8/15 ln 50 + 0.9588) Stokes = -2.8700449484e-5 kg/s. Rupture distance
// (1 + theta/2) cbrt(V) / 10 = 1.7770665e-4 m.
#[test]
fn bridge_across_a_gap_matches_hand_computed_force() {
    let w = equal_pair();
    assert!(close_to(
        w.rupture_distance(&w.bond()),
        0.00017770665358531217,
        1e-9
    ));
    let g = Gap {
        delta: [2.01e-3, 0.0, 0.0],
        rsq: 2.01e-3 * 2.01e-3,
        vi: [0.05, 0.0, 0.0],
        vj: [0.0, 0.0, 0.0],
        omegai: [0.0, 0.0, 100.0],
        omegaj: [0.0, 0.0, 100.0],
        dt: 1e-5,
    };
    let mut flag = 1.0;
    let Close::Holds(Some(f)) = easo().close(&w, &g, &mut flag) else {
        panic!("the bridge should hold");
    };
    assert_eq!(flag, 1.0);
    let normal = -0.00033682682471531707 - 2.3561944901923446e-05;
    assert!(close_to(f.f[0], normal, 1e-8), "{}", f.f[0]);
    // surface velocity of the spinning pair: -(dx wr_z) with wr_z = 2 R omega / r
    let vtr_y = -(2.01e-3 * (2e-3 * 100.0 / 2.01e-3));
    assert!(close_to(f.f[1], -2.8700449484029406e-05 * vtr_y, 1e-7));
    // no bridge was ever formed: no force
    let mut flag = 0.0;
    assert_eq!(easo().close(&w, &g, &mut flag), Close::Dry);
}

// Ri = 1 mm (content 0.01), Rj = 2 mm (0.02), theta 0.2, dt = 10 us: the bridge holds
// V = 2.44981257e-8 and breaks beyond 0.1 (Ri + Rj) = 0.3 mm although its own rupture
// distance is 0.319 mm; its liquid splits 1 : 8 (the volume ratio), so i's content
// changes by -62.338707 /s and j's by +7.7923384 /s, and the liquid is conserved.
#[test]
fn breaking_bridge_splits_its_liquid_by_volume() {
    let w = WetPair {
        is_wall: false,
        radi: 1e-3,
        radj: 2e-3,
        radsum: 3e-3,
        liquid_i: 0.01,
        liquid_j: 0.02,
        contact_angle: 0.2,
        area_ratio: 1.0,
    };
    assert!(close_to(w.bond().volume, 2.4498125735491138e-08, 1e-9));
    assert!(close_to(
        w.rupture_distance(&w.bond()),
        0.0003194750682531907,
        1e-9
    ));
    let at = |gap: f64| Gap {
        delta: [0.0, 3e-3 + gap, 0.0],
        rsq: (3e-3 + gap) * (3e-3 + gap),
        dt: 1e-5,
        ..Gap::default()
    };
    let mut flag = 1.0;
    assert!(matches!(
        easo().close(&w, &at(0.29e-3), &mut flag),
        Close::Holds(Some(_))
    ));
    let Close::Breaks { flux_i, flux_j } = easo().close(&w, &at(0.31e-3), &mut flag) else {
        panic!("the bridge should break");
    };
    assert_eq!(flag, 0.0);
    assert!(close_to(flux_i, -62.33870696186524, 1e-8), "{flux_i}");
    assert!(close_to(flux_j, 7.792338370233155, 1e-8), "{flux_j}");
    let moved = flux_i * 1e-9 + flux_j * 8e-9;
    assert!(moved.abs() < 1e-12 * flux_j * 8e-9, "{moved}");
    // once broken it stays dry
    assert_eq!(easo().close(&w, &at(0.1e-3), &mut flag), Close::Dry);
}

#[test]
fn dry_particles_and_walls_move_no_liquid() {
    let mut w = equal_pair();
    w.liquid_i = 0.0;
    w.liquid_j = 0.0;
    let mut flag = 0.0;
    let m = Motion {
        en: [0.0, 0.0, 1.0],
        vn: -1.0,
        ..Motion::default()
    };
    // too little liquid: the bridge is flagged but exerts nothing
    assert_eq!(easo().intersect(&w, &m, &mut flag), None);
    assert_eq!(flag, 1.0);
    let wall = WetPair {
        is_wall: true,
        radj: 1e-3,
        radsum: 1e-3,
        liquid_i: 0.01,
        ..equal_pair()
    };
    // a wall bridge holds half the film: film / 2
    assert!(close_to(
        wall.bond().volume,
        4.18879020478639e-8 / 2.0,
        1e-9
    ));
    let g = Gap {
        delta: [0.0, 0.0, 1.3e-3],
        rsq: 1.3e-3 * 1.3e-3,
        dt: 1e-5,
        ..Gap::default()
    };
    let mut flag = 1.0;
    assert_eq!(
        easo().close(&wall, &g, &mut flag),
        Close::Breaks {
            flux_i: 0.0,
            flux_j: 0.0
        }
    );
}

/// One dumped atom of the golden run: id, x, v, omega, f, torque, content, flux.
struct Row {
    x: Vec3,
    v: Vec3,
    omega: Vec3,
    f: Vec3,
    t: Vec3,
    liquid: f64,
    flux: f64,
}

fn rows(section: &str, step: u64) -> Vec<Row> {
    let text = include_str!("golden.txt");
    let body = text.split(&format!("{section}\n")).nth(1).unwrap();
    let mut out = Vec::new();
    for line in body.lines() {
        if line.starts_with(char::is_alphabetic) {
            break;
        }
        let v: Vec<f64> = line
            .split_whitespace()
            .map(|s| s.parse().unwrap())
            .collect();
        if v.len() < 17 || v[0] as u64 != step {
            continue;
        }
        let a = |k: usize| [v[k], v[k + 1], v[k + 2]];
        out.push(Row {
            x: a(2),
            v: a(5),
            omega: a(8),
            f: a(11),
            t: a(14),
            liquid: v.get(17).copied().unwrap_or(0.0),
            flux: v.get(18).copied().unwrap_or(0.0),
        });
    }
    assert_eq!(out.len(), 3, "step {step}");
    out
}

/// The golden deck's coefficients: sigma 0.072 N/m, mu 0.05 Pa s, ratios 0.01 and 1.1,
/// contact angles 0.3 and 0.5 degrees (types 1 and 2; the wall is type 2), content 0.4.
fn golden_easo() -> Easo {
    Easo {
        surface_tension: 0.072,
        fluid_viscosity: 0.05,
        min_separation: 0.01,
        max_separation: 1.1,
        tangential_reduce: false,
    }
}

const RAD: [f64; 3] = [0.01, 0.012, 0.01];
const DT: f64 = 2e-4;

fn golden_pair(liquid_i: f64, liquid_j: f64) -> WetPair {
    WetPair {
        is_wall: false,
        radi: RAD[0],
        radj: RAD[1],
        radsum: RAD[0] + RAD[1],
        liquid_i,
        liquid_j,
        contact_angle: effective_contact_angle(0.3, 0.5),
        area_ratio: 1.0,
    }
}

fn golden_wall() -> WetPair {
    WetPair {
        is_wall: true,
        radi: RAD[2],
        radj: RAD[2],
        radsum: RAD[2],
        liquid_i: 0.4,
        liquid_j: 0.0,
        contact_angle: effective_contact_angle(0.3, 0.5),
        area_ratio: 1.0,
    }
}

fn pair_gap(a: &Row, b: &Row) -> Gap {
    let delta = [a.x[0] - b.x[0], a.x[1] - b.x[1], a.x[2] - b.x[2]];
    Gap {
        delta,
        rsq: delta[0] * delta[0] + delta[1] * delta[1] + delta[2] * delta[2],
        vi: a.v,
        vj: b.v,
        omegai: a.omega,
        omegaj: b.omega,
        dt: DT,
    }
}

/// The zplane -0.05 wall as LIGGGHTS resolves it: r = R + gap, delta from the plane.
fn wall_gap(a: &Row) -> Gap {
    let gap = a.x[2] - (-0.05) - RAD[2];
    let r = RAD[2] - -gap;
    Gap {
        delta: [0.0, 0.0, a.x[2] - (-0.05)],
        rsq: r * r,
        vi: a.v,
        omegai: a.omega,
        dt: DT,
        ..Gap::default()
    }
}

// Golden values from Debian's LIGGGHTS 3.8.0: `model hertz tangential history cohesion
// easo/capillary/viscous` (pair_style gran and a primitive `zplane -0.05` wall/gran of
// type 2), properties as in `golden_easo`; atom 1 (R 10 mm) pulled away from atom 2 (R 12
// mm, not integrated) and atom 3 (R 10 mm) lifted off the wall, both by `fix move linear`,
// dt 2e-4, dumped with `%.17g` (`id x y z vx vy vz omegax omegay omegaz fx fy fz tqx tqy
// tqz f_surfaceLiquidContent f_liquidFlux`; section DRY: the same deck without cohesion).
// Apart, the bridge force is all there is, so it must agree bit for bit.
#[test]
fn golden_bridges_across_gaps_are_bit_identical_to_liggghts() {
    let e = golden_easo();
    for step in [14, 15, 20, 24, 35] {
        let r = rows("WET", step);
        let mut flag = 1.0;
        let Close::Holds(Some(f)) =
            e.close(&golden_pair(0.4, 0.4), &pair_gap(&r[0], &r[1]), &mut flag)
        else {
            panic!("step {step}: the pair bridge should hold");
        };
        assert_eq!(f.f, r[0].f, "step {step}");
        assert_eq!(f.ti, r[0].t, "step {step}");
        assert_eq!([-f.f[0], -f.f[1], -f.f[2]], r[1].f, "step {step}");
        assert_eq!(f.tj, r[1].t, "step {step}");
    }
    for step in [5, 10, 15, 20, 24] {
        let r = rows("WET", step);
        let mut flag = 1.0;
        let Close::Holds(Some(f)) = e.close(&golden_wall(), &wall_gap(&r[2]), &mut flag) else {
            panic!("step {step}: the wall bridge should hold");
        };
        assert_eq!(f.f, r[2].f, "step {step}");
        assert_eq!(f.ti, r[2].t, "step {step}");
    }
}

#[test]
fn golden_ruptures_and_liquid_transfer_are_bit_identical_to_liggghts() {
    let e = golden_easo();
    // the wall bridge breaks at step 25 without moving liquid
    let r = rows("WET", 25);
    let mut flag = 1.0;
    assert!(matches!(
        e.close(&golden_wall(), &wall_gap(&r[2]), &mut flag),
        Close::Breaks { .. }
    ));
    assert_eq!(r[2].f, [0.0; 3]);
    // the pair bridge breaks at step 36; the fluxes are integrated in the same step
    let r = rows("WET", 36);
    let mut flag = 1.0;
    let Close::Breaks { flux_i, flux_j } =
        e.close(&golden_pair(0.4, 0.4), &pair_gap(&r[0], &r[1]), &mut flag)
    else {
        panic!("the pair bridge should break");
    };
    assert_eq!(flux_i, r[0].flux);
    assert_eq!(flux_j, r[1].flux);
    assert_eq!(0.4 + flux_i * DT, r[0].liquid);
    assert_eq!(0.4 + flux_j * DT, r[1].liquid);
    // afterwards: dry, content kept
    let r = rows("WET", 37);
    assert_eq!(r[0].f, [0.0; 3]);
    assert_eq!(r[0].flux, 0.0);
    assert_eq!(0.4 + flux_i * DT, r[0].liquid);
}

// The same run against a mesh wall (two triangles in the plane z = -0.05; atom 3 is over
// triangle 0). LIGGGHTS 3.8.0's `surfacesClose` takes the wall's velocity from
// `atom->v[j]`, and j is the triangle's index at a mesh: the bridge across a gap to
// triangle 0 moves with LIGGGHTS's local atom 0, here atom 3 itself, so its translation
// drops out (at a primitive wall j is minus the wall type, an out-of-range read that gave
// zero). Touching, the mesh gives the primitive wall's force.
#[test]
fn golden_mesh_bridges_take_the_velocity_of_the_atom_indexed_by_the_triangle() {
    let e = golden_easo();
    for step in [8, 15, 20, 24] {
        let r = rows("MESH", step);
        let mut g = wall_gap(&r[2]);
        // LIGGGHTS's atom 0 after its spatial sort at setup: atom 3 (the lowest)
        g.vj = r[2].v;
        let mut flag = 1.0;
        let Close::Holds(Some(f)) = e.close(&golden_wall(), &g, &mut flag) else {
            panic!("step {step}: the wall bridge should hold");
        };
        assert_eq!(f.f, r[2].f, "step {step}");
        assert_eq!(f.ti, r[2].t, "step {step}");
    }
    assert_eq!(rows("MESH", 2)[2].f, rows("WET", 2)[2].f);
    assert_eq!(rows("MESH", 25)[2].f, [0.0; 3]);
}

/// The touching bridge of the golden run: LIGGGHTS's wet force less its dry force (the
/// same deck without cohesion) is the bridge force, up to the rounding of the sums.
#[test]
fn golden_touching_bridges_match_liggghts() {
    let e = golden_easo();
    for step in [2, 3, 10] {
        let wet = rows("WET", step);
        let dry = rows("DRY", step);
        // pair 1-2
        let (a, b) = (&wet[0], &wet[1]);
        let g = pair_gap(a, b);
        let r = g.rsq.sqrt();
        let mut c = Contact {
            radi: RAD[0],
            radj: RAD[1],
            radsum: RAD[0] + RAD[1],
            r,
            rinv: 1.0 / r,
            delta: g.delta,
            en: [
                g.delta[0] * (1.0 / r),
                g.delta[1] * (1.0 / r),
                g.delta[2] * (1.0 / r),
            ],
            vi: a.v,
            vj: b.v,
            omegai: a.omega,
            omegaj: b.omega,
            ..Contact::default()
        };
        DefaultSurface.surfaces_intersect(&mut c);
        let m = Motion {
            en: c.en,
            vn: c.vn,
            vtr: c.vtr,
            cri: c.cri,
            crj: c.crj,
        };
        let mut flag = 0.0;
        let f = e.intersect(&golden_pair(0.4, 0.4), &m, &mut flag).unwrap();
        for d in 0..3 {
            let want = wet[0].f[d] - dry[0].f[d];
            assert!(
                (f.f[d] - want).abs() < 1e-12,
                "step {step}: {} {want}",
                f.f[d]
            );
            let want = wet[0].t[d] - dry[0].t[d];
            assert!(
                (f.ti[d] - want).abs() < 1e-15,
                "step {step}: {} {want}",
                f.ti[d]
            );
            let want = wet[1].t[d] - dry[1].t[d];
            assert!(
                (f.tj[d] - want).abs() < 1e-15,
                "step {step}: {} {want}",
                f.tj[d]
            );
        }
        // wall contact of atom 3 (touching up to step 4)
        let a = &wet[2];
        let gap = a.x[2] + 0.05 - RAD[2];
        if gap > 0.0 {
            continue;
        }
        let rw = RAD[2] + gap;
        let mut c = Contact {
            is_wall: true,
            radi: RAD[2],
            radsum: RAD[2],
            r: rw,
            rinv: 1.0 / rw,
            delta: [0.0, 0.0, a.x[2] + 0.05],
            en: [0.0, 0.0, (a.x[2] + 0.05) * (1.0 / rw)],
            deltan: -gap,
            vi: a.v,
            omegai: a.omega,
            ..Contact::default()
        };
        DefaultSurface.surfaces_intersect(&mut c);
        let m = Motion {
            en: c.en,
            vn: c.vn,
            vtr: c.vtr,
            cri: c.cri,
            crj: 0.0,
        };
        let f = e.intersect(&golden_wall(), &m, &mut flag).unwrap();
        for d in 0..3 {
            let want = wet[2].f[d] - dry[2].f[d];
            assert!(
                (f.f[d] - want).abs() < 1e-12,
                "step {step}: {} {want}",
                f.f[d]
            );
            let want = wet[2].t[d] - dry[2].t[d];
            assert!(
                (f.ti[d] - want).abs() < 1e-15,
                "step {step}: {} {want}",
                f.ti[d]
            );
        }
    }
}
