//! Rigid clumps (`fix multisphere`) against physics that holds without LIGGGHTS: a spinning
//! clump in free fall keeps its shape exactly and its centre of mass follows g; two clumps
//! colliding without walls or gravity keep their total momentum.

mod common;

use std::path::{Path, PathBuf};

/// Runs `deck` in a fresh directory; returns the directory and stdout.
fn run(name: &str, deck: &str, flags: &[&str]) -> (PathBuf, String) {
    let dir = common::scratch_dir(&format!("ms-{name}"));
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let out = common::run_deck(&dir, "in.deck", deck, flags);
    let stdout = String::from_utf8_lossy(&out.stdout).to_string();
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (dir, stdout)
}

/// Rows (id, mol, x, y, z, vx, vy, vz, mass) of the snapshots of `post/d_*.dump`, by step.
fn snapshots(dir: &Path) -> Vec<(i64, Vec<[f64; 9]>)> {
    let mut out = Vec::new();
    for e in std::fs::read_dir(dir.join("post")).unwrap() {
        let text = std::fs::read_to_string(e.unwrap().path()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let step: i64 = lines[1].trim().parse().unwrap();
        let rows = lines[9..]
            .iter()
            .map(|l| {
                let w: Vec<f64> = l.split_whitespace().map(|v| v.parse().unwrap()).collect();
                [w[0], w[1], w[2], w[3], w[4], w[5], w[6], w[7], w[8]]
            })
            .collect();
        out.push((step, rows));
    }
    out.sort_by_key(|s| s.0);
    out
}

const HEADER: &str = "atom_style sphere\natom_modify map array sort 0 0\nboundary f f f\n\
    newton off\ncommunicate single vel yes\nunits si\n\
    region reg block -0.1 0.1 -0.1 0.1 -0.5 0.5 units box\ncreate_box 1 reg\n\
    neighbor 0.002 bin\nneigh_modify delay 0\n\
    fix m1 all property/global youngsModulus peratomtype 1.e7\n\
    fix m2 all property/global poissonsRatio peratomtype 0.45\n\
    fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
    fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
    pair_style gran model hertz tangential history\npair_coeff * *\ntimestep 0.00001\n";

/// Four spheres symmetric about the origin; with `mass ... use_density` the centre of mass
/// is the origin exactly (no sampling), so the members' mean offset is zero.
const CROSS: &str = "fix t all particletemplate/multisphere 15485863 atom_type 1 density \
    constant 2500 nspheres 4 ntry 100000 spheres 0.006 0 0 0.004 -0.006 0 0 0.004 \
    0 0.003 0 0.003 0 -0.003 0 0.003 type 1 mass 0.004 inertia_tensor 6e-8 0 0 2e-8 0 7e-8 \
    use_density\nfix d all particledistribution/discrete 15485867 1 t 1.0\n";

const DUMP: &str = "dump d all custom 500 post/d_*.dump id mol x y z vx vy vz mass\n\
    dump_modify d format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\" sort id\n";

fn dist(a: &[f64; 9], b: &[f64; 9]) -> f64 {
    ((a[2] - b[2]).powi(2) + (a[3] - b[3]).powi(2) + (a[4] - b[4]).powi(2)).sqrt()
}

#[test]
fn a_spinning_clump_in_free_fall_keeps_its_shape_and_follows_g() {
    let deck = format!(
        "{HEADER}fix g all gravity 9.81 vector 0 0 -1\n{CROSS}\
         region r block -0.02 0.02 -0.02 0.02 0.3 0.32 units box\n\
         fix ins all insert/pack seed 32452843 distributiontemplate d vel constant 0.2 0 0.5 \
         omega constant 3 -20 40 insert_every once overlapcheck yes region r \
         particles_in_region 1\nfix integr all multisphere\n\
         thermo_style custom step atoms ke\nthermo 500\nthermo_modify norm no\nrun 1\n\
         {DUMP}run 6000\n"
    );
    for flags in [&[][..], &["-sf", "fast"][..]] {
        let (dir, out) = run("fall", &deck, flags);
        let snaps = snapshots(&dir);
        assert_eq!(
            snaps.len(),
            12,
            "dumps at steps 500, 1000, ..., 6000: {out}"
        );
        let first = &snaps[0].1;
        assert_eq!(first.len(), 4);
        assert!(first.iter().all(|r| r[1] == 1.0), "every member in body 1");
        // the shape: every member distance as at insertion, to round-off
        for (step, rows) in &snaps {
            for i in 0..4 {
                for j in i + 1..4 {
                    let (d0, d) = (dist(&first[i], &first[j]), dist(&rows[i], &rows[j]));
                    assert!(
                        ((d - d0) / d0).abs() < 1e-12,
                        "step {step}: members {i} {j} at {d} instead of {d0}"
                    );
                }
            }
        }
        // the centre of mass is the members' mean (symmetric clump): v = v0 + g t
        let (step0, t0) = (snaps[0].0, &snaps[0].1);
        let mean = |rows: &Vec<[f64; 9]>, c: usize| rows.iter().map(|r| r[c]).sum::<f64>() / 4.0;
        let vz0 = mean(t0, 7);
        let z0 = mean(t0, 4);
        for (step, rows) in &snaps {
            let t = (step - step0) as f64 * 1e-5;
            let vz = mean(rows, 7);
            assert!(
                (vz - (vz0 - 9.81 * t)).abs() < 1e-10,
                "step {step}: vz {vz}"
            );
            let z = mean(rows, 4);
            let want = z0 + vz0 * t - 0.5 * 9.81 * t * t;
            assert!(
                (z - want).abs() < 1e-10,
                "step {step}: z {z} instead of {want}"
            );
            assert!((mean(rows, 5) - 0.2).abs() < 1e-12);
        }
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn two_clumps_colliding_keep_their_momentum() {
    let deck = format!(
        "{HEADER}{CROSS}\
         region r1 block -0.03 -0.02 -0.001 0.001 -0.001 0.001 units box\n\
         region r2 block 0.02 0.03 0.001 0.003 -0.001 0.001 units box\n\
         fix ins1 all insert/pack seed 32452843 distributiontemplate d vel constant 0.5 0 0 \
         omega constant 0 0 10 insert_every once overlapcheck yes region r1 particles_in_region 1\n\
         fix ins2 all insert/pack seed 32452867 distributiontemplate d vel constant -0.3 0.05 0 \
         insert_every once overlapcheck yes region r2 particles_in_region 1\n\
         fix integr all multisphere\n\
         thermo_style custom step atoms ke\nthermo 500\nthermo_modify norm no\nrun 1\n\
         {DUMP}run 10000\n"
    );
    let (dir, out) = run("collide", &deck, &[]);
    let snaps = snapshots(&dir);
    let momentum = |rows: &Vec<[f64; 9]>| {
        let mut p = [0.0; 3];
        for r in rows {
            for c in 0..3 {
                // each member carries the body's mass: a quarter of the body's momentum
                p[c] += r[8] * r[5 + c] / 4.0;
            }
        }
        p
    };
    let p0 = momentum(&snaps[0].1);
    let scale = (p0[0].powi(2) + p0[1].powi(2)).sqrt();
    // the clumps have met: the first one's x velocity has dropped
    let last = &snaps.last().unwrap().1;
    assert!(last[0][5] < 0.4, "no collision: {out}");
    for (step, rows) in &snaps {
        let p = momentum(rows);
        for c in 0..3 {
            assert!(
                (p[c] - p0[c]).abs() < 1e-12 * scale,
                "step {step}: momentum {p:?} instead of {p0:?}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(dir);
}

/// Runs `deck` and returns its exit code with stdout and stderr together.
fn failing(name: &str, deck: &str) -> (Option<i32>, String) {
    let dir = common::scratch_dir(&format!("ms-{name}"));
    let out = common::run_deck(&dir, "in.deck", deck, &[]);
    let _ = std::fs::remove_dir_all(dir);
    (
        out.status.code(),
        format!(
            "{}{}",
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr)
        ),
    )
}

#[test]
fn clump_decks_regolith_cannot_run_yet_are_refused_and_misuse_is_an_error() {
    let insert = "region r block -0.02 0.02 -0.02 0.02 0.3 0.32 units box\n\
         fix ins all insert/pack seed 32452843 distributiontemplate d vel constant 0 0 0 \
         insert_every once overlapcheck yes region r particles_in_region 1\n";
    // clumps inserted without fix multisphere: LIGGGHTS's error at the insertion
    let (code, text) = failing("nofix", &format!("{HEADER}{CROSS}{insert}run 2\n"));
    assert_eq!(code, Some(1), "{text}");
    assert!(
        text.contains("You have to use exactly one fix multisphere"),
        "{text}"
    );
    // the body data cannot be unfixed
    let (code, text) = failing(
        "unfix",
        &format!("{HEADER}{CROSS}fix ms all multisphere\nunfix ms\n"),
    );
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("may not be unfixed"), "{text}");
    // the mol column needs the bodies' tags
    let (code, text) = failing(
        "mol",
        &format!("{HEADER}dump d all custom 10 d.dump id mol x\n"),
    );
    assert_eq!(code, Some(1), "{text}");
    assert!(
        text.contains("Dumping an atom property that isn't allocated"),
        "{text}"
    );
    // clumps by insert/rate/region, a constant orientation, and keywords of fix
    // multisphere are not supported yet
    let rate = "region r block -0.02 0.02 -0.02 0.02 0.3 0.32 units box\n\
         fix ins all insert/rate/region seed 32452843 distributiontemplate d nparticles 5 \
         particlerate 1000 insert_every 100 overlapcheck yes vel constant 0 0 0 region r\n";
    let (code, text) = failing("rate", &format!("{HEADER}{CROSS}{rate}"));
    assert_eq!(code, Some(3), "{text}");
    assert!(
        text.contains("fix insert/rate/region of multisphere clumps: not supported yet"),
        "{text}"
    );
    let constant = insert.replace(
        "insert_every once",
        "orientation constant 1 0 0 0 insert_every once",
    );
    let (code, text) = failing("constant", &format!("{HEADER}{CROSS}{constant}"));
    assert_eq!(code, Some(3), "{text}");
    assert!(
        text.contains("insertion orientation constant: not supported yet"),
        "{text}"
    );
    // LIGGGHTS streams clumps at a constant velocity only
    let dir = common::scratch_dir("ms-stream-vel");
    std::fs::write(
        dir.join("face.stl"),
        "solid f\nfacet normal 0 0 -1\nouter loop\nvertex 0.02 0.02 0.3\nvertex 0.02 -0.02 0.3\n\
         vertex -0.02 0.02 0.3\nendloop\nendfacet\nendsolid f\n",
    )
    .unwrap();
    let stream = "fix face all mesh/surface file face.stl type 1\n\
         fix ins all insert/stream seed 32452843 distributiontemplate d nparticles 5 \
         particlerate 1000 overlapcheck yes vel uniform 0 0 -1 0.1 0.1 0.1 insert_every 1000 \
         insertion_face face\nfix ms all multisphere\nrun 1\n";
    let out = common::run_deck(&dir, "in.deck", &format!("{HEADER}{CROSS}{stream}"), &[]);
    let _ = std::fs::remove_dir_all(dir);
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{text}");
    assert!(
        text.contains("Fix insert/stream (id ins): Currently only fix insert/stream with multisphere particles only supports constant velocity"),
        "{text}"
    );
    let (code, text) = failing(
        "keyword",
        &format!("{HEADER}fix ms all multisphere allow_heatsource yes\n"),
    );
    assert_eq!(code, Some(3), "{text}");
    assert!(
        text.contains("fix multisphere allow_heatsource: not supported yet"),
        "{text}"
    );
}
