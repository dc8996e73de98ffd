//! The same deck gives bit-identical dumps run to run and for any thread count. The deck
//! packs ~3000 overlapping spheres so the contact loop takes its parallel path; on the fast
//! path with more than one thread its 200 steps also switch from stages shared out (steps
//! 1-100) to stages on one thread (101-200), as a small run measures both.

mod common;

use std::process::Command;

const DECK: &str = "\
atom_style granular
atom_modify map array
boundary p p f
newton off
communicate single vel yes
units si
region reg block 0 0.0372 0 0.0372 0 0.03 units box
create_box 1 reg
neighbor 0.0005 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.2
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 1.0
fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.8
fix m6 all property/global coefficientRollingViscousDamping peratomtypepair 1 2.0
fix m7 all property/global cohesionEnergyDensity peratomtypepair 1 1000
pair_style gran model hertz tangential history cohesion sjkr rolling_friction epsd
pair_coeff * *
fix floor all wall/gran model hertz tangential history cohesion sjkr rolling_friction epsd primitive type 1 zplane 0.0
lattice sc 0.00248
region pile block 0 0.0372 0 0.0372 0.0013 0.02 units box
create_atoms 1 region pile
set group all diameter 0.0025 density 2500
displace_atoms all random 0.00003 0.00003 0.00003 15485863
fix gr all gravity 1.625 vector 0 0 -1
fix integr all nve/sphere
timestep 1e-6
thermo 100
dump d all custom 100 out.dump id x y z vx vy vz fx fy fz omegax omegay omegaz
dump_modify d format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 200
";

fn run(threads: usize, tag: &str) -> Vec<u8> {
    run_with(threads, tag, &[], DECK)
}

fn run_with(threads: usize, tag: &str, flags: &[&str], deck: &str) -> Vec<u8> {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-determinism-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("in.deck"), deck).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["-in", "in.deck", "-log", "none"])
        .args(flags)
        .env("RAYON_NUM_THREADS", threads.to_string())
        // take the parallel contact loop even for this small pile
        .env("REGOLITH_PARALLEL_PAIRS", "0")
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dump = std::fs::read(dir.join("out.dump")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    dump
}

#[test]
fn dumps_are_identical_for_any_thread_count() {
    let one = run(1, "a");
    let two = run(2, "b");
    let again = run(2, "c");
    assert!(
        one.len() > 100_000,
        "the deck dumps its ~3000 atoms three times"
    );
    assert!(one == two, "1 and 2 threads gave different dumps");
    assert!(two == again, "two runs with 2 threads gave different dumps");
}

#[test]
fn the_fast_path_gives_the_same_dumps_for_1_2_and_3_threads() {
    let one = run_with(1, "f1", &["-sf", "fast", "-pk", "fast", "1"], DECK);
    let two = run_with(2, "f2", &["-sf", "fast", "-pk", "fast", "2"], DECK);
    let three = run_with(3, "f3", &["-sf", "fast", "-pk", "fast", "3"], DECK);
    assert!(one.len() > 100_000);
    assert!(
        one == two,
        "fast path: 1 and 2 threads gave different dumps"
    );
    assert!(
        one == three,
        "fast path: 1 and 3 threads gave different dumps"
    );
}

/// Largest deviation of `b` from `a` relative to each column's largest magnitude in `a`
/// (atoms matched by ID), over all snapshots.
fn scale_deviation(a: &[u8], b: &[u8]) -> f64 {
    common::scale_deviation(&String::from_utf8_lossy(a), &String::from_utf8_lossy(b))
}

#[test]
fn the_fast_path_agrees_with_the_exact_path_to_round_off() {
    let exact = run_with(1, "e1", &[], DECK);
    let fast = run_with(2, "e2", &["-sf", "fast"], DECK);
    let dev = scale_deviation(&exact, &fast);
    assert!(dev < 1e-10, "fast vs exact: {dev:e} of a column's scale");
    assert!(dev > 0.0 || exact == fast);
}

#[test]
fn after_a_fast_run_particles_are_back_in_the_exact_order() {
    // delete_atoms renumbers IDs in memory order: the fast path must leave the particles
    // in the order the exact path holds them (LIGGGHTS's spatial sort), so the IDs match
    let deck = DECK.replace(
        "run 200\n",
        "run 150\nregion top block INF INF INF INF 0.012 INF units box\n\
         delete_atoms region top compress yes\nrun 50\n",
    );
    let deck = deck.replace(
        "neigh_modify delay 0",
        "neigh_modify delay 0\natom_modify sort 100 0.0",
    );
    // without contact history: after compress, LIGGGHTS hands a pair across a periodic face
    // the history each side finds under the renumbered IDs, which may differ between the
    // two sides (the exact path keeps both, the fast path one); the order is what is tested
    let deck = deck.replace(
        "tangential history cohesion sjkr rolling_friction epsd",
        "tangential no_history cohesion sjkr",
    );
    assert!(!deck.contains("tangential history"));
    let exact = run_with(1, "o1", &[], &deck);
    let fast = run_with(2, "o2", &["-sf", "fast"], &deck);
    let dev = scale_deviation(&exact, &fast);
    assert!(dev < 1e-10, "fast vs exact after delete_atoms: {dev:e}");
}

#[test]
fn after_delete_atoms_both_paths_carry_the_same_contact_history() {
    // inside the box (no periodic faces), the history each renumbered pair takes after
    // delete_atoms compress, LIGGGHTS's way, is the same on both paths
    let deck = DECK.replace("boundary p p f", "boundary f f f").replace(
        "run 200\n",
        "run 150\nregion top block INF INF INF INF 0.012 INF units box\n\
         delete_atoms region top compress yes\nrun 50\n",
    );
    assert!(deck.contains("tangential history"));
    let exact = run_with(1, "h1", &[], &deck);
    let fast = run_with(2, "h2", &["-sf", "fast"], &deck);
    let dev = scale_deviation(&exact, &fast);
    assert!(dev < 1e-10, "fast vs exact after delete_atoms: {dev:e}");
}
