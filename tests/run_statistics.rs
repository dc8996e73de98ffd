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
