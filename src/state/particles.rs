//! Per-particle state as a structure of arrays: one contiguous vector per quantity, so force
//! loops stream through memory and vectorise. Vectors are `[f64; 3]` (x, y, z).
use crate::state::limits::LimitError;

/// All particles of the simulation (SI units unless the deck says otherwise).
#[derive(Debug, Clone, Default)]
pub struct Particles {
    /// Atom IDs (LIGGGHTS `tag`), 1-based.
    pub id: Vec<i64>,
    /// Atom types, 1-based.
    pub kind: Vec<u32>,
    /// Group membership bits (bit 0 is group `all`).
    pub mask: Vec<u32>,
    /// Positions (length).
    pub x: Vec<[f64; 3]>,
    /// Velocities (length/time).
    pub v: Vec<[f64; 3]>,
    /// Forces (force).
    pub f: Vec<[f64; 3]>,
    /// Angular velocities (1/time).
    pub omega: Vec<[f64; 3]>,
    /// Torques (force x length).
    pub torque: Vec<[f64; 3]>,
    /// Radii (length).
    pub radius: Vec<f64>,
    /// Masses (mass).
    pub mass: Vec<f64>,
    /// Densities (mass/length^3).
    pub density: Vec<f64>,
    /// Periodic image counts per direction.
    pub image: Vec<[i32; 3]>,
    /// Extra per-particle arrays owned by fixes (e.g. wall contact history), kept in step
    /// with the particles when they are reordered or removed.
    pub extra: Vec<PerAtom>,
}

/// A named per-particle array of `width` doubles per particle.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PerAtom {
    /// Name (e.g. `history_wall1`).
    pub name: String,
    /// Values per particle.
    pub width: usize,
    /// The values, particle-major.
    pub data: Vec<f64>,
    /// The values a new particle starts with (`width` of them; empty: zeros).
    pub fill: Vec<f64>,
}

impl Particles {
    /// Index of the extra array `name`, creating it (zero-filled) if needed.
    pub fn extra_index(&mut self, name: &str, width: usize) -> usize {
        if let Some(k) = self
            .extra
            .iter()
            .position(|e| e.name == name && e.width == width)
        {
            return k;
        }
        self.extra.retain(|e| e.name != name);
        self.extra.push(PerAtom {
            name: name.to_string(),
            width,
            data: vec![0.0; width * self.len()],
            fill: Vec::new(),
        });
        self.extra.len() - 1
    }
}

impl Particles {
    /// Number of particles.
    pub fn len(&self) -> usize {
        self.id.len()
    }

    /// True when there are no particles.
    pub fn is_empty(&self) -> bool {
        self.id.is_empty()
    }

    /// Set every force (force units) and torque (force*length) to zero.
    pub fn clear_forces(&mut self) {
        self.f.fill([0.0; 3]);
        self.torque.fill([0.0; 3]);
    }

    /// Append a particle at rest with the given id, type, position, radius (length) and
    /// density (mass/length^3); its mass is that of a sphere.
    pub fn push(&mut self, id: i64, kind: u32, x: [f64; 3], radius: f64, density: f64) {
        self.id.push(id);
        self.kind.push(kind);
        self.mask.push(1);
        self.x.push(x);
        self.v.push([0.0; 3]);
        self.f.push([0.0; 3]);
        self.omega.push([0.0; 3]);
        self.torque.push([0.0; 3]);
        self.radius.push(radius);
        self.mass.push(sphere_mass(radius, density));
        self.density.push(density);
        self.image.push([0; 3]);
        for e in &mut self.extra {
            if e.fill.len() == e.width {
                e.data.extend_from_slice(&e.fill);
            } else {
                e.data.extend(std::iter::repeat_n(0.0, e.width));
            }
        }
    }

