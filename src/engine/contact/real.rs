//! The number type the contact sub-models compute with: plain `f64` (one contact at a time,
//! the exact path and the walls) or [`F64x4`] (four contacts side by side, the fast path's
//! pair kernel). Every sub-model is written once, generic over [`Real`]; each lane of an
//! `F64x4` runs exactly the operations an `f64` would, in the same order, so a contact's
//! force does not depend on which batch or thread computed it.
//!
//! Branches that depend on a contact's values (the Coulomb cap, rolling-torque cap) are
//! written as [`Real::select`] between both outcomes; uniform settings (model keywords,
//! setup versus step) stay ordinary `if`s.

use std::ops::{Add, AddAssign, Div, Mul, MulAssign, Neg, Sub, SubAssign};

/// A lane mask: which contacts of a batch a condition holds for.
pub trait Mask: Copy + Send + Sync + std::fmt::Debug {
    /// Lane-wise and.
    fn and(self, other: Self) -> Self;
    /// Lane-wise or.
    fn or(self, other: Self) -> Self;
    /// Lane-wise not.
    fn not(self) -> Self;
    /// True if the condition holds in any lane.
    fn any(self) -> bool;
}

impl Mask for bool {
    #[inline(always)]
    fn and(self, other: bool) -> bool {
        self && other
    }
    #[inline(always)]
    fn or(self, other: bool) -> bool {
        self || other
    }
    #[inline(always)]
    fn not(self) -> bool {
        !self
    }
    #[inline(always)]
    fn any(self) -> bool {
        self
    }
}

/// A number (or a batch of numbers) in SI units, with IEEE-754 double arithmetic per lane.
pub trait Real:
    Copy
    + Send
    + Sync
    + Default
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// The mask type of comparisons.
    type Mask: Mask;
    /// The same value in every lane.
    fn splat(v: f64) -> Self;
    /// Square root (correctly rounded).
    fn sqrt(self) -> Self;
    /// Absolute value.
    fn abs(self) -> Self;
    /// `self.powf(e)` lane by lane (libm).
    fn powf(self, e: f64) -> Self;
    /// Lane-wise `self < o`.
    fn lt(self, o: Self) -> Self::Mask;
    /// Lane-wise `self > o`.
    fn gt(self, o: Self) -> Self::Mask;
    /// Lane-wise `self >= o`.
    fn ge(self, o: Self) -> Self::Mask;
    /// Lane-wise `self != o`.
    fn ne(self, o: Self) -> Self::Mask;
    /// Lane-wise `self == o`.
    fn eq(self, o: Self) -> Self::Mask;
    /// Lane-wise infinity test.
    fn is_infinite(self) -> Self::Mask;
    /// `a` where `m` holds, `b` elsewhere.
    fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}

impl Real for f64 {
    type Mask = bool;
    #[inline(always)]
    fn splat(v: f64) -> f64 {
        v
    }
    #[inline(always)]
    fn sqrt(self) -> f64 {
        f64::sqrt(self)
    }
    #[inline(always)]
    fn abs(self) -> f64 {
        f64::abs(self)
    }
    #[inline(always)]
    fn powf(self, e: f64) -> f64 {
        f64::powf(self, e)
    }
    #[inline(always)]
    fn lt(self, o: f64) -> bool {
        self < o
    }
    #[inline(always)]
    fn gt(self, o: f64) -> bool {
        self > o
    }
    #[inline(always)]
    fn ge(self, o: f64) -> bool {
        self >= o
    }
    #[inline(always)]
    fn ne(self, o: f64) -> bool {
        self != o
    }
    #[inline(always)]
    fn eq(self, o: f64) -> bool {
        self == o
    }
    #[inline(always)]
    fn is_infinite(self) -> bool {
        f64::is_infinite(self)
    }
    #[inline(always)]
    fn select(m: bool, a: f64, b: f64) -> f64 {
        if m {
            a
        } else {
            b
        }
    }
}

/// Number of lanes of [`F64x4`].
pub const LANES: usize = 4;

