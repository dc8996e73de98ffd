//! Physics checks that hold independently of LIGGGHTS: energy conservation of an elastic
//! collision and the 5/7 rule of a sphere that stops sliding and rolls.

mod common;

use std::path::PathBuf;

/// Run `deck` in a fresh directory and return the numbers printed on lines starting `tag`.
fn printed(name: &str, deck: &str, tag: &str) -> Vec<Vec<f64>> {
    let dir = common::scratch_dir(&format!("physics-{name}"));
    let out = common::run_deck(&dir, "in.deck", deck, &[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all::<PathBuf>(dir);
    stdout
        .lines()
        .filter_map(|l| l.strip_prefix(tag))
        .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
        .collect()
}

const HEADER: &str = "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n\
    communicate single vel yes\nunits si\nregion b block -1 1 -1 1 -1 1 units box\n\
    create_box 1 b\nneighbor 0.001 bin\nneigh_modify delay 0\n\
    fix m1 all property/global youngsModulus peratomtype 5e6\n\
    fix m2 all property/global poissonsRatio peratomtype 0.3\n";

#[test]
fn elastic_head_on_collision_conserves_kinetic_energy() {
    let deck = format!(
        "{HEADER}fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\npair_coeff * *\n\
         create_atoms 1 single -0.0101 0 0 units box\ncreate_atoms 1 single 0.0101 0 0 units box\n\
         set group all diameter 0.02 density 2500\nset atom 1 vx 0.5\nset atom 2 vx -0.5\n\
         fix i all nve/sphere\ntimestep 1e-6\nthermo 1000\n\
         variable kk equal ke\nvariable v1 equal vx[1]\nvariable v2 equal vx[2]\n\
         run 0\nprint \"energy ${{kk}} ${{v1}} ${{v2}}\"\n\
         run 20000\nprint \"energy ${{kk}} ${{v1}} ${{v2}}\"\n"
    );
    let e = printed("elastic", &deck, "energy ");
    assert_eq!(e.len(), 2);
    let (before, after) = (e[0][0], e[1][0]);
    // the spheres have met and separated: velocities reversed
    assert!(e[1][1] < -0.49 && e[1][2] > 0.49, "{e:?}");
    let drift = ((after - before) / before).abs();
    assert!(drift < 1e-6, "kinetic energy drift {drift:e}");
}

#[test]
fn sliding_sphere_rolls_at_five_sevenths_of_its_speed() {
    // a sphere launched without spin on a frictional floor slides until v = r omega, which
    // happens at v = 5/7 v0 for a solid sphere; without rolling friction it then rolls on
    let deck = format!(
        "{HEADER}fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\npair_coeff * *\n\
         fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0\n\
         create_atoms 1 single 0 0 0.00999 units box\nset group all diameter 0.02 density 2500\n\
         set atom 1 vx 1.0\nfix g all gravity 9.81 vector 0 0 -1\nfix i all nve/sphere\n\
         timestep 1e-6\nthermo 100000\nvariable v equal vx[1]\nvariable w equal omegay[1]\n\
         run 300000\nprint \"rolling ${{v}} ${{w}}\"\n"
    );
    let r = printed("rolling", &deck, "rolling ");
    let (v, w) = (r[0][0], r[0][1]);
    assert!((v - 5.0 / 7.0).abs() < 0.01 * 5.0 / 7.0, "v = {v}");
    // rolling without slipping: v = r omega (r = 0.01 m)
    assert!(
        (v - 0.01 * w).abs() < 0.01 * v,
        "v = {v}, r omega = {}",
        0.01 * w
    );
}

#[test]
fn a_pair_style_redefined_with_a_wider_history_continues() {
    // two spheres pressed together and sliding: history from `tangential history` (3 values)
    // meets a pair style that stores 6 (rolling friction epsd); LIGGGHTS replaces its
    // contact-history fix and runs on, so must regolith (it used to index past the old history)
    let deck = format!(
        "{HEADER}fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.3\n\
         fix m6 all property/global coefficientRollingViscousDamping peratomtypepair 1 0.1\n\
         pair_style gran model hertz tangential history\npair_coeff * *\n\
         create_atoms 1 single -0.0099 0 0 units box\ncreate_atoms 1 single 0.0099 0 0 units box\n\
         set group all diameter 0.02 density 2500\nset atom 1 vy 0.1\nset atom 2 vy -0.1\n\
         fix i all nve/sphere\ntimestep 1e-6\nthermo 1000\nvariable kk equal ke\n\
         run 200\nprint \"energy ${{kk}}\"\n\
         pair_style gran model hertz tangential history rolling_friction epsd\npair_coeff * *\n\
         run 200\nprint \"energy ${{kk}}\"\n"
    );
    let e = printed("history_width", &deck, "energy ");
    assert_eq!(e.len(), 2);
    assert!(e[1][0].is_finite() && e[1][0] > 0.0, "{e:?}");
}
