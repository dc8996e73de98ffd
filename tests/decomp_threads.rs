//! Domain decomposition on threads standing in for MPI ranks: migration, ghosts, forward
//! and reverse communication compared with the serial answer, pair by pair and bit by bit.

use proptest::prelude::*;
use regolith::engine::decomp::{
    borders, canonical_sum, forward, migrate, reverse, reverse_contributions, Contribution,
    Decomposition, GhostPlan, PartnerHistory,
};
use regolith::engine::neighbor::Pair;
use regolith::engine::particles::Particles;
use regolith::util::comm::Comm;
use regolith::util::comm_threads::ThreadRanks;

mod decomp_common;
use decomp_common::{particles, Case, HI, LO};

/// Position of `b`'s image `k` (box lengths per axis), as a ghost's is computed.
fn image(xb: [f64; 3], k: [i32; 3]) -> [f64; 3] {
    [0, 1, 2].map(|d| xb[d] + f64::from(k[d]) * (HI[d] - LO[d]))
}

/// A pair force on `a` from `b` at `xb` (a spring on the overlap), if they are in reach.
fn pair_force(case: &Case, xa: [f64; 3], xb: [f64; 3], ra: f64, rb: f64) -> Option<[f64; 3]> {
    let del = [0, 1, 2].map(|d| xa[d] - xb[d]);
    let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
    let reach = case.reach(ra, rb);
    if rsq >= reach * reach {
        return None;
    }
    let r = rsq.sqrt();
    let s = 1.0e3 * (reach - r) / r;
    Some(del.map(|c| c * s))
}

/// Serial answer: every ordered pair (a, b) in reach, with b's nearest image, and its force.
fn serial_pairs(case: &Case, x: &[[f64; 3]], radius: &[f64]) -> Vec<(i64, i64, [f64; 3])> {
    let ks: Vec<[i32; 3]> = (0..27)
        .map(|m| [m % 3 - 1, (m / 3) % 3 - 1, m / 9 - 1])
        .filter(|k| (0..3).all(|d| case.periodic[d] || k[d] == 0))
        .collect();
    let mut out = Vec::new();
    for a in 0..x.len() {
        for b in 0..x.len() {
            for k in &ks {
                if a == b && *k == [0, 0, 0] {
                    continue;
                }
                if let Some(f) = pair_force(case, x[a], image(x[b], *k), radius[a], radius[b]) {
                    out.push((a as i64 + 1, b as i64 + 1, f));
                }
            }
        }
    }
    out.sort_by_key(|p| (p.0, p.1));
    out
}

/// What one rank found.
struct RankResult {
    owned: Vec<(i64, [f64; 3])>,
    /// (ID, image) of owned particles and ghosts.
    copies: Vec<(i64, [i32; 3])>,
    /// Ordered pairs (owned a, any b) with the force on a.
    pairs: Vec<(i64, i64, [f64; 3])>,
    /// Canonical sums on owned particles: pairs on both sides (no reverse communication).
    newton_off: Vec<(i64, [f64; 3])>,
    /// Canonical sums on owned particles: each pair once, the other side sent back.
    newton_on: Vec<(i64, [f64; 3])>,
    /// Plain reverse-communicated sums on owned particles.
    summed: Vec<(i64, [f64; 3])>,
    /// Ghosts whose forward-communicated values differ from their owners'.
    stale_ghosts: usize,
    /// Owned particles whose fix state or contact history did not travel with them.
    lost_state: usize,
    /// Pairs whose history, taken back from the partner lists, is not the one they had.
    wrong_history: usize,
    /// Pairs that took back a history (in contact at the start).
    carried_history: usize,
}

/// Which history values are vectors (they change sign seen from the other particle).
const FLIPS: [bool; 3] = [true, false, true];

/// The contact history of two particles in contact at the start, seen from `a`.
fn history_between(a: i64, b: i64) -> [f64; 3] {
    let (lo, hi) = (a.min(b), a.max(b));
    let seen_from_lo = [(lo * 1000 + hi) as f64, 0.5, -(hi as f64)];
    let sign = if a == lo { 1.0 } else { -1.0 };
    [
        sign * seen_from_lo[0],
        seen_from_lo[1],
        sign * seen_from_lo[2],
    ]
}

