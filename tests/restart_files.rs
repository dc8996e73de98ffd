//! Restart files regolith writes: a run split by `write_restart` / `read_restart` continues
//! as the uninterrupted run (pair and wall history carried), `restart N root` writes one
//! file per interval with the step in the name, `restart N a b` alternates two files, and
//! every file written reads back.

mod common;

use std::path::Path;
use std::process::Command;

const SETUP: &str = "atom_modify map array\nneighbor 0.001 bin\nneigh_modify delay 0\n\
fix m1 all property/global youngsModulus peratomtype 5e6\n\
fix m2 all property/global poissonsRatio peratomtype 0.3\n\
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
fix m4 all property/global coefficientFriction peratomtypepair 1 0.7\n\
fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.3\n\
fix m6 all property/global coefficientRollingViscousDamping peratomtypepair 1 0.5\n\
pair_style gran model hertz tangential history rolling_friction epsd\npair_coeff * *\n\
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0\n\
fix gr all gravity 9.81 vector 0 0 -1\nfix integr all nve/sphere\ntimestep 1e-5\n\
thermo 100\n";

const HEAD: &str = "units si\natom_style granular\nboundary p p f\nnewton off\n\
communicate single vel yes\n";

fn run(dir: &Path, name: &str, deck: &str) {
    std::fs::write(dir.join(name), deck).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["-in", name, "-log", "none"])
        .current_dir(dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{name}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn split_runs_continue_and_restart_files_rotate() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-restarts-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let create = "region reg block 0 0.02 0 0.02 0 0.04 units box\ncreate_box 1 reg\n\
        lattice sc 0.004 origin 0.5 0.5 0.5\nregion fill block 0 5 0 5 0 4 units lattice\n\
        create_atoms 1 region fill\nset group all diameter 0.0038 density 2500\n\
        displace_atoms all random 0.0001 0.0001 0.0001 10007 units box\n";
    let dump = "dump d all custom 4000 end.dump id x y z vx vy vz fx fy fz omegax omegay omegaz\n\
        dump_modify d format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\" sort id\n";
    // uninterrupted: 4000 steps (contacts with the floor and each other form by then)
    run(
        &dir,
        "in.whole",
        &format!("{HEAD}{create}{SETUP}restart 1000 r.*\nrestart 1500 a.rst b.rst\nrun 3000\n{dump}run 1000\n"),
    );
    std::fs::rename(dir.join("end.dump"), dir.join("whole.dump")).unwrap();
    for f in ["r.1000", "r.2000", "r.3000", "a.rst", "b.rst"] {
        assert!(dir.join(f).exists(), "{f} not written");
    }
    // a.rst was written at step 1500, b.rst at 3000 (a is next in turn at 4500)
    // split: the restart of step 3000 read into a fresh deck, then 1000 steps
    run(
        &dir,
        "in.split",
        &format!("{HEAD}read_restart r.3000\n{SETUP}{dump}run 1000\n"),
    );
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args([
            "diff",
            "whole.dump",
            "end.dump",
            "--steps",
            "4000",
            "--rtol",
            "1e-9",
        ])
        .current_dir(&dir)
        .output()
        .unwrap();
    let report = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "{report}");
    assert!(report.contains("1 steps compared"), "{report}");
    // the alternating pair: b.rst holds step 3000, a.rst step 1500
    for (f, step) in [("a.rst", 1500), ("b.rst", 3000), ("r.2000", 2000)] {
        let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
            .args(["convert", f, &format!("{f}.data"), "--from", "restart"])
            .current_dir(&dir)
            .output()
            .unwrap();
        let summary = String::from_utf8_lossy(&out.stdout);
        assert!(summary.contains(&format!("step {step}")), "{f}: {summary}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_deck_that_writes_then_reads_a_restart_checks_and_runs() {
    let dir = common::scratch_dir("restart-check");
    let deck = format!(
        "{HEAD}region reg block 0 0.02 0 0.02 0 0.04 units box\ncreate_box 1 reg\n\
         create_atoms 1 single 0.01 0.01 0.01\nset group all diameter 0.002 density 2500\n\
         write_restart mid.restart\nclear\n{HEAD}read_restart mid.restart\nprint \"atoms $(atoms)\"\n"
    );
    // the check before running must see the restart the deck writes (it does not exist yet)
    run(&dir, "in.deck", &deck);
    assert!(dir.join("mid.restart").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A primitive wall without a tangential history (LIGGGHTS's default `tangential off`, or
/// `no_history`) keeps no per-atom history, so a restart file names none for it, as
/// LIGGGHTS's; one with `tangential history` does.
#[test]
fn history_free_walls_leave_no_history_in_restart_files() {
    let dir = common::scratch_dir("restart-walls");
    let deck = format!(
        "{HEAD}region reg block 0 0.02 0 0.02 0 0.04 units box\ncreate_box 1 reg\n\
         create_atoms 1 single 0.01 0.01 0.002 units box\nset atom 1 diameter 0.004 density 2500\n\
         {SETUP}fix plain all wall/gran model hertz primitive type 1 zplane 0.04\n\
         fix damped all wall/gran model hertz tangential no_history primitive type 1 xplane 0.0\n\
         run 10\nwrite_restart walls.restart\n"
    );
    run(&dir, "in.walls", &deck);
    let r = regolith::io::restart::read(&dir.join("walls.restart").to_string_lossy()).unwrap();
    let ids: Vec<&str> = r.peratom_fixes.iter().map(|f| f.id.as_str()).collect();
    assert!(ids.contains(&"history_floor"), "{ids:?}");
    assert!(
        !ids.iter()
            .any(|id| *id == "history_plain" || *id == "history_damped"),
        "{ids:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A stress mesh's restart state is LIGGGHTS's, byte for byte: regolith writes for the deck
/// `compat/engine/stress_reads.inputs/in.make_stress` (a worn mesh on a wiggle, reference
/// point given) the nodes, wear and the global part `[1, p_ref, 1, p_ref]` LIGGGHTS wrote in
/// `stress.restart` (which engine deck `stress_reads` reads).
#[test]
fn a_stress_mesh_is_stored_as_liggghts_stores_it() {
    let inputs = Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine/stress_reads.inputs");
    let dir = common::scratch_dir("restart-stress");
    std::fs::copy(inputs.join("square.stl"), dir.join("square.stl")).unwrap();
    let deck = std::fs::read_to_string(inputs.join("in.make_stress")).unwrap();
    run(&dir, "in.make_stress", &deck);
    let mesh = |path: &Path| {
        let r = regolith::io::restart::read(&path.to_string_lossy()).unwrap();
        let f = r.global_fixes.into_iter().find(|g| g.id == "cad").unwrap();
        assert_eq!(f.style, "mesh/surface/stress");
        f.state
    };
    let (got, want) = (
        mesh(&dir.join("stress.restart")),
        mesh(&inputs.join("stress.restart")),
    );
    let doubles = |b: &[u8]| -> Vec<f64> {
        b.chunks_exact(8)
            .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
            .collect()
    };
    let w = doubles(&want);
    // 32 triangles of 10 values and the wear, then the reference point twice
    assert_eq!(w[..3], [32.0, 11.0, 8.0]);
    let tail = &w[w.len() - 8..];
    assert_eq!([tail[0], tail[4]], [1.0, 1.0]);
    assert_eq!(tail[1..4], tail[5..8]);
    assert_eq!([tail[1], tail[2]], [0.001, 0.002]);
    // each record: its length 12, nine node values, the id, the wear
    let wear: f64 = (0..32).map(|k| w[3 + 12 * k + 11]).sum();
    assert!(wear > 0.0, "the particles wore the mesh");
    assert_eq!(doubles(&got), w);
    let _ = std::fs::remove_dir_all(&dir);
}
