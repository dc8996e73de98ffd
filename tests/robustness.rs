//! The defects of the robustness review, one test each: decks and files a user can write
//! that once made regolith hang, abort, print NaN with exit status 0, clobber a special file,
//! leave temporary files behind, or skip part of a deck in its check. Every run here has a
//! time limit (and some a memory limit), so a regression fails instead of hanging CI.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What one run of the binary gave.
struct Outcome {
    status: Option<i32>,
    signal: Option<i32>,
    stdout: String,
    stderr: String,
}

impl Outcome {
    fn both(&self) -> String {
        format!("{}{}", self.stdout, self.stderr)
    }

    fn assert_error(&self, needles: &[&str]) {
        assert_eq!(self.status, Some(1), "{}", self.both());
        for n in needles {
            assert!(
                self.stderr.contains(n),
                "missing {n:?} in:\n{}",
                self.both()
            );
        }
    }

    fn assert_ok(&self) {
        assert_eq!(self.status, Some(0), "{}", self.both());
    }
}

/// A folder for one test, removed when the test ends.
struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A fresh folder holding the decks of tests/robustness.
fn scratch(name: &str) -> Scratch {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-robust-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let decks = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/robustness");
    for e in std::fs::read_dir(decks).unwrap().flatten() {
        std::fs::copy(e.path(), dir.join(e.file_name())).unwrap();
    }
    Scratch(dir)
}

/// Run regolith with `args` in `dir`, killed after `secs` seconds (a hang fails the test);
/// `memory_kb` limits its address space (`ulimit -v`).
fn run_limited(dir: &Path, args: &[&str], secs: u64, memory_kb: Option<u64>) -> Outcome {
    let bin = env!("CARGO_BIN_EXE_regolith");
    let mut cmd = match memory_kb {
        Some(kb) => {
            let mut c = Command::new("sh");
            c.arg("-c")
                .arg(format!("ulimit -v {kb}; exec \"$0\" \"$@\""))
                .arg(bin)
                .args(args);
            c
        }
        None => {
            let mut c = Command::new(bin);
            c.args(args);
            c
        }
    };
    let mut child = cmd
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let out = child.stdout.take().unwrap();
    let err = child.stderr.take().unwrap();
    let read = |mut r: Box<dyn std::io::Read + Send>| {
        std::thread::spawn(move || {
            let mut s = Vec::new();
            let _ = r.read_to_end(&mut s);
            String::from_utf8_lossy(&s).into_owned()
        })
    };
    let (out, err) = (read(Box::new(out)), read(Box::new(err)));
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > Duration::from_secs(secs) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("regolith {args:?} did not finish within {secs} s (a hang)");
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    use std::os::unix::process::ExitStatusExt;
    Outcome {
        status: status.code(),
        signal: status.signal(),
        stdout: out.join().unwrap(),
        stderr: err.join().unwrap(),
    }
}

fn run(dir: &Path, args: &[&str]) -> Outcome {
    run_limited(dir, args, 60, None)
}

fn deck(dir: &Path, deck: &str) -> Outcome {
    run(dir, &["-in", deck, "-log", "none"])
}

/// The deck of in.two_spheres with `dt` as its time step and `extra` after it.
fn two_spheres(dir: &Path, name: &str, dt: &str, extra: &str) -> String {
    let text = format!("variable dt index {dt}\ninclude in.two_spheres\n{extra}");
    std::fs::write(dir.join(name), text).unwrap();
    name.to_string()
}

/// Replace the one occurrence of the double `from` in `bytes` with `to`.
fn patch_double(bytes: &mut [u8], from: f64, to: f64) {
    let needle = from.to_le_bytes();
    let at: Vec<usize> = (0..bytes.len() - 7)
        .filter(|&i| bytes[i..i + 8] == needle)
        .collect();
    assert_eq!(at.len(), 1, "{from} occurs {} times", at.len());
    bytes[at[0]..at[0] + 8].copy_from_slice(&to.to_le_bytes());
}

/// two.restart with atom 1's x (or radius) replaced by `value`, then in.read_two run on it.
fn read_two_with(dir: &Path, x: Option<f64>, radius: Option<f64>) -> Outcome {
    deck(dir, "in.write_two").assert_ok();
    let path = dir.join("two.restart");
    let mut bytes = std::fs::read(&path).unwrap();
    if let Some(v) = x {
        patch_double(&mut bytes, 0.012345678, v);
    }
    if let Some(v) = radius {
        patch_double(&mut bytes, 0.5 * 0.00246912, v);
    }
    std::fs::write(&path, bytes).unwrap();
    deck(dir, "in.read_two")
}

