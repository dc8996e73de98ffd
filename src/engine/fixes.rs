//! Fixes that act on particles each step, in LIGGGHTS's phases: `initial_integrate`
//! (nve/sphere, move), `post_force` (gravity, setforce, addforce, walls) and
//! `final_integrate`. Within a phase fixes act in the order they were defined; the styles
//! written as modules ([`FixStyle`], [`FixKind::Style`]) take their turn among the others.

use crate::engine::domain::Domain;
use crate::engine::error::EngineError;
use crate::engine::particles::Particles;

mod ave_time;
mod check_timestep;
mod meshes;
mod motion;
mod stream;
mod style;
mod walls;

pub use ave_time::{AveInput, AveMode, AveSchedule, AveTime};
pub use check_timestep::CheckTimestep;
pub use meshes::{move_meshes, MeshFix};
pub use motion::{Motion, Move};
pub use stream::StreamFix;
pub use style::{
    FixInit, FixStep, FixStyle, ForcePass, PairInit, PerAtomShape, RestoreError, SetupPass,
    StepInputs,
};
pub use walls::{
    dry_history_width, mesh_wall_contacts, mesh_wall_force, refresh_trackers, MeshWallFix, WallFix,
};

/// What a fix does.
pub enum FixKind {
    /// A style written as a module (see [`FixStyle`]): its hooks run in each phase.
    Style(Box<dyn FixStyle>),
    /// The fix's state is out of its slot while one of its own hooks runs with the fix
    /// list or the whole simulation at hand: no phase runs it and its values cannot be
    /// read. A slot holds this only during such a hook ([`lend_style`]).
    Lent,
}

impl FixKind {
    /// The triangle mesh of a `fix mesh/surface...` (None: a fix of another style).
    pub fn mesh(&self) -> Option<&MeshFix> {
        self.style_as()
    }

    /// [`FixKind::mesh`], to change.
    pub fn mesh_mut(&mut self) -> Option<&mut MeshFix> {
        self.style_as_mut()
    }

    /// The state of a module fix style (see [`FixStyle::as_any`]) as type `T` (None: a fix
    /// of another style or kind).
    pub fn style_as<T: 'static>(&self) -> Option<&T> {
        match self {
            FixKind::Style(s) => s.as_any()?.downcast_ref(),
            _ => None,
        }
    }

    /// [`FixKind::style_as`], to change.
    pub fn style_as_mut<T: 'static>(&mut self) -> Option<&mut T> {
        match self {
            FixKind::Style(s) => s.as_any_mut()?.downcast_mut(),
            _ => None,
        }
    }

    /// The per-atom property of a `fix property/atom` (None: a fix of another style).
    pub fn property_atom(&self) -> Option<&crate::engine::heat::PropertyAtom> {
        self.style_as()
    }

    /// [`FixKind::property_atom`], to change.
    pub fn property_atom_mut(&mut self) -> Option<&mut crate::engine::heat::PropertyAtom> {
        self.style_as_mut()
    }

    /// The motion of a `fix move/mesh` (None: a fix of another style).
    pub fn mover(&self) -> Option<&crate::engine::mesh_motion::MoveMesh> {
        self.style_as()
    }

    /// [`FixKind::mover`], to change.
    pub fn mover_mut(&mut self) -> Option<&mut crate::engine::mesh_motion::MoveMesh> {
        self.style_as_mut()
    }

    /// The insertion of a `fix insert/stream` (None: a fix of another style).
    pub fn stream(&self) -> Option<&StreamFix> {
        self.style_as()
    }

    /// [`FixKind::stream`], to change.
    pub fn stream_mut(&mut self) -> Option<&mut StreamFix> {
        self.style_as_mut()
    }

    /// The insertion of a `fix insert/pack` or `insert/rate/region` (None: a fix of another
    /// style).
    pub fn insert_pack(&self) -> Option<&crate::engine::insert::InsertPack> {
        self.style_as()
    }

    /// [`FixKind::insert_pack`], to change.
    pub fn insert_pack_mut(&mut self) -> Option<&mut crate::engine::insert::InsertPack> {
        self.style_as_mut()
    }

    /// The sphere of a `fix particletemplate/sphere` (None: a fix of another style).
    pub fn template(&self) -> Option<&crate::engine::insert::Template> {
        self.style_as()
    }

    /// The mix of a `fix particledistribution/discrete...` (None: a fix of another style).
    pub fn distribution(&self) -> Option<&crate::engine::insert::Distribution> {
        self.style_as()
    }

    /// [`FixKind::distribution`], to change.
    pub fn distribution_mut(&mut self) -> Option<&mut crate::engine::insert::Distribution> {
        self.style_as_mut()
    }

    /// The granular mesh walls of a `fix wall/gran ... mesh` (None: a fix of another style).
    pub fn mesh_wall(&self) -> Option<&MeshWallFix> {
        self.style_as()
    }

    /// [`FixKind::mesh_wall`], to change.
    pub fn mesh_wall_mut(&mut self) -> Option<&mut MeshWallFix> {
        self.style_as_mut()
    }

    /// The contact model a `fix wall/gran` names, of primitive or mesh walls (None: a fix of
    /// another style).
    pub fn wall_selection(&self) -> Option<&crate::engine::granular::Selection> {
        if let Some(w) = self.mesh_wall() {
            return Some(&w.selection);
        }
        Some(&self.primitive_wall()?.selection)
    }

    /// The primitive wall of a `fix wall/gran ... primitive` (None: a fix of another style).
    pub fn primitive_wall(&self) -> Option<&WallFix> {
        self.style_as()
    }

    /// Can the fix evaluate variables or computes inside a step (so per-atom computes must
    /// be current on every step)? A lent slot answers no.
    pub fn may_read_computes(&self) -> bool {
        match self {
            FixKind::Style(s) => s.reads_computes(),
            FixKind::Lent => false,
        }
    }
}

