//! A simulation's state to and from a LIGGGHTS restart file: atoms (with group masks,
//! images and spins), box, step, groups, the pair model, wall contact history
//! (`history_<wall ID>` per-atom arrays) and pair contact history (`contacthistory`: per atom
//! its touching partners' IDs with their history values, the second atom of a pair holding
//! the negated copy, as LIGGGHTS's pre_exchange stores them).

use std::collections::HashMap;

use crate::engine::contact::UnitStyle;
use crate::engine::error::EngineError;
use crate::engine::sim::Simulation;
use crate::io::restart::{self, GlobalFix, PeratomFix, Restart, Value};
pub use crate::io::restart_values::check_restart_values;

/// Pair contact history read from a restart, waiting for the first neighbour build.
#[derive(Debug, Clone, Default)]
pub struct PendingHistory {
    /// Values per contact in the file.
    pub width: usize,
    /// Per atom ID: (partner ID, values).
    pub partners: HashMap<i64, Vec<(i64, Vec<f64>)>>,
    /// The contacts a run on several ranks left (the list of one process holds them after
    /// a run, so a restart file written now holds them), not those of a file just read.
    pub live: bool,
}

/// LIGGGHTS's numeric IDs of contact sub-models (for the pair style's hash code).
const NORMAL: &[(&str, i64)] = &[
    ("hooke", 0),
    ("hooke/stiffness", 1),
    ("hooke/hysteresis", 2),
    ("hertz", 3),
    ("hertz/stiffness", 4),
];
const TANGENTIAL: &[(&str, i64)] = &[("off", 0), ("no_history", 1), ("history", 2)];
const COHESION: &[(&str, i64)] = &[
    ("off", 0),
    ("sjkr", 1),
    ("sjkr2", 2),
    ("washino/capillary/viscous", 7),
    ("easo/capillary/viscous", 8),
];
const ROLLING: &[(&str, i64)] = &[
    ("off", 0),
    ("cdt", 1),
    ("epsd", 2),
    ("epsd2", 3),
    ("epsd3", 4),
];
const SURFACE: &[(&str, i64)] = &[("default", 0)];

fn id_of(table: &[(&str, i64)], name: &str) -> Option<i64> {
    table.iter().find(|(n, _)| *n == name).map(|(_, k)| *k)
}

