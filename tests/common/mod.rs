//! Helpers shared by the integration tests that compare regolith with LIGGGHTS.
// each test crate that includes this module uses only some of it
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The rank tests' soft granular material (E 5 MPa, nu 0.2, e 0.5, friction 0.8, rolling
/// friction 0.3), Hertz with tangential history and `cdt` rolling friction between
/// particles, and a primitive floor at z = 0: deck lines, for `concat!`.
#[allow(unused_macros)]
macro_rules! soft_material_on_a_floor {
    () => {
        "fix m1 all property/global youngsModulus peratomtype 5e6\n\
fix m2 all property/global poissonsRatio peratomtype 0.2\n\
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
fix m4 all property/global coefficientFriction peratomtypepair 1 0.8\n\
fix m5 all property/global coefficientRollingFriction peratomtypepair 1 0.3\n\
pair_style gran model hertz tangential history rolling_friction cdt\n\
pair_coeff * *\n\
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0\n"
    };
}

/// The pour tests' box (20 x 20 x 30 mm with a floor, gravity), material (Hertz with
/// tangential history) and distribution `pdd` of spheres of radius 0.8 mm (60 %) and
/// 0.6 mm: deck lines, for `concat!`.
#[allow(unused_macros)]
macro_rules! pour_box_and_spheres {
    () => {
        "region reg block 0 0.02 0 0.02 0 0.03 units box\n\
create_box 1 reg\n\
neighbor 0.0005 bin\n\
neigh_modify delay 0\n\
fix m1 all property/global youngsModulus peratomtype 5e6\n\
fix m2 all property/global poissonsRatio peratomtype 0.3\n\
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
pair_style gran model hertz tangential history\n\
pair_coeff * *\n\
timestep 1e-5\n\
fix gr all gravity 9.81 vector 0 0 -1\n\
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0\n\
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.0008\n\
fix pts2 all particletemplate/sphere 15485867 atom_type 1 density constant 2500 radius constant 0.0006\n\
fix pdd all particledistribution/discrete 32452843 2 pts1 0.6 pts2 0.4\n"
    };
}

