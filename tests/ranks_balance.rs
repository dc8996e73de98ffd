//! Load balancing on several ranks, in-process (N ranks are N threads, each running the
//! whole deck as `mpirun -np N regolith -sf fast -in deck` would): `balance` and `fix
//! balance` on a heaped bed whose left third holds most particles. The per-rank counts
//! after balancing are within the threshold, the dumps equal the serial run's (within 1e-10
//! of each column's scale; the cuts only decide which rank owns a particle), one process
//! prints what LAMMPS prints with one rank, and bad arguments are refused with their line.

#[macro_use]
mod common;

use regolith::cli::DeckOptions;
use regolith::error::ExitStatus;
use regolith::util::comm::Ranks;

/// A heap of 84 spheres against the left of a periodic box and a layer of 24 on the floor
/// to its right (108 in all), settling; `${balance}` is replaced by the balancing lines.
const HEAP: &str = concat!(
    "\
atom_style granular
atom_modify map array
boundary p p f
newton off
communicate single vel yes
units si
${grid}
region reg block 0 0.02976 0 0.00744 0 0.02 units box
create_box 1 reg
neighbor 0.0005 bin
neigh_modify delay 0
",
    soft_material_on_a_floor!(),
    "lattice sc 0.00248
region heap block 0 0.0099 0 0.00744 0.0013 0.019 units box
region layer block 0.0099 0.0297 0 0.00744 0.0013 0.004 units box
create_atoms 1 region heap
create_atoms 1 region layer
set group all diameter 0.0025 density 2500
displace_atoms all random 0.0001 0.0001 0.0001 15485863
velocity all set 0.01 0.0 -0.05
fix gr all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
timestep 2e-6
${balance}
thermo_style custom step atoms ke
thermo 50
dump d all custom 25 ${out} id type x y z vx vy vz fx fy fz omegax omegay omegaz radius
dump_modify d sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 150
"
);

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

/// The dump and the log of the heap with `balance` lines run on `n` ranks (0: the serial
/// fast path) with `processors` line `grid`.
fn run_heap(balance: &str, n: usize, grid: &str, tag: &str) -> (String, String) {
    run_heap_on(balance, n, grid, tag, true)
}

/// [`run_heap`] on the fast path or (`fast` false, one process only) the exact path.
fn run_heap_on(balance: &str, n: usize, grid: &str, tag: &str, fast: bool) -> (String, String) {
    let dir = common::scratch_dir(&format!("balance-{tag}"));
    let path = dir.join("in.deck");
    std::fs::write(&path, HEAP.replace("${balance}", balance)).unwrap();
    let (dump, log) = (dir.join("out.dump"), dir.join("log.txt"));
    let opts = |size: usize, rank: usize| {
        let mut o = options(&path, &dump, grid, size.max(1));
        o.ranks.rank = rank;
        o.log = Some(log.to_string_lossy().into_owned());
        o.fast = fast;
        o
    };
    let status = common::run_on_ranks(n, opts);
    let log_text = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{tag} on {n} ranks: {status:?}\n{log_text}"
    );
    let text = std::fs::read_to_string(&dump).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (text, log_text)
}

/// The numbers after `label` on the log's lines that start with it (after blanks).
fn numbers_after(log: &str, label: &str) -> Vec<Vec<f64>> {
    log.lines()
        .filter_map(|l| l.trim_start().strip_prefix(label))
        .map(|rest| {
            rest.split_whitespace()
                .filter_map(|w| w.parse::<f64>().ok())
                .collect()
        })
        .collect()
}

/// Every run's `Nlocal` (ave, max, min) in the log.
fn nlocal(log: &str) -> Vec<[f64; 3]> {
    numbers_after(log, "Nlocal:")
        .into_iter()
        .map(|v| [v[0], v[1], v[2]])
        .collect()
}

