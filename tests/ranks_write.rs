//! `write_data` and `write_dump` on several ranks, in-process (N ranks as N threads, each
//! running the whole deck as `mpirun -np N regolith -sf fast -in deck` would): between runs
//! and after the last one, rank 0 alone writes the files one process writes.

#[macro_use]
mod common;

use regolith::cli::DeckOptions;
use regolith::error::ExitStatus;
use regolith::util::comm::Ranks;

/// 211 spheres over a floor, walls all round; `${diameter}` is their size (0.002:
/// apart from each other and falling alike, 0.0025: a settling bed with contact history).
/// Data and dump files before the first run, between the runs and after the last, into
/// folder `${dir}`.
const BED: &str = concat!(
    "\
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
${grid}
region reg block 0 0.01488 0 0.01488 0 0.02 units box
create_box 1 reg
neighbor 0.0005 bin
neigh_modify delay 0 every 1 check no
",
    soft_material_on_a_floor!(),
    "lattice sc 0.00248
region pile block 0 0.01488 0 0.01488 0.0013 0.019 units box
create_atoms 1 region pile
set group all diameter ${diameter} density 2500
displace_atoms all random 0.0001 0.0001 0.0001 15485863
velocity all set 0.01 0.0 -0.05
fix gr all gravity 9.81 vector 0 0 -1
fix integr all nve/sphere
compute k all ke/atom
timestep 2e-6
thermo_style custom step atoms ke
thermo 50
write_data ${dir}/start.data
run 100
write_data ${dir}/mid.data
write_dump all custom ${dir}/mid.dump id type x y z vx vy vz fx fy fz omegax omegay omegaz radius c_k modify sort id format \"%d %d %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\"
run 50
write_dump all custom ${dir}/end.dump id x y z c_k modify sort id
write_data ${dir}/end.data
"
);

/// The files the deck writes.
const FILES: [&str; 5] = ["start.data", "mid.data", "mid.dump", "end.dump", "end.data"];

