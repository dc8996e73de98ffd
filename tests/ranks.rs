//! Runs on several ranks, in-process: N ranks are N threads joined by channels, each running
//! the whole deck as `mpirun -np N regolith -sf fast -in deck` would. Dumps are compared with
//! the serial fast path's (within 1e-10 of each column's scale) and between rank counts and
//! repeated runs (bit for bit).

#[macro_use]
mod common;

use regolith::cli::DeckOptions;
use regolith::error::ExitStatus;
use regolith::util::comm::Ranks;

/// About 300 spheres poured on a floor, periodic in x and y, touching when the run starts
/// (a settling bed with contact history, friction and rolling friction).
const BED: &str = concat!(
    "\
atom_style granular
atom_modify map array
boundary p p f
newton off
communicate single vel yes
units si
${grid}
region reg block 0 0.01488 0 0.01488 0 0.02 units box
create_box 1 reg
neighbor 0.0005 bin
neigh_modify delay 0
",
    soft_material_on_a_floor!(),
    "lattice sc 0.00248
region pile block 0 0.01488 0 0.01488 0.0013 0.019 units box
create_atoms 1 region pile
set group all diameter 0.0025 density 2500
displace_atoms all random 0.0001 0.0001 0.0001 15485863
velocity all set 0.01 0.0 -0.05
fix gr all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
timestep 2e-6
thermo_style custom step atoms ke
thermo 50
dump d all custom 25 ${out} id type x y z vx vy vz fx fy fz omegax omegay omegaz radius
dump_modify d sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 100
run 50
"
);

fn scratch(tag: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-ranks-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn options(deck: &std::path::Path, dump: &std::path::Path, grid: &str, size: usize) -> DeckOptions {
    DeckOptions {
        input: Some(deck.to_string_lossy().into_owned()),
        vars: vec![
            ("out".into(), vec![dump.to_string_lossy().into_owned()]),
            ("grid".into(), vec![grid.into()]),
        ],
        log: Some("none".into()),
        screen: Some("none".into()),
        fast: true,
        threads: Some(1),
        ranks: Ranks {
            size,
            rank: 0,
            per_node: size,
        },
        ..DeckOptions::default()
    }
}

/// The dump of `deck` run on `n` ranks (0: the serial fast path) with `processors` line
/// `grid` (may be empty).
fn dump_of(deck: &str, n: usize, grid: &str, tag: &str) -> String {
    outputs_of(deck, n, grid, tag).0
}

/// The dump and the log of `deck` run on `n` ranks (0: the serial fast path) with
/// `processors` line `grid` (may be empty).
fn outputs_of(deck: &str, n: usize, grid: &str, tag: &str) -> (String, String) {
    let dir = scratch(tag);
    let log = run_in(&dir, deck, n, grid);
    let text = std::fs::read_to_string(dir.join("out.dump")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (text, log)
}

/// Run `deck` in folder `dir` (`${dir}` in it names the folder, `${out}` is `dir/out.dump`)
/// on `n` ranks (0: the serial fast path) with `processors` line `grid`; its log.
fn run_in(dir: &std::path::Path, deck: &str, n: usize, grid: &str) -> String {
    let path = dir.join("in.deck");
    std::fs::write(&path, deck.replace("${dir}", &dir.to_string_lossy())).unwrap();
    let (dump, log) = (dir.join("out.dump"), dir.join("log.txt"));
    let opts = |size: usize, rank: usize| {
        let mut o = options(&path, &dump, grid, size.max(1));
        o.ranks.rank = rank;
        o.log = Some(log.to_string_lossy().into_owned());
        o
    };
    let status = common::run_on_ranks(n, opts);
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{} on {n} ranks: {status:?}",
        dir.display()
    );
    std::fs::read_to_string(&log).unwrap()
}

/// `deck` on the serial fast path and on the rank grids `grids` ((ranks, processors line)):
/// every rank run within 1e-10 of each column's scale of the serial dump, and the dumps
/// of the rank runs (the first one twice).
fn on_grids(deck: &str, grids: &[(usize, &str)], tag: &str) -> (String, Vec<String>) {
    let serial = dump_of(deck, 0, "", &format!("{tag}-serial"));
    let mut dumps = Vec::new();
    for (k, &(n, grid)) in grids.iter().enumerate() {
        let dump = dump_of(deck, n, grid, &format!("{tag}-{k}"));
        let d = common::scale_deviation(&serial, &dump);
        assert!(
            d < 1e-10,
            "{tag}: {grid} differs from the serial run by {d:e}"
        );
        dumps.push(dump);
    }
    let (n, grid) = grids[0];
    let again = dump_of(deck, n, grid, &format!("{tag}-again"));
    assert!(
        again == dumps[0],
        "{tag}: {grid} run twice gave different dumps"
    );
    (serial, dumps)
}

/// The files of folder `dir` by name, with their text.
fn texts_in(dir: &std::path::Path) -> std::collections::BTreeMap<String, String> {
    std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .filter(|e| e.path().is_file())
        .map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read_to_string(e.path()).unwrap_or_default())
        })
        .collect()
}

#[test]
fn xyz_atom_and_vtk_dumps_on_ranks_write_what_one_process_writes() {
    // rank 0 writes every rank's particles gathered: the sorted dumps are one process's
    // text, the unsorted xyz file the same lines in another order
    let deck = BED.replace(
        "run 100\n",
        "dump x all xyz 50 ${dir}/bed*.xyz
dump a all atom 50 ${dir}/bed*.atom
dump_modify a sort id
dump v all custom/vtk 50 ${dir}/bed*.vtk id type vx omegaz radius
dump_modify v sort id
run 100\n",
    );
    let files = |n: usize, grid: &str| {
        let dir = scratch(&format!("styles-{n}"));
        run_in(&dir, &deck, n, grid);
        let mut t = texts_in(&dir);
        t.retain(|name, _| name.starts_with("bed"));
        let _ = std::fs::remove_dir_all(&dir);
        t
    };
    let serial = files(0, "");
    // snapshots at 0, 50, 100 and 150; the VTK files with the box beside each
    assert_eq!(serial.len(), 16, "{:?}", serial.keys());
    let lines = |t: &str| {
        let mut l: Vec<&str> = t.lines().collect();
        l.sort_unstable();
        l.join("\n")
    };
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 1 3 1")] {
        let got = files(n, grid);
        assert!(got.keys().eq(serial.keys()), "{grid}: {:?}", got.keys());
        for (name, want) in &serial {
            if name.ends_with(".xyz") {
                assert_eq!(want.lines().next(), Some("252"));
                assert!(lines(&got[name]) == lines(want), "{grid}: {name}");
            } else {
                assert!(got[name] == *want, "{grid}: {name} differs");
            }
        }
    }
}

