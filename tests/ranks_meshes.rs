//! Mesh walls on several ranks, in-process (N ranks are N threads joined by channels, each
//! running the whole deck as `mpirun -np N regolith -sf fast -in deck` would): compat decks
//! with static meshes (`fix mesh/surface` with `fix wall/gran ... mesh`) and meshes moved by
//! `fix move/mesh`, on grids that make particles touching a mesh migrate. Dumps are compared
//! with the serial fast path's (within 1e-10 of each column's scale) and between repeated
//! runs (bit for bit).

mod common;

use regolith::cli::DeckOptions;
use regolith::error::ExitStatus;
use regolith::util::comm::Ranks;

/// A fresh folder for one run, holding the mesh files of compat deck `name`.
fn scratch(name: &str, tag: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "regolith-ranks-meshes-{}-{tag}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(dir.join("post")).unwrap();
    let inputs = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("compat/engine")
        .join(format!("{name}.inputs"));
    for e in std::fs::read_dir(inputs).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), dir.join(e.file_name())).unwrap();
    }
    dir
}

/// The text of compat deck `name` with a `processors` line `grid` after `units si` and every
/// file name in `files` (meshes, dumps, restart files) moved into folder `dir`.
fn deck_in(name: &str, dir: &std::path::Path, grid: &str, files: &[&str]) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("compat/engine")
        .join(format!("in.{name}"));
    let mut text = std::fs::read_to_string(path).unwrap();
    text = text.replacen("units si\n", &format!("units si\n{grid}\n"), 1);
    for f in files {
        text = text.replace(f, &dir.join(f).to_string_lossy());
    }
    text
}

/// Run `text` in folder `dir` on `n` ranks (0: the serial fast path); each rank's status
/// must be success.
fn run(dir: &std::path::Path, text: &str, n: usize) {
    let path = dir.join("in.deck");
    std::fs::write(&path, text).unwrap();
    let opts = |size: usize, rank: usize| DeckOptions {
        input: Some(path.to_string_lossy().into_owned()),
        log: Some("none".into()),
        screen: Some("none".into()),
        fast: true,
        threads: Some(1),
        ranks: Ranks {
            size,
            rank,
            per_node: size,
        },
        ..DeckOptions::default()
    };
    let status = common::run_on_ranks(n, |size: usize, rank: usize| opts(size.max(1), rank));
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{} on {n} ranks: {status:?}",
        dir.display()
    );
}

/// The dumps `dumps` (file names in the folder) of compat deck `name` run on `n` ranks with
/// `processors` line `grid` (`files` moved into the run's folder).
fn dumps_of(name: &str, files: &[&str], dumps: &[&str], n: usize, grid: &str) -> Vec<String> {
    let tag = format!("{name}-{n}-{}", grid.replace(' ', ""));
    let dir = scratch(name, &tag);
    run(&dir, &deck_in(name, &dir, grid, files), n);
    let out = dumps
        .iter()
        .map(|d| std::fs::read_to_string(dir.join(d)).unwrap())
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    out
}

/// Compat deck `name` on the serial fast path and on the rank grids `grids`: every dump of
/// `dumps` within 1e-10 of each column's scale of the serial one, the first grid's dumps
/// the same bits when run again. The serial dumps.
fn on_grids(name: &str, files: &[&str], dumps: &[&str], grids: &[(usize, &str)]) -> Vec<String> {
    let serial = dumps_of(name, files, dumps, 0, "");
    for (k, &(n, grid)) in grids.iter().enumerate() {
        let got = dumps_of(name, files, dumps, n, grid);
        for ((a, b), d) in serial.iter().zip(&got).zip(dumps) {
            let dev = common::scale_deviation(a, b);
            assert!(dev < 1e-10, "{name} {d}: {grid} differs by {dev:e}");
        }
        if k == 0 {
            let again = dumps_of(name, files, dumps, n, grid);
            assert!(again == got, "{name}: {grid} run twice gave other dumps");
        }
    }
    serial
}

#[test]
fn spheres_on_a_static_mesh_on_ranks_match_the_serial_fast_path() {
    // sphere 3 slides across the square's diagonal and across y = 0, the cut of the 1 2 1
    // grid, while touching the mesh: its mesh contact history moves to the other rank
    let files = ["square.stl", "dump.sqd"];
    let grids = [
        (2, "processors 1 2 1"),
        (3, "processors 1 3 1"),
        (2, "processors 2 1 1"),
        (3, "processors 3 1 1"),
    ];
    let serial = on_grids("mesh_square_drop", &files, &["dump.sqd"], &grids);
    let snaps = regolith::io::dump_compare::parse(&serial[0]).unwrap();
    assert_eq!(snaps.len(), 21, "steps 0..2000 every 100");
    // sphere 3 slides on the mesh all the way (overlapping it, held up against its weight)
    // and crosses the cut at y = 0
    let col = |name: &str| snaps[0].columns.iter().position(|c| c == name).unwrap();
    let (y, z, fz) = (col("y"), col("z"), col("fz"));
    let weight = 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 0.005f64.powi(3) * 9.81;
    for s in &snaps[1..] {
        let r = &s.rows[&3];
        assert!(
            r[z] < 0.005 && r[fz] > -0.5 * weight,
            "step {}: {r:?}",
            s.step
        );
    }
    let last = snaps.last().unwrap();
    assert!(snaps[0].rows[&3][y] > 0.0 && last.rows[&3][y] < -0.002);
}

