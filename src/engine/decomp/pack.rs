//! Particles to bytes and back, for messages between ranks: every per-particle array of
//! [`Particles`] (the fixes' `extra` arrays included) and the contact history a particle
//! carries ([`PartnerHistory`]). Numbers are little-endian; doubles keep their bits.

use crate::engine::particles::Particles;

/// Why a message between ranks could not be read.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum DecompError {
    /// A message ended before the record it announced.
    #[error("a message between ranks ended early ({need} bytes needed at byte {at} of {len})")]
    Truncated {
        /// Bytes the next field needed.
        need: usize,
        /// Where it started.
        at: usize,
        /// The message length.
        len: usize,
    },
    /// A ghost plan that does not fit the particle arrays it is replayed on.
    #[error(
        "the ghost plan names {ghosts} ghosts, which the {particles} particle slots do not hold"
    )]
    PlanMismatch {
        /// Ghost slots the plan writes up to.
        ghosts: usize,
        /// Particle slots there are.
        particles: usize,
    },
    /// Ranks disagree on the per-particle arrays fixes keep.
    #[error("ranks disagree on the per-atom arrays of fixes (expected {expected} values per atom, a message has {found})")]
    ExtraWidth {
        /// Values per particle this rank keeps.
        expected: usize,
        /// Values per particle the message holds.
        found: usize,
    },
}

/// Appends numbers to a message.
#[derive(Debug, Default)]
pub struct Writer {
    /// The message so far.
    pub bytes: Vec<u8>,
}

impl Writer {
    /// Append a double.
    pub fn f64(&mut self, v: f64) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    /// Append three doubles.
    pub fn vec3(&mut self, v: [f64; 3]) {
        v.iter().for_each(|&c| self.f64(c));
    }
    /// Append a signed integer.
    pub fn i64(&mut self, v: i64) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    /// Append an unsigned 32-bit integer.
    pub fn u32(&mut self, v: u32) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
    /// Append a signed 32-bit integer.
    pub fn i32(&mut self, v: i32) {
        self.bytes.extend_from_slice(&v.to_le_bytes());
    }
}

/// Reads numbers off a message in the order they were written.
#[derive(Debug)]
pub struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    /// Read `bytes` from the start.
    pub fn new(bytes: &'a [u8]) -> Reader<'a> {
        Reader { bytes, at: 0 }
    }
    /// True when every byte has been read.
    pub fn done(&self) -> bool {
        self.at >= self.bytes.len()
    }
    /// The read position (bytes).
    pub fn position(&self) -> usize {
        self.at
    }
    /// Move the read position to `at` (bytes).
    pub fn seek(&mut self, at: usize) {
        self.at = at;
    }
    fn take<const N: usize>(&mut self) -> Result<[u8; N], DecompError> {
        let end = self.at + N;
        let slice = self.bytes.get(self.at..end).ok_or(DecompError::Truncated {
            need: N,
            at: self.at,
            len: self.bytes.len(),
        })?;
        let mut w = [0u8; N];
        w.copy_from_slice(slice);
        self.at = end;
        Ok(w)
    }
    /// Read a double.
    pub fn f64(&mut self) -> Result<f64, DecompError> {
        Ok(f64::from_le_bytes(self.take()?))
    }
    /// Read three doubles.
    pub fn vec3(&mut self) -> Result<[f64; 3], DecompError> {
        Ok([self.f64()?, self.f64()?, self.f64()?])
    }
    /// Read a signed integer.
    pub fn i64(&mut self) -> Result<i64, DecompError> {
        Ok(i64::from_le_bytes(self.take()?))
    }
    /// Read an unsigned 32-bit integer.
    pub fn u32(&mut self) -> Result<u32, DecompError> {
        Ok(u32::from_le_bytes(self.take()?))
    }
    /// Read a signed 32-bit integer.
    pub fn i32(&mut self) -> Result<i32, DecompError> {
        Ok(i32::from_le_bytes(self.take()?))
    }
}

