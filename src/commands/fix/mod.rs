//! Fix styles: one file per style (or small family of styles) and one row per style name in
//! [`STYLES`]. Adding a fix style is writing its file and adding its row.

mod adapt;
mod ave_atom;
pub(crate) mod ave_euler;
mod ave_histo;
mod ave_spatial;
mod ave_time;
mod aveforce;
mod balance;
mod buoyancy;
mod check_timestep;
mod deform;
pub(crate) mod diam_max;
mod distribution;
mod enforce2d;
mod force;
mod freeze;
mod gravity;
mod heat_gran;
mod insert_pack;
mod insert_stream;
mod insertion;
mod lineforce;
mod massflow_mesh;
mod mesh_servo;
mod mesh_surface;
mod momentum;
mod move_atoms;
mod move_mesh;
mod multicontact;
mod multisphere;
mod nve;
mod nve_limit;
mod particle_template;
mod particle_template_multisphere;
mod print;
mod property_atom;
mod property_global;
mod spring;
mod spring_self;
mod store_state;
mod tracer;
mod viscous;
mod wall_gran;

use crate::commands::specs::Spec;
use crate::commands::style_table::{StyleRow, StyleTable};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{Fix, FixKind, FixStyle};

/// What a style's builder is told about the fix being defined.
#[derive(Debug, Clone, Copy)]
pub struct FixDef<'a> {
    /// The fix ID.
    pub id: &'a str,
    /// The group ID as written.
    pub group: &'a str,
    /// The group's bit mask.
    pub bit: u32,
    /// The style name as written.
    pub style: &'a str,
}

/// Builds a module fix style (see [`FixStyle`]) from the `fix` command's arguments.
pub type BuildStyle = fn(&Args, &mut Ctx, &FixDef) -> Result<Box<dyn FixStyle>, CommandError>;

/// One row of the module fix styles: the style's declared signature (its name is the
/// spec's style; `check`, `regolith help` and `compat/SUPPORT.md` read it), whether 2d runs
/// take it, and its builder.
#[derive(Debug, Clone, Copy)]
pub struct FixRow {
    /// The declared signature.
    pub spec: Spec,
    /// The style runs in 2d (`dimension 2`) decks.
    pub planar: bool,
    /// Makes the fix's state from the command's arguments.
    pub build: BuildStyle,
}

impl StyleRow for FixRow {
    fn spec(&self) -> &Spec {
        &self.spec
    }
}

