//! Commands that drive and observe the run: fixes regolith integrates, thermo, dumps, `run`.

use crate::commands::registry::Handler;
use crate::commands::CommandError;
use crate::commands::{Args, Ctx};
use crate::engine::error::EngineError;
use crate::engine::fixes::FixKind;
use crate::lang::system::Mode;

mod compute;
mod dumps;

use compute::*;
use dumps::undump;
pub(super) use dumps::{dump, dump_modify};

type Result = std::result::Result<(), CommandError>;

/// The commands that drive and observe the run, and their handlers.
pub const COMMANDS: &[(&str, Handler)] = &[
    ("fix", fix),
    ("unfix", unfix),
    ("thermo", thermo),
    ("thermo_style", thermo_style),
    ("thermo_modify", thermo_modify),
    ("dump", dump),
    ("dump_modify", dump_modify),
    ("undump", undump),
    ("run", run),
    ("compute", compute),
    ("uncompute", uncompute),
    ("pair_style", pair_style),
    ("pair_coeff", pair_coeff),
    ("pair_modify", pair_modify),
    ("soft_particles", |a, ctx| {
        soft_hard("soft_particles", a, ctx)
    }),
    ("hard_particles", |a, ctx| {
        soft_hard("hard_particles", a, ctx)
    }),
    ("write_dump", super::write_dump::write_dump),
    ("thermo_log", super::logs::thermo_log),
    ("modify_timing", super::logs::modify_timing),
];

/// `fix ID GROUP STYLE ...`: the style's own file builds the fix (see [`super::fix`]).
fn fix(a: &Args, ctx: &mut Ctx) -> Result {
    super::fix::define(a, ctx)
}

fn unfix(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "unfix ID")?;
    let id = a.word(0)?;
    if ctx
        .sim
        .computes
        .iter()
        .any(|c| c.style().reads_wall() == Some(id))
    {
        return Err(a.error(0, format!("Fix wall/gran (id {id}): need to uncompute the active compute wall/gran/local before unfixing the wall")));
    }
    let movers = |mesh: &str| -> Vec<usize> {
        (0..ctx.sim.fixes.len())
            .filter(|&k| {
                ctx.sim.fixes[k]
                    .kind
                    .mover()
                    .is_some_and(|m| m.mesh == mesh)
            })
            .collect()
    };
    if let Some(k) = ctx.sim.fixes.iter().position(|f| f.id == id) {
        match &ctx.sim.fixes[k].kind {
            kind if kind.style_as::<crate::engine::clumps::Clumps>().is_some() => {
                return Err(a.error(0, format!("Fix multisphere (id {id}): this fix may not be unfixed as it holds all the internal data for multi-spheres")));
            }
            kind if kind.mover().is_some() => {
                let mesh = kind.mover().map_or(String::new(), |mv| mv.mesh.clone());
                let on_mesh = movers(&mesh);
                if on_mesh.len() > 1 && on_mesh[0] == k {
                    return Err(a.error(0, "Illegal deletion of a fix move/mesh. There is another fix move/mesh command active on the same mesh. Superposed fix move/mesh commands must be unfixed in reverse order of creation"));
                }
                // the mesh stays where it is, at rest
                if let Some(m) = crate::engine::fixes::mesh_named_mut(&mut ctx.sim.fixes, &mesh) {
                    if let Some(v) = &mut m.node_v {
                        v.iter_mut().for_each(|t| *t = [[0.0; 3]; 3]);
                    }
                }
            }
            kind if kind.mesh().is_some() => {
                if let Some(&m) = movers(id).first() {
                    return Err(a.error(0, format!("Fix mesh/surface (id {id}): illegal unfix command, may not unfix a moving mesh while a fix move is applied to it. Unfix the fix move/mesh first (id: {})", ctx.sim.fixes[m].id)));
                }
            }
            _ => {}
        }
    }
    remove_by_id(
        &mut ctx.sim.fixes,
        |f| &f.id,
        a,
        "Could not find fix ID to delete",
    )?;
    ctx.sim.modify_list.remove(id);
    Ok(())
}