#[test]
fn one_process_prints_what_lammps_prints_with_one_rank() {
    let (_, log) = run_heap("balance 1.0 shift x 10 1.1", 0, "", "serial-report");
    let start = log.find("Balancing ...").expect("report");
    let report: Vec<&str> = log[start..].lines().take(7).collect();
    assert_eq!(
        report,
        [
            "Balancing ...",
            "  iteration count = 0",
            "  initial/final maximal load/proc = 108 108",
            "  initial/final imbalance factor  = 1 1",
            "  x cuts: 0 1",
            "  y cuts: 0 1",
            "  z cuts: 0 1",
        ]
    );
    // below the threshold: only the first line, as LAMMPS returns there
    let (_, log) = run_heap("balance 1.1 shift x 10 1.1", 0, "", "serial-below");
    let start = log.find("Balancing ...").expect("report");
    assert!(!log[start..].contains("iteration count"), "{log}");
}

#[test]
fn balance_evens_the_counts_and_the_dumps_equal_the_serial_run() {
    let lines = "balance 1.0 shift x 20 1.05";
    let (serial, _) = run_heap(lines, 0, "", "cmd-serial");
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 3 1 1")] {
        // unbalanced: the uniform bricks
        let (plain, before) = run_heap("", n, grid, &format!("plain-{n}"));
        let (dump, log) = run_heap(lines, n, grid, &format!("cmd-{n}"));
        let loads = numbers_after(&log, "initial/final maximal load/proc =");
        let factors = numbers_after(&log, "initial/final imbalance factor  =");
        assert_eq!(loads.len(), 1, "{log}");
        let avg = 108.0 / n as f64;
        // the uniform bricks: the heap's rank holds most particles
        assert!(factors[0][0] > 1.4, "{n} ranks: {factors:?}");
        assert!(loads[0][1] <= 1.05 * avg, "{n} ranks: {loads:?}");
        assert!(factors[0][1] <= 1.05, "{n} ranks: {factors:?}");
        // the run starts with the balanced counts
        let runs = nlocal(&log);
        let unbalanced = nlocal(&before);
        assert!(runs[0][1] <= 1.05 * avg + 1.0, "{n} ranks: {runs:?}");
        assert!(unbalanced[0][1] > 1.3 * avg, "{n} ranks: {unbalanced:?}");
        let cuts = numbers_after(&log, "x cuts:");
        assert_eq!(cuts[0].len(), n + 1);
        assert!(cuts[0][1] < 1.0 / n as f64, "{cuts:?}");
        for (what, other) in [("uniform", &plain), ("balanced", &dump)] {
            let d = common::scale_deviation(&serial, other);
            assert!(d < 1e-10, "{n} ranks {what}: differs from serial by {d:e}");
        }
    }
    // the same rank count twice: the same bits
    let (again, _) = run_heap(lines, 2, "processors 2 1 1", "cmd-again");
    let (first, _) = run_heap(lines, 2, "processors 2 1 1", "cmd-first");
    assert!(again == first, "two runs on 2 ranks differ");
}

#[test]
fn fix_balance_keeps_the_counts_even_during_the_run() {
    let lines = "fix lb all balance 25 1.05 shift x 20 1.05";
    let with_values = |s: &str| {
        s.replace(
            "thermo_style custom step atoms ke",
            "thermo_style custom step atoms ke f_lb f_lb[1] f_lb[2] f_lb[3]",
        )
    };
    let deck_lines = lines.to_string();
    let (serial, serial_log) = {
        let text = with_values(HEAP);
        run_custom(&text, &deck_lines, 0, "", "fix-serial")
    };
    // one process: imbalance 1, every particle on it
    let rows = thermo_rows(&serial_log);
    assert!(
        rows.iter()
            .all(|r| r[3] == 1.0 && r[4] == 108.0 && r[6] == 1.0),
        "{rows:?}"
    );
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 3 1 1")] {
        let (dump, log) = run_custom(
            &with_values(HEAP),
            &deck_lines,
            n,
            grid,
            &format!("fix-{n}"),
        );
        let avg = 108.0 / n as f64;
        let rows = thermo_rows(&log);
        assert!(!rows.is_empty());
        for r in &rows {
            // after each look: at most the threshold, or left alone below it
            assert!(r[3] <= 1.05 + 1e-12, "{n} ranks: {r:?}");
            assert!(r[4] <= 1.05 * avg + 1e-9, "{n} ranks: {r:?}");
        }
        // the setup rebalanced the heap: the factor before it is the uniform bricks'
        assert!(rows[0][6] > 1.4 && rows[0][5] > 0.0, "{n} ranks: {rows:?}");
        for r in nlocal(&log) {
            assert!(r[1] <= 1.05 * avg + 1.0, "{n} ranks: {r:?}");
        }
        let d = common::scale_deviation(&serial, &dump);
        assert!(d < 1e-10, "{n} ranks: differs from serial by {d:e}");
    }
}

