//! Fixes that act on particles each step, in LIGGGHTS's phases: `initial_integrate`
//! (nve/sphere, move), `post_force` (gravity, setforce, addforce, walls) and
//! `final_integrate`. Within a phase fixes act in the order they were defined; the styles
//! written as modules ([`FixStyle`], [`FixKind::Style`]) take their turn among the others.

use std::collections::HashMap;

use crate::engine::domain::Domain;
use crate::engine::error::EngineError;
use crate::engine::integrate::{self, Gravity};
use crate::engine::particles::Particles;

mod ave_time;
mod style;

pub use ave_time::{AveInput, AveMode, AveSchedule, AveTime};
pub use style::{FixStep, FixStyle, PerAtomShape};

/// Prescribed motion of `fix move` (length and time units).
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// `linear vx vy vz`: constant velocity; None components are integrated freely.
    Linear([Option<f64>; 3]),
    /// `wiggle Ax Ay Az period`: x = x0 + A sin(2 pi t / period).
    Wiggle {
        /// Amplitudes (length); None components are integrated.
        amplitude: [Option<f64>; 3],
        /// 2 pi / period (1/time).
        omega: f64,
    },
    /// `rotate Px Py Pz Rx Ry Rz period`: rotation about the axis through P along R.
    Rotate {
        /// A point on the axis (length).
        point: [f64; 3],
        /// Unit vector along the axis.
        axis: [f64; 3],
        /// 2 pi / period (1/time).
        omega: f64,
    },
    /// `variable dx dy dz vx vy vz`: displacements from the start position and velocities
    /// from equal- or atom-style variables (NULL: not given).
    Variable {
        /// Displacement variables (length).
        displace: [ForceValue; 3],
        /// Velocity variables (length/time).
        velocity: [ForceValue; 3],
    },
}

/// A `fix move`: the motion, where each atom started (unwrapped) and the start step.
#[derive(Debug, Clone, PartialEq)]
pub struct Move {
    /// The motion.
    pub motion: Motion,
    /// Unwrapped start positions by atom ID.
    pub origin: HashMap<i64, [f64; 3]>,
    /// The step the fix was defined at (its time origin).
    pub start_step: i64,
    /// `move variable`: this step's displacement and velocity values per local atom.
    pub resolved: Vec<[Option<f64>; 6]>,
}

impl Move {
    /// Record the current unwrapped positions of the group's atoms as the origin.
    pub fn new(motion: Motion, p: &Particles, group: u32, domain: &Domain, step: i64) -> Move {
        let mut origin = HashMap::new();
        for i in 0..p.len() {
            if p.mask[i] & group != 0 {
                let mut x = p.x[i];
                for (d, xd) in x.iter_mut().enumerate() {
                    *xd += p.image[i][d] as f64 * domain.length(d);
                }
                origin.insert(p.id[i], x);
            }
        }
        Move {
            motion,
            origin,
            start_step: step,
            resolved: Vec::new(),
        }
    }

    /// Which components the motion prescribes (the rest are integrated).
    fn prescribed(&self) -> [bool; 3] {
        match &self.motion {
            Motion::Linear(v) => v.map(|c| c.is_some()),
            Motion::Wiggle { amplitude, .. } => amplitude.map(|c| c.is_some()),
            Motion::Rotate { .. } => [true; 3],
            Motion::Variable { displace, velocity } => {
                [0, 1, 2].map(|d| !displace[d].is_null() || !velocity[d].is_null())
            }
        }
    }