fn thermo(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "thermo N")?;
    let n = a.int(0)?;
    if n < 0 {
        return Err(a.error(0, "Illegal thermo command"));
    }
    ctx.sim.thermo.every = n;
    Ok(())
}

fn thermo_style(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=usize::MAX, "thermo_style one|custom KEYWORDS...")?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Thermo_style command before simulation box is defined"));
    }
    if ctx.sim.thermo.modified {
        ctx.say("WARNING: New thermo_style command, previous thermo_modify settings will be lost (./src/output.cpp:725)\n");
        ctx.sim.thermo.modified = false;
    }
    let words: Vec<&str> = match a.word(0)? {
        "one" => vec!["step", "atoms", "ke", "cpu"],
        "custom" => (1..a.len())
            .map(|i| a.word(i))
            .collect::<std::result::Result<_, _>>()?,
        "multi" => vec!["step", "atoms", "ke", "cpu"],
        _ => return Err(a.keyword_error(0, &["one", "custom", "multi"])),
    };
    if a.word(0)? != "custom" && a.len() > 1 {
        return Err(a.error(1, "Illegal thermo_style command"));
    }
    ctx.sim.thermo.custom = a.word(0)? == "custom";
    ctx.sim.thermo.set_style(&words).map_err(|e| {
        let m = e.to_string();
        let at = words
            .iter()
            .position(|w| m.contains(w))
            .map_or(0, |k| k + 1);
        match e {
            EngineError::Unsupported(what) => a.unsupported(at, &what),
            other => a.error(at, other.to_string()),
        }
    })?;
    if a.word(0)? == "custom" {
        check_thermo_references(a, ctx)?;
    }
    // LIGGGHTS: a new thermo_style resets thermo_modify settings
    let t = &mut ctx.sim.thermo;
    t.multi = a.word(0)? == "multi";
    t.int_format = None;
    t.float_format = None;
    t.column_formats = vec![None; t.fields.len()];
    ctx.sim.thermo.norm = false;
    ctx.sim.lost_ignore = true;
    Ok(())
}

/// LIGGGHTS's checks of `thermo_style custom`'s `c_ID`, `f_ID` and `v_name` fields when the
/// command is read: the compute, fix or equal-style variable must exist by then, and a fix
/// without global values (walls, motion, templates) cannot be printed.
fn check_thermo_references(a: &Args, ctx: &Ctx) -> Result {
    for k in 1..a.len() {
        let word = a.word(k)?;
        let Some(body) = word
            .strip_prefix("c_")
            .or_else(|| word.strip_prefix("f_"))
            .or_else(|| word.strip_prefix("v_"))
        else {
            continue;
        };
        let (id, indexed) = match body.split_once('[') {
            Some((id, _)) => (id, true),
            None => (body, false),
        };
        match &word[..1] {
            "c" => {
                let own = crate::commands::system_init::LIGGGHTS_OWN.contains(&id);
                if !ctx.sim.computes.iter().any(|c| c.id == id) && !own {
                    return Err(a.error(k, "Could not find thermo custom compute ID"));
                }
            }
            "f" => {
                let fix = ctx.sim.fixes.iter().find(|f| f.id == id);
                let Some(fix) = fix else {
                    return Err(a.error(k, "Could not find thermo custom fix ID"));
                };
                let silent = match &fix.kind {
                    FixKind::Style(s) => s.refuses_thermo(),
                    _ => false,
                };
                if silent {
                    let what = if indexed { "vector" } else { "scalar" };
                    return Err(a.error(k, format!("Thermo fix does not compute {what}")));
                }
            }
            _ => match ctx.vars.get(id) {
                None => return Err(a.error(k, "Could not find thermo custom variable name")),
                Some(v) if v.style != crate::lang::variables::Style::Equal => {
                    return Err(a.error(k, "Thermo custom variable is not equal-style variable"));
                }
                Some(_) if indexed => {
                    return Err(a.error(k, "Thermo custom variable cannot be indexed"));
                }
                Some(_) => {}
            },
        }
    }
    Ok(())
}

