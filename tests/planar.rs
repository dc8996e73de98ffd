//! 2d runs (`dimension 2`): the errors LIGGGHTS 3.8.0 gives for 2d decks (each message as
//! Debian's `liggghts` prints it for the same deck), and the 2d features regolith does not
//! run yet, refused alike by `check` and by a run. The runs themselves are compared with
//! LIGGGHTS by the engine decks `planar_pile` and `planar_periodic` (tests/compat_engine.rs).

mod common;

use std::process::Command;

const HEAD_2D: &str = "dimension 2
atom_style granular
atom_modify map array
boundary p f p
newton off
communicate single vel yes
units si
region box block 0 0.1 0 0.1 -0.005 0.005 units box
create_box 1 box
";

/// Run `deck` (written as `in.t` in a fresh directory); (exit status, stdout and stderr).
fn run(name: &str, deck: &str) -> (Option<i32>, String) {
    let dir = common::scratch_dir(&format!("planar-{name}"));
    let out = common::run_deck(&dir, "in.t", deck, &[]);
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.code(), text)
}

/// `regolith check` of `deck`; (exit status, stdout and stderr).
fn check(name: &str, deck: &str) -> (Option<i32>, String) {
    let dir = common::scratch_dir(&format!("planar-check-{name}"));
    std::fs::write(dir.join("in.t"), deck).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["check", "in.t"])
        .current_dir(&dir)
        .output()
        .unwrap();
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    (out.status.code(), text)
}

/// The deck fails (exit status 1) with `message` among its errors.
fn fails_with(name: &str, deck: &str, message: &str) {
    let (status, text) = run(name, deck);
    assert_eq!(status, Some(1), "{text}");
    assert!(text.contains(message), "missing {message:?} in:\n{text}");
    assert!(!text.contains("panicked"), "{text}");
}

fn head_3d() -> String {
    HEAD_2D.replace("dimension 2", "dimension 3")
}

#[test]
fn z_must_be_periodic() {
    fails_with(
        "zfixed",
        &HEAD_2D.replace("boundary p f p", "boundary p f f"),
        "Cannot run 2d simulation with nonperiodic Z dimension",
    );
}

#[test]
fn dimension_errors_are_liggghts_s() {
    fails_with("dim4", "dimension 4\n", "Illegal dimension command");
    fails_with(
        "dimafter",
        &format!("{HEAD_2D}dimension 2\n"),
        "Dimension command after simulation box is defined",
    );
}

#[test]
fn lattices_must_match_the_dimension() {
    let incompatible = "Lattice style incompatible with simulation dimension";
    fails_with(
        "sq3",
        &format!("{}lattice sq 0.01\n", head_3d()),
        incompatible,
    );
    fails_with(
        "hex3",
        &format!("{}lattice hex 0.01\n", head_3d()),
        incompatible,
    );
    fails_with(
        "fcc2",
        &format!("{HEAD_2D}lattice fcc 0.01\n"),
        incompatible,
    );
    fails_with(
        "origin2",
        &format!("{HEAD_2D}lattice sq 0.01 origin 0 0 0.5\n"),
        "Lattice settings are not compatible with 2d simulation",
    );
}

#[test]
fn enforce2d_needs_a_2d_run() {
    fails_with(
        "enf3",
        &format!(
            "{}neighbor 0.002 bin\nfix e all enforce2d\nrun 1\n",
            head_3d()
        ),
        "Cannot use fix enforce2d with 3d simulation",
    );
    fails_with(
        "enfarg",
        &format!("{HEAD_2D}fix e all enforce2d 1\n"),
        "Illegal fix enforce2d command",
    );
}

#[test]
fn velocities_stay_in_the_plane() {
    let atom = "create_atoms 1 single 0.05 0.05 0\n";
    fails_with(
        "vz",
        &format!("{HEAD_2D}{atom}velocity all set 0 0 1\n"),
        "Cannot set non-zero z velocity for 2d simulation",
    );
    fails_with(
        "vzvar",
        &format!("{HEAD_2D}{atom}variable a atom x\nvelocity all set 0 0 v_a\n"),
        "Cannot set variable z velocity for 2d simulation",
    );
    fails_with(
        "ramp",
        &format!("{HEAD_2D}{atom}velocity all ramp vz 0 1 x 0 1\n"),
        "Velocity ramp in z for a 2d problem",
    );
    // a zero or NULL z velocity is fine
    let (status, text) = run(
        "vz0",
        &format!("{HEAD_2D}{atom}velocity all set 0.1 0 0\nvelocity all set 0.1 0 NULL\n"),
    );
    assert_eq!(status, Some(0), "{text}");
}

#[test]
fn insertion_in_2d_is_refused_by_check_and_run_alike() {
    let deck = format!(
        "{HEAD_2D}fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.002\n"
    );
    let (status, text) = run("insert", &deck);
    assert!(!matches!(status, Some(0) | None), "{text}");
    assert!(text.contains("not supported yet"), "{text}");
    assert!(text.contains("in a 2d simulation"), "{text}");
    let (status, text) = check("insert", &deck);
    assert_ne!(status, Some(0), "{text}");
    assert!(text.contains("in a 2d simulation"), "{text}");
}

/// The 2d engine decks on the exact path: every dump byte for byte LIGGGHTS's (the engine
/// deck test allows round-off; 2d runs on the exact path have none).
#[test]
fn planar_decks_dump_byte_identical_to_liggghts() {
    let engine = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("compat/engine");
    for (name, dump) in [("planar_pile", "d2.dump"), ("planar_periodic", "flow.dump")] {
        let deck = std::fs::read_to_string(engine.join(format!("in.{name}"))).unwrap();
        let dir = common::scratch_dir(&format!("planar-deck-{name}"));
        let out = common::run_deck(&dir, &format!("in.{name}"), &deck, &[]);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let want = std::fs::read(engine.join(format!("{name}.ref/{dump}"))).unwrap();
        let got = std::fs::read(dir.join(dump)).unwrap();
        assert!(got == want, "{name}: {dump} differs from LIGGGHTS's");
        let thermo =
            std::fs::read_to_string(engine.join(format!("{name}.ref/thermo.txt"))).unwrap();
        let lines = common::thermo_lines(&String::from_utf8_lossy(&out.stdout));
        assert_eq!(lines, thermo.lines().collect::<Vec<_>>(), "{name}: thermo");
    }
}