/// Four doubles, one per contact of a batch (lane-wise IEEE arithmetic).
///
/// On x86-64 every operation is one AVX instruction on a 256-bit register, so **the
/// processor must support AVX**: the pair kernel runs `F64x4` code only after checking
/// (`batch::Kernel`), and runs the `f64` code one pair at a time otherwise. Elsewhere the
/// lanes are plain arrays. Either way each lane rounds exactly as `f64` does (no fused
/// multiply-add).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(32))]
pub struct F64x4(pub [f64; LANES]);

/// The mask of [`F64x4`] comparisons: each lane all ones (true) or all zeros (false), the
/// layout of a SIMD compare, so selects are bitwise blends with no conversion.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[repr(C, align(32))]
pub struct M4(pub [u64; LANES]);

impl M4 {
    /// The mask with lanes `b`.
    #[inline(always)]
    pub fn from_bools(b: [bool; LANES]) -> M4 {
        M4(b.map(|t| (t as u64).wrapping_neg()))
    }

    /// The lanes that hold as bits (lane k is bit k).
    #[inline(always)]
    pub fn bits(self) -> u32 {
        #[cfg(target_arch = "x86_64")]
        return avx::bits(self);
        #[cfg(not(target_arch = "x86_64"))]
        (0..LANES).fold(0, |b, k| b | (((self.0[k] >> 63) as u32) << k))
    }
}

/// The 256-bit AVX operations behind [`F64x4`] and [`M4`] on x86-64.
#[cfg(target_arch = "x86_64")]
mod avx {
    use super::{F64x4, M4};
    use std::arch::x86_64::*;

    // SAFETY (every function here): F64x4 and M4 are 32-byte aligned arrays of four
    // 8-byte lanes, the layout of __m256d; the AVX instructions are available because
    // F64x4 code runs only where the processor has AVX (see F64x4's documentation).

    /// The lanes as a register.
    #[inline(always)]
    pub fn get(a: F64x4) -> __m256d {
        unsafe { _mm256_load_pd(a.0.as_ptr()) }
    }

    /// A register as lanes.
    #[inline(always)]
    pub fn put(r: __m256d) -> F64x4 {
        let mut out = F64x4::default();
        unsafe { _mm256_store_pd(out.0.as_mut_ptr(), r) };
        out
    }

    /// A mask as a register.
    #[inline(always)]
    pub fn get_mask(m: M4) -> __m256d {
        unsafe { _mm256_load_pd(m.0.as_ptr().cast()) }
    }

    /// A register as a mask.
    #[inline(always)]
    pub fn put_mask(r: __m256d) -> M4 {
        let mut out = M4::default();
        unsafe { _mm256_store_pd(out.0.as_mut_ptr().cast(), r) };
        out
    }

    macro_rules! binary {
        ($name:ident, $intr:ident) => {
            /// Lane-wise operation.
            #[inline(always)]
            pub fn $name(a: F64x4, b: F64x4) -> F64x4 {
                put(unsafe { $intr(get(a), get(b)) })
            }
        };
    }
    binary!(add, _mm256_add_pd);
    binary!(sub, _mm256_sub_pd);
    binary!(mul, _mm256_mul_pd);
    binary!(div, _mm256_div_pd);

    /// Lane-wise square root (correctly rounded, as `f64::sqrt`).
    #[inline(always)]
    pub fn sqrt(a: F64x4) -> F64x4 {
        put(unsafe { _mm256_sqrt_pd(get(a)) })
    }

    /// Lane-wise sign flip (as `-x`, also for zeros and NaN).
    #[inline(always)]
    pub fn neg(a: F64x4) -> F64x4 {
        put(unsafe { _mm256_xor_pd(get(a), _mm256_set1_pd(-0.0)) })
    }

