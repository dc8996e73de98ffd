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
pub trait Mask: Copy + Send + Sync {
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

/// Four doubles, one per contact of a batch (lane-wise IEEE arithmetic; the compiler maps
/// it onto SIMD registers).
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
}

impl Mask for M4 {
    #[inline(always)]
    fn and(self, o: M4) -> M4 {
        M4(std::array::from_fn(|k| self.0[k] & o.0[k]))
    }
    #[inline(always)]
    fn or(self, o: M4) -> M4 {
        M4(std::array::from_fn(|k| self.0[k] | o.0[k]))
    }
    #[inline(always)]
    fn not(self) -> M4 {
        M4(self.0.map(|b| !b))
    }
    #[inline(always)]
    fn any(self) -> bool {
        (self.0[0] | self.0[1] | self.0[2] | self.0[3]) != 0
    }
}

macro_rules! lanewise {
    ($trait:ident, $f:ident, $op:tt) => {
        impl $trait for F64x4 {
            type Output = F64x4;
            #[inline(always)]
            fn $f(self, o: F64x4) -> F64x4 {
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
    ($f:ident, $op:tt) => {
        #[inline(always)]
        fn $f(self, o: F64x4) -> M4 {
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
        F64x4(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn abs(self) -> F64x4 {
        F64x4(self.0.map(f64::abs))
    }
    #[inline(always)]
    fn powf(self, e: f64) -> F64x4 {
        F64x4(self.0.map(|x| x.powf(e)))
    }
    compare!(lt, <);
    compare!(gt, >);
    compare!(ge, >=);
    compare!(ne, !=);
    compare!(eq, ==);
    #[inline(always)]
    fn is_infinite(self) -> M4 {
        M4::from_bools(self.0.map(f64::is_infinite))
    }
    #[inline(always)]
    fn select(m: M4, a: F64x4, b: F64x4) -> F64x4 {
        F64x4(std::array::from_fn(|k| {
            f64::from_bits((a.0[k].to_bits() & m.0[k]) | (b.0[k].to_bits() & !m.0[k]))
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_compute_what_scalars_compute() {
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
    }
}