/// Contact history kept with the particles (LIGGGHTS's per-atom partner lists): for each
/// particle, the IDs of the partners it touches and `width` history values per partner,
/// as seen from that particle. Moves with its particle between ranks.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PartnerHistory {
    /// History values per contact.
    pub width: usize,
    /// Partner IDs, per particle.
    pub partners: Vec<Vec<i64>>,
    /// `width` values per partner, partner-major, per particle.
    pub values: Vec<Vec<f64>>,
    /// Per-atom state of fixes that travels with the particle besides its pair contacts
    /// (the mesh walls' candidate triangles and contact history), as the fixes encode it.
    pub attached: Vec<Vec<f64>>,
}

impl PartnerHistory {
    /// No contacts for `n` particles, `width` values per contact.
    pub fn new(width: usize, n: usize) -> PartnerHistory {
        PartnerHistory {
            width,
            partners: vec![Vec::new(); n],
            values: vec![Vec::new(); n],
            attached: vec![Vec::new(); n],
        }
    }

    /// The history of particle `i` with partner `id`, if any.
    pub fn get(&self, i: usize, id: i64) -> Option<&[f64]> {
        let k = self.partners.get(i)?.iter().position(|&p| p == id)?;
        Some(&self.values[i][k * self.width..(k + 1) * self.width])
    }

    /// Record `values` as particle `i`'s history with partner `id`.
    pub fn insert(&mut self, i: usize, id: i64, values: &[f64]) {
        self.partners[i].push(id);
        self.values[i].extend_from_slice(&values[..self.width]);
    }

    /// Remove particle `i`, the last one taking its place (as [`Particles::fill_from_last`]).
    pub fn fill_from_last(&mut self, i: usize) {
        if i < self.partners.len() {
            self.partners.swap_remove(i);
            self.values.swap_remove(i);
        }
        if i < self.attached.len() {
            self.attached.swap_remove(i);
        }
    }
}

/// Values per particle in the fixes' extra arrays.
pub fn extra_width(p: &Particles) -> usize {
    p.extra.iter().map(|e| e.width).sum()
}

/// Append particle `i` (every array; `shift` added to its position, length) and, when
/// given, its contact history, as one record led by its length.
pub fn pack_particle(
    w: &mut Writer,
    p: &Particles,
    i: usize,
    shift: [f64; 3],
    hist: Option<&PartnerHistory>,
) {
    let start = w.bytes.len();
    w.u32(0);
    w.i64(p.id[i]);
    w.u32(p.kind[i]);
    w.u32(p.mask[i]);
    w.vec3([0, 1, 2].map(|d| p.x[i][d] + shift[d]));
    for v in [p.v[i], p.f[i], p.omega[i], p.torque[i]] {
        w.vec3(v);
    }
    w.f64(p.radius[i]);
    w.f64(p.mass[i]);
    w.f64(p.density[i]);
    p.image[i].iter().for_each(|&m| w.i32(m));
    w.u32(extra_width(p) as u32);
    for e in &p.extra {
        e.data[i * e.width..(i + 1) * e.width]
            .iter()
            .for_each(|&v| w.f64(v));
    }
    if let Some(h) = hist {
        w.u32(h.partners[i].len() as u32);
        for (&id, vals) in h.partners[i].iter().zip(h.values[i].chunks(h.width.max(1))) {
            w.i64(id);
            vals.iter().take(h.width).for_each(|&v| w.f64(v));
        }
        let attached = h.attached.get(i).map_or(&[][..], Vec::as_slice);
        w.u32(attached.len() as u32);
        attached.iter().for_each(|&v| w.f64(v));
    }
    let len = (w.bytes.len() - start) as u32;
    w.bytes[start..start + 4].copy_from_slice(&len.to_le_bytes());
}

/// The position of the record starting at the reader's position, and where it ends.
pub fn peek_position(r: &mut Reader) -> Result<([f64; 3], usize), DecompError> {
    let start = r.position();
    let len = r.u32()? as usize;
    r.i64()?;
    r.u32()?;
    r.u32()?;
    let x = r.vec3()?;
    r.seek(start);
    Ok((x, start + len))
}