fn thermo_modify(a: &Args, ctx: &mut Ctx) -> Result {
    ctx.sim.thermo.modified = true;
    let mut i = 0;
    while i < a.len() {
        match a.word(i)? {
            "norm" => ctx.sim.thermo.norm = a.word_in(i + 1, &["yes", "no"])? == "yes",
            "lost" => {
                ctx.sim.lost_ignore = a.word_in(i + 1, &["ignore", "warn", "error"])? != "error"
            }
            "flush" => {
                a.word_in(i + 1, &["yes", "no"])?;
            }
            "line" => ctx.sim.thermo.multi = a.word_in(i + 1, &["one", "multi"])? == "multi",
            "format" => {
                let which = a.word(i + 1)?;
                let spec = a.word(i + 2)?.to_string();
                let probe = if which == "int" { 1.0 } else { 0.5 };
                crate::util::format::with_spec(&spec, probe)
                    .map_err(|m| a.error(i + 2, format!("thermo_modify format: {m}")))?;
                let t = &mut ctx.sim.thermo;
                match which {
                    "int" => {
                        if !spec.contains('d') {
                            return Err(a.error(
                                i + 2,
                                "Thermo_modify int format does not contain d character",
                            ));
                        }
                        t.int_format = Some(spec)
                    }
                    "float" => t.float_format = Some(spec),
                    n => {
                        let k = n.parse::<i64>().unwrap_or(0) - 1;
                        if k < 0 || k as usize >= t.fields.len() {
                            return Err(a.error(i + 1, "Illegal thermo_modify command"));
                        }
                        t.column_formats.resize(t.fields.len(), None);
                        t.column_formats[k as usize] = Some(spec);
                    }
                }
                i += 1;
            }
            other => return Err(a.unsupported(i, &format!("thermo_modify {other}"))),
        }
        i += 2;
    }
    Ok(())
}

/// The keywords of a `run` command: `upto`, `start`, `stop` and `pre` (`post` is checked and
/// takes no effect).
struct RunOptions {
    upto: bool,
    start: Option<i64>,
    stop: Option<i64>,
    pre: bool,
}

/// `run N [upto] [start N] [stop N] [pre yes|no] [post yes|no]`: the run's length and
/// bounds checked as LIGGGHTS checks them, then a dry run (check mode) or the run itself.
fn run(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(
        1..=usize::MAX,
        "run N [upto] [start N] [stop N] [pre yes|no] [post yes|no] [every M c1 c2 ...]",
    )?;
    let n = a.int(0)?;
    let options = run_options(a)?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Run command before simulation box is defined"));
    }
    let nsteps = run_steps(a, ctx, n, &options)?;
    super::system_init::system_init(a, ctx, None)?;
    super::fix::check_deform_variables(ctx).map_err(|e| a.engine_error(0, e))?;
    super::fix::check_servo_variables(ctx).map_err(|e| a.engine_error(0, e))?;
    crate::engine::temperature::setup_counts(ctx.sim);
    if ctx.sys.mode == Mode::Check {
        return dry_run(a, ctx, nsteps, &options);
    }
    ctx.sim.ramp_bounds = (options.start, options.stop);
    announce_meshes(a, ctx)?;
    let out = &mut *ctx.out;
    let mut sink = |s: &str| out.engine_text(s);
    let mut vars = crate::lang::scope::RunVariables::new(&mut *ctx.vars, &mut *ctx.sys);
    ctx.sim
        .run_with_setup(nsteps, options.pre, &mut sink, &mut vars)
        .map_err(|e| a.engine_error(0, e))
}

/// The keywords of a `run` command after N.
fn run_options(a: &Args) -> std::result::Result<RunOptions, CommandError> {
    let mut o = RunOptions {
        upto: false,
        start: None,
        stop: None,
        pre: true,
    };
    let mut i = 1;
    while i < a.len() {
        match a.word(i)? {
            "upto" => {
                o.upto = true;
                i += 1;
            }
            "start" => {
                o.start = Some(a.int(i + 1)?);
                i += 2;
            }
            "stop" => {
                o.stop = Some(a.int(i + 1)?);
                i += 2;
            }
            "post" => {
                // post no only shortens LIGGGHTS's timing summary, which regolith keeps short
                a.word_in(i + 1, &["yes", "no"])?;
                i += 2;
            }
            "pre" => {
                o.pre = a.word_in(i + 1, &["yes", "no"])? == "yes";
                i += 2;
            }
            // the interpreter splits `every` runs into chunks before they get here
            "every" => return Err(a.error(i, "Illegal run command")),
            _ => return Err(a.keyword_error(i, &["upto", "start", "stop", "pre", "post", "every"])),
        }
    }
    Ok(o)
}

