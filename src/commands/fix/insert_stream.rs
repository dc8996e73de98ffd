//! `fix insert/stream`: particles inserted through a mesh face.

use super::insertion::{keyword, yes, Family, Insertion, Schedule};
use crate::commands::fix::FixDef;
use crate::commands::specs::{style, Spec, INSERT_KEYWORDS};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStyle, RestoreError, StreamFix};
use crate::engine::insert::{InsertRestart, UNLIMITED};
use crate::io::stl::Triangle;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "insert/stream",
    "fix ID GROUP insert/stream seed SEED distributiontemplate D nparticles N particlerate R insertion_face MESH extrude_length L",
    INSERT_KEYWORDS,
    "stream particles through a mesh face",
);

/// `fix ID GROUP insert/stream seed S distributiontemplate D nparticles N particlerate R
/// insertion_face MESH extrude_length L|insert_every N vel ... [overlapcheck ...]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let id = fix.id;
    ctx.sim.inserts_atoms = true;
    a.count(5..=usize::MAX, "fix ID GROUP insert/stream seed S distributiontemplate D nparticles N particlerate R insertion_face MESH extrude_length L ...")?;
    let mut stream = StreamArgs::new(ctx.sim.step, id);
    let families: [Family<StreamArgs>; 5] = [
        |s, a, ctx, i, w| s.common.keyword(a, ctx, i, w),
        StreamArgs::face,
        StreamArgs::amounts,
        |s, a, ctx, i, w| s.schedule.keyword(a, ctx, i, w),
        StreamArgs::all_in,
    ];
    // LIGGGHTS reads the general insertion keywords first, then insert/stream's own; a
    // general one after those is an error there
    let mut own_part = false;
    let mut i = 3;
    while i < a.len() {
        let w = a.word(i)?;
        if OWN.contains(&w) {
            own_part = true;
        } else if own_part {
            return Err(a.error(
                i,
                format!("Fix insert/stream (id {id}): unknown keyword or wrong keyword order"),
            ));
        }
        match keyword(&mut stream, &families, a, ctx, i, w)? {
            Some(used) => i += used,
            None => return Err(unknown(a, i, w)),
        }
    }
    stream.common.check_seeds(a, ctx)?;
    stream.finish(a, id)
}

/// insert/stream's own keywords (after the general insertion keywords).
const OWN: &[&str] = &[
    "insertion_face",
    "extrude_length",
    "duration",
    "duration_time",
    "parallel",
    "ntry_mc",
    "save_template",
];

/// A keyword no family knows: LIGGGHTS's keywords regolith does not run, else the known ones.
fn unknown(a: &Args, i: usize, w: &str) -> CommandError {
    if matches!(
        w,
        "parallel" | "set_property" | "compress_tags" | "random_distribute"
    ) {
        return a.unsupported(i, &format!("fix insert/stream {w}"));
    }
    a.keyword_error(
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
    )
}

/// The keywords of `fix insert/stream` as given.
struct StreamArgs {
    /// The fix ID (LIGGGHTS's messages name it).
    id: String,
    /// The keywords every insertion fix takes.
    common: Insertion,
    /// `insertion_face MESH`: its triangles and whether it is a planar mesh.
    face: Option<(Vec<Triangle>, bool)>,
    /// The insertion face's fix ID.
    face_id: String,
    /// `extrude_length L` (length).
    extrude: Option<f64>,
    /// `insert_every N` and `start N`.
    schedule: Schedule,
    /// `duration N` (steps).
    duration: Option<i64>,
    /// `nparticles N` (Ok) or `mass M` (Err).
    total: Option<Result<i64, f64>>,
    /// `particlerate R` (Ok) or `massrate R` (Err).
    rate: Option<Result<f64, f64>>,
    /// `ntry_mc N`.
    ntry_mc: i64,
    /// `all_in yes|no`.
    all_in: bool,
}

impl StreamArgs {
    /// LIGGGHTS's defaults at step `step`.
    fn new(step: i64, id: &str) -> StreamArgs {
        StreamArgs {
            id: id.to_string(),
            common: Insertion::default(),
            face: None,
            face_id: String::new(),
            extrude: None,
            schedule: Schedule::new(step, false),
            duration: None,
            total: None,
            rate: None,
            ntry_mc: 100000,
            all_in: false,
        }
    }

