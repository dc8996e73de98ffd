//! Researchers' own decks (issue 15): what `check` and `run` report on them, each problem at
//! its own line, and the commands they use.

use std::path::PathBuf;
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-real-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn regolith(dir: &PathBuf, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

const HEAD: &str = "atom_style granular
atom_modify map array
boundary p p f
newton off
communicate single vel yes
units si
region reg block 0 0.1 0 0.1 0 0.1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
";

const MATERIAL: &str = "fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
";

#[test]
fn an_unsupported_pair_setting_is_reported_alone() {
    let dir = scratch("pairsetting");
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history computeDissipatedEnergy on\n\
         pair_coeff * *\ntimestep 1e-5\nrun 1\n"
    );
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    // the problems (file:line lines); check's notes on the contact model follow them
    let stdout = text(&out.stdout);
    let problems: Vec<&str> = stdout.lines().filter(|l| l.starts_with("in.t:")).collect();
    assert_eq!(
        problems,
        ["in.t:15: pair_style gran setting computeDissipatedEnergy on: not supported yet"]
    );
    assert_eq!(out.status.code(), Some(3));
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(3));
    let err = text(&out.stderr);
    assert!(
        !err.contains("Pair_coeff command before pair_style"),
        "{err}"
    );
}

#[test]
fn a_misspelt_pair_style_is_the_only_error_in_check_and_run() {
    // LIGGGHTS 3.8.0 stops at the pair_style line ("Invalid model specified"); the
    // pair_coeff after it must not add "Pair_coeff command before pair_style is defined"
    for (style, message) in [
        (
            "gran model hertzz tangential history",
            "Invalid model specified",
        ),
        ("granx model hertz", "Invalid pair style"),
    ] {
        let dir = scratch("pairtypo");
        let deck =
            format!("{HEAD}{MATERIAL}pair_style {style}\npair_coeff * *\ntimestep 1e-5\nrun 1\n");
        std::fs::write(dir.join("in.t"), deck).unwrap();
        let out = regolith(&dir, &["check", "in.t"]);
        let stdout = text(&out.stdout);
        let problems: Vec<&str> = stdout.lines().filter(|l| l.starts_with("in.t:")).collect();
        assert_eq!(problems.len(), 1, "{stdout}");
        assert!(
            problems[0].starts_with(&format!("in.t:15: {message}")),
            "{stdout}"
        );
        assert_eq!(out.status.code(), Some(1));
        let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
        assert_eq!(out.status.code(), Some(1));
        let err = text(&out.stderr);
        assert!(err.contains(message), "{err}");
        assert!(
            !err.contains("Pair_coeff command before pair_style"),
            "{err}"
        );
        assert!(err.contains("1 problem(s) found"), "{err}");
    }
}

#[test]
fn dump_modify_binary_is_illegal_for_text_dumps_as_in_liggghts() {
    // LIGGGHTS 3.8.0's dump custom takes no `binary` keyword (a .bin file name makes it
    // binary), nor may an xyz dump be binary
    for (dump, line, message) in [
        (
            "dump d all custom 10 d.txt id x\ndump_modify d binary yes\n",
            18,
            "Illegal dump_modify command",
        ),
        ("dump d all xyz 10 d.bin\n", 17, "Invalid dump xyz filename"),
    ] {
        let dir = scratch("dumpbinary");
        let deck = format!("{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n{dump}");
        std::fs::write(dir.join("in.t"), deck).unwrap();
        let out = regolith(&dir, &["check", "in.t"]);
        let stdout = text(&out.stdout);
        let problems: Vec<&str> = stdout.lines().filter(|l| l.starts_with("in.t:")).collect();
        assert_eq!(problems.len(), 1, "{stdout}");
        assert!(
            problems[0].starts_with(&format!("in.t:{line}: {message}")),
            "{stdout}"
        );
        assert_eq!(out.status.code(), Some(1));
    }
}