#[test]
fn a_settling_bed_on_ranks_matches_the_serial_fast_path() {
    let grids = [
        (2, "processors 2 1 1"),
        (3, "processors 3 1 1"),
        (2, "processors 1 2 1"),
        (4, "processors 2 2 1"),
    ];
    let (serial, _) = on_grids(BED, &grids, "bed");
    let snaps = regolith::io::dump_compare::parse(&serial).unwrap();
    assert_eq!(snaps.len(), 7, "steps 0..150 every 25");
    assert_eq!(snaps[0].rows.len(), 252);
    // the bed moves: velocities change over the run
    let last = snaps.last().unwrap();
    assert!(snaps[0].rows.iter().any(|(id, r)| r[7] != last.rows[id][7]));
}

#[test]
fn without_periodic_faces_any_grid_gives_the_same_bits() {
    // walls all round and a list rebuilt every step: particles migrate and their contact
    // history is carried at every step
    let deck = BED.replace("boundary p p f", "boundary f f f").replace(
        "neigh_modify delay 0",
        "neigh_modify delay 0 every 1 check no",
    );
    let grids = [
        (2, "processors 2 1 1"),
        (3, "processors 3 1 1"),
        (3, "processors 1 3 1"),
        (4, "processors 2 2 1"),
    ];
    let (_, dumps) = on_grids(&deck, &grids, "fixed");
    for (d, (_, grid)) in dumps.iter().zip(&grids).skip(1) {
        assert!(*d == dumps[0], "{grid} and 2 1 1 gave different dumps");
    }
}

/// The problems `regolith check` finds in `text` on two ranks, fast path or not.
fn check_on_two(text: &str, fast: bool) -> Vec<String> {
    let opts = DeckOptions {
        fast,
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
fn what_does_not_run_on_ranks_is_refused_by_name() {
    let deck = BED
        .replace("${grid}", "processors 2 1 1")
        .replace("${out}", "out.dump");
    assert_eq!(check_on_two(&deck, true), Vec::<String>::new());
    let exact = check_on_two(&deck, false);
    assert_eq!(exact.len(), 2, "{exact:?}");
    assert!(exact[0].starts_with(
        "in.deck:33: run on the exact path (add -sf fast) on more than one MPI rank: not supported yet"
    ), "{exact:?}");
    let before_run = |line: &str| (String::from("run 50\n"), format!("{line}\nrun 50\n"));
    for ((from, to), at, refused) in [
        (
            before_run("compute c all contact/atom"),
            34,
            "compute contact/atom",
        ),
        (
            before_run("fix push all addforce 0 0 v_f"),
            34,
            "fix addforce with a variable",
        ),
        (
            before_run("fix pts all particletemplate/multisphere 15485863"),
            34,
            "fix particletemplate/multisphere",
        ),
        (
            before_run("thermo_style custom step c_thermo_press"),
            34,
            "thermo keyword c_thermo_press",
        ),
        (
            before_run("dump d2 all decomposition/vtk 10 out.vtk"),
            34,
            "dump decomposition/vtk",
        ),
        (before_run("run 10 every 5 NULL"), 34, "run every"),
    ] {
        let text = deck.replace(&from, &to);
        let got = check_on_two(&text, true);
        let want = format!("in.deck:{at}: {refused} on more than one MPI rank: not supported yet");
        assert!(
            got.first().is_some_and(|g| g.starts_with(&want)),
            "{to}: {got:?}"
        );
    }
}

/// The bed with per-particle force fixes, computes in thermo and a variable column in the dump.
fn bed_with_computes() -> String {
    BED.replace(
        "fix integr all nve/sphere",
        "fix integr all nve/sphere
group low id <= 40
fix push all addforce 0.0 0.0 -1e-5
fix visc all viscous 1e-5
fix hold low freeze
compute rke all erotate/sphere
variable fmag atom sqrt(fx*fx+fy*fy+fz*fz)
compute fmax all reduce max v_fmag
compute fsum all reduce sum fz
variable vz equal vcm(all,z)",
    )
    .replace(
        "thermo_style custom step atoms ke",
        "thermo_style custom step atoms ke c_rke c_fmax c_fsum v_vz
thermo_modify format float %.16g",
    )
    .replace("omegaz radius", "omegaz radius v_fmag")
    .replace("%.17g\"", "%.17g %.17g\"")
}

/// The thermo rows (numbers) of the log of `deck` on `n` ranks (0: serial).
fn thermo_rows(deck: &str, n: usize, tag: &str) -> Vec<Vec<f64>> {
    let dir = scratch(tag);
    let path = dir.join("in.deck");
    std::fs::write(&path, deck).unwrap();
    let (dump, log) = (dir.join("out.dump"), dir.join("log.txt"));
    let opts = |size: usize, rank: usize| {
        let mut o = options(&path, &dump, "processors * 1 1", size.max(1));
        o.ranks.rank = rank;
        o.log = Some(log.to_string_lossy().into_owned());
        if size == 0 {
            o.vars.retain(|(k, _)| k != "grid");
            o.vars.push(("grid".into(), vec![String::new()]));
        }
        o
    };
    let status = common::run_on_ranks(n, opts);
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{tag}: {status:?}"
    );
    let text = std::fs::read_to_string(&log).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    thermo_table(&text)
}

/// The thermo rows (numbers) of a log, warnings between them left out.
fn thermo_table(log: &str) -> Vec<Vec<f64>> {
    let mut rows = Vec::new();
    let mut inside = false;
    for line in log.lines() {
        if line.trim_start().starts_with("Step") {
            inside = true;
        } else if line.starts_with("Loop time") {
            inside = false;
        } else if inside && !line.starts_with("WARNING") {
            rows.push(
                line.split_whitespace()
                    .map(|w| w.parse().unwrap())
                    .collect(),
            );
        }
    }
    rows
}

#[test]
fn force_fixes_computes_and_variables_on_ranks_match_the_serial_fast_path() {
    let deck = bed_with_computes();
    let grids = [(2, "processors 2 1 1"), (3, "processors 1 3 1")];
    let (serial, _) = on_grids(&deck, &grids, "computes");
    let snaps = regolith::io::dump_compare::parse(&serial).unwrap();
    // the frozen particles keep their velocities (no force acts on them), the others not
    let (first, last) = (&snaps[0], snaps.last().unwrap());
    for id in 1..=40 {
        assert_eq!(first.rows[&id][5..8], last.rows[&id][5..8], "atom {id}");
    }
    assert_ne!(first.rows[&41][5..8], last.rows[&41][5..8]);
    let serial = thermo_rows(&deck, 0, "computes-thermo-serial");
    assert_eq!(serial.len(), 5, "steps 0, 50, 100, then 100, 150");
    for n in [2, 3] {
        let ranks = thermo_rows(&deck, n, &format!("computes-thermo-{n}"));
        assert_eq!(ranks.len(), serial.len());
        for (a, b) in serial.iter().zip(&ranks) {
            for (k, (x, y)) in a.iter().zip(b).enumerate() {
                let scale = serial.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
                assert!(
                    (x - y).abs() <= 1e-10 * scale,
                    "{n} ranks, column {k}: {x} against {y}"
                );
            }
        }
    }
    // the values are not trivial: rotation, a largest force and the centre of mass moving
    assert!(serial.iter().all(|r| r[4] > 0.0 && r[6] != 0.0));
    assert!(serial[1..].iter().all(|r| r[3] > 0.0));
}

#[test]
fn fix_print_and_the_other_thermo_keywords_on_ranks_match_the_serial_fast_path() {
    // rank 0 prints, its variables (atoms by ID, erotate) over every rank's particles; the
    // file appended to by rank 0 alone
    let deck = BED.replace(
        "thermo_style custom step atoms ke\n",
        "thermo_style custom step atoms ke erotate fmax fnorm density xlat cella cellalpha
thermo_modify format float %.16g
variable xx equal x[1]
variable e equal erotate
fix p1 all print 25 \"at $(step) x1 ${xx} e ${e}\"
fix p2 all print 50 \"x7 $(x[7]*2)\" append ${dir}/print.txt screen no title \"# my title\"
",
    );
    let outputs = |n: usize, grid: &str| {
        let dir = scratch(&format!("print-{n}"));
        let log = run_in(&dir, &deck, n, grid);
        let file = std::fs::read_to_string(dir.join("print.txt")).unwrap();
        let _ = std::fs::remove_dir_all(&dir);
        let printed: Vec<String> = log
            .lines()
            .filter(|l| l.starts_with("at "))
            .map(str::to_string)
            .collect();
        let thermo: String = log
            .lines()
            .filter(|l| !l.starts_with("at "))
            .map(|l| format!("{l}\n"))
            .collect();
        (printed, file, thermo_table(&thermo))
    };
    let numbers = |lines: &[String]| -> Vec<Vec<f64>> {
        lines
            .iter()
            .map(|l| {
                l.split_whitespace()
                    .filter_map(|w| w.parse().ok())
                    .collect()
            })
            .collect()
    };
    let close = |a: &[Vec<f64>], b: &[Vec<f64>], what: &str| {
        assert_eq!(a.len(), b.len(), "{what}: rows");
        for (x, y) in a.iter().zip(b) {
            assert_eq!(x.len(), y.len(), "{what}: {x:?} against {y:?}");
            for (k, (u, v)) in x.iter().zip(y).enumerate() {
                let scale = a
                    .iter()
                    .filter_map(|r| r.get(k))
                    .fold(0.0, |m: f64, v| m.max(v.abs()));
                assert!(
                    (u - v).abs() <= 1e-10 * scale,
                    "{what}: {x:?} against {y:?}"
                );
            }
        }
    };
    let (printed, file, thermo) = outputs(0, "");
    // at the end of steps 25..100 in the first run, 125 and 150 in the second
    assert_eq!(printed.len(), 6, "{printed:?}");
    let file_lines: Vec<String> = file.lines().map(str::to_string).collect();
    assert_eq!(file_lines[0], "# my title");
    assert_eq!(file_lines.len(), 4, "{file}");
    assert_eq!(thermo.len(), 5);
    // spinning particles: erotate and the largest force are not zero past the start
    assert!(thermo[1..].iter().all(|r| r[3] > 0.0 && r[4] > 0.0));
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 1 3 1")] {
        let (p, f, t) = outputs(n, grid);
        close(&numbers(&printed), &numbers(&p), "fix print to the log");
        let f: Vec<String> = f.lines().map(str::to_string).collect();
        assert_eq!(f[0], "# my title", "one title, from rank 0");
        close(&numbers(&file_lines), &numbers(&f), "fix print file");
        close(&thermo, &t, "thermo");
    }
}

