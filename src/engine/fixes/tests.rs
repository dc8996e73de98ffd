use super::*;

#[test]
fn wiggle_velocity_after_one_period_is_a_omega() {
    // LIGGGHTS-BEHAVIOUR item 10: after exactly one period |v| = A w, not 0
    let mut p = Particles::default();
    p.push(1, 1, [0.0, 0.0, 1.0], 0.001, 2500.0);
    let domain = Domain::default();
    let (a, f) = (1e-3, 50.0);
    let omega = 2.0 * std::f64::consts::PI / (1.0 / f);
    let m = Move::new(
        Motion::Wiggle {
            amplitude: [None, None, Some(a)],
            omega,
        },
        &p,
        1,
        &domain,
        0,
    );
    let mut fixes = vec![Fix {
        id: "m".into(),
        style: "move".into(),
        group: 1,
        kind: FixKind::Style(Box::new(m)),
        args: vec![],
        clock: Default::default(),
    }];
    let dt = 1e-4;
    for step in 1..=200 {
        initial_integrate(&mut fixes, &mut p, step, dt, &domain);
        p.f[0] = [0.0; 3];
        post_force(
            &mut fixes,
            &mut p,
            (step, &domain),
            dt,
            true,
            (0, 0.0),
            false,
        );
        final_integrate(&mut fixes, &mut p, step, dt, &domain);
    }
    assert!((p.v[0][2] - a * omega).abs() < 1e-9);
    assert!((p.x[0][2] - 1.0).abs() < 1e-12);
}

#[test]
fn a_moved_atom_stays_at_the_image_nearest_its_old_position() {
    // an atom that crossed a periodic face (image 1) keeps its wrapped position under a
    // wiggle, as LIGGGHTS's remap_near does, instead of jumping to its unwrapped start
    let mut domain = Domain::default();
    domain.boundary = crate::engine::domain::parse_boundary(&["p", "p", "f"]).unwrap();
    domain.create([0.0; 3], [1.0, 1.0, 1.0]);
    let mut p = Particles::default();
    p.push(1, 1, [0.2, 0.5, 0.5], 0.01, 2500.0);
    p.image[0] = [1, 0, 0];
    let m = Move::new(
        Motion::Wiggle {
            amplitude: [Some(0.0), Some(0.0), Some(1e-3)],
            omega: 10.0,
        },
        &p,
        1,
        &domain,
        0,
    );
    assert_eq!(m.origin[&1][0], 1.2);
    let mut fixes = vec![Fix {
        id: "m".into(),
        style: "move".into(),
        group: 1,
        kind: FixKind::Style(Box::new(m)),
        args: vec![],
        clock: Default::default(),
    }];
    initial_integrate(&mut fixes, &mut p, 1, 1e-3, &domain);
    assert!((p.x[0][0] - 0.2).abs() < 1e-12, "x = {:?}", p.x[0]);
    assert!((p.x[0][2] - (0.5 + 1e-3 * (1e-2f64).sin())).abs() < 1e-15);
}

/// A module style in the test: f -= gamma v.
struct Drag(f64);

impl FixStyle for Drag {
    fn name(&self) -> &str {
        "drag"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        for i in (0..p.len()).filter(|&i| p.mask[i] & at.group != 0) {
            for d in 0..3 {
                p.f[i][d] -= self.0 * p.v[i][d];
            }
        }
    }
}

/// A module style in the test: a constant force added (`addforce`).
struct Push([f64; 3]);

impl FixStyle for Push {
    fn name(&self) -> &str {
        "push"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        for i in (0..p.len()).filter(|&i| p.mask[i] & at.group != 0) {
            for d in 0..3 {
                p.f[i][d] += self.0[d];
            }
        }
    }
}

/// A module style in the test: the y force set (`setforce NULL FY NULL`).
struct Pin(f64);

impl FixStyle for Pin {
    fn name(&self) -> &str {
        "pin"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        for i in (0..p.len()).filter(|&i| p.mask[i] & at.group != 0) {
            p.f[i][1] = self.0;
        }
    }
}

/// A module style in the test: force and torque zero, the particles held still.
struct Hold;

impl FixStyle for Hold {
    fn name(&self) -> &str {
        "hold"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        for i in (0..p.len()).filter(|&i| p.mask[i] & at.group != 0) {
            p.f[i] = [0.0; 3];
            p.torque[i] = [0.0; 3];
        }
    }

    fn holds_still(&self) -> bool {
        true
    }
}

#[test]
fn post_force_order_and_freeze() {
    let mut p = Particles::default();
    p.push(1, 1, [0.0; 3], 0.5, 1.0);
    p.v[0] = [1.0, 0.0, 0.0];
    p.torque[0] = [1.0; 3];
    let mk = |kind| Fix {
        id: "f".into(),
        style: "x".into(),
        group: 1,
        kind,
        args: vec![],
        clock: Default::default(),
    };
    let fixes = vec![
        mk(FixKind::Style(Box::new(Push([1.0, 2.0, 3.0])))),
        mk(FixKind::Style(Box::new(Drag(0.5)))),
        mk(FixKind::Style(Box::new(Pin(7.0)))),
    ];
    let mut fixes = fixes;
    post_force(
        &mut fixes,
        &mut p,
        (0, &Domain::default()),
        0.1,
        true,
        (0, 0.0),
        false,
    );
    assert_eq!(p.f[0], [0.5, 7.0, 3.0]);
    post_force(
        &mut [mk(FixKind::Style(Box::new(Hold)))],
        &mut p,
        (0, &Domain::default()),
        0.1,
        true,
        (0, 0.0),
        false,
    );
    assert_eq!((p.f[0], p.torque[0]), ([0.0; 3], [0.0; 3]));
    assert_eq!(frozen_groups(&[mk(FixKind::Style(Box::new(Hold)))]), 1);
    assert_eq!(frozen_groups(&[mk(FixKind::Style(Box::new(Drag(0.5))))]), 0);
}