    /// The face and its extrusion: `insertion_face`, `extrude_length`, `duration`, `ntry_mc`.
    fn face(
        &mut self,
        a: &Args,
        ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        let id = &self.id;
        match w {
            "insertion_face" => {
                let m = a.word(i + 1)?;
                let tri = crate::engine::fixes::mesh_named(&ctx.sim.fixes, m)
                    .map(|mesh| (mesh.triangles().to_vec(), mesh.planar));
                self.face_id = m.to_string();
                self.face = Some(tri.ok_or_else(|| {
                    a.error(
                        i + 1,
                        "Fix insert/stream: could not find the insertion_face mesh",
                    )
                })?);
            }
            "extrude_length" => self.extrude = Some(a.real(i + 1)?),
            "duration" | "duration_time" => {
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
                self.duration = Some(d);
            }
            "ntry_mc" => {
                self.ntry_mc = a.int32(i + 1)?;
                if self.ntry_mc < 1000 {
                    return Err(a.error(
                        i + 1,
                        format!("Fix insert/stream (id {id}): ntry_mc must be > 1000"),
                    ));
                }
            }
            _ => return Ok(None),
        }
        Ok(Some(2))
    }

    /// How many and how fast: `nparticles` or `mass`, `particlerate` or `massrate`.
    fn amounts(
        &mut self,
        a: &Args,
        _ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        match w {
            "nparticles" | "mass" => {
                if self.total.is_some() {
                    return Err(a.error(
                        i,
                        format!("Fix insert/stream (id {}): must not define both 'nparticles' and 'mass'", a.word(0)?),
                    ));
                }
                // INF: no total, insertion at the rate until the runs end
                self.total = Some(if a.word(i + 1)? == "INF" {
                    Ok(UNLIMITED)
                } else if w == "mass" {
                    Err(a.real(i + 1)?)
                } else {
                    Ok(a.int32(i + 1)?)
                });
            }
            "particlerate" | "massrate" => {
                if self.rate.is_some() {
                    return Err(a.error(
                        i,
                        format!("Fix insert/stream (id {}): must not define both 'particlerate' and 'massrate'", a.word(0)?),
                    ));
                }
                let r = a.real(i + 1)?;
                self.rate = Some(if w == "massrate" { Err(r) } else { Ok(r) });
            }
            _ => return Ok(None),
        }
        Ok(Some(2))
    }

    /// Where in the face: `all_in`.
    fn all_in(
        &mut self,
        a: &Args,
        _ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        if w != "all_in" {
            return Ok(None);
        }
        self.all_in = yes(a, i + 1)?;
        Ok(Some(2))
    }

    /// The fix from the keywords, after LIGGGHTS's checks of the fix line; what the
    /// keywords must define together LIGGGHTS checks at the run (the first run's setup
    /// checks them here too, see `Simulation::stream_plan`).
    fn finish(self, a: &Args, id: &str) -> Result<Box<dyn FixStyle>, CommandError> {
        let need = |what: &str| a.error(2, format!("Fix insert/stream: have to define '{what}'"));
        let common = self.common;
        let seed = common.seed.ok_or_else(|| need("seed"))?;
        let distribution = common
            .distribution
            .ok_or_else(|| need("distributiontemplate"))?;
        let (triangles, planar) = self.face.unwrap_or_default();
        Ok(Box::new(StreamFix {
            id: id.to_string(),
            seed,
            distribution,
            triangles,
            face_id: self.face_id,
            planar,
            all_in: self.all_in,
            extrude: self.extrude,
            every: self.schedule.every,
            duration: self.duration,
            total: self.total,
            rate: self.rate,
            velocity: common.velocity,
            omega: common.omega,
            overlapcheck: common.overlapcheck,
            maxattempt: common.maxattempt,
            ntry_mc: self.ntry_mc,
            verbose: common.verbose,
            start: self.schedule.start,
            state: None,
            restored: None,
            random_orientation: common.random_orientation,
        }))
    }
}

/// A stream sets itself up, inserts and carries its particles to their release in the
/// run's insertion passes, which find it by type ([`FixKind::stream`]).
///
/// [`FixKind::stream`]: crate::engine::fixes::FixKind::stream
impl FixStyle for StreamFix {
    fn name(&self) -> &str {
        "insert/stream"
    }

    /// The running insertion's state; before its first setup, the state it was defined
    /// with (or took from a restart file).
    fn restart_state(&self) -> Option<Vec<u8>> {
        let state = match &self.state {
            Some(s) => s.restart_state(),
            None => InsertRestart {
                rng_state: self.restored.map_or(self.seed, |r| r.rng_state),
                inserted: self.restored.map_or(0, |r| r.inserted),
                first_step: self.restored.map_or(self.start, |r| r.first_step),
                next: self.start,
                mass: self.restored.map_or(0.0, |r| r.mass),
            },
        };
        Some(state.bytes())
    }

    /// Taken over at the first setup; the next insertion step at once.
    fn restore_state(&mut self, state: &[u8]) -> Result<(), RestoreError> {
        let r = InsertRestart::parse(state).map_err(|e| RestoreError::Malformed(e.to_string()))?;
        if r.next != 0 {
            self.start = r.next;
        }
        self.restored = Some(r);
        Ok(())
    }

    /// Each particle's release data, which copies could not take over.
    fn keeps_per_atom_state(&self) -> bool {
        true
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}