fn atoms_at_end(stdout: &str) -> usize {
    let last = stdout
        .lines()
        .rfind(|l| l.trim_start().starts_with("20 "))
        .unwrap_or_else(|| panic!("no thermo line of step 20:\n{stdout}"));
    last.split_whitespace().nth(1).unwrap().parse().unwrap()
}

/// Defect 1: a huge or infinite coordinate in a periodic direction: no hang. A negative time step
/// of 1e30 runs (as in LIGGGHTS) with the motion guard's warning (|v| |dt| > r); a restart holding x = inf (or NaN)
/// loses that atom as LIGGGHTS does, one holding x = 1e300 wraps it at once.
#[test]
fn huge_coordinates_in_periodic_directions_do_not_hang() {
    let dir = scratch("periodic");
    let name = two_spheres(&dir, "in.neg", "-1e30", "");
    let out = deck(&dir, &name);
    out.assert_ok();
    assert!(
        out.stderr
            .contains("WARNING: step 1: atom 2 moves 2e+31 radii in one time step (|v| dt > r"),
        "{}",
        out.both()
    );
    assert!(!out.stdout.contains("nan") && !out.stdout.contains("inf"));
    // a negative time step of ordinary size runs, as in LIGGGHTS
    let name = two_spheres(&dir, "in.negsmall", "-1e-5", "");
    deck(&dir, &name).assert_ok();
    for (x, atoms) in [(f64::INFINITY, 1), (f64::NAN, 1), (1e300, 2), (-1e300, 2)] {
        let out = read_two_with(&dir, Some(x), None);
        out.assert_ok();
        assert_eq!(atoms_at_end(&out.stdout), atoms, "x = {x}: {}", out.both());
        assert!(!out.stdout.contains("nan") && !out.stdout.contains("inf"));
    }
}

/// Defect 2: size requests are checked: 30 000 atom types with a pair style and a restart refuse
/// with LIGGGHTS's "Failed to allocate" (run and check, under a memory limit), and a
/// lattice far finer than the box is refused with its count, at once, in check mode too.
#[test]
fn absurd_sizes_are_refused_with_a_message() {
    let dir = scratch("sizes");
    let types = "atom_style granular\natom_modify map array sort 0 0\nboundary p p f\nunits si\n\
                 newton off\ncommunicate single vel yes\n\
                 region reg block -0.1 0.1 -0.1 0.1 0 0.5 units box\ncreate_box 30000 reg\n\
                 pair_style gran model hertz tangential history\npair_coeff * *\n\
                 write_restart x.restart\n";
    std::fs::write(dir.join("in.types"), types).unwrap();
    for args in [
        &["-in", "in.types", "-log", "none"][..],
        &["check", "in.types"],
    ] {
        let out = run_limited(&dir, args, 60, Some(2_000_000));
        assert_eq!(out.signal, None, "{}", out.both());
        assert_eq!(out.status, Some(1), "{}", out.both());
        assert!(out.both().contains("Failed to allocate"), "{}", out.both());
        assert!(out.both().contains("in.types:9"), "{}", out.both());
    }
    let lattice = |spacing: &str| {
        format!(
            "atom_style granular\natom_modify map array sort 0 0\nboundary p p f\nunits si\n\
             region reg block 0 1 0 1 0 1 units box\ncreate_box 1 reg\nlattice sc {spacing}\n\
             create_atoms 1 box\nprint done\n"
        )
    };
    std::fs::write(dir.join("in.fine"), lattice("1e-12")).unwrap();
    for args in [
        &["check", "in.fine"][..],
        &["-in", "in.fine", "-log", "none"],
    ] {
        let out = run_limited(&dir, args, 20, None);
        assert_eq!(out.status, Some(1), "{}", out.both());
        assert!(
            out.both().contains("1e+36 lattice points"),
            "{}",
            out.both()
        );
    }
    // 1e9 atoms: validated, not built, by the check; refused for lack of memory by the run
    std::fs::write(dir.join("in.billion"), lattice("1e-3")).unwrap();
    run_limited(&dir, &["check", "in.billion"], 20, Some(2_000_000)).assert_ok();
    let out = run_limited(
        &dir,
        &["-in", "in.billion", "-log", "none"],
        60,
        Some(2_000_000),
    );
    out.assert_error(&["Failed to allocate", "for array atoms", "in.billion:8"]);
}