    /// `move variable`: x = x0 + dx where dx is given, v = vx where vx is given (with no dx,
    /// x advances by dt vx); components with neither are integrated (LIGGGHTS's order).
    fn variable_integrate(&self, p: &mut Particles, group: u32, dt: f64, domain: &Domain) {
        let dtf = 0.5 * dt;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let xold = p.x[i];
            let x0 = self.origin.get(&p.id[i]).copied().unwrap_or([0.0; 3]);
            let r = self.resolved.get(i).copied().unwrap_or([None; 6]);
            for d in 0..3 {
                match (r[d], r[3 + d]) {
                    (Some(dx), Some(v)) => {
                        p.v[i][d] = v;
                        p.x[i][d] = x0[d] + dx;
                    }
                    (Some(dx), None) => p.x[i][d] = x0[d] + dx,
                    (None, Some(v)) => {
                        p.v[i][d] = v;
                        p.x[i][d] += dt * p.v[i][d];
                    }
                    (None, None) => {
                        p.v[i][d] += dtf / p.mass[i] * p.f[i][d];
                        p.x[i][d] += dt * p.v[i][d];
                    }
                }
            }
            domain.remap_near(&mut p.x[i], &xold);
        }
    }

    /// Prescribe (or integrate) the group's positions and velocities for `step`; positions
    /// set from the unwrapped start point are brought back to the image nearest the old
    /// position, as LIGGGHTS's `remap_near` does.
    fn initial_integrate(
        &self,
        p: &mut Particles,
        group: u32,
        step: i64,
        dt: f64,
        domain: &Domain,
    ) {
        if matches!(self.motion, Motion::Variable { .. }) {
            return self.variable_integrate(p, group, dt, domain);
        }
        let delta = (step - self.start_step) as f64 * dt;
        let dtf = 0.5 * dt;
        if let Motion::Rotate {
            point,
            axis: r,
            omega,
        } = self.motion
        {
            // X = P + C + A cos(wt) + B sin(wt), V = w R x (A cos(wt) + B sin(wt))
            let arg = omega * delta;
            let (sine, cosine) = (arg.sin(), arg.cos());
            for i in 0..p.len() {
                if p.mask[i] & group == 0 {
                    continue;
                }
                let xold = p.x[i];
                let x0 = self.origin.get(&p.id[i]).copied().unwrap_or([0.0; 3]);
                let d = [x0[0] - point[0], x0[1] - point[1], x0[2] - point[2]];
                let ddotr = d[0] * r[0] + d[1] * r[1] + d[2] * r[2];
                let c = [ddotr * r[0], ddotr * r[1], ddotr * r[2]];
                let a = [d[0] - c[0], d[1] - c[1], d[2] - c[2]];
                let b = [
                    r[1] * a[2] - r[2] * a[1],
                    r[2] * a[0] - r[0] * a[2],
                    r[0] * a[1] - r[1] * a[0],
                ];
                let disp = [
                    a[0] * cosine + b[0] * sine,
                    a[1] * cosine + b[1] * sine,
                    a[2] * cosine + b[2] * sine,
                ];
                for k in 0..3 {
                    p.x[i][k] = point[k] + c[k] + disp[k];
                }
                p.v[i] = [
                    omega * (r[1] * disp[2] - r[2] * disp[1]),
                    omega * (r[2] * disp[0] - r[0] * disp[2]),
                    omega * (r[0] * disp[1] - r[1] * disp[0]),
                ];
                p.omega[i] = [omega * r[0], omega * r[1], omega * r[2]];
                domain.remap_near(&mut p.x[i], &xold);
            }
            return;
        }
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let xold = p.x[i];
            let x0 = self.origin.get(&p.id[i]).copied().unwrap_or([0.0; 3]);
            for d in 0..3 {
                let set = match &self.motion {
                    Motion::Linear(v) => v[d].map(|vd| (vd, x0[d] + vd * delta)),
                    Motion::Wiggle { amplitude, omega } => amplitude[d].map(|a| {
                        let arg = omega * delta;
                        (a * omega * arg.cos(), x0[d] + a * arg.sin())
                    }),
                    Motion::Rotate { .. } | Motion::Variable { .. } => {
                        unreachable!("handled above")
                    }
                };
                match set {
                    Some((v, x)) => {
                        p.v[i][d] = v;
                        p.x[i][d] = x;
                    }
                    None => {
                        let dtfm = dtf / p.mass[i];
                        p.v[i][d] += dtfm * p.f[i][d];
                        p.x[i][d] += dt * p.v[i][d];
                    }
                }
            }
            domain.remap_near(&mut p.x[i], &xold);
        }
    }

    fn final_integrate(&self, p: &mut Particles, group: u32, dt: f64) {
        let free = self.prescribed().map(|s| !s);
        let dtf = 0.5 * dt;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            for (d, &free) in free.iter().enumerate() {
                if free {
                    let dtfm = dtf / p.mass[i];
                    p.v[i][d] += dtfm * p.f[i][d];
                }
            }
        }
    }
}

