//! The domain decomposition over MPI (build with `--features mpi`): under
//! `mpirun -np N`, particles migrate, ghosts are made, positions go forward and pair
//! forces come back on N ranks; rank 0 then does the same on N threads and checks that the
//! owned particles, ghost counts and force sums (canonical order) are the same, bit for bit.

use regolith::engine::decomp::{
    borders, canonical_sum, forward, migrate, reverse_contributions, Contribution, Decomposition,
    Halo,
};
use regolith::engine::particles::Particles;
use regolith::engine::procmap::{choose_grid, Processors};
use regolith::util::comm::Comm;
use regolith::util::comm_mpi::MpiComm;
use regolith::util::comm_threads::ThreadRanks;

const LO: [f64; 3] = [0.0, -0.2, 0.0];
const HI: [f64; 3] = [1.0, 0.6, 0.5];
const SKIN: f64 = 0.005;

/// Particles as (position before, position after one move, radius), the same everywhere.
fn particles(n: usize) -> Vec<([f64; 3], [f64; 3], f64)> {
    let mut s = 0x9E37_79B9_7F4A_7C15u64;
    let mut unit = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let x = [0, 1, 2].map(|d| LO[d] + (HI[d] - LO[d]) * unit());
            let mut y = x;
            for d in 0..3 {
                let len = HI[d] - LO[d];
                y[d] += (unit() - 0.5) * 0.05 * len;
                y[d] -= len * ((y[d] - LO[d]) / len).floor();
            }
            (x, y, 0.01 + 0.01 * unit())
        })
        .collect()
}

/// One rank's share: (ID, canonical force sum) of its owned particles, and its ghosts.
fn run(c: &impl Comm, procs: [usize; 3]) -> (Vec<(i64, [f64; 3])>, usize) {
    let dec = Decomposition::cartesian(procs, c.rank(), LO, HI, [true; 3]);
    let all = particles(2000);
    let mut p = Particles::default();
    for (i, (x, _, r)) in all.iter().enumerate() {
        if dec.owns(*x) {
            p.push(i as i64 + 1, 1, *x, *r, 2500.0);
        }
    }
    for i in 0..p.len() {
        p.x[i] = all[p.id[i] as usize - 1].1;
    }
    migrate(c, &dec, &mut p, None).expect("migrate");
    let nlocal = p.len();
    let plan =
        borders(c, &dec, &Halo::granular(0.04 + SKIN, SKIN), &mut p, nlocal).expect("borders");
    forward(c, &dec, &plan, &mut p, true).expect("forward");
    let mut lists: Vec<Vec<Contribution>> = vec![Vec::new(); p.len()];
    for a in 0..nlocal {
        for b in 0..p.len() {
            if a == b || p.id[a] > p.id[b] {
                continue;
            }
            let del = [0, 1, 2].map(|d| p.x[a][d] - p.x[b][d]);
            let r = (del[0] * del[0] + del[1] * del[1] + del[2] * del[2]).sqrt();
            let reach = p.radius[a] + p.radius[b];
            if r >= reach {
                continue;
            }
            let f = del.map(|v| v * 1e4 * (reach - r) / r);
            let t = [0.0; 3];
            let (ia, ib) = (p.id[a], p.id[b]);
            lists[a].push(Contribution {
                partner: ib,
                f,
                torque: t,
            });
            let minus = f.map(|v| -v);
            lists[b].push(Contribution {
                partner: ia,
                f: minus,
                torque: t,
            });
        }
    }
    reverse_contributions(c, &dec, &plan, &mut lists).expect("reverse");
    let mut owned: Vec<(i64, [f64; 3])> = (0..nlocal)
        .map(|i| (p.id[i], canonical_sum(&mut lists[i]).0))
        .collect();
    owned.sort_by_key(|o| o.0);
    (owned, plan.nghost())
}

fn to_bytes(owned: &[(i64, [f64; 3])], nghost: usize) -> Vec<u8> {
    let mut b = (nghost as u64).to_le_bytes().to_vec();
    for (id, f) in owned {
        b.extend_from_slice(&id.to_le_bytes());
        f.iter().for_each(|v| b.extend_from_slice(&v.to_le_bytes()));
    }
    b
}

fn main() {
    let Some(comm) = MpiComm::init() else {
        eprintln!("MPI could not be initialised");
        std::process::exit(1);
    };
    let n = comm.size();
    let p = Processors {
        nprocs: n as i64,
        ..Processors::default()
    };
    let prd = [0, 1, 2].map(|d| HI[d] - LO[d]);
    let procs = match choose_grid(&p, prd) {
        Ok(g) => g.procs.map(|v| v as usize),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    };
    let (owned, nghost) = run(&comm, procs);
    let gathered = comm.gather_bytes(&to_bytes(&owned, nghost));
    if let Some(mpi) = gathered {
        let threads: Vec<Vec<u8>> = ThreadRanks::run(n, |c| {
            let (o, g) = run(c, procs);
            to_bytes(&o, g)
        });
        let same = mpi == threads;
        let ghosts: Vec<u64> = mpi
            .iter()
            .map(|b| u64::from_le_bytes(b[..8].try_into().unwrap_or_default()))
            .collect();
        println!(
            "{n} ranks, grid {procs:?}, ghosts per rank {ghosts:?}: MPI and threads {}",
            if same { "agree bit for bit" } else { "DIFFER" }
        );
        if !same {
            std::process::exit(1);
        }
    }
}