    /// Lane-wise absolute value (sign bit cleared, as `f64::abs`).
    #[inline(always)]
    pub fn abs(a: F64x4) -> F64x4 {
        put(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), get(a)) })
    }

    /// Lane-wise comparison with predicate `P` (an `_CMP_*` constant).
    #[inline(always)]
    pub fn cmp<const P: i32>(a: F64x4, b: F64x4) -> M4 {
        put_mask(unsafe { _mm256_cmp_pd::<P>(get(a), get(b)) })
    }

    /// `a` where `m` holds, `b` elsewhere.
    #[inline(always)]
    pub fn select(m: M4, a: F64x4, b: F64x4) -> F64x4 {
        put(unsafe { _mm256_blendv_pd(get(b), get(a), get_mask(m)) })
    }

    macro_rules! mask_binary {
        ($name:ident, $intr:ident) => {
            /// Lane-wise bit operation.
            #[inline(always)]
            pub fn $name(a: M4, b: M4) -> M4 {
                put_mask(unsafe { $intr(get_mask(a), get_mask(b)) })
            }
        };
    }
    mask_binary!(and, _mm256_and_pd);
    mask_binary!(or, _mm256_or_pd);

    /// Lane-wise not.
    #[inline(always)]
    pub fn not(a: M4) -> M4 {
        put_mask(unsafe { _mm256_xor_pd(get_mask(a), _mm256_castsi256_pd(_mm256_set1_epi64x(-1))) })
    }

    /// The set lanes as bits.
    #[inline(always)]
    pub fn bits(a: M4) -> u32 {
        unsafe { _mm256_movemask_pd(get_mask(a)) as u32 }
    }

    /// True if any lane is set.
    #[inline(always)]
    pub fn any(a: M4) -> bool {
        unsafe { _mm256_movemask_pd(get_mask(a)) != 0 }
    }
}

impl Mask for M4 {
    #[inline(always)]
    fn and(self, o: M4) -> M4 {
        #[cfg(target_arch = "x86_64")]
        return avx::and(self, o);
        #[cfg(not(target_arch = "x86_64"))]
        M4(std::array::from_fn(|k| self.0[k] & o.0[k]))
    }
    #[inline(always)]
    fn or(self, o: M4) -> M4 {
        #[cfg(target_arch = "x86_64")]
        return avx::or(self, o);
        #[cfg(not(target_arch = "x86_64"))]
        M4(std::array::from_fn(|k| self.0[k] | o.0[k]))
    }
    #[inline(always)]
    fn not(self) -> M4 {
        #[cfg(target_arch = "x86_64")]
        return avx::not(self);
        #[cfg(not(target_arch = "x86_64"))]
        M4(self.0.map(|b| !b))
    }
    #[inline(always)]
    fn any(self) -> bool {
        #[cfg(target_arch = "x86_64")]
        return avx::any(self);
        #[cfg(not(target_arch = "x86_64"))]
        ((self.0[0] | self.0[1] | self.0[2] | self.0[3]) != 0)
    }
}