/// Defect 3: a number that overflows a double is an error naming the word, like `inf`.
#[test]
fn overflowing_numbers_are_errors() {
    let dir = scratch("overflow");
    let text = "region reg block -0.1 1e400 -0.1 0.1 0 0.5 units box\n";
    std::fs::write(dir.join("in.big"), text).unwrap();
    deck(&dir, "in.big").assert_error(&["'1e400'", "out of range", "in.big:1"]);
    std::fs::write(
        dir.join("in.formula"),
        "variable a equal 2*1e400\nprint ${a}\n",
    )
    .unwrap();
    deck(&dir, "in.formula").assert_error(&["1e400", "out of range"]);
    std::fs::write(dir.join("in.int"), "run 99999999999999999999\n").unwrap();
    deck(&dir, "in.int").assert_error(&["'99999999999999999999'", "out of range"]);
}

/// Defect 4: particles without size: LIGGGHTS's "Fix nve/sphere requires extended particles" for
/// `set diameter 0` and a restart with radius 0; a restart radius that is negative or NaN is
/// refused when read.
#[test]
fn particles_without_size_are_refused() {
    let dir = scratch("radius");
    let name = two_spheres(&dir, "in.zero", "1e-5", "set atom 2 diameter 0\nrun 10\n");
    deck(&dir, &name).assert_error(&["Fix nve/sphere requires extended particles"]);
    // the check before the run finds it: nothing runs
    let out = deck(&dir, &name);
    assert!(out.stderr.contains("nothing was run"), "{}", out.both());
    read_two_with(&dir, None, Some(0.0))
        .assert_error(&["Fix nve/sphere requires extended particles"]);
    for r in [-0.001, f64::NAN, f64::INFINITY] {
        read_two_with(&dir, None, Some(r)).assert_error(&["has radius", "in.read_two:2"]);
    }
}

/// Defect 5: physically impossible sizes are refused where they are set, with the allowed range.
#[test]
fn impossible_sizes_are_refused_where_set() {
    let dir = scratch("sizes5");
    let name = two_spheres(
        &dir,
        "in.huge",
        "1e-5",
        "set atom 2 diameter 1e306\nrun 10\n",
    );
    deck(&dir, &name).assert_error(&["diameter 1e+306 is out of range", "<= ", "in.huge:3"]);
    let name = two_spheres(
        &dir,
        "in.dense",
        "1e-5",
        "set atom 2 diameter 10 density 1e308\nrun 10\n",
    );
    deck(&dir, &name).assert_error(&["density 1e+308 is out of range"]);
}

/// Defect 6: a deck reading back the files of its own `restart` command runs (and checks) cleanly.
#[test]
fn periodic_restart_files_are_known_to_the_check() {
    let dir = scratch("periodic_restart");
    run(&dir, &["check", "in.periodic_restart"]).assert_ok();
    let out = deck(&dir, "in.periodic_restart");
    out.assert_ok();
    assert!(out.stdout.contains("      45        2"), "{}", out.stdout);
    assert!(dir.join("series.60").exists() && dir.join("b.restart").exists());
}

/// Defect 7: a device, a named pipe or a symbolic link given as output is written, not replaced.
#[test]
fn special_files_are_not_replaced() {
    let dir = scratch("special");
    deck(&dir, "in.write_two").assert_ok();
    use std::os::unix::fs::FileTypeExt;
    // a device like /dev/null (made here: a regression must not replace the real one),
    // where the right to make one is given
    let null = dir.join("null");
    let c = std::ffi::CString::new(null.to_str().unwrap()).unwrap();
    // SAFETY: mknod reads the NUL-terminated name only
    if unsafe { libc::mknod(c.as_ptr(), libc::S_IFCHR | 0o666, libc::makedev(1, 3)) } == 0 {
        run(&dir, &["convert", "two.restart", "null", "--to", "data"]).assert_ok();
        assert!(std::fs::metadata(&null)
            .unwrap()
            .file_type()
            .is_char_device());
    }
    // through a symbolic link: the link stays, its target gets the data
    std::fs::write(dir.join("real.data"), "old").unwrap();
    std::os::unix::fs::symlink("real.data", dir.join("link.data")).unwrap();
    run(&dir, &["convert", "two.restart", "link.data"]).assert_ok();
    assert!(std::fs::symlink_metadata(dir.join("link.data"))
        .unwrap()
        .file_type()
        .is_symlink());
    let data = std::fs::read_to_string(dir.join("real.data")).unwrap();
    assert!(data.contains("2 atoms"), "{data}");
    // -r into a named pipe with a reader at the other end
    let fifo = dir.join("pipe.data");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: mkfifo reads the NUL-terminated name only
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let reader = {
        let fifo = fifo.clone();
        std::thread::spawn(move || std::fs::read_to_string(fifo).unwrap())
    };
    run(&dir, &["-r", "two.restart", "pipe.data"]).assert_ok();
    assert!(reader.join().unwrap().contains("2 atoms"));
    assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
}

