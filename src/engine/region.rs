//! Geometric regions (`region` command): block, cylinder, sphere, cone, plane, prism and
//! their intersections and unions, with `side in/out`. Inside tests follow LIGGGHTS
//! exactly, boundaries included (a point on a block face is inside).

use crate::engine::error::EngineError;
use crate::util::numbers::numeric;

/// Region styles regolith runs (`region ID STYLE ...`); others are "not supported yet".
pub const STYLES: &[&str] = &[
    "block",
    "cone",
    "cylinder",
    "intersect",
    "mesh/tet",
    "plane",
    "prism",
    "sphere",
    "union",
    "wedge",
];

/// Stand-in for an infinite bound (`INF`), as LIGGGHTS uses.
pub const BIG: f64 = 1.0e20;

/// The shape of a region (lengths in box units).
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// Axis-aligned box between `lo` and `hi`.
    Block { lo: [f64; 3], hi: [f64; 3] },
    /// Cylinder along `axis` (0, 1, 2) centred at (c1, c2) in the other two coordinates.
    Cylinder {
        axis: usize,
        c1: f64,
        c2: f64,
        radius: f64,
        lo: f64,
        hi: f64,
    },
    /// Sphere of `radius` around `centre`.
    Sphere { centre: [f64; 3], radius: f64 },
    /// Truncated cone along `axis`, radius `radlo` at `lo` to `radhi` at `hi`.
    Cone {
        axis: usize,
        c1: f64,
        c2: f64,
        radlo: f64,
        radhi: f64,
        lo: f64,
        hi: f64,
    },
    /// Half space on the side `normal` (unit) points to, through `point`.
    Plane { point: [f64; 3], normal: [f64; 3] },
    /// Parallelepiped with origin `lo`, edge lengths from `lo`/`hi` and tilts xy, xz, yz.
    Prism {
        lo: [f64; 3],
        hi: [f64; 3],
        tilt: [f64; 3],
        hinv: [[f64; 3]; 3],
    },
    /// Inside all of the listed regions (indices into the region list).
    Intersect(Vec<usize>),
    /// Inside any of the listed regions.
    Union(Vec<usize>),
    /// Strictly inside one of the tetrahedra of a `mesh/tet` file (the mesh lies in the box).
    TetMesh(Box<crate::engine::tet_mesh::TetMesh>),
    /// A wedge of a cylinder (`region wedge`).
    Wedge(Box<crate::engine::region_wedge::Wedge>),
}

/// A named region.
#[derive(Debug, Clone, PartialEq)]
pub struct Region {
    /// The region ID.
    pub id: String,
    /// Its style name as written (`block`, `cylinder`, ...).
    pub style: String,
    /// The geometry.
    pub shape: Shape,
    /// `side in` (true) or `side out`.
    pub interior: bool,
    /// A radius given as `v_name`: the equal-style variable and its length scale.
    pub radius_variable: Option<(String, f64)>,
    /// The step the variable radius was last evaluated at (once per step, as LIGGGHTS).
    pub shaped_at: Option<i64>,
    /// `move`/`rotate`: a dynamic region's motion.
    pub motion: Option<crate::engine::region_motion::Motion>,
}

impl Region {
    /// Whether variables change the region during a run (a variable radius or a motion).
    pub fn is_dynamic(&self) -> bool {
        self.radius_variable.is_some() || self.motion.is_some()
    }
}

/// All regions defined so far, in order.
#[derive(Debug, Clone, Default)]
pub struct Regions {
    /// The regions.
    pub list: Vec<Region>,
}

fn axis_of(word: &str) -> Result<usize, EngineError> {
    match word {
        "x" => Ok(0),
        "y" => Ok(1),
        "z" => Ok(2),
        _ => Err(format!("expected an axis x, y or z, got '{word}'").into()),
    }
}

/// The other two axes of a cylinder/cone along `axis`, in LIGGGHTS's order.
fn cross_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

/// Is `x` inside `shape`, a cylinder (false for any other shape)? All three tests without
/// early exit, so a loop over particles has no branches.
#[inline(always)]
fn in_cylinder(shape: &Shape, x: [f64; 3]) -> bool {
    let Shape::Cylinder {
        axis,
        c1,
        c2,
        radius,
        lo,
        hi,
    } = *shape
    else {
        return false;
    };
    let (a1, a2) = cross_axes(axis);
    let (d1, d2) = (x[a1] - c1, x[a2] - c2);
    let dist = (d1 * d1 + d2 * d2).sqrt();
    (dist <= radius) & (x[axis] >= lo) & (x[axis] <= hi)
}