/// Every particle's partner list at the start: the serial pair list (each pair once, from
/// its lower ID) and its history written into the particles.
fn start_history(case: &Case, start: &[[f64; 3]], radius: &[f64]) -> PartnerHistory {
    let serial = serial_pairs(case, start, radius);
    let once: Vec<_> = serial.iter().filter(|p| p.0 < p.1).collect();
    let pairs: Vec<Pair> = once
        .iter()
        .map(|p| Pair {
            i: p.0 as u32 - 1,
            j: p.1 as u32 - 1,
            shift: [0.0; 3],
        })
        .collect();
    let values: Vec<f64> = once
        .iter()
        .flat_map(|p| history_between(p.0, p.1))
        .collect();
    let ids: Vec<i64> = (1..=case.n as i64).collect();
    PartnerHistory::from_pairs(&pairs, &values, &ids, case.n, &FLIPS)
}

/// Pairs in reach on a rank (owned first, or a ghost first for odd IDs) and how many took
/// the wrong history back from the partner lists, and how many took a non-zero one.
fn history_check(
    case: &Case,
    p: &Particles,
    nlocal: usize,
    hist: &PartnerHistory,
    start: &PartnerHistory,
) -> (usize, usize) {
    let mut pairs = Vec::new();
    for a in 0..nlocal {
        for b in 0..p.len() {
            let listed = b >= nlocal || a < b;
            if a == b
                || !listed
                || pair_force(case, p.x[a], p.x[b], p.radius[a], p.radius[b]).is_none()
            {
                continue;
            }
            let (i, j) = if b >= nlocal && p.id[b] % 2 == 1 {
                (b, a)
            } else {
                (a, b)
            };
            pairs.push(Pair {
                i: i as u32,
                j: j as u32,
                shift: [0.0; 3],
            });
        }
    }
    let got = hist.to_pairs(&pairs, &p.id, nlocal, &FLIPS);
    let mut wrong = 0;
    let mut carried = 0;
    for (k, q) in pairs.iter().enumerate() {
        let (a, b) = (p.id[q.i as usize], p.id[q.j as usize]);
        let touched = start.get(a as usize - 1, b).is_some();
        let want = if touched {
            history_between(a, b)
        } else {
            [0.0; 3]
        };
        if got[3 * k..3 * k + 3] != want {
            wrong += 1;
        }
        carried += usize::from(touched);
    }
    (wrong, carried)
}

fn run_rank(c: &impl Comm, case: &Case) -> RankResult {
    let dec = Decomposition::cartesian(case.procs, c.rank(), LO, HI, case.periodic);
    let (start, moved, radius) = particles(case);
    let mut p = Particles::default();
    let k = p.extra_index("fix_state", 2);
    let global = start_history(case, &start, &radius);
    let mut hist = PartnerHistory::new(3, 0);
    for (i, x) in start.iter().enumerate() {
        if dec.owns(*x) {
            let id = i as i64 + 1;
            p.push(id, 1, *x, radius[i], 2500.0);
            let n = p.len();
            p.extra[k].data[2 * (n - 1)..2 * n].copy_from_slice(&[id as f64, -0.25 * id as f64]);
            hist.partners.push(global.partners[i].clone());
            hist.values.push(global.values[i].clone());
        }
    }
    for i in 0..p.len() {
        p.x[i] = moved[p.id[i] as usize - 1];
    }
    migrate(c, &dec, &mut p, Some(&mut hist)).expect("migrate");
    let nlocal = p.len();
    let mut lost_state = 0;
    for i in 0..nlocal {
        let id = p.id[i];
        let (partners, values) = (
            &global.partners[id as usize - 1],
            &global.values[id as usize - 1],
        );
        let fix_ok = p.extra[k].data[2 * i..2 * i + 2] == [id as f64, -0.25 * id as f64];
        if !fix_ok || hist.partners[i] != *partners || hist.values[i] != *values {
            lost_state += 1;
        }
    }
    let plan = borders(c, &dec, &case.halo(), &mut p, nlocal).expect("borders");
    let mut copies: Vec<(i64, [i32; 3])> = (0..nlocal).map(|i| (p.id[i], [0; 3])).collect();
    copies.extend((0..plan.nghost()).map(|g| (p.id[nlocal + g], plan.ghost_image[g])));
    let (wrong_history, carried_history) = history_check(case, &p, nlocal, &hist, &global);
    let result = forces(c, case, &dec, &plan, &mut p);
    let stale_ghosts = forward_check(c, &dec, &plan, &mut p);
    RankResult {
        owned: (0..nlocal).map(|i| (p.id[i], p.x[i])).collect(),
        copies,
        stale_ghosts,
        lost_state,
        wrong_history,
        carried_history,
        ..result
    }
}

