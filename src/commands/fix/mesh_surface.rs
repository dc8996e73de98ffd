//! `fix mesh/surface[/planar|/stress|/stress/servo]`: a triangle mesh read from a file.

use super::insertion::{keyword, Family};
use super::mesh_servo::{ServoArgs, KEYWORDS as SERVO_KEYWORDS};
use crate::commands::fix::FixDef;
use crate::commands::specs::{
    arg, kw, style, Spec, Value, LENGTH, NUMBER, ON_OFF, VELOCITY, YES_NO,
};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::{FixStyle, MeshFix};
use crate::engine::mesh::MeshSettings;
use crate::engine::restart_fixes::MeshExtras;
use crate::io::stl::{MeshOp, Triangle};

/// The declared signature.
pub const SPEC: Spec = style("fix", "mesh/surface", "fix ID GROUP mesh/surface file FILE type T", &[kw("scale", &[arg("S", NUMBER)], "scale the mesh"), kw("move", &[arg("DX DY DZ", LENGTH)], "translate the mesh"), kw("rotate", &[arg("axis X Y Z angle A", Value::Real("angle in degrees"))], "rotate the mesh"), kw("curvature", &[arg("C", NUMBER)], "edge curvature tolerance"), kw("surface_vel", &[arg("VX VY VZ", VELOCITY)], "conveyor velocity of the surface"), kw("temperature", &[arg("T", NUMBER)], "fixed wall temperature (K) that fix heat/gran conducts into touching particles"), kw("verbose", &[arg("yes|no", YES_NO)], "report mesh checks"), kw("element_exclusion_list", &[arg("read|write FILE", Value::OneOf(&["read", "write"]))], "leave out the triangles listed in FILE (ASCII STL: the lines of their facet keywords; binary: their positions from 1), or create FILE for the elements the mesh checks remove")], "a triangle mesh from an STL or VTK file");

/// The declared signature of `mesh/surface/planar`.
pub const PLANAR: Spec = style(
    "fix",
    "mesh/surface/planar",
    "fix ID GROUP mesh/surface/planar file FILE type T",
    &[],
    "a planar triangle mesh",
);

/// The declared signature of `mesh/surface/stress`.
pub const STRESS: Spec = style(
    "fix",
    "mesh/surface/stress",
    "fix ID GROUP mesh/surface/stress file FILE type T",
    &[
        kw(
            "stress",
            &[arg("on|off", ON_OFF)],
            "sum forces and torques on the mesh",
        ),
        kw(
            "wear",
            &[arg("finnie|off", Value::OneOf(&["finnie", "off"]))],
            "Finnie wear of the mesh",
        ),
    ],
    "a triangle mesh that sums the forces on it",
);

/// The declared signature of `mesh/surface/stress/servo`.
pub const SERVO: Spec = style("fix", "mesh/surface/stress/servo", "fix ID GROUP mesh/surface/stress/servo file FILE type T ... com X Y Z ctrlPV force axis X Y Z target_val F vel_max V", &[kw("com", &[arg("X Y Z", LENGTH)], "centre of mass of the wall"), kw("ctrlPV", &[arg("force", Value::OneOf(&["force", "torque"]))], "the controlled value (torque: not supported yet)"), kw("axis", &[arg("X Y Z", NUMBER)], "direction of the motion"), kw("target_val", &[arg("F", Value::Real("force"))], "target force (negative: towards -axis), or v_name: an equal-style variable evaluated each step"), kw("vel_max", &[arg("V", VELOCITY)], "largest wall speed"), kw("kp", &[arg("K", NUMBER)], "proportional gain"), kw("ki", &[arg("K", NUMBER)], "integral gain"), kw("kd", &[arg("K", NUMBER)], "derivative gain"), kw("mode", &[arg("auto", Value::OneOf(&["auto"]))], "gain-scheduled proportional controller"), kw("ratio", &[arg("R", NUMBER)], "auto mode speed near particles, in smallest radii per step")], "a mesh wall a servo drives to a target force");