/// Defect 8: no temporary file outlives a failed write (here: the file size limit, as a full disk),
/// and one left by a killed run is removed by the next write of that name.
#[test]
fn temporary_files_are_cleaned() {
    let dir = scratch("temps");
    deck(&dir, "in.write_two").assert_ok();
    // a stale temporary file of a process that is gone
    let stale = dir.join(".out.data.regolith-tmp.4194305");
    std::fs::write(&stale, "half a file").unwrap();
    let deck_text = "read_restart two.restart\nwrite_data out.data\n";
    std::fs::write(dir.join("in.wd"), deck_text).unwrap();
    deck(&dir, "in.wd").assert_ok();
    assert!(!stale.exists(), "the stale temporary file is still there");
    // a write that fails for lack of space: an error, and no temporary file left
    let out = Command::new("sh")
        .arg("-c")
        .arg("ulimit -f 0; trap '' XFSZ; exec \"$0\" -in in.wd -log none")
        .arg(env!("CARGO_BIN_EXE_regolith"))
        .current_dir(&dir)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let temps: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("regolith-tmp") || n.contains(".tmp"))
        .collect();
    assert!(temps.is_empty(), "left behind: {temps:?}");
}

/// Defect 9: the check reaches every line: after a `next`/`jump SELF` loop (with the loop
/// variable's real last value), and after a run whose values it cannot know.
#[test]
fn the_check_covers_the_whole_deck() {
    let dir = scratch("whole");
    let out = run(&dir, &["check", "in.loop_then_typo"]);
    assert_eq!(out.status, Some(1), "{}", out.both());
    assert!(
        out.stdout
            .contains("in.loop_then_typo:8: Unknown command: runn"),
        "{}",
        out.both()
    );
    assert_eq!(out.stdout.lines().count(), 1, "{}", out.both());
    let start = Instant::now();
    let out = deck(&dir, "in.typo_after_run");
    out.assert_error(&[
        "Unknown command: writ_restart",
        "in.typo_after_run:7",
        "nothing was run",
    ]);
    assert!(start.elapsed() < Duration::from_secs(20));
}

/// Defect 10: an empty dump is not converted "successfully".
#[test]
fn an_empty_dump_does_not_convert() {
    let dir = scratch("empty_dump");
    std::fs::write(dir.join("empty.dump"), "").unwrap();
    let out = run(&dir, &["convert", "empty.dump", "out.vtk"]);
    assert_ne!(out.status, Some(0), "{}", out.both());
    assert!(out.stderr.contains("empty.dump"), "{}", out.both());
    assert!(!dir.join("out.vtk").exists());
}

