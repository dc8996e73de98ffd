//! `fix insert/stream`: its settings and its running state.

/// `fix insert/stream` as given, and its state once set up.
#[derive(Debug, Clone)]
pub struct StreamFix {
    /// Fix ID.
    pub id: String,
    /// Seed of the fix generator.
    pub seed: i32,
    /// The distribution fix's ID.
    pub distribution: String,
    /// The insertion face's triangles (empty without `insertion_face`, which LIGGGHTS
    /// refuses at the run's init).
    pub triangles: Vec<crate::io::stl::Triangle>,
    /// The insertion face's mesh fix ID.
    pub face_id: String,
    /// The insertion face is a `fix mesh/surface/planar` (which `all_in yes` needs).
    pub planar: bool,
    /// `all_in yes`: whole particles inside the extruded face (planar faces only).
    pub all_in: bool,
    /// `extrude_length` (length), if given.
    pub extrude: Option<f64>,
    /// `insert_every`, if given.
    pub every: Option<i64>,
    /// `duration` (steps a particle travels in the extrusion zone), if given.
    pub duration: Option<i64>,
    /// `nparticles N` (Ok) or `mass M` (Err, mass units); None when neither was given,
    /// which LIGGGHTS refuses at the first run's setup.
    pub total: Option<Result<i64, f64>>,
    /// `particlerate R` (Ok, 1/time) or `massrate R` (Err, mass/time); None as for `total`.
    pub rate: Option<Result<f64, f64>>,
    /// `vel`.
    pub velocity: crate::engine::insert::Velocity,
    /// `omega constant`.
    pub omega: [f64; 3],
    /// `overlapcheck`.
    pub overlapcheck: bool,
    /// `maxattempt`.
    pub maxattempt: i64,
    /// `ntry_mc`.
    pub ntry_mc: i64,
    /// `verbose`.
    pub verbose: bool,
    /// The first insertion step.
    pub start: i64,
    /// The running insertion, after setup.
    pub state: Option<crate::engine::insert::InsertStream>,
    /// State restored from a restart file, taken over at setup.
    pub restored: Option<crate::engine::insert::InsertRestart>,
    /// `orientation random`.
    pub random_orientation: bool,
}
