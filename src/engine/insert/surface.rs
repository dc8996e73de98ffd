//! Where a candidate particle meets an insertion region's surface: the faces it reaches
//! inside or outside, and the contact points with the region's walls.

use super::*;

/// Number of interior faces of a block or cylinder closer than `cut` to `x` (0 outside).
pub fn surface_interior(shape: &Shape, x: [f64; 3], cut: f64) -> usize {
    match shape {
        Shape::Block { lo, hi } => {
            if !(0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]) {
                return 0;
            }
            (0..3)
                .map(|d| (x[d] - lo[d] < cut) as usize + (hi[d] - x[d] < cut) as usize)
                .sum()
        }
        Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        } => {
            let (a1, a2) = cross_axes(*axis);
            let (d1, d2) = (x[a1] - c1, x[a2] - c2);
            let r = (d1 * d1 + d2 * d2).sqrt();
            let a = x[*axis];
            if r > *radius || a < *lo || a > *hi {
                return 0;
            }
            (radius - r < cut && r > 0.0) as usize
                + (a - lo < cut) as usize
                + (hi - a < cut) as usize
        }
        _ => 0,
    }
}

/// Whether `x` lies outside a block or cylinder but closer than `cut` to its surface.
pub fn surface_exterior(shape: &Shape, x: [f64; 3], cut: f64) -> bool {
    let dist = |p: [f64; 3]| {
        let d = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
    };
    match shape {
        Shape::Block { lo, hi } => {
            if (0..3).any(|d| x[d] <= lo[d] - cut || x[d] >= hi[d] + cut) {
                return false;
            }
            if (0..3).all(|d| x[d] > lo[d] && x[d] < hi[d]) {
                return false;
            }
            let p = [0, 1, 2].map(|d| x[d].clamp(lo[d], hi[d]));
            dist(p) < cut
        }
        Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        } => {
            let (a1, a2) = cross_axes(*axis);
            let (d1, d2) = (x[a1] - c1, x[a2] - c2);
            let r = (d1 * d1 + d2 * d2).sqrt();
            let a = x[*axis];
            if r >= radius + cut || a <= lo - cut || a >= hi + cut {
                return false;
            }
            if r < *radius && a > *lo && a < *hi {
                return false;
            }
            let mut p = x;
            if r > *radius {
                p[a1] = c1 + (x[a1] - c1) * radius / r;
                p[a2] = c2 + (x[a2] - c2) * radius / r;
            }
            p[*axis] = a.clamp(*lo, *hi);
            dist(p) < cut
        }
        _ => false,
    }
}

/// Contacts (vectors from the surface point to `x`) of `x` with region `index`'s surface
/// within `cut`, honouring `side` as LIGGGHTS's `Region::surface` does; intersections keep a
/// sub-region's contact only where its surface point lies in all the other sub-regions.
pub fn surface_contacts(regions: &Regions, index: usize, x: [f64; 3], cut: f64) -> Vec<[f64; 3]> {
    let r = &regions.list[index];
    surface_contacts_side(regions, index, x, cut, r.interior)
}

/// [`surface_contacts`] with the inside (`interior`) or outside of the region's surface
/// taken as its side.
pub(super) fn surface_contacts_side(
    regions: &Regions,
    index: usize,
    x: [f64; 3],
    cut: f64,
    interior: bool,
) -> Vec<[f64; 3]> {
    let r = &regions.list[index];
    let mut out = Vec::new();
    match &r.shape {
        Shape::Block { lo, hi } if interior => block_inside(x, *lo, *hi, cut, &mut out),
        Shape::Block { lo, hi } => {
            let outside = (0..3).any(|d| x[d] <= lo[d] - cut || x[d] >= hi[d] + cut);
            let inside = (0..3).all(|d| x[d] > lo[d] && x[d] < hi[d]);
            if !outside && !inside {
                let p = [0, 1, 2].map(|d| x[d].clamp(lo[d], hi[d]));
                push_within(x, p, cut, &mut out);
            }
        }
        Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        } => {
            let c = Can {
                axis: *axis,
                centre: (*c1, *c2),
                radius: *radius,
                ends: (*lo, *hi),
            };
            if interior {
                c.inside(x, cut, &mut out)
            } else {
                c.outside(x, cut, &mut out)
            }
        }
        Shape::Intersect(members) => {
            // interior: sub-region contacts whose point is in all the others; exterior:
            // with every sub-region's side flipped, points in none of the others
            for (k, &m) in members.iter().enumerate() {
                let side = regions.list[m].interior == interior;
                for v in surface_contacts_side(regions, m, x, cut, side) {
                    let p = [x[0] - v[0], x[1] - v[1], x[2] - v[2]];
                    // with the sides flipped for the exterior, "in none of the flipped others"
                    // is again "in all of the others"
                    let keep = members
                        .iter()
                        .enumerate()
                        .filter(|(j, _)| *j != k)
                        .all(|(_, &o)| regions.matches(o, p));
                    if keep {
                        out.push(v);
                    }
                }
            }
        }
        _ => {}
    }
    out
}