/// Bounds of a body of revolution along `axis`: radius `r` around (c1, c2), from lo to hi.
fn axial_box(axis: usize, c1: f64, c2: f64, r: f64, lo: f64, hi: f64) -> ([f64; 3], [f64; 3]) {
    let (a1, a2) = cross_axes(axis);
    let mut l = [0.0; 3];
    let mut h = [0.0; 3];
    l[axis] = lo;
    h[axis] = hi;
    l[a1] = c1 - r;
    h[a1] = c1 + r;
    l[a2] = c2 - r;
    h[a2] = c2 + r;
    (l, h)
}

/// What a region definition needs to know about the box and lattice.
#[derive(Debug, Clone, Copy)]
pub struct RegionContext {
    /// Box bounds, if the box exists (for `EDGE` and `INF`).
    pub bounds: Option<([f64; 3], [f64; 3])>,
    /// Lattice spacings for `units lattice` (None when no lattice is defined).
    pub lattice: Option<[f64; 3]>,
}

impl RegionContext {
    /// The bound a word `INF` or `EDGE` names along dimension `d` (the low side when
    /// `lo_side`): ±[`BIG`] or the box face; None for any other word (a number).
    pub fn inf_or_edge(
        &self,
        w: &str,
        d: usize,
        lo_side: bool,
    ) -> Result<Option<f64>, EngineError> {
        if w != "INF" && w != "EDGE" {
            return Ok(None);
        }
        let (lo, hi) = self
            .bounds
            .ok_or("Cannot use region INF or EDGE when box does not exist")?;
        Ok(Some(match (w, lo_side) {
            ("INF", true) => -BIG,
            ("INF", false) => BIG,
            (_, true) => lo[d],
            (_, false) => hi[d],
        }))
    }
}

impl Regions {
    /// Find a region by ID.
    pub fn find(&self, id: &str) -> Option<usize> {
        self.list.iter().position(|r| r.id == id)
    }

    /// Parse `region ID STYLE args... [keyword value ...]` (`args` excludes the command name).
    pub fn define(&mut self, args: &[&str], ctx: RegionContext) -> Result<(), EngineError> {
        if args.len() < 2 {
            return Err("Illegal region command".into());
        }
        let (id, style) = (args[0], args[1]);
        if self.find(id).is_some() {
            return Err("Reuse of region ID".into());
        }
        if style == "delete" {
            return Err(EngineError::Unsupported("region delete".into()));
        }
        if !STYLES.contains(&style) {
            return Err(EngineError::Unsupported(format!("region {style}")));
        }
        if style == "wedge" {
            return self.define_wedge(args, ctx);
        }
        let nshape = match style {
            "block" => 6,
            "cylinder" | "plane" => 6,
            "sphere" => 4,
            "cone" => 7,
            "prism" => 9,
            "intersect" | "union" => {
                let n = args.get(2).ok_or("Illegal region command")?;
                let n: usize = n
                    .parse()
                    .map_err(|_| "Illegal region command".to_string())?;
                if n < 2 {
                    return Err(format!("Illegal region {style} command").into());
                }
                n + 1
            }
            other => return Err(EngineError::Unsupported(format!("region {other}"))),
        };
        if args.len() < 2 + nshape {
            return Err(format!("Illegal region {style} command").into());
        }
        let geometry = &args[2..2 + nshape];
        let (interior, scale, motion) = options(&args[2 + nshape..], ctx)?;
        if motion.is_some() && matches!(style, "union" | "intersect") {
            return Err("Region union or intersect cannot be dynamic".into());
        }
        let coord = |w: &str, d: usize, lo_side: bool| -> Result<f64, EngineError> {
            if let Some(b) = ctx.inf_or_edge(w, d, lo_side)? {
                return Ok(b);
            }
            Ok(scale[d] * numeric(w)?)
        };
        let mut radius_variable = None;
        let mut plain = |w: &str, scale: f64| -> Result<f64, EngineError> {
            if let Some(name) = w.strip_prefix("v_") {
                radius_variable = Some((name.to_string(), scale));
                return Ok(0.0);
            }
            Ok(scale * numeric(w)?)
        };
        let shape = match style {
            "block" => {
                let mut lo = [0.0; 3];
                let mut hi = [0.0; 3];
                for d in 0..3 {
                    lo[d] = coord(geometry[2 * d], d, true)?;
                    hi[d] = coord(geometry[2 * d + 1], d, false)?;
                }
                if (0..3).any(|d| lo[d] > hi[d]) {
                    return Err("Illegal region block command".into());
                }
                Shape::Block { lo, hi }
            }
            "cylinder" | "cone" => cylinder_or_cone(style, geometry, scale, &coord, &mut plain)?,
            "sphere" => sphere(geometry, scale, &mut plain)?,
            "plane" => plane(geometry, scale)?,
            "prism" => prism(geometry, scale, &coord)?,
            _ => {
                let mut members = Vec::new();
                for name in &geometry[1..] {
                    members.push(self.find(name).ok_or_else(|| {
                        format!("Region {style} region ID {name} does not exist")
                    })?);
                }
                if style == "intersect" {
                    Shape::Intersect(members)
                } else {
                    Shape::Union(members)
                }
            }
        };
        self.list.push(Region {
            id: id.to_string(),
            style: style.to_string(),
            shape,
            interior,
            radius_variable,
            shaped_at: None,
            motion,
        });
        Ok(())
    }

