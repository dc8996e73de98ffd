use super::*;
use crate::engine::domain::parse_boundary;
use crate::engine::domain::Domain;

fn brute(x: &[[f64; 3]], cut: f64, domain: &Domain) -> Vec<(u32, u32)> {
    let mut v = Vec::new();
    for i in 0..x.len() {
        for j in i + 1..x.len() {
            let mut d = [x[j][0] - x[i][0], x[j][1] - x[i][1], x[j][2] - x[i][2]];
            domain.minimum_image(&mut d);
            if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() < cut {
                v.push((i as u32, j as u32));
            }
        }
    }
    v
}

#[test]
fn matches_brute_force_with_periodic_faces() {
    let mut domain = Domain::default();
    domain.boundary = parse_boundary(&["p", "f", "p"]).unwrap();
    domain.create([0.0; 3], [1.0, 1.0, 0.5]);
    let mut r = crate::util::random::RanPark::new(12345).unwrap();
    let x: Vec<[f64; 3]> = (0..400)
        .map(|_| [r.uniform(), r.uniform(), 0.5 * r.uniform()])
        .collect();
    let reach = vec![0.04; x.len()];
    let mut list = NeighborList::default();
    list.build(&x, &reach, 0.02, &domain, None);
    let got = unordered_pairs(&list);
    assert_eq!(got, brute(&x, 0.1, &domain));
    for p in &list.pairs {
        let (i, j) = (p.i as usize, p.j as usize);
        let d: Vec<f64> = (0..3).map(|k| x[j][k] + p.shift[k] - x[i][k]).collect();
        assert!((d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() < 0.1);
    }
    assert!(!list.needs_rebuild(&x, 0.02));
    let mut moved = x.clone();
    moved[7][0] += 0.011;
    assert!(list.needs_rebuild(&moved, 0.02));
}

#[test]
fn the_stencil_walk_lists_what_the_sorted_build_lists_in_the_same_order() {
    for (boundary, hi) in [
        (["p", "p", "f"], [0.3, 0.25, 0.2]),
        (["f", "f", "f"], [0.3, 0.25, 0.2]),
        (["p", "f", "p"], [0.22, 0.3, 0.21]),
    ] {
        let mut domain = Domain::default();
        domain.boundary = parse_boundary(&boundary).unwrap();
        domain.create([0.0; 3], hi);
        let mut r = crate::util::random::RanPark::new(98765).unwrap();
        let x: Vec<[f64; 3]> = (0..900)
            .map(|_| {
                [
                    hi[0] * r.uniform(),
                    hi[1] * r.uniform(),
                    hi[2] * r.uniform(),
                ]
            })
            .collect();
        let reach: Vec<f64> = (0..x.len()).map(|_| 0.01 + 0.01 * r.uniform()).collect();
        let skin = 0.005;
        let cut = 2.0 * 0.02 + skin;
        let order = BinOrder::new(domain.lo, domain.hi, cut);
        let mut sorted = NeighborList::default();
        sorted.build(&x, &reach, skin, &domain, Some(&order));
        let mut walked = NeighborList::default();
        assert!(walked.build_stencil(&x, &reach, skin, &domain, &order));
        assert!(sorted.pairs.len() > 1000);
        assert_eq!(sorted.pairs, walked.pairs, "{boundary:?}");
    }
}

#[test]
fn pairs_across_periodic_faces_get_a_mirror_among_their_second_atoms_entries() {
    let mut domain = Domain::default();
    domain.boundary = parse_boundary(&["p", "p", "f"]).unwrap();
    let hi = [0.3, 0.25, 0.2];
    domain.create([0.0; 3], hi);
    let mut r = crate::util::random::RanPark::new(4321).unwrap();
    let x: Vec<[f64; 3]> = (0..600)
        .map(|_| std::array::from_fn(|d| hi[d] * r.uniform()))
        .collect();
    let reach = vec![0.015; x.len()];
    let order = BinOrder::new(domain.lo, domain.hi, 2.0 * 0.015 + 0.005);
    let mut list = NeighborList::default();
    assert!(list.build_stencil(&x, &reach, 0.005, &domain, &order));
    assert!(list.mirrored);
    let across = list.pairs.iter().filter(|p| p.shift != [0.0; 3]).count();
    assert!(across > 20);
    assert_eq!(list.mirrors.len(), across);
    let mut seen = vec![false; list.pairs.len()];
    for (k, m) in list.mirrors.iter().enumerate() {
        let e = list.pairs[m.entry as usize];
        assert_eq!((m.pair.i, m.pair.j), (e.j, e.i));
        assert_eq!(m.pair.shift, e.shift.map(|v| -v));
        assert!(!std::mem::replace(&mut seen[m.entry as usize], true));
        // placed within (or right after) its first atom's block, in order
        let at = m.at as usize;
        assert!(at == list.pairs.len() || list.pairs[at].i >= m.pair.i);
        assert!(at == 0 || list.pairs[at - 1].i <= m.pair.i);
        assert!(k == 0 || list.mirrors[k - 1].at <= m.at);
    }
    // the same list without periodic faces has no mirrors
    domain.boundary = parse_boundary(&["f", "f", "f"]).unwrap();
    assert!(list.build_stencil(&x, &reach, 0.005, &domain, &order));
    assert!(!list.mirrored && list.mirrors.is_empty());
}

#[test]
fn history_follows_atom_ids() {
    let old = vec![Pair {
        i: 0,
        j: 1,
        shift: [0.0; 3],
    }];
    let hist = vec![1.0, 2.0, 3.0];
    // atoms were reordered: ids [5, 9] became [9, 5]
    let new = vec![Pair {
        i: 0,
        j: 1,
        shift: [0.0; 3],
    }];
    let carried = carry_history(&old, &hist, &new, &[9, 5], &[5, 9], &[true; 3], |_| true);
    assert_eq!(carried, vec![-1.0, -2.0, -3.0]);
    let fresh = carry_history(&old, &hist, &new, &[9, 7], &[5, 9], &[true; 3], |_| true);
    assert_eq!(fresh, vec![0.0; 3]);
    // a pair turned down (not touching at the build) starts afresh
    let dropped = carry_history(&old, &hist, &new, &[9, 5], &[5, 9], &[true; 3], |_| false);
    assert_eq!(dropped, vec![0.0; 3]);
}

#[test]
fn blocks_start_at_their_first_particles_entries() {
    let pair = |i: u32, j: u32| Pair {
        i,
        j,
        shift: [0.0; 3],
    };
    let b = BLOCK_PARTICLES as u32;
    // block 0: entries 0..3, block 1 (no entries): 3..3, block 2: 3..5
    let pairs = [
        pair(0, 1),
        pair(0, b + 3),
        pair(b - 1, 2 * b),
        pair(2 * b, 2 * b + 1),
        pair(2 * b + 5, 7),
    ];
    let n = 2 * BLOCK_PARTICLES + 10;
    assert_eq!(block_starts(&pairs, n), Some(vec![0, 3, 3, 5]));
    // no list, one block per BLOCK_PARTICLES particles all the same
    assert_eq!(block_starts(&[], n), Some(vec![0, 0, 0, 0]));
    // not grouped by ascending first particle, or a particle past the end: none
    assert_eq!(block_starts(&[pair(5, 6), pair(1, 2)], n), None);
    assert_eq!(block_starts(&[pair(n as u32, 1)], n), None);
}

#[test]
fn particles_flung_far_apart_get_a_small_grid() {
    // a blow-up leaves particles 1e22 m apart with a 1 mm cutoff: 1024 cells a side would
    // be 2^30 cells (8 GB of cell starts); the grids are coarsened and the lists still right
    let mut domain = Domain::default();
    domain.boundary = parse_boundary(&["f", "f", "f"]).unwrap();
    domain.create([0.0; 3], [1.0, 1.0, 1.0]);
    let x = vec![
        [0.0, 0.0, 0.0],
        [0.0005, 0.0, 0.0],
        [1e22, 1e22, 1e22],
        [1e22, 1e22, 1e22 + 0.0004],
    ];
    let reach = vec![0.0003; x.len()];
    let mut list = NeighborList::default();
    list.build(&x, &reach, 0.0002, &domain, None);
    let got = unordered_pairs(&list);
    assert_eq!(got, vec![(0, 1), (2, 3)]);
    let grid = crate::engine::cells::CellGrid::new(&x, 0.0008, &domain).unwrap();
    assert!(grid.len() <= 1 << 15, "{} cells", grid.len());
}

/// The list's pairs as (smaller, larger) particle index, sorted.
fn unordered_pairs(list: &NeighborList) -> Vec<(u32, u32)> {
    let mut got: Vec<(u32, u32)> = list
        .pairs
        .iter()
        .map(|p| (p.i.min(p.j), p.i.max(p.j)))
        .collect();
    got.sort();
    got
}