/// What a fix does.
pub enum FixKind {
    /// `fix nve/sphere`.
    NveSphere,
    /// `fix nve/sphere` in 2d: discs (moment of inertia 0.5 m r^2).
    NveDisc,
    /// `fix move`.
    Move(Move),
    /// `fix gravity`.
    Gravity(Gravity),
    /// `fix setforce fx fy fz` (None: leave that component).
    SetForce(ForceFix),
    /// `fix addforce fx fy fz` (force units).
    AddForce(ForceFix),
    /// `fix wall/gran ... primitive`: a granular plane wall.
    WallGran(WallFix),
    /// `fix check/timestep/gran`: time step as a fraction of Rayleigh and Hertz times.
    CheckTimestep(CheckTimestep),
    /// `print N "text" [file F | append F] [screen yes|no] [title T]`.
    Print(PrintFix),
    /// `fix ave/time` (scalar mode).
    AveTime(AveTime),
    /// `fix spring/self`: particles tethered to their positions at definition.
    SpringSelf(crate::engine::spring_self::SpringSelf),
    /// `fix mesh/surface`: a triangle mesh (walls and insertion faces use it).
    Mesh(Box<MeshFix>),
    /// `fix particletemplate/sphere`.
    Template(crate::engine::insert::Template),
    /// `fix particletemplate/multisphere`: a rigid clump of spheres.
    ClumpTemplate(Box<crate::engine::multisphere::ClumpTemplate>),
    /// `fix particledistribution/discrete...`.
    Distribution(crate::engine::insert::Distribution),
    /// `fix insert/pack`.
    InsertPack(Box<crate::engine::insert::InsertPack>),
    /// `fix insert/stream` (None until its first setup computes the face geometry).
    InsertStream(Box<StreamFix>),
    /// `fix wall/gran ... mesh`: granular walls of triangle meshes.
    MeshWall(MeshWallFix),
    /// `fix adapt N atom diameter v_name`: particle diameters from a variable.
    Adapt(Adapt),
    /// `fix move/mesh`: prescribed motion of a mesh.
    MoveMesh(crate::engine::mesh_motion::MoveMesh),
    /// `fix massflow/mesh`: particles and mass crossing a mesh face.
    Massflow(Box<crate::engine::massflow::Massflow>),
    /// `fix buoyancy`: the weight of displaced liquid below a level.
    Buoyancy(crate::engine::buoyancy::Buoyancy),
    /// `fix property/atom/tracer`: particles marked in a region.
    Tracer(Box<crate::engine::tracer::Tracer>),
    /// A fix that only holds settings read by other parts (e.g. `property/global`).
    Settings,
    /// `fix property/atom`: a per-atom property (values in the particle array of the fix ID).
    PropertyAtom(crate::engine::heat::PropertyAtom),
    /// `fix heat/gran`, `heat/gran/conduction`: heat conduction between touching particles.
    HeatGran(crate::engine::heat::HeatGran),
    /// `fix multisphere`: the rigid clumps and their integration.
    Multisphere(Box<crate::engine::clumps::Clumps>),
    /// `fix ave/atom`: per-particle time averages.
    AveAtom(Box<crate::engine::ave_atom::AveAtom>),
    /// `ave/histo`: histograms of per-atom values written to a file.
    AveHisto(Box<crate::engine::ave_histo::AveHisto>),
    /// `ave/spatial`: per-bin averages written to a file.
    AveSpatial(Box<crate::engine::ave_spatial::AveSpatial>),
    /// `store/state`: per-particle snapshots (f_ID, f_ID[N]).
    StoreState(Box<crate::engine::store_state::StoreState>),
    /// A style written as a module (see [`FixStyle`]): its hooks run in each phase.
    Style(Box<dyn FixStyle>),
    /// `fix deform`: the box changes every N steps.
    Deform(Box<crate::engine::deform::Deform>),
}

impl FixKind {
    /// Can the fix evaluate variables or computes inside a step (so per-atom computes must
    /// be current on every step)? Kinds not listed answer yes.
    pub fn may_read_computes(&self) -> bool {
        let variable = |v: &ForceValue| matches!(v, ForceValue::Equal(_) | ForceValue::Atom(_));
        match self {
            FixKind::NveSphere
            | FixKind::NveDisc
            | FixKind::Gravity(_)
            | FixKind::WallGran(_)
            | FixKind::CheckTimestep(_)
            | FixKind::Mesh(_)
            | FixKind::Template(_)
            | FixKind::ClumpTemplate(_)
            | FixKind::Distribution(_)
            | FixKind::InsertPack(_)
            | FixKind::InsertStream(_)
            | FixKind::MeshWall(_)
            | FixKind::Massflow(_)
            | FixKind::Tracer(_)
            | FixKind::Settings
            | FixKind::PropertyAtom(_)
            | FixKind::HeatGran(_) => false,
            FixKind::SetForce(f) | FixKind::AddForce(f) => f.values.iter().any(variable),
            FixKind::Move(m) => matches!(m.motion, Motion::Variable { .. }),
            FixKind::Style(s) => s.reads_computes(),
            _ => true,
        }
    }
}

/// `fix adapt N atom diameter v_name [scale yes|no] [reset yes|no]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Adapt {
    /// Apply every this many steps (0: only at the setup of each run).
    pub every: i64,
    /// The diameter (length), or the factor on the current diameter with `scale yes`.
    pub diameter: ForceValue,
    /// `scale yes`: the variable multiplies the current diameter.
    pub scale: bool,
}

