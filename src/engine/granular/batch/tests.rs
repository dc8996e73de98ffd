//! The batched kernel and touching test against the one-pair versions, bit for bit.

use super::touching::touching_one_by_one;
use super::*;

#[test]
fn four_at_a_time_touching_test_finds_what_the_pair_by_pair_one_finds() {
    let mut r = crate::util::random::RanPark::new(4711).unwrap();
    let packed = Packed {
        records: Vec::new(),
        spheres: (0..50)
            .map(|_| {
                Sphere([
                    r.uniform(),
                    r.uniform(),
                    r.uniform(),
                    0.1 + 0.2 * r.uniform(),
                ])
            })
            .collect(),
    };
    let pairs: Vec<Pair> = (0..403)
        .map(|k| Pair {
            i: (k % 50) as u32,
            j: ((k * 7 + 3) % 50) as u32,
            shift: if k % 5 == 0 {
                [1.0, 0.0, -1.0]
            } else {
                [0.0; 3]
            },
        })
        .collect();
    let mut fast = vec![7];
    touching_entries(&packed, &pairs, 10, &mut fast);
    let mut slow = vec![0; pairs.len()];
    let spare: &mut [std::mem::MaybeUninit<u32>] =
        // SAFETY: u32 and MaybeUninit<u32> share a layout
        unsafe { std::mem::transmute(&mut slow[..]) };
    let n = touching_one_by_one(&packed.spheres, &pairs, 10, spare);
    slow.truncate(n);
    assert!(
        n > 20 && n < pairs.len() - 20,
        "{n} touching of {}",
        pairs.len()
    );
    assert_eq!(fast[0], 7);
    assert_eq!(&fast[1..], &slow[..]);
}

/// Collects every result in the order the kernel hands them over.
#[derive(Default)]
struct Collect(Vec<(usize, PairResult)>);

impl Sink for Collect {
    fn take(&mut self, entry: usize, _: &Pair, result: &PairResult) {
        self.0.push((entry, *result));
    }
}

/// The batched kernel (eight, then four pairs at a time where the processor allows)
/// gives every pair the forces, torques, overlap and history the one-pair kernel gives,
/// bit for bit, with one atom type and with two.
#[test]
fn batched_pairs_equal_one_at_a_time() {
    use crate::engine::contact::tangential::History;
    use crate::engine::contact::{Epsd, Hertz, MaterialInput, Sjkr};
    let model = ContactModel::new(Hertz::default(), History, Sjkr::default(), Epsd::default());
    for ntypes in [1usize, 2] {
        let input = MaterialInput {
            ntypes,
            youngs_modulus: Some(vec![5e6, 7e6][..ntypes].to_vec()),
            poissons_ratio: Some(vec![0.25, 0.3][..ntypes].to_vec()),
            coefficient_restitution: Some(vec![0.5; ntypes * ntypes]),
            coefficient_friction: Some(vec![0.6; ntypes * ntypes]),
            coefficient_rolling_friction: Some(vec![0.3; ntypes * ntypes]),
            coefficient_rolling_viscous_damping: Some(vec![1.5; ntypes * ntypes]),
            cohesion_energy_density: Some(vec![2e3; ntypes * ntypes]),
            ..MaterialInput::default()
        };
        let material = Material::new(&input, &model.properties()).unwrap();
        let mut r = crate::util::random::RanPark::new(104729).unwrap();
        let mut u = |lo: f64, hi: f64| lo + (hi - lo) * r.uniform();
        let n = 80;
        let records: Vec<Record> = (0..n)
            .map(|k| {
                let frozen = if k % 17 == 3 { 1.0 } else { 0.0 };
                Record([
                    u(0.0, 6e-3),
                    u(0.0, 6e-3),
                    u(0.0, 6e-3),
                    u(0.8e-3, 1.2e-3),
                    u(-0.2, 0.2),
                    u(-0.2, 0.2),
                    u(-0.2, 0.2),
                    u(1e-5, 3e-5),
                    u(-40.0, 40.0),
                    u(-40.0, 40.0),
                    u(-40.0, 40.0),
                    frozen,
                ])
            })
            .collect();
        let kinds: Vec<u32> = (0..n).map(|k| 1 + (k % ntypes) as u32).collect();
        let mut pairs = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let (a, b) = (&records[i].0, &records[j].0);
                let d2: f64 = (0..3).map(|d| (a[d] - b[d]).powi(2)).sum();
                if d2 < (a[3] + b[3]).powi(2) {
                    pairs.push(Pair {
                        i: i as u32,
                        j: j as u32,
                        shift: [0.0; 3],
                    });
                }
            }
        }
        assert!(pairs.len() > 8 * 6 + 3, "{} touching pairs", pairs.len());
        let packed = Packed {
            records,
            spheres: Vec::new(),
        };
        // every pair but a few, so the last batches are short
        let entries: Vec<u32> = (0..pairs.len() as u32).filter(|e| e % 11 != 5).collect();
        let width = model.history_len();
        let mut h_batched = vec![0.0; pairs.len() * width];
        let mut h_single = h_batched.clone();
        let kernel = Kernel::new(&model, &material, 1e-6, true);
        for _ in 0..3 {
            let (mut batched, mut single) = (Collect::default(), Collect::default());
            kernel.run(
                &packed,
                &kinds,
                &pairs,
                &entries,
                &mut h_batched,
                &mut batched,
            );
            kernel.run_scalar(
                &packed,
                &kinds,
                &pairs,
                &entries,
                &mut h_single,
                &mut single,
            );
            assert_eq!(batched.0.len(), entries.len());
            for ((e1, r1), (e2, r2)) in batched.0.iter().zip(&single.0) {
                assert_eq!(e1, e2);
                let bits = |r: &PairResult| {
                    [r.fi, r.fj, r.ti, r.tj]
                        .concat()
                        .iter()
                        .map(|x| x.to_bits())
                        .chain([r.overlap_ratio.to_bits()])
                        .collect::<Vec<_>>()
                };
                assert_eq!(bits(r1), bits(r2), "entry {e1}, {ntypes} types");
            }
        }
        let bits = |h: &[f64]| h.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&h_batched), bits(&h_single));
        assert!(h_single.iter().any(|&x| x != 0.0));
    }
}
