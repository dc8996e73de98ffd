//! Triangle meshes of `fix mesh/surface`: per-triangle geometry, LIGGGHTS's topology (which
//! edges and corners of a triangle are *active*, i.e. report contacts) and the closest
//! feature of a triangle to a sphere. Lengths are in box units.
//!
//! The rules follow LIGGGHTS 3.8.0 (`docs/notes/mesh_contact.md` describes them): a shared
//! edge between non-coplanar triangles is active only on the higher-ID triangle, a coplanar
//! shared edge on neither; a corner is active only on the highest-ID triangle of its fan,
//! unless two edges through it are colinear or none of its edges is active. Arithmetic is
//! written in LIGGGHTS's order so contact forces agree to the last bit.

use crate::engine::error::EngineError;
use crate::io::stl::Triangle;

type V3 = [f64; 3];

#[inline(always)]
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
fn mag(a: V3) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// `v * (1/s)` per component, as LIGGGHTS's vectorScalarDiv3D.
#[inline(always)]
fn div(v: V3, s: f64) -> V3 {
    let inv = 1. / s;
    [inv * v[0], inv * v[1], inv * v[2]]
}

/// LIGGGHTS's tolerance defaults and topology settings of one mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSettings {
    /// Two nodes are one when every coordinate differs by less than this (length).
    pub precision: f64,
    /// Cosine of the largest angle between normals of triangles counted as coplanar
    /// (`curvature DEG`; default 1 - 1e-5, i.e. 0.256 degrees).
    pub curvature: f64,
    /// `curvature_tolerant yes`: triangles with an angle below the curvature angle are
    /// accepted.
    pub curvature_tolerant: bool,
}

impl Default for MeshSettings {
    fn default() -> Self {
        MeshSettings {
            precision: 1e-8,
            curvature: 1. - 1e-5,
            curvature_tolerant: false,
        }
    }
}

/// The closest feature of a triangle to a sphere that touches or nearly touches it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closest {
    /// Distance from the centre to the feature minus the radius (negative: overlap).
    pub gap: f64,
    /// Vector from the centre to the closest point.
    pub to_wall: V3,
    /// Barycentric coordinates of the closest point.
    pub bary: V3,
    /// The closest point lies inside the face (not on an edge or corner).
    pub face: bool,
}

/// A triangle mesh with LIGGGHTS's per-triangle quantities and topology.
#[derive(Debug, Clone, PartialEq)]
pub struct TriMesh {
    /// Nodes of each triangle, in STL order.
    pub nodes: Vec<[V3; 3]>,
    /// Centroids.
    pub center: Vec<V3>,
    /// Bounding radius around the centroid.
    pub r_bound: Vec<f64>,
    /// Unit edge vectors: edge k runs from node k to node k+1.
    pub edge_vec: Vec<[V3; 3]>,
    /// Edge lengths.
    pub edge_len: Vec<V3>,
    /// Unit normals (from the vertex winding).
    pub normal: Vec<V3>,
    /// Areas (length²), as LIGGGHTS computes them from edge vectors and lengths.
    pub area: Vec<f64>,
    /// Unit in-plane edge normals (edge vector x normal).
    pub edge_norm: Vec<[V3; 3]>,
    /// The obtuse node LIGGGHTS recognises (2, or -1; see the module notes).
    pub obtuse: Vec<i8>,
    /// Edge k reports contacts.
    pub edge_active: Vec<[bool; 3]>,
    /// Corner k reports contacts.
    pub corner_active: Vec<[bool; 3]>,
    /// Triangles sharing an edge, in the order they were found.
    pub neighbors: Vec<Vec<u32>>,
    /// Triangles that share a node or an edge and are coplanar within the curvature
    /// (contact history passes between them), sorted.
    pub coplanar_neighbors: Vec<Vec<u32>>,
    /// Tolerances and settings.
    pub settings: MeshSettings,
    /// The topology has been built (at the first run).
    pub has_topology: bool,
}