/// `fix check/timestep/gran N rayleigh_limit hertz_limit [warn yes|no] [error yes|no] [vmax V]`.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckTimestep {
    /// Check every this many steps (at the end of the step).
    pub every: i64,
    /// Warn above this fraction of the Rayleigh time.
    pub rayleigh_limit: f64,
    /// Warn above this fraction of the Hertz time.
    pub hertz_limit: f64,
    /// Print warnings.
    pub warn: bool,
    /// Stop with an error instead.
    pub error: bool,
    /// A velocity (length/time) assumed at least for the Hertz estimate.
    pub vmax_user: f64,
    /// dt / Rayleigh time, dt / Hertz time, relative travel per step / skin (f_ID[1..3]).
    pub values: [f64; 3],
    /// Per type (1-based index - 1): Young's modulus, Poisson ratio, and Yeff of the type with itself.
    pub materials: Vec<(f64, f64, f64)>,
}

impl CheckTimestep {
    /// LIGGGHTS's estimates; returns the warnings to print.
    pub fn evaluate(&mut self, p: &Particles, group: u32, dt: f64, skin: f64) -> Vec<String> {
        const BIG: f64 = 1.0e20;
        let mut rayleigh = BIG;
        let mut r_min = BIG;
        let mut vmax_sqr: f64 = 0.0;
        for i in 0..p.len() {
            if p.mask[i] & group == 0 {
                continue;
            }
            let rad = p.radius[i];
            let (y, nu, _) = self.materials[p.kind[i] as usize - 1];
            let shear = y / (2. * (nu + 1.));
            let t =
                std::f64::consts::PI * rad * (p.density[i] / shear).sqrt() / (0.1631 * nu + 0.8766);
            if t < rayleigh {
                rayleigh = t;
            }
            let v = p.v[i];
            let vsq = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
            if vsq > vmax_sqr {
                vmax_sqr = vsq;
            }
            if rad < r_min {
                r_min = rad;
            }
        }
        if self.vmax_user * self.vmax_user > vmax_sqr {
            vmax_sqr = self.vmax_user * self.vmax_user;
        }
        let v_rel = (2. * vmax_sqr.sqrt()).max(vmax_sqr.sqrt() + 0.0);
        let mut hertz: f64 = 1000000.;
        if (v_rel - 0.0).abs() >= 1e-13 {
            for ti in 1..=self.materials.len() {
                let eeff = self.materials[ti - 1].2;
                for i in 0..p.len() {
                    if p.mask[i] & group == 0 || p.kind[i] as usize != ti {
                        continue;
                    }
                    let r = p.radius[i];
                    let meff = 4. * r * r * r * std::f64::consts::PI / 3. * p.density[i];
                    let reff = r / 2.;
                    let t = 2.87 * (meff * meff / (reff * eeff * eeff * v_rel)).powf(0.2);
                    if t < hertz {
                        hertz = t;
                    }
                }
            }
        }
        self.values = [dt / rayleigh, dt / hertz, v_rel * dt / skin];
        let mut messages = Vec::new();
        if self.warn || self.error {
            if self.values[0] > self.rayleigh_limit {
                messages.push(format!(
                    "time-step is {} % of rayleigh time",
                    crate::util::format::with_spec("%f", self.values[0] * 100.).unwrap_or_default()
                ));
            }
            if self.values[1] > self.hertz_limit {
                messages.push(format!(
                    "time-step is {} % of hertz time",
                    crate::util::format::with_spec("%f", self.values[1] * 100.).unwrap_or_default()
                ));
            }
            if self.values[2] > 1.0 {
                messages.push(format!(
                    "time step too large or skin too small - particles may relatively travel a distance of {} per time-step, but skin is {}",
                    crate::util::format::with_spec("%f", v_rel * dt).unwrap_or_default(),
                    crate::util::format::with_spec("%f", skin).unwrap_or_default()
                ));
            }
            if v_rel * dt > r_min {
                messages.push("time step way too large - particles relativley move further than the minimum radius in one step".into());
            }
        }
        messages
    }
}

/// A primitive granular wall: its models, the plane, and the built interaction.
pub struct WallFix {
    /// Selected contact models.
    pub selection: crate::engine::granular::Selection,
    /// The plane.
    pub plane: crate::engine::granular::Primitive,
    /// The wall's atom type (for material coefficients).
    pub wall_type: usize,
    /// `shear dim vshear`: the wall surface moves along `dim` at `vshear` (m/s); for a
    /// cylinder sheared across its axis, it turns about the axis at `vshear` (rad/s).
    pub shear: Option<(usize, f64)>,
    /// Built at each run from the current materials.
    pub model: Option<Box<dyn crate::engine::granular::WallInteraction>>,
    /// Name of the per-particle history array (`history_<fix ID>`, as in LIGGGHTS restarts).
    pub history_name: String,
}