    /// The variable a region's radius follows, if any (checked and first evaluated when the
    /// region is defined).
    pub fn radius_variable(&self, index: usize) -> Option<&str> {
        self.list[index]
            .radius_variable
            .as_ref()
            .map(|(n, _)| n.as_str())
    }

    /// Re-evaluate variable radii at most once per step (`None`: unconditionally, as at
    /// definition), with `equal` evaluating an equal-style variable.
    pub fn reshape(
        &mut self,
        step: Option<i64>,
        equal: &mut dyn FnMut(&str) -> Result<f64, EngineError>,
    ) -> Result<(), EngineError> {
        for r in &mut self.list {
            if !r.is_dynamic() || (step.is_some() && r.shaped_at == step) {
                continue;
            }
            if let Some(m) = &mut r.motion {
                m.update(equal)?;
            }
            let Some((name, scale)) = &r.radius_variable else {
                if step.is_some() {
                    r.shaped_at = step;
                }
                continue;
            };
            let value = equal(name)?;
            if value < 0.0 {
                return Err("Variable evaluation in region gave bad value".into());
            }
            match &mut r.shape {
                Shape::Sphere { radius, .. } | Shape::Cylinder { radius, .. } => {
                    *radius = scale * value
                }
                _ => {}
            }
            if step.is_some() {
                r.shaped_at = step;
            }
        }
        Ok(())
    }

    /// Is point `x` in region `index`, honouring `side`?
    pub fn matches(&self, index: usize, x: [f64; 3]) -> bool {
        let r = &self.list[index];
        let x = match &r.motion {
            Some(m) => m.inverse(x),
            None => x,
        };
        self.inside(&r.shape, x) == r.interior
    }

    /// [`Regions::matches`] for every point of `xs` (one call for a fix's particles instead
    /// of one dynamic call per particle).
    pub fn matches_each(&self, index: usize, xs: &[[f64; 3]]) -> Vec<bool> {
        let r = &self.list[index];
        match (&r.shape, &r.motion) {
            // the commonest dynamic region: a still cylinder whose radius follows a
            // variable, in one tight loop
            (cylinder @ Shape::Cylinder { .. }, None) => xs
                .iter()
                .map(|&x| in_cylinder(cylinder, x) == r.interior)
                .collect(),
            _ => xs.iter().map(|&x| self.matches(index, x)).collect(),
        }
    }