/// The mesh of the `fix mesh/surface...` with ID `id` among `fixes` (None: no mesh fix has
/// that ID).
pub fn mesh_named<'a>(fixes: &'a [Fix], id: &str) -> Option<&'a MeshFix> {
    fixes.iter().find(|f| f.id == id)?.kind.mesh()
}

/// [`mesh_named`], to change.
pub fn mesh_named_mut<'a>(fixes: &'a mut [Fix], id: &str) -> Option<&'a mut MeshFix> {
    fixes.iter_mut().find(|f| f.id == id)?.kind.mesh_mut()
}

/// Every `fix mesh/surface...` among `fixes`, in definition order, with its fix.
pub fn meshes(fixes: &[Fix]) -> impl Iterator<Item = (&Fix, &MeshFix)> {
    fixes.iter().filter_map(|f| Some((f, f.kind.mesh()?)))
}

/// The `fix property/atom` fixes among `fixes` whose property (variable name) is `name`, in
/// definition order.
pub fn properties_named<'a>(
    fixes: &'a [Fix],
    name: &'a str,
) -> impl DoubleEndedIterator<Item = (&'a Fix, &'a crate::engine::heat::PropertyAtom)> {
    fixes
        .iter()
        .filter_map(move |f| Some((f, f.kind.property_atom().filter(|pa| pa.name == name)?)))
}

/// The index among `fixes` of the fix with ID `id`, and its particle distribution (None:
/// no fix has that ID; Some((k, None)): fix `k` is not a `particledistribution/discrete...`).
pub fn distribution_named<'a>(
    fixes: &'a [Fix],
    id: &str,
) -> Option<(usize, Option<&'a crate::engine::insert::Distribution>)> {
    let k = fixes.iter().position(|f| f.id == id)?;
    Some((k, fixes[k].kind.distribution()))
}

/// Whether a `fix move/mesh` among `fixes` moves mesh `id`.
pub fn moves_mesh(fixes: &[Fix], id: &str) -> bool {
    fixes
        .iter()
        .any(|f| f.kind.mover().is_some_and(|mv| mv.mesh == id))
}

/// The first `fix wall/gran ... mesh` among `fixes` whose meshes include mesh `id`: its
/// index among `fixes`, its walls, and the mesh's index among its meshes.
pub fn first_wall_on<'a>(fixes: &'a [Fix], id: &str) -> Option<(usize, &'a MeshWallFix, usize)> {
    fixes.iter().enumerate().find_map(|(k, f)| {
        let w = f.kind.mesh_wall()?;
        Some((k, w, w.meshes.iter().position(|m| m == id)?))
    })
}

