//! The "one file + one row" promise of module fix styles, checked from outside the crate: this
//! file defines a fix style (`toy/drag GAMMA`, a drag force -GAMMA v with its step count as
//! `f_ID`, the group's drag as `f_ID[1..3]`, each particle's drag as dump columns
//! `f_ID[1..3]`, and the count kept in restart files), registers it with one row, and runs
//! decks with it. The velocity must follow velocity Verlet's recurrence for a linear drag
//! and, within the step's error, the analytic decay exp(-GAMMA t / m).

use regolith::commands::fix::{FixDef, FixRow};
use regolith::commands::specs::Spec;
use regolith::commands::{fix, Args, CommandError, Ctx};
use regolith::engine::fixes::{FixStep, FixStyle, PerAtomShape, RestoreError};
use regolith::engine::particles::Particles;
use regolith::io::output::Output;
use regolith::lang::system::Mode;
use regolith::script::interp::{Interpreter, Source};

/// `fix ID GROUP toy/drag GAMMA`: f -= GAMMA v (GAMMA force per velocity).
struct ToyDrag {
    gamma: f64,
    /// post_force calls so far (f_ID), kept across restarts.
    calls: i64,
    /// Each group particle's drag of the last post_force (force), three per particle.
    drag: Vec<[f64; 3]>,
}

impl FixStyle for ToyDrag {
    fn name(&self) -> &str {
        "toy/drag"
    }

    fn post_force(&mut self, p: &mut Particles, at: &FixStep) {
        self.calls += 1;
        self.drag = vec![[0.0; 3]; p.len()];
        for i in (0..p.len()).filter(|&i| p.mask[i] & at.group != 0) {
            for d in 0..3 {
                let f = -self.gamma * p.v[i][d];
                self.drag[i][d] = f;
                p.f[i][d] += f;
            }
        }
    }

    fn value(&self, index: Option<usize>) -> Option<f64> {
        match index {
            None => Some(self.calls as f64),
            Some(d @ 1..=3) => Some(self.drag.iter().map(|f| f[d - 1]).sum()),
            _ => None,
        }
    }

    fn per_atom_shape(&self) -> PerAtomShape {
        PerAtomShape::Array(3)
    }

    fn per_atom(&self, p: &Particles) -> Vec<f64> {
        (0..p.len())
            .flat_map(|i| self.drag.get(i).copied().unwrap_or([0.0; 3]))
            .collect()
    }

    fn restart_state(&self) -> Option<Vec<u8>> {
        Some((self.calls as f64).to_le_bytes().to_vec())
    }

    fn restore_state(&mut self, state: &[u8]) -> Result<(), RestoreError> {
        let bytes: [u8; 8] = state
            .get(..8)
            .and_then(|b| b.try_into().ok())
            .ok_or_else(|| RestoreError::Malformed("toy/drag: short state".into()))?;
        self.calls = f64::from_le_bytes(bytes) as i64;
        Ok(())
    }
}

fn build(a: &Args, _ctx: &mut Ctx, _fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    a.count(4..=4, "fix ID GROUP toy/drag GAMMA")?;
    Ok(Box::new(ToyDrag {
        gamma: a.real(3)?,
        calls: 0,
        drag: Vec::new(),
    }))
}

/// The one row.
fn row() -> FixRow {
    FixRow {
        spec: Spec {
            command: "fix",
            style: Some("toy/drag"),
            usage: "fix ID GROUP toy/drag GAMMA",
            keywords: &[],
            about: "a drag force -GAMMA v (force per velocity)",
        },
        planar: true,
        build,
    }
}

const GAMMA: f64 = 1e-4;
const DT: f64 = 1e-4;
const V0: f64 = 0.1;

/// A single sphere (diameter 4 mm, 2500 kg/m^3) moving at V0 along x, nothing else acting.
fn head() -> String {
    format!(
        "atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
region reg block 0 0.1 0 0.1 0 0.1 units box
create_box 1 reg
neighbor 0.002 bin
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.2
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
create_atoms 1 single 0.05 0.05 0.05 units box
set group all diameter 0.004 density 2500
velocity all set {V0} 0 0 units box
timestep {DT}
fix integr all nve/sphere
fix drag all toy/drag {GAMMA}
"
    )
}

