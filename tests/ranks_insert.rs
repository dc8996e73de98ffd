//! Insertion on several ranks, in-process (N ranks are N threads joined by channels, each
//! running the whole deck as `mpirun -np N regolith -sf fast -in deck` would): pours with
//! `fix insert/pack`, `insert/rate/region` and `insert/stream` into a box with a floor, on
//! grids cut across and along the pour. Dumps are compared with the serial fast path's
//! (within 1e-10 of each column's scale, the same atoms at every snapshot), the atom count
//! of every thermo line with the serial one's, and repeated runs bit for bit.

#[macro_use]
mod common;

use regolith::cli::DeckOptions;
use regolith::error::ExitStatus;
use regolith::util::comm::Ranks;

/// A pour into a box with a floor: `${insert}` is the insertion (its distribution of
/// spheres of radius 0.8 mm is `pdd`), `${extra}` more set-up lines, `${grid}` the
/// `processors` line.
const POUR: &str = concat!(
    "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
${grid}
",
    pour_box_and_spheres!(),
    "${extra}
${insert}
fix integr all nve/sphere
thermo_style custom step atoms ke
thermo 25
dump d all custom 25 ${dir}/out.dump id x y z vx vy vz radius
dump_modify d sort id format \"%d %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 300
run 200
write_restart ${dir}/pour.restart
"
);

/// An insertion face for `insert/stream`: a square at z = 0.013 over most of the box, as
/// two triangles of an ASCII STL file.
const FACE: &str = "\
solid face
facet normal 0 0 1
outer loop
vertex 0.002 0.002 0.013
vertex 0.018 0.002 0.013
vertex 0.018 0.018 0.013
endloop
endfacet
facet normal 0 0 1
outer loop
vertex 0.002 0.002 0.013
vertex 0.018 0.018 0.013
vertex 0.002 0.018 0.013
endloop
endfacet
endsolid face
";

/// A tilted tray for a mesh wall: a plane rising from z = 0.004 at x = 0.0005 to z = 0.008
/// at x = 0.0195, across the box in y, as two triangles of an ASCII STL file.
const TRAY: &str = "\
solid tray
facet normal -0.2 0 1
outer loop
vertex 0.0005 0.0005 0.004
vertex 0.0195 0.0005 0.008
vertex 0.0195 0.0195 0.008
endloop
endfacet
facet normal -0.2 0 1
outer loop
vertex 0.0005 0.0005 0.004
vertex 0.0195 0.0195 0.008
vertex 0.0005 0.0195 0.004
endloop
endfacet
endsolid tray
";

/// The pour deck with insertion `insert` and set-up lines `extra`.
fn pour(insert: &str, extra: &str) -> String {
    POUR.replace("${insert}", insert).replace("${extra}", extra)
}

