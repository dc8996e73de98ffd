//! The ghosts and neighbour counts of the domain decomposition against LIGGGHTS 3.8.0's
//! under `mpirun`.

use regolith::engine::decomp::{borders, Decomposition, Halo};
use regolith::engine::particles::Particles;
use regolith::util::comm::Comm;
use regolith::util::comm_threads::ThreadRanks;

mod decomp_common;
use decomp_common::{particles, Case, HI, LO, SKIN};

/// The particles of `liggghts_case` as a LIGGGHTS data file (atom style granular), for
/// the counts in [`ghosts_and_neighbours_as_liggghts`].
fn liggghts_data(case: &Case) -> String {
    let (start, _, radius) = particles(case);
    let mut s = format!("LIGGGHTS data file\n\n{} atoms\n1 atom types\n\n", case.n);
    for (d, axis) in ["x", "y", "z"].iter().enumerate() {
        s.push_str(&format!("{:?} {:?} {axis}lo {axis}hi\n", LO[d], HI[d]));
    }
    s.push_str("\nAtoms\n\n");
    for (i, x) in start.iter().enumerate() {
        s.push_str(&format!(
            "{} 1 {:?} 2500 {:?} {:?} {:?}\n",
            i + 1,
            2.0 * radius[i],
            x[0],
            x[1],
            x[2]
        ));
    }
    s
}

fn liggghts_case() -> Case {
    Case {
        procs: [1, 1, 1],
        periodic: [true; 3],
        cut: None,
        n: 400,
        seed: 11,
    }
}

#[test]
#[ignore = "writes the data file the LIGGGHTS counts were taken from"]
fn write_liggghts_data() {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("decomp.data");
    std::fs::write(&path, liggghts_data(&liggghts_case())).expect("write");
    println!("{}", path.display());
}

/// Per rank: owned particles, ghosts and LIGGGHTS's neighbour count (pairs i < j with i
/// owned and j owned or ghost, closer than or at ri + rj + skin).
fn liggghts_counts(procs: [usize; 3], periodic: [bool; 3], cutuser: f64) -> Vec<[usize; 3]> {
    let case = liggghts_case();
    let (start, _, radius) = particles(&case);
    let rmax = radius.iter().cloned().fold(0.0, f64::max);
    let halo = Halo::granular((2.0 * rmax + SKIN).max(cutuser), SKIN);
    ThreadRanks::run(procs.iter().product(), |c| {
        let dec = Decomposition::cartesian(procs, c.rank(), LO, HI, periodic);
        let mut p = Particles::default();
        for (i, x) in start.iter().enumerate() {
            if dec.owns(*x) {
                p.push(i as i64 + 1, 1, *x, radius[i], 2500.0);
            }
        }
        let nlocal = p.len();
        let plan = borders(c, &dec, &halo, &mut p, nlocal).expect("borders");
        let mut neighs = 0;
        for i in 0..nlocal {
            for j in i + 1..p.len() {
                let del = [0, 1, 2].map(|d| p.x[i][d] - p.x[j][d]);
                let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
                let reach = p.radius[i] + p.radius[j] + SKIN;
                neighs += usize::from(rsq <= reach * reach);
            }
        }
        [nlocal, plan.nghost(), neighs]
    })
}

/// LIGGGHTS 3.8.0 on `mpirun -np N` with the particles of [`liggghts_data`]: `boundary`,
/// `communicate single vel yes cutoff C`, `processors`, `neighbor 0.01 bin`, pair gran
/// hertz with history, `newton off`, `run 0`; its Nlocal, Nghost and Neighs lines (ave,
/// max, min over ranks) and "Total # of neighbors".
#[test]
fn ghosts_and_neighbours_as_liggghts() {
    type Row = (
        [usize; 3],
        [bool; 2],
        f64,
        [f64; 3],
        [f64; 3],
        [f64; 3],
        usize,
    );
    let rows: [Row; 9] = [
        (
            [1, 1, 1],
            [true, true],
            0.0,
            [400.0, 400.0, 400.0],
            [444.0, 444.0, 444.0],
            [411.0, 411.0, 411.0],
            411,
        ),
        (
            [2, 1, 1],
            [true, true],
            0.0,
            [200.0, 212.0, 188.0],
            [281.0, 289.0, 273.0],
            [210.0, 237.0, 183.0],
            420,
        ),
        (
            [3, 1, 1],
            [true, false],
            0.0,
            [133.333, 143.0, 126.0],
            [116.667, 128.0, 102.0],
            [121.667, 144.0, 99.0],
            365,
        ),
        (
            [2, 2, 1],
            [true, true],
            0.0,
            [100.0, 112.0, 90.0],
            [180.75, 187.0, 174.0],
            [107.5, 136.0, 78.0],
            430,
        ),
        (
            [2, 2, 1],
            [false, false],
            0.0,
            [100.0, 112.0, 90.0],
            [42.75, 46.0, 37.0],
            [81.5, 93.0, 57.0],
            326,
        ),
        (
            [1, 1, 4],
            [true, true],
            0.0,
            [100.0, 116.0, 92.0],
            [280.25, 298.0, 257.0],
            [122.5, 165.0, 92.0],
            490,
        ),
        (
            [1, 1, 4],
            [true, true],
            0.2,
            [100.0, 116.0, 92.0],
            [450.25, 465.0, 442.0],
            [122.5, 165.0, 92.0],
            490,
        ),
        (
            [1, 1, 4],
            [false, false],
            0.2,
            [100.0, 116.0, 92.0],
            [160.5, 218.0, 103.0],
            [96.5, 121.0, 58.0],
            386,
        ),
        (
            [1, 1, 1],
            [true, true],
            0.2,
            [400.0, 400.0, 400.0],
            [653.0, 653.0, 653.0],
            [411.0, 411.0, 411.0],
            411,
        ),
    ];
    for (procs, [pxy, pz], cut, nlocal, nghost, neighs, total) in rows {
        let counts = liggghts_counts(procs, [pxy, pxy, pz], cut);
        let n = counts.len() as f64;
        for (k, want) in [nlocal, nghost, neighs].iter().enumerate() {
            let got: Vec<usize> = counts.iter().map(|c| c[k]).collect();
            let ave = got.iter().sum::<usize>() as f64 / n;
            let (max, min) = (got.iter().max(), got.iter().min());
            let what = ["Nlocal", "Nghost", "Neighs"][k];
            assert!((ave - want[0]).abs() < 1e-3, "{procs:?} {what} ave {ave}");
            assert_eq!(max, Some(&(want[1] as usize)), "{procs:?} {what} max");
            assert_eq!(min, Some(&(want[2] as usize)), "{procs:?} {what} min");
        }
        assert_eq!(
            counts.iter().map(|c| c[2]).sum::<usize>(),
            total,
            "{procs:?}"
        );
    }
}