/// Pairs and forces three ways on one rank.
fn forces(
    c: &impl Comm,
    case: &Case,
    dec: &Decomposition,
    plan: &GhostPlan,
    p: &mut Particles,
) -> RankResult {
    let nlocal = plan.nlocal;
    let mut pairs = Vec::new();
    let mut off: Vec<Vec<Contribution>> = vec![Vec::new(); nlocal];
    let mut on: Vec<Vec<Contribution>> = vec![Vec::new(); p.len()];
    p.clear_forces();
    for a in 0..nlocal {
        for b in 0..p.len() {
            if a == b {
                continue;
            }
            let Some(f) = pair_force(case, p.x[a], p.x[b], p.radius[a], p.radius[b]) else {
                continue;
            };
            pairs.push((p.id[a], p.id[b], f));
            let (ia, ib) = (p.id[a], p.id[b]);
            off[a].push(Contribution {
                partner: ib,
                f,
                torque: [0.0; 3],
            });
            // each pair once: on the rank owning its lower ID, from that particle's side
            if ia < ib {
                on[a].push(Contribution {
                    partner: ib,
                    f,
                    torque: [0.0; 3],
                });
                let minus = f.map(|v| -v);
                on[b].push(Contribution {
                    partner: ia,
                    f: minus,
                    torque: [0.0; 3],
                });
                for d in 0..3 {
                    p.f[a][d] += f[d];
                    p.f[b][d] += minus[d];
                }
            }
        }
    }
    reverse_contributions(c, dec, plan, &mut on).expect("reverse contributions");
    reverse(c, dec, plan, p).expect("reverse");
    let ids = &p.id;
    RankResult {
        owned: Vec::new(),
        copies: Vec::new(),
        pairs,
        newton_off: off
            .iter_mut()
            .enumerate()
            .map(|(i, l)| (ids[i], canonical_sum(l).0))
            .collect(),
        newton_on: on[..nlocal]
            .iter_mut()
            .enumerate()
            .map(|(i, l)| (ids[i], canonical_sum(l).0))
            .collect(),
        summed: (0..nlocal).map(|i| (ids[i], p.f[i])).collect(),
        stale_ghosts: 0,
        lost_state: 0,
        wrong_history: 0,
        carried_history: 0,
    }
}

/// Move and spin the owned particles, forward them and count ghosts that do not match.
fn forward_check(c: &impl Comm, dec: &Decomposition, plan: &GhostPlan, p: &mut Particles) -> usize {
    let nlocal = plan.nlocal;
    let state = |id: i64| {
        let s = id as f64;
        (
            [1e-3 * s, -2e-3, 0.5e-3],
            [s, 2.0 * s, -s],
            [0.1 / s, 0.0, 3.0],
            0.01 + 1e-4 * s,
        )
    };
    for i in 0..nlocal {
        let (dx, v, w, r) = state(p.id[i]);
        for (c, step) in p.x[i].iter_mut().zip(dx) {
            *c += step;
        }
        (p.v[i], p.omega[i], p.radius[i]) = (v, w, r);
    }
    let owners: std::collections::HashMap<i64, [f64; 3]> =
        (0..nlocal).map(|i| (p.id[i], p.x[i])).collect();
    forward(c, dec, plan, p, true).expect("forward");
    let all = c.gather_bytes(&bincode_positions(&owners));
    let mut flat = Vec::new();
    if let Some(all) = &all {
        flat = all.concat();
    }
    c.broadcast_bytes(0, &mut flat);
    let positions = read_positions(&flat);
    (0..plan.nghost())
        .filter(|&g| {
            let i = nlocal + g;
            let (_, v, w, r) = state(p.id[i]);
            let want = image(positions[&p.id[i]], plan.ghost_image[g]);
            p.x[i] != want || p.v[i] != v || p.omega[i] != w || p.radius[i] != r
        })
        .count()
}