/// `fix ID GROUP mesh/surface[/planar] file F type T [scale f] [move x y z]
/// [rotate axis x y z angle deg] [curvature deg] [curvature_tolerant yes|no]
/// [precision p] [heal auto_remove_duplicates|no] [verbose yes|no]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    let style = fix.style;
    a.count(
        5..=usize::MAX,
        &format!("fix ID GROUP {style} file FILE type T ..."),
    )?;
    match a.word(3)? {
        "file" => {}
        "fix" => return Err(a.unsupported(3, "fix mesh/surface fix (meshes from another fix)")),
        _ => return Err(a.keyword_error(3, &["file", "fix"])),
    }
    let mut mesh = MeshArgs::new(a.word(4)?, style);
    let families: [Family<MeshArgs>; 2] = [MeshArgs::transform, MeshArgs::setting];
    let mut i = 5;
    while i < a.len() {
        let w = a.word(i)?;
        if let Some(used) = mesh.module_keyword(a, i, w)? {
            i += used;
            continue;
        }
        if let Some(at) = mesh.module_from {
            return Err(a.error(
                i,
                format!("Fix mesh/surface/stress: unknown keyword or wrong keyword order ('{w}' after the stress keyword at word {at})"),
            ));
        }
        mesh.check_order(a, i, w)?;
        match keyword(&mut mesh, &families, a, ctx, i, w)? {
            Some(used) => i += used,
            None => return Err(unknown(a, i, w)),
        }
    }
    let wall_type = mesh
        .wall_type
        .ok_or_else(|| a.error(2, "Fix mesh: must define type"))?;
    let (triangles, restored) = mesh.triangles(a, ctx)?;
    // LIGGGHTS's stress module, reading each reference point of a mesh already scaled,
    // moved or rotated
    if !mesh.ops.is_empty() {
        for _ in 0..mesh.references {
            ctx.say("WARNING: Mesh for fix mesh/surface/stress has been scaled, moved, or rotated.\nPlease note that values for 'reference_point' refer to the scaled, moved, or rotated configuration (./src/mesh_module_stress.cpp:104)\n");
        }
    }
    mesh.check(a, ctx, &triangles)?;
    mesh.assemble(a, wall_type, &triangles, restored)
}

/// A keyword no family knows: LIGGGHTS's keywords regolith does not run, else the known ones.
fn unknown(a: &Args, i: usize, w: &str) -> CommandError {
    if matches!(
        w,
        "mass_temperature" | "surface_ang_vel" | "region" | "extrude_planar" | "min_feature_length"
    ) {
        return a.unsupported(i, &format!("fix mesh/surface {w}"));
    }
    a.keyword_error(
        i,
        &[
            "type",
            "scale",
            "move",
            "rotate",
            "curvature",
            "curvature_tolerant",
            "precision",
            "heal",
            "verbose",
            "temperature",
            "surface_vel",
        ],
    )
}

/// The keywords of a `fix mesh/surface` style as given.
struct MeshArgs {
    /// The style name.
    style: String,
    /// The STL file as written.
    file: String,
    /// `type T`: the wall's atom type.
    wall_type: Option<usize>,
    /// `scale`, `move` and `rotate`, in order.
    ops: Vec<MeshOp>,
    /// `curvature`, `precision`, `curvature_tolerant`.
    settings: MeshSettings,
    /// `heal auto_remove_duplicates`.
    heal: bool,
    /// `surface_vel vx vy vz` (length/time).
    surface_vel: Option<[f64; 3]>,
    /// `temperature T`: the mesh's fixed temperature (K).
    temperature: Option<f64>,
    /// `element_exclusion_list read FILE`: the sorted triangle IDs left out.
    exclusion: Option<Vec<i64>>,
    /// `element_exclusion_list write FILE` (in a run): the file, created empty, that lists
    /// the triangles the checks of reading the mesh remove, and the word naming it.
    exclusion_write: Option<(std::path::PathBuf, usize)>,
    /// A keyword other than fix mesh's own has been read (fix mesh's own must come first).
    past_base: bool,
    /// The style is `mesh/surface/stress` or its servo.
    stress_style: bool,
    /// The style is `mesh/surface/stress/servo`.
    servo_style: bool,
    /// `stress on|off`.
    stress_on: bool,
    /// `wear finnie|off`.
    wear_on: bool,
    /// `reference_point x y z` (length).
    reference: [f64; 3],
    /// How many `reference_point` keywords were read.
    references: usize,
    /// The word the stress or servo module's keywords start at.
    module_from: Option<usize>,
    /// The servo module's keywords.
    servo: ServoArgs,
    /// The word the servo module's keywords start at.
    servo_from: Option<usize>,
}