    /// Make room for `additional` more particles, or say why there is none (LIGGGHTS's
    /// "Failed to allocate"); a request beyond the machine is refused before any allocation.
    pub fn try_reserve(&mut self, additional: usize) -> Result<(), LimitError> {
        let extra: usize = self.extra.iter().map(|e| e.width * 8).sum();
        let per_atom = Self::BYTES_PER_ATOM + extra;
        let what = "atoms";
        crate::state::limits::allocation(additional as f64, per_atom, what)?;
        let fail = |_| LimitError::Allocation {
            bytes: additional as f64 * per_atom as f64,
            what: what.to_string(),
        };
        self.id.try_reserve(additional).map_err(fail)?;
        self.kind.try_reserve(additional).map_err(fail)?;
        self.mask.try_reserve(additional).map_err(fail)?;
        for v in [
            &mut self.x,
            &mut self.v,
            &mut self.f,
            &mut self.omega,
            &mut self.torque,
        ] {
            v.try_reserve(additional).map_err(fail)?;
        }
        for v in [&mut self.radius, &mut self.mass, &mut self.density] {
            v.try_reserve(additional).map_err(fail)?;
        }
        self.image.try_reserve(additional).map_err(fail)?;
        for e in &mut self.extra {
            e.data.try_reserve(additional * e.width).map_err(fail)?;
        }
        Ok(())
    }

    /// Bytes the per-particle arrays take for one particle.
    pub const BYTES_PER_ATOM: usize = 8 + 4 + 4 + 5 * 24 + 3 * 8 + 12;

    /// Remove the particles for which `remove` is true, keeping the others' order.
    pub fn retain_by(&mut self, remove: &[bool]) {
        fn keep<T: Copy>(v: &mut Vec<T>, remove: &[bool]) {
            let mut i = 0;
            v.retain(|_| {
                let k = !remove[i];
                i += 1;
                k
            });
        }
        keep(&mut self.id, remove);
        keep(&mut self.kind, remove);
        keep(&mut self.mask, remove);
        keep(&mut self.x, remove);
        keep(&mut self.v, remove);
        keep(&mut self.f, remove);
        keep(&mut self.omega, remove);
        keep(&mut self.torque, remove);
        keep(&mut self.radius, remove);
        keep(&mut self.mass, remove);
        keep(&mut self.density, remove);
        keep(&mut self.image, remove);
        for e in &mut self.extra {
            let w = e.width;
            let mut out = Vec::with_capacity(e.data.len());
            for (i, r) in remove.iter().enumerate() {
                if !r {
                    out.extend_from_slice(&e.data[i * w..(i + 1) * w]);
                }
            }
            e.data = out;
        }
    }

    /// Remove the particles for which `remove` is true as LIGGGHTS's `delete_atoms` does:
    /// walking up from the first, each removed particle's slot is filled by the last
    /// particle (which is examined next).
    pub fn remove_filling_from_last(&mut self, remove: &[bool]) {
        for i in slots_filled_from_last(remove, self.len()) {
            self.fill_from_last(i);
        }
    }

    /// Remove particle `i` as LIGGGHTS deletes one: the last particle moves into its slot.
    pub fn fill_from_last(&mut self, i: usize) {
        fn fill<T: Copy>(v: &mut Vec<T>, i: usize) {
            v.swap_remove(i);
        }
        fill(&mut self.id, i);
        fill(&mut self.kind, i);
        fill(&mut self.mask, i);
        fill(&mut self.x, i);
        fill(&mut self.v, i);
        fill(&mut self.f, i);
        fill(&mut self.omega, i);
        fill(&mut self.torque, i);
        fill(&mut self.radius, i);
        fill(&mut self.mass, i);
        fill(&mut self.density, i);
        fill(&mut self.image, i);
        let n = self.id.len();
        for e in &mut self.extra {
            let w = e.width;
            if i < n {
                e.data.copy_within(n * w..(n + 1) * w, i * w);
            }
            e.data.truncate(n * w);
        }
    }

    /// Keep the first `n` particles (e.g. the owned ones, dropping the ghosts after them).
    pub fn truncate(&mut self, n: usize) {
        self.id.truncate(n);
        self.kind.truncate(n);
        self.mask.truncate(n);
        self.x.truncate(n);
        self.v.truncate(n);
        self.f.truncate(n);
        self.omega.truncate(n);
        self.torque.truncate(n);
        self.radius.truncate(n);
        self.mass.truncate(n);
        self.density.truncate(n);
        self.image.truncate(n);
        for e in &mut self.extra {
            e.data.truncate(n * e.width);
        }
    }