/// Defect 11: the lesser ones: a neighbour skin the box cannot bin (LIGGGHTS's message), a
/// log that cannot be written, coincident atoms named as such, a box without volume, unknown
/// commands not called LIGGGHTS commands.
#[test]
fn lesser_defects() {
    let dir = scratch("lesser");
    let pair = "fix m1 all property/global youngsModulus peratomtype 5e6 5e6\n\
                fix m2 all property/global poissonsRatio peratomtype 0.3 0.3\n\
                fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5\n\
                fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5\n\
                pair_style gran model hertz tangential history\npair_coeff * *\n";
    let name = two_spheres(
        &dir,
        "in.skin",
        "1e-5",
        &format!("{pair}neighbor 1e308 bin\nrun 10\n"),
    );
    deck(&dir, &name).assert_error(&["Cannot use neighbor bins - box size << cutoff"]);
    let name = two_spheres(&dir, "in.log", "1e-5", "");
    let out = run(&dir, &["-in", &name, "-log", "/dev/full"]);
    out.assert_error(&["writing the log file failed"]);
    let twin = format!("{pair}set atom 2 x 0.012345678 y 0.0 z 0.3 diameter 0.00246912\nrun 10\n");
    let name = two_spheres(&dir, "in.twin", "1e-5", &twin);
    deck(&dir, &name).assert_error(&["atoms 1 and 2 sit at the same position"]);
    // a box without volume, or one longer than a double: LIGGGHTS's "Box bounds are invalid"
    for bounds in ["0 0 0 1 0 1", "-1e308 1e308 0 1 0 1"] {
        let text = format!("region reg block {bounds} units box\ncreate_box 1 reg\n");
        std::fs::write(dir.join("in.box"), text).unwrap();
        deck(&dir, "in.box").assert_error(&["Box bounds are invalid", "in.box:2"]);
    }
    std::fs::write(dir.join("in.foo"), "foo 1 2\n").unwrap();
    let out = deck(&dir, "in.foo");
    out.assert_error(&["Unknown command: foo", "not a command of LIGGGHTS 3.8.0"]);
    assert!(!out.stderr.contains("(a LIGGGHTS command)"));
}

/// Issue 16: a 10 m/s piston driven into a settled soft bed (compat/engine/in.piston_overlap,
/// run for 600 steps instead of 100) squeezes particles far beyond half a radius of overlap.
/// LIGGGHTS runs it to the end (its last thermo line: step 3600, 314 atoms, KinEng
/// 0.19488337); regolith warns once with step, atoms and overlap, sums the recurrences up at
/// the run's end, and finishes with finite output close to LIGGGHTS's.
#[test]
fn a_piston_squeezing_a_soft_bed_warns_and_runs_to_the_end() {
    let dir = scratch("piston");
    let compat = Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine/in.piston_overlap");
    let text = std::fs::read_to_string(compat).unwrap();
    assert!(text.contains("\nrun 100\n"));
    let text = text
        .replace("\nrun 100\n", "\nrun 600\n")
        .replace("dump d all custom 50", "dump d all custom 100");
    std::fs::create_dir_all(dir.join("post")).unwrap();
    std::fs::write(dir.join("in.piston"), text).unwrap();
    let out = deck(&dir, "in.piston");
    out.assert_ok();
    // warned once, at the first overlap beyond 50 % (the run is bit-identical with
    // LIGGGHTS's up to there)
    // on standard error: the screen and log keep LIGGGHTS's lines
    assert!(!out.stdout.contains("overlap"), "{}", out.stdout);
    let first: Vec<&str> = out
        .stderr
        .lines()
        .filter(|l| l.contains("overlap by"))
        .collect();
    assert_eq!(first.len(), 1, "{}", out.stderr);
    assert!(
        first[0].starts_with(
            "WARNING: step 3016: atoms 130 and 134 overlap by 51.7 % of the smaller radius (more than 50 %)"
        ),
        "{}",
        first[0]
    );
    let summary = out
        .stderr
        .lines()
        .find(|l| l.starts_with("WARNING: overlaps beyond 50 % of the smaller radius at "))
        .unwrap_or_else(|| panic!("no summary:\n{}", out.stderr));
    let largest: f64 = summary
        .split("the largest ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{summary}"));
    assert!(largest > 100.0 && largest < 200.0, "{summary}");
    // the last thermo line against LIGGGHTS's
    let last = out
        .stdout
        .lines()
        .rfind(|l| l.trim_start().starts_with("3600 "))
        .unwrap_or_else(|| panic!("no step 3600:\n{}", out.stdout));
    let w: Vec<f64> = last
        .split_whitespace()
        .map(|x| x.parse().unwrap())
        .collect();
    assert_eq!(w[1], 314.0, "{last}");
    assert!((w[2] / 0.19488337 - 1.0).abs() < 0.01, "{last}");
    let dump = std::fs::read_to_string(dir.join("post/piston.dump")).unwrap();
    assert_eq!(dump.matches("ITEM: TIMESTEP").count(), 7);
    for word in dump.split_whitespace() {
        if let Ok(x) = word.parse::<f64>() {
            assert!(x.is_finite(), "{word} in the dump");
        }
    }
    assert!(!out.stdout.contains("nan") && !out.stdout.contains("inf"));
    // the run header on standard error names the composed contact models and their history:
    // tangential history keeps 3 doubles (the shear displacement), epsd 3 more (the rolling
    // spring), sjkr none; the pair's history is per listed pair
    let e = &out.stderr;
    assert!(e.contains("Contact models (regolith):\n  pair_style gran: normal hertz, tangential history, cohesion sjkr, rolling epsd; history 6 doubles (48 bytes) per neighbour pair, "), "{e}");
    assert!(e.contains("\n  fix floor (wall/gran primitive): normal hertz, tangential history, cohesion sjkr, rolling epsd; history 6 doubles (48 bytes) per particle\n"), "{e}");
    assert!(e.contains("\n  fix front (wall/gran primitive): normal hertz, tangential history; history 3 doubles (24 bytes) per particle\n"), "{e}");
    let listed = e.split("per neighbour pair, ").nth(1).unwrap();
    let pairs: f64 = listed.split(' ').next().unwrap().parse().unwrap();
    let bytes: f64 = listed
        .split("listed now: ")
        .nth(1)
        .and_then(|t| t.split(' ').next())
        .and_then(|t| t.parse().ok())
        .unwrap();
    assert!(pairs > 320.0, "{listed}");
    assert!((bytes - 48.0 * pairs / 320.0).abs() < 0.1, "{listed}");
    // and the time-step margin of the piston run (dt 5e-6 s, fix push at 10 m/s)
    assert!(e.contains("from fix push (move linear)"), "{e}");
}