/// The fix styles, written as modules: one file each in this folder, one row here. The
/// `fix` command looks a style up here (rows registered at run time included).
pub static TABLE: StyleTable<FixRow> = StyleTable::new(&[
    FixRow {
        spec: mesh_surface::SPEC,
        planar: false,
        build: mesh_surface::build,
    },
    FixRow {
        spec: mesh_surface::PLANAR,
        planar: false,
        build: mesh_surface::build,
    },
    FixRow {
        spec: mesh_surface::STRESS,
        planar: false,
        build: mesh_surface::build,
    },
    FixRow {
        spec: mesh_surface::SERVO,
        planar: false,
        build: mesh_surface::build,
    },
    FixRow {
        spec: multisphere::SPEC,
        planar: false,
        build: multisphere::build,
    },
    FixRow {
        spec: property_global::SPEC,
        planar: true,
        build: property_global::build,
    },
    FixRow {
        spec: wall_gran::SPEC,
        planar: true,
        build: wall_gran::build,
    },
    FixRow {
        spec: nve::SPHERE,
        planar: true,
        build: nve::sphere,
    },
    FixRow {
        spec: viscous::SPEC,
        planar: true,
        build: viscous::build,
    },
    FixRow {
        spec: freeze::SPEC,
        planar: true,
        build: freeze::build,
    },
    FixRow {
        spec: diam_max::SPEC,
        planar: true,
        build: diam_max::build,
    },
    FixRow {
        spec: enforce2d::SPEC,
        planar: true,
        build: enforce2d::build,
    },
    FixRow {
        spec: nve::NOFORCE,
        planar: false,
        build: nve::noforce,
    },
    FixRow {
        spec: nve::PLAIN,
        planar: false,
        build: nve::plain,
    },
    FixRow {
        spec: nve_limit::SPEC,
        planar: false,
        build: nve_limit::build,
    },
    FixRow {
        spec: lineforce::LINE,
        planar: false,
        build: lineforce::build,
    },
    FixRow {
        spec: lineforce::PLANE,
        planar: false,
        build: lineforce::build,
    },
    FixRow {
        spec: aveforce::SPEC,
        planar: false,
        build: aveforce::build,
    },
    FixRow {
        spec: momentum::SPEC,
        planar: false,
        build: momentum::build,
    },
    FixRow {
        spec: ave_euler::SPEC,
        planar: false,
        build: ave_euler::build,
    },
    FixRow {
        spec: ave_euler::STRESS,
        planar: false,
        build: ave_euler::build,
    },
    FixRow {
        spec: spring::SPEC,
        planar: false,
        build: spring::build,
    },
    FixRow {
        spec: force::SETFORCE,
        planar: true,
        build: force::build,
    },
    FixRow {
        spec: force::ADDFORCE,
        planar: true,
        build: force::build,
    },
    FixRow {
        spec: gravity::SPEC,
        planar: true,
        build: gravity::build,
    },
    FixRow {
        spec: spring_self::SPEC,
        planar: false,
        build: spring_self::build,
    },
    FixRow {
        spec: print::SPEC,
        planar: true,
        build: print::build,
    },
    FixRow {
        spec: buoyancy::SPEC,
        planar: false,
        build: buoyancy::build,
    },
    FixRow {
        spec: adapt::SPEC,
        planar: false,
        build: adapt::build,
    },
    FixRow {
        spec: tracer::SPEC,
        planar: false,
        build: tracer::build,
    },
    FixRow {
        spec: check_timestep::SPEC,
        planar: true,
        build: check_timestep::build,
    },
    FixRow {
        spec: multicontact::SPEC,
        planar: false,
        build: multicontact::build,
    },
    FixRow {
        spec: ave_time::SPEC,
        planar: true,
        build: ave_time::build,
    },
    FixRow {
        spec: move_mesh::SPEC,
        planar: false,
        build: move_mesh::build,
    },
    FixRow {
        spec: move_atoms::SPEC,
        planar: false,
        build: move_atoms::build,
    },
    FixRow {
        spec: property_atom::SPEC,
        planar: false,
        build: property_atom::build,
    },
    FixRow {
        spec: heat_gran::SPEC,
        planar: false,
        build: heat_gran::build,
    },
    FixRow {
        spec: heat_gran::CONDUCTION,
        planar: false,
        build: heat_gran::build,
    },
    FixRow {
        spec: ave_histo::SPEC,
        planar: false,
        build: ave_histo::build,
    },
    FixRow {
        spec: ave_spatial::SPEC,
        planar: false,
        build: ave_spatial::build,
    },
    FixRow {
        spec: store_state::SPEC,
        planar: false,
        build: store_state::build,
    },
    FixRow {
        spec: ave_atom::SPEC,
        planar: false,
        build: ave_atom::build,
    },
    FixRow {
        spec: deform::SPEC,
        planar: false,
        build: deform::build,
    },
    FixRow {
        spec: massflow_mesh::SPEC,
        planar: false,
        build: massflow_mesh::build,
    },
    FixRow {
        spec: particle_template_multisphere::SPEC,
        planar: false,
        build: particle_template_multisphere::build,
    },
    FixRow {
        spec: particle_template::SPEC,
        planar: false,
        build: particle_template::build,
    },
    FixRow {
        spec: distribution::SPEC,
        planar: false,
        build: distribution::build,
    },
    FixRow {
        spec: distribution::MASSBASED,
        planar: false,
        build: distribution::build,
    },
    FixRow {
        spec: distribution::NUMBERBASED,
        planar: false,
        build: distribution::build,
    },
    FixRow {
        spec: insert_pack::SPEC,
        planar: false,
        build: insert_pack::build,
    },
    FixRow {
        spec: insert_pack::RATE_REGION,
        planar: false,
        build: insert_pack::build,
    },
    FixRow {
        spec: insert_stream::SPEC,
        planar: false,
        build: insert_stream::build,
    },
    FixRow {
        spec: balance::SPEC,
        planar: true,
        build: balance::build,
    },
]);

