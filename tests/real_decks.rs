//! Researchers' own decks (issue 15): what `check` and `run` report on them, each problem at
//! its own line, and the commands they use.

use std::path::PathBuf;
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("regolith-real-{}-{name}", std::process::id()));
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
         fix heat all heat/gran initial_temperature 300\n\
         fix pts all particletemplate/sphere 12345 atom_type 1 density constant 2500 radius constant 0.003\n"
    );
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let out = regolith(&dir, &["check", "in.t"]);
    let stdout = text(&out.stdout);
    assert!(
        stdout.starts_with("in.t:17: fix heat/gran: not supported yet\n"),
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