/// The vector from surface point `p` to `x` when shorter than `cut`, pushed to `out`.
fn push_within(x: [f64; 3], p: [f64; 3], cut: f64, out: &mut Vec<[f64; 3]>) {
    let v = [x[0] - p[0], x[1] - p[1], x[2] - p[2]];
    if (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt() < cut {
        out.push(v);
    }
}

/// A point inside block `lo`..`hi`: its contacts with each face nearer than `cut`.
fn block_inside(x: [f64; 3], lo: [f64; 3], hi: [f64; 3], cut: f64, out: &mut Vec<[f64; 3]>) {
    if !(0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]) {
        return;
    }
    for d in 0..3 {
        let delta = x[d] - lo[d];
        if delta < cut {
            let mut v = [0.0; 3];
            v[d] = delta;
            out.push(v);
        }
        let delta = hi[d] - x[d];
        if delta < cut {
            let mut v = [0.0; 3];
            v[d] = -delta;
            out.push(v);
        }
    }
}

/// A closed cylinder region: axis, centre in the two other axes, radius and ends along the
/// axis (m).
struct Can {
    axis: usize,
    centre: (f64, f64),
    radius: f64,
    ends: (f64, f64),
}

impl Can {
    /// A point inside: its contacts with the mantle and each end nearer than `cut`.
    fn inside(&self, x: [f64; 3], cut: f64, out: &mut Vec<[f64; 3]>) {
        let (axis, radius, (lo, hi)) = (self.axis, self.radius, self.ends);
        let (a1, a2) = cross_axes(axis);
        let (d1, d2) = (x[a1] - self.centre.0, x[a2] - self.centre.1);
        let rr = (d1 * d1 + d2 * d2).sqrt();
        let a = x[axis];
        if rr > radius || a < lo || a > hi {
            return;
        }
        let delta = radius - rr;
        if delta < cut && rr > 0.0 {
            let mut v = [0.0; 3];
            v[a1] = d1 * (1.0 - radius / rr);
            v[a2] = d2 * (1.0 - radius / rr);
            out.push(v);
        }
        let delta = a - lo;
        if delta < cut {
            let mut v = [0.0; 3];
            v[axis] = delta;
            out.push(v);
        }
        let delta = hi - a;
        if delta < cut {
            let mut v = [0.0; 3];
            v[axis] = -delta;
            out.push(v);
        }
    }

    /// A point outside: its contact with the nearest surface point when nearer than `cut`.
    fn outside(&self, x: [f64; 3], cut: f64, out: &mut Vec<[f64; 3]>) {
        let (axis, radius, (lo, hi)) = (self.axis, self.radius, self.ends);
        let (a1, a2) = cross_axes(axis);
        let (c1, c2) = self.centre;
        let (d1, d2) = (x[a1] - c1, x[a2] - c2);
        let rr = (d1 * d1 + d2 * d2).sqrt();
        let a = x[axis];
        if rr >= radius + cut || a <= lo - cut || a >= hi + cut {
            return;
        }
        if rr < radius && a > lo && a < hi {
            return;
        }
        let mut p = x;
        if rr > radius {
            p[a1] = c1 + d1 * radius / rr;
            p[a2] = c2 + d2 * radius / rr;
        }
        // (not `clamp`, which would panic on ends given in reverse)
        p[axis] = if a < lo {
            lo
        } else if a > hi {
            hi
        } else {
            a
        };
        push_within(x, p, cut, out);
    }
}

pub(super) fn cross_axes(axis: usize) -> (usize, usize) {
    match axis {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    }
}

pub(super) fn inside(shape: &Shape, x: [f64; 3]) -> bool {
    match shape {
        Shape::Block { lo, hi } => (0..3).all(|d| x[d] >= lo[d] && x[d] <= hi[d]),
        Shape::Cylinder {
            axis,
            c1,
            c2,
            radius,
            lo,
            hi,
        } => {
            let (a1, a2) = cross_axes(*axis);
            let (d1, d2) = (x[a1] - c1, x[a2] - c2);
            (d1 * d1 + d2 * d2).sqrt() <= *radius && x[*axis] >= *lo && x[*axis] <= *hi
        }
        _ => false,
    }
}