/// `fix wall/gran model ... mesh n_meshes N meshes ...`.
pub struct MeshWallFix {
    /// Selected contact models.
    pub selection: crate::engine::granular::Selection,
    /// IDs of the `fix mesh/surface` meshes, in the order given.
    pub meshes: Vec<String>,
    /// Index of the fix's group (LIGGGHTS ORs it into the mesh group bits).
    pub group_index: u32,
    /// Built at each run from the current materials.
    pub model: Option<Box<dyn crate::engine::mesh_wall::MeshWallInteraction>>,
    /// Contact bookkeeping per mesh (kept across runs).
    pub trackers: Vec<crate::engine::mesh_wall::Tracker>,
    /// The pair-list build the trackers' candidate lists belong to.
    pub built: Option<u64>,
}

impl MeshWallFix {
    /// Doubles of history per contact of its contact model (the model of the current run,
    /// or the one its selection gives before the first run).
    pub fn history_width(&self) -> usize {
        match &self.model {
            Some(m) => m.history_width(),
            None => crate::engine::contact::AnyContactModel::new(&self.selection)
                .map_or(0, |m| m.history_len()),
        }
    }
}

/// One defined fix.
pub struct Fix {
    /// The fix ID.
    pub id: String,
    /// Its style name.
    pub style: String,
    /// Group bits it acts on.
    pub group: u32,
    /// What it does.
    pub kind: FixKind,
    /// Its arguments after the style (for settings fixes).
    pub args: Vec<String>,
}

/// The meshes of a mesh wall, in its `meshes` order, as its force loop sees them.
fn mesh_refs<'a>(fixes: &'a [Fix], w: &MeshWallFix) -> Vec<crate::engine::mesh_wall::MeshRef<'a>> {
    w.meshes
        .iter()
        .filter_map(|id| {
            fixes.iter().find_map(|f| match &f.kind {
                FixKind::Mesh(m) if &f.id == id => {
                    let moving = m.servo.is_some()
                        || fixes
                            .iter()
                            .any(|g| matches!(&g.kind, FixKind::MoveMesh(mv) if &mv.mesh == id));
                    Some(crate::engine::mesh_wall::MeshRef {
                        moving,
                        stress: m.stress.is_some(),
                        mesh: &m.mesh,
                        wall_type: m.wall_type,
                        group: f.group | w.group_index,
                        node_v: m.node_v.as_deref(),
                    })
                }
                _ => None,
            })
        })
        .collect()
}

/// The contacts of the mesh wall fix `fixes[k]` as a second force pass finds them, with
/// nothing applied and no history advanced (`compute wall/gran/local`); empty before the
/// wall's first run.
pub fn mesh_wall_contacts(
    fixes: &[Fix],
    k: usize,
    p: &Particles,
    dt: f64,
) -> Vec<crate::engine::mesh_wall::WallContact> {
    let FixKind::MeshWall(w) = &fixes[k].kind else {
        return Vec::new();
    };
    let Some(model) = w.model.as_ref() else {
        return Vec::new();
    };
    let refs = mesh_refs(fixes, w);
    if w.trackers.len() != refs.len() {
        return Vec::new();
    }
    let mut trackers = w.trackers.clone();
    model.contacts(p, &refs, &mut trackers, dt)
}

/// The forces of the mesh wall fix `fixes[k]` on the particles.
fn mesh_wall_force(
    fixes: &mut [Fix],
    k: usize,
    p: &mut Particles,
    dt: f64,
    update: bool,
    list: (u64, f64),
    moving_skin: bool,
) {
    let mut kind = std::mem::replace(&mut fixes[k].kind, FixKind::Settings);
    if let FixKind::MeshWall(w) = &mut kind {
        if let Some(model) = w.model.as_ref() {
            let mesh_fix: Vec<usize> = w
                .meshes
                .iter()
                .filter_map(|id| {
                    fixes
                        .iter()
                        .position(|f| &f.id == id && matches!(f.kind, FixKind::Mesh(_)))
                })
                .collect();
            let refs = mesh_refs(fixes, w);
            if w.trackers.len() != refs.len() {
                w.trackers = vec![Default::default(); refs.len()];
                w.built = None;
            }
            if w.built != Some(list.0) {
                for (tr, m) in w.trackers.iter_mut().zip(&refs) {
                    let skin = if moving_skin || m.moving {
                        list.1
                    } else {
                        0.5 * list.1
                    };
                    tr.rebuild(p, m, skin);
                }
                w.built = Some(list.0);
            }
            let mut records = Vec::new();
            model.compute(p, &refs, &mut w.trackers, dt, update, &mut records);
            drop(refs);
            // a servo mesh sums its force in LIGGGHTS's loop order (it feeds back on the motion)
            for (k, &at) in mesh_fix.iter().enumerate() {
                if let FixKind::Mesh(m) = &fixes[at].kind {
                    if let Some(s) = m.servo.as_ref() {
                        let mut own: Vec<_> =
                            records.iter().filter(|r| r.0 == k).map(|r| r.1).collect();
                        crate::engine::mesh_servo::order_contacts(&mut own, &s.bins);
                        records.retain(|r| r.0 != k);
                        records.extend(own.into_iter().map(|c| (k, c)));
                    }
                }
            }
            for (mesh_index, c) in records {
                let f = &mut fixes[mesh_fix[mesh_index]];
                if p.mask[c.particle] & f.group == 0 {
                    continue;
                }
                if let FixKind::Mesh(m) = &mut f.kind {
                    let t = c.tri as usize;
                    let (normal, area) = (m.mesh.normal[t], m.mesh.area[t]);
                    if let Some(st) = m.stress.as_mut() {
                        st.add(
                            &c,
                            p.x[c.particle],
                            p.v[c.particle],
                            normal,
                            area,
                            m.wall_type,
                            p.kind[c.particle] as usize,
                            dt,
                        );
                    }
                }
            }
        }
    }
    fixes[k].kind = kind;
}