fn bincode_positions(m: &std::collections::HashMap<i64, [f64; 3]>) -> Vec<u8> {
    let mut out = Vec::new();
    for (id, x) in m {
        out.extend_from_slice(&id.to_le_bytes());
        x.iter()
            .for_each(|c| out.extend_from_slice(&c.to_le_bytes()));
    }
    out
}

fn read_positions(b: &[u8]) -> std::collections::HashMap<i64, [f64; 3]> {
    let word = |k: usize| {
        let mut w = [0u8; 8];
        w.copy_from_slice(&b[k..k + 8]);
        w
    };
    (0..b.len() / 32)
        .map(|r| {
            let o = 32 * r;
            let id = i64::from_le_bytes(word(o));
            (id, [1, 2, 3].map(|k| f64::from_le_bytes(word(o + 8 * k))))
        })
        .collect()
}

/// What a checked case gives back.
struct Checked {
    /// Pairs (ordered, over all ranks) that took back their contact history.
    carried: usize,
    /// Number of ordered pairs in reach.
    pairs: usize,
    /// Per particle (by ID - 1): the force summed by reverse communication.
    summed: Vec<[f64; 3]>,
    /// Per particle: the force summed in the canonical order.
    canonical: Vec<[f64; 3]>,
}

/// Run a case on its ranks and compare everything with the serial answer.
fn check(case: Case) -> Checked {
    let n = case.procs.iter().product();
    let results = ThreadRanks::run(n, |c| run_rank(c, &case));
    let (_, moved, radius) = particles(&case);
    // every particle owned once, where it is
    let mut owned: Vec<i64> = results
        .iter()
        .flat_map(|r| r.owned.iter().map(|o| o.0))
        .collect();
    owned.sort_unstable();
    assert_eq!(owned, (1..=case.n as i64).collect::<Vec<_>>(), "{case:?}");
    for (rank, r) in results.iter().enumerate() {
        let dec = Decomposition::cartesian(case.procs, rank, LO, HI, case.periodic);
        for (id, _) in &r.owned {
            assert!(
                dec.owns(moved[*id as usize - 1]),
                "{case:?}: {id} on {rank}"
            );
        }
        let mut copies = r.copies.clone();
        copies.sort_unstable();
        copies.dedup();
        assert_eq!(
            copies.len(),
            r.copies.len(),
            "{case:?}: a copy twice on {rank}"
        );
        assert_eq!(r.stale_ghosts, 0, "{case:?}: forward on {rank}");
        assert_eq!(r.lost_state, 0, "{case:?}: migrated state on {rank}");
        assert_eq!(r.wrong_history, 0, "{case:?}: contact history on {rank}");
    }
    // the same ordered pairs with the same forces, bit for bit
    let serial = serial_pairs(&case, &moved, &radius);
    let mut pairs: Vec<_> = results.iter().flat_map(|r| r.pairs.clone()).collect();
    pairs.sort_by_key(|p| (p.0, p.1));
    let first_difference = pairs.iter().zip(&serial).find(|(a, b)| a != b);
    assert_eq!(first_difference, None, "{case:?}");
    assert_eq!(pairs.len(), serial.len(), "{case:?}");
    // serial totals: contributions by partner ID, and each pair once from its lower ID
    let mut per: Vec<Vec<Contribution>> = vec![Vec::new(); case.n];
    let mut once: Vec<Vec<Contribution>> = vec![Vec::new(); case.n];
    for &(a, b, f) in &serial {
        let c = |partner, f| Contribution {
            partner,
            f,
            torque: [0.0; 3],
        };
        per[a as usize - 1].push(c(b, f));
        if a < b {
            once[a as usize - 1].push(c(b, f));
            once[b as usize - 1].push(c(a, f.map(|v| -v)));
        }
    }
    let total: Vec<[f64; 3]> = per.iter_mut().map(|l| canonical_sum(l).0).collect();
    let total_once: Vec<[f64; 3]> = once.iter_mut().map(|l| canonical_sum(l).0).collect();
    for r in &results {
        for (&(id, off), &(_, on)) in r.newton_off.iter().zip(&r.newton_on) {
            assert_eq!(off, total[id as usize - 1], "{case:?}: {id}");
            assert_eq!(on, total_once[id as usize - 1], "{case:?}: {id}");
        }
        for &(id, f) in &r.summed {
            let want = total_once[id as usize - 1];
            for d in 0..3 {
                let tol = 1e-9 * (1.0 + want[d].abs());
                assert!(
                    (f[d] - want[d]).abs() <= tol,
                    "{case:?}: {id} {f:?} {want:?}"
                );
            }
        }
    }
    let mut summed = vec![[0.0; 3]; case.n];
    for r in &results {
        for &(id, f) in &r.summed {
            summed[id as usize - 1] = f;
        }
    }
    Checked {
        carried: results.iter().map(|r| r.carried_history).sum(),
        pairs: serial.len(),
        summed,
        canonical: total_once,
    }
}