    /// Split off the particles from index `n` on (e.g. the ghosts after the owned ones),
    /// with their extra arrays; `self` keeps the first `n`.
    pub fn split_off(&mut self, n: usize) -> Particles {
        Particles {
            id: self.id.split_off(n),
            kind: self.kind.split_off(n),
            mask: self.mask.split_off(n),
            x: self.x.split_off(n),
            v: self.v.split_off(n),
            f: self.f.split_off(n),
            omega: self.omega.split_off(n),
            torque: self.torque.split_off(n),
            radius: self.radius.split_off(n),
            mass: self.mass.split_off(n),
            density: self.density.split_off(n),
            image: self.image.split_off(n),
            extra: self
                .extra
                .iter_mut()
                .map(|e| PerAtom {
                    name: e.name.clone(),
                    width: e.width,
                    data: e.data.split_off(n * e.width),
                    fill: e.fill.clone(),
                })
                .collect(),
        }
    }

    /// Copy the particles from index `n` on into `out`, replacing its particles (its extra
    /// arrays become this one's); `self` is unchanged.
    pub fn copy_tail_into(&self, n: usize, out: &mut Particles) {
        fn copy<T: Copy>(src: &[T], n: usize, dst: &mut Vec<T>) {
            dst.clear();
            dst.extend_from_slice(&src[n.min(src.len())..]);
        }
        copy(&self.id, n, &mut out.id);
        copy(&self.kind, n, &mut out.kind);
        copy(&self.mask, n, &mut out.mask);
        copy(&self.x, n, &mut out.x);
        copy(&self.v, n, &mut out.v);
        copy(&self.f, n, &mut out.f);
        copy(&self.omega, n, &mut out.omega);
        copy(&self.torque, n, &mut out.torque);
        copy(&self.radius, n, &mut out.radius);
        copy(&self.mass, n, &mut out.mass);
        copy(&self.density, n, &mut out.density);
        copy(&self.image, n, &mut out.image);
        out.extra.resize_with(self.extra.len(), PerAtom::default);
        for (e, o) in self.extra.iter().zip(out.extra.iter_mut()) {
            o.name.clone_from(&e.name);
            o.width = e.width;
            o.fill.clone_from(&e.fill);
            copy(&e.data, n * e.width, &mut o.data);
        }
    }

    /// Append copies of the particles of `other`; an extra array of this one that `other`
    /// lacks (by name and width) gets its new particles' fill values.
    pub fn extend_from(&mut self, other: &Particles) {
        self.id.extend_from_slice(&other.id);
        self.kind.extend_from_slice(&other.kind);
        self.mask.extend_from_slice(&other.mask);
        self.x.extend_from_slice(&other.x);
        self.v.extend_from_slice(&other.v);
        self.f.extend_from_slice(&other.f);
        self.omega.extend_from_slice(&other.omega);
        self.torque.extend_from_slice(&other.torque);
        self.radius.extend_from_slice(&other.radius);
        self.mass.extend_from_slice(&other.mass);
        self.density.extend_from_slice(&other.density);
        self.image.extend_from_slice(&other.image);
        let n = other.len();
        for (k, e) in self.extra.iter_mut().enumerate() {
            let same = |o: &&PerAtom| o.name == e.name && o.width == e.width;
            let found = other.extra.get(k).filter(same);
            match found.or_else(|| other.extra.iter().find(same)) {
                Some(o) => e.data.extend_from_slice(&o.data),
                None => {
                    for _ in 0..n {
                        if e.fill.len() == e.width {
                            e.data.extend_from_slice(&e.fill);
                        } else {
                            e.data.resize(e.data.len() + e.width, 0.0);
                        }
                    }
                }
            }
        }
    }

    /// Append the particles of `other` (split off by [`Self::split_off`], so its extra
    /// arrays are this one's, in the same order), leaving it empty.
    pub fn append(&mut self, other: &mut Particles) {
        self.id.append(&mut other.id);
        self.kind.append(&mut other.kind);
        self.mask.append(&mut other.mask);
        self.x.append(&mut other.x);
        self.v.append(&mut other.v);
        self.f.append(&mut other.f);
        self.omega.append(&mut other.omega);
        self.torque.append(&mut other.torque);
        self.radius.append(&mut other.radius);
        self.mass.append(&mut other.mass);
        self.density.append(&mut other.density);
        self.image.append(&mut other.image);
        for (e, o) in self.extra.iter_mut().zip(other.extra.iter_mut()) {
            e.data.append(&mut o.data);
        }
    }