fn name_of(table: &[(&'static str, i64)], id: i64) -> Option<&'static str> {
    table.iter().find(|(_, k)| *k == id).map(|(n, _)| *n)
}

/// The hash code LIGGGHTS stores for a `pair_style gran` model combination.
pub fn model_hash(
    normal: &str,
    tangential: &str,
    cohesion: &str,
    rolling: &str,
    surface: &str,
) -> Option<i64> {
    let m = id_of(NORMAL, normal)?;
    let t = id_of(TANGENTIAL, tangential)?;
    let c = id_of(COHESION, cohesion)?;
    let r = id_of(ROLLING, rolling)?;
    let s = id_of(SURFACE, surface)?;
    Some(m | (t << 6) | (c << 12) | (r << 18) | (s << 24))
}

/// The `pair_style gran ...` arguments a hash code stands for.
pub fn model_words(hash: i64) -> Option<String> {
    let part = |shift: i64| (hash >> shift) & 63;
    let normal = name_of(NORMAL, part(0))?;
    let tangential = name_of(TANGENTIAL, part(6))?;
    let cohesion = name_of(COHESION, part(12))?;
    let rolling = name_of(ROLLING, part(18))?;
    name_of(SURFACE, part(24))?;
    let mut w = format!("gran model {normal} tangential {tangential}");
    if cohesion != "off" {
        w.push_str(&format!(" cohesion {cohesion}"));
    }
    if rolling != "off" {
        w.push_str(&format!(" rolling_friction {rolling}"));
    }
    Some(w)
}

/// The pair style stored in a restart (its `pair_style` arguments), if any.
pub fn stored_pair_style(r: &Restart) -> Result<Option<String>, EngineError> {
    match &r.pair {
        None => Ok(None),
        Some((_, raw)) => {
            let hash = i64::from_le_bytes(raw[..8].try_into().expect("8 bytes"));
            model_words(hash).map(Some).ok_or_else(|| {
                format!("the restart's pair style (model hash {hash}) is not one regolith has")
                    .into()
            })
        }
    }
}

/// The partner lists of a contact history fix's per-atom blocks (block `k` of every atom):
/// the history width stored in the fix's global state, and per atom ID its (partner,
/// values) pairs; partners are atom IDs (pairs) or triangle ids (meshes).
fn partner_lists(r: &Restart, k: usize, id: &str) -> Result<(usize, PartnerLists), EngineError> {
    let width = r
        .global_fixes
        .iter()
        .find(|g| g.id == id)
        .and_then(|g| g.state.get(..8))
        .map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")) as usize)
        .unwrap_or(0);
    let mut out = HashMap::new();
    for a in &r.atoms {
        let b = &a.extra[k];
        let n = b.first().map_or(0, |v| v.to_bits() as i64) as usize;
        let expected = width
            .checked_add(1)
            .and_then(|w| n.checked_mul(w))
            .and_then(|v| v.checked_add(1));
        if expected != Some(b.len()) {
            return Err(format!(
                "restart: atom {}: contact history block of {} values for {n} partners of {width} values",
                a.id,
                b.len()
            ).into());
        }
        let list = (0..n)
            .map(|c| {
                let at = 1 + c * (width + 1);
                (b[at].to_bits() as i64, b[at + 1..at + 1 + width].to_vec())
            })
            .collect();
        out.insert(a.id, list);
    }
    Ok((width, out))
}

/// Per atom ID, its contact partners and their history values.
pub type PartnerLists = HashMap<i64, Vec<(i64, Vec<f64>)>>;

impl Simulation {
    /// Load a restart's state into an empty simulation (no box yet). Returns the pair
    /// style it names, for the caller to set up.
    pub fn load_restart(&mut self, r: &Restart) -> Result<Option<String>, EngineError> {
        match r.units() {
            "si" => self.units = UnitStyle::Si,
            "cgs" => self.units = UnitStyle::Cgs,
            other => {
                return Err(format!("units {other} in the restart file: not supported yet").into())
            }
        }
        check_restart_values(r, false)?;
        self.step = r.step();
        self.atime = 0.0;
        self.atime_step = 0;
        self.domain.boundary = r.boundary();
        let (lo, hi) = r.bounds();
        self.domain.create(lo, hi);
        self.ntypes = r.ntypes();
        self.groups = r
            .groups
            .iter()
            .map(|g| g.clone().unwrap_or_default())
            .collect();
        if self.groups.is_empty() {
            self.groups.push("all".into());
        }
        // per-atom fix blocks: property/atom arrays (wall history) and pair history
        let p = &mut self.particles;
        for a in &r.atoms {
            p.push(a.id, a.kind as u32, a.x, a.radius, a.density);
            let i = p.len() - 1;
            p.mass[i] = a.mass;
            p.mask[i] = a.mask as u32;
            p.image[i] = restart::unpack_image(a.image);
            p.v[i] = a.v;
            p.omega[i] = a.omega;
        }
        let mut pending = PendingHistory::default();
        for (k, fix) in r.peratom_fixes.iter().enumerate() {
            match fix.style.as_str() {
                "property/atom" => {
                    let width = r.atoms.first().map_or(0, |a| a.extra[k].len());
                    let e = p.extra_index(&fix.id, width);
                    for (i, a) in r.atoms.iter().enumerate() {
                        let vals = &a.extra[k];
                        if vals.len() != width {
                            return Err(format!(
                                "restart: fix {} has blocks of different sizes",
                                fix.id
                            )
                            .into());
                        }
                        p.extra[e].data[i * width..(i + 1) * width].copy_from_slice(vals);
                    }
                }
                "contacthistory" => {
                    let (width, partners) = partner_lists(r, k, &fix.id)?;
                    pending.width = width;
                    pending.partners = partners;
                }
                "contacthistory/mesh" => {
                    // `tracker_<mesh>`: each atom's triangles and their history
                    let (width, partners) = partner_lists(r, k, &fix.id)?;
                    let lists = partners
                        .into_iter()
                        .map(|(id, l)| (id, l.into_iter().map(|(t, h)| (t as i32, h)).collect()))
                        .collect();
                    self.restart_mesh_history
                        .insert(fix.id.clone(), (width, lists));
                }
                "move" | "spring/self" => {
                    // unwrapped start positions: fix move's origins, fix spring/self's
                    // tether points (keyed by style and ID)
                    let origins = r
                        .atoms
                        .iter()
                        .filter(|a| a.extra[k].len() >= 3)
                        .map(|a| (a.id, [a.extra[k][0], a.extra[k][1], a.extra[k][2]]))
                        .collect();
                    let key = match fix.style.as_str() {
                        "move" => fix.id.clone(),
                        style => format!("{style} {}", fix.id),
                    };
                    self.restart_move_origins.insert(key, origins);
                }
                _ => {} // state of fixes regolith does not have
            }
        }
        self.pending_history = Some(pending);
        stored_pair_style(r)
    }

    /// Fill the freshly built pair list's history from a restart's partner lists: a pair
    /// takes the values its first atom stored for the second (LIGGGHTS's rule).
    pub(crate) fn apply_pending_history(&mut self, pending: PendingHistory, width: usize) {
        if width == 0 || pending.width != width {
            return;
        }
        let flips = self
            .pair
            .as_ref()
            .map_or(vec![true; width], |p| p.history_flips());
        let ids = &self.particles.id;
        self.mirror_history
            .resize(self.list.mirrors.len() * width, 0.0);
        let sides = self.list.pairs.iter().map(|p| (p, false));
        let mirrors = self.list.mirrors.iter().map(|m| (&m.pair, true));
        for (k, (pair, mirror)) in sides.chain(mirrors).enumerate() {
            let (ti, tj) = (ids[pair.i as usize], ids[pair.j as usize]);
            let found = pending
                .partners
                .get(&ti)
                .and_then(|l| l.iter().find(|(t, _)| *t == tj))
                .map(|(_, v)| (v, 1.0))
                .or_else(|| {
                    pending
                        .partners
                        .get(&tj)
                        .and_then(|l| l.iter().find(|(t, _)| *t == ti))
                        .map(|(_, v)| (v, -1.0))
                });
            if let Some((v, sign)) = found {
                let (history, k) = if mirror {
                    (&mut self.mirror_history, k - self.list.pairs.len())
                } else {
                    (&mut self.history, k)
                };
                for (d, x) in history[k * width..(k + 1) * width].iter_mut().enumerate() {
                    *x = if flips[d] { sign * v[d] } else { v[d] };
                }
            }
        }
    }

    /// Pair history per atom ID for every listed pair that has touched (non-zero history):
    /// the pair's first atom holds the values, the second the negated copy (LIGGGHTS's
    /// pre_exchange). Uses the current list, so call it before the list is rebuilt; after a
    /// run on several ranks, the contacts every rank got back. On the fast path each atom's
    /// contacts are listed by partner ID (its list's order depends on how it was built; this
    /// one is the same for any rank and thread count).
    pub fn contact_partners(&self) -> HashMap<i64, Vec<(i64, Vec<f64>)>> {
        let mut out = self.listed_partners();
        if self.accel.fast {
            for contacts in out.values_mut() {
                contacts.sort_by_key(|c| c.0);
            }
        }
        out
    }

    /// [`Self::contact_partners`] in the order of the list (or of the ranks' partner lists).
    fn listed_partners(&self) -> HashMap<i64, Vec<(i64, Vec<f64>)>> {
        let mut out: HashMap<i64, Vec<(i64, Vec<f64>)>> = HashMap::new();
        let width = self.pair.as_ref().map_or(0, |p| p.history_width());
        if let Some(pending) = self.pending_history.as_ref().filter(|h| h.live) {
            if width > 0 && pending.width == width && self.list.pairs.is_empty() {
                return pending.partners.clone();
            }
        }
        let p = &self.particles;
        if width == 0 || self.history.len() != self.list.pairs.len() * width {
            return out;
        }
        let flips = self.pair.as_ref().map_or(Vec::new(), |p| p.history_flips());
        let mirrors = &self.list.mirrors;
        // the fast path keeps one history for both sides of a pair across a periodic face
        // (its list entry's): the mirrors' copies are not kept up to date
        let mirrored = self.list.mirrored
            && !self.accel.fast
            && self.mirror_history.len() == mirrors.len() * width;
        let mut next_mirror = 0;
        for (k, pair) in self.list.pairs.iter().enumerate() {
            // a mirror keeps its own side's values (LIGGGHTS's order: in its atom's entries)
            while mirrored && next_mirror < mirrors.len() && mirrors[next_mirror].at as usize <= k {
                let m = &mirrors[next_mirror];
                let h = &self.mirror_history[next_mirror * width..(next_mirror + 1) * width];
                let (i, j) = (m.pair.i as usize, m.pair.j as usize);
                if i < p.len() && j < p.len() && h.iter().any(|v| *v != 0.0) {
                    out.entry(p.id[i]).or_default().push((p.id[j], h.to_vec()));
                }
                next_mirror += 1;
            }
            let (i, j) = (pair.i as usize, pair.j as usize);
            if i >= p.len() || j >= p.len() {
                continue;
            }
            // LIGGGHTS keeps a pair's history (and stores it) from its first touch for as
            // long as the pair stays listed, touching or not: a pair with history is one
            // that touched
            let h = &self.history[k * width..(k + 1) * width];
            if h.iter().all(|v| *v == 0.0) {
                continue;
            }
            out.entry(p.id[i]).or_default().push((p.id[j], h.to_vec()));
            if mirrored && pair.shift != [0.0; 3] {
                continue;
            }
            out.entry(p.id[j]).or_default().push((
                p.id[i],
                h.iter()
                    .zip(&flips)
                    .map(|(v, &f)| if f { -v } else { *v })
                    .collect(),
            ));
        }
        for (k, m) in mirrors.iter().enumerate().skip(next_mirror) {
            if !mirrored {
                break;
            }
            let h = &self.mirror_history[k * width..(k + 1) * width];
            let (i, j) = (m.pair.i as usize, m.pair.j as usize);
            if i < p.len() && j < p.len() && h.iter().any(|v| *v != 0.0) {
                out.entry(p.id[i]).or_default().push((p.id[j], h.to_vec()));
            }
        }
        out
    }

    /// Whether a restart file of this simulation fits in memory (the file is built whole,
    /// then encoded): LIGGGHTS's "Failed to allocate" if it does not.
    pub fn check_restart_size(&self) -> Result<(), EngineError> {
        // the servo module's state (centre, velocity, controller) is not written yet
        if let Some(f) = self
            .fixes
            .iter()
            .find(|f| f.kind.mesh().is_some_and(|m| m.servo.is_some()))
        {
            return Err(EngineError::Unsupported(format!(
                "a restart file with fix mesh/surface/stress/servo (id {})",
                f.id
            )));
        }
        let n = self.ntypes as f64;
        let pair = if self.pair_selection.is_some() {
            8.0 + 4.0 * n * (n + 1.0) / 2.0
        } else {
            0.0
        };
        let extra: usize = self.particles.extra.iter().map(|e| e.width + 1).sum();
        let atoms = self.particles.len() as f64 * 8.0 * (24 + extra) as f64;
        // the file's parts, its atom records and the encoded bytes
        Ok(crate::engine::checks::allocation(
            3.0 * (pair + atoms),
            1,
            "restart file",
        )?)
    }

    /// The restart file's pair style entry: the granular model's hash and one flag per
    /// type pair (None without a hashed granular model).
    fn pair_restart_entry(&self) -> Option<(String, Vec<u8>)> {
        if let Some(sel) = &self.pair_selection {
            if let Some(hash) = model_hash(
                &sel.normal,
                &sel.tangential,
                &sel.cohesion,
                &sel.rolling,
                &sel.surface,
            ) {
                let n = self.ntypes as usize;
                let mut raw = Vec::with_capacity(8 + 4 * (n * (n + 1) / 2));
                raw.extend_from_slice(&hash.to_le_bytes());
                for _ in 0..n * (n + 1) / 2 {
                    raw.extend_from_slice(&1i32.to_le_bytes());
                }
                return Some(("gran".into(), raw));
            }
        }
        None
    }

    /// The per-atom values written to a restart file as `property/atom` fixes: primitive
    /// walls' contact history (when their model keeps one) and `fix property/atom` values
    /// with restart `yes`.
    fn restarted_per_atom(&self) -> Vec<&crate::engine::particles::PerAtom> {
        let wall_history = |e: &crate::engine::particles::PerAtom| {
            // LIGGGHTS keeps a primitive wall's history only when its model has one
            e.width > 0
                && self.fixes.iter().any(|f| {
                    f.kind
                        .primitive_wall()
                        .is_some_and(|w| w.history_name == e.name)
                })
        };
        let kept_property = |e: &crate::engine::particles::PerAtom| {
            // property/atom fixes with restart `yes` (the heat fixes' Temp too)
            self.fixes.iter().any(|f| {
                f.kind
                    .property_atom()
                    .is_some_and(|pa| pa.restart && f.id == e.name && pa.defaults.len() == e.width)
            })
        };
        self.particles
            .extra
            .iter()
            .filter(|e| wall_history(e) || kept_property(e))
            .collect()
    }

    /// This simulation as a restart file LIGGGHTS 3.8.0 reads, with pair history from
    /// [`Simulation::contact_partners`].
    pub fn to_restart(&self, partners: &HashMap<i64, Vec<(i64, Vec<f64>)>>) -> Restart {
        let units = match self.units {
            UnitStyle::Cgs => "cgs",
            _ => "si",
        };
        let mut r = restart::fresh_header(&self.domain, self.ntypes, units);
        for (f, v) in r.header.iter_mut() {
            match *f {
                5 => *v = Value::Big(self.step),
                23 => *v = Value::Big(self.particles.len() as i64),
                _ => {}
            }
        }
        r.groups = self
            .groups
            .iter()
            .map(|g| (!g.is_empty()).then(|| g.clone()))
            .collect();
        r.ngroup = r.groups.iter().filter(|g| g.is_some()).count() as i32;
        let width = self.pair.as_ref().map_or(0, |p| p.history_width());
        r.pair = self.pair_restart_entry();
        // fix states in fix order (templates, distributions, meshes, insertion, release
        // data), then wall histories of existing walls, then the pair contact history
        let (globals, release) = self.fix_restart_entries();
        r.global_fixes.extend(globals);
        for (header, _) in &release {
            r.peratom_fixes.push(header.clone());
        }
        let p = &self.particles;
        let walls = self.restarted_per_atom();
        for w in &walls {
            r.global_fixes.push(GlobalFix {
                id: w.name.clone(),
                style: "property/atom".into(),
                state: (w.width as f64).to_le_bytes().to_vec(),
            });
            r.peratom_fixes.push(PeratomFix {
                id: w.name.clone(),
                style: "property/atom".into(),
                maxsize: w.width as i32 + 1,
            });
        }
        let none = Vec::new();
        let of = |i: usize| partners.get(&p.id[i]).unwrap_or(&none);
        if width > 0 {
            let maxtouch = partners.values().map(Vec::len).max().unwrap_or(0);
            let mut state = (width as f64).to_le_bytes().to_vec();
            state.extend_from_slice(&(maxtouch as f64).to_le_bytes());
            r.global_fixes.push(GlobalFix {
                id: "contacthistory".into(),
                style: "contacthistory".into(),
                state,
            });
            r.peratom_fixes.push(PeratomFix {
                id: "contacthistory".into(),
                style: "contacthistory".into(),
                maxsize: ((width + 1) * maxtouch + 2) as i32,
            });
        }
        r.atoms = (0..p.len())
            .map(|i| {
                let mut extra: Vec<Vec<f64>> =
                    release.iter().map(|(_, rows)| rows[i].clone()).collect();
                extra.extend(
                    walls
                        .iter()
                        .map(|w| w.data[i * w.width..(i + 1) * w.width].to_vec()),
                );
                if width > 0 {
                    let mut b = vec![f64::from_bits(of(i).len() as u64)];
                    for (t, h) in of(i) {
                        b.push(f64::from_bits(*t as u64));
                        b.extend_from_slice(h);
                    }
                    extra.push(b);
                }
                restart::AtomRecord {
                    x: p.x[i],
                    id: p.id[i],
                    kind: p.kind[i] as i64,
                    mask: p.mask[i] as i64,
                    image: restart::pack_image(p.image[i]),
                    v: p.v[i],
                    radius: p.radius[i],
                    mass: p.mass[i],
                    density: p.density[i],
                    omega: p.omega[i],
                    extra,
                }
            })
            .collect();
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn model_hash_codes() {
        // hertz (3), history (2), sjkr (1), epsd (2), default (0)
        let h = model_hash("hertz", "history", "sjkr", "epsd", "default").unwrap();
        assert_eq!(h, 3 | (2 << 6) | (1 << 12) | (2 << 18));
        assert_eq!(
            model_words(h).unwrap(),
            "gran model hertz tangential history cohesion sjkr rolling_friction epsd"
        );
        assert!(model_words(63).is_none());
        // LIGGGHTS's liquid bridges (cohesion_model_easo_capillary_viscous.h: 8)
        let h = model_hash(
            "hertz",
            "history",
            "easo/capillary/viscous",
            "off",
            "default",
        );
        assert_eq!(h, Some(32899));
    }
}