fn scratch(tag: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-ranks-write-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Run the bed of spheres of `diameter` on `n` ranks (0: the serial fast path) with
/// `processors` line `grid`, rank K's `${dir}` being `dir/rK` (made here, empty): the files
/// of each rank's folder by name, with their bytes.
fn files_of(
    dir: &std::path::Path,
    diameter: &str,
    n: usize,
    grid: &str,
) -> Vec<std::collections::BTreeMap<String, Vec<u8>>> {
    std::fs::create_dir_all(dir).unwrap();
    let deck = dir.join("in.deck");
    std::fs::write(&deck, BED).unwrap();
    let folder = |rank: usize| dir.join(format!("r{rank}"));
    for rank in 0..n.max(1) {
        std::fs::create_dir_all(folder(rank)).unwrap();
    }
    let opts = |rank: usize| DeckOptions {
        input: Some(deck.to_string_lossy().into_owned()),
        vars: vec![
            (
                "dir".into(),
                vec![folder(rank).to_string_lossy().into_owned()],
            ),
            ("grid".into(), vec![grid.into()]),
            ("diameter".into(), vec![diameter.into()]),
        ],
        log: Some("none".into()),
        screen: Some("none".into()),
        fast: true,
        threads: Some(1),
        ranks: Ranks {
            size: n.max(1),
            rank,
            per_node: n.max(1),
        },
        ..DeckOptions::default()
    };
    let status = common::run_on_ranks(n, |_, rank| opts(rank));
    assert!(
        status.iter().all(|s| *s == ExitStatus::Success),
        "{} on {n} ranks: {status:?}",
        dir.display()
    );
    (0..n.max(1))
        .map(|rank| {
            std::fs::read_dir(folder(rank))
                .unwrap()
                .flatten()
                .map(|e| {
                    let name = e.file_name().to_string_lossy().into_owned();
                    (name, std::fs::read(e.path()).unwrap())
                })
                .collect()
        })
        .collect()
}

/// The numbers of a data file's `Atoms` section by atom ID.
fn atoms(data: &[u8]) -> std::collections::BTreeMap<i64, Vec<f64>> {
    let text = String::from_utf8_lossy(data);
    let start = text.find("Atoms").expect("an Atoms section");
    let body = &text[start..];
    let body = body.lines().skip(2).take_while(|l| !l.trim().is_empty());
    body.map(|l| {
        let v: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
        (v[0] as i64, v)
    })
    .collect()
}

/// On 2 and 3 ranks: rank 0's folder holds exactly the files one process writes, the other
/// ranks' folders nothing; `same` (the spheres never touch: every step is one process's
/// bits) asks for the same bytes, otherwise each file's numbers within 1e-10 of each
/// column's scale and the same bytes on every grid.
fn compare(tag: &str, diameter: &str, same: bool) {
    let dir = scratch(tag);
    let serial = files_of(&dir.join("serial"), diameter, 0, "").remove(0);
    let names: Vec<&String> = serial.keys().collect();
    assert_eq!(names, {
        let mut want = FILES.to_vec();
        want.sort_unstable();
        want
    });
    // the data files hold every sphere, moved by the runs
    let (start, end) = (atoms(&serial["start.data"]), atoms(&serial["end.data"]));
    // (the lattice's sites on the upper faces are outside a box with fixed faces)
    // (the settling bed pushes some out through its open sides: lost)
    assert_eq!(start.len(), 211);
    assert!(
        end.len() == 211 || (!same && end.len() > 150),
        "{}",
        end.len()
    );
    // id type diameter density x y z ...: apart, every sphere lower at the end; the
    // settling bed (overlapping at the start) spreads: every sphere elsewhere
    let fell = end.iter().filter(|(id, v)| v[6] < start[*id][6]).count();
    let moved = end
        .iter()
        .filter(|(id, v)| v[4..7] != start[*id][4..7])
        .count();
    assert!(
        fell == 211 || (!same && moved == end.len()),
        "{fell}, {moved}"
    );
    let mid = String::from_utf8_lossy(&serial["mid.dump"]).into_owned();
    assert!(
        mid.starts_with("ITEM: TIMESTEP\n100\nITEM: NUMBER OF ATOMS\n"),
        "{mid}"
    );
    let mut on_ranks = Vec::new();
    for (n, grid) in [(2, "processors 2 1 1"), (3, "processors 1 3 1")] {
        let folders = files_of(&dir.join(n.to_string()), diameter, n, grid);
        for (rank, files) in folders.iter().enumerate().skip(1) {
            assert!(
                files.is_empty(),
                "{grid}: rank {rank} wrote {:?}",
                files.keys()
            );
        }
        let files = &folders[0];
        assert_eq!(files.keys().collect::<Vec<_>>(), names, "{grid}");
        for name in FILES {
            if same || name == "start.data" {
                assert!(files[name] == serial[name], "{grid}: {name} differs");
                continue;
            }
            let (a, b) = (
                String::from_utf8_lossy(&serial[name]),
                String::from_utf8_lossy(&files[name]),
            );
            let d = if name.ends_with(".data") {
                data_deviation(&serial[name], &files[name])
            } else {
                common::scale_deviation(&a, &b)
            };
            assert!(d < 1e-10, "{grid}: {name} differs by {d:e}");
        }
        on_ranks.push(files.clone());
    }
    assert!(
        on_ranks[0] == on_ranks[1],
        "2 and 3 ranks wrote other bytes"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Largest difference of data file `b`'s atoms from `a`'s in units of each column's scale.
fn data_deviation(a: &[u8], b: &[u8]) -> f64 {
    let (a, b) = (atoms(a), atoms(b));
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>());
    let columns = a.values().next().map_or(0, Vec::len);
    let mut worst: f64 = 0.0;
    for c in 0..columns {
        let scale = a
            .values()
            .map(|v| v[c].abs())
            .fold(0.0, f64::max)
            .max(1e-300);
        for (id, va) in &a {
            worst = worst.max((va[c] - b[id][c]).abs() / scale);
        }
    }
    worst
}

#[test]
fn falling_apart_the_files_are_one_process_bytes_from_rank_0_alone() {
    compare("apart", "0.002", true);
}

#[test]
fn a_settling_bed_writes_one_process_files_from_rank_0_alone() {
    compare("bed", "0.0025", false);
}

#[test]
fn write_dump_of_a_style_that_does_not_run_on_ranks_is_refused_by_name() {
    let opts = DeckOptions {
        fast: true,
        ranks: Ranks {
            size: 2,
            rank: 0,
            per_node: 2,
        },
        ..DeckOptions::default()
    };
    let deck = BED
        .replace("${grid}", "processors 2 1 1")
        .replace("${diameter}", "0.0025")
        .replace("${dir}", ".");
    for (line, refused) in [
        ("write_dump all xyz out.xyz", "write_dump xyz"),
        ("write_dump all local out.local c_p[1]", "write_dump local"),
        (
            "write_dump all custom out.dump id f_floor[1]",
            "write_dump custom column f_floor[1]",
        ),
    ] {
        let text = deck.replace("run 50\n", &format!("{line}\nrun 50\n"));
        let source = regolith::script::interp::Source::from_text("in.deck", &text, false);
        let got: Vec<String> = regolith::session::check_deck(source, &opts)
            .iter()
            .map(|d| d.one_line())
            .collect();
        let at = text.lines().position(|l| l == line).unwrap() + 1;
        let want = format!("in.deck:{at}: {refused} on more than one MPI rank: not supported yet");
        assert!(
            got.first().is_some_and(|g| g.starts_with(&want)),
            "{line}: {got:?}"
        );
    }
}