#[test]
fn fix_move_dump_columns_on_ranks_match_the_serial_fast_path() {
    // fix move keeps each atom's start position by ID on every rank: rank 0 writes its
    // `f_` columns for every gathered atom (a mover crossing the periodic x faces, a second
    // one defined between runs)
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine/in.dump_fix_move");
    let deck = std::fs::read_to_string(path)
        .unwrap()
        .replace("post/", "${dir}/");
    let dumps = |n: usize, grid: &str| {
        let dir = scratch(&format!("fix-move-{n}"));
        let deck = deck.replace("units si\n", &format!("units si\n{grid}\n"));
        run_in(&dir, &deck, n, "");
        let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
        let out = [read("fix_move.exact.dump"), read("fix_wiggle.exact.dump")];
        let _ = std::fs::remove_dir_all(&dir);
        out
    };
    let serial = dumps(0, "");
    let snaps = regolith::io::dump_compare::parse(&serial[0]).unwrap();
    // the top atoms' start x is not zero, the free atoms' is
    let last = snaps.last().unwrap();
    assert!(last.rows.values().any(|r| r[7] > 0.0));
    assert!(last.rows.values().any(|r| r[7] == 0.0));
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 3 1 1")] {
        let got = dumps(n, grid);
        for (a, b) in serial.iter().zip(&got) {
            let d = common::scale_deviation(a, b);
            assert!(d < 1e-10, "{grid}: {d:e}");
        }
    }
}

#[test]
fn local_gran_vtk_on_ranks_writes_every_ranks_contacts() {
    // compat deck vtk_contact_point: 60 spheres poured into a cylinder, their contacts as
    // VTK lines every 1000 steps; on ranks rank 0 writes every rank's contacts (in rank
    // order, so compared as a set: each contact's three points as printed)
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("compat/engine/in.vtk_contact_point");
    let deck = std::fs::read_to_string(path)
        .unwrap()
        .replace("post/", "${dir}/");
    let contacts = |n: usize, grid: &str| {
        let dir = scratch(&format!("local-vtk-{n}"));
        let deck = deck.replace("units si\n", &format!("units si\n{grid}\n"));
        run_in(&dir, &deck, n, "");
        let sets: Vec<Vec<Vec<String>>> = [0, 1000, 2000, 3000]
            .iter()
            .map(|step| {
                let text =
                    std::fs::read_to_string(dir.join(format!("contacts{step}.vtk"))).unwrap();
                let mut words = text.split_whitespace();
                let count: usize = words
                    .by_ref()
                    .skip_while(|w| *w != "POINTS")
                    .nth(1)
                    .unwrap()
                    .parse()
                    .unwrap();
                let floats: Vec<String> =
                    words.skip(1).take(3 * count).map(str::to_string).collect();
                let mut set: Vec<Vec<String>> = floats.chunks(9).map(<[String]>::to_vec).collect();
                set.sort();
                set
            })
            .collect();
        let _ = std::fs::remove_dir_all(&dir);
        sets
    };
    let serial = contacts(0, "");
    assert!(
        serial[3].len() > 5,
        "contacts at the end: {}",
        serial[3].len()
    );
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 1 3 1")] {
        assert!(contacts(n, grid) == serial, "{grid}: other contacts");
    }
}

