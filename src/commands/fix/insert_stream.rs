//! `fix insert/stream`: particles inserted through a mesh face.

use super::seed_arg;
use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP insert/stream seed S distributiontemplate D nparticles N particlerate R
/// insertion_face MESH extrude_length L|insert_every N vel ... [overlapcheck ...]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let id = fix.id;
    ctx.sim.inserts_atoms = true;
    use crate::engine::insert::Velocity;
    a.count(5..=usize::MAX, "fix ID GROUP insert/stream seed S distributiontemplate D nparticles N particlerate R insertion_face MESH extrude_length L ...")?;
    let (mut seed, mut dist, mut face, mut extrude, mut every) = (None, None, None, None, None);
    let mut duration = None;
    let (mut total, mut rate) = (None, None);
    let (mut overlap, mut maxattempt, mut ntry_mc, mut verbose) = (true, 50i64, 100000i64, true);
    let mut velocity = Velocity::Constant([0.0; 3]);
    let mut omega = [0.0; 3];
    let mut random_orientation = false;
    let mut start = ctx.sim.step + 1;
    let (mut all_in, mut all_in_at, mut face_id) = (false, 0, String::new());
    let mut i = 3;
    let yes = |a: &Args, k: usize| a.word_in(k, &["yes", "no"]).map(|w| w == "yes");
    // LIGGGHTS reads the general insertion keywords first, then insert/stream's own; a
    // general one after those is an error there
    let mut own_part = false;
    while i < a.len() {
        let w = a.word(i)?;
        let own = matches!(
            w,
            "insertion_face"
                | "extrude_length"
                | "duration"
                | "duration_time"
                | "parallel"
                | "ntry_mc"
                | "save_template"
        );
        if own {
            own_part = true;
        } else if own_part {
            return Err(a.error(
                i,
                format!("Fix insert/stream (id {id}): unknown keyword or wrong keyword order"),
            ));
        }
        match w {
            "seed" => {
                seed = Some(seed_arg(a, ctx, i + 1)?);
                i += 2;
            }
            "distributiontemplate" => {
                let d = a.word(i + 1)?;
                if !ctx
                    .sim
                    .fixes
                    .iter()
                    .any(|f| f.id == d && matches!(f.kind, FixKind::Distribution(_)))
                {
                    return Err(a.error(i + 1, "Fix insert: distributiontemplate must be a fix particledistribution/discrete"));
                }
                dist = Some(d.to_string());
                i += 2;
            }
            "insertion_face" => {
                let m = a.word(i + 1)?;
                let tri = ctx.sim.fixes.iter().find_map(|f| match &f.kind {
                    FixKind::Mesh(mesh) if f.id == m => {
                        Some((mesh.triangles().to_vec(), mesh.planar))
                    }
                    _ => None,
                });
                face_id = m.to_string();
                face = Some(tri.ok_or_else(|| {
                    a.error(
                        i + 1,
                        "Fix insert/stream: could not find the insertion_face mesh",
                    )
                })?);
                i += 2;
            }
            "extrude_length" => {
                extrude = Some(a.real(i + 1)?);
                i += 2;
            }
            w @ ("insert_every" | "every" | "insert_every_time") => {
                every = Some(if w == "insert_every_time" {
                    (a.real(i + 1)? / ctx.sim.dt) as i32 as i64
                } else {
                    a.int(i + 1)?
                });
                i += 2;
            }
            w @ ("duration" | "duration_time") => {
                let d = if w == "duration_time" {
                    (a.real(i + 1)? / ctx.sim.dt) as i32 as i64
                } else {
                    a.int(i + 1)?
                };
                if d < 1 {
                    return Err(a.error(
                        i + 1,
                        format!("Fix insert/stream (id {id}): 'duration' can not be < 1"),
                    ));
                }
                duration = Some(d);
                i += 2;
            }
            w @ ("nparticles" | "mass") => {
                if a.word(i + 1)? == "INF" {
                    return Err(a.unsupported(i + 1, &format!("fix insert/stream {w} INF")));
                }
                if total.is_some() {
                    return Err(a.error(
                        i,
                        "Fix insert/stream: must not define both 'nparticles' and 'mass'",
                    ));
                }
                total = Some(if w == "mass" {
                    Err(a.real(i + 1)?)
                } else {
                    Ok(a.int32(i + 1)?)
                });
                i += 2;
            }
            w @ ("particlerate" | "massrate") => {
                if rate.is_some() {
                    return Err(a.error(
                        i,
                        "Fix insert/stream: must not define both 'particlerate' and 'massrate'",
                    ));
                }
                let r = a.real(i + 1)?;
                rate = Some(if w == "massrate" { Err(r) } else { Ok(r) });
                i += 2;
            }
            "start" => {
                start = a.int(i + 1)?;
                i += 2;
            }
            "overlapcheck" => {
                overlap = yes(a, i + 1)?;
                i += 2;
            }
            "verbose" => {
                verbose = yes(a, i + 1)?;
                i += 2;
            }
            "maxattempt" => {
                maxattempt = a.int32(i + 1)?;
                i += 2;
            }
            "ntry_mc" => {
                ntry_mc = a.int32(i + 1)?;
                if ntry_mc < 1000 {
                    return Err(a.error(
                        i + 1,
                        format!("Fix insert/stream (id {id}): ntry_mc must be > 1000"),
                    ));
                }
                i += 2;
            }
            "vel" => {
                let used;
                (velocity, used) = super::insertion_velocity(a, i)?;
                i += used;
            }
            "omega" => {
                a.word_in(i + 1, &["constant"])?;
                omega = [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?];
                i += 5;
            }
            "all_in" => {
                all_in = yes(a, i + 1)?;
                all_in_at = i;
                i += 2;
            }
            "orientation" => {
                random_orientation = super::orientation_arg(a, i)?;
                i += 2;
            }
            w @ ("parallel" | "set_property" | "compress_tags" | "random_distribute") => {
                return Err(a.unsupported(i, &format!("fix insert/stream {w}")))
            }
            _ => {
                return Err(a.keyword_error(
                    i,
                    &[
                        "seed",
                        "distributiontemplate",
                        "nparticles",
                        "mass",
                        "particlerate",
                        "massrate",
                        "insertion_face",
                        "extrude_length",
                        "insert_every",
                        "insert_every_time",
                        "duration",
                        "duration_time",
                        "vel",
                        "omega",
                        "overlapcheck",
                        "maxattempt",
                        "ntry_mc",
                        "verbose",
                        "start",
                        "all_in",
                        "orientation",
                    ],
                ))
            }
        }
    }
    let need = |what: &str| a.error(2, format!("Fix insert/stream: have to define '{what}'"));
    let seed = seed.ok_or_else(|| need("seed"))?;
    let distribution = dist.ok_or_else(|| need("distributiontemplate"))?;
    let (triangles, planar) = face.ok_or_else(|| need("insertion_face"))?;
    if all_in && !planar {
        return Err(a.error(
            all_in_at,
            format!("Fix insert/stream (id {id}): using all_in yes requires you to use a fix mesh/surface/planar"),
        ));
    }
    let total = total.ok_or_else(|| {
        a.error(
            2,
            "Fix insert/stream: must define either 'nparticles' or 'mass'",
        )
    })?;
    let rate = rate.ok_or_else(|| {
        a.error(
            2,
            "Fix insert/stream: must define either 'massrate' or 'particlerate'",
        )
    })?;
    if extrude.is_some() == every.is_some() {
        return Err(a.error(
            2,
            "Fix insert/stream: must define either 'insert_every' or 'extrude_length'",
        ));
    }
    if extrude.is_some() && duration.is_some() {
        return Err(a.error(
            2,
            format!("Fix insert/stream (id {id}): must not provide both 'extrude_length' and 'duration'"),
        ));
    }
    Ok(FixKind::InsertStream(Box::new(
        crate::engine::fixes::StreamFix {
            id: id.to_string(),
            seed,
            distribution,
            triangles,
            face_id,
            all_in,
            extrude,
            every,
            duration,
            total,
            rate,
            velocity,
            omega,
            overlapcheck: overlap,
            maxattempt,
            ntry_mc,
            verbose,
            start,
            state: None,
            restored: None,
            random_orientation,
        },
    )))
}