/// `fix move/mesh` in `initial_integrate`: every mover in definition order moves its mesh
/// and adds its node velocities (the first mover of a mesh zeroes them first); the rotation
/// centres of the movers after it follow the displacement.
pub fn move_meshes(fixes: &mut [Fix], dt: f64) {
    let movers: Vec<usize> = (0..fixes.len())
        .filter(|&k| matches!(fixes[k].kind, FixKind::MoveMesh(_)))
        .collect();
    for (pos, &k) in movers.iter().enumerate() {
        let FixKind::MoveMesh(mut mv) = std::mem::replace(&mut fixes[k].kind, FixKind::Settings)
        else {
            unreachable!("listed as a mover")
        };
        let first = !movers[..pos]
            .iter()
            .any(|&e| matches!(&fixes[e].kind, FixKind::MoveMesh(o) if o.mesh == mv.mesh));
        let mesh_at = fixes
            .iter()
            .position(|f| f.id == mv.mesh && matches!(f.kind, FixKind::Mesh(_)));
        let mut shift = None;
        if let Some(FixKind::Mesh(m)) = mesh_at.map(|i| &mut fixes[i].kind) {
            let n = m.mesh.len();
            let v = m.node_v.get_or_insert_with(|| vec![[[0.0; 3]; 3]; n]);
            if first {
                v.iter_mut().for_each(|t| *t = [[0.0; 3]; 3]);
            }
            let d = mv.step(&mut m.mesh, v, dt);
            mv.follow(&d);
            shift = Some(d);
        }
        let mesh = mv.mesh.clone();
        fixes[k].kind = FixKind::MoveMesh(mv);
        if let Some(d) = shift {
            for &later in &movers[pos + 1..] {
                if let FixKind::MoveMesh(o) = &mut fixes[later].kind {
                    if o.mesh == mesh {
                        o.follow(&d);
                    }
                }
            }
        }
    }
}

/// Run the `initial_integrate` phase of all fixes.
pub fn initial_integrate(
    fixes: &mut [Fix],
    p: &mut Particles,
    step: i64,
    dt: f64,
    domain: &Domain,
) {
    // clumps from an insertion face move at its velocity until released
    let has_stream = fixes
        .iter()
        .any(|f| matches!(f.kind, FixKind::InsertStream(_)));
    for fix in fixes {
        match &mut fix.kind {
            FixKind::NveSphere => integrate::initial_integrate(p, fix.group, dt),
            FixKind::NveDisc => integrate::initial_integrate_with(
                p,
                fix.group,
                dt,
                crate::engine::planar::DISC_INERTIA,
            ),
            FixKind::Multisphere(ms) => ms.initial_integrate(p, dt, domain, step, has_stream),
            FixKind::Move(m) => m.initial_integrate(p, fix.group, step, dt, domain),
            FixKind::HeatGran(h) => h.initial_integrate(p),
            FixKind::Style(s) => s.initial_integrate(
                p,
                &FixStep {
                    group: fix.group,
                    step,
                    dt,
                    domain,
                    virial: &[],
                    contact: 0.0,
                },
            ),
            _ => {}
        }
    }
}

/// `fix print`: a line with variables substituted every `every` steps.
pub struct PrintFix {
    /// Print every this many steps.
    pub every: i64,
    /// The text, `$` references still in it.
    pub text: String,
    /// Also print to screen and log.
    pub screen: bool,
    /// The output file, if any.
    pub file: Option<std::io::BufWriter<std::fs::File>>,
}

