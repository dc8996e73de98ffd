//! Everyday styles of researchers' decks (fix nve, nve/limit, lineforce, planeforce,
//! aveforce, ave/atom, viscous ... scale; compute msd, displace/atom, erotate/sphere/atom, reduce/region):
//! bad arguments get LIGGGHTS's error at their line, and what stays unfinished is refused
//! alike by `check` and `run`. Their results are compared with LIGGGHTS by the compat decks
//! integrators_forces, displacement_computes, ave_atom and group_functions.

use std::path::PathBuf;
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-everyday-{}-{name}", std::process::id()));
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

#[test]
fn bad_arguments_get_liggghts_errors() {
    let dir = scratch("errors");
    for (body, needle) in [
        ("fix f all nve extra", "Illegal fix nve command"),
        (
            "fix_modify nowhere energy no",
            "Could not find fix_modify ID",
        ),
        (
            "fix f all nve/sphere\nfix_modify f",
            "Illegal fix_modify command",
        ),
        (
            "fix f all nve/sphere\nfix_modify f energy maybe",
            "Illegal fix_modify command",
        ),
        (
            "fix f all nve/sphere\nfix_modify f temp t",
            "Illegal fix_modify command",
        ),
        // a keyword LIGGGHTS refuses beats one regolith does not run yet
        (
            "fix g all gravity 9.81 vector 0 0 -1\nfix_modify g energy yes temp t",
            "Illegal fix_modify command",
        ),
        // one atom type here: type 2 is out of range
        (
            "fix f all viscous 0.1 scale 2 2.0",
            "Illegal fix viscous command",
        ),
        (
            "fix f all viscous 0.1 scale 1",
            "Illegal fix viscous command",
        ),
        (
            "fix f all viscous 0.1 scal 1 2",
            "Illegal fix viscous command",
        ),
        ("fix f all viscous", "Illegal fix viscous command"),
        (
            "fix f all nve/limit relative 0.1",
            "expecting keyword 'absolute' or 'radius_ratio'",
        ),
        (
            "fix f all nve/limit absolute",
            "Illegal fix nve/limit command",
        ),
        ("fix f all lineforce 0 0 0", "Illegal fix lineforce command"),
        ("fix f all planeforce 0 1", "Illegal fix planeforce command"),
        ("fix f all aveforce 0 0", "Illegal fix aveforce command"),
        (
            "fix f all aveforce 0 0 0 bogus",
            "Illegal fix aveforce command",
        ),
        (
            "fix f all ave/atom 10 5 100",
            "Illegal fix ave/atom command",
        ),
        (
            "fix f all ave/atom 10 20 100 vx",
            "Illegal fix ave/atom command",
        ),
        (
            "fix f all ave/atom 10 5 100 radius",
            "Illegal fix ave/atom command",
        ),
        (
            "fix f all ave/atom 10 5 100 c_none",
            "Compute ID for fix ave/atom does not exist",
        ),
        (
            "variable e equal 1\nfix f all ave/atom 10 5 100 v_e",
            "Fix ave/atom variable is not atom-style variable",
        ),
        (
            "compute r all reduce/region nowhere sum vx",
            "Region ID for compute reduce/region does not exist",
        ),
        (
            "compute r all reduce/region reg sum",
            "Illegal compute reduce/region command",
        ),
        ("compute m all msd com maybe", "Illegal compute msd command"),
        (
            "compute d all displace/atom com yes",
            "Illegal compute displace/atom command",
        ),
        (
            "compute e all erotate/sphere/atom extra",
            "Illegal compute erotate/sphere/atom command",
        ),
        // compute coord/atom and contact/atom (messages printed by Debian's LIGGGHTS)
        (
            "compute c all coord/atom",
            "Compute coord/atom (id c): Illegal # of arguments",
        ),
        ("compute c all coord/atom 0.003 2", "is out of bounds"),
        (
            "compute c all coord/atom 0.003 mix maybe",
            "Compute coord/atom (id c): valid arguments for 'mix' are 'yes' or 'no'",
        ),
        (
            "compute c all coord/atom abc",
            "Expected floating point parameter",
        ),
        (
            "compute c all contact/atom skan 1",
            "Illegal compute contact/atom command, expecting keyword 'skin'",
        ),
        (
            "compute c all coord/atom 0.003\nrun 0",
            "Compute coord/atom requires a pair style be defined",
        ),
        // fix store/state
        ("fix s all store/state 0", "Illegal fix store/state command"),
        (
            "fix s all store/state -1 x",
            "Illegal fix store/state command",
        ),
        (
            "fix s all store/state 0 x com maybe",
            "Illegal fix store/state command",
        ),
        (
            "fix s all store/state 0 x bogus",
            "Illegal fix store/state command",
        ),
        (
            "fix s all store/state 0 q",
            "Fix store/state for atom property that isn't allocated",
        ),
        (
            "fix s all store/state 0 c_none",
            "Compute ID for fix store/state does not exist",
        ),
        (
            "compute k all ke/atom\nfix s all store/state 0 c_k[1]",
            "Fix store/state compute does not calculate a per-atom array",
        ),
        (
            "compute d all displace/atom\nfix s all store/state 0 c_d",
            "Fix store/state compute does not calculate a per-atom vector",
        ),
        (
            "compute d all displace/atom\nfix s all store/state 0 c_d[5]",
            "Fix store/state compute array is accessed out-of-range",
        ),
        (
            "fix s all store/state 0 f_none",
            "Fix ID for fix store/state does not exist",
        ),
        (
            "variable e equal 1\nfix s all store/state 0 v_e",
            "Fix store/state variable is not atom-style variable",
        ),
        (
            "fix s all store/state 0 v_none",
            "Variable name for fix store/state does not exist",
        ),
        // fix ave/spatial
        (
            "fix a all ave/spatial 10 5 100 q lower 0.005 vx",
            "Illegal fix ave/spatial command",
        ),
        (
            "fix a all ave/spatial 10 5 100 z lower 0.005 z lower 0.01 vx",
            "Same dimension twice in fix ave/spatial",
        ),
        (
            "fix a all ave/spatial 10 5 100 z lower 0.005 vx norm maybe",
            "Illegal fix ave/spatial command",
        ),
        (
            "fix a all ave/spatial 10 5 100 z lower 0.005 vx overwrite",
            "Illegal fix ave/spatial command",
        ),
        (
            "fix a all ave/spatial 10 5 100 z lower 0.005 c_none",
            "Compute ID for fix ave/spatial does not exist",
        ),
        (
            "fix a all ave/spatial 10 5 100 z lower 0.005 vx region nowhere",
            "Region ID for fix ave/spatial does not exist",
        ),
        (
            "fix a all ave/spatial 10 20 100 z lower 0.005 vx",
            "Illegal fix ave/spatial command",
        ),
        (
            "fix a all ave/spatial 10 5 100 z lower 0 vx",
            "Illegal fix ave/spatial command",
        ),
        (
            "fix a all ave/spatial 10 5 100 z lower 0.005 vx file nodir/a.txt",
            "Cannot open fix ave/spatial file nodir/a.txt",
        ),
        // fix ave/histo
        (
            "fix h all ave/histo 10 5 100 0 1 4 vx",
            "Fix ave/histo cannot input per-atom values in scalar mode",
        ),
        (
            "fix h all ave/histo 10 5 100 1 0 4 vx mode vector",
            "Illegal fix ave/histo command",
        ),
        (
            "fix h all ave/histo 10 5 100 0 1 0 vx mode vector",
            "Illegal fix ave/histo command",
        ),
        (
            "fix h all ave/histo 10 5 100 0 1 4 vx mode vector beyond maybe",
            "Illegal fix ave/histo command",
        ),
        (
            "fix h all ave/histo 10 5 100 0 1 4 c_none mode vector",
            "Compute ID for fix ave/histo does not exist",
        ),
        (
            "fix h all ave/histo 10 5 100 0 1 4 vx mode vector overwrite",
            "Illegal fix ave/histo command",
        ),
        // thermo keywords in formulas
        (
            "thermo_style custom step\nvariable e equal erotate\nprint \"${e}\"",
            "Thermo keyword in variable requires thermo to use/init erotate",
        ),
        (
            "variable e equal elaplong\nprint \"${e}\"",
            "This variable thermo keyword cannot be used between runs",
        ),
    ] {
        std::fs::write(dir.join("in.t"), format!("{HEAD}{body}\n")).unwrap();
        let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{body}: {err}");
        assert!(err.contains(needle), "{body}: {err}");
    }
}

