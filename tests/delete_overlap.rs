//! `delete_atoms overlap`: after it, no two atoms of the groups lie closer than the cutoff
//! (periodic images included), and the atoms removed are those of LIGGGHTS's documented rule
//! (memory order; a partner already removed does not count), recomputed here by brute force.
//! Debian's LIGGGHTS 3.8.0 itself removes the wrong atoms (see README, deviations).

mod common;

const CUT: f64 = 0.0029;

fn deck(stage: &str) -> String {
    format!(
        "units si\natom_style granular\natom_modify map array\nboundary p f f\nnewton off\n\
         communicate single vel yes\nregion reg block 0 0.02 -0.005 0.025 -0.005 0.025 units box\n\
         create_box 1 reg\nneighbor 0.001 bin\n\
         fix m1 all property/global youngsModulus peratomtype 5e6\n\
         fix m2 all property/global poissonsRatio peratomtype 0.3\n\
         fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\npair_coeff * *\n\
         lattice sc 0.004\nregion fill block 0 5 0 5 0 5 units lattice\n\
         create_atoms 1 region fill\nset group all diameter 0.002 density 2500\n\
         displace_atoms all random 0.0009 0.0009 0.0009 10007 units box\n\
         {stage}\
         dump d all custom 1 atoms.dump id x y z\ndump_modify d sort id\nrun 0\n"
    )
}

/// Run a deck; return the (id, x, y, z) rows of its dump and its screen output.
fn run(name: &str, deck: &str) -> (Vec<[f64; 4]>, String) {
    let dir = common::scratch_dir(&format!("overlap-{name}"));
    let out = common::run_deck(&dir, "in.deck", deck, &[]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(dir.join("atoms.dump")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let rows = text
        .lines()
        .skip_while(|l| !l.starts_with("ITEM: ATOMS"))
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|w| w.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3]]
        })
        .collect();
    (rows, String::from_utf8_lossy(&out.stdout).into_owned())
}

/// Distance with the minimum image along periodic x (box length 0.02).
fn distance(a: &[f64; 4], b: &[f64; 4]) -> (f64, bool) {
    let mut dx = a[1] - b[1];
    let across = dx.abs() > 0.01;
    if across {
        dx -= 0.02 * dx.signum();
    }
    let (dy, dz) = (a[2] - b[2], a[3] - b[3]);
    ((dx * dx + dy * dy + dz * dz).sqrt(), across)
}

#[test]
fn overlap_deletion_leaves_no_close_pairs_and_follows_the_rule() {
    let (before, _) = run("before", &deck(""));
    let (after, screen) = run(
        "after",
        &deck(&format!("delete_atoms overlap {CUT} all all compress no\n")),
    );
    assert_eq!(
        before.len(),
        180,
        "no atom may be lost: memory order must be ID order"
    );
    // brute force: memory order is ID order here (no step has sorted the atoms yet)
    let mut gone = vec![false; before.len()];
    for i in 0..before.len() {
        for j in 0..before.len() {
            let (d, across) = distance(&before[i], &before[j]);
            if i == j || d >= CUT {
                continue;
            }
            if (!across && gone[j]) || (across && before[i][0] > before[j][0]) {
                continue;
            }
            gone[i] = true;
            break;
        }
    }
    let expected: Vec<f64> = (0..before.len())
        .filter(|&i| !gone[i])
        .map(|i| before[i][0])
        .collect();
    let ids: Vec<f64> = after.iter().map(|r| r[0]).collect();
    assert!(
        expected.len() < 170,
        "the lattice should have close pairs: {}",
        expected.len()
    );
    assert_eq!(ids, expected);
    for (k, a) in after.iter().enumerate() {
        for b in &after[k + 1..] {
            assert!(
                distance(a, b).0 >= CUT,
                "atoms {} and {} still overlap",
                a[0],
                b[0]
            );
        }
    }
    assert!(screen.contains(&format!(
        "Deleted {} atoms, new total = {}",
        before.len() - expected.len(),
        expected.len()
    )));
}