fn run(deck: &str) -> Interpreter {
    let mut interp = Interpreter::new(Mode::Run, Output::silent());
    let source = Source::from_text("in.toy", deck, false);
    if let Err(d) = interp.run_source(source) {
        panic!("{}", d.render());
    }
    interp
}

/// Velocity Verlet from `v0` with f = -GAMMA v from the setup force on: (v after `steps`
/// steps, the drag of the last force evaluation).
fn recurrence(v0: f64, m: f64, steps: usize) -> (f64, f64) {
    let (mut v, mut f) = (v0, -GAMMA * v0);
    let dtf = 0.5 * DT;
    for _ in 0..steps {
        v += dtf / m * f;
        f = -GAMMA * v;
        v += dtf / m * f;
    }
    (v, f)
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-toy-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_style_from_one_file_and_one_row_runs() {
    let dir = scratch("run");
    let (dump, restart) = (dir.join("toy.dump"), dir.join("toy.restart"));
    // not runnable before its row is registered
    let mut interp = Interpreter::new(Mode::Run, Output::silent());
    let early = interp.run_source(Source::from_text("in.toy", &head(), false));
    assert!(early.is_err());
    fix::TABLE.register(row());

    let steps = 1000;
    let deck = format!(
        "{}dump d all custom {steps} {} id vx f_drag[1]
dump_modify d format \"%d %.17g %.17g\"
run {steps}
write_restart {}
",
        head(),
        dump.display(),
        restart.display()
    );
    let interp = run(&deck);
    let p = &interp.engine.sim.particles;
    let m = p.mass[0];
    let (v, f) = recurrence(V0, m, steps);
    let got = p.v[0];
    assert!((got[0] - v).abs() <= 1e-14 * v, "{} vs {v}", got[0]);
    assert_eq!((got[1], got[2]), (0.0, 0.0));
    // within velocity Verlet's error of the continuous decay: with a force from the half-step
    // velocity the scheme is first order, its leading relative error (GAMMA/m)^2 dt t / 2
    let t = steps as f64 * DT;
    let analytic = V0 * (-GAMMA * t / m).exp();
    let leading = 0.5 * (GAMMA / m).powi(2) * DT * t;
    let error = (v / analytic - 1.0).abs();
    assert!((error / leading - 1.0).abs() < 0.01, "{v} vs {analytic}");
    assert!(v < 0.9 * V0, "the drag slowed the sphere: {v}");
    // f_ID (post_force calls: the setup's and one per step) and f_ID[1]
    let sim = &interp.engine.sim;
    assert_eq!(sim.fix_value("drag", None).unwrap(), (steps + 1) as f64);
    let fx = sim.fix_value("drag", Some(1)).unwrap();
    assert!((fx - f).abs() <= 1e-14 * f.abs(), "{fx} vs {f}");
    assert!(sim.fix_value("drag", Some(4)).is_err());
    // the dump's per-atom column
    let text = std::fs::read_to_string(&dump).unwrap();
    let last: Vec<f64> = text
        .lines()
        .last()
        .unwrap()
        .split_whitespace()
        .map(|w| w.parse().unwrap())
        .collect();
    assert_eq!(last[0], 1.0);
    assert_eq!(last[1], got[0]);
    assert_eq!(last[2], fx);

    // the count comes back from the restart file when the fix is defined again
    let deck = format!(
        "atom_style granular
atom_modify map array
communicate single vel yes
read_restart {}
newton off
neighbor 0.002 bin
fix m1 all property/global youngsModulus peratomtype 5e6
fix m2 all property/global poissonsRatio peratomtype 0.2
fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5
fix m4 all property/global coefficientFriction peratomtypepair 1 0.5
pair_style gran model hertz tangential history
pair_coeff * *
timestep {DT}
fix integr all nve/sphere
fix drag all toy/drag {GAMMA}
run 10
",
        restart.display()
    );
    let interp = run(&deck);
    let sim = &interp.engine.sim;
    assert_eq!(
        sim.fix_value("drag", None).unwrap(),
        (steps + 1 + 11) as f64
    );
    let (v, _) = recurrence(got[0], m, 10);
    let after = sim.particles.v[0][0];
    assert!((after - v).abs() <= 1e-14 * v, "{after} vs {v}");
}