/// The log of `deck` on `n` ranks (0: serial).
fn log_of(deck: &str, n: usize, tag: &str) -> String {
    let dir = scratch(tag);
    let path = dir.join("in.deck");
    std::fs::write(&path, deck.replace("${dir}", &dir.to_string_lossy())).unwrap();
    let (dump, log) = (dir.join("out.dump"), dir.join("log.txt"));
    let opts = |size: usize, rank: usize| {
        let mut o = options(&path, &dump, "processors * 1 1", size.max(1));
        o.ranks.rank = rank;
        o.log = Some(log.to_string_lossy().into_owned());
        o
    };
    let status = common::run_on_ranks(n, opts);
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{tag}: {status:?}"
    );
    assert!(
        dir.join("made").is_dir(),
        "{tag}: shell mkdir made no folder"
    );
    let text = std::fs::read_to_string(&log).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    text
}

#[test]
fn the_time_step_check_and_shell_run_on_ranks_as_on_one_process() {
    let deck = BED
        .replace(
            "fix integr all nve/sphere",
            "fix integr all nve/sphere
shell mkdir ${dir}/made
fix ts all check/timestep/gran 50 0.001 0.001",
        )
        .replace(
            "thermo_style custom step atoms ke",
            "thermo_style custom step atoms ke f_ts[1] f_ts[2] f_ts[3]
thermo_modify format float %.16g",
        )
        .replace("${grid}", "processors * 1 1")
        .replace("${out}", "${dir}/out.dump");
    let serial = log_of(&deck, 0, "ts-serial");
    let warnings = |log: &str| {
        log.lines()
            .filter(|l| l.starts_with("WARNING: time-step is"))
            .map(String::from)
            .collect::<Vec<_>>()
    };
    // one check at each multiple of 50 steps, each over both limits (the Rayleigh and Hertz
    // warnings), the values in thermo from step 50 on
    let want = warnings(&serial);
    assert_eq!(want.len(), 6, "{want:?}");
    let serial_rows = thermo_table(&serial);
    assert_eq!(serial_rows.len(), 5);
    assert!(serial_rows[1][3] > 0.001 && serial_rows[1][4] > 0.001 && serial_rows[1][5] > 0.0);
    for n in [2, 3] {
        let log = log_of(&deck, n, &format!("ts-{n}"));
        assert_eq!(warnings(&log).len(), want.len(), "{n} ranks");
        for (a, b) in serial_rows.iter().zip(thermo_table(&log)) {
            for k in 3..6 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-10 * a[k].abs(),
                    "{n} ranks: f_ts[{}] {} against {}",
                    k - 2,
                    a[k],
                    b[k]
                );
            }
        }
    }
}

#[test]
fn per_atom_stress_on_ranks_matches_the_serial_fast_path() {
    // the pair virial of each particle (with the kinetic part) in the dump
    let deck = BED
        .replace(
            "fix integr all nve/sphere",
            "fix integr all nve/sphere\ncompute stress all stress/atom",
        )
        .replace(
            "omegaz radius",
            "omegaz radius c_stress[1] c_stress[3] c_stress[4]",
        )
        .replace("%.17g\"", "%.17g %.17g %.17g %.17g\"");
    let grids = [(2, "processors 2 1 1"), (3, "processors 1 3 1")];
    let (serial, _) = on_grids(&deck, &grids, "stress");
    // the stresses are not trivial: the bed presses on its lower layers
    let last = regolith::io::dump_compare::parse(&serial).unwrap();
    let rows = &last.last().unwrap().rows;
    let pressed = rows.values().filter(|r| r[15] < 0.0 && r[16] < 0.0).count();
    assert!(
        pressed > rows.len() / 2,
        "{pressed} of {} compressed",
        rows.len()
    );
}

#[test]
fn prescribed_motion_on_ranks_matches_the_serial_fast_path() {
    // the lowest spheres shaken sideways and up (wiggle), a few others pushed (linear),
    // defined between the runs as the shock deck does
    let deck = BED.replace(
        "run 50\n",
        "group low id <= 40
group push id 100:110
group free subtract all low push
fix integr free nve/sphere
fix shake low move wiggle 2e-5 0.0 5e-5 0.0005
fix slide push move linear 0.0 0.01 NULL
run 50
",
    );
    let grids = [(2, "processors 2 1 1"), (3, "processors 1 3 1")];
    let (serial, _) = on_grids(&deck, &grids, "move");
    // the shaken spheres follow the wiggle: their vertical speed is the prescribed one
    let snaps = regolith::io::dump_compare::parse(&serial).unwrap();
    let last = snaps.last().unwrap();
    let t = 50.0 * 2e-6 / 0.0005;
    let w = 2.0 * std::f64::consts::PI / 0.0005;
    let vz = 5e-5 * w * (2.0 * std::f64::consts::PI * t).cos();
    for id in 1..=40 {
        let got = last.rows[&id][7];
        assert!(
            (got - vz).abs() <= 1e-2 * vz.abs(),
            "atom {id}: vz {got} against {vz}"
        );
    }
    assert!(last.rows[&105][6] == 0.01);
}

/// Every field `compute pair/gran/local` reports (LIGGGHTS's column order: positions,
/// velocities, IDs and periodic flag, force and its parts, torque and its parts, the
/// tangential history, contact area, overlap, contact point).
const LOCAL_FIELDS: &str = "pos vel id force force_normal force_tangential torque \
    torque_normal torque_tangential history contactArea delta contactPoint";

/// Columns of [`LOCAL_FIELDS`] with a three-value history.
const LOCAL_COLUMNS: usize = 41;

/// The bed with every contact in a `dump local` at full precision, the list rebuilt every
/// step and LIGGGHTS's spatial sort every 40 steps (the pairs are reported from the atom
/// first in its order).
fn bed_with_contacts() -> String {
    let columns: Vec<String> = (1..=LOCAL_COLUMNS).map(|k| format!("c_pl[{k}]")).collect();
    let format = vec!["%.17g"; LOCAL_COLUMNS].join(" ");
    BED.replace(
        "create_box 1 reg",
        "create_box 1 reg\natom_modify sort 40 0.0",
    )
    .replace(
        "neigh_modify delay 0",
        "neigh_modify delay 0 every 1 check no",
    )
    .replace(
        "dump d all custom 25 ${out}",
        "dump d all custom 25 ${out}.atoms",
    )
    .replace(
        "fix integr all nve/sphere",
        &format!(
            "fix integr all nve/sphere
compute pl all pair/gran/local {LOCAL_FIELDS}
dump dl all local 25 ${{out}} {}
dump_modify dl format \"{format}\"",
            columns.join(" ")
        ),
    )
}