impl MeshArgs {
    /// LIGGGHTS's defaults for `style` reading `file`.
    fn new(file: &str, style: &str) -> MeshArgs {
        MeshArgs {
            style: style.to_string(),
            file: file.to_string(),
            wall_type: None,
            ops: Vec::new(),
            settings: MeshSettings::default(),
            heal: false,
            surface_vel: None,
            temperature: None,
            exclusion: None,
            exclusion_write: None,
            past_base: false,
            stress_style: style.starts_with("mesh/surface/stress"),
            servo_style: style == "mesh/surface/stress/servo",
            stress_on: true,
            wear_on: false,
            reference: [0.0; 3],
            references: 0,
            module_from: None,
            servo: ServoArgs::default(),
            servo_from: None,
        }
    }

    /// A keyword of the stress module (after all mesh/surface keywords, as LIGGGHTS
    /// requires) or of the servo module (after the stress module's): the words it took.
    fn module_keyword(
        &mut self,
        a: &Args,
        mut i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        if self.servo_style && SERVO_KEYWORDS.contains(&w) {
            self.module_from.get_or_insert(i);
            self.servo_from.get_or_insert(i);
            return self.servo.parse(a, i).map(Some);
        }
        let module_keyword = matches!(w, "stress" | "wear" | "reference_point");
        if !(self.stress_style && module_keyword && self.servo_from.is_none()) {
            return Ok(None);
        }
        let from = i;
        self.module_from.get_or_insert(i);
        match w {
            "stress" => self.stress_on = a.word_in(i + 1, &["on", "off"])? == "on",
            "wear" => self.wear_on = a.word_in(i + 1, &["finnie", "off"])? == "finnie",
            _ => {
                self.reference = [a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?];
                self.references += 1;
                i += 2;
            }
        }
        i += 2;
        Ok(Some(i - from))
    }

    /// `scale`, `move` and `rotate`.
    fn transform(
        &mut self,
        a: &Args,
        _ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        Ok(Some(match w {
            "scale" => {
                self.ops.push(MeshOp::Scale(a.real(i + 1)?));
                2
            }
            "move" => {
                self.ops.push(MeshOp::Move([
                    a.real(i + 1)?,
                    a.real(i + 2)?,
                    a.real(i + 3)?,
                ]));
                4
            }
            "rotate" => {
                if a.word(i + 1)? != "axis" || a.word(i + 5)? != "angle" {
                    return Err(a
                        .error(i, "Illegal fix mesh/surface command")
                        .with_help("expected: rotate axis AX AY AZ angle DEGREES"));
                }
                self.ops.push(MeshOp::Rotate {
                    axis: [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?],
                    degrees: a.real(i + 6)?,
                });
                7
            }
            _ => return Ok(None),
        }))
    }

    /// LIGGGHTS's fix mesh reads its own keywords first; once another follows, they are
    /// refused.
    fn check_order(&mut self, a: &Args, i: usize, w: &str) -> Result<(), CommandError> {
        let base = matches!(
            w,
            "type"
                | "verbose"
                | "region"
                | "heal"
                | "precision"
                | "min_feature_length"
                | "element_exclusion_list"
        );
        if !base {
            self.past_base = true;
        } else if self.past_base {
            return Err(a.error(
                i,
                format!(
                    "Fix {} (id {}): unknown keyword or wrong keyword order: {w}",
                    self.style,
                    a.word(0)?
                ),
            ));
        }
        Ok(())
    }