/// The files `post/*` compat deck `in.move_mesh_restart` writes, run on `n` ranks (0: the
/// serial fast path) with `processors` line `grid`: its two phases (a run, a restart file
/// written mid-motion, a second run; then the file read and the second run again) as two
/// decks in one folder, by file name.
fn moving_mesh_files(n: usize, grid: &str) -> std::collections::BTreeMap<String, String> {
    let name = "move_mesh_restart";
    let dir = scratch(name, &format!("{n}-{}", grid.replace(' ', "")));
    let files = ["left.stl", "right.stl", "post/"];
    let text = deck_in(name, &dir, grid, &files);
    // one phase per deck: the loop's `clear` and `jump` are the script's, not the run's
    let script = ["label", "clear", "next", "jump", "shell"];
    let body: String = text
        .lines()
        .filter(|l| !script.contains(&l.split(' ').next().unwrap_or("")))
        .map(|l| format!("{l}\n"))
        .collect();
    for phase in ["1", "2"] {
        let deck = body.replace(
            "variable phase loop 2",
            &format!("variable phase index {phase}"),
        );
        run(&dir, &deck, n);
    }
    let mut out = std::collections::BTreeMap::new();
    for e in std::fs::read_dir(dir.join("post")).unwrap() {
        let e = e.unwrap();
        let file = e.file_name().to_string_lossy().into_owned();
        if file.ends_with(".dump") {
            out.insert(file, std::fs::read_to_string(e.path()).unwrap());
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    out
}

#[test]
fn spheres_on_moving_meshes_through_a_restart_on_ranks_match_the_serial_fast_path() {
    let serial = moving_mesh_files(0, "");
    // phase 1: steps 0..5500 every 500; phase 2: 2750..5500 from the restart file
    assert_eq!(serial.len(), 12 + 6, "{:?}", serial.keys());
    let grids = [
        (2, "processors 2 1 1"),
        (3, "processors 3 1 1"),
        (2, "processors 1 1 2"),
    ];
    for (k, (n, grid)) in grids.into_iter().enumerate() {
        let got = moving_mesh_files(n, grid);
        assert!(got.keys().eq(serial.keys()), "{grid}: {:?}", got.keys());
        for (file, text) in &serial {
            let d = common::scale_deviation(text, &got[file]);
            assert!(d < 1e-10, "{file}: {grid} differs by {d:e}");
        }
        if k == 0 {
            assert!(moving_mesh_files(n, grid) == got, "{grid} run twice");
        }
    }
    // the continuation from the restart file is the run that went on (the meshes' motion
    // and the spheres' mesh contacts restored)
    let a = &serial["phase1_5500.dump"];
    let b = &serial["phase2_5500.dump"];
    assert!(common::scale_deviation(a, b) < 1e-6);
}

/// The problems `regolith check` finds in `text` on two ranks (fast path).
fn check_on_two(text: &str) -> Vec<String> {
    let opts = DeckOptions {
        fast: true,
        ranks: Ranks {
            size: 2,
            rank: 0,
            per_node: 2,
        },
        ..DeckOptions::default()
    };
    let source = regolith::script::interp::Source::from_text("in.deck", text, false);
    regolith::session::check_deck(source, &opts)
        .iter()
        .map(|d| d.one_line())
        .collect()
}

#[test]
fn mesh_walls_pass_the_check_on_ranks_and_what_sums_over_ranks_is_refused() {
    let dir = scratch("mesh_square_drop", "check");
    let deck = deck_in("mesh_square_drop", &dir, "", &["square.stl"]);
    assert_eq!(check_on_two(&deck), Vec::<String>::new());
    let wall = "fix wall all wall/gran model hertz tangential history mesh";
    for (from, to, refused) in [
        (
            "fix sq all mesh/surface file",
            "fix sq all mesh/surface/stress file",
            "fix mesh/surface/stress",
        ),
        (
            wall,
            "fix mc all multicontact/halfspace 1\nfix wall all wall/gran model hertz tangential history surface multicontact mesh",
            "fix multicontact/halfspace",
        ),
        (
            wall,
            "fix wall all wall/gran model hertz tangential history surface multicontact mesh",
            "fix wall/gran with surface multicontact",
        ),
    ] {
        let text = deck.replace(from, to);
        let got = check_on_two(&text);
        let want = format!("{refused} on more than one MPI rank: not supported yet");
        assert!(
            got.first().is_some_and(|g| g.contains(&want)),
            "{to}: {got:?}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn dump_mesh_stl_on_ranks_writes_what_one_process_writes() {
    // every rank holds the meshes whole, moved alike: rank 0 writes one process's file
    let files = ["mesh.stl", "insertion_face.stl", "post/mesh_stl"];
    let dumps = ["post/mesh_stl0.stl", "post/mesh_stl10.stl"];
    let serial = dumps_of("mesh_stl", &files, &dumps, 0, "");
    assert!(serial[1].starts_with("solid") && serial[1].matches("facet normal").count() == 94);
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 1 1 3")] {
        let got = dumps_of("mesh_stl", &files, &dumps, n, grid);
        assert!(got == serial, "{grid}: other STL files");
    }
}