    fn inside(&self, shape: &Shape, x: [f64; 3]) -> bool {
        match shape {
            Shape::Block { lo, hi } => (0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]),
            Shape::Cylinder { .. } => in_cylinder(shape, x),
            Shape::Sphere { centre, radius } => {
                let d = [x[0] - centre[0], x[1] - centre[1], x[2] - centre[2]];
                (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() <= *radius
            }
            Shape::Cone {
                axis,
                c1,
                c2,
                radlo,
                radhi,
                lo,
                hi,
            } => {
                let (a1, a2) = cross_axes(*axis);
                let (d1, d2) = (x[a1] - c1, x[a2] - c2);
                let dist = (d1 * d1 + d2 * d2).sqrt();
                let current = radlo + (x[*axis] - lo) * (radhi - radlo) / (hi - lo);
                dist <= current && x[*axis] >= *lo && x[*axis] <= *hi
            }
            Shape::Plane { point, normal } => {
                (x[0] - point[0]) * normal[0]
                    + (x[1] - point[1]) * normal[1]
                    + (x[2] - point[2]) * normal[2]
                    >= 0.0
            }
            Shape::Prism { lo, hinv, .. } => {
                let a = hinv[0][0] * (x[0] - lo[0])
                    + hinv[0][1] * (x[1] - lo[1])
                    + hinv[0][2] * (x[2] - lo[2]);
                let b = hinv[1][1] * (x[1] - lo[1]) + hinv[1][2] * (x[2] - lo[2]);
                let c = hinv[2][2] * (x[2] - lo[2]);
                (0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b) && (0.0..=1.0).contains(&c)
            }
            Shape::Intersect(members) => members.iter().all(|&m| self.matches(m, x)),
            Shape::Union(members) => members.iter().any(|&m| self.matches(m, x)),
            Shape::TetMesh(mesh) => mesh.inside(x),
            Shape::Wedge(w) => w.inside(x),
        }
    }

    /// Axis-aligned bounds of region `index` (for `create_box`), if it has finite ones.
    pub fn extent(&self, index: usize) -> Option<([f64; 3], [f64; 3])> {
        let r = &self.list[index];
        if !r.interior {
            return None;
        }
        match &r.shape {
            Shape::Block { lo, hi } => Some((*lo, *hi)),
            Shape::Cylinder {
                axis,
                c1,
                c2,
                radius,
                lo,
                hi,
            } => Some(axial_box(*axis, *c1, *c2, *radius, *lo, *hi)),
            Shape::Sphere { centre, radius } => Some((
                [centre[0] - radius, centre[1] - radius, centre[2] - radius],
                [centre[0] + radius, centre[1] + radius, centre[2] + radius],
            )),
            Shape::Cone {
                axis,
                c1,
                c2,
                radlo,
                radhi,
                lo,
                hi,
            } => Some(axial_box(*axis, *c1, *c2, radlo.max(*radhi), *lo, *hi)),
            Shape::Prism { .. } | Shape::Plane { .. } => None,
            Shape::TetMesh(mesh) => Some((mesh.lo, mesh.hi)),
            Shape::Wedge(w) => w.bounds,
            Shape::Intersect(m) => {
                let boxes: Vec<_> = m.iter().filter_map(|&i| self.extent(i)).collect();
                let first = *boxes.first()?;
                Some(boxes.iter().fold(first, |(l, h), (bl, bh)| {
                    (
                        [l[0].max(bl[0]), l[1].max(bl[1]), l[2].max(bl[2])],
                        [h[0].min(bh[0]), h[1].min(bh[1]), h[2].min(bh[2])],
                    )
                }))
            }
            Shape::Union(m) => {
                let boxes: Option<Vec<_>> = m.iter().map(|&i| self.extent(i)).collect();
                let boxes = boxes?;
                let first = *boxes.first()?;
                Some(boxes.iter().fold(first, |(l, h), (bl, bh)| {
                    (
                        [l[0].min(bl[0]), l[1].min(bl[1]), l[2].min(bl[2])],
                        [h[0].max(bh[0]), h[1].max(bh[1]), h[2].max(bh[2])],
                    )
                }))
            }
        }
    }
}