/// The number of steps of `run N` (`upto`: up to step N), with LIGGGHTS's checks of the
/// step count and of the `start`/`stop` bounds.
fn run_steps(
    a: &Args,
    ctx: &Ctx,
    n: i64,
    o: &RunOptions,
) -> std::result::Result<i64, CommandError> {
    let nsteps = if o.upto {
        let delta = n - ctx.sim.step;
        if delta < 0 {
            return Err(a.error(0, "Invalid run command upto value"));
        }
        delta
    } else {
        if n < 0 {
            return Err(a.error(0, "Invalid run command N value"));
        }
        n
    };
    if ctx
        .sim
        .step
        .checked_add(nsteps)
        .is_none_or(|last| last >= 9.2e18 as i64)
    {
        return Err(a.error(0, "Too many timesteps"));
    }
    if o.start.is_some_and(|s| s < 0 || s > ctx.sim.step) {
        return Err(a.error(0, "Run command start value is after start of run"));
    }
    if o.stop.is_some_and(|s| s < ctx.sim.step + nsteps) {
        return Err(a.error(0, "Run command stop value is before end of run"));
    }
    Ok(nsteps)
}

/// A dry run (check mode) validates the deck but never steps: it makes LIGGGHTS's init
/// checks, keeps the restart files the run would write, and moves the step count to the
/// run's end.
fn dry_run(a: &Args, ctx: &mut Ctx, nsteps: i64, o: &RunOptions) -> Result {
    ctx.sim.check_run().map_err(|e| a.engine_error(0, e))?;
    let first = ctx.sim.step;
    let bounds = (o.start.unwrap_or(first), o.stop.unwrap_or(first + nsteps));
    (ctx.sim.deform_ramp(first, bounds)).map_err(|e| a.engine_error(0, e))?;
    ctx.sim.init_heat().map_err(|m| a.error(0, &m))?;
    ctx.sim.init_liquid().map_err(|m| a.error(0, &m))?;
    if let Some(m) = ctx.sim.new_margin() {
        ctx.sim.margin_notes.push(m);
    }
    if ctx.sim.restart_output.iter().any(Option::is_some) {
        ctx.sim
            .check_restart_size()
            .map_err(|e| a.engine_error(0, e))?;
    }
    keep_periodic_restarts(ctx, nsteps);
    ctx.sim.step += nsteps;
    // what a run leaves behind (contact history) counts as there for later commands
    ctx.sim.has_run = true;
    Ok(())
}

/// LIGGGHTS's line of each mesh's first setup (screen only), after its check that the mesh
/// lies in the box (a mesh that lost triangles to the box stops the run before its lines).
fn announce_meshes(a: &Args, ctx: &mut Ctx) -> Result {
    use crate::state::domain::Boundary;
    let (lo, hi) = (ctx.sim.domain.lo, ctx.sim.domain.hi);
    // LIGGGHTS's setup shrink-wraps the box around every mesh node first (FixMesh's
    // box_extent), so no node lies beyond a shrink-wrapped face when it tests them
    let bounds = ctx.sim.domain.boundary;
    let wraps =
        |d: usize, side: usize| matches!(bounds[d][side], Boundary::Shrink | Boundary::ShrinkMin);
    for k in 0..ctx.sim.fixes.len() {
        ctx.sim
            .check_mesh_in_box(k)
            .map_err(|e| a.engine_error(0, e))?;
        let f = &mut ctx.sim.fixes[k];
        let Some(m) = f.kind.mesh_mut() else {
            continue;
        };
        if m.announced {
            continue;
        }
        m.announced = true;
        // LIGGGHTS's quality check counts skewed triangles (surface_mesh_I.h)
        let (soft, hard) = m.mesh.skewed_counts();
        if soft > 0 {
            ctx.out.screen(&format!(
                "{}\n",
                crate::engine::mesh::soft_limit_line(&f.id, soft)
            ));
            ctx.out.both("WARNING: Fix mesh: Mesh contains highly skewed element, moving mesh (if used) will not parallelize well (./src/surface_mesh_I.h:657)\n");
        }
        if hard > 0 {
            ctx.out.screen(&format!(
                "{}\n",
                crate::engine::mesh::hard_limit_line(&f.id, hard)
            ));
            return Err(a.engine_error(0, crate::engine::mesh::BAD_MESH_HARD_LIMIT.into()));
        }
        // LIGGGHTS's test of every node against the closed box (fix_mesh.cpp)
        let outside = m.mesh.nodes.iter().flatten().any(|p| {
            (0..3).any(|d| !((p[d] >= lo[d] || wraps(d, 0)) && (p[d] <= hi[d] || wraps(d, 1))))
        });
        if outside {
            ctx.out.both("WARNING: Not all nodes of fix mesh inside simulation box, elements will be deleted or wrapped around periodic boundary conditions (./src/fix_mesh.cpp:531)\n");
        }
        ctx.out.screen(&format!(
            "Import and parallelization of mesh {} containing {} triangle(s) successful\n",
            f.id,
            m.mesh.len()
        ));
    }
    Ok(())
}