/// The state of a fix of `style` from its row's builder; None when no row runs the style.
fn build_kind(a: &Args, ctx: &mut Ctx, def: &FixDef) -> Option<Result<FixKind, CommandError>> {
    let style = def.style;
    let row = TABLE.row(style)?;
    if ctx.sim.dimension == 2 && !row.planar {
        return Some(Err(
            a.unsupported(2, &format!("fix {style} in a 2d simulation"))
        ));
    }
    Some((row.build)(a, ctx, def).map(FixKind::Style))
}

/// `fix ID GROUP STYLE ...`: checks what every fix shares, has the style's builder make its
/// state, then adds the fix (or replaces the one with its ID).
pub fn define(a: &Args, ctx: &mut Ctx) -> Result<(), CommandError> {
    a.count(3..=usize::MAX, "fix ID GROUP STYLE ...")?;
    let (id, group, style) = (a.word(0)?, a.word(1)?, a.word(2)?);
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Fix command before simulation box is defined"));
    }
    if !id.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
        return Err(a.error(0, "Fix ID must be alphanumeric or underscore characters"));
    }
    let bit = ctx
        .sim
        .group_bit(group)
        .ok_or_else(|| a.error(1, "Could not find fix group ID"))?;
    let definition = FixDef {
        id,
        group,
        bit,
        style,
    };
    let Some(kind) = build_kind(a, ctx, &definition) else {
        return Err(a.unsupported(2, &format!("fix {style}")));
    };
    let kind = kind?;
    let args: Vec<String> = (3..a.len())
        .map(|i| a.word(i).map(str::to_string))
        .collect::<std::result::Result<_, _>>()?;
    let mut fix = Fix {
        id: id.to_string(),
        style: style.to_string(),
        group: bit,
        kind,
        args,
        clock: Default::default(),
    };
    for line in crate::commands::fix_state::restore_fix_state(a, ctx, &mut fix)? {
        ctx.say(&format!("{line}\n"));
    }
    let position = ctx.sim.fixes.iter().position(|f| f.id == id);
    let created = crate::engine::fix_timing::created_with(
        &fix,
        &ctx.sim.fixes[..position.unwrap_or(ctx.sim.fixes.len())],
    );
    match position {
        Some(i) => {
            if ctx.sim.fixes[i].style != style {
                return Err(a.error(2, "Replacing a fix, but new style != old style"));
            }
            ctx.sim.fixes[i] = fix;
        }
        None => ctx.sim.fixes.push(fix),
    }
    ctx.sim.modify_list.define(id, style, &created);
    Ok(())
}

pub(crate) use deform::check_variables as check_deform_variables;
pub(crate) use mesh_servo::check_variables as check_servo_variables;

/// The compute a `c_ID` input of fix `style` names (word `i`), or LIGGGHTS's error.
pub(crate) fn input_compute<'c>(
    a: &Args,
    ctx: &'c Ctx,
    i: usize,
    id: &str,
    style: &str,
) -> Result<&'c crate::engine::computes::Compute, CommandError> {
    ctx.sim
        .computes
        .iter()
        .find(|c| c.id == id)
        .ok_or_else(|| a.error(i, format!("Compute ID for fix {style} does not exist")))
}

/// Check that the `v_name` input of fix `style` (word `i`) is an atom-style variable, with
/// LIGGGHTS's errors.
pub(crate) fn input_atom_variable(
    a: &Args,
    ctx: &Ctx,
    i: usize,
    name: &str,
    style: &str,
) -> Result<(), CommandError> {
    match ctx.vars.get(name).map(|v| v.style) {
        Some(crate::lang::variables::Style::Atom) => Ok(()),
        Some(_) => Err(a.error(
            i,
            format!("Fix {style} variable is not atom-style variable"),
        )),
        None => Err(a.error(i, format!("Variable name for fix {style} does not exist"))),
    }
}