impl TriMesh {
    /// A mesh of `triangles` with its geometric quantities; every edge and corner active
    /// until [`TriMesh::build_topology`] runs.
    pub fn new(triangles: &[Triangle], settings: MeshSettings) -> TriMesh {
        let n = triangles.len();
        let mut m = TriMesh {
            nodes: triangles.to_vec(),
            center: vec![[0.0; 3]; n],
            r_bound: vec![0.0; n],
            edge_vec: vec![[[0.0; 3]; 3]; n],
            edge_len: vec![[0.0; 3]; n],
            normal: vec![[0.0; 3]; n],
            area: vec![0.0; n],
            edge_norm: vec![[[0.0; 3]; 3]; n],
            obtuse: vec![-1; n],
            edge_active: vec![[true; 3]; n],
            corner_active: vec![[true; 3]; n],
            neighbors: vec![Vec::new(); n],
            coplanar_neighbors: vec![Vec::new(); n],
            settings,
            has_topology: false,
        };
        m.recompute();
        m
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The mesh has no triangles.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Recompute centroids, bounding radii, edge vectors, normals and edge normals from the
    /// nodes (after reading, and after the mesh moved).
    pub fn recompute(&mut self) {
        for t in 0..self.nodes.len() {
            let n = self.nodes[t];
            let mut c = [0.0; 3];
            for node in &n {
                for (ck, nk) in c.iter_mut().zip(node) {
                    *ck += nk;
                }
            }
            let c = div(c, 3.0);
            self.center[t] = c;
            self.r_bound[t] = n.iter().map(|node| mag(sub(c, *node))).fold(0.0, f64::max);
        }
        self.recompute_surface();
    }

    /// Recompute edge vectors and lengths, normals, edge normals and obtuse flags from the
    /// nodes, keeping centroids and bounding radii (LIGGGHTS's refresh of a moving mesh at
    /// a re-neighbouring).
    pub fn recompute_surface(&mut self) {
        for t in 0..self.nodes.len() {
            let n = self.nodes[t];
            let mut e = [[0.0; 3]; 3];
            let mut len = [0.0; 3];
            for i in 0..3 {
                let v = sub(n[(i + 1) % 3], n[i]);
                len[i] = mag(v);
                e[i] = div(v, len[i]);
            }
            let mut nrm = cross(e[0], e[1]);
            let fallbacks = [
                (e[1], e[2]),
                (e[2], e[0]),
                (e[0], [1.1233, 2.123231, -3.3343434]),
                (e[1], [1.1233, 2.123231, -3.3343434]),
                (e[0], [1.1233, -2.123231, 3.3343434]),
                (e[1], [1.1233, -2.123231, 3.3343434]),
            ];
            for (a, b) in fallbacks {
                if mag(nrm) >= 1e-15 {
                    break;
                }
                nrm = cross(a, b);
            }
            let nrm = div(nrm, mag(nrm));
            let mut en = [[0.0; 3]; 3];
            for i in 0..3 {
                let m = cross(e[i], nrm);
                en[i] = if mag(m) < 1e-15 {
                    e[(i + 1) % 3]
                } else {
                    div(m, mag(m))
                };
            }
            // LIGGGHTS overwrites the index for each node in turn: only node 2 can remain
            self.obtuse[t] = if dot(e[2], e[1]) > 0. { 2 } else { -1 };
            self.edge_vec[t] = e;
            self.edge_len[t] = len;
            self.area[t] = 0.5 * mag(cross(e[0], e[1])) * len[0] * len[1];
            self.normal[t] = nrm;
            self.edge_norm[t] = en;
        }
    }

    /// Translate by `dx` (length): nodes and centroids; stored vectors are unchanged.
    pub fn translate(&mut self, dx: V3) {
        for t in 0..self.nodes.len() {
            for node in &mut self.nodes[t] {
                for k in 0..3 {
                    node[k] += dx[k];
                }
            }
            for (ck, dk) in self.center[t].iter_mut().zip(dx) {
                *ck += dk;
            }
        }
    }

    /// Rotate by `angle` (radians) about `axis` through `origin`, as LIGGGHTS's
    /// MultiNodeMesh::rotate: the axis normalised (again), a quaternion applied to the nodes
    /// and to the stored edge vectors, normals and edge normals; centroids from the nodes.
    pub fn rotate(&mut self, angle: f64, axis: V3, origin: V3) {
        let s = 1.0 / ((axis[0] * axis[0] + axis[1] * axis[1]) + axis[2] * axis[2]).sqrt();
        let u = axis.map(|a| s * a);
        let q = rotation_quaternion(angle, u);
        let shift = origin[0] * origin[0] + origin[1] * origin[1] + origin[2] * origin[2] > 0.0;
        for t in 0..self.nodes.len() {
            for node in &mut self.nodes[t] {
                let p = if shift { sub(*node, origin) } else { *node };
                let r = quat_rotate(q, p);
                *node = if shift {
                    [r[0] + origin[0], r[1] + origin[1], r[2] + origin[2]]
                } else {
                    r
                };
            }
            let n = self.nodes[t];
            let third = 1.0 / 3.0;
            self.center[t] = [0, 1, 2].map(|k| third * ((n[0][k] + n[1][k]) + n[2][k]));
            for i in 0..3 {
                self.edge_vec[t][i] = quat_rotate(q, self.edge_vec[t][i]);
                self.edge_norm[t][i] = quat_rotate(q, self.edge_norm[t][i]);
            }
            self.normal[t] = quat_rotate(q, self.normal[t]);
        }
    }

    /// Two nodes are the same within the mesh precision.
    #[inline]
    fn same(&self, a: V3, b: V3) -> bool {
        let p = self.settings.precision;
        (0..3).all(|k| (a[k] - b[k]).abs() < p)
    }

    /// Index of `node` among triangle t's nodes.
    fn contains(&self, t: usize, node: V3) -> Option<usize> {
        (0..3).find(|&k| self.same(self.nodes[t][k], node))
    }

    /// The two node pairs two triangles share, if they share an edge (LIGGGHTS's
    /// share2Nodes: the first two equal pairs, i's nodes outer).
    fn shared_edge(&self, i: usize, j: usize) -> Option<(usize, usize)> {
        let d = sub(self.center[i], self.center[j]);
        let radsum = self.r_bound[i] + self.r_bound[j];
        if dot(d, d) > radsum * radsum {
            return None;
        }
        let mut found: Vec<(usize, usize)> = Vec::with_capacity(2);
        'outer: for a in 0..3 {
            for b in 0..3 {
                if self.same(self.nodes[i][a], self.nodes[j][b]) {
                    found.push((a, b));
                    if found.len() == 2 {
                        break 'outer;
                    }
                }
            }
        }
        if found.len() < 2 {
            return None;
        }
        let edge = |x: usize, y: usize| if x + y == 2 { 2 } else { x.min(y) };
        Some((edge(found[0].0, found[1].0), edge(found[0].1, found[1].1)))
    }