/// Check mode: the files `restart N ...` would write during a run of `nsteps` from the current
/// step, kept in memory (holding the dry run's state) for a later `read_restart`.
fn keep_periodic_restarts(ctx: &mut Ctx, nsteps: i64) {
    use crate::lang::system::{KeptFile, KeptSeries};
    let (first, last) = (ctx.sim.step, ctx.sim.step + nsteps);
    let mut bytes: Option<std::rc::Rc<Vec<u8>>> = None;
    for k in 0..ctx.sim.restart_output.len() {
        let Some(out) = ctx.sim.restart_output[k].clone() else {
            continue;
        };
        // multiples of the interval after the first step, up to the last
        let from = first.div_euclid(out.every) + 1;
        let to = last.div_euclid(out.every);
        if to < from {
            continue;
        }
        let contents = bytes
            .get_or_insert_with(|| {
                let partners = ctx.sim.contact_partners();
                std::rc::Rc::new(ctx.sim.to_restart(&partners).to_bytes())
            })
            .clone();
        let writes = to - from + 1;
        if out.files.len() == 1 {
            ctx.sys.keep_series(KeptSeries {
                template: out.files[0].clone(),
                every: out.every,
                after: first,
                upto: last,
                bytes: contents,
            });
        } else {
            // two names in turn: each holds its last write
            for i in (writes - 2).max(0)..writes {
                let name = &out.files[(out.toggle + i as usize) % 2];
                let file = KeptFile {
                    bytes: contents.clone(),
                    step: Some((from + i) * out.every),
                };
                ctx.sys.keep_file(std::path::Path::new(name), file);
            }
        }
        if let Some(o) = ctx.sim.restart_output[k].as_mut() {
            o.toggle = (o.toggle + writes as usize) % 2;
            o.last = Some(to * out.every);
        }
    }
}

/// Parse `model M tangential T ... [option on|off ...]` starting at argument `start` in
/// LIGGGHTS's fixed keyword order; returns the selection and the index after the on/off
/// settings. Without a `tangential` keyword there is no tangential force (LIGGGHTS's
/// default `tangential off`, for pair styles and walls alike).
#[allow(clippy::type_complexity)]
pub(super) fn gran_models(
    a: &Args,
    ctx: &mut Ctx,
    start: usize,
    what: &str,
) -> std::result::Result<
    (
        crate::engine::granular::Selection,
        usize,
        Option<CommandError>,
    ),
    CommandError,
