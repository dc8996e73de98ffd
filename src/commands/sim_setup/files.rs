//! `read_data`, `write_data`, `read_restart`, `write_restart` and `restart`.

use super::*;

/// `read_data FILE`: box, atom types, atoms and velocities of a granular data file.
pub(super) fn read_data(a: &Args, ctx: &mut Ctx) -> Result {
    if ctx.sim.dimension == 2 {
        return Err(a.unsupported(0, "read_data in a 2d simulation"));
    }
    a.count(1..=1, "read_data FILE")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Cannot read_data after simulation box is defined"));
    }
    let name = a.word(0)?;
    let text = if name.ends_with(".gz") {
        crate::io::diff::read_text(&ctx.sys.resolve(name).to_string_lossy())
            .map_err(|e| e.to_string())
    } else {
        ctx.sys.read(name).map_err(|e| e.to_string())
    }
    .map_err(|m| a.file_error(0, format!("Cannot open file {name}: {m}")))?;
    let data = crate::io::data::parse(&text, name).map_err(|m| a.error(0, &m))?;
    crate::engine::checks::check_ntypes(data.ntypes as i64)
        .map_err(|m| a.error(0, format!("{name}: {m}")))?;
    let sim = &mut *ctx.sim;
    sim.domain.create(data.lo, data.hi);
    sim.ntypes = data.ntypes;
    for atom in &data.atoms {
        let mut x = atom.x;
        let mut image = atom.image;
        for d in 0..3 {
            let inside = x[d] >= data.lo[d] && x[d] < data.hi[d];
            if !inside && !sim.domain.periodic(d) {
                return Err(a.error(
                    0,
                    format!(
                        "Did not assign all atoms correctly: {name}: atom {} at ({}, {}, {}) lies outside the box",
                        atom.id, x[0], x[1], x[2]
                    ),
                ));
            }
        }
        sim.domain.remap(&mut x, &mut image);
        sim.particles
            .push(atom.id, atom.kind, x, 0.5 * atom.diameter, atom.density);
        let i = sim.particles.len() - 1;
        let p = &mut sim.particles;
        p.image[i] = image;
        p.v[i] = atom.v;
        p.omega[i] = atom.omega;
        if atom.diameter == 0.0 {
            p.mass[i] = atom.density; // a point particle's density column is its mass
        }
    }
    let (lo, hi) = (data.lo, data.hi);
    let grid =
        crate::commands::processors::grid_lines(a, ctx, [0, 1, 2].map(|d| hi[d] - lo[d]), 0)?;
    ctx.say(&format!(
        "Reading data file ...\n  orthogonal box = ({} {} {}) to ({} {} {})\n{grid}  {} atoms\n",
        g(lo[0]),
        g(lo[1]),
        g(lo[2]),
        g(hi[0]),
        g(hi[1]),
        g(hi[2]),
        data.atoms.len()
    ));
    if data.velocities > 0 {
        ctx.say(&format!("  {} velocities\n", data.velocities));
    }
    Ok(())
}

/// `write_data FILE`: the granular data file of the current state, written atomically.
pub(super) fn write_data(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "write_data FILE")?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Write_data command before simulation box is defined"));
    }
    let name = a.word(0)?;
    crate::commands::system_init::system_init(a, ctx, Some("write_data"))?;
    if ctx.sys.mode != Mode::Run {
        return Ok(());
    }
    // as LIGGGHTS: positions wrapped and the box shrink-wrapped before writing
    ctx.sim.pbc_and_box().map_err(|e| a.engine_error(0, e))?;
    let text = crate::io::data::write(
        &ctx.sim.particles,
        &ctx.sim.domain,
        ctx.sim.ntypes,
        ctx.sim.step,
        concat!("regolith ", env!("CARGO_PKG_VERSION")),
    );
    let path = ctx.sys.resolve(name).to_string_lossy().into_owned();
    // on several ranks rank 0 alone writes (every rank holds the whole set between runs)
    let written = if ctx.sim.writes_files() {
        crate::io::write_atomically(&path, text.as_bytes())
            .map_err(|e| format!("Cannot open data file {name}: {e}"))
    } else {
        Ok(())
    };
    ctx.sim
        .agree_on_file(written, name)
        .map_err(|m| a.file_error(0, m))
}