    /// Candidate pairs (j < i) whose bounding spheres overlap, through a grid of the
    /// centroids.
    fn close_pairs(&self) -> Vec<(usize, usize)> {
        let n = self.len();
        let rmax = self.r_bound.iter().copied().fold(0.0, f64::max);
        let cell = (2.0 * rmax).max(1e-300);
        let key = |c: V3| c.map(|v| (v / cell).floor() as i64);
        let mut grid: std::collections::HashMap<[i64; 3], Vec<usize>> =
            std::collections::HashMap::new();
        let mut pairs = Vec::new();
        for i in 0..n {
            let k = key(self.center[i]);
            let mut near = Vec::new();
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        // saturating: a degenerate mesh (scale 1e-30) puts centroids at the i64 ends
                        let cell = [
                            k[0].saturating_add(dx),
                            k[1].saturating_add(dy),
                            k[2].saturating_add(dz),
                        ];
                        if let Some(list) = grid.get(&cell) {
                            near.extend_from_slice(list);
                        }
                    }
                }
            }
            near.sort_unstable();
            pairs.extend(near.into_iter().map(|j| (i, j)));
            grid.entry(k).or_default().push(i);
        }
        pairs
    }

    /// Build neighbours and edge and corner activity (LIGGGHTS's buildNeighbours), and run
    /// its quality checks; `box_lo`/`box_hi` is the simulation box (corners of nodes outside
    /// it stay active on every triangle). `name` names the mesh in errors.
    pub fn build_topology(
        &mut self,
        box_lo: V3,
        box_hi: V3,
        name: &str,
    ) -> Result<(), EngineError> {
        let n = self.len();
        self.edge_active = vec![[true; 3]; n];
        self.corner_active = vec![[true; 3]; n];
        self.neighbors = vec![Vec::new(); n];
        let curvature = self.settings.curvature;
        let pairs = self.close_pairs();
        for &(i, j) in &pairs {
            let Some((ie, je)) = self.shared_edge(i, j) else {
                continue;
            };
            self.neighbors[i].push(j as u32);
            self.neighbors[j].push(i as u32);
            let coplanar = dot(self.normal[i], self.normal[j]).abs() >= curvature;
            // i > j: a kept edge stays on the higher ID
            if !coplanar || self.coplanar_overlap(i, ie, j, je) {
                self.edge_active[i][ie] = true;
                self.edge_active[j][je] = false;
            } else {
                self.edge_active[i][ie] = false;
                self.edge_active[j][je] = false;
            }
        }
        for t in 0..n {
            if self.neighbors[t].len() > 5 {
                return Err(format!(
                    "Mesh {name}: element {t} has {} neighbours sharing an edge, at most 5 are allowed (a non-manifold mesh)",
                    self.neighbors[t].len()
                ).into());
            }
        }
        for t in 0..n {
            for k in 0..3 {
                self.handle_corner(t, k, box_lo, box_hi);
            }
        }
        // history passes between coplanar triangles that share an edge or a node
        for list in self.coplanar_neighbors.iter_mut() {
            list.clear();
        }
        self.coplanar_neighbors = vec![Vec::new(); n];
        for &(i, j) in &pairs {
            let edge_neighbors = self.neighbors[i].contains(&(j as u32));
            let share_node = edge_neighbors
                || (0..3).any(|a| (0..3).any(|b| self.same(self.nodes[i][a], self.nodes[j][b])));
            if share_node && dot(self.normal[i], self.normal[j]).abs() > curvature {
                self.coplanar_neighbors[i].push(j as u32);
                self.coplanar_neighbors[j].push(i as u32);
            }
        }
        for list in self.coplanar_neighbors.iter_mut() {
            list.sort_unstable();
        }
        self.quality_check(name)?;
        self.has_topology = true;
        Ok(())
    }

    /// Two coplanar triangles sharing an edge lie on the same side of it (they overlap).
    fn coplanar_overlap(&self, i: usize, ie: usize, j: usize, je: usize) -> bool {
        let p_ref = self.nodes[i][ie];
        let m = self.edge_norm[i][ie];
        let d1 = dot(sub(self.nodes[i][(ie + 2) % 3], p_ref), m);
        let d2 = dot(sub(self.nodes[j][(je + 2) % 3], p_ref), m);
        d1 * d2 > 0.
    }

    /// LIGGGHTS's handleCorner for node k of triangle t.
    fn handle_corner(&mut self, t: usize, k: usize, box_lo: V3, box_hi: V3) {
        let node = self.nodes[t][k];
        let mut visited = Vec::new();
        let mut has_node = Vec::new();
        let mut edges: Vec<(V3, V3)> = Vec::new();
        let mut any_active = false;
        let mut stack = vec![t];
        // depth-first in neighbour order, as the recursion visits them
        fn visit(
            m: &TriMesh,
            s: usize,
            node: V3,
            visited: &mut Vec<usize>,
            has_node: &mut Vec<usize>,
            edges: &mut Vec<(V3, V3)>,
            any_active: &mut bool,
        ) {
            if visited.contains(&s) {
                return;
            }
            visited.push(s);
            let Some(i) = m.contains(s, node) else { return };
            has_node.push(s);
            let im = (i + 2) % 3;
            edges.push((m.edge_vec[s][i], m.nodes[s][(i + 1) % 3]));
            edges.push((m.edge_vec[s][im], m.nodes[s][im]));
            if m.edge_active[s][i] || m.edge_active[s][im] {
                *any_active = true;
            }
            for &nb in &m.neighbors[s] {
                visit(m, nb as usize, node, visited, has_node, edges, any_active);
            }
        }
        stack.clear();
        visit(
            self,
            t,
            node,
            &mut visited,
            &mut has_node,
            &mut edges,
            &mut any_active,
        );
        let pad = 1e-8;
        let inside = (0..3).all(|d| node[d] >= box_lo[d] - pad && node[d] < box_hi[d] + pad);
        if !inside {
            return;
        }
        let max_id = has_node.iter().copied().max().unwrap_or(t);
        let curvature = self.settings.curvature;
        let mut colinear = false;
        for a in 0..edges.len() {
            for b in a + 1..edges.len() {
                if dot(edges[a].0, edges[b].0).abs() > curvature
                    && !self.same(edges[a].1, edges[b].1)
                {
                    colinear = true;
                }
            }
        }
        self.corner_active[t][k] = !colinear && any_active && t == max_id;
    }

    /// Cosine of LIGGGHTS's hard limit on a triangle's smallest angle (0.0573 degrees).
    fn hard_angle_cos() -> f64 {
        (0.0573_f64 * std::f64::consts::PI / 180.)
            .cos()
            .max(0.9999995)
    }

    /// Triangle `t` has an angle at or below LIGGGHTS's hard limit (0.0573 degrees): a
    /// run refuses it, `element_exclusion_list write` lists it as the mesh is read.
    pub fn below_hard_angle(&self, t: usize) -> bool {
        let e = self.edge_vec[t];
        (0..3).any(|k| -dot(e[k], e[(k + 2) % 3]) >= Self::hard_angle_cos())
    }

    /// LIGGGHTS's counts of skewed triangles at a mesh's first setup: triangles with an
    /// angle below its soft limit (0.5 degrees), and angles below its hard limit (0.0573
    /// degrees; a run refuses the mesh when there is any).
    pub fn skewed_counts(&self) -> (usize, usize) {
        let soft = (0.5_f64 * std::f64::consts::PI / 180.).cos();
        let hard = Self::hard_angle_cos();
        let mut soft_triangles = 0;
        let mut hard_angles = 0;
        for e in &self.edge_vec {
            let cosines = [0, 1, 2].map(|k| -dot(e[k], e[(k + 2) % 3]));
            if cosines.iter().any(|&c| c > soft) {
                soft_triangles += 1;
            }
            hard_angles += cosines.iter().filter(|&&c| c > hard).count();
        }
        (soft_triangles, hard_angles)
    }

    /// LIGGGHTS's mesh quality checks (angles, duplicates).
    fn quality_check(&self, name: &str) -> Result<(), EngineError> {
        // in LIGGGHTS's order: duplicates, the curvature angle, the hard limit
        for &(i, j) in &self.close_pairs() {
            let shared = (0..3)
                .filter(|&a| (0..3).any(|b| self.same(self.nodes[i][a], self.nodes[j][b])))
                .count();
            if shared == 3 {
                return Err(format!(
                    "Mesh {name}: elements {j} and {i} are duplicates; use 'heal auto_remove_duplicates' or fix the mesh"
                ).into());
            }
        }
        for t in 0..self.len() {
            let e = self.edge_vec[t];
            for k in 0..3 {
                let c = -dot(e[k], e[(k + 2) % 3]);
                if c > self.settings.curvature && !self.settings.curvature_tolerant {
                    // LIGGGHTS's words (it adds the element's line in the file)
                    return Err(format!(
                        "Mesh {name}: The minumum angle of mesh element {t} is lower than the specified curvature. Increase mesh quality or decrease curvature (currently {:.6}\u{b0})\nFix mesh: Bad mesh, cannot continue. You can try setting 'curvature' to 1e-5 or lower or use 'curvature_tolerant yes'",
                        self.settings.curvature.acos() * 180. / std::f64::consts::PI
                    ).into());
                }
            }
        }
        let (_, hard_angles) = self.skewed_counts();
        if hard_angles > 0 {
            return Err(format!(
                "{}\n{BAD_MESH_HARD_LIMIT}",
                hard_limit_line(name, hard_angles)
            )
            .into());
        }
        Ok(())
    }

    /// May a sphere at `p` come within `reach` of triangle t (LIGGGHTS's generous prism
    /// test for the mesh neighbour list)?
    #[inline]
    pub fn near(&self, t: usize, p: V3, reach: f64) -> bool {
        let d_norm = dot(self.normal[t], sub(p, self.center[t])).abs();
        if d_norm > reach {
            return false;
        }
        let r2 = reach * reach;
        (0..3).all(|i| {
            let d = dot(self.edge_norm[t][i], sub(p, self.nodes[t][i]));
            !(d > 0. && d * d > r2)
        })
    }

    /// The closest active feature of triangle t to a sphere at `p` of radius `r` (LIGGGHTS's
    /// resolveTriSphereContactBary); None when the closest feature is inactive.
    #[inline]
    pub fn closest(&self, t: usize, p: V3, r: f64) -> Option<Closest> {
        let n = &self.nodes[t];
        let e = &self.edge_vec[t];
        let len = &self.edge_len[t];
        let ap = sub(p, n[0]);
        let a = dot(ap, e[0]);
        let b = dot(ap, e[2]);
        let c = dot(e[0], e[2]);
        let one_min_c_sqr = 1. - c * c;
        let b1 = (a - b * c) / (len[0] * one_min_c_sqr);
        let b2 = (a * c - b) / (len[2] * one_min_c_sqr);
        let b0 = 1. - b1 - b2;
        let invlen = 1. / (2. * self.r_bound[t]);
        let tol = -self.settings.precision * invlen;
        let sign = (b0 > tol) as u8 + 2 * (b1 > tol) as u8 + 4 * (b2 > tol) as u8;
        let obtuse = self.obtuse[t];
        let (d, to_wall, bary) = match sign {
            1 => self.corner(t, 0, obtuse == 0, p)?,
            2 => self.corner(t, 1, obtuse == 1, p)?,
            3 => self.edge(t, 0, p)?,
            4 => self.corner(t, 2, obtuse == 2, p)?,
            5 => self.edge(t, 2, p)?,
            6 => self.edge(t, 1, p)?,
            7 => {
                let nrm = self.normal[t];
                let d_norm = dot(nrm, ap);
                let q = sub(p, [nrm[0] * d_norm, nrm[1] * d_norm, nrm[2] * d_norm]);
                let (d, to_wall) = dist(p, q);
                (d, to_wall, [b0, b1, b2])
            }
            // all three coordinates at or below -tol cannot happen (they sum to 1)
            _ => return None,
        };
        Some(Closest {
            gap: d - r,
            to_wall,
            bary,
            face: sign == 7,
        })
    }

    /// Edge `i` region of triangle t (or the corners at its ends).
    #[inline]
    fn edge(&self, t: usize, i: usize, p: V3) -> Option<(f64, V3, V3)> {
        const SMALL: f64 = 1e-10;
        let (ip, ipp) = ((i + 1) % 3, (i + 2) % 3);
        let n = &self.nodes[t];
        let along = dot(sub(p, n[i]), self.edge_vec[t][i]);
        let mut bary = [0.0; 3];
        if along < -SMALL {
            if !self.corner_active[t][i] {
                return None;
            }
            bary[i] = 1.;
            let (d, w) = dist(p, n[i]);
            return Some((d, w, bary));
        }
        if along > self.edge_len[t][i] + SMALL {
            if !self.corner_active[t][ip] {
                return None;
            }
            bary[ip] = 1.;
            let (d, w) = dist(p, n[ip]);
            return Some((d, w, bary));
        }
        if !self.edge_active[t][i] {
            return None;
        }
        let q = add_multiple(n[i], along, self.edge_vec[t][i]);
        let (d, w) = dist(p, q);
        bary[ipp] = 0.;
        bary[i] = 1. - along / self.edge_len[t][i];
        bary[ip] = 1. - bary[i];
        Some((d, w, bary))
    }

    /// Corner `k` region of triangle t, with LIGGGHTS's obtuse-angle handling.
    #[inline]
    fn corner(&self, t: usize, k: usize, obtuse: bool, p: V3) -> Option<(f64, V3, V3)> {
        const SMALL: f64 = 1e-10;
        let (ip, ipp) = ((k + 1) % 3, (k + 2) % 3);
        let n = &self.nodes[t];
        let mut bary = [0.0; 3];
        if obtuse {
            let e = &self.edge_vec[t];
            let len = &self.edge_len[t];
            let w = sub(p, n[k]);
            let along = dot(w, e[ipp]);
            if along < SMALL {
                if along > -len[ipp] {
                    if !self.edge_active[t][ipp] {
                        return None;
                    }
                    let q = add_multiple(n[k], along, e[ipp]);
                    bary[ip] = 0.;
                    bary[k] = 1. + along / len[ipp];
                    bary[ipp] = 1. - bary[k];
                    let (d, v) = dist(p, q);
                    return Some((d, v, bary));
                }
                if !self.corner_active[t][ipp] {
                    return None;
                }
                bary[ipp] = 1.;
                let (d, v) = dist(p, n[ipp]);
                return Some((d, v, bary));
            }
            let along = dot(w, e[k]);
            if along > -SMALL {
                if along < len[k] {
                    if !self.edge_active[t][k] {
                        return None;
                    }
                    let q = add_multiple(n[k], along, e[k]);
                    bary[ipp] = 0.;
                    bary[k] = 1. - along / len[k];
                    bary[ip] = 1. - bary[k];
                    let (d, v) = dist(p, q);
                    return Some((d, v, bary));
                }
                if !self.corner_active[t][ip] {
                    return None;
                }
                bary[ip] = 1.;
                let (d, v) = dist(p, n[ip]);
                return Some((d, v, bary));
            }
        }
        if !self.corner_active[t][k] {
            return None;
        }
        bary[k] = 1.;
        let (d, v) = dist(p, n[k]);
        Some((d, v, bary))
    }

    /// Distance from `p` to the nearest active edge of the whole mesh is at least `delta`
    /// (used by `insert/stream ... all_in yes` on planar faces).
    pub fn far_from_active_edges(&self, p: V3, delta: f64) -> bool {
        for t in 0..self.len() {
            for i in 0..3 {
                if !self.edge_active[t][i] {
                    continue;
                }
                if edge_point_dist(
                    self.nodes[t][i],
                    self.edge_vec[t][i],
                    self.edge_len[t][i],
                    p,
                ) < delta
                {
                    return false;
                }
            }
        }
        true
    }
}

