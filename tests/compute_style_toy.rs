//! The "one file + one row" promise of module compute styles, checked from outside the crate:
//! this file defines a compute style (`toy/speed`: each particle's speed as `c_ID` per atom,
//! the group's largest speed as the scalar `c_ID`, the group's momentum as `c_ID[1..3]`),
//! registers it with one row, and reads it through thermo, equal- and atom-style variables
//! and `compute reduce`.

use regolith::commands::compute::{ComputeDef, ComputeRow};
use regolith::commands::specs::Spec;
use regolith::commands::{compute, Args, CommandError, Ctx};
use regolith::engine::computes::{ComputeAt, ComputeStyle};
use regolith::engine::error::EngineError;
use regolith::engine::sim::VariableSource;
use regolith::io::output::Output;
use regolith::lang::system::Mode;
use regolith::script::interp::{Interpreter, Source};

/// `compute ID GROUP toy/speed`.
#[derive(Debug)]
struct ToySpeed;

/// |v| of particle `i` (velocity).
fn speed(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

impl ComputeStyle for ToySpeed {
    fn name(&self) -> &str {
        "toy/speed"
    }

    fn has_scalar(&self) -> bool {
        true
    }

    fn scalar(&self, at: &ComputeAt, _vars: &mut dyn VariableSource) -> Result<f64, EngineError> {
        let p = &at.sim.particles;
        Ok((0..p.len())
            .filter(|&i| at.in_group(i))
            .map(|i| speed(p.v[i]))
            .fold(0.0, f64::max))
    }

    fn vector_len(&self) -> usize {
        3
    }

    fn vector(
        &self,
        at: &ComputeAt,
        index: usize,
        _vars: &mut dyn VariableSource,
    ) -> Result<f64, EngineError> {
        let p = &at.sim.particles;
        Ok((0..p.len())
            .filter(|&i| at.in_group(i))
            .map(|i| p.mass[i] * p.v[i][index - 1])
            .sum())
    }

    fn per_atom_columns(&self) -> usize {
        1
    }

    fn per_atom(
        &self,
        at: &ComputeAt,
        values: &mut [f64],
        _vars: &mut dyn VariableSource,
    ) -> Result<(), EngineError> {
        let p = &at.sim.particles;
        for (i, value) in values.iter_mut().enumerate() {
            if at.in_group(i) {
                *value = speed(p.v[i]);
            }
        }
        Ok(())
    }
}

fn build(
    a: &Args,
    _ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    a.count(3..=3, "compute ID GROUP toy/speed")?;
    Ok(Box::new(ToySpeed))
}

/// The one row.
fn row() -> ComputeRow {
    ComputeRow {
        spec: Spec {
            command: "compute",
            style: Some("toy/speed"),
            usage: "compute ID GROUP toy/speed",
            keywords: &[],
            about: "speed per particle (velocity), the largest, and the momentum",
        },
        build,
    }
}

/// Two spheres far apart, moving freely: (3, 4, 0) and (0, 0, -12) (velocity, /10).
fn head() -> String {
    "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block 0 1 0 1 0 1 units box
create_box 1 reg
neighbor 0.002 bin
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.2
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
create_atoms 1 single 0.2 0.2 0.5 units box
create_atoms 1 single 0.8 0.8 0.5 units box
set group all diameter 0.004 density 2500
set atom 2 diameter 0.008
velocity all set 0.3 0.4 0 units box
group two id 2
velocity two set 0 0 -1.2 units box
timestep 1e-5
fix integr all nve/sphere
compute toy all toy/speed
"
    .to_string()
}

#[test]
fn a_compute_style_from_one_file_and_one_row_gives_its_values() {
    let mut interp = Interpreter::new(Mode::Run, Output::silent());
    let early = interp.run_source(Source::from_text("in.toy", &head(), false));
    assert!(early.is_err(), "not defined before its row is registered");
    compute::TABLE.register(row());

    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-compute-toy-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let log = dir.join("log.toy");
    let deck = format!(
        "log {}
{}compute top all reduce max c_toy
compute sum two reduce sum c_toy
variable s equal c_toy
variable px equal c_toy[1]
variable pz equal c_toy[3]
variable twice atom 2*c_toy
compute twice all reduce sum v_twice
thermo_style custom step c_toy c_toy[2] v_s c_top
thermo 5
run 10
",
        log.display(),
        head()
    );
    let mut interp = Interpreter::new(Mode::Run, Output::silent());
    if let Err(d) = interp.run_source(Source::from_text("in.toy", &deck, false)) {
        panic!("{}", d.render());
    }
    let p = &interp.engine.sim.particles;
    let (m1, m2) = (p.mass[0], p.mass[1]);
    assert!(
        m2 > 7.9 * m1,
        "the second sphere is twice as wide: {m1} {m2}"
    );
    let text = interp
        .substitute("${s} ${px} ${pz} $(c_sum) $(c_twice) $(c_top)", false)
        .expect("the variables evaluate");
    let got: Vec<f64> = text
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * b.abs().max(1e-30);
    // no forces act: the velocities are those set
    assert!(close(got[0], 1.2), "largest speed {}", got[0]);
    assert!(
        close(got[1], 0.3 * m1),
        "x momentum {} vs {}",
        got[1],
        0.3 * m1
    );
    assert!(close(got[2], -1.2 * m2), "z momentum {}", got[2]);
    assert!(close(got[3], 1.2), "per-atom speed of group two {}", got[3]);
    assert!(close(got[4], 2.0 * (0.5 + 1.2)), "atom variable {}", got[4]);
    assert!(close(got[5], 1.2), "reduce max {}", got[5]);

    // the thermo columns: step, c_toy, c_toy[2], v_s, c_top
    let log = std::fs::read_to_string(&log).unwrap();
    let rows: Vec<Vec<f64>> = log
        .lines()
        .map(|l| {
            l.split_whitespace()
                .map(str::parse)
                .collect::<Result<Vec<f64>, _>>()
        })
        .filter_map(Result::ok)
        .filter(|r| r.len() == 5)
        .collect();
    assert_eq!(
        rows.iter().map(|r| r[0]).collect::<Vec<_>>(),
        vec![0.0, 5.0, 10.0],
        "{log}"
    );
    for r in &rows {
        assert!((r[1] - 1.2).abs() < 1e-7, "{log}");
        assert!((r[2] - 0.4 * m1).abs() < 1e-7 * 0.4 * m1, "{log}");
        assert!(
            (r[3] - 1.2).abs() < 1e-7 && (r[4] - 1.2).abs() < 1e-7,
            "{log}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