> {
    use crate::engine::contact::ModelError;
    use crate::engine::granular::Selection;
    let words: Vec<&str> = (start..a.len())
        .map(|i| a.word(i))
        .collect::<std::result::Result<_, _>>()?;
    let wall = what == "fix wall/gran";
    // a wall's errors name the fix (LIGGGHTS's `fix_error`)
    let named = |m: &dyn std::fmt::Display| {
        if wall {
            format!("Fix wall/gran (id {}): {m}", a.word(0).unwrap_or(""))
        } else {
            m.to_string()
        }
    };
    let (mut sel, used) = Selection::select(&words).map_err(|m| {
        let err = a.error(start, named(&m));
        match words.first() {
            // LIGGGHTS 2.x: `wall/gran kn kt gamman gammat xmu dampflag wallstyle ...`
            Some(w) if what.contains("wall") && w.parse::<f64>().is_ok() => err.with_help(
                "numeric coefficients here are LIGGGHTS 2.x syntax; LIGGGHTS 3.x writes \
                 `fix ID group wall/gran model hertz tangential history primitive type 1 \
                 zplane 0.0` with the material in `fix property/global`",
            ),
            _ => err,
        }
    })?;
    // LIGGGHTS creates the model now, before reading its settings
    if !crate::engine::contact::whitelist::whitelisted(&sel) {
        ctx.say(crate::engine::contact::whitelist::WARNING);
    }
    // the pair style's on/off settings are the rest of its words, as LIGGGHTS reads them
    // (a word out of place is its 'Unknown argument or wrong keyword order'); a wall's
    // come after its own keywords
    let end = if wall { used } else { words.len() };
    let settings: Vec<&str> = words[used..end]
        .iter()
        .map(|w| match *w {
            "yes" => "on",
            "no" => "off",
            w => w,
        })
        .collect();
    let mut pending = None;
    if let Err(e) = sel.apply_settings(&settings) {
        match e {
            // a valid LIGGGHTS setting regolith cannot run: the rest of the style stands
            ModelError::Unsupported(setting) => {
                let at = (start + used..start + end)
                    .find(|&i| setting.starts_with(&format!("'{} ", a.word(i).unwrap_or(""))))
                    .unwrap_or(start + used);
                pending = Some(a.unsupported(
                    at,
                    &format!("{what} setting {}", setting.trim_matches('\'')),
                ));
            }
            ModelError::Invalid(m) => {
                return Err(a.error(start + used, &m).with_help(format!(
                    "{what}: model keywords go in the order model, tangential, cohesion, rolling_friction, surface, then on/off settings"
                )))
            }
        }
    }
    // every model name the engine lacks is valid LIGGGHTS; the pair loop runs liquid
    // bridges around any dry model it runs, the pair and wall loops the multiple-contact
    // model around theirs
    let mut dry = sel.clone();
    if what == "pair_style gran" {
        dry = crate::engine::wet::dry(&sel);
    } else if dry.surface == "multicontact" {
        dry.surface = "default".into();
    }
    crate::engine::contact::AnyContactModel::new(&dry).map_err(|e| match e {
        ModelError::Unsupported(m) | ModelError::Invalid(m) => {
            a.unsupported(start, &format!("{what} {m}"))
        }
    })?;
    Ok((sel, start + end, pending))
}

fn pair_style(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=usize::MAX, "pair_style gran model M tangential T ...")?;
    if a.word(0)? != "gran" {
        return Err(a.unsupported(0, &format!("pair_style {}", a.word(0)?)));
    }
    let (sel, next, pending) = gran_models(a, ctx, 1, "pair_style gran")?;
    if next < a.len() {
        return Err(a.unsupported(next, &format!("pair_style gran option {}", a.word(next)?)));
    }
    ctx.sim.pair_selection = Some(sel);
    // a new pair style: computed until `pair_modify compute no`
    ctx.sim.pair_compute = true;
    ctx.sim.pair_coeff_set = false;
    ctx.sim.pair_coeff_types.clear();
    if let Some(d) = pending {
        // the style is defined (so `pair_coeff` is not refused), only this setting is reported
        return Err(d);
    }
    // the per-type-pair tables this pair style needs must fit the machine (the style stays
    // defined, so that a dry run does not also report every later pair command)
    let n = ctx.sim.ntypes.max(1) as f64;
    crate::engine::checks::allocation(
        n * n,
        std::mem::size_of::<crate::engine::contact::PairCoeffs>(),
        &format!("pair coefficients ({} atom types)", ctx.sim.ntypes),
    )
    .map_err(|m| a.error(0, &m))
}