/// Run `hook` on the module fix style `fixes[k]` with the fix list at hand, the fix's slot
/// [`FixKind::Lent`] meanwhile (None: fix `k` is not a module style).
pub fn lend_style<R>(
    fixes: &mut [Fix],
    k: usize,
    hook: impl FnOnce(&mut dyn FixStyle, &mut [Fix]) -> R,
) -> Option<R> {
    if !matches!(fixes[k].kind, FixKind::Style(_)) {
        return None;
    }
    let FixKind::Style(mut style) = std::mem::replace(&mut fixes[k].kind, FixKind::Lent) else {
        unreachable!("checked above")
    };
    let result = hook(&mut *style, fixes);
    fixes[k].kind = FixKind::Style(style);
    Some(result)
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
    /// Its time in the current run (`modify_timing`).
    pub clock: crate::engine::fix_timing::FixClock,
}

/// Run the `initial_integrate` phase of all fixes.
pub fn initial_integrate(
    fixes: &mut [Fix],
    p: &mut Particles,
    step: i64,
    dt: f64,
    domain: &Domain,
) {
    for k in 0..fixes.len() {
        let clock = fixes[k].clock.start();
        let at = FixStep::plain(fixes[k].group, step, dt, domain);
        match &mut fixes[k].kind {
            FixKind::Style(s) if s.among_fixes() => {
                lend_style(fixes, k, |s, fixes| {
                    s.initial_integrate_among(fixes, p, &at)
                });
            }
            FixKind::Style(s) => s.initial_integrate(p, &at),
            _ => {}
        }
        fixes[k].clock.stop(clock);
    }
}

/// A value a fix reads each step (`fix setforce`/`addforce` components, `fix move variable`
/// displacements and velocities, `fix adapt` diameters), in the fix's units.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum ForceValue {
    /// `NULL` (not given: the component is left alone).
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
    let pass = ForcePass {
        update,
        list,
        moving_skin,
    };
    for k in 0..fixes.len() {
        let clock = fixes[k].clock.start();
        let step = FixStep::plain(fixes[k].group, at.0, dt, at.1);
        match &mut fixes[k].kind {
            FixKind::Style(s) if s.among_fixes() => {
                lend_style(fixes, k, |s, fixes| {
                    s.post_force_among(fixes, p, &step, &pass)
                });
            }
            FixKind::Style(s) => s.post_force(p, &step),
            _ => {}
        }
        fixes[k].clock.stop(clock);
    }
}

/// Run the `final_integrate` phase of all fixes for `step`.
pub fn final_integrate(fixes: &mut [Fix], p: &mut Particles, step: i64, dt: f64, domain: &Domain) {
    for k in 0..fixes.len() {
        let clock = fixes[k].clock.start();
        let at = FixStep::plain(fixes[k].group, step, dt, domain);
        match &mut fixes[k].kind {
            FixKind::Style(s) if s.among_fixes() => {
                lend_style(fixes, k, |s, fixes| s.final_integrate_among(fixes, p, &at));
            }
            FixKind::Style(s) => s.final_integrate(p, &at),
            _ => {}
        }
        fixes[k].clock.stop(clock);
    }
}

/// The uniform acceleration of the first fix among `fixes` that adds one (`fix gravity`;
/// length/time^2), which clumps take as their weight.
pub fn gravity(fixes: &[Fix]) -> Option<[f64; 3]> {
    fixes.iter().find_map(|f| match &f.kind {
        FixKind::Style(s) => s.acceleration(),
        _ => None,
    })
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

/// The largest bounding radius of the first `particledistribution/discrete*` fix among
/// `fixes` (length; 0 without one): LIGGGHTS finds the distribution by its style's prefix.
pub fn first_distribution_bound(fixes: &[Fix]) -> f64 {
    fixes
        .iter()
        .find_map(|f| Some(f.kind.distribution()?.max_radius))
        .unwrap_or(0.0)
}