#[test]
fn material_limits_point_at_the_property_line_in_check_and_run() {
    let dir = scratch("youngs");
    let deck = format!(
        "{HEAD}{}pair_style gran model hertz tangential history\npair_coeff * *\n\
         create_atoms 1 single 0.05 0.05 0.05\nset atom 1 diameter 0.01 density 2500\n\
         timestep 1e-5\nfix i all nve/sphere\nrun 1\n",
        MATERIAL.replace("5e6", "5e4")
    );
    std::fs::write(dir.join("in.t"), &deck).unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    assert!(
        stdout.starts_with("in.t:11: youngsModulus >= 5e6 required for SI units"),
        "{stdout}"
    );
    assert_eq!(out.status.code(), Some(1));
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    let err = text(&out.stderr);
    assert!(err.contains("--> in.t:11"), "{err}");
    assert_eq!(out.status.code(), Some(1));
    // `soft_particles yes` before the run allows it, as in LIGGGHTS
    let soft = deck.replace("timestep 1e-5", "soft_particles yes\ntimestep 1e-5");
    std::fs::write(dir.join("in.soft"), soft).unwrap();
    let out = regolith(&dir, &["check", "in.soft"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
}

#[test]
fn check_reports_errors_after_an_unsupported_command() {
    let dir = scratch("afterunsupported");
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         fix heat all multisphere/break\n\
         fix pts all particletemplate/sphere 12345 atom_type 1 density constant 2500 radius constant 0.003\n"
    );
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    assert!(
        stdout.starts_with("in.t:17: fix multisphere/break: not supported yet\n"),
        "{stdout}"
    );
    assert!(
        stdout.contains("in.t:18: Random number generation"),
        "{stdout}"
    );
    assert_eq!(out.status.code(), Some(1));
    // a missing restart file after an unsupported atom style
    std::fs::write(
        dir.join("in.r"),
        "atom_style ellipsoid\nread_restart missing.restart\n",
    )
    .unwrap();
    let out = regolith(&dir, &["check", "in.r"]);
    let stdout = text(&out.stdout);
    assert!(
        stdout.starts_with(
            "in.r:1: atom_style ellipsoid: not supported yet\nin.r:2: Cannot open restart file"
        ),
        "{stdout}"
    );
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn write_dump_errors_name_the_line() {
    let dir = scratch("writedump");
    for (body, needle) in [
        ("write_dump all custom", "Illegal write_dump command"),
        (
            "write_dump nogroup custom a.dump id",
            "Could not find dump group ID",
        ),
        ("write_dump all custom a.dump id bogus", "bogus"),
        ("write_dump all custom a.dump id modify sort", "Illegal"),
    ] {
        std::fs::write(dir.join("in.t"), format!("{HEAD}{body}\n")).unwrap();
        let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{body}: {err}");
        assert!(err.contains("in.t:11"), "{body}: {err}");
        assert!(err.contains(needle), "{body}: {err}");
    }
}

#[test]
fn new_styles_refuse_what_liggghts_refuses() {
    let dir = scratch("newstyles");
    for (body, needle) in [
        (
            "fix f all nve/noforce extra",
            "Illegal fix nve/noforce command",
        ),
        (
            "compute a all erotate\ncompute b all erotate",
            "Reuse of compute ID",
        ),
        (
            "group g id 1\ncompute p g pe",
            "Compute pe must use group all",
        ),
        ("compute p all pe heat", "Illegal compute pe command"),
    ] {
        std::fs::write(dir.join("in.t"), format!("{HEAD}{body}\n")).unwrap();
        let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{body}: {err}");
        assert!(err.contains(needle), "{body}: {err}");
    }
}

#[test]
fn cfd_coupling_and_sph_are_said_plainly() {
    let dir = scratch("scope");
    let deck =
        format!("{HEAD}fix cfd all couple/cfd couple_every 100 mpi\nfix f all couple/cfd/force\n");
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    assert!(
        stdout.starts_with(
            "in.t:11: fix couple/cfd: needs an external CFD solver; regolith has no CFD coupling ("
        ),
        "{stdout}"
    );
    assert!(stdout.contains("in.t:12: fix couple/cfd/force: needs an external CFD solver"));
    assert!(!stdout.contains("not supported yet"), "{stdout}");
    assert_eq!(out.status.code(), Some(3));
    std::fs::write(dir.join("in.s"), "atom_style sph\n").unwrap();
    let out = regolith(&dir, &["check", "in.s"]);
    assert!(
        text(&out.stdout).contains("atom_style sph: out of scope: SPH is a fluid method"),
        "{}",
        text(&out.stdout)
    );
}

#[test]
fn check_stops_blaming_lines_after_an_error() {
    // LIGGGHTS stops at the missing restart file: the box-less lines after it are not errors
    let dir = scratch("aftererror");
    std::fs::write(
        dir.join("in.t"),
        "atom_style granular\nread_restart missing.restart\nfix g all gravity 9.81 vector 0 0 -1\nrun 10\n",
    )
    .unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    assert!(
        stdout.starts_with("in.t:2: Cannot open restart file missing.restart"),
        "{stdout}"
    );
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn thermo_log_and_modify_timing_arguments() {
    let dir = scratch("thermolog");
    for (body, needle) in [
        ("thermo_log a.log extra", "Illegal thermo_log command"),
        ("thermo_log", "Illegal thermo_log command"),
        ("modify_timing sometimes", "Illegal modify_timing command"),
    ] {
        std::fs::write(dir.join("in.t"), format!("{HEAD}{body}\n")).unwrap();
        let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{body}: {err}");
        assert!(err.contains(needle), "{body}: {err}");
    }
}

#[test]
fn neigh_modify_binsize_as_liggghts_checks_it() {
    let dir = scratch("binsize");
    let body = |binsize: &str| {
        format!(
            "{HEAD}neigh_modify binsize {binsize}\n{MATERIAL}pair_style gran model hertz tangential history\n\
             pair_coeff * *\ncreate_atoms 1 single 0.05 0.05 0.05\nset atom 1 diameter 0.01 density 2500\n\
             timestep 1e-5\nfix i all nve/sphere\nrun 1\n"
        )
    };
    // bins a hundred box lengths wide, and more bins than an int counts: errors at the run
    for (binsize, needle) in [
        ("20", "Cannot use neighbor bins - box size << cutoff"),
        ("1e-6", "Too many neighbor bins"),
    ] {
        std::fs::write(dir.join("in.t"), body(binsize)).unwrap();
        let out = regolith(&dir, &["check", "in.t"]);
        let stdout = text(&out.stdout);
        assert!(
            stdout.starts_with(&format!("in.t:22: {needle}")),
            "{stdout}"
        );
        let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
        let err = text(&out.stderr);
        assert!(err.contains(needle) && err.contains("--> in.t:22"), "{err}");
        assert_eq!(out.status.code(), Some(1));
    }
    // a bin grid other than the default (compat deck neigh_binsize: LIGGGHTS's order)
    std::fs::write(dir.join("in.t"), body("0.003")).unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    // 0 (or less) is LIGGGHTS's default; a missing value is an error at the line
    std::fs::write(dir.join("in.t"), body("0")).unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(!text(&out.stderr).contains("binsize"));
    std::fs::write(dir.join("in.t"), format!("{HEAD}neigh_modify binsize\n")).unwrap();
    for mode in [&["check", "in.t"][..], &["-in", "in.t", "-log", "none"]] {
        let out = regolith(&dir, mode);
        let all = text(&out.stdout) + &text(&out.stderr);
        assert!(all.contains("Illegal neigh_modify command"), "{all}");
        assert_eq!(out.status.code(), Some(1));
    }
}

/// `body` appended to HEAD fails in both `check` and `-in` with `needle`, at `line`.
fn fails_alike(dir: &PathBuf, body: &str, needle: &str, line: usize) {
    stops_alike(dir, body, needle, line, 1);
}

/// As [`fails_alike`], with exit status `code` (3: not supported yet).
fn stops_alike(dir: &PathBuf, body: &str, needle: &str, line: usize, code: i32) {
    stops_deck(dir, &format!("{HEAD}{body}\n"), needle, line, code);
}

/// The whole `deck` stops in both `check` and `-in` with `needle` at `line`, status `code`.
fn stops_deck(dir: &PathBuf, deck: &str, needle: &str, line: usize, code: i32) {
    let body = deck;
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let out = regolith(dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    assert!(
        stdout.starts_with(&format!("in.t:{line}: {needle}")),
        "{body}: {stdout}"
    );
    assert_eq!(out.status.code(), Some(code), "{body}");
    let out = regolith(dir, &["-in", "in.t", "-log", "none"]);
    let err = text(&out.stderr);
    assert!(
        err.contains(needle) && err.contains(&format!("--> in.t:{line}")),
        "{body}: {err}"
    );
    assert_eq!(out.status.code(), Some(code), "{body}");
}

#[test]
fn change_box_errors_as_liggghts_reports_them() {
    let dir = scratch("changebox");
    for (body, needle) in [
        ("change_box all", "Illegal change_box command"),
        ("change_box all units box", "Illegal change_box command"),
        (
            "change_box nog x final 0 1",
            "Could not find change_box group ID",
        ),
        // options end the operations: nothing may follow them
        (
            "change_box all x final 0 1 units lattice remap",
            "Illegal change_box command",
        ),
        ("change_box all x final 0.2 0.1", "Box bounds are invalid"),
        ("change_box all x scale", "Illegal change_box command"),
        (
            "change_box all y volume",
            "Change_box volume used incorrectly",
        ),
        (
            "change_box all x final 0 1 y volume z volume x volume",
            "Change_box volume used incorrectly",
        ),
        (
            "change_box all xy final 0.1",
            "Cannot change box tilt factors for orthogonal box",
        ),
        ("change_box all boundary p p", "Illegal change_box command"),
        (
            "change_box all boundary p p x",
            "Illegal change_box command",
        ),
        (
            "change_box all boundary p p fp",
            "Both sides of boundary must be periodic",
        ),
        // a shrink-wrapped face around no atoms turns the box inside out, as in LIGGGHTS
        ("change_box all boundary p p fs", "Illegal simulation box"),
        (
            "dump d all custom 1 d.dump id\nchange_box all ortho",
            "Cannot change box ortho/triclinic with dumps defined",
        ),
    ] {
        let line = 11 + body.matches('\n').count();
        fails_alike(&dir, body, needle, line);
    }
    stops_alike(
        &dir,
        "change_box all triclinic",
        "change_box triclinic: not supported yet",
        11,
        3,
    );
    // before the box
    std::fs::write(dir.join("in.t"), "change_box all x final 0 1\n").unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    assert!(text(&out.stdout)
        .starts_with("in.t:1: Change_box command before simulation box is defined"));
    // bounds in lattice units (a lattice of spacing 1 when none was defined)
    std::fs::write(
        dir.join("in.t"),
        format!("{HEAD}change_box all x final 0 2 units lattice\nlattice sc 0.5\nchange_box all y final 0 2 z scale 2 units lattice\n"),
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains("Changing box ...\n  orthogonal box = (0 0 0) to (2 0.1 0.1)\n"),
        "{stdout}"
    );
    assert!(
        stdout.contains("  orthogonal box = (0 0 0) to (2 1 0.1)\n  orthogonal box = (0 0 -0.05) to (2 1 0.15)\n"),
        "{stdout}"
    );
}

#[test]
fn change_box_after_a_restart_with_per_atom_state_needs_force() {
    let dir = scratch("changeboxrestart");
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         create_atoms 1 single 0.05 0.05 0.05\nset atom 1 diameter 0.01 density 2500\n\
         timestep 1e-5\nfix i all nve/sphere\nrun 1\nwrite_restart r.restart\n"
    );
    std::fs::write(dir.join("in.w"), deck).unwrap();
    assert!(regolith(&dir, &["-in", "in.w", "-log", "none"])
        .status
        .success());
    let read = "atom_style granular\nread_restart r.restart\nchange_box all boundary p p fs";
    std::fs::write(dir.join("in.t"), format!("{read}\n")).unwrap();
    for mode in [&["check", "in.t"][..], &["-in", "in.t", "-log", "none"]] {
        let out = regolith(&dir, mode);
        let all = text(&out.stdout) + &text(&out.stderr);
        assert!(
            all.contains("Cannot change_box after reading restart file with per-atom info"),
            "{all}"
        );
        assert_eq!(out.status.code(), Some(1));
    }
    std::fs::write(dir.join("in.t"), format!("{read} force\n")).unwrap();
    for mode in [&["check", "in.t"][..], &["-in", "in.t", "-log", "none"]] {
        let out = regolith(&dir, mode);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    }
    // LIGGGHTS 3.8.0 forgets the restart file's fix entries at every system init (a run,
    // even `run 0`, or write_restart): change_box needs no `force` after one
    let setup = format!(
        "atom_style granular\nread_restart r.restart\nnewton off\ncommunicate single vel yes\n\
         neigh_modify delay 0\n{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n"
    );
    for init in ["run 0", "write_restart again.restart"] {
        std::fs::write(
            dir.join("in.t"),
            format!("{setup}{init}\nchange_box all boundary p p fs\n"),
        )
        .unwrap();
        for mode in [&["check", "in.t"][..], &["-in", "in.t", "-log", "none"]] {
            let out = regolith(&dir, mode);
            let all = text(&out.stdout) + &text(&out.stderr);
            assert_eq!(out.status.code(), Some(0), "{init}: {all}");
        }
    }
}

#[test]
fn compute_modify_and_group_variable_errors() {
    let dir = scratch("computemodify");
    for (body, needle) in [
        (
            "compute_modify thermo_temp",
            "Illegal compute_modify command",
        ),
        (
            "compute_modify nope dynamic yes",
            "Could not find compute_modify ID",
        ),
        // extra/dof is a later LAMMPS keyword
        (
            "compute_modify thermo_temp extra/dof 0",
            "Illegal compute_modify command",
        ),
        (
            "compute_modify thermo_temp dynamic maybe",
            "Illegal compute_modify command",
        ),
        (
            "compute_modify thermo_temp extra",
            "Illegal compute_modify command",
        ),
        (
            "compute_modify thermo_temp extra 1.5",
            "Expected integer parameter",
        ),
        ("compute thermo_temp all temp", "Reuse of compute ID"),
        ("compute t all temp extra", "Illegal compute temp command"),
        (
            "group g variable nov",
            "Variable name for group does not exist",
        ),
        (
            "variable e equal 1\ngroup g variable e",
            "Variable for group is invalid style",
        ),
        ("group g initialize extra", "Illegal group command"),
    ] {
        let line = 11 + body.matches('\n').count();
        fails_alike(&dir, body, needle, line);
    }
    // accepted: the deprecation warning LIGGGHTS prints for thermo_temp, and both defaults
    std::fs::write(
        dir.join("in.t"),
        format!("{HEAD}compute_modify thermo_temp dynamic yes extra 0\ncompute_modify thermo_kin_eng thermo no\ngroup g initialize\ngroup g initialize\n"),
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains("WARNING: Changing thermo_temp compute object."),
        "{stdout}"
    );
    assert_eq!(
        stdout.matches("0 atoms in group g\n").count(),
        2,
        "{stdout}"
    );
    assert_eq!(regolith(&dir, &["check", "in.t"]).status.code(), Some(0));
}

#[test]
fn dump_columns_of_fixes_as_liggghts_checks_them() {
    let dir = scratch("dumpfix");
    for (body, needle) in [
        (
            "fix mv all move linear 0 0 0\ndump d all custom 1 d.dump id f_mv",
            "Dump custom fix does not compute per-atom vector",
        ),
        (
            "fix mv all move linear 0 0 0\ndump d all custom 1 d.dump id f_mv[4]",
            "Dump custom fix vector is accessed out-of-range",
        ),
        (
            "fix g all gravity 9.81 vector 0 0 -1\ndump d all custom 1 d.dump id x f_g",
            "Dump custom fix does not compute per-atom info",
        ),
        (
            "dump d all custom 1 d.dump id f_nope[1]",
            "Could not find dump custom fix ID",
        ),
    ] {
        let line = 11 + body.matches('\n').count();
        fails_alike(&dir, body, needle, line);
    }
    // fix move's start positions, 0 outside its group (without a pair style LIGGGHTS can
    // only run with the atom sort off)
    std::fs::write(
        dir.join("in.t"),
        format!(
            "{HEAD}create_atoms 1 single 0.05 0.05 0.05\ncreate_atoms 1 single 0.02 0.03 0.04\n\
             group one id 2\nfix mv one move linear 1 0 0\ntimestep 1e-3\n\
             dump d all custom 1 d.dump id f_mv[1] f_mv[2] f_mv[3]\ndump_modify d sort id\n\
             atom_modify sort 0 0\nrun 2\n"
        ),
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let dump = std::fs::read_to_string(dir.join("d.dump")).unwrap();
    assert!(
        dump.ends_with("ITEM: ATOMS id f_mv[1] f_mv[2] f_mv[3] \n1 0 0 0 \n2 0.02 0.03 0.04 \n"),
        "{dump}"
    );
}

/// A one-particle run after the pair style (five lines).
const RUN_ONE: &str =
    "create_atoms 1 single 0.05 0.05 0.05\nset atom 1 diameter 0.01 density 2500\n\
                       timestep 1e-5\nfix i all nve/sphere\nrun 1\n";

#[test]
fn pair_coeff_type_ranges_as_liggghts_sets_them() {
    let dir = scratch("paircoeff");
    // one atom type: `pair_coeff 1 1` sets every pair (a researcher's deck writes it so)
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff 1 1\n{RUN_ONE}"
    );
    std::fs::write(dir.join("in.t"), &deck).unwrap();
    for mode in [&["check", "in.t"][..], &["-in", "in.t", "-log", "none"]] {
        let out = regolith(&dir, mode);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    }
    // two types: LIGGGHTS needs every I,I pair set before the run, and refuses ranges that
    // set nothing or extra words
    let two = HEAD.replace("create_box 1 reg", "create_box 2 reg");
    let material = "fix m1 all property/global youngsModulus peratomtype 5e6 5e6\n\
                    fix m2 all property/global poissonsRatio peratomtype 0.45 0.45\n\
                    fix m3 all property/global coefficientRestitution peratomtypepair 2 0.3 0.3 0.3 0.3\n\
                    fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5\n";
    let pair = "pair_style gran model hertz tangential history";
    for (coeff, needle, line) in [
        ("pair_coeff 1 1", "All pair coeffs are not set", 21),
        ("pair_coeff 1*2 1", "All pair coeffs are not set", 21),
        ("pair_coeff 2 1", "Incorrect args for pair coefficients", 16),
        (
            "pair_coeff * * 5",
            "Incorrect args for pair coefficients",
            16,
        ),
    ] {
        let deck = format!("{two}{material}{pair}\n{coeff}\n{RUN_ONE}");
        stops_deck(&dir, &deck, needle, line, 1);
    }
    let deck = format!("{two}{material}{pair}\npair_coeff 1 *\npair_coeff 2 2\n{RUN_ONE}");
    std::fs::write(dir.join("in.t"), &deck).unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
}

#[test]
fn gravity_styles_refuse_what_liggghts_refuses() {
    let dir = scratch("gravity");
    for body in [
        "fix g all gravity 9.81",
        "fix g all gravity 9.81 chute",
        "fix g all gravity 9.81 chute 10 2",
        "fix g all gravity 9.81 spherical 1",
        "fix g all gravity 9.81 cute 3",
    ] {
        fails_alike(&dir, body, "Illegal fix gravity command", 11);
    }
}

#[test]
fn element_exclusion_lists_as_liggghts_reads_them() {
    let dir = scratch("exclusion");
    let facet = |x: f64| {
        format!(
            "facet normal 0 0 1\nouter loop\nvertex {x} 0 0\nvertex {} 0 0\nvertex {x} 0.05 0\n\
             endloop\nendfacet\n",
            x + 0.05
        )
    };
    let stl = format!("solid s\n{}{}endsolid s\n", facet(0.0), facet(0.05));
    std::fs::write(dir.join("floor.stl"), stl).unwrap();
    std::fs::write(dir.join("x.txt"), "9\n").unwrap();
    std::fs::write(dir.join("bad.txt"), "2x\n").unwrap();
    let mesh = "fix f all mesh/surface file floor.stl type 1";
    for (tail, needle) in [
        (
            "element_exclusion_list rd x.txt",
            "Fix mesh/surface (id f): expecing 'read' or 'write' after 'element_exclusion_list'",
        ),
        (
            "element_exclusion_list read missing.txt",
            "Fix mesh: can not open file for 'element_exclusion_list' for reading",
        ),
        (
            "element_exclusion_list read bad.txt",
            "Expected integer parameter in input script or data file",
        ),
        // LIGGGHTS's fix mesh keywords come before the surface's
        (
            "scale 1 element_exclusion_list read x.txt",
            "Fix mesh/surface (id f): unknown keyword or wrong keyword order: element_exclusion_list",
        ),
        (
            "scale 1 heal auto_remove_duplicates",
            "Fix mesh/surface (id f): unknown keyword or wrong keyword order: heal",
        ),
    ] {
        fails_alike(&dir, &format!("{mesh} {tail}"), needle, 11);
    }
    // the second facet (line 9) left out; `write` creates its (empty) list
    std::fs::write(
        dir.join("in.t"),
        format!(
            "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
             {mesh} element_exclusion_list read x.txt\n\
             fix g all mesh/surface file floor.stl type 1 element_exclusion_list write w.txt\n\
             create_atoms 1 single 0.05 0.05 0.05\nset atom 1 diameter 0.01 density 2500\n\
             dump s all stl 1 out*.stl f\nrun 0\n"
        ),
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stl = std::fs::read_to_string(dir.join("out0.stl")).unwrap();
    assert_eq!(stl.matches("facet normal").count(), 1, "{stl}");
    assert!(stl.contains("vertex 0 0 0"), "{stl}");
    assert_eq!(std::fs::read_to_string(dir.join("w.txt")).unwrap(), "");
}

#[test]
fn write_restart_creates_its_folders_as_liggghts_does() {
    let dir = scratch("restartdirs");
    // a CFD-DEM case's init deck writes ../DEM/post/restart/liggghts.restart before any
    // solver has made the folder
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         {RUN_ONE}write_restart post/restart/liggghts.restart\n"
    );
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(dir.join("post/restart/liggghts.restart").is_file());
}

#[test]
fn vtk_dump_file_names_as_liggghts_checks_them() {
    // a silo deck dumped its wear mesh with `mesh/vtk ... post/Container*.stl`
    let dir = scratch("vtkfiles");
    let particle = "Allowed file extensions for this dump style are: .vtk .vtu .pvtu .vtp .pvtp";
    let pair = "pair_style gran model hertz tangential history\npair_coeff * *\n\
                compute fc all pair/gran/local pos force\n";
    for (dump, needle) in [
        (
            "dump d all custom/vtk 10 post/a_*.txt id x",
            format!("dump custom/vtk: Could not find allowed filetype for serial writing. {particle}"),
        ),
        (
            "dump d all custom/vtk 10 post/a_*.vtk.gz id x",
            format!("dump custom/vtk: Could not find allowed filetype for writing of VTK file. {particle}"),
        ),
        (
            "dump d all custom/vtk 10 post/a_*.pvtx id x",
            format!("dump custom/vtk: Could not find allowed filetype for parallel writing. {particle}"),
        ),
        (
            "dump d all local/gran/vtk 10 post/l_*.dat fc",
            format!("dump local/gran/vtk: Could not find allowed filetype for serial writing. {particle}"),
        ),
        (
            "dump d all local/gran/vtk 10 post/l%_*.vtp fc",
            format!("dump local/gran/vtk: It is no longer allowed to enable parallel writing by setting the % character, please see the documentation for help. {particle}"),
        ),
        (
            "dump d all mesh/vtk 10 post/m_*.stl stress",
            "dump mesh/vtk: Could not find allowed filetype for serial writing. Allowed file extensions for this dump style are: .vtk .vtp .pvtp".to_string(),
        ),
    ] {
        fails_alike(&dir, &format!("{pair}{dump}"), &needle, 14);
    }
}

/// LIGGGHTS prints "Import and parallelization of mesh ID containing N triangle(s)
/// successful" at a mesh's first run setup only, before the thermo header (4 triangles in
/// this file, as Debian's LIGGGHTS 3.8.0 reports for this deck).
#[test]
fn a_mesh_is_announced_at_its_first_setup() {
    let dir = scratch("mesh-announce");
    let stl = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("compat/engine/wall_gran_local.inputs/left.stl");
    std::fs::copy(stl, dir.join("left.stl")).unwrap();
    std::fs::write(
        dir.join("in.t"),
        format!(
            "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
             fix cad all mesh/surface file left.stl type 1 move 0.07 0.05 0.02\n\
             fix wall all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad\n\
             create_atoms 1 single 0.05 0.05 0.05\nset atom 1 diameter 0.01 density 2500\n\
             fix integr all nve/sphere\ntimestep 1e-5\nrun 5\nrun 5\n"
        ),
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let line = "Import and parallelization of mesh cad containing 4 triangle(s) successful";
    let lines: Vec<&str> = stdout.lines().collect();
    let at: Vec<usize> = (0..lines.len()).filter(|&k| lines[k] == line).collect();
    assert_eq!(at.len(), 1, "{stdout}");
    let header = lines
        .iter()
        .position(|l| l.trim_start().starts_with("Step"))
        .unwrap();
    assert!(at[0] < header, "{stdout}");
}

/// A deck with insertions and a mesh partly outside the box (the third node below the floor).
fn screen_only_deck(dir: &std::path::Path, plate_z: [f64; 3]) {
    let plate = format!(
        "solid plate\nfacet normal 0 0 1\n outer loop\n  vertex 0.01 0.01 {}\n  vertex 0.09 0.01 {}\n  vertex 0.09 0.09 {}\n endloop\nendfacet\nendsolid plate\n",
        plate_z[0], plate_z[1], plate_z[2]
    );
    std::fs::write(dir.join("plate.stl"), plate).unwrap();
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         timestep 1e-5\nfix gr all gravity 9.81 vector 0 0 -1\n\
         fix plate all mesh/surface file plate.stl type 1\n\
         fix wall all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate\n\
         fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.002\n\
         fix pdd all particledistribution/discrete 32452843 1 pts 1.0\n\
         region top block 0.01 0.09 0.01 0.09 0.05 0.09 units box\n\
         region mid block 0.01 0.09 0.01 0.09 0.02 0.04 units box\n\
         fix pack all insert/pack seed 86028121 distributiontemplate pdd insert_every once overlapcheck yes particles_in_region 30 region mid\n\
         fix rate all insert/rate/region seed 49979687 distributiontemplate pdd nparticles 20 particlerate 2000 insert_every 200 overlapcheck yes region top\n\
         fix integr all nve/sphere\nthermo 100\nrun 400\n"
    );
    std::fs::write(dir.join("in.t"), deck).unwrap();
}

#[test]
fn the_log_leaves_out_what_liggghts_prints_on_the_screen_only() {
    let dir = scratch("screenonly");
    screen_only_deck(&dir, [0.002, 0.002, -0.001]);
    let out = regolith(&dir, &["-in", "in.t", "-log", "log.t"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let screen = text(&out.stdout);
    let log = std::fs::read_to_string(dir.join("log.t")).unwrap();
    // LIGGGHTS 3.8.0 (fix_mesh.cpp): a node outside the closed box is warned about, once,
    // on both; the rest below as its fprintf(screen, ...) and fprintf(logfile, ...) lines
    let warning = "WARNING: Not all nodes of fix mesh inside simulation box, elements will be deleted or wrapped around periodic boundary conditions (./src/fix_mesh.cpp:531)\n";
    assert_eq!(screen.matches(warning).count(), 1);
    assert_eq!(log.matches(warning).count(), 1);
    let rate = "INFO: Particle insertion rate: 4.000000 particles every 200 steps - particle rate 2000.000000";
    assert!(screen.contains(&format!("{rate}  (mass rate 1.675516e-01)\n")));
    assert!(log.contains(&format!("{rate}, (mass rate 1.675516e-01)\n")));
    for screen_only in [
        "\nReading STL file 'plate.stl' (mesh processing step 1/3) \n",
        "Import and parallelization of mesh plate containing 1 triangle(s) successful\n",
        "INFO: Resetting random generator for region mid\n",
        "INFO: Resetting random generator for region top\n",
        "insertion: proc 0 at 90 %\n",
    ] {
        assert!(
            screen.contains(screen_only),
            "{screen_only:?} not on the screen"
        );
        assert!(!log.contains(screen_only), "{screen_only:?} in the log");
    }
    // on both, as LIGGGHTS writes them
    for both in [
        "INFO: Particle insertion pack: inserting every 0 steps\n",
        "INFO: Particle insertion rate: inserted 4 particle templates (mass 3.351032e-04) at step 201\n",
    ] {
        assert!(screen.contains(both) && log.contains(both), "{both:?}");
    }
    // inside the box: no warning
    screen_only_deck(&dir, [0.002, 0.002, 0.001]);
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert!(!text(&out.stdout).contains("WARNING: Not all nodes"));
}

#[test]
fn a_mesh_wholly_outside_the_box_stops_the_run_before_its_lines() {
    let dir = scratch("meshlost");
    screen_only_deck(&dir, [-0.002, -0.002, -0.001]);
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(1));
    let screen = text(&out.stdout) + &text(&out.stderr);
    // LIGGGHTS's message when every element is lost, and neither the warning nor the
    // import line before it
    assert!(screen.contains("Mesh (id plate): All 1 mesh elements have been lost / left the domain. \nPlease use 'boundary m m m'"), "{screen}");
    assert!(!screen.contains("WARNING: Not all nodes"));
    assert!(!screen.contains("Import and parallelization"));
}

#[test]
fn insertion_fixes_name_what_they_miss_as_liggghts_means_it() {
    let dir = scratch("insertion_names");
    let tpl = "fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.003\n";
    let pdd = "fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0\n";
    let region = "region box block 0.01 0.09 0.01 0.09 0.02 0.09 units box\n";
    // a distribution that is not there (line 18), or not a distribution (line 18)
    let ins = |d: &str| {
        format!("fix ins all insert/pack seed 49979687 distributiontemplate {d} insert_every once particles_in_region 10 region box")
    };
    fails_alike(
        &dir,
        &format!("{MATERIAL}{tpl}{pdd}{region}{}", ins("pdd2")),
        "Fix insert/pack (id ins): Fix insert requires you to define a valid ID for a fix of type particledistribution/discrete (there is no fix pdd2; did you mean 'pdd1'?)",
        18,
    );
    fails_alike(
        &dir,
        &format!("{MATERIAL}{tpl}{pdd}{region}{}", ins("pts1")),
        "Fix insert/pack (id ins): Fix insert requires you to define a valid ID for a fix of type particledistribution/discrete (fix pts1 is a fix particletemplate/sphere)",
        18,
    );
    // a template that is not there (line 16)
    fails_alike(
        &dir,
        &format!("{MATERIAL}{tpl}fix pdd1 all particledistribution/discrete 32452843 1 pts2 1.0\n"),
        "Fix particledistribution/discrete (id pdd1): invalid ID for fix particletemplate provided (there is no fix pts2; did you mean 'pts1'?)",
        16,
    );
    // the insertion's seed equal to a template's (LIGGGHTS: all must differ)
    fails_alike(
        &dir,
        &format!(
            "{MATERIAL}{tpl}{pdd}{region}{}",
            ins("pdd1").replace("49979687", "15485863")
        ),
        "Fix insert/pack, ID ins: Random number generation: It is required that all the random seeds of this fix insert/*",
        18,
    );
}

#[test]
fn a_stream_face_extruded_out_of_the_box_is_refused_at_its_first_insertion() {
    // the face lies on the box top and is extruded upwards (against its normal, which points
    // down), so no point of the extruded volume is in the box: LIGGGHTS's Monte Carlo share
    // is 0 and it stops with fix_insert_stream.cpp:552 at the first insertion
    let dir = scratch("stream_outside");
    std::fs::write(
        dir.join("face.stl"),
        "solid f\nfacet normal 0 0 -1\nouter loop\nvertex 0.02 0.02 0.1\nvertex 0.02 0.08 0.1\nvertex 0.08 0.08 0.1\nendloop\nendfacet\nendsolid f\n",
    )
    .unwrap();
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.003
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
fix face all mesh/surface file face.stl type 1
fix ins all insert/stream seed 49979687 distributiontemplate pdd1 nparticles 10 particlerate 1000 vel constant 0 0 -1 insertion_face face extrude_length 0.05
fix integr all nve/sphere
run 10
"
    );
    std::fs::write(dir.join("in.t"), &deck).unwrap();
    // check draws the first insertion's Monte Carlo samples as the run draws them, so the
    // run stops before its first step (LIGGGHTS: after its setup lines and its warning
    // that the extruded face leaves the box)
    let out = regolith(&dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(
        stdout.starts_with("in.t:23: Fix insert/stream (id ins): insertion volume could not be distributed properly in parallel"),
        "{stdout}"
    );
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    assert_eq!(out.status.code(), Some(1), "{stdout}{stderr}");
    assert!(stderr.contains("nothing was run"), "{stderr}");
    assert!(
        stderr.contains("Fix insert/stream (id ins): insertion volume could not be distributed properly in parallel"),
        "{stderr}"
    );
}

#[test]
fn a_stream_face_that_is_not_planar_is_refused_as_liggghts_refuses_it() {
    // a face folded into a ridge (three triangles): LIGGGHTS's isPlanar fails and the run
    // stops at the stream's first setup (fix_insert_stream.cpp:300); `check` stops there too
    let dir = scratch("stream_folded");
    std::fs::write(
        dir.join("face.stl"),
        "solid v\nfacet normal 0 0 -1\nouter loop\nvertex 0.02 0.02 0.08\nvertex 0.02 0.08 0.08\nvertex 0.05 0.08 0.09\nendloop\nendfacet\nfacet normal 0 0 -1\nouter loop\nvertex 0.05 0.08 0.09\nvertex 0.05 0.02 0.09\nvertex 0.02 0.02 0.08\nendloop\nendfacet\nfacet normal 0 0 -1\nouter loop\nvertex 0.05 0.02 0.09\nvertex 0.05 0.08 0.09\nvertex 0.08 0.08 0.08\nendloop\nendfacet\nendsolid v\n",
    )
    .unwrap();
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.003
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
fix face all mesh/surface file face.stl type 1
fix ins all insert/stream seed 49979687 distributiontemplate pdd1 nparticles 10 particlerate 1000 vel constant 0 0 -1 insertion_face face extrude_length 0.03
fix integr all nve/sphere
run 10
"
    );
    std::fs::write(dir.join("in.t"), &deck).unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.contains("Fix insert/stream (id ins): command requires a planar face for insertion\n  --> in.t:23"),
        "{stderr}"
    );
    // `check` builds the face's topology as the run's setup does, and says so at the same line
    let out = regolith(&dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    let problems: Vec<&str> = stdout.lines().filter(|l| l.starts_with("in.t:")).collect();
    assert_eq!(
        problems,
        ["in.t:23: Fix insert/stream (id ins): command requires a planar face for insertion"],
        "{stdout}"
    );
    assert_eq!(out.status.code(), Some(1));
    // a flat face (at mid-height, its extrusion inside the box) passes both
    std::fs::write(
        dir.join("face.stl"),
        "solid v\nfacet normal 0 0 -1\nouter loop\nvertex 0.02 0.02 0.05\nvertex 0.02 0.08 0.05\nvertex 0.08 0.08 0.05\nendloop\nendfacet\nfacet normal 0 0 -1\nouter loop\nvertex 0.08 0.08 0.05\nvertex 0.08 0.02 0.05\nvertex 0.02 0.02 0.05\nendloop\nendfacet\nendsolid v\n",
    )
    .unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
}

/// `element_exclusion_list write` lists the triangles with an angle below the hard limit as
/// LIGGGHTS reads the mesh, in a deck that only writes the list (no run): a cyclone deck's
/// first step. Debian's LIGGGHTS 3.8.0 writes "16\n" for this file (the line of the sliver's
/// `facet`); reading the list back leaves the sliver out and the run goes on.
#[test]
fn an_exclusion_list_is_written_when_the_mesh_is_read() {
    let dir = scratch("exclusion_write");
    std::fs::write(
        dir.join("sliver.stl"),
        "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0.01 0.01 0.01\nvertex 0.09 0.01 0.01\nvertex 0.09 0.09 0.01\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0.01 0.01 0.01\nvertex 0.09 0.09 0.01\nvertex 0.01 0.09 0.01\nendloop\nendfacet\nfacet normal 0 -1 0\nouter loop\nvertex 0.01 0.095 0.02\nvertex 0.05 0.095 0.02\nvertex 0.09 0.095 0.02000001\nendloop\nendfacet\nendsolid s\n",
    )
    .unwrap();
    let mesh = "fix cad all mesh/surface file sliver.stl type 1 element_exclusion_list";
    let deck = format!(
        "{}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         {mesh} write sliver.exclude curvature_tolerant yes\n",
        HEAD.replace("p p f", "f f f")
    );
    std::fs::write(dir.join("in.w"), &deck).unwrap();
    let out = regolith(&dir, &["-in", "in.w", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert_eq!(
        std::fs::read_to_string(dir.join("sliver.exclude")).unwrap(),
        "16\n"
    );
    // the list read back: the run does not meet the sliver
    let read = deck.replace(
        "write sliver.exclude curvature_tolerant yes",
        "read sliver.exclude",
    ) + "create_atoms 1 single 0.05 0.05 0.02\nset atom 1 diameter 0.01 density 2500\n\
         fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad\n\
         fix i all nve/sphere\ntimestep 1e-5\nrun 10\n";
    std::fs::write(dir.join("in.r"), &read).unwrap();
    let out = regolith(&dir, &["-in", "in.r", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    // without the list, the run refuses the sliver
    std::fs::write(
        dir.join("in.n"),
        read.replace(" element_exclusion_list read sliver.exclude", ""),
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.n", "-log", "none"]);
    assert_eq!(out.status.code(), Some(1));
}

/// A mesh with angles below LIGGGHTS's hard limit stops the run with LIGGGHTS's count of
/// those angles and its "Bad mesh" error (a hopper deck's STL has two slivers; regolith
/// said it in words of its own), in `check` as in a run; a triangle below the soft limit
/// only (0.5 degrees) gets LIGGGHTS's count line on the screen and its warning in the log,
/// as Debian's LIGGGHTS 3.8.0 prints them for these two files.
#[test]
fn skewed_mesh_triangles_are_said_as_liggghts_says_them() {
    let dir = scratch("skewed_mesh");
    let sliver = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0.01 0.01 0.01\nvertex 0.09 0.01 0.01\nvertex 0.09 0.09 0.01\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0.01 0.01 0.01\nvertex 0.09 0.09 0.01\nvertex 0.01 0.09 0.01\nendloop\nendfacet\nfacet normal 0 -1 0\nouter loop\nvertex 0.01 0.095 0.02\nvertex 0.05 0.095 0.02\nvertex 0.09 0.095 0.02000001\nendloop\nendfacet\nendsolid s\n";
    std::fs::write(dir.join("sliver.stl"), sliver).unwrap();
    std::fs::write(
        dir.join("soft.stl"),
        sliver.replace("0.09 0.095 0.02000001", "0.09 0.095 0.0202"),
    )
    .unwrap();
    let deck = format!(
        "{}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         fix cad all mesh/surface file sliver.stl type 1 curvature_tolerant yes\n\
         create_atoms 1 single 0.05 0.05 0.02\nset atom 1 diameter 0.01 density 2500\n\
         fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad\n\
         fix i all nve/sphere\ntimestep 1e-5\nrun 10\n",
        HEAD.replace("p p f", "f f f")
    );
    stops_deck(
        &dir,
        &deck,
        "Mesh cad: 2 mesh elements have a really unreasonably high aspect ratio (hard limit: smallest angle must be > 0.057296 \u{b0})  \n\
         Fix mesh: Bad mesh, cannot continue. You will need to fix or remove these element. Remedies:\n \
         - You can use the 'element_exclusion_list' feature to remove elements with too many neighbors and elements with angles below the hard limit",
        23,
        1,
    );
    std::fs::write(dir.join("in.s"), deck.replace("sliver.stl", "soft.stl")).unwrap();
    let out = regolith(&dir, &["-in", "in.s", "-log", "log.s"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let warning = "WARNING: Fix mesh: Mesh contains highly skewed element, moving mesh (if used) will not parallelize well (./src/surface_mesh_I.h:657)\n";
    assert!(
        text(&out.stdout).contains(&format!(
            "Mesh cad: 1 elements have high aspect ratio (soft limit: smallest angle > 0.500000 \u{b0} required)\n{warning}\
             Import and parallelization of mesh cad containing 3 triangle(s) successful\n"
        )),
        "{}",
        text(&out.stdout)
    );
    let log = std::fs::read_to_string(dir.join("log.s")).unwrap();
    assert_eq!(log.matches(warning).count(), 1, "{log}");
    assert!(!log.contains("soft limit"), "{log}");
}

/// A mesh held at a temperature with no heat fix: LIGGGHTS stops at the run's init ("Could
/// not locate a fix/property storing value(s) for Temp as requested by wall/gran."); `check`
/// says the same at the run line, and the deck with its heat fix passes both.
#[test]
fn a_heated_mesh_without_a_heat_fix_is_refused_as_liggghts_refuses_it() {
    let dir = scratch("mesh_temperature");
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine");
    let deck = std::fs::read_to_string(root.join("in.mesh_temperature")).unwrap();
    std::fs::copy(
        root.join("mesh_temperature.inputs/square.stl"),
        dir.join("square.stl"),
    )
    .unwrap();
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let without: String = deck
        .lines()
        .filter(|l| !l.contains("heat/gran") && !l.contains("reduce") && !l.starts_with("dump"))
        .map(|l| {
            if l.starts_with("thermo_style") {
                "thermo_style custom step atoms ke".to_string()
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n");
    std::fs::write(dir.join("in.noheat"), format!("{without}\n")).unwrap();
    std::fs::write(dir.join("in.heat"), &deck).unwrap();
    let want =
        "Could not locate a fix/property storing value(s) for Temp as requested by wall/gran.";
    let run_line = without
        .lines()
        .position(|l| l.starts_with("run"))
        .expect("the deck runs")
        + 1;
    let check = regolith(&dir, &["check", "in.noheat"]);
    let said = text(&check.stdout) + &text(&check.stderr);
    assert_eq!(check.status.code(), Some(1), "{said}");
    assert!(
        said.contains(&format!("in.noheat:{run_line}: {want}")),
        "{said}"
    );
    let run = regolith(&dir, &["-in", "in.noheat", "-log", "none"]);
    let said = text(&run.stdout) + &text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{said}");
    assert!(said.contains(&format!("ERROR: {want}")), "{said}");
    let fine = regolith(&dir, &["check", "in.heat"]);
    assert_eq!(
        fine.status.code(),
        Some(0),
        "{}",
        text(&fine.stdout) + &text(&fine.stderr)
    );
}

/// A bin size far below the box (Debian's LIGGGHTS crashes there) stops the run with the
/// bin count instead of a panic.
#[test]
fn an_ave_spatial_bin_far_below_the_box_stops_the_run_with_its_count() {
    let dir = scratch("ave_spatial_bins");
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         timestep 1e-5\nregion fill block 0.01 0.09 0.01 0.09 0.01 0.05 units box\n\
         lattice sc 0.01\ncreate_atoms 1 region fill\nset group all diameter 0.004 density 2500\n\
         fix integr all nve/sphere\n\
         fix a all ave/spatial 1 1 1 x lower 0.01 y upper 1e-30 density/number file s.txt\n\
         run 1\n"
    );
    std::fs::write(dir.join("in.bins"), deck).unwrap();
    let run = regolith(&dir, &["-in", "in.bins", "-log", "none"]);
    let said = text(&run.stdout) + &text(&run.stderr);
    assert_eq!(run.status.code(), Some(1), "{said}");
    assert!(
        said.contains("ERROR: Fix ave/spatial: bin sizes 0.01 1e-30 give no bins or more than 67108864 of them"),
        "{said}"
    );
}

/// A stress mesh scaled, moved or rotated before its `reference_point` gets LIGGGHTS's
/// warning (mesh_module_stress.cpp:104), once per mesh; a mesh reaching past a
/// shrink-wrapped face gets no "Not all nodes" warning, as LIGGGHTS's setup wraps the box
/// around every mesh node before it tests them (found on a soil-mechanics deck of six
/// stress walls in an `m m m` box).
#[test]
fn stress_meshes_warn_as_liggghts_warns() {
    let dir = scratch("stress_warnings");
    // one node below the floor
    std::fs::write(
        dir.join("plate.stl"),
        "solid plate\nfacet normal 0 0 1\n outer loop\n  vertex 0.01 0.01 0.002\n  vertex 0.09 0.01 0.002\n  vertex 0.09 0.09 -0.001\n endloop\nendfacet\nendsolid plate\n",
    )
    .unwrap();
    let body = "pair_style gran model hertz tangential history\npair_coeff * *\n\
         fix a all mesh/surface/stress file plate.stl type 1 move 0 0 0.001 reference_point 0.05 0.05 0\n\
         fix b all mesh/surface/stress file plate.stl type 1 reference_point 0.05 0.05 0\n\
         fix wall all wall/gran model hertz tangential history mesh n_meshes 2 meshes a b\n\
         create_atoms 1 single 0.05 0.05 0.05\nset atom 1 diameter 0.01 density 2500\n\
         fix integr all nve/sphere\ntimestep 1e-5\nrun 2\n";
    let warning = "WARNING: Mesh for fix mesh/surface/stress has been scaled, moved, or rotated.\nPlease note that values for 'reference_point' refer to the scaled, moved, or rotated configuration (./src/mesh_module_stress.cpp:104)\n";
    let outside = "WARNING: Not all nodes of fix mesh inside simulation box";
    // as Debian's LIGGGHTS 3.8.0 warns for each boundary
    for (boundary, warned) in [
        ("boundary p p f", true),
        ("boundary p p m", false),
        ("boundary m m m", false),
    ] {
        let deck = format!("{HEAD}{MATERIAL}{body}").replace("boundary p p f", boundary);
        std::fs::write(dir.join("in.t"), deck).unwrap();
        let out = regolith(&dir, &["-in", "in.t", "-log", "log.t"]);
        let stdout = text(&out.stdout);
        assert_eq!(out.status.code(), Some(0), "{stdout}{}", text(&out.stderr));
        let log = std::fs::read_to_string(dir.join("log.t")).unwrap();
        assert_eq!(stdout.matches(warning).count(), 1, "{stdout}");
        assert_eq!(log.matches(warning).count(), 1, "{log}");
        assert_eq!(stdout.contains(outside), warned, "{boundary}: {stdout}");
    }
}

/// `fix_modify ID servo/target_val v_name` names an equal-style variable (LIGGGHTS's
/// checks there); the variable set point itself runs bit-identically to LIGGGHTS in the
/// engine deck servo_variable.
#[test]
fn a_servo_variable_set_point_is_checked_as_liggghts_checks_it() {
    let dir = scratch("servo_variable");
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine");
    std::fs::copy(
        root.join("servo_variable.inputs/plate.stl"),
        dir.join("plate.stl"),
    )
    .unwrap();
    let deck = std::fs::read_to_string(root.join("in.servo_variable")).unwrap();
    let line = deck
        .lines()
        .position(|l| l.starts_with("fix_modify lid servo/target_val v_t"))
        .unwrap()
        + 1;
    for (replacement, needle) in [
        (
            "fix_modify lid servo/target_val v_nothing",
            "Variable name does not exist",
        ),
        (
            "variable s string 3\nfix_modify lid servo/target_val v_s",
            "Variable is invalid style",
        ),
    ] {
        let bad = deck.replace("fix_modify lid servo/target_val v_t", replacement);
        let at = line + replacement.lines().count() - 1;
        stops_deck(&dir, &bad, needle, at, 1);
    }
    // the fix's own target_val v_name is checked at the run's init
    let bad = deck.replace("target_val v_half", "target_val v_nothing");
    let run_line = bad.lines().position(|l| l.starts_with("run")).unwrap() + 1;
    stops_deck(
        &dir,
        &bad,
        "Fix mesh/surface/stress/servo (id top): Variable name does not exist",
        run_line,
        1,
    );
    // a servo mesh's state is not written to restart files yet: said as such (status 3)
    let with_restart = format!("{deck}write_restart x.restart\n");
    let at = with_restart.lines().count();
    stops_deck(
        &dir,
        &with_restart,
        "a restart file with fix mesh/surface/stress/servo (id lid): not supported yet",
        at,
        3,
    );
}

/// A wearing stress mesh without `k_finnie` stops at the run's init with LIGGGHTS's
/// message, in `check` as in a run (a silo deck passed check and failed to run).
#[test]
fn wear_without_k_finnie_stops_check_and_run_at_the_run() {
    let dir = scratch("k_finnie");
    let stl = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("compat/engine/wall_gran_local.inputs/left.stl");
    std::fs::copy(stl, dir.join("left.stl")).unwrap();
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         fix cad all mesh/surface/stress file left.stl type 1 wear finnie\n\
         fix wall all wall/gran model hertz tangential history mesh n_meshes 1 meshes cad\n\
         timestep 1e-5\nrun 1\n"
    );
    stops_deck(
        &dir,
        &deck,
        "Could not locate a fix/property storing value(s) for k_finnie as requested by meshmodule/stress (fix mesh/surface/stress cad has wear finnie",
        20,
        1,
    );
}

/// Mesh IDs beyond `n_meshes` are LIGGGHTS's unknown argument, with a hint that the list
/// outnumbers the count (a silo deck listing four meshes after `n_meshes 3`); an unknown
/// mesh module names the fix as LIGGGHTS does.
#[test]
fn mesh_wall_and_module_errors_name_what_is_wrong() {
    let dir = scratch("n_meshes");
    let stl = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("compat/engine/wall_gran_local.inputs/left.stl");
    std::fs::copy(stl, dir.join("left.stl")).unwrap();
    let meshes = "fix a all mesh/surface file left.stl type 1\nfix b all mesh/surface file left.stl type 1\n";
    let extra = "fix w all wall/gran model hertz tangential history mesh n_meshes 1 meshes a b";
    fails_alike(
        &dir,
        &format!("{MATERIAL}{meshes}{extra}"),
        "Fix wall/gran (id w): Unknown argument or wrong keyword order: 'b'",
        17,
    );
    for mode in [&["check", "in.t"][..], &["-in", "in.t", "-log", "none"]] {
        let out = regolith(&dir, mode);
        let all = text(&out.stdout) + &text(&out.stderr);
        assert!(
            all.contains("'b' is a mesh: the meshes listed outnumber n_meshes"),
            "{all}"
        );
    }
    fails_alike(
        &dir,
        "fix a all mesh/surface/omp file left.stl type 1",
        "Fix mesh/surface/omp (id a): unknown keyword in style definition: mesh/surface/omp (omp)",
        11,
    );
}

/// After a shell command whose effects check cannot follow, a problem check finds is said
/// as a warning instead of passing in silence (a transfer-chute deck symlinking its output
/// folder passed check with no word and stopped at its first insertion).
#[test]
fn check_says_what_a_run_may_stop_at_after_a_shell_command() {
    let dir = scratch("uncertain");
    std::fs::write(
        dir.join("face.stl"),
        "solid f\nfacet normal 0 0 -1\nouter loop\nvertex 0.02 0.02 0.1\nvertex 0.02 0.08 0.1\nvertex 0.08 0.08 0.1\nendloop\nendfacet\nendsolid f\n",
    )
    .unwrap();
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.003
fix pdd1 all particledistribution/discrete 32452843 1 pts1 1.0
fix face all mesh/surface file face.stl type 1
fix ins all insert/stream seed 49979687 distributiontemplate pdd1 nparticles 10 particlerate 1000 vel constant 0 0 -1 insertion_face face extrude_length 0.05
fix integr all nve/sphere
shell ln -s . here
run 10
"
    );
    std::fs::write(dir.join("in.t"), &deck).unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("in.t:24: warning: a run may stop here (check cannot be sure after a command whose effects it cannot follow): Fix insert/stream (id ins): insertion volume could not be distributed properly in parallel"),
        "{stdout}"
    );
    // without the shell command the same problem is check's own error (status 1), as the
    // run's first insertion stops there
    let certain = deck.replace("shell ln -s . here\n", "");
    stops_deck(
        &dir,
        &certain,
        "Fix insert/stream (id ins): insertion volume could not be distributed properly in parallel",
        23,
        1,
    );
}

/// A model keyword after the on/off settings' place (cohesion after rolling_friction, as an
/// auger-dosing deck generator writes it when cohesion is on) is LIGGGHTS's "Unknown
/// argument or wrong keyword order" (pair_gran_base.h:129), not a setting regolith lacks.
#[test]
fn a_pair_model_keyword_out_of_order_is_liggghts_s_error() {
    let dir = scratch("pair_order");
    fails_alike(
        &dir,
        &format!("{MATERIAL}pair_style gran model hertz tangential history rolling_friction epsd2 cohesion sjkr\npair_coeff * *"),
        "Unknown argument or wrong keyword order: 'cohesion'",
        15,
    );
    // a known setting with a value that is not on/off
    fails_alike(
        &dir,
        &format!("{MATERIAL}pair_style gran model hertz tangential history rolling_friction epsd2 torsionTorque 1\npair_coeff * *"),
        "while parsing 'torsionTorque' argument: unknown option or wrong keyword order: '1'",
        15,
    );
}

/// `compute erotate` prints `igrpu: GROUP` with `printf` when it is defined, as LIGGGHTS
/// 3.8.0's constructor does (an angle-of-repose deck's screen has it after its mesh's
/// `Reading STL file` line): on standard output, not in the log; a second one is
/// LIGGGHTS's "Reuse of compute ID".
#[test]
fn compute_erotate_prints_its_group_as_liggghts_does() {
    let dir = scratch("erotate_printf");
    let deck = format!(
        "{HEAD}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
         region sub block 0 0.05 0 0.1 0 0.1 units box\ngroup half region sub\n\
         compute er half erotate\nprint done\n"
    );
    std::fs::write(dir.join("in.t"), &deck).unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "log.t"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("igrpu: half\ndone\n"),
        "{}",
        text(&out.stdout)
    );
    let log = std::fs::read_to_string(dir.join("log.t")).unwrap();
    assert!(!log.contains("igrpu"), "{log}");
    let twice = deck.replace("print done\n", "compute er2 all erotate\n");
    std::fs::write(dir.join("in.t"), twice).unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).contains("Reuse of compute ID"),
        "{}",
        text(&out.stderr)
    );
}

/// A `dump_modify` keyword LIGGGHTS 3.8.0 does not have (`domainfile`, of LIGGGHTS-PFM's
/// VTK dumps, in a forked test deck) is its "Illegal dump_modify command" in `check` and in
/// a run, as Debian's LIGGGHTS 3.8.0 says (regolith said "not supported yet").
#[test]
fn an_unknown_dump_modify_keyword_is_illegal() {
    let dir = scratch("dump_modify_unknown");
    std::fs::create_dir_all(dir.join("post")).unwrap();
    fails_alike(
        &dir,
        "dump d all custom/vtk 10 post/d*.vtk id type x y z\ndump_modify d domainfile no",
        "Illegal dump_modify command",
        12,
    );
}

/// Multisphere templates of several types: each template's insertion generator is its
/// seed when an insertion checks the seeds (regolith took every clump template's as 0 and
/// refused a hopper deck of four clump shapes with LIGGGHTS's "seeds ... are different"),
/// and the run's init checks their types as LIGGGHTS's first template does: unique, and 1
/// to their count (Debian's LIGGGHTS 3.8.0 runs the first deck and refuses the others
/// with these words).
#[test]
fn multisphere_template_seeds_and_types_as_liggghts_checks_them() {
    let dir = scratch("clump_types");
    let clump = |id: &str, seed: u32, ty: u32| {
        format!(
            "fix {id} all particletemplate/multisphere {seed} atom_type 1 density constant 2500 \
             nspheres 2 ntry 10000 spheres 0 0 0 0.004 0.005 0 0 0.003 type {ty}\n"
        )
    };
    let deck = |t2: u32| {
        format!(
            "{}{MATERIAL}pair_style gran model hertz tangential history\npair_coeff * *\n\
             timestep 0.00001\n{}{}\
             fix pdd all particledistribution/discrete/numberbased 15485867 2 pts1 0.5 pts2 0.5\n\
             region bc block 0.02 0.08 0.02 0.08 0.02 0.08 units box\n\
             fix ins all insert/pack seed 32452843 distributiontemplate pdd vel constant 0 0 0 \
             insert_every once overlapcheck yes region bc ntry_mc 10000 particles_in_region 6\n\
             fix integr all multisphere\nrun 1\n",
            HEAD.replace("p p f", "f f f"),
            clump("pts1", 15485863, 1),
            clump("pts2", 67867967, t2)
        )
    };
    std::fs::write(dir.join("in.t"), deck(2)).unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("inserted 6 particle templates"));
    let fix = "Fix particletemplate/multisphere (id pts1): multisphere template types have to be";
    stops_deck(&dir, &deck(1), &format!("{fix} unique"), 24, 1);
    stops_deck(
        &dir,
        &deck(3),
        &format!("{fix} consecutive starting from 1"),
        24,
        1,
    );
}