/// `pair_modify KEYWORD VALUE ...`: LIGGGHTS's keywords of every pair style. Only `compute
/// yes|no` changes a granular run (no: the pair forces are not computed, as LIGGGHTS's
/// integrator skips the pair); mixing, shifting, tables and tail corrections concern
/// potentials with coefficients, which `pair_style gran` has not.
fn pair_modify(a: &Args, ctx: &mut Ctx) -> Result {
    if ctx.sim.pair_selection.is_none() {
        return Err(a.error(0, "Pair_modify command before pair_style is defined"));
    }
    let illegal = |i: usize| {
        a.error(i.min(a.len().saturating_sub(1)), "Illegal pair_modify command")
            .with_help("pair_modify compute yes|no | mix geometric|arithmetic|sixthpower | shift yes|no | tail yes|no | table N | table/disp N | tabinner R | tabinner/disp R")
    };
    if a.is_empty() {
        return Err(illegal(0));
    }
    let mut compute = ctx.sim.pair_compute;
    let mut i = 0;
    while i < a.len() {
        if i + 2 > a.len() {
            return Err(illegal(i));
        }
        let value = a.word(i + 1)?;
        match a.word(i)? {
            "compute" | "shift" | "tail" => {
                let yes = match value {
                    "yes" => true,
                    "no" => false,
                    _ => return Err(illegal(i + 1)),
                };
                if a.word(i)? == "compute" {
                    compute = yes;
                }
            }
            "mix" => {
                if !["geometric", "arithmetic", "sixthpower"].contains(&value) {
                    return Err(illegal(i + 1));
                }
            }
            "table" | "table/disp" => {
                if a.int(i + 1)? > 32 {
                    return Err(a.error(i + 1, "Too many total bits for bitmapped lookup table"));
                }
            }
            "tabinner" | "tabinner/disp" => {
                a.real(i + 1)?;
            }
            _ => return Err(illegal(i)),
        }
        i += 2;
    }
    ctx.sim.pair_compute = compute;
    Ok(())
}

fn pair_coeff(a: &Args, ctx: &mut Ctx) -> Result {
    if ctx.sim.pair_selection.is_none() {
        return Err(a.error(0, "Pair_coeff command before pair_style is defined"));
    }
    // granular pair styles take no coefficients: exactly the two type ranges
    if a.len() != 2 {
        return Err(a.error(0, "Incorrect args for pair coefficients"));
    }
    let ntypes = ctx.sim.ntypes.max(1) as i64;
    let mut range = [(0, 0); 2];
    for (i, r) in range.iter_mut().enumerate() {
        *r = crate::util::numbers::bounds(a.word(i)?, ntypes).map_err(|m| a.error(i, &m))?;
    }
    // as LIGGGHTS's granular pair styles: every I,J with I <= J in the ranges is set
    let ((ilo, ihi), (jlo, jhi)) = (range[0], range[1]);
    let mut count = 0;
    let types = &mut ctx.sim.pair_coeff_types;
    types.resize(ntypes as usize, false);
    for i in ilo..=ihi {
        for j in jlo.max(i)..=jhi {
            if i == j {
                types[(i - 1) as usize] = true;
            }
            count += 1;
        }
    }
    if count == 0 {
        return Err(a.error(0, "Incorrect args for pair coefficients"));
    }
    ctx.sim.pair_coeff_set = types.iter().all(|&t| t);
    Ok(())
}

fn soft_hard(name: &str, a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, &format!("{name} yes|no"))?;
    let on = a.word_in(0, &["yes", "no"])? == "yes";
    if name == "soft_particles" {
        ctx.sim.soft_hard.0 = on;
    } else {
        ctx.sim.soft_hard.1 = on;
    }
    Ok(())
}

/// Remove the item whose ID is the command's first argument, or fail with `missing`.
fn remove_by_id<T>(
    items: &mut Vec<T>,
    id_of: impl Fn(&T) -> &String,
    a: &Args,
    missing: &str,
) -> Result {
    let id = a.word(0)?;
    let k = items
        .iter()
        .position(|t| id_of(t) == id)
        .ok_or_else(|| a.error(0, missing))?;
    items.remove(k);
    Ok(())
}