#[test]
fn unfinished_keywords_are_refused_by_check_and_run_alike() {
    let dir = scratch("refused");
    for (body, needle) in [
        (
            "variable f equal 1\nfix f all aveforce v_f 0 0",
            "fix aveforce with variables: not supported yet",
        ),
        (
            "fix f all aveforce 0 0 0 region reg",
            "fix aveforce region: not supported yet",
        ),
        (
            "fix g all gravity 9.81 vector 0 0 -1\nfix_modify g energy yes",
            "fix_modify energy yes on fix gravity (its energy in compute pe): not supported yet",
        ),
    ] {
        std::fs::write(dir.join("in.t"), format!("{HEAD}{body}\n")).unwrap();
        let run = regolith(&dir, &["-in", "in.t", "-log", "none"]);
        let err = text(&run.stderr);
        assert_ne!(run.status.code(), Some(0), "{body}: {err}");
        assert!(err.contains(needle), "{body}: {err}");
        let check = regolith(&dir, &["check", "in.t"]);
        let said = text(&check.stdout);
        assert_ne!(check.status.code(), Some(0), "{body}: {said}");
        assert!(said.contains(needle), "{body}: {said}");
    }
}

#[test]
fn fix_modify_energy_of_a_fix_without_energy_changes_nothing() {
    // LIGGGHTS accepts it; a granular fix adds no energy, so the run is the same
    let dir = scratch("fix_modify");
    let body = "create_atoms 1 single 0.05 0.05 0.05 units box
set type 1 diameter 0.01 density 2500
velocity all set 0.1 0 0
fix f all nve/sphere
fix_modify f energy yes energy no
thermo_style custom step ke
atom_modify sort 0 0
run 10
";
    std::fs::write(dir.join("in.t"), format!("{HEAD}{body}")).unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    // ke = m v^2 / 2 of one 1 cm sphere of 2500 kg/m^3 at 0.1 m/s
    let stdout = text(&out.stdout);
    assert!(
        stdout
            .lines()
            .any(|l| l.split_whitespace().eq(["10", "6.5449847e-06"])),
        "{stdout}"
    );
}