impl Regions {
    /// `region ID mesh/tet file F scale S move DX DY DZ rotate AX AY AZ [side in|out] units
    /// box` (`args` excludes the command name): `read` gives the file's text, `in_box` tells
    /// whether a placed node lies in the box (`box_bounds`). Returns what reading reported.
    pub fn define_tet(
        &mut self,
        args: &[&str],
        ctx: RegionContext,
        read: &dyn Fn(&str) -> Result<String, EngineError>,
    ) -> Result<crate::engine::tet_mesh::ReadNotes, EngineError> {
        use crate::engine::tet_mesh::Placement;
        if args.len() < 14 {
            return Err("Illegal region mesh/tet command".into());
        }
        let id = args[0];
        if self.find(id).is_some() {
            return Err("Reuse of region ID".into());
        }
        let words = args;
        if let Some(opt) = words[14..]
            .iter()
            .step_by(2)
            .find(|w| matches!(**w, "move" | "rotate"))
        {
            return Err(EngineError::Unsupported(format!(
                "region mesh/tet option {opt}"
            )));
        }
        // LIGGGHTS's default `units lattice` is refused for this style
        let units_box = words[14..]
            .windows(2)
            .rfind(|w| w[0] == "units")
            .is_some_and(|w| w[1] == "box");
        if !units_box {
            return Err(
                "Lattice scaling not implemented for region mesh/tet, please use 'units box'"
                    .into(),
            );
        }
        // `side out`: every point not inside a tetrahedron (LIGGGHTS 3.8.0's create_atoms and
        // group take the complement of `side in`)
        let (interior, _, _) = options(&words[14..], ctx)?;
        let expect = |k: usize, what: &str| -> Result<(), EngineError> {
            if words[k] == what {
                Ok(())
            } else {
                Err(format!("Illegal region mesh/tet command, expecting keyword '{what}'").into())
            }
        };
        expect(2, "file")?;
        expect(4, "scale")?;
        expect(6, "move")?;
        expect(10, "rotate")?;
        let num = |k: usize| numeric(words[k]).map_err(EngineError::from);
        let place = Placement {
            scale: num(5)?,
            offset: [num(7)?, num(8)?, num(9)?],
            rotate: [num(11)?, num(12)?, num(13)?],
        };
        let (lo, hi) = ctx
            .bounds
            .ok_or("Cannot load mesh before simulation box is defined.")?;
        let in_box = |x: [f64; 3]| (0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]);
        let text = read(words[3])?;
        let (mesh, notes) = crate::engine::tet_mesh::read(&text, &place, &in_box)?;
        // LIGGGHTS builds the surface of a `side in` region, whose checks refuse flat faces in
        // words regolith does not reproduce
        if interior
            && mesh
                .tets
                .iter()
                .any(|n| crate::engine::tet_mesh::signed_volume(n[0], n[1], n[2], n[3]) == 0.0)
        {
            return Err(EngineError::Unsupported(
                "region mesh/tet with a flat tetrahedron (side in)".into(),
            ));
        }
        self.list.push(Region {
            id: id.to_string(),
            style: "mesh/tet".to_string(),
            shape: Shape::TetMesh(Box::new(mesh)),
            interior,
            radius_variable: None,
            shaped_at: None,
            motion: None,
        });
        Ok(notes)
    }
}

/// A region's interior flag, lattice scale and motion.
pub(crate) type Options = (bool, [f64; 3], Option<crate::engine::region_motion::Motion>);

/// Trailing `units`, `side`, `seed`, `volume_limit`, `move`, `rotate` options.
pub(crate) fn options(words: &[&str], ctx: RegionContext) -> Result<Options, EngineError> {
    let mut interior = true;
    let mut lattice = false;
    // the motion keywords, parsed once the scale is known
    let mut moves: Vec<usize> = Vec::new();
    let mut i = 0;
    while i < words.len() {
        if matches!(words[i], "move" | "rotate") {
            let n = if words[i] == "move" { 4 } else { 8 };
            if i + n > words.len() {
                return Err("Illegal region command".into());
            }
            moves.push(i);
            i += n;
            continue;
        }
        let value = words.get(i + 1).ok_or("Illegal region command")?;
        match (words[i], *value) {
            ("units", "box") => lattice = false,
            ("units", "lattice") => lattice = true,
            ("side", "in") => interior = true,
            ("side", "out") => interior = false,
            ("seed", _) | ("volume_limit", _) => {
                numeric(value)?;
            }
            _ => {
                return Err(
                    format!("Illegal region command (unknown option '{}')", words[i]).into(),
                )
            }
        }
        i += 2;
    }
    let scale = if lattice {
        ctx.lattice.ok_or("Use of region with undefined lattice")?
    } else {
        [1.0; 3]
    };
    let mut motion = None;
    for k in moves {
        crate::engine::region_motion::Motion::parse(&mut motion, &words[k..], scale)?;
    }
    Ok((interior, scale, motion))
}

/// A coordinate word of a region (`INF`/`EDGE` or a number, scaled), along a dimension,
/// on the low side or not.
type Coord<'a> = dyn Fn(&str, usize, bool) -> Result<f64, EngineError> + 'a;

/// A scaled length word of a region, or a `v_name` radius (then 0 until evaluated).
type Plain<'a> = dyn FnMut(&str, f64) -> Result<f64, EngineError> + 'a;