#[test]
fn time_weights_after_a_run_keep_the_dumps() {
    let lines = "run 50\nbalance 1.0 shift x 10 1.1 weight time 0.8";
    let (dump, log) = run_heap(lines, 2, "processors 2 1 1", "time-2");
    assert!(log.contains("  time weight factor: 0.8\n"), "{log}");
    let loads = numbers_after(&log, "initial/final maximal load/proc =");
    assert_eq!(loads.len(), 1, "{log}");
    assert_eq!(nlocal(&log).len(), 2, "{log}");
    // the same two runs on the uniform bricks (the dumps start with the second run)
    let (uniform, _) = run_heap("run 50", 2, "processors 2 1 1", "time-uniform");
    let d = common::scale_deviation(&uniform, &dump);
    assert!(d < 1e-10, "differs from the uniform bricks by {d:e}");
    // explicit cuts: the heap's third to the first rank, as given
    let (plain, _) = run_heap("", 0, "", "cuts-serial");
    let (dump, log) = run_heap("balance 0.5 x 0.3", 2, "processors 2 1 1", "cuts-2");
    assert_eq!(numbers_after(&log, "x cuts:"), vec![vec![0.0, 0.3, 1.0]]);
    let d = common::scale_deviation(&plain, &dump);
    assert!(d < 1e-10, "differs from serial by {d:e}");
}

#[test]
fn a_second_run_in_a_box_three_diameters_deep_keeps_the_contacts_across_its_faces() {
    // the periodic y direction holds fewer than three list cells: the list pairs across
    // its faces with a mirror each (the exact path's list, which the fast path takes
    // here); the second run's setup re-sorts the particles and rebuilds the list, and the
    // pairs whose first particle changed take their history from the mirrors. The exact
    // path equals LIGGGHTS 3.8.0 (its dump of this deck is the exact path's to the bit)
    let runs = "run 50";
    let (exact, _) = run_heap_on(runs, 0, "", "second-exact", false);
    let (serial, _) = run_heap(runs, 0, "", "second-serial");
    let snaps = regolith::io::dump_compare::parse(&exact).unwrap();
    assert_eq!(snaps.len(), 7, "steps 50..200 every 25");
    assert_eq!(snaps[0].step, 50);
    let d = common::scale_deviation(&exact, &serial);
    assert!(d < 1e-10, "fast path: differs from the exact path by {d:e}");
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 3 1 1")] {
        let (dump, _) = run_heap(runs, n, grid, &format!("second-{n}"));
        for (what, other) in [("serial fast path", &serial), ("exact path", &exact)] {
            let d = common::scale_deviation(other, &dump);
            assert!(d < 1e-10, "{n} ranks: differ from the {what} by {d:e}");
        }
    }
}

/// The heap with thermo and balancing lines of its own.
fn run_custom(deck: &str, lines: &str, n: usize, grid: &str, tag: &str) -> (String, String) {
    let dir = common::scratch_dir(&format!("balance-{tag}"));
    let path = dir.join("in.deck");
    std::fs::write(&path, deck.replace("${balance}", lines)).unwrap();
    let (dump, log) = (dir.join("out.dump"), dir.join("log.txt"));
    let opts = |size: usize, rank: usize| {
        let mut o = options(&path, &dump, grid, size.max(1));
        o.ranks.rank = rank;
        o.log = Some(log.to_string_lossy().into_owned());
        o
    };
    let status = common::run_on_ranks(n, opts);
    let log_text = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{tag} on {n} ranks: {status:?}\n{log_text}"
    );
    let text = std::fs::read_to_string(&dump).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    (text, log_text)
}