    /// Reorder every array by `order` (new index -> old index), e.g. to sort by cell.
    pub fn permute(&mut self, order: &[usize]) {
        fn apply<T: Copy>(v: &mut Vec<T>, order: &[usize]) {
            let old = std::mem::take(v);
            v.extend(order.iter().map(|&i| old[i]));
        }
        apply(&mut self.id, order);
        apply(&mut self.kind, order);
        apply(&mut self.mask, order);
        apply(&mut self.x, order);
        apply(&mut self.v, order);
        apply(&mut self.f, order);
        apply(&mut self.omega, order);
        apply(&mut self.torque, order);
        apply(&mut self.radius, order);
        apply(&mut self.mass, order);
        apply(&mut self.density, order);
        apply(&mut self.image, order);
        for e in &mut self.extra {
            let w = e.width;
            let old = std::mem::take(&mut e.data);
            for &i in order {
                e.data.extend_from_slice(&old[i * w..(i + 1) * w]);
            }
        }
    }

    /// Largest atom ID in use (0 when empty).
    pub fn max_id(&self) -> i64 {
        self.id.iter().copied().max().unwrap_or(0)
    }
}

/// Mass of a sphere of radius `r` and density `rho`, as LIGGGHTS computes it (4/3 pi r^3 rho).
pub fn sphere_mass(r: f64, rho: f64) -> f64 {
    4.0 * std::f64::consts::PI / 3.0 * r * r * r * rho
}

impl AsRef<Particles> for Particles {
    fn as_ref(&self) -> &Particles {
        self
    }
}

/// The slots LIGGGHTS's `delete_atoms` fills, in order, when removing the flagged ones of
/// `len` particles: walking up from the first, each removed slot takes the last particle
/// (which is examined next), and the count shrinks by one each time.
pub fn slots_filled_from_last(remove: &[bool], len: usize) -> Vec<usize> {
    let mut flags = remove.to_vec();
    flags.resize(len, false);
    let (mut i, mut n, mut filled) = (0, len, Vec::new());
    while i < n {
        if flags[i] {
            flags[i] = flags[n - 1];
            filled.push(i);
            n -= 1;
        } else {
            i += 1;
        }
    }
    filled
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ghosts_split_off_and_appended_come_back_unchanged() {
        let mut p = Particles::default();
        let k = p.extra_index("history_wall", 2);
        for id in 1..=5 {
            p.push(id, 1, [id as f64, 0.0, 0.0], 0.1, 2500.0);
        }
        p.extra[k].data = (0..10).map(f64::from).collect();
        let before = format!("{p:?}");
        let mut ghosts = p.split_off(3);
        assert_eq!((p.len(), ghosts.len()), (3, 2));
        assert_eq!(ghosts.id, vec![4, 5]);
        assert_eq!(ghosts.extra[0].data, vec![6.0, 7.0, 8.0, 9.0]);
        assert_eq!(p.extra[0].data.len(), 6);
        p.append(&mut ghosts);
        assert!(ghosts.is_empty());
        assert_eq!(format!("{p:?}"), before);
    }

    #[test]
    fn push_remove_permute() {
        let mut p = Particles::default();
        for i in 0..4 {
            p.push(i + 1, 1, [i as f64, 0.0, 0.0], 0.5, 1000.0);
        }
        assert!((p.mass[0] - 4.0 / 3.0 * std::f64::consts::PI * 0.125 * 1000.0).abs() < 1e-12);
        p.retain_by(&[false, true, false, false]);
        assert_eq!(p.id, [1, 3, 4]);
        p.permute(&[2, 0, 1]);
        assert_eq!(p.id, [4, 1, 3]);
        assert_eq!(p.x[0], [3.0, 0.0, 0.0]);
        assert_eq!(p.max_id(), 4);
    }
}