/// The unit quaternion of a rotation by `angle` (radians) about unit `u`.
pub fn rotation_quaternion(angle: f64, u: V3) -> [f64; 4] {
    let h = angle * 0.5;
    let (sn, cs) = (h.sin(), h.cos());
    [cs, u[0] * sn, u[1] * sn, u[2] * sn]
}

/// Quaternion product a ⊗ b, evaluated left to right as LIGGGHTS does.
#[inline]
fn quat_mul(a: [f64; 4], b: [f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + b[0] * a[1] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] + b[0] * a[2] + a[3] * b[1] - a[1] * b[3],
        a[0] * b[3] + b[0] * a[3] + a[1] * b[2] - a[2] * b[1],
    ]
}

/// Rotate `p` by unit quaternion `q`: q ⊗ (0, p) ⊗ conj(q).
pub fn quat_rotate(q: [f64; 4], p: V3) -> V3 {
    let t = quat_mul(q, [0.0, p[0], p[1], p[2]]);
    let r = quat_mul(t, [q[0], -q[1], -q[2], -q[3]]);
    [r[1], r[2], r[3]]
}

/// `n + s e` per component.
#[inline(always)]
fn add_multiple(n: V3, s: f64, e: V3) -> V3 {
    [n[0] + s * e[0], n[1] + s * e[1], n[2] + s * e[2]]
}