/// A fresh folder for one run.
fn scratch(tag: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "regolith-ranks-insert-{}-{tag}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The dump and the log of `deck` run on `n` ranks (0: the serial fast path) with
/// `processors` line `grid` (`${dir}` in the deck names the run's folder, which holds the
/// insertion face `face.stl` and the tray `tray.stl`).
fn outputs_of(deck: &str, n: usize, grid: &str, tag: &str) -> Outputs {
    let dir = scratch(tag);
    std::fs::write(dir.join("face.stl"), FACE).unwrap();
    std::fs::write(dir.join("tray.stl"), TRAY).unwrap();
    let path = dir.join("in.deck");
    let text = deck
        .replace("${dir}", &dir.to_string_lossy())
        .replace("${grid}", grid);
    std::fs::write(&path, text).unwrap();
    let log = dir.join("log.txt");
    let opts = |size: usize, rank: usize| DeckOptions {
        input: Some(path.to_string_lossy().into_owned()),
        log: Some(log.to_string_lossy().into_owned()),
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
    let log_text = std::fs::read_to_string(&log).unwrap_or_default();
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{tag} on {n} ranks: {status:?}\n{log_text}"
    );
    let dump = std::fs::read_to_string(dir.join("out.dump")).unwrap();
    let restart = dir.join("pour.restart");
    let r = regolith::io::restart::read(&restart.to_string_lossy()).unwrap();
    let ids = r.atoms.iter().map(|a| a.id).collect();
    let _ = std::fs::remove_dir_all(&dir);
    (dump, log_text, ids)
}

/// A run's dump, log and the atom IDs of its final restart file in the file's order.
type Outputs = (String, String, Vec<i64>);

/// The (step, atoms) of every thermo line of a log.
fn atom_counts(log: &str) -> Vec<(i64, i64)> {
    let mut rows = Vec::new();
    let mut inside = false;
    for line in log.lines() {
        if line.trim_start().starts_with("Step") {
            inside = true;
        } else if line.starts_with("Loop time") {
            inside = false;
        } else if inside && !line.starts_with("WARNING") && !line.starts_with("INFO") {
            let w: Vec<&str> = line.split_whitespace().collect();
            if let (Some(Ok(step)), Some(Ok(atoms))) =
                (w.first().map(|s| s.parse()), w.get(1).map(|s| s.parse()))
            {
                rows.push((step, atoms));
            }
        }
    }
    rows
}

/// `deck` on the serial fast path and on the grids `grids` ((ranks, processors line)):
/// every dump within 1e-10 of each column's scale of the serial one with the same atoms
/// at each snapshot, the same atom count at every thermo line, the final restart file's
/// atoms in the serial one's order (the exact path's, new particles in the order they were
/// inserted), the first grid the same bits when run again. The serial dump and thermo
/// counts.
fn on_grids(deck: &str, grids: &[(usize, &str)], tag: &str) -> (String, Vec<(i64, i64)>) {
    let (serial, log, order) = outputs_of(deck, 0, "", &format!("{tag}-serial"));
    let counts = atom_counts(&log);
    assert_eq!(counts.len(), 22, "{tag}: thermo lines of two runs\n{log}");
    assert_eq!(order.len() as i64, counts.last().unwrap().1);
    for (k, &(n, grid)) in grids.iter().enumerate() {
        let (dump, log, ids) = outputs_of(deck, n, grid, &format!("{tag}-{k}"));
        assert_eq!(atom_counts(&log), counts, "{tag}: {grid} atom counts");
        let d = common::scale_deviation(&serial, &dump);
        assert!(d < 1e-10, "{tag}: {grid} differs from serial by {d:e}");
        assert!(
            ids == order,
            "{tag}: {grid} stores the atoms in another order"
        );
        if k == 0 {
            let (again, ..) = outputs_of(deck, n, grid, &format!("{tag}-again"));
            assert!(again == dump, "{tag}: {grid} run twice gave other dumps");
        }
    }
    (serial, counts)
}

/// Grids across the pour (x), along it (z) and over three ranks.
const GRIDS: [(usize, &str); 3] = [
    (2, "processors 2 1 1"),
    (2, "processors 1 1 2"),
    (3, "processors 3 1 1"),
];

/// The insertion events of a run: the steps at which the atom count grew, from the
/// thermo counts (every 25 steps).
fn growth(counts: &[(i64, i64)]) -> usize {
    counts.windows(2).filter(|w| w[1].1 > w[0].1).count()
}

#[test]
fn insert_pack_on_ranks_matches_the_serial_fast_path() {
    // the region is refilled to 40 particles every 50 steps as the particles fall out of it
    // (the spatial sort every 100 steps reorders the exact order's record, new particles
    // among the old)
    let deck = pour(
        "region ins block 0.001 0.019 0.001 0.019 0.006 0.016 units box
fix ins all insert/pack seed 32452867 distributiontemplate pdd insert_every 50 \
overlapcheck yes vel constant 0.1 -0.05 -3 region ins particles_in_region 40",
        "atom_modify sort 100 0.002",
    );
    let (serial, counts) = on_grids(&deck, &GRIDS, "pack");
    assert!(growth(&counts) >= 5, "insertion events: {counts:?}");
    let last = regolith::io::dump_compare::parse(&serial).unwrap();
    let last = last.last().unwrap();
    assert_eq!(last.step, 500);
    assert!(
        last.rows.len() >= 120,
        "{} atoms: {counts:?}",
        last.rows.len()
    );
    // some have reached the floor and rest on it (z within a radius of it)
    let col = |name: &str| last.columns.iter().position(|c| c == name).unwrap();
    let (z, radius) = (col("z"), col("radius"));
    let on_floor = last
        .rows
        .values()
        .filter(|r| r[z] < r[radius] * 1.01)
        .count();
    assert!(on_floor > 0, "no particle on the floor");
}

#[test]
fn insert_rate_region_on_ranks_matches_the_serial_fast_path() {
    // 240 particles at 60000 per second, every 40 steps (24 a time): 10 insertions, onto
    // a tilted mesh tray (the particles on it carry their mesh contacts through every
    // insertion's gathering and to other ranks as they slide across the x cuts)
    let deck = pour(
        "region ins block 0.001 0.019 0.001 0.019 0.012 0.022 units box
fix ins all insert/rate/region seed 32452867 distributiontemplate pdd nparticles 240 \
particlerate 60000 insert_every 40 overlapcheck yes vel constant 0 0 -3 region ins",
        "fix tray all mesh/surface file ${dir}/tray.stl type 1
fix trayw all wall/gran model hertz tangential history mesh n_meshes 1 meshes tray",
    );
    let (serial, counts) = on_grids(&deck, &GRIDS, "rate");
    assert!(growth(&counts) >= 8, "insertion events: {counts:?}");
    // all 240 inserted (a few bounce out through the side faces later, on every grid alike)
    assert_eq!(counts.iter().map(|c| c.1).max(), Some(240), "{counts:?}");
    let snaps = regolith::io::dump_compare::parse(&serial).unwrap();
    let last = snaps.last().unwrap();
    let col = |name: &str| last.columns.iter().position(|c| c == name).unwrap();
    let (x, z, radius) = (col("x"), col("z"), col("radius"));
    // the tray's height at x
    let tray = |x: f64| 0.004 + (x - 0.0005) / 0.019 * 0.004;
    let on_tray = last
        .rows
        .values()
        .filter(|r| r[z] - tray(r[x]) < 1.2 * r[radius])
        .count();
    assert!(on_tray >= 10, "{on_tray} particles on the tray");
    assert!(
        last.rows.values().all(|r| r[z] > tray(r[x])),
        "through the tray"
    );
}

#[test]
fn insert_stream_on_ranks_matches_the_serial_fast_path() {
    // particles are inserted in the face at z = 0.013 extruded upstream (to z = 0.017) and
    // carried 80 steps at 5 m/s to the face before they fall freely: the face spans the
    // cuts of the x grids, so carried particles belong to each rank, and they cross the
    // cut of the z grid (z = 0.015) while carried
    let deck = pour(
        "fix ins all insert/stream seed 32452867 distributiontemplate pdd nparticles 200 \
particlerate 40000 insert_every 80 overlapcheck yes vel constant 0 0 -5 insertion_face inface",
        "fix inface all mesh/surface file ${dir}/face.stl type 1",
    );
    let (serial, counts) = on_grids(&deck, &GRIDS, "stream");
    assert!(growth(&counts) >= 6, "insertion events: {counts:?}");
    assert_eq!(counts.last().unwrap().1, 200, "{counts:?}");
    // a particle still carried moves at the stream's velocity exactly
    let snaps = regolith::io::dump_compare::parse(&serial).unwrap();
    let col = |name: &str| snaps[0].columns.iter().position(|c| c == name).unwrap();
    let v = [col("vx"), col("vy"), col("vz")];
    let carried = snaps
        .iter()
        .flat_map(|s| s.rows.values())
        .filter(|r| r[v[0]] == 0.0 && r[v[1]] == 0.0 && r[v[2]] == -5.0)
        .count();
    assert!(carried > 0, "no particle carried by the stream");
}

#[test]
fn insert_stream_all_in_on_ranks_matches_the_serial_fast_path() {
    // the same stream through a planar face with `all_in yes` (every particle wholly
    // inside the face's extrusion, tested against the face's edges)
    let deck = pour(
        "fix ins all insert/stream seed 32452867 distributiontemplate pdd nparticles 200 \
particlerate 40000 insert_every 80 overlapcheck yes all_in yes vel constant 0 0 -5 \
insertion_face inface",
        "fix inface all mesh/surface/planar file ${dir}/face.stl type 1",
    );
    let (serial, counts) = on_grids(&deck, &GRIDS[..2], "stream-all-in");
    assert!(growth(&counts) >= 6, "insertion events: {counts:?}");
    // every particle inserted wholly inside the face's square (x and y from 0.002 to 0.018)
    let snaps = regolith::io::dump_compare::parse(&serial).unwrap();
    let col = |name: &str| snaps[0].columns.iter().position(|c| c == name).unwrap();
    let (x, y, vz, radius) = (col("x"), col("y"), col("vz"), col("radius"));
    let carried: Vec<&Vec<f64>> = snaps
        .iter()
        .flat_map(|s| s.rows.values())
        .filter(|r| r[vz] == -5.0)
        .collect();
    assert!(!carried.is_empty(), "no particle carried by the stream");
    for r in carried {
        for c in [x, y] {
            assert!(
                r[c] - r[radius] >= 0.002 && r[c] + r[radius] <= 0.018,
                "{r:?}"
            );
        }
    }
}