/// The snapshots of a `dump local` file: (step, the header's entry count, the rows).
fn local_snapshots(text: &str) -> Vec<(i64, usize, Vec<Vec<f64>>)> {
    let mut out = Vec::new();
    let mut lines = text.lines();
    while let Some(line) = lines.next() {
        if line != "ITEM: TIMESTEP" {
            continue;
        }
        let step = lines.next().unwrap().trim().parse().unwrap();
        assert_eq!(lines.next(), Some("ITEM: NUMBER OF ENTRIES"));
        let count: usize = lines.next().unwrap().trim().parse().unwrap();
        let header = lines.by_ref().find(|l| l.starts_with("ITEM: ENTRIES"));
        assert!(header.is_some(), "step {step}: no entries line");
        let rows = lines
            .by_ref()
            .take(count)
            .map(|l| l.split_whitespace().map(|w| w.parse().unwrap()).collect())
            .collect();
        out.push((step, count, rows));
    }
    out
}

/// Largest difference of the rows of `b` from those of `a` in units of each column's scale
/// (its largest magnitude over all of `a`; the normal and tangential parts of the force and
/// torque at least the whole's, since the torque's normal part is round-off alone), rows
/// matched by the reporting atom's and its partner's IDs (columns 13, 14): the same pairs
/// reported from the same side, the headers' counts equal.
fn local_deviation(a: &str, b: &str) -> f64 {
    let (a, b) = (local_snapshots(a), local_snapshots(b));
    assert_eq!(a.len(), b.len(), "snapshot counts");
    let mut scale: Vec<f64> = (0..LOCAL_COLUMNS)
        .map(|c| {
            a.iter()
                .flat_map(|s| &s.2)
                .map(|r| r[c].abs())
                .fold(0.0, f64::max)
        })
        .collect();
    // force 16-18 with its parts 19-24, torque 25-27 with its parts 28-33 (1-based)
    for whole in [15, 24] {
        let s = scale[whole..whole + 3].iter().copied().fold(0.0, f64::max);
        for part in &mut scale[whole + 3..whole + 9] {
            *part = part.max(s);
        }
    }
    let mut worst: f64 = 0.0;
    for (sa, sb) in a.iter().zip(&b) {
        assert_eq!((sa.0, sa.1), (sb.0, sb.1), "step and entry count");
        assert_eq!(sb.2.len(), sb.1, "step {}: rows against the count", sb.0);
        let by_ids = |rows: &[Vec<f64>]| -> std::collections::BTreeMap<(i64, i64), Vec<f64>> {
            rows.iter()
                .map(|r| ((r[12] as i64, r[13] as i64), r.clone()))
                .collect()
        };
        let (ra, rb) = (by_ids(&sa.2), by_ids(&sb.2));
        assert_eq!(ra.len(), sa.1, "step {}: a pair reported twice", sa.0);
        assert!(
            ra.keys().eq(rb.keys()),
            "step {}: other pairs or other sides",
            sa.0
        );
        for (k, r) in &ra {
            for c in 0..LOCAL_COLUMNS {
                if scale[c] > 0.0 {
                    worst = worst.max((r[c] - rb[k][c]).abs() / scale[c]);
                }
            }
        }
    }
    worst
}

/// The `dump local` of `deck` on `n` ranks (0: one process), on the fast path or not.
fn local_dump_of(deck: &str, n: usize, fast: bool, tag: &str) -> String {
    let dir = scratch(tag);
    let path = dir.join("in.deck");
    std::fs::write(&path, deck).unwrap();
    let dump = dir.join("local.dump");
    let grid = if n == 3 {
        "processors 1 3 1"
    } else {
        "processors * 1 1"
    };
    let opts = |size: usize, rank: usize| {
        let mut o = options(&path, &dump, grid, size.max(1));
        o.ranks.rank = rank;
        o.fast = fast;
        o
    };
    let status = common::run_on_ranks(n, opts);
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{tag}: {status:?}"
    );
    let text = std::fs::read_to_string(&dump).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    text
}

#[test]
fn pair_contacts_on_ranks_are_those_of_one_process() {
    let deck = bed_with_contacts();
    let exact = local_dump_of(&deck, 0, false, "local-exact");
    let serial = local_dump_of(&deck, 0, true, "local-serial");
    // the fast path reports each pair from the side the exact path (LIGGGHTS) does
    let d = local_deviation(&exact, &serial);
    assert!(
        d < 1e-10,
        "the fast path differs from the exact path by {d:e}"
    );
    let snaps = local_snapshots(&serial);
    assert_eq!(snaps.len(), 7, "steps 0..150 every 25 (the run's end once)");
    // contacts in the bed, some across the periodic faces (flag in column 15), with
    // friction (tangential history) and overlap
    for (step, count, rows) in &snaps {
        assert!(*count > 300, "step {step}: {count} contacts");
        assert!(rows.iter().any(|r| r[14] == 1.0), "step {step}");
        assert!(rows.iter().all(|r| r[37] > 0.0), "step {step}: overlaps");
        assert!(
            *step == 0 || rows.iter().any(|r| r[33] != 0.0),
            "step {step}: history"
        );
    }
    for n in [2, 3] {
        let ranks = local_dump_of(&deck, n, true, &format!("local-{n}"));
        let d = local_deviation(&serial, &ranks);
        assert!(d < 1e-10, "{n} ranks differ from one process by {d:e}");
        if n == 2 {
            let again = local_dump_of(&deck, n, true, "local-again");
            assert!(again == ranks, "2 ranks run twice gave different dumps");
        }
    }
}

/// The bed with the faces `faces` (some shrink-wrapped), its list rebuilt every step (the
/// box follows the particles at every step) and the box in thermo at full precision.
fn shrink_bed(faces: &str) -> String {
    BED.replace("boundary p p f", &format!("boundary {faces}"))
        .replace(
            "neigh_modify delay 0",
            "neigh_modify delay 0 every 1 check no",
        )
        .replace(
            "thermo_style custom step atoms ke",
            "thermo_style custom step atoms ke vol lx ly lz xlo xhi zlo zhi
thermo_modify format float %.16g",
        )
        .replace("thermo 50", "thermo 10")
}