/// Distance from `p` to `q` and the vector q - p (LIGGGHTS's calcDist).
#[inline(always)]
fn dist(p: V3, q: V3) -> (f64, V3) {
    let w = sub(q, p);
    let d = ((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]))
        + (p[2] - q[2]) * (p[2] - q[2]);
    (d.sqrt(), w)
}

/// Distance from `p` to the segment starting at `a` along unit `e` of length `len`.
fn edge_point_dist(a: V3, e: V3, len: f64, p: V3) -> f64 {
    let s = dot(sub(p, a), e).clamp(0.0, len);
    mag(sub(p, add_multiple(a, s, e)))
}

/// LIGGGHTS's line counting the `angles` angles below its hard limit (0.0573 degrees) of
/// mesh `name`, said on the screen before its error (surface_mesh_I.h, qualityCheck).
pub fn hard_limit_line(name: &str, angles: usize) -> String {
    format!("Mesh {name}: {angles} mesh elements have a really unreasonably high aspect ratio (hard limit: smallest angle must be > 0.057296 \u{b0})  ")
}

/// LIGGGHTS's error for a mesh with angles below its hard limit.
pub const BAD_MESH_HARD_LIMIT: &str = "Fix mesh: Bad mesh, cannot continue. You will need to fix or remove these element. Remedies:\n - You can use the 'element_exclusion_list' feature to remove elements with too many neighbors and elements with angles below the hard limit";