/// Issue 16: `thermo_modify lost error` names the lost atoms (ID, position, velocity, step);
/// LIGGGHTS only counts them ("Lost atoms: original 1 current 1" for this deck, at the
/// thermo output of step 50). Atom 2 starts at x = 0.09 with vx = 2 m/s and dt 1e-4 s: it
/// crosses the face x = 0.1 after 50 steps, where the check finds it.
#[test]
fn lost_atoms_are_named() {
    let dir = scratch("lost");
    std::fs::write(
        dir.join("in.lost"),
        "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n\
         communicate single vel yes\nunits si\nregion reg block 0 0.1 0 0.1 0 0.1 units box\n\
         create_box 1 reg\nneighbor 0.002 bin\n\
         fix m1 all property/global youngsModulus peratomtype 5e6\n\
         fix m2 all property/global poissonsRatio peratomtype 0.2\n\
         fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\npair_coeff * *\n\
         create_atoms 1 single 0.05 0.05 0.05 units box\n\
         create_atoms 1 single 0.09 0.02 0.03 units box\n\
         set group all diameter 0.004 density 2500\nset atom 2 vx 2.0 vy 0.5\n\
         fix integr all nve/sphere\ntimestep 1e-4\nthermo_style custom step atoms ke\n\
         thermo_modify lost error\nthermo 10\nrun 100\n",
    )
    .unwrap();
    let out = deck(&dir, "in.lost");
    out.assert_error(&["Lost atoms: original 2 current 1 (at step 50", "in.lost:"]);
    let line = out
        .stderr
        .lines()
        .find(|l| l.contains("Lost atoms"))
        .unwrap();
    let x = 0.09 + 50.0 * 2.0 * 1e-4;
    let y = 0.02 + 50.0 * 0.5 * 1e-4;
    // the position as integrated, every digit (x just past 0.1), and the velocity
    let want = "atom 2 at x = (";
    let at = line.find(want).unwrap_or_else(|| panic!("{line}"));
    let coords: Vec<f64> = line[at + want.len()..]
        .split(')')
        .next()
        .unwrap()
        .split(", ")
        .map(|c| c.parse().unwrap())
        .collect();
    assert!(coords[0] > 0.1 && (coords[0] - x).abs() < 1e-15, "{line}");
    assert!((coords[1] - y).abs() < 1e-15 && coords[2] == 0.03, "{line}");
    assert!(line.ends_with("with v = (2, 0.5, 0))"), "{line}");
    assert!(!line.contains("atom 1 "), "{line}");
    // thermo lines up to step 40, as LIGGGHTS prints them
    assert!(
        out.stdout.contains("      40        2  0.00017802358 "),
        "{}",
        out.stdout
    );
}