/// Largest difference of thermo table `b` from `a` in units of each column's scale (its
/// largest magnitude in `a`); the tables have the same rows.
fn thermo_deviation(a: &[Vec<f64>], b: &[Vec<f64>]) -> f64 {
    assert_eq!(a.len(), b.len(), "thermo rows");
    let mut worst: f64 = 0.0;
    for (ra, rb) in a.iter().zip(b) {
        assert_eq!(ra.len(), rb.len(), "thermo columns");
        for (k, (x, y)) in ra.iter().zip(rb).enumerate() {
            let scale = a.iter().map(|r| r[k].abs()).fold(0.0, f64::max);
            if scale > 0.0 {
                worst = worst.max((x - y).abs() / scale);
            }
        }
    }
    worst
}

/// Largest difference of the box bounds of dump `b`'s snapshots from `a`'s, in units of
/// the largest bound of `a`.
fn box_deviation(a: &str, b: &str) -> f64 {
    let (a, b) = (
        regolith::io::dump_compare::parse(a).unwrap(),
        regolith::io::dump_compare::parse(b).unwrap(),
    );
    assert_eq!(a.len(), b.len(), "snapshot counts");
    let scale = a
        .iter()
        .flat_map(|s| s.bounds.iter().flatten())
        .map(|v| v.abs())
        .fold(0.0, f64::max);
    let mut worst: f64 = 0.0;
    for (sa, sb) in a.iter().zip(&b) {
        for (x, y) in sa.bounds.iter().flatten().zip(sb.bounds.iter().flatten()) {
            worst = worst.max((x - y).abs() / scale);
        }
    }
    worst
}

#[test]
fn shrink_wrapped_faces_on_ranks_follow_the_particles_of_every_rank() {
    // split along the shrink-wrapped direction (the bricks follow the box) and across it
    let cases: [(&str, &[(usize, &str)]); 2] = [
        (
            "p p s",
            &[
                (2, "processors 1 1 2"),
                (3, "processors 1 1 3"),
                (1, "processors 1 1 1"),
            ],
        ),
        ("f f s", &[(2, "processors 2 1 1"), (3, "processors 1 3 1")]),
    ];
    for (faces, grids) in cases {
        let deck = shrink_bed(faces);
        let tag = format!("shrink-{}", faces.replace(' ', ""));
        let (serial, _) = on_grids(&deck, grids, &tag);
        let (_, log) = outputs_of(&deck, 0, "", &format!("{tag}-log"));
        let want = thermo_table(&log);
        // steps 0..100 every 10, then 100..150: the box's bottom and top follow the bed at
        // every step (the bottom layer settles, the top spreads)
        assert_eq!(want.len(), 17, "{faces}");
        let (first, last) = (&want[0], &want[want.len() - 1]);
        assert!(
            last[9] < first[9] && last[10] != first[10],
            "{faces}: {first:?} {last:?}"
        );
        // through a shrink-wrapped face no particle is lost (through the fixed ones some are)
        assert!(faces != "p p s" || want.iter().all(|r| r[1] == first[1]));
        for &(n, grid) in grids {
            let (dump, log) = outputs_of(&deck, n, grid, &format!("{tag}-log-{n}"));
            let got = thermo_table(&log);
            let d = thermo_deviation(&want, &got);
            assert!(d < 1e-10, "{faces}, {grid}: thermo differs by {d:e}");
            let d = box_deviation(&serial, &dump);
            assert!(d < 1e-10, "{faces}, {grid}: dump box differs by {d:e}");
        }
    }
}

/// The settings a restart file does not hold, from the bed's deck.
fn bed_settings() -> &'static str {
    BED.split_once("neighbor 0.0005 bin")
        .and_then(|(_, rest)| rest.split_once("lattice"))
        .unwrap()
        .0
}

/// A deck that reads restart file `file` on the processor grid `${grid}` with the bed's
/// settings, its box in thermo every 10 steps, then `rest`.
fn read_deck(file: &str, rest: &str) -> String {
    format!(
        "atom_style granular\natom_modify map array\nnewton off\ncommunicate single vel yes\n\
         units si\n${{grid}}\nread_restart {file}\nneighbor 0.0005 bin{}\
         fix gr all gravity 9.81 vector 0 0 -1\nfix integr all nve/sphere\ntimestep 2e-6\n\
         thermo_style custom step atoms ke vol lz zlo zhi\nthermo_modify format float %.16g\n\
         thermo 10\n{rest}",
        bed_settings()
    )
}

/// The atoms of a restart file by ID, each as its numbers (position, ID, type, mask, image,
/// velocity, radius, mass, density, angular velocity, then its fixes' blocks).
fn restart_atoms(path: &std::path::Path) -> std::collections::BTreeMap<i64, Vec<f64>> {
    let r = regolith::io::restart::read(&path.to_string_lossy()).unwrap();
    r.atoms
        .iter()
        .map(|a| {
            let mut v = a.x.to_vec();
            v.extend([a.id, a.kind, a.mask, a.image].map(|k| k as f64));
            v.extend(a.v);
            v.extend([a.radius, a.mass, a.density]);
            v.extend(a.omega);
            v.extend(a.extra.iter().flatten());
            (a.id, v)
        })
        .collect()
}

/// Largest difference of restart file `b`'s atoms from `a`'s in units of each number's
/// scale (its largest magnitude over `a`'s atoms); the same atoms with the same contacts
/// (a contact's partner ID and the counts are stored as the bits of small integers and
/// must be equal).
fn restart_deviation(a: &std::path::Path, b: &std::path::Path) -> f64 {
    let (a, b) = (restart_atoms(a), restart_atoms(b));
    assert!(a.keys().eq(b.keys()), "other atoms");
    let width = a.values().map(Vec::len).max().unwrap_or(0);
    let scale: Vec<f64> = (0..width)
        .map(|k| {
            a.values()
                .filter_map(|v| v.get(k))
                .map(|x| x.abs())
                .fold(0.0, f64::max)
        })
        .collect();
    let mut worst: f64 = 0.0;
    for (id, va) in &a {
        let vb = &b[id];
        assert_eq!(va.len(), vb.len(), "atom {id}: other contacts");
        for (k, (x, y)) in va.iter().zip(vb).enumerate() {
            if x.to_bits() < 1 << 32 || y.to_bits() < 1 << 32 {
                assert_eq!(x.to_bits(), y.to_bits(), "atom {id}, number {k}");
            } else if scale[k] > 0.0 {
                worst = worst.max((x - y).abs() / scale[k]);
            }
        }
    }
    worst
}