/// `cylinder DIM C1 C2 R LO HI` or `cone DIM C1 C2 RADLO RADHI LO HI` (length).
fn cylinder_or_cone(
    style: &str,
    geometry: &[&str],
    scale: [f64; 3],
    coord: &Coord,
    plain: &mut Plain,
) -> Result<Shape, EngineError> {
    let axis = axis_of(geometry[0])?;
    let (a1, a2) = cross_axes(axis);
    let c1 = scale[a1] * numeric(geometry[1])?;
    let c2 = scale[a2] * numeric(geometry[2])?;
    if style == "cylinder" {
        let radius = plain(geometry[3], scale[0])?;
        let lo = coord(geometry[4], axis, true)?;
        let hi = coord(geometry[5], axis, false)?;
        if radius <= 0.0 && !geometry[3].starts_with("v_") {
            return Err("Illegal region cylinder command".into());
        }
        Ok(Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        })
    } else {
        let radlo = scale[a1] * numeric(geometry[3])?;
        let radhi = scale[a1] * numeric(geometry[4])?;
        let lo = coord(geometry[5], axis, true)?;
        let hi = coord(geometry[6], axis, false)?;
        if radlo < 0.0 || radhi < 0.0 || (radlo == 0.0 && radhi == 0.0) || lo >= hi {
            return Err("Illegal region cone command".into());
        }
        Ok(Shape::Cone {
            axis,
            c1,
            c2,
            radlo,
            radhi,
            lo,
            hi,
        })
    }
}

/// `prism XLO XHI YLO YHI ZLO ZHI XY XZ YZ` (length): the box and the inverse of its
/// triangular shape matrix.
/// A `sphere` region's shape: centre (scaled by the lattice), radius (a number or v_name,
/// the variable read later).
fn sphere(geometry: &[&str], scale: [f64; 3], plain: &mut Plain) -> Result<Shape, EngineError> {
    let mut centre = [0.0; 3];
    for d in 0..3 {
        centre[d] = scale[d] * numeric(geometry[d])?;
    }
    let radius = plain(geometry[3], scale[0])?;
    if radius < 0.0 {
        return Err("Illegal region sphere command".into());
    }
    Ok(Shape::Sphere { centre, radius })
}

/// A `plane` region's shape: a point and the unit normal (both scaled by the lattice).
fn plane(geometry: &[&str], scale: [f64; 3]) -> Result<Shape, EngineError> {
    let mut point = [0.0; 3];
    let mut normal = [0.0; 3];
    for d in 0..3 {
        point[d] = scale[d] * numeric(geometry[d])?;
        normal[d] = scale[d] * numeric(geometry[3 + d])?;
    }
    let rsq = normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2];
    if rsq == 0.0 {
        return Err("Illegal region plane command".into());
    }
    for n in &mut normal {
        *n /= rsq.sqrt();
    }
    Ok(Shape::Plane { point, normal })
}

