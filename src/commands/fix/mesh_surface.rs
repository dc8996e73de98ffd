//! `fix mesh/surface[/planar|/stress|/stress/servo]`: a triangle mesh read from a file.

use crate::commands::fix::FixDef;
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::fixes::FixKind;

/// `fix ID GROUP mesh/surface[/planar] file F type T [scale f] [move x y z]
/// [rotate axis x y z angle deg] [curvature deg] [curvature_tolerant yes|no]
/// [precision p] [heal auto_remove_duplicates|no] [verbose yes|no]`.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<FixKind, CommandError> {
    let style = fix.style;
    use crate::io::stl::MeshOp;
    a.count(
        5..=usize::MAX,
        &format!("fix ID GROUP {style} file FILE type T ..."),
    )?;
    match a.word(3)? {
        "file" => {}
        "fix" => return Err(a.unsupported(3, "fix mesh/surface fix (meshes from another fix)")),
        _ => return Err(a.keyword_error(3, &["file", "fix"])),
    }
    let file = a.word(4)?.to_string();
    let (mut wall_type, mut ops) = (None, Vec::new());
    let mut settings = crate::engine::mesh::MeshSettings::default();
    let (mut heal, mut surface_vel) = (false, None);
    let mut exclusion: Option<Vec<i64>> = None;
    let mut past_base = false;
    // the stress module's keywords (after all mesh/surface keywords, as LIGGGHTS requires)
    let (mut stress_on, mut wear_on, mut reference) = (true, false, [0.0; 3]);
    let mut module_from = None;
    let module_keyword = |w: &str| matches!(w, "stress" | "wear" | "reference_point");
    let stress_style = style.starts_with("mesh/surface/stress");
    let servo_style = style == "mesh/surface/stress/servo";
    // the servo module's keywords (after the stress module's)
    let mut servo = super::mesh_servo::ServoArgs::default();
    let mut servo_from = None;
    let mut i = 5;
    while i < a.len() {
        let w = a.word(i)?;
        if servo_style && super::mesh_servo::KEYWORDS.contains(&w) {
            module_from.get_or_insert(i);
            servo_from.get_or_insert(i);
            i += servo.parse(a, i)?;
            continue;
        }
        if stress_style && module_keyword(w) && servo_from.is_none() {
            module_from.get_or_insert(i);
            match w {
                "stress" => stress_on = a.word_in(i + 1, &["on", "off"])? == "on",
                "wear" => wear_on = a.word_in(i + 1, &["finnie", "off"])? == "finnie",
                _ => {
                    reference = [a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?];
                    i += 2;
                }
            }
            i += 2;
            continue;
        }
        if let Some(at) = module_from {
            return Err(a.error(
                i,
                format!("Fix mesh/surface/stress: unknown keyword or wrong keyword order ('{w}' after the stress keyword at word {at})"),
            ));
        }
        // LIGGGHTS's fix mesh reads its own keywords first; once another follows, they are
        // refused
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
            past_base = true;
        } else if past_base {
            return Err(a.error(
                i,
                format!(
                    "Fix {style} (id {}): unknown keyword or wrong keyword order: {w}",
                    a.word(0)?
                ),
            ));
        }
        match w {
            "type" => {
                let t = a.int(i + 1)?;
                if t < 1 || t > ctx.sim.ntypes as i64 {
                    return Err(a.error(i + 1, "Fix mesh: type is out of range"));
                }
                wall_type = Some(t as usize);
                i += 2;
            }
            "scale" => {
                ops.push(MeshOp::Scale(a.real(i + 1)?));
                i += 2;
            }
            "move" => {
                ops.push(MeshOp::Move([
                    a.real(i + 1)?,
                    a.real(i + 2)?,
                    a.real(i + 3)?,
                ]));
                i += 4;
            }
            "rotate" => {
                if a.word(i + 1)? != "axis" || a.word(i + 5)? != "angle" {
                    return Err(a
                        .error(i, "Illegal fix mesh/surface command")
                        .with_help("expected: rotate axis AX AY AZ angle DEGREES"));
                }
                ops.push(MeshOp::Rotate {
                    axis: [a.real(i + 2)?, a.real(i + 3)?, a.real(i + 4)?],
                    degrees: a.real(i + 6)?,
                });
                i += 7;
            }
            "curvature" => {
                let v = a.real(i + 1)?;
                if v <= 0.0 || v > 60.0 {
                    return Err(a.error(i + 1, "Fix mesh: 0° < curvature < 60° required"));
                }
                settings.curvature = (v * std::f64::consts::PI / 180.).cos();
                i += 2;
            }
            "precision" => {
                let v = a.real(i + 1)?;
                if v <= 0.0 || v > 0.001 {
                    return Err(a.error(i + 1, "Fix mesh: 0 < precision < 0.001 required"));
                }
                settings.precision = v;
                i += 2;
            }
            "curvature_tolerant" => {
                settings.curvature_tolerant = a.word_in(i + 1, &["yes", "no"])? == "yes";
                i += 2;
            }
            // only LIGGGHTS's extra screen output
            "verbose" => {
                a.word_in(i + 1, &["yes", "no"])?;
                i += 2;
            }
            "heal" => {
                heal = a.word_in(i + 1, &["auto_remove_duplicates", "no"])? != "no";
                i += 2;
            }
            "surface_vel" => {
                surface_vel = Some([a.real(i + 1)?, a.real(i + 2)?, a.real(i + 3)?]);
                i += 4;
            }
            "element_exclusion_list" => {
                exclusion = Some(exclusion_list(a, i, ctx)?);
                i += 3;
            }
            w @ ("temperature" | "mass_temperature" | "surface_ang_vel" | "region"
            | "extrude_planar" | "min_feature_length") => {
                return Err(a.unsupported(i, &format!("fix mesh/surface {w}")))
            }
            _ => {
                return Err(a.keyword_error(
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
                ))
            }
        }
    }
    let wall_type = wall_type.ok_or_else(|| a.error(2, "Fix mesh: must define type"))?;
    let path = ctx.sys.resolve(&file).to_string_lossy().into_owned();
    let stored = ctx
        .sim
        .held_fix_state(a.word(0)?, style)
        .map(<[u8]>::to_vec);
    let mut restored = None;
    let mut triangles = if let Some(bytes) = stored {
        // LIGGGHTS takes the nodes from the restart file (scale/move/rotate act on an empty
        // mesh); the file must still open
        if std::fs::File::open(&path).is_err() {
            return Err(a.file_error(
                4,
                format!("Cannot open mesh file {file}. FYI: This file is required, but data will be taken from restart file"),
            ));
        }
        ctx.say(&format!("INFO: mesh file ({file}) is required, but data will be taken from restart file (./src/fix_mesh.cpp:417)\n"));
        // the stress module adds each triangle's wear (when on) and the reference point
        if servo_style {
            return Err(a.unsupported(2, "fix mesh/surface/stress/servo from a restart file"));
        }
        let stress = stress_style;
        let (element, global) = match (stress, wear_on) {
            (true, true) => (1, 3),
            (true, false) => (0, 3),
            _ => (0, 0),
        };
        let (t, extras) = crate::engine::restart_fixes::mesh_from_state(&bytes, element, global)
            .map_err(|m| a.error(2, m))?;
        restored = Some(extras);
        t
    } else {
        ctx.say(&format!(
            "\nReading STL file '{file}' (mesh processing step 1/3) \n"
        ));
        let (t, ids, ascii) = crate::io::stl::read_with_ids(&path).map_err(|m| a.error(4, &m))?;
        let mut t = match &exclusion {
            Some(list) => crate::io::stl::exclude(t, &ids, list, ascii),
            None => t,
        };
        crate::io::stl::transform(&mut t, &ops);
        t
    };
    if heal && restored.is_none() {
        // `heal auto_remove_duplicates`: a triangle with the nodes of an earlier one goes
        let p = settings.precision;
        let same = |x: [f64; 3], y: [f64; 3]| (0..3).all(|k| (x[k] - y[k]).abs() < p);
        let mut kept: Vec<crate::io::stl::Triangle> = Vec::with_capacity(triangles.len());
        for t in triangles {
            let dup = kept
                .iter()
                .any(|u| t.iter().all(|n| u.iter().any(|m| same(*n, *m))));
            if !dup {
                kept.push(t);
            }
        }
        triangles = kept;
    }
    let d = &ctx.sim.domain;
    let size = (0..3).map(|k| d.length(k)).fold(0.0, f64::max);
    for w in crate::io::stl::check(&triangles, &file, Some(size)).map_err(|m| a.error(4, &m))? {
        ctx.say(&format!("WARNING: {w}\n"));
    }
    if style == "mesh/surface/planar" {
        let n0 = crate::io::stl::normal(&triangles[0]);
        let p0 = triangles[0][0];
        let off = |v: [f64; 3]| (0..3).map(|k| (v[k] - p0[k]) * n0[k]).sum::<f64>().abs();
        let scale = size.max(f64::MIN_POSITIVE);
        if triangles.iter().flatten().any(|v| off(*v) > 1e-8 * scale) {
            return Err(a.error(4, "Fix mesh/surface/planar: the mesh is not planar"));
        }
    }
    let mut fix = crate::engine::fixes::MeshFix {
        file,
        wall_type,
        mesh: crate::engine::mesh::TriMesh::new(&triangles, settings),
        node_v: None,
        surface_vel,
        planar: style == "mesh/surface/planar",
        nodes_at_refresh: Vec::new(),
        stress: None,
        servo: None,
    };
    if stress_style {
        let mut st = crate::engine::mesh_stress::MeshStress::new(
            fix.mesh.len(),
            stress_on,
            wear_on,
            reference,
        );
        if let Some(extras) = restored {
            if wear_on {
                st.wear = extras.element.iter().map(|e| e[0]).collect();
            }
            st.reference = [extras.global[0], extras.global[1], extras.global[2]];
        }
        fix.stress = Some(st);
    }
    if servo_style {
        let s = servo.build(a, 2)?;
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
    Ok(FixKind::Mesh(Box::new(fix)))
}

/// `element_exclusion_list read|write FILE` at word `i`: the sorted triangle IDs to leave out
/// (`read`), or none (`write`: LIGGGHTS creates the file at once and lists in it the elements
/// its mesh checks remove, which a mesh those checks pass leaves empty).
fn exclusion_list(a: &Args, i: usize, ctx: &mut Ctx) -> Result<Vec<i64>, CommandError> {
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