fn case(procs: [usize; 3], periodic: [bool; 3], cut: Option<f64>) -> Case {
    Case {
        procs,
        periodic,
        cut,
        n: 300,
        seed: 7,
    }
}

/// Check a case with enough pairs and carried contacts to mean something.
fn checked(c: Case) {
    let r = check(c);
    assert!(
        r.pairs > 100 && r.carried > 20,
        "{c:?}: {} {}",
        r.pairs,
        r.carried
    );
}

#[test]
fn one_rank_periodic_makes_self_images() {
    checked(case([1, 1, 1], [true; 3], None));
    checked(case([1, 1, 1], [true, false, true], Some(0.12)));
}

#[test]
fn two_ranks_along_x() {
    checked(case([2, 1, 1], [true; 3], None));
    checked(case([2, 1, 1], [false; 3], None));
    checked(case([2, 1, 1], [false, true, false], Some(0.15)));
}

#[test]
fn three_ranks_along_x() {
    checked(case([3, 1, 1], [true; 3], None));
    checked(case([3, 1, 1], [false, true, true], Some(0.2)));
}

#[test]
fn four_ranks_two_by_two_and_in_a_row() {
    checked(case([2, 2, 1], [true; 3], None));
    checked(case([2, 2, 1], [true, false, false], Some(0.1)));
    // ghosts from two ranks away: the cutoff is wider than a sub-domain (0.125 in z)
    checked(case([1, 1, 4], [true; 3], Some(0.2)));
    checked(case([1, 1, 4], [false; 3], Some(0.2)));
}

#[test]
fn canonical_sums_are_the_same_bits_for_any_rank_count() {
    let on = |procs| check(case(procs, [true; 3], None));
    let serial = on([1, 1, 1]);
    let mut reordered = 0;
    for procs in [[2, 1, 1], [3, 1, 1], [2, 2, 1], [1, 2, 2], [4, 1, 1]] {
        let ranks = on(procs);
        assert_eq!(ranks.canonical, serial.canonical, "{procs:?}");
        reordered += (0..ranks.summed.len())
            .filter(|&i| ranks.summed[i] != serial.summed[i])
            .count();
    }
    // the plain reverse sums, added in an order that follows the ranks, do change bits
    assert!(reordered > 0);
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn any_grid_of_up_to_four_ranks_matches_serial(
        grid in 0usize..6,
        periodic in proptest::array::uniform3(any::<bool>()),
        cut in proptest::option::of(0.05f64..0.24),
        n in 1usize..120,
        seed in any::<u64>(),
    ) {
        let procs = [[1, 1, 1], [2, 1, 1], [1, 3, 1], [2, 2, 1], [1, 2, 2], [4, 1, 1]][grid];
        check(Case { procs, periodic, cut, n, seed: seed | 1 });
    }
}