/// LIGGGHTS's line counting mesh `name`'s `triangles` with an angle below its soft limit
/// (0.5 degrees), said on the screen before its warning.
pub fn soft_limit_line(name: &str, triangles: usize) -> String {
    format!("Mesh {name}: {triangles} elements have high aspect ratio (soft limit: smallest angle > 0.500000 \u{b0} required)")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> TriMesh {
        let t0 = [[-0.05, -0.05, 0.], [0.05, -0.05, 0.], [0.05, 0.05, 0.]];
        let t1 = [[-0.05, -0.05, 0.], [0.05, 0.05, 0.], [-0.05, 0.05, 0.]];
        let mut m = TriMesh::new(&[t0, t1], MeshSettings::default());
        m.build_topology([-0.1; 3], [0.1; 3], "square").unwrap();
        m
    }

    #[test]
    fn coplanar_diagonal_is_inactive_and_corners_belong_to_one_triangle() {
        let m = square();
        // triangle 0: edges n0-n1 (y = -0.05), n1-n2 (x = 0.05), n2-n0 (diagonal)
        assert_eq!(m.edge_active[0], [true, true, false]);
        // triangle 1: edges n0-n1 (diagonal), n1-n2 (y = 0.05), n2-n0 (x = -0.05)
        assert_eq!(m.edge_active[1], [false, true, true]);
        // the diagonal's end corners are active on triangle 1 only
        assert_eq!(m.corner_active[0], [false, true, false]);
        assert_eq!(m.corner_active[1], [true, true, true]);
        assert_eq!(m.coplanar_neighbors[0], vec![1]);
    }

    #[test]
    fn closest_features_match_liggghts() {
        let m = square();
        // face
        let c = m.closest(0, [0.02, -0.02, 0.0049], 0.005).unwrap();
        assert!(c.face);
        assert!((c.gap + 1e-4).abs() < 1e-15);
        // outer edge x = 0.05 of triangle 0, centre outside
        let c = m.closest(0, [0.052, 0.0, 0.0045], 0.005).unwrap();
        assert!(!c.face);
        let d = (0.002f64 * 0.002 + 0.0045 * 0.0045).sqrt();
        assert!((c.gap - (d - 0.005)).abs() < 1e-15);
        // beyond the diagonal (inactive on both): triangle 0 gives nothing
        assert!(m.closest(0, [-0.02, 0.03, 0.0049], 0.005).is_none());
        // corner (0.05, 0.05) is active on triangle 1 only
        let p = [0.051, 0.051, 0.0047];
        assert!(m.closest(0, p, 0.005).is_none());
        assert!(m.closest(1, p, 0.005).is_some());
    }
}
