//! The end-of-run neighbour statistics agree with Debian's LIGGGHTS 3.8.0: a rebuild forced
//! by inserted particles is not dangerous, rebuilds the distance check triggers at the first
//! allowed step are (the counts LIGGGHTS printed for this deck: builds 1, 1, 5; dangerous
//! 0, 0, 5).

use std::process::Command;

const DECK: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block -0.05 0.05 -0.05 0.05 0. 0.15 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.7
fix m4 all property/global coefficientFriction peratomtypepair 1 0.05
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.000025
fix gravi all gravity 9.81 vector 0.0 0.0 -1.0
fix zwalls1 all wall/gran model hertz tangential history primitive type 1 zplane 0.0
region bc cylinder z 0. 0. 0.045 0.00 0.15 units box
fix pts1 all particletemplate/sphere 15485863 atom_type 1 density constant 8000 radius constant 0.004
fix pdd1 all particledistribution/discrete 15485867 1 pts1 1.0
fix ins all insert/pack seed 32452843 distributiontemplate pdd1 vel constant 0. 0. -0.3 insert_every once overlapcheck yes all_in yes particles_in_region 50 region bc
fix integr all nve/sphere
thermo 100
run 1
unfix ins
run 200
velocity all set 0 0 -60
run 5
";

fn statistics(flags: &[&str], tag: &str) -> Vec<(u64, u64)> {
    let work = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-stats-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).unwrap();
    std::fs::write(work.join("in.stats"), DECK).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(flags)
        .args(["-in", "in.stats", "-log", "none"])
        .current_dir(&work)
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&work);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    let value = |line: &str, key: &str| line.strip_prefix(key).map(|v| v.trim().parse().unwrap());
    let builds: Vec<u64> = text
        .lines()
        .filter_map(|l| value(l, "Neighbor list builds = "))
        .collect();
    let dangerous: Vec<u64> = text
        .lines()
        .filter_map(|l| value(l, "Dangerous builds = "))
        .collect();
    builds.into_iter().zip(dangerous).collect()
}

#[test]
fn dangerous_builds_are_counted_as_liggghts_counts_them() {
    let want = vec![(1, 0), (1, 0), (5, 5)];
    assert_eq!(statistics(&[], "exact"), want);
    assert_eq!(statistics(&["-sf", "fast"], "fast"), want);
}

/// A deck with `modify_timing on`, then `verbose`, then `off`: a primitive and a mesh wall,
/// an insertion, computes that keep a store, a fix unfixed and one added between runs.
const TIMING_DECK: &str = "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block 0 0.1 0 0.1 0 0.1 units box
create_box 1 reg
neighbor 0.002 bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 5.e6
fix m2 all property/global poissonsRatio peratomtype 0.45
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.3
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep 0.00001
fix gr all gravity 9.81 vector 0.0 0.0 -1.0
fix floor all wall/gran model hertz tangential history primitive type 1 zplane 0.0
fix plate all mesh/surface file plate.stl type 1
fix pw all wall/gran model hertz tangential history mesh n_meshes 1 meshes plate
fix pts all particletemplate/sphere 15485863 atom_type 1 density constant 2500 radius constant 0.003
fix pdd all particledistribution/discrete 32452843 1 pts 1.0
region ins block 0.01 0.09 0.01 0.09 0.02 0.09 units box
fix ins all insert/pack seed 49979687 distributiontemplate pdd insert_every once overlapcheck yes all_in yes particles_in_region 100 region ins
fix integr all nve/sphere
compute msd all msd
modify_timing on
thermo 100
run 200
unfix floor
fix push all addforce 0 0 1e-4
compute disp all displace/atom
run 100
modify_timing verbose
run 10
modify_timing off
run 10
";

const PLATE: &str = "solid plate
facet normal 0 0 1
outer loop
vertex 0.0 0.0 0.01
vertex 0.1 0.0 0.01
vertex 0.1 0.1 0.01
endloop
endfacet
facet normal 0 0 1
outer loop
vertex 0.0 0.0 0.01
vertex 0.1 0.1 0.01
vertex 0.0 0.1 0.01
endloop
endfacet
endsolid plate
";

/// The fixes Debian's LIGGGHTS 3.8.0 lists after the first run of `TIMING_DECK`, in its
/// order (its own `history_floor`, the mesh wall's three, the computes' stores and the pair
/// style's `contacthistory` among them).
const FIRST_RUN: [&str; 18] = [
    "m1 property/global",
    "m2 property/global",
    "m3 property/global",
    "m4 property/global",
    "gr gravity",
    "floor wall/gran",
    "history_floor property/atom",
    "plate mesh/surface",
    "pw wall/gran",
    "wall_neighlist_plate neighlist/mesh",
    "n_neighs_mesh_plate property/atom",
    "tracker_plate contacthistory/mesh",
    "pts particletemplate/sphere",
    "pdd particledistribution/discrete",
    "ins insert/pack",
    "integr nve/sphere",
    "msd_COMPUTE_STORE STORE",
    "contacthistory contacthistory",
];

/// One run's timing report: the loop time, the time lines by name (time, percent) and the
/// fix lines (`ID style`, time, percent), read from `text`'s `run`-th run.
struct Report {
    total: f64,
    lines: Vec<(String, f64, f64)>,
    fixes: Vec<(String, f64, f64)>,
    per_process: Vec<String>,
}