/// `read_restart FILE` (a `*` picks the largest step, a `%` the multi-file form).
pub(super) fn read_restart(a: &Args, ctx: &mut Ctx) -> Result {
    if ctx.sim.dimension == 2 {
        return Err(a.unsupported(0, "read_restart in a 2d simulation"));
    }
    a.count(1..=1, "read_restart FILE")?;
    if ctx.sim.domain.exists {
        return Err(a.error(0, "Cannot read_restart after simulation box is defined"));
    }
    let name = a.word(0)?;
    let mut path = ctx.sys.resolve(name).to_string_lossy().into_owned();
    if path.contains('*') {
        // the largest step on disk, or among the files a dry run's deck wrote before
        let on_disk = crate::io::diff::expand(&path)
            .ok()
            .and_then(|mut v| v.pop());
        let disk_step = on_disk.as_deref().map(step_of_name);
        let kept = ctx.sys.kept_matching(&path).pop();
        path = match (on_disk, kept) {
            (Some(d), Some((k, kept))) => {
                if disk_step.is_some_and(|s| s > k) {
                    d
                } else {
                    kept
                }
            }
            (Some(d), None) => d,
            (None, Some((_, kept))) => kept,
            (None, None) => return Err(a.error(0, "Found no restart file matching pattern")),
        };
    }
    let r = match ctx.sys.kept_binary(std::path::Path::new(&path)) {
        // check mode: a restart this deck wrote earlier (periodic output holds its own step)
        Some(kept) => crate::io::restart::Restart::parse(&kept.bytes, &path, None).map(|mut r| {
            if let Some(step) = kept.step {
                r.set_step(step);
            }
            r
        }),
        None => crate::io::restart::read(&path),
    }
    // the file as the deck names it (not the folder it was resolved against)
    .map_err(|e| a.error(0, e.to_string().replace(&path, name)))?;
    ctx.say("Reading restart file ...\n");
    if let (Some((major, minor)), Mode::Run) = (r.version_numbers(), ctx.sys.mode) {
        // LIGGGHTS prints the version it parsed with printf: on standard output only
        ctx.out.stdout(&format!("version {major} {minor}\n"));
    }
    // as LIGGGHTS's header reading: a file written by another processor count or (for a
    // grid the deck gave) another grid is read all the same, with its warnings
    let (nprocs, user) = (ctx.sim.procs.nprocs, ctx.sim.procs.user);
    if r.int(7).is_some_and(|n| n != nprocs) {
        ctx.say(
            "WARNING: Restart file used different # of processors (./src/read_restart.cpp:574)\n",
        );
    }
    let file_grid = [8, 9, 10].map(|f| r.int(f).unwrap_or(1));
    if user[0] != 0 && file_grid != user {
        ctx.say(
            "WARNING: Restart file used different 3d processor grid (./src/read_restart.cpp:587)\n",
        );
    }
    let pair = ctx.sim.load_restart(&r).map_err(|m| a.error(0, &m))?;
    ctx.sim.restart_in_progress = !r.global_fixes.is_empty() || !r.peratom_fixes.is_empty();
    ctx.sim.extras.restart_peratom_fixes = r.peratom_fixes.len();
    ctx.sim.restart_fixes = r.global_fixes.clone();
    ctx.sim.restart_peratom = r
        .peratom_fixes
        .iter()
        .map(|f| (f.id.clone(), f.style.clone()))
        .collect();
    let (lo, hi) = (ctx.sim.domain.lo, ctx.sim.domain.hi);
    let grid =
        crate::commands::processors::grid_lines(a, ctx, [0, 1, 2].map(|d| hi[d] - lo[d]), 0)?;
    let line = format!(
        "{}{grid}",
        crate::commands::change_box::orthogonal_box_line(lo, hi),
    );
    ctx.say(&line);
    // the pair style stored in the file, as LIGGGHTS recreates it (decks usually repeat it)
    // before it reads the atoms
    if let Some(words) = pair {
        for text in [format!("pair_style {words}"), "pair_coeff * *".to_string()] {
            let words = crate::lang::line::split_words(&text)
                .map_err(|_| a.error(0, "restart: bad stored pair style"))?;
            let cmd = crate::commands::CommandLine {
                words,
                text: text.clone(),
                location: a.cmd.location.clone(),
            };
            let args = Args { cmd: &cmd };
            if let Some(run) = registry::handler(cmd.name()) {
                run(&args, ctx).map_err(|e| CommandError::Reported(e.into_diagnostic(&cmd)))?;
            }
        }
    }
    let atoms = format!("  {} atoms\n", ctx.sim.particles.len());
    ctx.say(&atoms);
    Ok(())
}

