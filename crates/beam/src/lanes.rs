//! Four numbers side by side: the element kernels evaluated for four elements at once, one
//! element per lane.
//!
//! [`Lanes4`] does each IEEE operation lane by lane (no fused multiply-add, no reassociation), so
//! a kernel written once over [`Real`] gives in every lane exactly what its `f64` instance gives
//! for that element alone. The compiler turns the lane-by-lane loops into vector instructions
//! (4-wide with AVX2): the square roots and divisions of four elements then share one
//! instruction each instead of waiting on the divider one after another.

use std::ops::{Add, Div, Mul, Neg, Sub};

/// The arithmetic a lane-generic kernel uses: `f64`, or [`Lanes4`] (the same operations per
/// lane).
pub(crate) trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// `x` in every lane.
    fn splat(x: f64) -> Self;
    /// The square root of every lane.
    fn sqrt(self) -> Self;
}

impl Real for f64 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
}

/// Four `f64` lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Lanes4(pub(crate) [f64; 4]);

macro_rules! lanewise {
    ($trait:ident, $f:ident, $op:tt) => {
        impl $trait for Lanes4 {
            type Output = Lanes4;
            #[inline(always)]
            fn $f(self, o: Lanes4) -> Lanes4 {
                let (a, b) = (self.0, o.0);
                Lanes4([a[0] $op b[0], a[1] $op b[1], a[2] $op b[2], a[3] $op b[3]])
            }
        }
    };
}
lanewise!(Add, add, +);
lanewise!(Sub, sub, -);
lanewise!(Mul, mul, *);
lanewise!(Div, div, /);

impl Neg for Lanes4 {
    type Output = Lanes4;
    #[inline(always)]
    fn neg(self) -> Lanes4 {
        let a = self.0;
        Lanes4([-a[0], -a[1], -a[2], -a[3]])
    }
}

impl Real for Lanes4 {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Lanes4([x; 4])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        let a = self.0;
        Lanes4([a[0].sqrt(), a[1].sqrt(), a[2].sqrt(), a[3].sqrt()])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_lane_gets_the_scalar_operations_bit_for_bit() {
        let x = [0.3, -1.7e-3, 2.5e8, -1.0 / 3.0];
        let y = [7.1, 3.3e-9, 4.0, 1e-300];
        let (a, b) = (Lanes4(x), Lanes4(y));
        let r = ((a * b + a) / (b - Lanes4::splat(2.0)) + -a).sqrt();
        for k in 0..4 {
            let s = ((x[k] * y[k] + x[k]) / (y[k] - 2.0) + -x[k]).sqrt();
            assert!(s.is_finite() && s > 0.0, "lane {k}: {s}");
            assert_eq!(r.0[k].to_bits(), s.to_bits(), "lane {k}");
        }
    }
}