macro_rules! lanewise {
    ($trait:ident, $f:ident, $op:tt) => {
        impl $trait for F64x4 {
            type Output = F64x4;
            #[inline(always)]
            fn $f(self, o: F64x4) -> F64x4 {
                #[cfg(target_arch = "x86_64")]
                return avx::$f(self, o);
                #[cfg(not(target_arch = "x86_64"))]
                F64x4([
                    self.0[0] $op o.0[0],
                    self.0[1] $op o.0[1],
                    self.0[2] $op o.0[2],
                    self.0[3] $op o.0[3],
                ])
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);
lanewise!(Div, div, /);

impl Neg for F64x4 {
    type Output = F64x4;
    #[inline(always)]
    fn neg(self) -> F64x4 {
        #[cfg(target_arch = "x86_64")]
        return avx::neg(self);
        #[cfg(not(target_arch = "x86_64"))]
        F64x4(self.0.map(|x| -x))
    }
}

impl AddAssign for F64x4 {
    #[inline(always)]
    fn add_assign(&mut self, o: F64x4) {
        *self = *self + o;
    }
}

impl SubAssign for F64x4 {
    #[inline(always)]
    fn sub_assign(&mut self, o: F64x4) {
        *self = *self - o;
    }
}

impl MulAssign for F64x4 {
    #[inline(always)]
    fn mul_assign(&mut self, o: F64x4) {
        *self = *self * o;
    }
}

macro_rules! compare {
    ($f:ident, $op:tt, $pred:ident) => {
        #[inline(always)]
        fn $f(self, o: F64x4) -> M4 {
            #[cfg(target_arch = "x86_64")]
            return avx::cmp::<{ std::arch::x86_64::$pred }>(self, o);
            #[cfg(not(target_arch = "x86_64"))]
            M4::from_bools([
                self.0[0] $op o.0[0],
                self.0[1] $op o.0[1],
                self.0[2] $op o.0[2],
                self.0[3] $op o.0[3],
            ])
        }
    };
}

impl Real for F64x4 {
    type Mask = M4;
    #[inline(always)]
    fn splat(v: f64) -> F64x4 {
        F64x4([v; LANES])
    }
    #[inline(always)]
    fn sqrt(self) -> F64x4 {
        #[cfg(target_arch = "x86_64")]
        return avx::sqrt(self);
        #[cfg(not(target_arch = "x86_64"))]
        F64x4(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> F64x4 {
        #[cfg(target_arch = "x86_64")]
        return avx::abs(self);
        #[cfg(not(target_arch = "x86_64"))]
        F64x4(self.0.map(f64::abs))
    }
    #[inline(always)]
    fn powf(self, e: f64) -> F64x4 {
        F64x4(self.0.map(|x| x.powf(e)))
    }
    // ordered predicates are false for NaN, as Rust's <, >, >=, ==; != is unordered (true)
    compare!(lt, <, _CMP_LT_OQ);
    compare!(gt, >, _CMP_GT_OQ);
    compare!(ge, >=, _CMP_GE_OQ);
    compare!(ne, !=, _CMP_NEQ_UQ);
    compare!(eq, ==, _CMP_EQ_OQ);
    #[inline(always)]
    fn is_infinite(self) -> M4 {
        self.abs().eq(F64x4::splat(f64::INFINITY))
    }
    #[inline(always)]
    fn select(m: M4, a: F64x4, b: F64x4) -> F64x4 {
        #[cfg(target_arch = "x86_64")]
        return avx::select(m, a, b);
        #[cfg(not(target_arch = "x86_64"))]
        F64x4(std::array::from_fn(|k| {
            f64::from_bits((a.0[k].to_bits() & m.0[k]) | (b.0[k].to_bits() & !m.0[k]))
        }))
    }
}

/// Number of lanes of [`F64x8`].
pub const WIDE_LANES: usize = 8;

/// Eight doubles, one per contact of a wide batch (lane-wise IEEE arithmetic).
///
/// On x86-64 every operation is one AVX-512 instruction on a 512-bit register, so **the
/// processor must support AVX-512F**: the pair kernel runs `F64x8` code only after checking
/// ([`wide_lanes_supported`]). Twice the contacts per instruction as [`F64x4`] keeps twice
/// as many independent divisions and square roots in flight. Each lane rounds exactly as
/// `f64` does (no fused multiply-add).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(64))]
pub struct F64x8(pub [f64; WIDE_LANES]);

/// The mask of [`F64x8`] comparisons: lane k is bit k (the layout of an AVX-512 mask
/// register).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct M8(pub u8);

impl F64x8 {
    /// Lanes 0..4 and 4..8 as two [`F64x4`].
    #[inline(always)]
    pub fn halves(self) -> (F64x4, F64x4) {
        #[cfg(target_arch = "x86_64")]
        return avx512::halves(self);
        #[cfg(not(target_arch = "x86_64"))]
        {
            let a = self.0;
            (
                F64x4([a[0], a[1], a[2], a[3]]),
                F64x4([a[4], a[5], a[6], a[7]]),
            )
        }
    }

    /// The lanes of `lo` then those of `hi`.
    #[inline(always)]
    pub fn from_halves(lo: F64x4, hi: F64x4) -> F64x8 {
        #[cfg(target_arch = "x86_64")]
        return avx512::from_halves(lo, hi);
        #[cfg(not(target_arch = "x86_64"))]
        F64x8(std::array::from_fn(|k| {
            if k < 4 {
                lo.0[k]
            } else {
                hi.0[k - 4]
            }
        }))
    }
}

/// The 512-bit AVX-512F operations behind [`F64x8`] on x86-64.
#[cfg(target_arch = "x86_64")]
mod avx512 {
    use super::{F64x4, F64x8, M8};
    use std::arch::x86_64::*;

    // SAFETY (every function here): F64x8 is a 64-byte aligned array of eight doubles, the
    // layout of __m512d, F64x4 that of __m256d; the AVX-512F instructions are available
    // because F64x8 code runs only where the processor has them (see F64x8).

    /// The lanes as a register.
    #[inline(always)]
    pub fn get(a: F64x8) -> __m512d {
        unsafe { _mm512_load_pd(a.0.as_ptr()) }
    }

    /// A register as lanes.
    #[inline(always)]
    pub fn put(r: __m512d) -> F64x8 {
        let mut out = F64x8::default();
        unsafe { _mm512_store_pd(out.0.as_mut_ptr(), r) };
        out
    }

    /// Lanes 0..4 and 4..8.
    #[inline(always)]
    pub fn halves(a: F64x8) -> (F64x4, F64x4) {
        let r = get(a);
        unsafe {
            (
                super::avx::put(_mm512_castpd512_pd256(r)),
                super::avx::put(_mm512_extractf64x4_pd::<1>(r)),
            )
        }
    }

    /// Two quads as one register.
    #[inline(always)]
    pub fn from_halves(lo: F64x4, hi: F64x4) -> F64x8 {
        unsafe {
            put(_mm512_insertf64x4::<1>(
                _mm512_castpd256_pd512(super::avx::get(lo)),
                super::avx::get(hi),
            ))
        }
    }

    macro_rules! binary {
        ($name:ident, $intr:ident) => {
            /// Lane-wise operation.
            #[inline(always)]
            pub fn $name(a: F64x8, b: F64x8) -> F64x8 {
                put(unsafe { $intr(get(a), get(b)) })
            }
        };
    }
    binary!(add, _mm512_add_pd);
    binary!(sub, _mm512_sub_pd);
    binary!(mul, _mm512_mul_pd);
    binary!(div, _mm512_div_pd);

    /// Lane-wise square root (correctly rounded, as `f64::sqrt`).
    #[inline(always)]
    pub fn sqrt(a: F64x8) -> F64x8 {
        put(unsafe { _mm512_sqrt_pd(get(a)) })
    }

    /// Lane-wise sign flip (as `-x`, also for zeros and NaN).
    #[inline(always)]
    pub fn neg(a: F64x8) -> F64x8 {
        put(unsafe {
            _mm512_castsi512_pd(_mm512_xor_si512(
                _mm512_castpd_si512(get(a)),
                _mm512_set1_epi64(i64::MIN),
            ))
        })
    }

    /// Lane-wise absolute value (sign bit cleared, as `f64::abs`).
    #[inline(always)]
    pub fn abs(a: F64x8) -> F64x8 {
        put(unsafe { _mm512_abs_pd(get(a)) })
    }

    /// Lane-wise comparison with predicate `P` (an `_CMP_*` constant).
    #[inline(always)]
    pub fn cmp<const P: i32>(a: F64x8, b: F64x8) -> M8 {
        M8(unsafe { _mm512_cmp_pd_mask::<P>(get(a), get(b)) })
    }

    /// `a` where `m` holds, `b` elsewhere.
    #[inline(always)]
    pub fn select(m: M8, a: F64x8, b: F64x8) -> F64x8 {
        put(unsafe { _mm512_mask_blend_pd(m.0, get(b), get(a)) })
    }
}

impl Mask for M8 {
    #[inline(always)]
    fn and(self, o: M8) -> M8 {
        M8(self.0 & o.0)
    }
    #[inline(always)]
    fn or(self, o: M8) -> M8 {
        M8(self.0 | o.0)
    }
    #[inline(always)]
    fn not(self) -> M8 {
        M8(!self.0)
    }
    #[inline(always)]
    fn any(self) -> bool {
        self.0 != 0
    }
}

macro_rules! lanewise8 {
    ($trait:ident, $f:ident, $op:tt) => {
        impl $trait for F64x8 {
            type Output = F64x8;
            #[inline(always)]
            fn $f(self, o: F64x8) -> F64x8 {
                #[cfg(target_arch = "x86_64")]
                return avx512::$f(self, o);
                #[cfg(not(target_arch = "x86_64"))]
                F64x8(std::array::from_fn(|k| self.0[k] $op o.0[k]))
            }
        }
    };
}
lanewise8!(Add, add, +);
lanewise8!(Sub, sub, -);
lanewise8!(Mul, mul, *);
lanewise8!(Div, div, /);

impl Neg for F64x8 {
    type Output = F64x8;
    #[inline(always)]
    fn neg(self) -> F64x8 {
        #[cfg(target_arch = "x86_64")]
        return avx512::neg(self);
        #[cfg(not(target_arch = "x86_64"))]
        F64x8(self.0.map(|x| -x))
    }
}

impl AddAssign for F64x8 {
    #[inline(always)]
    fn add_assign(&mut self, o: F64x8) {
        *self = *self + o;
    }
}

impl SubAssign for F64x8 {
    #[inline(always)]
    fn sub_assign(&mut self, o: F64x8) {
        *self = *self - o;
    }
}

impl MulAssign for F64x8 {
    #[inline(always)]
    fn mul_assign(&mut self, o: F64x8) {
        *self = *self * o;
    }
}

macro_rules! compare8 {
    ($f:ident, $op:tt, $pred:ident) => {
        #[inline(always)]
        fn $f(self, o: F64x8) -> M8 {
            #[cfg(target_arch = "x86_64")]
            return avx512::cmp::<{ std::arch::x86_64::$pred }>(self, o);
            #[cfg(not(target_arch = "x86_64"))]
            M8((0..WIDE_LANES).fold(0, |m, k| m | (((self.0[k] $op o.0[k]) as u8) << k)))
        }
    };
}

impl Real for F64x8 {
    type Mask = M8;
    #[inline(always)]
    fn splat(v: f64) -> F64x8 {
        F64x8([v; WIDE_LANES])
    }
    #[inline(always)]
    fn sqrt(self) -> F64x8 {
        #[cfg(target_arch = "x86_64")]
        return avx512::sqrt(self);
        #[cfg(not(target_arch = "x86_64"))]
        F64x8(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> F64x8 {
        #[cfg(target_arch = "x86_64")]
        return avx512::abs(self);
        #[cfg(not(target_arch = "x86_64"))]
        F64x8(self.0.map(f64::abs))
    }
    #[inline(always)]
    fn powf(self, e: f64) -> F64x8 {
        F64x8(self.0.map(|x| x.powf(e)))
    }
    // ordered predicates are false for NaN, as Rust's <, >, >=, ==; != is unordered (true)
    compare8!(lt, <, _CMP_LT_OQ);
    compare8!(gt, >, _CMP_GT_OQ);
    compare8!(ge, >=, _CMP_GE_OQ);
    compare8!(ne, !=, _CMP_NEQ_UQ);
    compare8!(eq, ==, _CMP_EQ_OQ);
    #[inline(always)]
    fn is_infinite(self) -> M8 {
        self.abs().eq(F64x8::splat(f64::INFINITY))
    }
    #[inline(always)]
    fn select(m: M8, a: F64x8, b: F64x8) -> F64x8 {
        #[cfg(target_arch = "x86_64")]
        return avx512::select(m, a, b);
        #[cfg(not(target_arch = "x86_64"))]
        F64x8(std::array::from_fn(|k| {
            if m.0 >> k & 1 == 1 {
                a.0[k]
            } else {
                b.0[k]
            }
        }))
    }
}

/// Does this processor run [`F64x8`] code (AVX-512F on x86-64; always elsewhere)? Checked
/// once; `REGOLITH_NO_AVX512` answers no (the pair kernel then runs four lanes at a time).
pub fn wide_lanes_supported() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        static HAS: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        *HAS.get_or_init(|| {
            lanes_supported()
                && std::env::var_os("REGOLITH_NO_AVX512").is_none()
                && is_x86_feature_detected!("avx512f")
        })
    }
    #[cfg(not(target_arch = "x86_64"))]
    true
}

/// Does this processor run [`F64x4`] code (AVX on x86-64; always elsewhere)? Checked once;
/// `REGOLITH_NO_AVX2` answers no (the pair kernel then runs one pair at a time).
pub fn lanes_supported() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        static HAS: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
        *HAS.get_or_init(|| {
            std::env::var_os("REGOLITH_NO_AVX2").is_none() && is_x86_feature_detected!("avx2")
        })
    }
    #[cfg(not(target_arch = "x86_64"))]
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_compute_what_scalars_compute() {
        if !lanes_supported() {
            return;
        }
        let a = F64x4([1.0, -2.0, 0.1, 3.0]);
        let b = F64x4([0.3, 0.7, -0.2, 3.0]);
        let r = ((a * b + a) / b).sqrt().abs() - F64x4::splat(0.5);
        for k in 0..LANES {
            let (x, y) = (a.0[k], b.0[k]);
            let s = ((x * y + x) / y).sqrt().abs() - 0.5;
            assert!(r.0[k].to_bits() == s.to_bits() || (r.0[k].is_nan() && s.is_nan()));
        }
        let m = a.gt(b);
        assert_eq!(m, M4::from_bools([true, false, true, false]));
        assert_eq!(F64x4::select(m, a, b).0, [1.0, 0.7, 0.1, 3.0]);
        assert!(m.any() && !M4::default().any());
        assert_eq!(
            m.not().and(a.eq(b)),
            M4::from_bools([false, false, false, true])
        );
        // signs of zeros and NaN comparisons as f64 has them
        let z = F64x4([0.0, -0.0, f64::NAN, f64::NEG_INFINITY]);
        let flipped = -z;
        for k in 0..LANES {
            assert_eq!(flipped.0[k].to_bits(), (-z.0[k]).to_bits());
            assert_eq!(z.abs().0[k].to_bits(), z.0[k].abs().to_bits());
        }
        let one = F64x4::splat(1.0);
        assert_eq!(z.lt(one), M4::from_bools([true, true, false, true]));
        assert_eq!(z.ge(one), M4::from_bools([false; 4]));
        assert_eq!(z.ne(z), M4::from_bools([false, false, true, false]));
        assert_eq!(z.is_infinite(), M4::from_bools([false, false, false, true]));
        assert!(!M4::from_bools([false; 4]).or(M4::default()).any());
    }

    #[test]
    fn wide_lanes_compute_what_scalars_compute() {
        if !wide_lanes_supported() {
            return;
        }
        let x = [1.0, -2.0, 0.1, 3.0, 0.0, -0.0, f64::NAN, f64::NEG_INFINITY];
        let y = [0.3, 0.7, -0.2, 3.0, 1.0, 1.0, 1.0, 1.0];
        let (a, b) = (F64x8(x), F64x8(y));
        let r = ((a * b + a) / b).sqrt().abs() - F64x8::splat(0.5);
        let flipped = -a;
        for k in 0..WIDE_LANES {
            let s = ((x[k] * y[k] + x[k]) / y[k]).sqrt().abs() - 0.5;
            assert!(r.0[k].to_bits() == s.to_bits() || (r.0[k].is_nan() && s.is_nan()));
            assert_eq!(flipped.0[k].to_bits(), (-x[k]).to_bits());
            assert_eq!(a.abs().0[k].to_bits(), x[k].abs().to_bits());
            assert_eq!(a.lt(b).0 >> k & 1 == 1, x[k] < y[k]);
            assert_eq!(a.ge(b).0 >> k & 1 == 1, x[k] >= y[k]);
            assert_eq!(a.ne(a).0 >> k & 1 == 1, x[k] != x[k]);
        }
        assert_eq!(a.is_infinite(), M8(0b1000_0000));
        let m = a.gt(b);
        assert_eq!(m, M8(0b0000_0101));
        let picked = F64x8::select(m, a, b);
        for k in 0..WIDE_LANES {
            let want = if m.0 >> k & 1 == 1 { x[k] } else { y[k] };
            assert_eq!(picked.0[k].to_bits(), want.to_bits());
        }
        assert!(m.any() && !M8::default().any() && m.not().and(m) == M8(0));
        let (lo, hi) = a.halves();
        assert_eq!(lo.0[..3], x[..3]);
        assert_eq!(hi.0[..2], x[4..6]);
        let back = F64x8::from_halves(lo, hi);
        for k in 0..WIDE_LANES {
            assert_eq!(back.0[k].to_bits(), x[k].to_bits());
        }
    }
}
