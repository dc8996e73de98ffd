//! `dump xyz`: the particle count, a comment line, then `ELEMENT x y z` per particle.

use crate::commands::dump::{no_columns, Built, DumpDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::dump_style::{DumpAt, DumpStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;

/// The declared signature of `xyz`.
pub const SPEC: Spec = style(
    "dump",
    "xyz",
    "dump ID GROUP xyz N FILE",
    &[],
    "type and position every N steps",
);

/// `dump xyz` with the element names of the types (`dump_modify element`; else the type
/// number).
#[derive(Debug, Default)]
pub struct Xyz {
    /// One name per atom type, or none.
    elements: Vec<String>,
}

impl DumpStyle for Xyz {
    fn name(&self) -> &str {
        "xyz"
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        _vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let mut text = Vec::new();
        write(&mut text, at, &self.elements).map_err(|e| e.to_string())?;
        Ok(text)
    }

    fn elements(&mut self) -> Option<&mut Vec<String>> {
        Some(&mut self.elements)
    }

    fn takes_binary(&self) -> Option<bool> {
        Some(false)
    }
}

/// The group's particles as `ELEMENT x y z` lines.
fn write(text: &mut Vec<u8>, at: &DumpAt, elements: &[String]) -> std::io::Result<()> {
    use std::io::Write;
    let (p, group) = (&at.sim.particles, at.dump.group);
    let atoms: Vec<usize> = (0..p.len()).filter(|&i| p.mask[i] & group != 0).collect();
    writeln!(text, "{}\nAtoms. Timestep: {}", atoms.len(), at.sim.step)?;
    for &i in &atoms {
        let t = p.kind[i] as usize;
        let element = elements
            .get(t.wrapping_sub(1))
            .cloned()
            .unwrap_or_else(|| t.to_string());
        let g = crate::util::format::g;
        let x = p.x[i];
        writeln!(text, "{element} {} {} {}", g(x[0]), g(x[1]), g(x[2]))?;
    }
    Ok(())
}

/// `dump ID GROUP xyz N FILE`.
pub fn build(a: &Args, _ctx: &mut Ctx, def: &DumpDef) -> Result<Built, CommandError> {
    a.count(5..=5, "dump ID GROUP xyz N FILE")?;
    if def.file.ends_with(".bin") {
        // LAMMPS's xyz dumps have no binary format
        return Err(a.error(4, "Invalid dump xyz filename"));
    }
    Ok((no_columns(), Box::<Xyz>::default()))
}
