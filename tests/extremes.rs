//! Stability at the extremes (issue 16): elastic two-sphere collisions (e = 1, no friction)
//! at Young's moduli 1e5 and 2.1e11 Pa, a 10:1 radius ratio, an impact at 20 % of the bar
//! sound speed sqrt(E / rho), and a time step of 1e-10 s conserve energy and momentum; a
//! particle leaving through a fixed face is dropped as LIGGGHTS drops it; no dump any of
//! them writes holds NaN or infinity. Each deck's result line is also LIGGGHTS's
//! (Debian's liggghts 3.8.0 printed the same line for the same deck and variables).

mod common;

use std::path::{Path, PathBuf};

/// Two spheres (radii R1 >= R2) meet head-on at v each from a gap of 0.05 R2 and part;
/// the run ends two Hertz contact times after the touch. `drift` is the kinetic energy
/// after over before, minus 1; `dp` the change of momentum over the momentum scale.
const PAIR: &str = r#"variable E index 5e6
variable rho index 2500
variable R1 index 0.00125
variable R2 index 0.00125
variable v index 1
variable frac index 0.02
variable nu equal 0.2
variable G equal ${E}/(2*(1+${nu}))
variable Rmin equal ${R2}
variable tR equal PI*${Rmin}*sqrt(${rho}/${G})/(0.1631*${nu}+0.8766)
variable dt index $(v_frac*v_tR)
variable m1 equal 4/3*PI*${R1}^3*${rho}
variable m2 equal 4/3*PI*${R2}^3*${rho}
variable Rs equal ${R1}*${R2}/(${R1}+${R2})
variable ms equal ${m1}*${m2}/(${m1}+${m2})
variable Ys equal ${E}/(2*(1-${nu}^2))
variable tc equal 2.87*(${ms}^2/(${Rs}*${Ys}^2*2*${v}))^0.2
variable gap equal 0.05*${Rmin}
variable nsteps equal ceil((${gap}/(2*${v})+2*${tc})/${dt})
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
soft_particles yes
hard_particles yes
region box block $(-3*v_R1) $(3*v_R2) $(-2*v_R1) $(2*v_R1) $(-2*v_R1) $(2*v_R1) units box
create_box 1 box
neighbor $(0.2*v_Rmin) bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype ${E}
fix m2 all property/global poissonsRatio peratomtype ${nu}
fix m3 all property/global coefficientRestitution peratomtypepair 1 1.0
fix m4 all property/global coefficientFriction peratomtypepair 1 0.0
pair_style gran model hertz tangential history
pair_coeff * *
timestep ${dt}
create_atoms 1 single $(-v_R1-v_gap/2) 0 0 units box
create_atoms 1 single $(v_R2+v_gap/2) 0 0 units box
set atom 1 diameter $(2*v_R1) density ${rho}
set atom 2 diameter $(2*v_R2) density ${rho}
set atom 1 vx ${v}
set atom 2 vx -${v}
fix integr all nve/sphere
compute ke all ke
variable px equal mass[1]*vx[1]+mass[2]*vx[2]
variable p0 equal ${m1}*${v}-${m2}*${v}
variable ke0 equal 0.5*(${m1}+${m2})*${v}^2
variable drift equal c_ke/${ke0}-1
variable dp equal (v_px-${p0})/(${m1}*${v}+${m2}*${v})
thermo_style custom step atoms c_ke v_drift v_dp
thermo_modify norm no
thermo $(v_nsteps)
dump d all custom $(ceil(v_nsteps/10)) d_*.dump id x y z vx vy vz fx fy fz omegax omegay omegaz
run ${nsteps}
print "RESULT drift ${drift} dp ${dp} steps ${nsteps}"
"#;

fn scratch(name: &str) -> PathBuf {
    common::scratch_dir(&format!("extremes-{name}"))
}

/// Run `deck` (text) in a fresh folder with `vars`; (exit code, stdout, stderr, folder).
fn run(name: &str, deck: &str, vars: &[(&str, &str)]) -> (Option<i32>, String, String, PathBuf) {
    let dir = scratch(name);
    let args: Vec<&str> = vars.iter().flat_map(|&(k, v)| ["-var", k, v]).collect();
    let out = common::run_deck(&dir, "in.deck", deck, &args);
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        dir,
    )
}

/// Every number in every dump of `dir` is finite; returns how many dumps were read.
fn scan_dumps(dir: &Path) -> usize {
    let mut n = 0;
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let path = e.path();
        if path.extension().and_then(|x| x.to_str()) != Some("dump") {
            continue;
        }
        n += 1;
        let text = std::fs::read_to_string(&path).unwrap();
        for word in text.split_whitespace() {
            let lower = word.to_ascii_lowercase();
            assert!(
                !(lower.contains("nan") || lower.contains("inf")) || word.starts_with("ITEM"),
                "{word} in {}",
                path.display()
            );
            if let Ok(x) = word.parse::<f64>() {
                assert!(x.is_finite(), "{word} in {}", path.display());
            }
        }
    }
    n
}