/// Read one record written by [`pack_particle`] and append the particle to `p` (and its
/// contact history to `hist` when given: the record must then hold one).
pub fn unpack_particle(
    r: &mut Reader,
    p: &mut Particles,
    hist: Option<&mut PartnerHistory>,
) -> Result<(), DecompError> {
    r.u32()?;
    let id = r.i64()?;
    let kind = r.u32()?;
    let mask = r.u32()?;
    let x = r.vec3()?;
    let [v, f, omega, torque] = [r.vec3()?, r.vec3()?, r.vec3()?, r.vec3()?];
    let (radius, mass, density) = (r.f64()?, r.f64()?, r.f64()?);
    let image = [r.i32()?, r.i32()?, r.i32()?];
    let width = r.u32()? as usize;
    if width != extra_width(p) {
        return Err(DecompError::ExtraWidth {
            expected: extra_width(p),
            found: width,
        });
    }
    let mut extra = Vec::with_capacity(width);
    for _ in 0..width {
        extra.push(r.f64()?);
    }
    // the whole record is read before anything is appended
    let contacts = match &hist {
        Some(h) => {
            let n = r.u32()? as usize;
            let mut partners = Vec::with_capacity(n);
            let mut values = Vec::with_capacity(n * h.width);
            for _ in 0..n {
                partners.push(r.i64()?);
                for _ in 0..h.width {
                    values.push(r.f64()?);
                }
            }
            let n = r.u32()? as usize;
            let mut attached = Vec::with_capacity(n);
            for _ in 0..n {
                attached.push(r.f64()?);
            }
            Some((partners, values, attached))
        }
        None => None,
    };
    p.id.push(id);
    p.kind.push(kind);
    p.mask.push(mask);
    p.x.push(x);
    p.v.push(v);
    p.f.push(f);
    p.omega.push(omega);
    p.torque.push(torque);
    p.radius.push(radius);
    p.mass.push(mass);
    p.density.push(density);
    p.image.push(image);
    let mut k = 0;
    for e in &mut p.extra {
        e.data.extend_from_slice(&extra[k..k + e.width]);
        k += e.width;
    }
    if let (Some(h), Some((partners, values, attached))) = (hist, contacts) {
        h.partners.push(partners);
        h.values.push(values);
        h.attached.push(attached);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_particle_survives_the_round_trip_bit_for_bit() {
        let mut p = Particles::default();
        let k = p.extra_index("history_wall", 2);
        p.push(7, 2, [0.1, 0.2, 0.3], 0.004, 2500.0);
        p.v[0] = [1.0 / 3.0, -0.0, 1e-300];
        p.omega[0] = [f64::MIN_POSITIVE, 2.0, 3.0];
        p.image[0] = [-1, 0, 5];
        p.extra[k].data = vec![0.25, -7.5];
        let mut h = PartnerHistory::new(3, 1);
        h.insert(0, 12, &[1.0, 2.0, 3.0]);
        h.insert(0, 3, &[-1.0, -2.0, -3.0]);
        h.attached[0] = vec![2.0, 0.5, -1e-300];
        let mut w = Writer::default();
        pack_particle(&mut w, &p, 0, [10.0, 0.0, 0.0], Some(&h));
        let mut q = Particles::default();
        q.extra_index("history_wall", 2);
        let mut g = PartnerHistory::new(3, 0);
        let mut r = Reader::new(&w.bytes);
        assert_eq!(
            peek_position(&mut r).unwrap(),
            ([10.1, 0.2, 0.3], w.bytes.len())
        );
        unpack_particle(&mut r, &mut q, Some(&mut g)).unwrap();
        assert!(r.done());
        assert_eq!(q.x[0], [10.1, 0.2, 0.3]);
        q.x[0] = p.x[0];
        assert_eq!(format!("{q:?}"), format!("{p:?}"));
        assert_eq!(g, h);
        // a cut message and a rank without the fix's array are refused
        let mut r = Reader::new(&w.bytes[..40]);
        assert!(matches!(
            unpack_particle(&mut r, &mut q, None),
            Err(DecompError::Truncated { .. })
        ));
        let mut r = Reader::new(&w.bytes);
        assert_eq!(
            unpack_particle(&mut r, &mut Particles::default(), None),
            Err(DecompError::ExtraWidth {
                expected: 0,
                found: 2
            })
        );
    }
}