/// A fresh, empty directory `regolith-TAG-PID` in the build's temporary folder (target/tmp).
pub fn scratch_dir(tag: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Run regolith in `dir` with `args` (stdin empty), its output captured.
pub fn regolith(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// Captured output bytes as text (invalid UTF-8 replaced).
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Run regolith in `dir` on `deck`, written there as `file`, with `-log none` and `args`.
pub fn run_deck(dir: &Path, file: &str, deck: &str, args: &[&str]) -> Output {
    std::fs::write(dir.join(file), deck).unwrap();
    Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(["-in", file, "-log", "none"])
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// Run blocks as compat/regenerate.sh cuts them from LIGGGHTS's screen output: from each
/// header line starting with `Step` up to (not including) `Loop time`, so lines that fixes
/// print during a run (fix print, warnings) are compared too.
pub fn thermo_lines(stdout: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in stdout.lines() {
        if line.starts_with("Loop time") {
            inside = false;
        }
        if inside {
            out.push(line.to_string());
        }
        if line.trim_start().starts_with("Step ") {
            inside = true;
            out.push(line.to_string());
        }
    }
    out
}

/// The official LIGGGHTS tutorials of Debian's liggghts-doc (or `REGOLITH_TUTORIALS`);
/// fails the test with the install command when they are missing.
pub fn tutorials_root() -> PathBuf {
    let root = std::env::var("REGOLITH_TUTORIALS").unwrap_or_else(|_| {
        "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public".to_string()
    });
    let root = PathBuf::from(root);
    assert!(
        root.is_dir(),
        "the LIGGGHTS tutorials are missing at {}: apt-get install -y liggghts-doc",
        root.display()
    );
    root
}

/// The largest difference of dump text `b` from dump text `a` in units of each column's
/// scale (its largest magnitude in `a`'s snapshot), atoms matched by ID; fails the test when
/// the snapshots' counts, steps or atoms differ.
pub fn scale_deviation(a: &str, b: &str) -> f64 {
    use regolith::io::dump_compare::parse;
    let (a, b) = (parse(a).unwrap(), parse(b).unwrap());
    assert_eq!(a.len(), b.len(), "snapshot counts");
    let mut worst: f64 = 0.0;
    for (sa, sb) in a.iter().zip(&b) {
        assert_eq!(sa.step, sb.step, "snapshot steps");
        assert!(
            sa.rows.keys().eq(sb.rows.keys()),
            "step {}: other atoms",
            sa.step
        );
        for c in 0..sa.columns.len() {
            let scale = sa.rows.values().map(|r| r[c].abs()).fold(0.0, f64::max);
            if scale > 0.0 {
                for (id, r) in &sa.rows {
                    worst = worst.max((r[c] - sb.rows[id][c]).abs() / scale);
                }
            }
        }
    }
    worst
}

/// The engine decks' folder, compat/engine.
pub fn engine_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine")
}

/// The names of the engine decks (`in.NAME` in compat/engine), sorted.
pub fn engine_decks() -> Vec<String> {
    let mut decks: Vec<String> = std::fs::read_dir(engine_dir())
        .unwrap()
        .filter_map(|e| {
            e.unwrap()
                .file_name()
                .to_str()?
                .strip_prefix("in.")
                .map(str::to_string)
        })
        .collect();
    decks.sort();
    decks
}

/// Copy every file and folder in `from` into `to`.
pub fn copy_tree(from: &Path, to: &Path) {
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        if e.path().is_dir() {
            std::fs::create_dir_all(to.join(e.file_name())).unwrap();
            copy_tree(&e.path(), &to.join(e.file_name()));
        } else {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

/// A fresh folder `regolith-engine-PID-NAME-TAG` in the build's temporary folder holding
/// `deck_text` as `in.NAME` and the files of the deck's `NAME.inputs` folder.
pub fn engine_deck_copy(name: &str, deck_text: &str, tag: &str) -> PathBuf {
    let work = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "regolith-engine-{}-{name}-{tag}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).unwrap();
    std::fs::write(work.join(format!("in.{name}")), deck_text).unwrap();
    let inputs = engine_dir().join(format!("{name}.inputs"));
    if inputs.is_dir() {
        copy_tree(&inputs, &work);
    }
    work
}

/// The deck cut after its first `run` (at top level), which runs 100 steps with every
/// particle dumped every 10 steps at full precision (`fastcheck_*.dump`); None for decks
/// whose first run is inside a loop or condition.
pub fn first_hundred_steps(text: &str) -> Option<String> {
    let mut out = String::new();
    for line in text.lines() {
        let word = line.split_whitespace().next().unwrap_or("");
        if matches!(word, "jump" | "label" | "next" | "if") {
            return None;
        }
        if word == "run" {
            out.push_str(
                "dump fastcheck all custom 10 fastcheck_*.dump id x y z vx vy vz fx fy fz omegax omegay omegaz\n\
                 dump_modify fastcheck format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"\n\
                 run 100\n",
            );
            return Some(out);
        }
        out.push_str(line);
        out.push('\n');
    }
    None
}

/// The snapshots of every `fastcheck_*.dump` in `dir` (files in name order).
pub fn fastcheck_dumps(dir: &Path) -> Vec<regolith::io::dump_compare::Snapshot> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("fastcheck_"))
        })
        .collect();
    files.sort();
    files
        .iter()
        .flat_map(|f| {
            regolith::io::dump_compare::parse(&std::fs::read_to_string(f).unwrap()).unwrap()
        })
        .collect()
}

/// Largest |a - b| relative to the column's largest magnitude in `a`, over all snapshots
/// (atoms matched by ID); Err for differing steps, atoms or columns.
pub fn snapshots_deviation(
    a: &[regolith::io::dump_compare::Snapshot],
    b: &[regolith::io::dump_compare::Snapshot],
) -> Result<f64, String> {
    if a.len() != b.len() {
        return Err(format!("{} snapshots against {}", a.len(), b.len()));
    }
    let mut worst: f64 = 0.0;
    for (sa, sb) in a.iter().zip(b) {
        if sa.step != sb.step || sa.columns != sb.columns {
            return Err(format!("step {} against {}", sa.step, sb.step));
        }
        if sa.rows.keys().ne(sb.rows.keys()) {
            return Err(format!("step {}: other atoms", sa.step));
        }
        for c in 0..sa.columns.len() {
            let scale = sa.rows.values().map(|r| r[c].abs()).fold(0.0, f64::max);
            if scale == 0.0 {
                continue;
            }
            for (id, r) in &sa.rows {
                worst = worst.max((r[c] - sb.rows[id][c]).abs() / scale);
            }
        }
    }
    Ok(worst)
}

/// Each rank's exit status of a deck run on `n` in-process ranks (N threads joined by
/// channels, each running the whole deck as `mpirun -np N` would), or on one process for
/// `n` = 0 (with `opts(0, 0)`); `opts(size, rank)` gives a rank's options.
pub fn run_on_ranks(
    n: usize,
    opts: impl Fn(usize, usize) -> regolith::cli::DeckOptions + Sync,
) -> Vec<regolith::error::ExitStatus> {
    use regolith::util::comm::Comm;
    if n == 0 {
        return vec![regolith::session::run_deck(&opts(0, 0))];
    }
    regolith::util::comm_threads::ThreadRanks::run_owned(n, |c| {
        let o = opts(n, c.rank());
        regolith::session::run_deck_on(&o, Some(Box::new(c)))
    })
}