/// A `v_name` argument of a fix: equal- or atom-style, its style read as LIGGGHTS reads it.
fn variable_value(
    a: &Args,
    ctx: &Ctx,
    at: usize,
    name: &str,
    style: &str,
) -> Result<crate::engine::fixes::ForceValue, CommandError> {
    use crate::engine::fixes::ForceValue;
    use crate::lang::variables::Style;
    match ctx.vars.get(name).map(|v| v.style) {
        Some(Style::Equal) => Ok(ForceValue::Equal(name.into())),
        Some(Style::Atom) => Ok(ForceValue::Atom(name.into())),
        Some(_) => Err(a.error(
            at,
            format!("Variable {name} for fix {style} is invalid style"),
        )),
        None => Err(a.error(at, format!("Variable name for fix {style} does not exist"))),
    }
}

/// Argument `i` as a seed of LIGGGHTS's Park random generator (positive, within an int),
/// read as LIGGGHTS reads it, with C's `atol` (`32452843.0` is 32452843, `abc` is 0).
fn seed_arg(a: &Args, ctx: &Ctx, i: usize) -> Result<i32, CommandError> {
    let seed = crate::util::numbers::atol(a.word(i)?);
    if !ctx.sim.seed_tolerant {
        crate::util::random::check_seed(seed).map_err(|m| a.error(i, &m))?;
    }
    if seed <= 0 || seed > i32::MAX as i64 {
        return Err(a.error(i, "Invalid seed for Park random # generator"));
    }
    Ok(seed as i32)
}

#[cfg(test)]
mod toy;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::commands::{CommandLine, Engine};
    use crate::error::Location;
    use crate::io::output::Output;
    use crate::lang::system::{Mode, System};
    use crate::lang::variables::Variables;

    #[test]
    fn every_declared_fix_style_has_a_row_and_every_row_a_declaration() {
        let mut rows: Vec<&str> = TABLE.modules().iter().map(StyleRow::name).collect();
        rows.sort();
        let mut declared = crate::commands::specs::styles("fix");
        declared.sort();
        assert_eq!(rows, declared);
    }

    fn line(text: &str) -> CommandLine {
        CommandLine {
            words: crate::lang::line::split_words(text).expect("words"),
            text: text.to_string(),
            location: Location {
                file: "in.toy".into(),
                line: 1,
            },
        }
    }

    struct Deck {
        engine: Engine,
        sys: System,
        vars: Variables,
        out: Output,
    }

    impl Deck {
        fn run(&mut self, text: &str) {
            let (sys, vars, out) = (&mut self.sys, &mut self.vars, &mut self.out);
            if let Err(d) = self.engine.execute(&line(text), sys, vars, out) {
                panic!("{text}: {}", d.render());
            }
        }
    }

    /// One file ([`toy`]) and one row: a style the table lacked is defined and acts in a run.
    #[test]
    fn a_toy_style_from_one_file_runs() {
        let mut deck = Deck {
            engine: Engine::new(),
            sys: System::new(Mode::Run),
            vars: Variables::default(),
            out: Output::silent(),
        };
        for text in [
            "atom_style granular",
            "boundary f f f",
            "units si",
            "region reg block 0 0.1 0 0.1 0 0.1 units box",
            "create_box 1 reg",
            "neighbor 0.002 bin",
            "newton off",
            "communicate single vel yes",
            "fix m1 all property/global youngsModulus peratomtype 5e6",
            "fix m2 all property/global poissonsRatio peratomtype 0.2",
            "fix m3 all property/global coefficientRestitution peratomtypepair 1 0.5",
            "fix m4 all property/global coefficientFriction peratomtypepair 1 0.5",
            "pair_style gran model hertz tangential history",
            "pair_coeff * *",
            "create_atoms 1 single 0.05 0.05 0.05 units box",
            "set group all diameter 0.004 density 2500",
        ] {
            deck.run(text);
        }
        let toy_line = line("fix push all toy/push 1e-6");
        let Deck {
            engine,
            sys,
            vars,
            out,
        } = &mut deck;
        // not a style of the table the `fix` command reads
        assert!(engine.execute(&toy_line, sys, vars, out).is_err());
        TABLE.register(FixRow {
            spec: toy::SPEC,
            planar: false,
            build: toy::build,
        });
        for text in [
            "fix push all toy/push 1e-6",
            "fix integr all nve/sphere",
            "timestep 1e-4",
            "run 10",
        ] {
            deck.run(text);
        }
        let v = deck.engine.sim.particles.v[0];
        assert!(v[0] > 0.0 && v[1] == 0.0 && v[2] == 0.0, "{v:?}");
    }
}