impl PrintFix {
    /// Write one substituted line where the fix sends it.
    pub fn emit(&mut self, line: &str, out: &mut dyn FnMut(&str)) -> Result<(), EngineError> {
        use std::io::Write;
        if self.screen {
            out(&format!("{line}\n"));
        }
        if let Some(f) = self.file.as_mut() {
            writeln!(f, "{line}")
                .and_then(|_| f.flush())
                .map_err(|e| format!("fix print: {e}"))?;
        }
        Ok(())
    }
}

/// One component of `fix setforce`/`addforce` (force units).
#[derive(Debug, Clone, PartialEq, Default)]
pub enum ForceValue {
    /// `NULL` (setforce: leave the component alone).
    #[default]
    Null,
    /// A number.
    Constant(f64),
    /// `v_name` of an equal-style variable (evaluated each step).
    Equal(String),
    /// `v_name` of an atom-style variable (evaluated each step, per atom).
    Atom(String),
}

impl ForceValue {
    /// True for `NULL`.
    pub fn is_null(&self) -> bool {
        matches!(self, ForceValue::Null)
    }
}

/// `fix setforce`/`addforce`: three components and an optional region.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceFix {
    /// x, y, z components.
    pub values: [ForceValue; 3],
    /// `region ID`: only particles inside (region index).
    pub region: Option<usize>,
    /// Per-particle components of this step when variables or a region are involved
    /// (None: leave / add nothing), filled by the simulation before `post_force`.
    pub resolved: Vec<[Option<f64>; 3]>,
}

impl ForceFix {
    /// True if the components must be evaluated per step and particle.
    pub fn needs_resolving(&self) -> bool {
        self.region.is_some()
            || self
                .values
                .iter()
                .any(|v| matches!(v, ForceValue::Equal(_) | ForceValue::Atom(_)))
    }

    /// The constant components (None for NULL); only valid without variables.
    fn constants(&self) -> [Option<f64>; 3] {
        self.values.clone().map(|v| match v {
            ForceValue::Constant(c) => Some(c),
            _ => None,
        })
    }

    /// The components for particle `i`.
    #[inline]
    fn at(&self, i: usize, constants: &[Option<f64>; 3]) -> [Option<f64>; 3] {
        if self.resolved.is_empty() {
            *constants
        } else {
            self.resolved[i]
        }
    }
}

/// Run the `post_force` phase of all fixes at step `at.0` in the box `at.1`. `list` is the
/// pair list's build count and skin; `moving_skin` is whether mesh neighbour lists need the
/// full skin (moving meshes or a changing box).
pub fn post_force(
    fixes: &mut [Fix],
    p: &mut Particles,
    at: (i64, &Domain),
    dt: f64,
    update: bool,
    list: (u64, f64),
    moving_skin: bool,
) {
    let buoyancy_g = crate::engine::buoyancy::gravity_for(fixes);
    for k in 0..fixes.len() {
        if let FixKind::MeshWall(_) = fixes[k].kind {
            mesh_wall_force(fixes, k, p, dt, update, list, moving_skin);
            continue;
        }
        let fix = &mut fixes[k];
        let g = fix.group;
        match &mut fix.kind {
            FixKind::WallGran(wall) => {
                if let Some(model) = wall.model.as_mut() {
                    let w = model.history_width();
                    let k = p.extra_index(&wall.history_name, w);
                    let mut history = std::mem::take(&mut p.extra[k].data);
                    model.compute(p, g, &mut history, dt, update, list);
                    p.extra[k].data = history;
                }
            }
            FixKind::Gravity(grav) => grav.apply(p),
            FixKind::SetForce(f) => {
                let c = f.constants();
                for i in (0..p.len()).filter(|&i| p.mask[i] & g != 0) {
                    let v = f.at(i, &c);
                    for d in 0..3 {
                        if let Some(v) = v[d] {
                            p.f[i][d] = v;
                        }
                    }
                }
            }
            FixKind::AddForce(f) => {
                let c = f.constants();
                for i in (0..p.len()).filter(|&i| p.mask[i] & g != 0) {
                    let v = f.at(i, &c);
                    for d in 0..3 {
                        if let Some(v) = v[d] {
                            p.f[i][d] += v;
                        }
                    }
                }
            }
            FixKind::Buoyancy(b) => {
                if let Some(gv) = buoyancy_g {
                    b.apply(p, g, gv);
                }
            }
            FixKind::Style(s) => s.post_force(
                p,
                &FixStep {
                    group: g,
                    step: at.0,
                    dt,
                    domain: at.1,
                    virial: &[],
                    contact: 0.0,
                },
            ),
            FixKind::SpringSelf(s) => s.apply(p, g),
            _ => {}
        }
    }
}