fn reports(text: &str) -> Vec<Report> {
    let mut out: Vec<Report> = Vec::new();
    for l in text.lines() {
        if let Some(rest) = l.strip_prefix("Loop time of ") {
            let total = rest.split_whitespace().next().unwrap().parse().unwrap();
            out.push(Report {
                total,
                lines: vec![],
                fixes: vec![],
                per_process: vec![],
            });
            continue;
        }
        let Some(r) = out.last_mut() else { continue };
        if l.contains("[0] Fix ") {
            r.per_process.push(l.to_string());
            continue;
        }
        let Some((name, values)) = l.split_once(" time (%) = ") else {
            continue;
        };
        let (t, p) = values.trim_end_matches(')').split_once(" (").unwrap();
        let entry = (name.to_string(), t.parse().unwrap(), p.parse().unwrap());
        match name.strip_prefix("Fix ") {
            Some(fix) => r.fixes.push((fix.to_string(), entry.1, entry.2)),
            None => r.lines.push(entry),
        }
    }
    out
}

fn timing_run(flags: &[&str], tag: &str) -> (String, String) {
    let work = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-timing-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    std::fs::create_dir_all(&work).unwrap();
    std::fs::write(work.join("in.timing"), TIMING_DECK).unwrap();
    std::fs::write(work.join("plate.stl"), PLATE).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(flags)
        .args(["-in", "in.timing", "-log", "log.timing"])
        .current_dir(&work)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let log = std::fs::read_to_string(work.join("log.timing")).unwrap();
    let _ = std::fs::remove_dir_all(&work);
    (String::from_utf8_lossy(&out.stdout).into_owned(), log)
}

/// `%g`'s six significant digits: values printed from the same sum agree to this.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-5 * a.abs().max(b.abs()) + 1e-12
}

#[test]
fn modify_timing_lists_liggghts_fixes_in_its_order_with_consistent_times() {
    for (flags, tag) in [(&[][..], "exact"), (&["-sf", "fast"][..], "fast")] {
        let (screen, log) = timing_run(flags, tag);
        let runs = reports(&screen);
        assert_eq!(runs.len(), 4);
        // the time lines in LIGGGHTS's order, Modfy only while timing is on
        let names = |r: &Report| r.lines.iter().map(|l| l.0.clone()).collect::<Vec<_>>();
        let timed = ["Pair ", "Neigh", "Comm ", "Outpt", "Modfy", "Other"];
        for r in &runs[..3] {
            assert_eq!(names(r), timed);
        }
        assert_eq!(
            names(&runs[3]),
            ["Pair ", "Neigh", "Comm ", "Outpt", "Other"]
        );
        assert!(runs[3].fixes.is_empty());
        // the fixes: LIGGGHTS's list; `floor` and its history gone, the new fix and store
        // after the contact history
        let ids = |r: &Report| r.fixes.iter().map(|f| f.0.clone()).collect::<Vec<_>>();
        assert_eq!(ids(&runs[0]), FIRST_RUN);
        let mut second: Vec<String> = FIRST_RUN
            .iter()
            .filter(|f| !f.contains("floor"))
            .map(|f| f.to_string())
            .collect();
        second.extend(["push addforce".into(), "disp_COMPUTE_STORE STORE".into()]);
        assert_eq!(ids(&runs[1]), second);
        assert_eq!(ids(&runs[2]), second);
        for r in &runs[..3] {
            // Modfy is the fixes' sum; the lines add up to the loop time; each percentage
            // is its time over the loop time
            let fix_sum: f64 = r.fixes.iter().map(|f| f.1).sum();
            let modify = r.lines[4].1;
            assert!(close(modify, fix_sum) || (modify - fix_sum).abs() < 1e-9 * 20.0);
            let all: f64 = r.lines.iter().map(|l| l.1).sum();
            assert!(
                (all - r.total).abs() <= 1e-5 * r.total,
                "{all} vs {}",
                r.total
            );
            for (_, t, p) in r.lines.iter().chain(&r.fixes) {
                assert!(close(*p, 100.0 * t / r.total), "{t} {p} {}", r.total);
            }
            // the integrator and gravity do work every step
            let time_of = |id: &str| r.fixes.iter().find(|f| f.0.starts_with(id)).unwrap().1;
            assert!(time_of("integr ") > 0.0 && time_of("gr ") > 0.0);
        }
        // verbose: one per-process line after each fix line, two spaces on the screen and
        // one in the log (as LIGGGHTS writes them), and the modify total per process
        assert_eq!(runs[2].per_process.len(), second.len());
        for (line, fix) in runs[2].per_process.iter().zip(&second) {
            assert!(
                line.starts_with(&format!("  [0] Fix {fix} time ")),
                "{line}"
            );
        }
        assert!(screen.contains("  Modify   time [0] (%) = "));
        let log_lines: Vec<&str> = log.lines().filter(|l| l.contains("[0] Fix ")).collect();
        assert_eq!(log_lines.len(), second.len());
        assert!(log_lines.iter().all(|l| l.starts_with(" [0] Fix ")));
    }
}
