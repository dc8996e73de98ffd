//! `fix mesh/surface/stress/servo` against Debian's LIGGGHTS: the servo decks of
//! compat/engine (a plate driven by the PID controller, and by the auto mode, compressing a
//! bed of 324 spheres to a target force) give LIGGGHTS's thermo lines (plate force, torque
//! and position to 15 digits) and particle dumps byte for byte; bad settings are refused as
//! LIGGGHTS refuses them, and what regolith does not run yet is refused as such.

use std::path::Path;

mod common;

use common::{run_deck, scratch_dir, thermo_lines};

fn engine_dir() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/compat/engine"))
}

/// Run compat/engine/in.NAME in a scratch copy; its thermo lines must be LIGGGHTS's and every
/// reference dump identical byte for byte.
fn bit_identical(name: &str) {
    let dir = scratch_dir(&format!("servo-{name}"));
    for e in std::fs::read_dir(engine_dir().join(format!("{name}.inputs"))).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), dir.join(e.file_name())).unwrap();
    }
    let deck = std::fs::read_to_string(engine_dir().join(format!("in.{name}"))).unwrap();
    let out = run_deck(&dir, &format!("in.{name}"), &deck, &[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{name} failed:\n{stdout}");
    let reference = engine_dir().join(format!("{name}.ref"));
    let want = std::fs::read_to_string(reference.join("thermo.txt")).unwrap();
    assert_eq!(
        thermo_lines(&stdout),
        want.lines().collect::<Vec<_>>(),
        "{name}: thermo"
    );
    let mut dumps = 0;
    for e in std::fs::read_dir(reference.join("post")).unwrap() {
        let e = e.unwrap();
        let got = std::fs::read(dir.join("post").join(e.file_name())).unwrap_or_default();
        assert!(
            std::fs::read(e.path()).unwrap() == got,
            "{name}: {:?} differs from LIGGGHTS's",
            e.file_name()
        );
        dumps += 1;
    }
    assert_eq!(dumps, 1, "{name}: one dump file");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn pid_servo_is_bit_identical_to_liggghts() {
    bit_identical("servo_compress");
}

#[test]
fn auto_mode_servo_is_bit_identical_to_liggghts() {
    bit_identical("servo_auto");
}

const BASE: &str = "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region domain block -0.0105 0.0105 -0.0105 0.0105 -0.001 0.03 units box
create_box 1 domain
neighbor 0.001 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 1e-5
create_atoms 1 single 0 0 0.005 units box
set group all diameter 0.002 density 2500
fix integr all nve/sphere
";

const SERVO: &str =
    "fix servo all mesh/surface/stress/servo file plate.stl type 1 move 0. 0. 0.0095";
const WALL: &str =
    "fix top all wall/gran model hertz tangential history mesh n_meshes 1 meshes servo";

/// The combined output of the base deck with `rest` appended.
fn run_with(rest: &str, tag: &str) -> (bool, String) {
    let dir = scratch_dir(&format!("servo-err-{tag}"));
    std::fs::copy(
        engine_dir().join("servo_auto.inputs/plate.stl"),
        dir.join("plate.stl"),
    )
    .unwrap();
    let out = run_deck(&dir, "in.t", &format!("{BASE}{rest}\n"), &[]);
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(&dir);
    (out.status.success(), text)
}

#[test]
fn bad_servo_settings_are_refused_as_liggghts_refuses_them() {
    let ok = "com 0 0 0.0095 ctrlPV force axis 0 0 1 target_val -0.5";
    let cases = [
        (
            format!("{SERVO} ctrlPV force axis 0 0 1 target_val -0.5 vel_max 0.2\n{WALL}\nrun 1"),
            "please define 'com' for the mesh",
        ),
        (
            format!("{SERVO} com 0 0 0.0095 axis 0 0 1 target_val -0.5 vel_max 0.2\n{WALL}\nrun 1"),
            "Bad registration of upcoming move.",
        ),
        (
            format!("{SERVO} {ok} vel_max 80\n{WALL}\nrun 1"),
            "vel_max < skin/(2.*dt) required",
        ),
        (
            format!("{SERVO} {ok} vel_max 0.2\nrun 1"),
            "The servo-wall requires a contact model",
        ),
        (
            format!("{SERVO} {ok} vel_max 0.2\n{WALL}\nfix mv all move/mesh mesh servo linear 0 0 1\nrun 1"),
            "this fix does not allow superposition with moving mesh fixes",
        ),
        (
            format!("{SERVO} {ok} vel_max 0.2 mode auto\n{WALL}\nrun 1"),
            "please define 'ratio' for the mesh, since you use the auto mode",
        ),
        (
            format!("{SERVO} {ok} vel_max 0.2 kp 0\n{WALL}\nrun 1"),
            "kp, ki, and kd are zero. Please set a valid configuration",
        ),
        (
            format!("{SERVO} {ok} vel_max 0.2 kp -1\n{WALL}\nrun 1"),
            "kp, ki, and kd >= 0 required.",
        ),
        (
            format!("{SERVO} com 0 0 0.0095 ctrlPV velocity vel_max 0.2\n{WALL}\nrun 1"),
            "only 'force', 'torque' are valid arguments for ctrlPV",
        ),
        (
            format!("{SERVO} {ok} vel_max 0.2 mode manual\n{WALL}\nrun 1"),
            "mode supports only auto",
        ),
        (
            format!("{SERVO} {ok} vel_max 0\n{WALL}\nrun 1"),
            "vel_max > 0 required",
        ),
        (
            format!("{SERVO} {ok} vel_max 0.2 stress on\n{WALL}\nrun 1"),
            "wrong keyword order",
        ),
        // a variable set point names an equal-style variable, checked at the run's init
        // (LIGGGHTS: mesh_module_stress_servo.cpp:322)
        (
            format!("{SERVO} com 0 0 0.0095 ctrlPV force axis 0 0 1 target_val v_f vel_max 0.2\n{WALL}\nrun 1"),
            "Fix mesh/surface/stress/servo (id servo): Variable name does not exist",
        ),
    ];
    for (k, (rest, message)) in cases.iter().enumerate() {
        let (ok, text) = run_with(rest, &k.to_string());
        assert!(!ok, "case {k} ran:\n{rest}");
        assert!(
            text.contains(message),
            "case {k}: no {message:?} in\n{text}"
        );
        assert!(!text.contains("panicked"), "case {k} panicked:\n{text}");
    }
}

#[test]
fn what_is_not_run_yet_is_refused_as_not_supported() {
    let cases = [
        format!("{SERVO} com 0 0 0.0095 ctrlPV torque axis 0 0 1 target_val -0.5 vel_max 0.2\n{WALL}\nrun 1"),
        format!("{SERVO} com 0 0 0.0095 ctrlPV force axis 0 0 1 target_val -0.5 vel_max 0.2\n{WALL}\nrun 1\nwrite_restart r.restart"),
    ];
    for (k, rest) in cases.iter().enumerate() {
        let (ok, text) = run_with(rest, &format!("u{k}"));
        assert!(!ok, "case {k} ran:\n{rest}");
        assert!(
            text.contains("not supported yet"),
            "case {k}: not refused as unsupported:\n{text}"
        );
    }
}