/// The thermo rows (lines of numbers only) of a log.
fn thermo_rows(log: &str) -> Vec<Vec<f64>> {
    log.lines()
        .filter_map(|l| {
            let v: Option<Vec<f64>> = l.split_whitespace().map(|w| w.parse().ok()).collect();
            v.filter(|v| v.len() == 7)
        })
        .collect()
}

/// What `regolith check` reports about `text` on `size` ranks (one line each).
fn check(text: &str, size: usize) -> Vec<String> {
    let opts = DeckOptions {
        fast: true,
        ranks: Ranks {
            size,
            rank: 0,
            per_node: size,
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
fn bad_arguments_are_refused_with_their_line_in_check_and_run() {
    let deck = |line: &str| {
        HEAP.replace("${balance}", line)
            .replace("${grid}", "")
            .replace("${out}", "out.dump")
    };
    // the balancing line is line 31
    for (line, want) in [
        ("balance 1.0 shift q 10 1.1", "in.deck:31: Balance shift string is invalid"),
        ("balance 1.0 shift xx 10 1.1", "in.deck:31: Balance shift string is invalid"),
        ("balance 1.0 shift x 0 1.1", "in.deck:31: Illegal balance command"),
        ("balance 1.0 shift x 10 0.9", "in.deck:31: Illegal balance command"),
        ("balance 1.0 shift x 10", "in.deck:31: Illegal balance command"),
        ("balance 1.0", "in.deck:31: Illegal balance command"),
        ("balance 1.0 x 1.5", "in.deck:31: Illegal balance command"),
        ("balance 1.0 shift x 10 1.1 weight time -1", "in.deck:31: Illegal balance command"),
        ("balance 1.0 shift x 10 1.1 bogus", "in.deck:31: Illegal balance command: unknown keyword 'bogus'"),
        ("fix lb all balance -5 1.1 shift x 10 1.1", "in.deck:31: Illegal fix balance command"),
        ("fix lb all balance 10 1.1 shift w 10 1.1", "in.deck:31: Balance shift string is invalid"),
        (
            "balance 1.0 rcb",
            "in.deck:31: balance rcb (recursive bisection needs a tiled decomposition; supported: shift",
        ),
        (
            "fix lb all balance 10 1.1 rcb",
            "in.deck:31: fix balance rcb (recursive bisection needs a tiled decomposition; supported: shift",
        ),
        (
            "balance 1.0 shift x 10 1.1 weight neigh 0.8",
            "in.deck:31: balance weight neigh (supported: shift",
        ),
    ] {
        let text = deck(line);
        for size in [1, 2] {
            let got = check(&text, size);
            assert!(
                got.first().is_some_and(|g| g.starts_with(want)),
                "`{line}` on {size} ranks: {got:?}"
            );
        }
        // the run stops at the same line with the same words
        let dir = common::scratch_dir("balance-bad");
        let out = common::run_deck(&dir, "in.deck", &text, &["-sf", "fast"]);
        let stderr = common::text(&out.stderr) + &common::text(&out.stdout);
        let words = want.trim_start_matches("in.deck:31: ");
        assert!(!out.status.success(), "`{line}` ran");
        assert!(stderr.contains(words) && stderr.contains(":31"), "`{line}`: {stderr}");
        let _ = std::fs::remove_dir_all(&dir);
    }
    // the good lines pass the check on one and two ranks
    for line in [
        "balance 1.0 shift xy 10 1.1",
        "balance 1.0 x uniform",
        "fix lb all balance 0 1.1 shift x 10 1.1 weight time 1.0",
    ] {
        for size in [1, 2] {
            assert_eq!(check(&deck(line), size), Vec::<String>::new(), "`{line}`");
        }
    }
}