#[test]
fn a_restart_with_a_shrink_wrapped_top_runs_and_is_written_on_ranks() {
    // a bed written with a shrink-wrapped top reaching the top of its box, as the lunar
    // channel's bed is; read back, thrown up (the shock) so the box follows it up
    let dir = scratch("lunar");
    let write = BED
        .replace("boundary p p f", "boundary p p fm")
        .replace("0 0.01488 0 0.01488 0 0.02", "0 0.01488 0 0.01488 0 0.0176")
        .replace("run 50\n", "write_restart ${dir}/bed.restart\n");
    run_in(&dir, &write, 0, "");
    let bed = dir.join("bed.restart");
    let read = read_deck(
        &bed.to_string_lossy(),
        "dump d all custom 25 ${out} id type x y z vx vy vz fx fy fz omegax omegay omegaz radius
dump_modify d sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 0
write_restart ${dir}/zero.restart
neigh_modify delay 0 every 1 check no
velocity all set 0.0 0.0 2.0
run 100
write_restart ${dir}/after.restart
write_restart ${dir}/after.%.restart
",
    );
    let runs: Vec<(usize, &str, std::path::PathBuf)> = [
        (0, "", "serial"),
        (1, "processors 1 1 1", "one"),
        (2, "processors 1 1 2", "two"),
        (3, "processors 1 3 1", "three"),
        (2, "processors 1 1 2", "again"),
    ]
    .into_iter()
    .map(|(n, grid, tag)| {
        let d = dir.join(tag);
        std::fs::create_dir_all(&d).unwrap();
        (n, grid, d)
    })
    .collect();
    let logs: Vec<String> = runs
        .iter()
        .map(|(n, grid, d)| run_in(d, &read, *n, grid))
        .collect();
    let serial_dir = &runs[0].2;
    let serial_dump = std::fs::read_to_string(serial_dir.join("out.dump")).unwrap();
    let want = thermo_table(&logs[0]);
    // the box: the top at the file's m face (its box top), then above it with the bed
    let (zhi, top) = (0.0176, want.last().unwrap()[6]);
    assert_eq!(want.len(), 1 + 11, "run 0, then steps 0..100 every 10");
    assert!((want[0][6] - zhi).abs() < 1e-12, "{:?}", want[0]);
    assert!(top > zhi + 1e-4, "the top {top}");
    let restored = |log: &str| {
        log.lines()
            .filter(|l| l.starts_with("Resetting") && l.contains("Fix contacthistory"))
            .count()
    };
    assert_eq!(restored(&logs[0]), 2, "global and per-atom state");
    for ((n, grid, d), log) in runs.iter().zip(&logs).skip(1) {
        assert_eq!(restored(log), 2, "{n} ranks: {log}");
        let dump = std::fs::read_to_string(d.join("out.dump")).unwrap();
        let dev = [
            common::scale_deviation(&serial_dump, &dump),
            box_deviation(&serial_dump, &dump),
            thermo_deviation(&want, &thermo_table(log)),
            restart_deviation(&serial_dir.join("after.restart"), &d.join("after.restart")),
        ];
        assert!(
            dev.iter().all(|&v| v < 1e-10),
            "{n} ranks ({grid}): dump, box, thermo, restart differ by {dev:?}"
        );
        // nothing has moved after run 0: the file one process writes, byte for byte
        let bytes = |d: &std::path::Path, f: &str| std::fs::read(d.join(f)).unwrap();
        assert!(
            bytes(d, "zero.restart") == bytes(serial_dir, "zero.restart"),
            "{n} ranks: zero.restart differs from one process's"
        );
        // one file per rank, read back as the same atoms as the single file
        let r = regolith::io::restart::read(&d.join("after.%.restart").to_string_lossy()).unwrap();
        assert_eq!(
            r.int(7),
            Some(*n.max(&1) as i64),
            "processor count in the base file"
        );
        assert!(!d.join(format!("after.{}.restart", n.max(&1))).exists());
        let single = restart_atoms(&d.join("after.restart"));
        let split = restart_atoms(&d.join("after.%.restart"));
        assert!(single == split, "{n} ranks: the % files hold other atoms");
        // the order one process writes: by the IDs the serial file lists
        let order = |d: &std::path::Path| -> Vec<i64> {
            let r = regolith::io::restart::read(&d.join("after.restart").to_string_lossy());
            r.unwrap().atoms.iter().map(|a| a.id).collect()
        };
        assert_eq!(order(d), order(serial_dir), "{n} ranks: atom order");
    }
    // the contacts are in the files (the bed is touching): 16 numbers, the floor's history
    // (3), the contact count and 4 numbers per contact
    for f in ["zero.restart", "after.restart"] {
        let atoms = restart_atoms(&serial_dir.join(f));
        let touching = atoms.values().filter(|v| v.len() >= 24).count();
        assert!(
            touching > atoms.len() / 2,
            "{f}: {touching} of {}",
            atoms.len()
        );
    }
    // run to run on 2 ranks: the same bytes
    let (two, again) = (&runs[2].2, &runs[4].2);
    for f in [
        "after.restart",
        "after.0.restart",
        "after.1.restart",
        "after.base.restart",
    ] {
        assert!(
            std::fs::read(two.join(f)).unwrap() == std::fs::read(again.join(f)).unwrap(),
            "{f} differs run to run"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn restart_files_written_on_any_grid_without_periodic_faces_are_the_same_bytes() {
    // fixed and shrink-wrapped faces: any grid gives the same bits, so the same file
    let deck =
        shrink_bed("f f s").replace("run 50\n", "run 50\nwrite_restart ${dir}/end.restart\n");
    let dir = scratch("restart-grids");
    let mut files = Vec::new();
    for (n, grid) in [
        (2, "processors 2 1 1"),
        (3, "processors 1 1 3"),
        (4, "processors 2 2 1"),
    ] {
        let d = dir.join(n.to_string());
        std::fs::create_dir_all(&d).unwrap();
        run_in(&d, &deck, n, grid);
        files.push(std::fs::read(d.join("end.restart")).unwrap());
    }
    assert!(
        files.iter().all(|f| *f == files[0]),
        "restart files differ between grids"
    );
    // the serial file holds the same atoms in the same order, within round-off
    let d = dir.join("serial");
    std::fs::create_dir_all(&d).unwrap();
    run_in(&d, &deck, 0, "");
    let dev = restart_deviation(&d.join("end.restart"), &dir.join("2/end.restart"));
    assert!(dev < 1e-10, "2 ranks differ from one process by {dev:e}");
    let ids = |f: &std::path::Path| -> Vec<i64> {
        let r = regolith::io::restart::read(&f.to_string_lossy()).unwrap();
        r.atoms.iter().map(|a| a.id).collect()
    };
    let serial_ids = ids(&d.join("end.restart"));
    assert!(serial_ids.len() > 150);
    assert_eq!(ids(&dir.join("3/end.restart")), serial_ids);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Thermo of Debian's LIGGGHTS 3.8.0 reading `ranks_inputs/liggghts_np2.restart` (written by
/// `mpirun -np 2 liggghts -in in.liggghts_np2`) or its `%` form, on one process and on 2 and
/// 3: step, atoms, ke, vol, lz, zlo, zhi (the kinetic energy's last digit differs between
/// its processor counts).
const LIGGGHTS_READS_NP2: [[f64; 7]; 3] = [
    [
        100.0,
        252.0,
        0.0002674241035887983,
        3.344550958948044e-06,
        0.01510539043055937,
        0.002353491419140677,
        0.01745888184970004,
    ],
    [
        110.0,
        252.0,
        0.000240916426068446,
        3.346280351833156e-06,
        0.01511320109185832,
        0.002347579548812927,
        0.01746078064067125,
    ],
    [
        120.0,
        252.0,
        0.0002188339773479873,
        3.34812995881553e-06,
        0.01512155469027999,
        0.002341306302017337,
        0.01746286099229732,
    ],
];

#[test]
fn restart_files_liggghts_wrote_on_two_processors_are_read_on_any_rank_count() {
    let inputs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/ranks_inputs");
    let want: Vec<Vec<f64>> = LIGGGHTS_READS_NP2.iter().map(|r| r.to_vec()).collect();
    for file in ["liggghts_np2.restart", "liggghts_np2.%.restart"] {
        let deck = read_deck(
            &inputs.join(file).to_string_lossy(),
            "neigh_modify delay 0 every 1 check no\nrun 20\n",
        );
        for (n, grid) in [(0, ""), (2, "processors 1 1 2"), (3, "processors 1 3 1")] {
            let dir = scratch(&format!("liggghts-np2-{n}-{}", file.len()));
            let log = run_in(&dir, &deck, n, grid);
            let _ = std::fs::remove_dir_all(&dir);
            let d = thermo_deviation(&want, &thermo_table(&log));
            assert!(
                d < 1e-10,
                "{file} on {n} ranks differs from LIGGGHTS by {d:e}"
            );
            // LIGGGHTS's warnings: another processor count; another grid than the deck's
            let said = |w: &str| log.lines().filter(|l| l.contains(w)).count();
            let other_count = usize::from(n != 2);
            assert_eq!(
                said("Restart file used different # of processors"),
                other_count,
                "{log}"
            );
            let other_grid = usize::from(n == 3);
            assert_eq!(
                said("Restart file used different 3d processor grid"),
                other_grid,
                "{log}"
            );
        }
    }
}

#[test]
fn periodic_restart_files_on_ranks_are_those_of_one_process_and_read_back() {
    // `restart N root` (one file, or `%`: a base file and one per rank) and `restart N a b`
    // during the bed's two runs, then the file of step 100 read back and run on
    let deck = BED.replace(
        "run 100\n",
        "restart 50 ${dir}/bed.*.restart\nrestart 50 ${dir}/a.%.restart ${dir}/b.%.restart\nrun 100\n",
    );
    let dir = scratch("periodic-restart");
    let grids = [
        (0, "", "serial"),
        (2, "processors 2 1 1", "two"),
        (3, "processors 1 3 1", "three"),
    ];
    let mut dumps = Vec::new();
    for (n, grid, tag) in grids {
        let d = dir.join(tag);
        std::fs::create_dir_all(&d).unwrap();
        run_in(&d, &deck, n, grid);
        dumps.push(std::fs::read_to_string(d.join("out.dump")).unwrap());
    }
    let serial = dir.join("serial");
    for ((n, grid, tag), dump) in grids.iter().zip(&dumps).skip(1) {
        let d = dir.join(tag);
        let dev = common::scale_deviation(&dumps[0], dump);
        assert!(dev < 1e-10, "{grid}: the run differs by {dev:e}");
        for step in [50, 100, 150] {
            let f = format!("bed.{step}.restart");
            let dev = restart_deviation(&serial.join(&f), &d.join(&f));
            assert!(
                dev < 1e-10,
                "{grid}: {f} differs from one process's by {dev:e}"
            );
            // the order one process writes after the run: the serial file's IDs in turn
            // are those of the exact path, which every rank count gathers
            let r = regolith::io::restart::read(&d.join(&f).to_string_lossy()).unwrap();
            assert_eq!(r.atoms.len(), 252);
            assert_eq!(r.int(7), Some(1), "one file: written as by one processor");
        }
        // the two names in turn: a at 50 and 150, b at 100, one file per rank each
        for (name, step) in [("a", 150), ("b", 100)] {
            let split = d.join(format!("{name}.%.restart"));
            let base = regolith::io::restart::read(&split.to_string_lossy()).unwrap();
            assert_eq!(base.int(7), Some(*n as i64), "{name}: processor count");
            assert!(d.join(format!("{name}.{}.restart", n - 1)).exists());
            assert!(!d.join(format!("{name}.{n}.restart")).exists());
            let single = restart_atoms(&d.join(format!("bed.{step}.restart")));
            assert!(
                restart_atoms(&split) == single,
                "{grid}: {name} holds other atoms"
            );
        }
    }
    // the contacts are in the files: most atoms touch something
    let atoms = restart_atoms(&serial.join("bed.100.restart"));
    let touching = atoms.values().filter(|v| v.len() >= 24).count();
    assert!(touching > atoms.len() / 2, "{touching} of {}", atoms.len());
    // the file of step 100 read back on one process and on ranks: the second run again
    // from its first step (the forces of the reading run's setup differ from those the
    // writing run had at step 100 in LIGGGHTS 3.8.0 as well)
    let tail = |dump: &str| dump[dump.find("ITEM: TIMESTEP\n125\n").unwrap()..].to_string();
    let want = tail(&dumps[0]);
    for (n, grid, tag) in [(0, "", "read-serial"), (2, "processors 2 1 1", "read-two")] {
        let d = dir.join(tag);
        std::fs::create_dir_all(&d).unwrap();
        let file = dir.join("two/bed.100.restart");
        let read = read_deck(
            &file.to_string_lossy(),
            "dump d all custom 25 ${out} id type x y z vx vy vz fx fy fz omegax omegay omegaz radius
dump_modify d sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
restart 50 ${dir}/again.*.restart
run 50
",
        );
        run_in(&d, &read, n, grid);
        // (the file due at step 150 wraps the particles into the box there, as it did in
        // the run that wrote the file read)
        let dump = tail(&std::fs::read_to_string(d.join("out.dump")).unwrap());
        let dev = common::scale_deviation(&want, &dump);
        assert!(
            dev < 1e-10,
            "{tag}: differs from the run that wrote it by {dev:e}"
        );
        let again = d.join("again.150.restart");
        let dev = restart_deviation(&serial.join("bed.150.restart"), &again);
        assert!(
            dev < 1e-10,
            "{tag}: its file of step 150 differs by {dev:e}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