    /// The mesh's settings: `type`, `curvature`, `precision`, `curvature_tolerant`,
    /// `verbose`, `heal`, `surface_vel`.
    fn setting(
        &mut self,
        a: &Args,
        ctx: &Ctx,
        i: usize,
        w: &str,
    ) -> Result<Option<usize>, CommandError> {
        match w {
            "type" => {
                let t = a.int(i + 1)?;
                if t < 1 || t > ctx.sim.ntypes as i64 {
                    return Err(a.error(i + 1, "Fix mesh: type is out of range"));
                }
                self.wall_type = Some(t as usize);
            }
            "curvature" => {
                let v = a.real(i + 1)?;
                if v <= 0.0 || v > 60.0 {
                    return Err(a.error(i + 1, "Fix mesh: 0° < curvature < 60° required"));
                }
                self.settings.curvature = (v * std::f64::consts::PI / 180.).cos();
            }
            "precision" => {
                let v = a.real(i + 1)?;
                if v <= 0.0 || v > 0.001 {
                    return Err(a.error(i + 1, "Fix mesh: 0 < precision < 0.001 required"));
                }
                self.settings.precision = v;
            }
            "curvature_tolerant" => {
                self.settings.curvature_tolerant = a.word_in(i + 1, &["yes", "no"])? == "yes";
            }
            // only LIGGGHTS's extra screen output
            "verbose" => {
                a.word_in(i + 1, &["yes", "no"])?;
            }
            "heal" => {
                self.heal = a.word_in(i + 1, &["auto_remove_duplicates", "no"])? != "no";
            }
            "temperature" => self.temperature = Some(a.real(i + 1)?),
            "surface_vel" => {
                self.surface_vel = Some([a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?]);
                return Ok(Some(4));
            }
            "element_exclusion_list" => {
                self.exclusion = Some(exclusion_list(a, i, ctx)?);
                if a.word(i + 1)? == "write" && ctx.sys.mode == crate::lang::system::Mode::Run {
                    self.exclusion_write = Some((std::path::PathBuf::from(a.word(i + 2)?), i + 2));
                }
                return Ok(Some(3));
            }
            _ => return Ok(None),
        }
        Ok(Some(2))
    }

    /// The triangles: from a restart file's state of this fix (with the stress module's
    /// extras), else read from the STL file, transformed and healed.
    fn triangles(
        &self,
        a: &Args,
        ctx: &mut Ctx,
    ) -> Result<(Vec<Triangle>, Option<MeshExtras>), CommandError> {
        let (file, style) = (&self.file, self.style.as_str());
        let path = ctx.sys.resolve(file).to_string_lossy().into_owned();
        let stored = ctx
            .sim
            .held_fix_state(a.word(0)?, style)
            .map(<[u8]>::to_vec);
        if let Some(bytes) = stored {
            // LIGGGHTS takes the nodes from the restart file (scale/move/rotate act on an
            // empty mesh); the file must still open
            if std::fs::File::open(&path).is_err() {
                return Err(a.file_error(
                    4,
                    format!("Cannot open mesh file {file}. FYI: This file is required, but data will be taken from restart file"),
                ));
            }
            ctx.say(&format!("INFO: mesh file ({file}) is required, but data will be taken from restart file (./src/fix_mesh.cpp:417)\n"));
            // the stress module adds each triangle's wear (when on) and the reference point
            if self.servo_style {
                return Err(a.unsupported(2, "fix mesh/surface/stress/servo from a restart file"));
            }
            let global = crate::engine::restart_fixes::STRESS_GLOBAL_SIZE;
            let (element, global) = match (self.stress_style, self.wear_on) {
                (true, true) => (1, global),
                (true, false) => (0, global),
                _ => (0, 0),
            };
            let (t, extras) =
                crate::engine::restart_fixes::mesh_from_state(&bytes, element, global)
                    .map_err(|m| a.error(2, m))?;
            return Ok((t, Some(extras)));
        }
        // LIGGGHTS prints this line on the screen only
        if ctx.sys.mode == crate::lang::system::Mode::Run {
            ctx.out.screen(&format!(
                "\nReading STL file '{file}' (mesh processing step 1/3) \n"
            ));
        }
        let (t, ids, ascii) = crate::io::stl::read_with_ids(&path).map_err(|m| match m {
            // the file as the deck names it, as LIGGGHTS says it
            crate::io::error::StlError::Open { source, .. } => {
                a.file_error(4, format!("Cannot open mesh file {file}: {source}"))
            }
            other => a.error(4, &other),
        })?;
        let mut t = match &self.exclusion {
            Some(list) => crate::io::stl::exclude(t, &ids, list, ascii),
            None => t,
        };
        crate::io::stl::transform(&mut t, &self.ops);
        if let Some((out, word)) = &self.exclusion_write {
            self.write_exclusions(a, (out, *word), &t, &ids)?;
        }
        if self.heal {
            t = self.healed(t);
        }
        Ok((t, None))
    }

