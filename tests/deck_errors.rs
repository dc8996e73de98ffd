//! Decks LIGGGHTS 3.8.0 rejects are rejected before anything runs, with LIGGGHTS's message,
//! the file and line, and what to write instead: `compute wall/gran/local` rules and the
//! LIGGGHTS 2.x syntax of the contactModels tutorial's `in.oldModels`. Errors met during a run
//! (a variable a `fix print` line cannot substitute) carry LIGGGHTS's message too.

mod common;

use std::path::PathBuf;

/// Run `deck` in a fresh directory (with `left.stl` beside it); (exit status, stderr).
fn run(name: &str, deck: &str) -> (Option<i32>, String) {
    let dir = common::scratch_dir(&format!("deckerr-{name}"));
    let stl = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("compat/engine/wall_gran_local.inputs/left.stl");
    std::fs::copy(stl, dir.join("left.stl")).unwrap();
    let out = common::run_deck(&dir, "in.t", deck, &[]);
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

const HEAD: &str = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region domain block -0.05 0.05 -0.03 0.03 -0.02 0.04 units box
create_box 1 domain
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
";

fn with(body: &str) -> String {
    format!("{HEAD}{body}")
}

/// The deck fails before running (exit status 1) with every one of `needles` in its errors.
fn fails_with(name: &str, deck: &str, needles: &[&str]) {
    let (status, err) = run(name, deck);
    assert_eq!(status, Some(1), "{err}");
    for n in needles {
        assert!(err.contains(n), "missing {n:?} in:\n{err}");
    }
}

#[test]
fn wall_gran_local_needs_a_mesh_wall_before_it() {
    fails_with(
        "nomesh",
        &with("fix side all wall/gran model hertz tangential history primitive type 1 zplane 0\ncompute c all wall/gran/local\n"),
        &[
            "Compute wall/gran/local requires a fix of type wall/gran using one or more mesh walls",
            "--> in.t:16",
        ],
    );
}

#[test]
fn wall_gran_local_rules_match_liggghts() {
    let mesh = "fix left all mesh/surface file left.stl type 1\nfix wall all wall/gran model hertz tangential history mesh n_meshes 1 meshes left\n";
    let cases: [(&str, String, &[&str]); 6] = [
        // one compute per wall
        (
            "twice",
            format!("{mesh}compute a all wall/gran/local\ncompute b all wall/gran/local id force\n"),
            &["Fix wall/gran (id wall): Fix wall/gran allows only one compute of type wall/gran/local"],
        ),
        // unknown keyword, with the valid ones listed
        (
            "keyword",
            format!("{mesh}compute a all wall/gran/local force bogus\n"),
            &[
                "Compute wall/gran/local (id a): illegal/unrecognized keyword",
                "force_tangential",
            ],
        ),
        // the wall cannot go while the compute reports it
        (
            "unfix",
            format!("{mesh}compute a all wall/gran/local\nunfix wall\n"),
            &["need to uncompute the active compute wall/gran/local before unfixing the wall"],
        ),
        // history of a wall model without history
        (
            "history",
            "fix left all mesh/surface file left.stl type 1\nfix wall all wall/gran model hertz tangential no_history mesh n_meshes 1 meshes left\ncompute a all wall/gran/local\n".to_string(),
            &["can not calculate history values"],
        ),
        // defined after the first run (a run without particles needs the atom sort off)
        (
            "late",
            format!("{mesh}timestep 1e-5\natom_modify sort 0 0\nrun 10\ncompute a all wall/gran/local\n"),
            &["Need to define this compute before first run"],
        ),
        // a dump of it names columns: the compute is an array even with one keyword
        (
            "vector",
            format!("{mesh}compute a all wall/gran/local delta\ndump d all local 10 post/w.dump c_a\n"),
            &["Dump local compute does not calculate local vector"],
        ),
    ];
    for (name, body, needles) in cases {
        fails_with(name, &with(&body), needles);
    }
}

#[test]
fn liggghts_2_syntax_is_refused_with_the_3x_equivalent() {
    let deck = "atom_style granular
boundary m m m
newton off
units si
region reg block -0.05 0.05 -0.05 0.05 0. 0.15 units box
create_box 1 reg
pair_style gran/hertz/history 266000.0 NULL 500.0 NULL 0.5 1
fix zwalls all wall/gran 266000.0 NULL 500.0 NULL 0.5 1 zplane 0.0 0.15
fix ins all pour 1000 1 1 vol 0.7 1000 diam 0.003 0.003 dens 2500 2500 vel 0. 0. 0. 0. -1. region reg
";
    fails_with(
        "old",
        deck,
        &[
            "ERROR: Invalid pair style",
            "`pair_style gran model hertz tangential history`",
            "ERROR: Fix wall/gran (id zwalls): Invalid model specified (check for typos and enable at least one model)",
            "`fix ID group wall/gran model hertz",
            "ERROR: Invalid fix style: \"pour\"",
            "`insert/stream`",
        ],
    );
}

#[test]
fn multisphere_template_errors_are_liggghts_s() {
    let fix = "fix t1 all particletemplate/multisphere 15485863 atom_type 1 density constant 2500 \
               nspheres 2 ntry";
    let spheres = "spheres 0 0 0 0.001 0.002 0 0 0.001";
    // each message checked against LIGGGHTS 3.8.0
    for (name, tail, message) in [
        (
            "ms_ntry",
            format!("100 {spheres} type 1"),
            "ntry is too low",
        ),
        (
            "ms_type",
            format!("1000 {spheres}"),
            "have to provide a type >=1",
        ),
        (
            "ms_mass",
            format!("1000 {spheres} type 1 mass 1"),
            "have to define either both 'mass' and 'inertia_tensor' or none of the two",
        ),
    ] {
        fails_with(
            name,
            &with(&format!("{fix} {tail}\n")),
            &[&format!(
                "Fix particletemplate/multisphere (id t1): {message}"
            )],
        );
    }
}

/// A `compute stress/atom` defined after a run reads the pair virial of the run's last
/// step; LIGGGHTS tallies it only when some compute needed it then, so without one the
/// dump stops with LIGGGHTS's error (with one, compat deck `stress_atom_steps` matches
/// LIGGGHTS's values).
#[test]
fn a_stress_compute_defined_after_a_run_needs_the_last_step_tallied() {
    let deck = with(
        "timestep 1e-5
fix gr all gravity 9.81 vector 0 0 -1
lattice sc 0.01
region col block -1 1 -1 1 0 3 units lattice
create_atoms 1 region col
set type 1 diameter 0.0102 density 2500
fix nve all nve/sphere
thermo 50
run 100
compute s all stress/atom
write_dump all custom after.dump id c_s[1]
",
    );
    let (status, err) = run("virial_untallied", &deck);
    assert_eq!(status, Some(1), "{err}");
    assert!(
        err.contains("Per-atom virial was not tallied on needed timestep"),
        "{err}"
    );
}

#[test]
fn an_undefined_variable_in_fix_print_is_liggghts_s_error_not_a_debug_dump() {
    let deck = with(
        "create_atoms 1 single 0 0 0 units box\nset atom 1 diameter 0.01 density 2500\n\
         fix integr all nve/sphere\ntimestep 1e-5\nfix p all print 5 \"value ${nothere}\"\nrun 10\n",
    );
    let (status, err) = run("printvar", &deck);
    assert_eq!(status, Some(1), "{err}");
    assert!(err.contains("Substitution for illegal variable"), "{err}");
    assert!(!err.contains("LexError"), "{err}");
}

#[test]
fn an_insertion_region_outside_the_box_stops_as_liggghts_does() {
    // no Monte Carlo test point lands in the region: LIGGGHTS stops instead of inserting
    let deck = with(
        "timestep 1e-5\n\
         fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.002\n\
         fix pdd all particledistribution/discrete 32452843 1 pts 1.0\n\
         region far block 1 2 1 2 1 2 units box\n\
         fix ins all insert/pack seed 49979693 distributiontemplate pdd insert_every once \
         overlapcheck yes all_in yes particles_in_region 10 region far\n\
         fix integr all nve/sphere\nrun 10\n",
    );
    let (status, err) = run("farregion", &deck);
    assert_eq!(status, Some(1), "{err}");
    assert!(err.contains("Unable to calculate region volume"), "{err}");
    assert!(
        err.contains("region volume is too small or out of domain"),
        "{err}"
    );
}

/// LIGGGHTS checks what an insert/stream's keywords must define together at the run (its
/// `init` and first `setup`), not at the fix line: the fix is defined, the `run` line fails
/// with LIGGGHTS's message (as Debian's LIGGGHTS 3.8.0 prints after the lines before `run`).
#[test]
fn insert_stream_settings_are_refused_at_the_run_as_liggghts_does() {
    let face = "solid face\n\
        facet normal 0 0 1\nouter loop\nvertex -0.02 -0.02 0.03\nvertex 0.02 -0.02 0.03\n\
        vertex 0.02 0.02 0.03\nendloop\nendfacet\n\
        facet normal 0 0 1\nouter loop\nvertex -0.02 -0.02 0.03\nvertex 0.02 0.02 0.03\n\
        vertex -0.02 0.02 0.03\nendloop\nendfacet\nendsolid face\n";
    let cases = [
        (
            "nparticles 100 massrate 0.1 insert_every 1000 insertion_face ins_mesh extrude_length 0.01",
            "must not provide both 'insert_every' and 'extrude_length'",
        ),
        (
            "nparticles 100 massrate 0.1 extrude_length 0.01",
            "must define an insertion face",
        ),
        (
            "massrate 0.1 insertion_face ins_mesh extrude_length 0.01",
            "must define either 'nparticles' or 'mass'",
        ),
        (
            "nparticles 100 insertion_face ins_mesh extrude_length 0.01",
            "must define either 'massrate' or 'particlerate'",
        ),
        (
            "nparticles 100 massrate 0.1 insertion_face ins_mesh",
            "must define either 'insert_every' or 'extrude_length'",
        ),
        (
            "nparticles 100 massrate 0.1 insertion_face ins_mesh extrude_length 0.01 duration 5",
            "must not provide both 'extrude_length' and 'duration'",
        ),
        (
            "nparticles 100 massrate 0.1 all_in yes insertion_face ins_mesh extrude_length 0.01",
            "using all_in yes requires you to use a fix mesh/surface/planar",
        ),
    ];
    for (k, (keywords, message)) in cases.iter().enumerate() {
        let deck = with(&format!(
            "timestep 1e-5\n\
             fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.002\n\
             fix pdd all particledistribution/discrete 32452843 1 pts 1.0\n\
             fix ins_mesh all mesh/surface file face.stl type 1\n\
             fix ins all insert/stream seed 49979693 distributiontemplate pdd overlapcheck yes \
             vel constant 0. 0. -1.0 {keywords}\n\
             fix integr all nve/sphere\nrun 10\n"
        ));
        let run_line = deck.lines().count();
        let dir = common::scratch_dir(&format!("deckerr-stream{k}"));
        std::fs::write(dir.join("face.stl"), face).unwrap();
        let out = common::run_deck(&dir, "in.t", &deck, &[]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{keywords}: {err}");
        assert!(
            err.contains(&format!("ERROR: Fix insert/stream (id ins): {message}")),
            "{keywords}: {err}"
        );
        assert!(
            err.contains(&format!("--> in.t:{run_line}\n")),
            "{keywords}: not at the run line {run_line}: {err}"
        );
    }
}

#[test]
fn more_atoms_than_int_ids_can_number_are_refused_at_their_line() {
    fails_with(
        "toomany",
        &with("create_atoms 1 random 3000000000 15485863 NULL\n"),
        &[
            "New atom IDs exceed maximum allowed ID: 3e+09 atoms requested \
             (at most 2147483647 atoms can be numbered)",
            "--> in.t:15",
        ],
    );
}