/// Run the `final_integrate` phase of all fixes for `step`.
pub fn final_integrate(fixes: &mut [Fix], p: &mut Particles, step: i64, dt: f64, domain: &Domain) {
    // the clumps' weight comes from the (single) gravity fix
    let gravity = fixes.iter().find_map(|f| match &f.kind {
        FixKind::Gravity(g) => Some(g.acc),
        _ => None,
    });
    for fix in fixes {
        match &mut fix.kind {
            FixKind::NveSphere => integrate::final_integrate(p, fix.group, dt),
            FixKind::NveDisc => integrate::final_integrate_with(
                p,
                fix.group,
                dt,
                crate::engine::planar::DISC_INERTIA,
            ),
            FixKind::Multisphere(ms) => {
                ms.calc_force(p, domain, gravity);
                ms.final_integrate(p, dt);
            }
            FixKind::Move(m) => m.final_integrate(p, fix.group, dt),
            FixKind::HeatGran(h) => h.final_integrate(p, fix.group, dt),
            FixKind::Style(s) => s.final_integrate(
                p,
                &FixStep {
                    group: fix.group,
                    step,
                    dt,
                    domain,
                    virial: &[],
                    contact: 0.0,
                },
            ),
            _ => {}
        }
    }
}

/// Group bits of all frozen particles (contacts treat them as infinitely heavy).
pub fn frozen_groups(fixes: &[Fix]) -> u32 {
    fixes
        .iter()
        .filter(|f| matches!(&f.kind, FixKind::Style(s) if s.holds_still()))
        .fold(0, |m, f| m | f.group)
}

#[cfg(test)]
mod tests;

/// `fix mesh/surface file F type T [scale|move|rotate ...] [curvature ...]`.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshFix {
    /// The file it was read from.
    pub file: String,
    /// The wall's atom type (material).
    pub wall_type: usize,
    /// The triangles after scale/move/rotate, with their geometry and topology (length).
    pub mesh: crate::engine::mesh::TriMesh,
    /// Velocities of each triangle's nodes (length/time), for moving meshes and conveyors.
    pub node_v: Option<Vec<[[f64; 3]; 3]>>,
    /// `surface_vel vx vy vz` (length/time): the conveyor velocity, projected per triangle.
    pub surface_vel: Option<[f64; 3]>,
    /// Defined as `mesh/surface/planar`.
    pub planar: bool,
    /// Nodes at the last refresh of a moving mesh (for the half-skin rebuild test).
    pub nodes_at_refresh: Vec<[[f64; 3]; 3]>,
    /// `mesh/surface/stress`: triangle forces, stresses and wear.
    pub stress: Option<crate::engine::mesh_stress::MeshStress>,
    /// `mesh/surface/stress/servo`: the controller that moves the mesh.
    pub servo: Option<Box<crate::engine::mesh_servo::MeshServo>>,
}

impl MeshFix {
    /// The triangles (nodes in STL order).
    pub fn triangles(&self) -> &[crate::io::stl::Triangle] {
        &self.mesh.nodes
    }

    /// LIGGGHTS's conveyor velocity of each node: the surface velocity with its component
    /// along the triangle normal removed, rescaled to the full speed.
    pub fn set_surface_velocity(&mut self) {
        let Some(v) = self.surface_vel else { return };
        let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let mut node_v = Vec::with_capacity(self.mesh.len());
        for n in &self.mesh.normal {
            let s = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
            let mut t = [v[0] - s * n[0], v[1] - s * n[1], v[2] - s * n[2]];
            let mag = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
            if mag > 0.0 {
                let inv = 1. / mag;
                t = t.map(|c| speed * (inv * c));
            }
            node_v.push([t; 3]);
        }
        self.node_v = Some(node_v);
    }
}

/// `fix insert/stream` as given, and its state once set up.
#[derive(Debug, Clone)]
pub struct StreamFix {
    /// Fix ID.
    pub id: String,
    /// Seed of the fix generator.
    pub seed: i32,
    /// The distribution fix's ID.
    pub distribution: String,
    /// The insertion face's triangles.
    pub triangles: Vec<crate::io::stl::Triangle>,
    /// The insertion face's mesh fix ID.
    pub face_id: String,
    /// `all_in yes`: whole particles inside the extruded face (planar faces only).
    pub all_in: bool,
    /// `extrude_length` (length), if given.
    pub extrude: Option<f64>,
    /// `insert_every`, if given.
    pub every: Option<i64>,
    /// `duration` (steps a particle travels in the extrusion zone), if given.
    pub duration: Option<i64>,
    /// `nparticles N` (Ok) or `mass M` (Err, mass units).
    pub total: Result<i64, f64>,
    /// `particlerate R` (Ok, 1/time) or `massrate R` (Err, mass/time).
    pub rate: Result<f64, f64>,
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