/// The step in a restart file's name: its last run of digits (0 if none).
pub(super) fn step_of_name(path: &str) -> i64 {
    let name = path.rsplit('/').next().unwrap_or(path);
    let digits: Vec<char> = name
        .chars()
        .rev()
        .skip_while(|c| !c.is_ascii_digit())
        .take_while(|c| c.is_ascii_digit())
        .collect();
    digits.iter().rev().collect::<String>().parse().unwrap_or(0)
}

/// `write_restart FILE`: the current state, atomically, after wrapping positions and the
/// box as LIGGGHTS does.
pub(super) fn write_restart(a: &Args, ctx: &mut Ctx) -> Result {
    a.count(1..=1, "write_restart FILE")?;
    if !ctx.sim.domain.exists {
        return Err(a.error(0, "Write_restart command before simulation box is defined"));
    }
    let path = ctx.sys.resolve(a.word(0)?).to_string_lossy().into_owned();
    let path = path.replace('*', &ctx.sim.step.to_string());
    crate::commands::system_init::system_init(a, ctx, Some("write_restart"))?;
    ctx.sim
        .check_restart_size()
        .map_err(|e| a.engine_error(0, e))?;
    if ctx.sys.mode != Mode::Run {
        // check mode: keep the file in memory for a later read_restart of the same deck
        let partners = ctx.sim.contact_partners();
        let bytes = ctx.sim.to_restart(&partners).to_bytes();
        ctx.sys.keep_binary(std::path::Path::new(&path), bytes);
        return Ok(());
    }
    // LIGGGHTS's write_restart (not the periodic `restart` output) creates the file's folders
    if let Some(dir) = std::path::Path::new(&path).parent() {
        let _ = std::fs::create_dir_all(dir);
    }
    ctx.sim
        .save_restart(&path)
        .map_err(|e| a.engine_error(0, e))
}

/// `restart 0` | `restart N ROOT` (`*` becomes the step; without one, `.STEP` is
/// appended) | `restart N FILE1 FILE2` (written in turn).
pub(super) fn restart(a: &Args, ctx: &mut Ctx) -> Result {
    use crate::engine::sim::RestartOutput;
    a.count(1..=3, "restart 0 | restart N ROOT | restart N FILE1 FILE2")?;
    if a.word(0)?.starts_with("v_") {
        return Err(a.unsupported(0, "restart with a variable interval"));
    }
    let every = a.int(0)?;
    if every == 0 {
        if a.len() != 1 {
            return Err(a.error(0, "Illegal restart command"));
        }
        ctx.sim.restart_output = [None, None];
        return Ok(());
    }
    if every < 0 || a.len() == 1 {
        return Err(a.error(0, "Illegal restart command"));
    }
    let resolve = |w: &str| ctx.sys.resolve(w).to_string_lossy().into_owned();
    let files = if a.len() == 2 {
        let mut root = resolve(a.word(1)?);
        if !root.contains('*') {
            root.push_str(".*");
        }
        vec![root]
    } else {
        vec![resolve(a.word(1)?), resolve(a.word(2)?)]
    };
    let slot = files.len() - 1;
    ctx.sim.restart_output[slot] = Some(RestartOutput {
        every,
        files,
        toggle: 0,
        last: None,
    });
    Ok(())
}