/// (name, variables, LIGGGHTS's result line, bound on |drift|)
type Case = (
    &'static str,
    &'static [(&'static str, &'static str)],
    &'static str,
    f64,
);

#[test]
fn elastic_collisions_conserve_energy_and_momentum_at_the_extremes() {
    let cases: [Case; 5] = [
        // soft_particles' lowest modulus: c = sqrt(1e5 / 2500) = 6.3 m/s, impact 0.2 m/s
        (
            "soft",
            &[("E", "1e5"), ("v", "0.1")],
            "RESULT drift 5.34525028306199e-06 dp 0 steps 230",
            1e-4,
        ),
        // steel: E 2.1e11, density 7800
        (
            "steel",
            &[("E", "2.1e11"), ("rho", "7800")],
            "RESULT drift 1.15485675244997e-07 dp 0 steps 1730",
            1e-5,
        ),
        // radius ratio 10:1 (the time step from the small sphere's Rayleigh time)
        (
            "ratio",
            &[("R1", "0.005"), ("R2", "0.0005")],
            "RESULT drift -1.15506980646884e-08 dp 0 steps 245",
            1e-5,
        ),
        // impact at 20 % of the sound speed: c = sqrt(5e6 / 2500) = 44.7 m/s, 2 v = 8.94 m/s;
        // the overlap passes half the radius (the guard warns; the run goes on)
        (
            "fast",
            &[("v", "4.47")],
            "RESULT drift -1.23560716280835e-05 dp 0 steps 151",
            1e-4,
        ),
        // dt 1e-10 s: 178 405 steps through a steel contact of 3.6e-6 s
        (
            "tiny_dt",
            &[
                ("E", "2.1e11"),
                ("rho", "7800"),
                ("R1", "0.0005"),
                ("R2", "0.0005"),
                ("dt", "1e-10"),
            ],
            "RESULT drift 2.07045491862345e-11 dp 0 steps 178405",
            1e-8,
        ),
    ];
    for (name, vars, liggghts, bound) in cases {
        let (code, stdout, stderr, dir) = run(name, PAIR, vars);
        assert_eq!(code, Some(0), "{name}: {stdout}{stderr}");
        let line = stdout
            .lines()
            .find(|l| l.starts_with("RESULT"))
            .unwrap_or_else(|| panic!("{name}: {stdout}"));
        assert_eq!(line, liggghts, "{name}");
        let words: Vec<&str> = line.split_whitespace().collect();
        let drift: f64 = words[2].parse().unwrap();
        let dp: f64 = words[4].parse().unwrap();
        assert!(drift.abs() < bound, "{name}: {line}");
        assert!(dp.abs() < 1e-12, "{name}: {line}");
        assert!(scan_dumps(&dir) >= 10, "{name}");
        if name == "fast" {
            assert!(
                stderr.contains("atoms 1 and 2 overlap by 50.2 % of the smaller radius"),
                "{stderr}"
            );
        } else {
            assert!(!stderr.contains("overlap by"), "{name}: {stderr}");
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

/// A sphere leaving through a fixed face is dropped at the next re-neighbouring, as
/// LIGGGHTS drops it (same thermo lines: 2 atoms to step 40, 1 from step 50), and the run
/// goes on with finite output.
#[test]
fn particles_leave_through_fixed_faces() {
    let deck = "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n\
         communicate single vel yes\nunits si\nregion reg block 0 0.1 0 0.1 0 0.1 units box\n\
         create_box 1 reg\nneighbor 0.002 bin\n\
         fix m1 all property/global youngsModulus peratomtype 5e6\n\
         fix m2 all property/global poissonsRatio peratomtype 0.2\n\
         fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\npair_coeff * *\n\
         create_atoms 1 single 0.05 0.05 0.05 units box\n\
         create_atoms 1 single 0.09 0.02 0.03 units box\n\
         set group all diameter 0.004 density 2500\nset atom 2 vx 2.0 vy 0.5\n\
         fix integr all nve/sphere\ntimestep 1e-4\nthermo_style custom step atoms ke\n\
         thermo 10\ndump d all custom 20 leave_*.dump id x y z vx vy vz fx fy fz\nrun 100\n";
    let (code, stdout, stderr, dir) = run("leave", deck, &[]);
    assert_eq!(code, Some(0), "{stdout}{stderr}");
    for (step, atoms, ke) in [(40, 2, "0.00017802358"), (50, 1, "0"), (100, 1, "0")] {
        let want = format!("{step:>8} {atoms:>8} {ke:>14} ");
        assert!(
            stdout.contains(&format!("\n{want}\n")),
            "{want:?}\n{stdout}"
        );
    }
    assert_eq!(scan_dumps(&dir), 6);
    let _ = std::fs::remove_dir_all(&dir);
}