    /// `element_exclusion_list write`: as LIGGGHTS adds each triangle of the mesh it reads,
    /// it lists in the file the ID (its line in an ASCII file) of one with an angle below
    /// the hard limit, the triangles a run would refuse (`triangles`, all of the file's,
    /// transformed, and their `ids`).
    fn write_exclusions(
        &self,
        a: &Args,
        (out, word): (&std::path::Path, usize),
        triangles: &[Triangle],
        ids: &[usize],
    ) -> Result<(), CommandError> {
        let mesh = crate::engine::mesh::TriMesh::new(triangles, self.settings);
        let lines: String = (0..mesh.len())
            .filter(|&t| mesh.below_hard_angle(t))
            .map(|t| format!("{}\n", ids[t]))
            .collect();
        if lines.is_empty() {
            return Ok(());
        }
        crate::io::write_atomically(&out.to_string_lossy(), lines.as_bytes()).map_err(|_| {
            a.file_error(
                word,
                "Fix mesh: can not open file for 'element_exclusion_list' for writing",
            )
        })
    }

    /// `heal auto_remove_duplicates`: a triangle with the nodes of an earlier one goes.
    fn healed(&self, triangles: Vec<Triangle>) -> Vec<Triangle> {
        let p = self.settings.precision;
        let same = |x: [f64; 3], y: [f64; 3]| (0..3).all(|k| (x[k] - y[k]).abs() < p);
        let mut kept: Vec<Triangle> = Vec::with_capacity(triangles.len());
        for t in triangles {
            let dup = kept
                .iter()
                .any(|u| t.iter().all(|n| u.iter().any(|m| same(*n, *m))));
            if !dup {
                kept.push(t);
            }
        }
        kept
    }

    /// LIGGGHTS's mesh checks (warnings said), and a planar style's flatness.
    fn check(&self, a: &Args, ctx: &mut Ctx, triangles: &[Triangle]) -> Result<(), CommandError> {
        let d = &ctx.sim.domain;
        let size = (0..3).map(|k| d.length(k)).fold(0.0, f64::max);
        for w in
            crate::io::stl::check(triangles, &self.file, Some(size)).map_err(|m| a.error(4, &m))?
        {
            ctx.say(&format!("WARNING: {w}\n"));
        }
        if self.style == "mesh/surface/planar" {
            let n0 = crate::io::stl::normal(&triangles[0]);
            let p0 = triangles[0][0];
            let off = |v: [f64; 3]| (0..3).map(|k| (v[k] - p0[k]) * n0[k]).sum::<f64>().abs();
            let scale = size.max(f64::MIN_POSITIVE);
            if triangles.iter().flatten().any(|v| off(*v) > 1e-8 * scale) {
                return Err(a.error(4, "Fix mesh/surface/planar: the mesh is not planar"));
            }
        }
        Ok(())
    }

