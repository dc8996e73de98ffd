//! The touching test: which listed pairs overlap this step, four at a time where the
//! processor allows, in list order.

use super::*;

/// Indices (into `pairs`, plus `offset`) of the listed pairs whose spheres overlap, in list
/// order, appended to `out`. Branch-free: every entry is written, the count advances only
/// on contact.
pub fn touching_entries(packed: &Packed, pairs: &[Pair], offset: usize, out: &mut Vec<u32>) {
    let rec = &packed.spheres[..];
    if rec.is_empty() {
        return;
    }
    let start = out.len();
    out.reserve(pairs.len());
    let dst = &mut out.spare_capacity_mut()[..pairs.len()];
    let mut n = 0;
    let mut done = 0;
    #[cfg(target_arch = "x86_64")]
    if crate::engine::contact::real::lanes_supported() {
        // SAFETY: the processor has AVX2 (checked at run time)
        (n, done) = unsafe { touching_avx2(rec, pairs, offset, dst) };
    }
    n += touching_one_by_one(rec, &pairs[done..], offset + done, &mut dst[n..]);
    // SAFETY: the first n slots past `start` were written above
    unsafe { out.set_len(start + n) };
}

/// The touching test pair by pair: writes the touching entries to `dst`, returns how many.
pub(super) fn touching_one_by_one(
    rec: &[Sphere],
    pairs: &[Pair],
    offset: usize,
    dst: &mut [std::mem::MaybeUninit<u32>],
) -> usize {
    let last = rec.len() - 1;
    let dst = &mut dst[..pairs.len()];
    let mut n = 0;
    for (k, pair) in pairs.iter().enumerate() {
        // every pair indexes packed particles; clamped all the same (two conditional
        // moves, no branch), so the unchecked loads below stay inside the records
        let (i, j) = ((pair.i as usize).min(last), (pair.j as usize).min(last));
        // SAFETY: i, j <= last < rec.len(); n <= k < dst.len()
        let (a, b, slot) = unsafe {
            (
                &rec.get_unchecked(i).0,
                &rec.get_unchecked(j).0,
                dst.get_unchecked_mut(n),
            )
        };
        let dx = a[0] - (b[0] + pair.shift[0]);
        let dy = a[1] - (b[1] + pair.shift[1]);
        let dz = a[2] - (b[2] + pair.shift[2]);
        let radsum = a[3] + b[3];
        slot.write((offset + k) as u32);
        n += (dx * dx + dy * dy + dz * dz < radsum * radsum) as usize;
    }
    n
}

/// For each 4-bit mask of touching lanes, the lanes in order (then padding).
#[cfg(target_arch = "x86_64")]
const COMPRESS: [[u32; 4]; 16] = {
    let mut table = [[0u32; 4]; 16];
    let mut m = 0;
    while m < 16 {
        let mut n = 0;
        let mut k = 0;
        while k < 4 {
            if m & (1 << k) != 0 {
                table[m][n] = k as u32;
                n += 1;
            }
            k += 1;
        }
        m += 1;
    }
    table
};

/// The touching test four pairs at a time (the same arithmetic per pair as
/// [`touching_one_by_one`], so the same answers): returns (entries written, pairs done).
///
/// # Safety
/// The processor must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn touching_avx2(
    rec: &[Sphere],
    pairs: &[Pair],
    offset: usize,
    dst: &mut [std::mem::MaybeUninit<u32>],
) -> (usize, usize) {
    use std::arch::x86_64::*;
    let last = rec.len() - 1;
    let quads = pairs.len() / 4;
    let mut n = 0;
    // four rows [a b c d] of four doubles as four columns
    #[inline(always)]
    unsafe fn columns(r: [__m256d; 4]) -> [__m256d; 4] {
        let t0 = _mm256_unpacklo_pd(r[0], r[1]);
        let t1 = _mm256_unpackhi_pd(r[0], r[1]);
        let t2 = _mm256_unpacklo_pd(r[2], r[3]);
        let t3 = _mm256_unpackhi_pd(r[2], r[3]);
        [
            _mm256_permute2f128_pd::<0x20>(t0, t2),
            _mm256_permute2f128_pd::<0x20>(t1, t3),
            _mm256_permute2f128_pd::<0x31>(t0, t2),
            _mm256_permute2f128_pd::<0x31>(t1, t3),
        ]
    }
    for q in 0..quads {
        // SAFETY: 4q + 3 < pairs.len()
        let p: [&Pair; 4] = std::array::from_fn(|k| unsafe { pairs.get_unchecked(4 * q + k) });
        // SAFETY: indices clamped to the records; Sphere is 32-byte aligned
        let a = columns(p.map(|p| unsafe {
            _mm256_load_pd(rec.get_unchecked((p.i as usize).min(last)).0.as_ptr())
        }));
        let b = columns(p.map(|p| unsafe {
            _mm256_load_pd(rec.get_unchecked((p.j as usize).min(last)).0.as_ptr())
        }));
        // each Pair is (i, j) then its shift: four doubles, the first not a number we use
        let s = columns(p.map(|p| unsafe { _mm256_loadu_pd((p as *const Pair).cast::<f64>()) }));
        let dx = _mm256_sub_pd(a[0], _mm256_add_pd(b[0], s[1]));
        let dy = _mm256_sub_pd(a[1], _mm256_add_pd(b[1], s[2]));
        let dz = _mm256_sub_pd(a[2], _mm256_add_pd(b[2], s[3]));
        let radsum = _mm256_add_pd(a[3], b[3]);
        let rsq = _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)),
            _mm256_mul_pd(dz, dz),
        );
        let mask = _mm256_movemask_pd(_mm256_cmp_pd::<_CMP_LT_OQ>(
            rsq,
            _mm256_mul_pd(radsum, radsum),
        )) as usize;
        let base = _mm_set1_epi32((offset + 4 * q) as i32);
        let lanes = _mm_loadu_si128(COMPRESS[mask & 15].as_ptr().cast());
        // SAFETY: n <= 4q, so slots n..n + 4 lie inside dst[..4q + 4]
        _mm_storeu_si128(dst.as_mut_ptr().add(n).cast(), _mm_add_epi32(base, lanes));
        n += mask.count_ones() as usize;
    }
    (n, 4 * quads)
}
