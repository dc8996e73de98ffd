//! The "one file + one row" promise of module dump styles, checked from outside the crate:
//! this file defines a dump style (`toy/speeds`: a `STEP N` line, then `ID SPEED` per particle
//! of the group in ID order), registers it with one row, and runs it as decks do: one file
//! per snapshot for a `*` name, one file for the run otherwise, `dump_modify every`, and
//! `dump_modify binary` refused as not supported yet.

use regolith::commands::dump::{no_columns, Built, DumpDef, DumpRow};
use regolith::commands::specs::Spec;
use regolith::commands::{dump, Args, CommandError, Ctx};
use regolith::engine::dump_style::{DumpAt, DumpStyle};
use regolith::engine::error::EngineError;
use regolith::engine::sim::VariableSource;
use regolith::io::output::Output;
use regolith::lang::system::Mode;
use regolith::script::interp::{Interpreter, Source};

/// `dump ID GROUP toy/speeds N FILE`.
#[derive(Debug)]
struct ToySpeeds;

impl DumpStyle for ToySpeeds {
    fn name(&self) -> &str {
        "toy/speeds"
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        _vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let p = &at.sim.particles;
        let mut atoms: Vec<usize> = (0..p.len())
            .filter(|&i| p.mask[i] & at.dump.group != 0)
            .collect();
        atoms.sort_by_key(|&i| p.id[i]);
        let mut text = format!("STEP {}\n", at.sim.step);
        for i in atoms {
            let v = p.v[i];
            let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            text.push_str(&format!("{} {speed:.6}\n", p.id[i]));
        }
        Ok(text.into_bytes())
    }
}

fn build(a: &Args, _ctx: &mut Ctx, _def: &DumpDef) -> Result<Built, CommandError> {
    a.count(5..=5, "dump ID GROUP toy/speeds N FILE")?;
    Ok((no_columns(), Box::new(ToySpeeds)))
}

/// The one row.
fn row() -> DumpRow {
    DumpRow {
        spec: Spec {
            command: "dump",
            style: Some("toy/speeds"),
            usage: "dump ID GROUP toy/speeds N FILE",
            keywords: &[],
            about: "each particle's speed (velocity) in ID order",
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
"
    .to_string()
}

#[test]
fn a_dump_style_from_one_file_and_one_row_writes_its_snapshots() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-dump-toy-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let d = dir.display();
    let dumps = format!(
        "dump each all toy/speeds 5 {d}/speeds.*.txt\ndump one two toy/speeds 5 {d}/two.txt\n"
    );
    let mut interp = Interpreter::new(Mode::Run, Output::silent());
    let early = interp.run_source(Source::from_text("in.toy", &(head() + &dumps), false));
    assert!(early.is_err(), "not defined before its row is registered");
    dump::TABLE.register(row());

    let deck = format!("{}{dumps}dump_modify one every 10\nrun 10\n", head());
    let mut interp = Interpreter::new(Mode::Run, Output::silent());
    if let Err(e) = interp.run_source(Source::from_text("in.toy", &deck, false)) {
        panic!("{}", e.render());
    }
    // no forces act: the speeds are those set, |(0.3, 0.4, 0)| and |(0, 0, -1.2)|
    let read = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap();
    for step in [0, 5, 10] {
        let text = read(&format!("speeds.{step}.txt"));
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], format!("STEP {step}"), "{text}");
        let speeds: Vec<f64> = lines[1..]
            .iter()
            .map(|l| l.split(' ').nth(1).unwrap().parse().unwrap())
            .collect();
        assert_eq!(speeds.len(), 2, "{text}");
        assert!((speeds[0] - 0.5).abs() < 1e-12, "{text}");
        assert!((speeds[1] - 1.2).abs() < 1e-12, "{text}");
    }
    assert!(!dir.join("speeds.1.txt").exists());
    // one file for the run, every 10 steps, the group's particle alone
    assert_eq!(read("two.txt"), "STEP 0\n2 1.200000\nSTEP 10\n2 1.200000\n");

    // style-specific keywords the style does not take are refused, naming the keyword
    let deck = format!("{}{dumps}dump_modify one binary yes\n", head());
    let mut interp = Interpreter::new(Mode::Run, Output::silent());
    let refused = interp
        .run_source(Source::from_text("in.toy", &deck, false))
        .expect_err("binary is not a keyword of the toy style")
        .render();
    assert!(refused.contains("dump_modify binary"), "{refused}");
    let _ = std::fs::remove_dir_all(&dir);
}