    /// The fix: the mesh with its stress and servo modules.
    fn assemble(
        self,
        a: &Args,
        wall_type: usize,
        triangles: &[Triangle],
        restored: Option<MeshExtras>,
    ) -> Result<Box<dyn FixStyle>, CommandError> {
        let mut fix = MeshFix {
            file: self.file,
            wall_type,
            mesh: crate::engine::mesh::TriMesh::new(triangles, self.settings),
            node_v: None,
            surface_vel: self.surface_vel,
            temperature: self.temperature,
            planar: self.style == "mesh/surface/planar",
            nodes_at_refresh: Vec::new(),
            stress: None,
            servo: None,
            announced: false,
        };
        if self.stress_style {
            let mut st = crate::engine::mesh_stress::MeshStress::new(
                fix.mesh.len(),
                self.stress_on,
                self.wear_on,
                self.reference,
            );
            if let Some(extras) = restored {
                if self.wear_on {
                    st.wear = extras.element.iter().map(|e| e[0]).collect();
                }
                st.reference = crate::engine::restart_fixes::stress_reference(&extras.global);
            }
            fix.stress = Some(st);
        }
        if self.servo_style {
            let s = self.servo.build(a, 2)?;
            if let Some(st) = fix.stress.as_mut() {
                if !st.stress {
                    return Err(a.error(2, "stress = 'on' required"));
                }
                st.reference = s.xcm;
            }
            fix.node_v = Some(vec![[[0.0; 3]; 3]; fix.mesh.len()]);
            fix.servo = Some(Box::new(s));
        }
        fix.set_surface_velocity();
        Ok(Box::new(fix))
    }
}

/// `element_exclusion_list read|write FILE` at word `i`: the sorted triangle IDs to leave out
/// (`read`), or none (`write`: LIGGGHTS creates the file at once and lists in it the elements
/// its mesh checks remove, which a mesh those checks pass leaves empty).
fn exclusion_list(a: &Args, i: usize, ctx: &Ctx) -> Result<Vec<i64>, CommandError> {
    let mode = a.word(i + 1)?;
    if mode != "read" && mode != "write" {
        // LIGGGHTS's own spelling
        return Err(a.error(
            i + 1,
            format!(
                "Fix {} (id {}): expecing 'read' or 'write' after 'element_exclusion_list'",
                a.word(2)?,
                a.word(0)?
            ),
        ));
    }
    let name = a.word(i + 2)?;
    if mode == "write" {
        if ctx.sys.mode != crate::lang::system::Mode::Run {
            return Ok(Vec::new());
        }
        std::fs::File::create(name).map_err(|_| {
            a.file_error(
                i + 2,
                "Fix mesh: can not open file for 'element_exclusion_list' for writing",
            )
        })?;
        return Ok(Vec::new());
    }
    let text = std::fs::read(ctx.sys.resolve(name)).map_err(|_| {
        a.file_error(
            i + 2,
            "Fix mesh: can not open file for 'element_exclusion_list' for reading",
        )
    })?;
    let mut list = Vec::new();
    // one ID a line, read as LIGGGHTS's integer parser reads it (digits and signs only)
    for line in String::from_utf8_lossy(&text).lines() {
        let word = line.trim_matches(|c: char| c.is_ascii_whitespace());
        if !word
            .chars()
            .all(|c| c.is_ascii_digit() || c == '-' || c == '+')
        {
            return Err(a.error(
                i + 2,
                "Expected integer parameter in input script or data file",
            ));
        }
        list.push(crate::util::numbers::atol(word));
    }
    list.sort_unstable();
    Ok(list)
}

/// A triangle mesh: no phase of its own (walls, insertion faces, movers and the stress and
/// servo passes read and change it by type,
/// [`FixKind::mesh`](crate::engine::fixes::FixKind::mesh)).
impl FixStyle for MeshFix {
    fn name(&self) -> &str {
        match (&self.servo, &self.stress, self.planar) {
            (Some(_), _, _) => "mesh/surface/stress/servo",
            (None, Some(_), _) => "mesh/surface/stress",
            (None, None, true) => "mesh/surface/planar",
            (None, None, false) => "mesh/surface",
        }
    }

    fn array_unsupported(&self) -> bool {
        true
    }
}