fn prism(geometry: &[&str], scale: [f64; 3], coord: &Coord) -> Result<Shape, EngineError> {
    let mut lo = [0.0; 3];
    let mut hi = [0.0; 3];
    for d in 0..3 {
        lo[d] = coord(geometry[2 * d], d, true)?;
        hi[d] = coord(geometry[2 * d + 1], d, false)?;
    }
    let tilt = [
        scale[0] * numeric(geometry[6])?,
        scale[0] * numeric(geometry[7])?,
        scale[1] * numeric(geometry[8])?,
    ];
    if (0..3).any(|d| lo[d] >= hi[d]) {
        return Err("Illegal region prism command".into());
    }
    let h = [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]];
    let hinv = [
        [
            1.0 / h[0],
            -tilt[0] / (h[0] * h[1]),
            (tilt[0] * tilt[2] - tilt[1] * h[1]) / (h[0] * h[1] * h[2]),
        ],
        [0.0, 1.0 / h[1], -tilt[2] / (h[1] * h[2])],
        [0.0, 0.0, 1.0 / h[2]],
    ];
    Ok(Shape::Prism { lo, hi, tilt, hinv })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ctx() -> RegionContext {
        RegionContext {
            bounds: Some(([0.0; 3], [1.0; 3])),
            lattice: Some([2.0; 3]),
        }
    }

    #[test]
    fn shapes_and_sides() {
        let mut r = Regions::default();
        r.define(&["b", "block", "0", "1", "0", "1", "INF", "EDGE"], ctx())
            .unwrap();
        assert!(r.matches(0, [1.0, 0.0, -5.0]));
        let points = [
            [1.0, 0.0, -5.0],
            [0.0, 1.0, 1.5],
            [0.5, 0.5, 1.0],
            [0.9, 0.9, 1.0],
        ];
        for k in 0..r.list.len() {
            let each: Vec<bool> = points.iter().map(|&x| r.matches(k, x)).collect();
            assert_eq!(r.matches_each(k, &points), each, "region {k}");
        }
        assert!(!r.matches(0, [1.0, 0.0, 1.5]));
        r.define(
            &["c", "cylinder", "z", "0", "0", "1", "0", "2", "side", "out"],
            ctx(),
        )
        .unwrap();
        assert!(!r.matches(1, [0.5, 0.5, 1.0]));
        assert!(r.matches(1, [0.9, 0.9, 1.0]));
        r.define(
            &["s", "sphere", "0", "0", "0", "1", "units", "lattice"],
            ctx(),
        )
        .unwrap();
        assert!(r.matches(2, [0.0, 1.9, 0.0]));
        r.define(&["p", "plane", "0", "0", "0.5", "0", "0", "-3"], ctx())
            .unwrap();
        assert!(r.matches(3, [9.0, 9.0, 0.2]) && !r.matches(3, [0.0, 0.0, 0.6]));
        r.define(&["k", "cone", "z", "0", "0", "1", "0", "0", "1"], ctx())
            .unwrap();
        assert!(r.matches(4, [0.4, 0.0, 0.5]) && !r.matches(4, [0.6, 0.0, 0.5]));
        r.define(&["i", "intersect", "2", "b", "s"], ctx()).unwrap();
        assert!(r.matches(5, [0.5, 0.5, 0.5]) && !r.matches(5, [-0.5, 0.5, 0.5]));
        r.define(&["u", "union", "2", "b", "s"], ctx()).unwrap();
        assert!(r.matches(6, [-0.5, 0.5, 0.5]));
        r.define(
            &["pr", "prism", "0", "1", "0", "1", "0", "1", "0.5", "0", "0"],
            ctx(),
        )
        .unwrap();
        assert!(r.matches(7, [1.4, 0.9, 0.5]) && !r.matches(7, [0.1, 0.9, 0.5]));
        r.define(
            &["ci", "cylinder", "x", "0.5", "0.5", "0.5", "0", "1"],
            ctx(),
        )
        .unwrap();
        // every shape's one-call test gives each point's own answer (on the surface too)
        let points = [
            [1.0, 0.0, -5.0],
            [0.5, 0.5, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
            [0.5, 0.0, 0.5],
            [1.0, 0.5, 0.5],
            [0.2, 1.0, 0.5],
            [-0.1, 0.2, 0.3],
        ];
        for k in 0..r.list.len() {
            let each: Vec<bool> = points.iter().map(|&x| r.matches(k, x)).collect();
            assert_eq!(r.matches_each(k, &points), each, "region {k}");
        }
        assert_eq!(r.matches_each(1, &points[..3]), [true, false, false]);
        assert_eq!(r.extent(1), None);
        assert_eq!(r.extent(2), Some(([-2.0; 3], [2.0; 3])));
    }

    #[test]
    fn errors() {
        let mut r = Regions::default();
        let none = RegionContext {
            bounds: None,
            lattice: None,
        };
        assert_eq!(
            r.define(&["b", "block", "0", "1", "0", "1", "0", "INF"], none)
                .unwrap_err(),
            EngineError::Invalid("Cannot use region INF or EDGE when box does not exist".into())
        );
        assert!(r
            .define(&["b", "block", "0", "1", "0", "1", "0", "x"], none)
            .is_err());
        assert!(r
            .define(
                &["s", "sphere", "0", "0", "0", "1", "units", "lattice"],
                none
            )
            .is_err());
        assert!(r
            .define(
                &["s", "sphere", "0", "0", "0", "1", "side", "sideways"],
                none
            )
            .is_err());
        r.define(&["s", "sphere", "0", "0", "0", "1"], none)
            .unwrap();
        assert_eq!(
            r.define(&["s", "sphere", "0", "0", "0", "1"], none)
                .unwrap_err(),
            EngineError::Invalid("Reuse of region ID".into())
        );
        assert!(r.define(&["u", "union", "2", "s", "nope"], none).is_err());
    }
}
