//! Double-double numbers (an unevaluated sum hi + lo of two `f64`, ≈ 106 bits, 32 digits) that
//! the generic position functions of the project accept: they implement num-dual's
//! [`DualNum`] with `f64` as the primitive, so `Dual3<DoubleDouble>` is a
//! [`mechdiff_core::Scalar`] and the geometry solver's closed forms, written once generic over
//! the scalar, evaluate in it with exact third derivatives ([`super::scene`]'s reference).
//!
//! Addition, subtraction, multiplication and division are the classic error-free-transform
//! algorithms (Dekker, Knuth; the product with a fused multiply-add), relative error below
//! ~4·2⁻¹⁰⁶. Every other function (square root, sine, arctangent, …) is computed by the
//! symbolic engine's 256-bit arithmetic from the exact hi + lo and rounded back to
//! double-double: slow (a few µs each), and correct to the double-double's last bit. Branch
//! decisions read the `f64` part [`DualStruct::re`], as in `f64`.

use std::cell::RefCell;
use std::cmp::Ordering;
use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{
    Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign,
};

use mechdiff_core::num_dual::{DualNum, DualStruct, Mappable};
use mechdiff_core::symbolic::{Arithmetic, BigArithmetic, BigReal, Binary, Unary};
use num_traits::{FromPrimitive, Inv, Num, One, Signed, Zero};

/// Bits of the arithmetic the functions other than + − × ÷ are computed in.
const FUNCTION_BITS: usize = 256;

/// A double-double number hi + lo, |lo| ≤ ulp(hi)/2 (see the module's documentation).
#[derive(Clone, Copy, Debug, Default, PartialEq, PartialOrd)]
pub struct DoubleDouble {
    /// The nearest `f64`.
    pub hi: f64,
    /// The remainder.
    pub lo: f64,
}

/// s + e = a + b exactly.
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// s + e = a + b exactly, for |a| ≥ |b|.
#[inline]
fn quick_two_sum(a: f64, b: f64) -> DoubleDouble {
    let s = a + b;
    if !s.is_finite() {
        return DoubleDouble { hi: s, lo: 0.0 };
    }
    DoubleDouble {
        hi: s,
        lo: b - (s - a),
    }
}

impl DoubleDouble {
    /// The number `x` (lo = 0).
    pub const fn new(x: f64) -> Self {
        DoubleDouble { hi: x, lo: 0.0 }
    }

    /// Whether both parts are finite.
    pub fn is_finite(&self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }

    /// The double-double nearest to a big real.
    pub fn from_big(value: &BigReal) -> Self {
        Self::round(&mut BigArithmetic::new(FUNCTION_BITS), value)
    }

    /// The double-double nearest to `value`, its low part computed with `arithmetic`.
    fn round(arithmetic: &mut BigArithmetic, value: &BigReal) -> Self {
        let hi = value.to_f64();
        if !hi.is_finite() {
            return DoubleDouble::new(hi);
        }
        let hi_big = arithmetic.constant(hi);
        let lo = arithmetic.binary(Binary::Sub, value, &hi_big).to_f64();
        DoubleDouble { hi, lo }
    }

    /// The exact value hi + lo as a big real.
    pub fn to_big(self, arithmetic: &mut BigArithmetic) -> BigReal {
        let hi = arithmetic.constant(self.hi);
        let lo = arithmetic.constant(self.lo);
        arithmetic.binary(Binary::Add, &hi, &lo)
    }

    /// |x − self|, with the low part: (x − hi) is exact when x is within a factor 2 of hi
    /// (Sterbenz), so the error of an `f64` result is resolved to its last bit.
    pub fn error(&self, x: f64) -> f64 {
        ((x - self.hi) - self.lo).abs()
    }

    /// `f` of the arguments, computed at 256 bits from their exact values.
    fn big(args: &[Self], f: impl FnOnce(&mut BigArithmetic, &[BigReal]) -> BigReal) -> Self {
        thread_local! {
            static ARITHMETIC: RefCell<BigArithmetic> =
                RefCell::new(BigArithmetic::new(FUNCTION_BITS));
        }
        ARITHMETIC.with(|a| {
            let a = &mut *a.borrow_mut();
            let values: Vec<BigReal> = args.iter().map(|x| x.to_big(a)).collect();
            let result = f(a, &values);
            Self::round(a, &result)
        })
    }

    fn unary(self, op: Unary) -> Self {
        Self::big(&[self], |a, x| a.unary(op, &x[0]))
    }
}

/// `op(x)` at 256 bits, with the constant `c` at hand.
fn with_constant(
    x: DoubleDouble,
    c: f64,
    f: impl FnOnce(&mut BigArithmetic, &BigReal, &BigReal) -> BigReal,
) -> DoubleDouble {
    DoubleDouble::big(&[x, DoubleDouble::new(c)], |a, v| f(a, &v[0], &v[1]))
}

impl From<f64> for DoubleDouble {
    fn from(x: f64) -> Self {
        DoubleDouble::new(x)
    }
}

impl fmt::Display for DoubleDouble {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut arithmetic = BigArithmetic::new(FUNCTION_BITS);
        write!(f, "{}", self.to_big(&mut arithmetic))
    }
}

impl PartialEq<f64> for DoubleDouble {
    fn eq(&self, other: &f64) -> bool {
        *self == DoubleDouble::new(*other)
    }
}

impl PartialOrd<f64> for DoubleDouble {
    fn partial_cmp(&self, other: &f64) -> Option<Ordering> {
        self.partial_cmp(&DoubleDouble::new(*other))
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    fn neg(self) -> Self {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    #[inline]
    fn add(self, y: Self) -> Self {
        let (s, e) = two_sum(self.hi, y.hi);
        let (t, f) = two_sum(self.lo, y.lo);
        let r = quick_two_sum(s, e + t);
        quick_two_sum(r.hi, r.lo + f)
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    #[inline]
    fn sub(self, y: Self) -> Self {
        self + (-y)
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    #[inline]
    fn mul(self, y: Self) -> Self {
        let p = self.hi * y.hi;
        let e = self.hi.mul_add(y.hi, -p);
        quick_two_sum(p, e + (self.hi * y.lo + self.lo * y.hi))
    }
}

impl Div for DoubleDouble {
    type Output = Self;
    #[inline]
    fn div(self, y: Self) -> Self {
        let q1 = self.hi / y.hi;
        if !q1.is_finite() || q1 == 0.0 {
            return DoubleDouble::new(q1);
        }
        let r = self - y * DoubleDouble::new(q1);
        let q2 = r.hi / y.hi;
        let r = r - y * DoubleDouble::new(q2);
        let q3 = r.hi / y.hi;
        quick_two_sum(q1, q2) + DoubleDouble::new(q3)
    }
}

impl Rem for DoubleDouble {
    type Output = Self;
    /// x − y·trunc(x/y), the quotient's integer part taken in double-double.
    fn rem(self, y: Self) -> Self {
        let q = self / y;
        let hi = q.hi.trunc();
        let whole = if hi == q.hi {
            quick_two_sum(hi, q.lo.trunc())
        } else {
            DoubleDouble::new(hi)
        };
        self - y * whole
    }
}

/// The operator for references and for `f64` operands, from the one on values.
macro_rules! forward {
    ($($trait:ident $method:ident $assign:ident $assign_method:ident),*) => {$(
        impl $trait<&DoubleDouble> for DoubleDouble {
            type Output = DoubleDouble;
            fn $method(self, y: &DoubleDouble) -> DoubleDouble {
                $trait::$method(self, *y)
            }
        }
        impl $trait<f64> for DoubleDouble {
            type Output = DoubleDouble;
            fn $method(self, y: f64) -> DoubleDouble {
                $trait::$method(self, DoubleDouble::new(y))
            }
        }
        impl $assign for DoubleDouble {
            fn $assign_method(&mut self, y: DoubleDouble) {
                *self = $trait::$method(*self, y);
            }
        }
        impl $assign<f64> for DoubleDouble {
            fn $assign_method(&mut self, y: f64) {
                *self = $trait::$method(*self, DoubleDouble::new(y));
            }
        }
    )*};
}

forward!(
    Add add AddAssign add_assign,
    Sub sub SubAssign sub_assign,
    Mul mul MulAssign mul_assign,
    Div div DivAssign div_assign,
    Rem rem RemAssign rem_assign
);

impl Zero for DoubleDouble {
    fn zero() -> Self {
        DoubleDouble::new(0.0)
    }
    fn is_zero(&self) -> bool {
        self.hi == 0.0
    }
}

impl One for DoubleDouble {
    fn one() -> Self {
        DoubleDouble::new(1.0)
    }
}

impl Num for DoubleDouble {
    type FromStrRadixErr = String;
    /// Decimal only (radix 10), exactly rounded from the text.
    fn from_str_radix(text: &str, radix: u32) -> Result<Self, String> {
        if radix != 10 {
            return Err(format!(
                "double-double numbers parse radix 10 only, not {radix}"
            ));
        }
        BigReal::parse(text, FUNCTION_BITS)
            .map(|b| DoubleDouble::from_big(&b))
            .map_err(|e| e.to_string())
    }
}

impl Signed for DoubleDouble {
    fn abs(&self) -> Self {
        if self.hi < 0.0 { -*self } else { *self }
    }
    fn abs_sub(&self, other: &Self) -> Self {
        if *self <= *other {
            Self::zero()
        } else {
            *self - *other
        }
    }
    fn signum(&self) -> Self {
        DoubleDouble::new(self.hi.signum())
    }
    fn is_positive(&self) -> bool {
        self.hi > 0.0
    }
    fn is_negative(&self) -> bool {
        self.hi < 0.0
    }
}

impl Inv for DoubleDouble {
    type Output = Self;
    fn inv(self) -> Self {
        DoubleDouble::one() / self
    }
}

impl Sum for DoubleDouble {
    fn sum<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::zero(), |s, x| s + x)
    }
}

impl Product for DoubleDouble {
    fn product<I: Iterator<Item = Self>>(iter: I) -> Self {
        iter.fold(Self::one(), |s, x| s * x)
    }
}

impl FromPrimitive for DoubleDouble {
    fn from_i64(n: i64) -> Option<Self> {
        let hi = n as f64;
        // n − hi is exact in i128 and below 2^11 in size: exact in f64.
        Some(quick_two_sum(hi, (i128::from(n) - hi as i128) as f64))
    }
    fn from_u64(n: u64) -> Option<Self> {
        let hi = n as f64;
        Some(quick_two_sum(hi, (i128::from(n) - hi as i128) as f64))
    }
    fn from_f64(x: f64) -> Option<Self> {
        Some(DoubleDouble::new(x))
    }
}

impl DualStruct for DoubleDouble {
    type Real = f64;
    type Inner = DoubleDouble;
    fn re(&self) -> f64 {
        self.hi
    }
    fn from_inner(inner: &Self) -> Self {
        *inner
    }
}

impl Mappable<DoubleDouble> for DoubleDouble {
    type Output<O> = O;
    fn map_dual<M: FnOnce(DoubleDouble) -> O, O>(self, f: M) -> O {
        f(self)
    }
}

impl DualNum for DoubleDouble {
    type Primitive = f64;
    const NDERIV: usize = 0;
    type InnerDual = DoubleDouble;

    fn from_re(re: Self) -> Self {
        re
    }
    fn scale(self, factor: &Self) -> Self {
        self * *factor
    }
    fn recip(&self) -> Self {
        DoubleDouble::one() / *self
    }
    fn powi(&self, n: i32) -> Self {
        let mut result = DoubleDouble::one();
        let mut base = *self;
        let mut k = n.unsigned_abs();
        while k > 0 {
            if k & 1 == 1 {
                result *= base;
            }
            base = base * base;
            k >>= 1;
        }
        if n < 0 { result.recip() } else { result }
    }
    fn powf(&self, n: f64) -> Self {
        with_constant(*self, n, |a, x, n| a.binary(Binary::Powf, x, n))
    }
    fn powd(&self, n: Self) -> Self {
        Self::big(&[*self, n], |a, v| a.binary(Binary::Powf, &v[0], &v[1]))
    }
    fn sqrt(&self) -> Self {
        self.unary(Unary::Sqrt)
    }
    fn cbrt(&self) -> Self {
        self.unary(Unary::Cbrt)
    }
    fn exp(&self) -> Self {
        self.unary(Unary::Exp)
    }
    fn exp2(&self) -> Self {
        with_constant(*self, 2.0, |a, x, two| a.binary(Binary::Powf, two, x))
    }
    fn exp_m1(&self) -> Self {
        with_constant(*self, 1.0, |a, x, one| {
            let e = a.unary(Unary::Exp, x);
            a.binary(Binary::Sub, &e, one)
        })
    }
    fn ln(&self) -> Self {
        self.unary(Unary::Ln)
    }
    fn log(&self, base: f64) -> Self {
        with_constant(*self, base, |a, x, b| {
            let (lx, lb) = (a.unary(Unary::Ln, x), a.unary(Unary::Ln, b));
            a.binary(Binary::Div, &lx, &lb)
        })
    }
    fn log2(&self) -> Self {
        self.log(2.0)
    }
    fn log10(&self) -> Self {
        self.log(10.0)
    }
    fn ln_1p(&self) -> Self {
        with_constant(*self, 1.0, |a, x, one| {
            let s = a.binary(Binary::Add, x, one);
            a.unary(Unary::Ln, &s)
        })
    }
    fn sin(&self) -> Self {
        self.unary(Unary::Sin)
    }
    fn cos(&self) -> Self {
        self.unary(Unary::Cos)
    }
    fn tan(&self) -> Self {
        self.unary(Unary::Tan)
    }
    fn sin_cos(&self) -> (Self, Self) {
        (self.sin(), self.cos())
    }
    fn asin(&self) -> Self {
        self.unary(Unary::Asin)
    }
    fn acos(&self) -> Self {
        self.unary(Unary::Acos)
    }
    fn atan(&self) -> Self {
        self.unary(Unary::Atan)
    }
    fn atan2(&self, other: Self) -> Self {
        Self::big(&[*self, other], |a, v| {
            a.binary(Binary::Atan2, &v[0], &v[1])
        })
    }
    fn sinh(&self) -> Self {
        self.unary(Unary::Sinh)
    }
    fn cosh(&self) -> Self {
        self.unary(Unary::Cosh)
    }
    fn tanh(&self) -> Self {
        self.unary(Unary::Tanh)
    }
    /// ln(|x| + √(x² + 1)) with the sign of x (no cancellation for x < 0).
    fn asinh(&self) -> Self {
        let magnitude = with_constant(self.abs(), 1.0, |a, x, one| {
            let x2 = a.binary(Binary::Mul, x, x);
            let s = a.binary(Binary::Add, &x2, one);
            let r = a.unary(Unary::Sqrt, &s);
            let sum = a.binary(Binary::Add, x, &r);
            a.unary(Unary::Ln, &sum)
        });
        if self.hi < 0.0 { -magnitude } else { magnitude }
    }
    fn acosh(&self) -> Self {
        with_constant(*self, 1.0, |a, x, one| {
            let x2 = a.binary(Binary::Mul, x, x);
            let s = a.binary(Binary::Sub, &x2, one);
            let r = a.unary(Unary::Sqrt, &s);
            let sum = a.binary(Binary::Add, x, &r);
            a.unary(Unary::Ln, &sum)
        })
    }
    fn atanh(&self) -> Self {
        with_constant(*self, 1.0, |a, x, one| {
            let p = a.binary(Binary::Add, one, x);
            let m = a.binary(Binary::Sub, one, x);
            let q = a.binary(Binary::Div, &p, &m);
            let l = a.unary(Unary::Ln, &q);
            let half = a.constant(0.5);
            a.binary(Binary::Mul, &half, &l)
        })
    }
    /// sin x / x (1 at x = 0).
    fn sph_j0(&self) -> Self {
        if self.hi == 0.0 {
            return DoubleDouble::one();
        }
        Self::big(&[*self], |a, v| {
            let s = a.unary(Unary::Sin, &v[0]);
            a.binary(Binary::Div, &s, &v[0])
        })
    }
    /// (sin x / x − cos x) / x (0 at x = 0).
    fn sph_j1(&self) -> Self {
        if self.hi == 0.0 {
            return DoubleDouble::zero();
        }
        Self::big(&[*self], |a, v| {
            let x = &v[0];
            let (s, c) = (a.unary(Unary::Sin, x), a.unary(Unary::Cos, x));
            let q = a.binary(Binary::Div, &s, x);
            let d = a.binary(Binary::Sub, &q, &c);
            a.binary(Binary::Div, &d, x)
        })
    }
    /// ((3 − x²) sin x − 3x cos x) / x³ (0 at x = 0).
    fn sph_j2(&self) -> Self {
        if self.hi == 0.0 {
            return DoubleDouble::zero();
        }
        Self::big(&[*self], |a, v| {
            let x = &v[0];
            let (s, c) = (a.unary(Unary::Sin, x), a.unary(Unary::Cos, x));
            let three = a.constant(3.0);
            let x2 = a.binary(Binary::Mul, x, x);
            let x3 = a.binary(Binary::Mul, &x2, x);
            let k = a.binary(Binary::Sub, &three, &x2);
            let ks = a.binary(Binary::Mul, &k, &s);
            let xc = a.binary(Binary::Mul, x, &c);
            let t = a.binary(Binary::Mul, &three, &xc);
            let n = a.binary(Binary::Sub, &ks, &t);
            a.binary(Binary::Div, &n, &x3)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `x` against a 256-bit value: |x − big| / |big|.
    fn relative(x: DoubleDouble, big: &BigReal) -> f64 {
        let mut a = BigArithmetic::new(FUNCTION_BITS);
        x.to_big(&mut a).relative_difference(big)
    }

    /// Addition, multiplication and division keep ~106 bits: (1/3)·3 − 1, √2·√2 − 2 and a
    /// sum are within 1e-30 of the exact results (2⁻¹⁰⁴ ≈ 5e-32 per operation, a few operations).
    #[test]
    fn arithmetic_keeps_double_double_precision() {
        let third = DoubleDouble::new(1.0) / DoubleDouble::new(3.0);
        assert!((third * 3.0 - 1.0).abs().hi <= 1e-30);
        let root = DoubleDouble::new(2.0).sqrt();
        assert!((root * root - 2.0).abs().hi <= 1e-30);
        // Σ 0.1 (the f64 nearest 0.1) ten times is exactly 10 × that f64: within 1e-30.
        let tenth = DoubleDouble::new(0.1);
        let sum: DoubleDouble = std::iter::repeat_n(tenth, 10).sum();
        let mut a = BigArithmetic::new(FUNCTION_BITS);
        let exact = {
            let t = a.constant(0.1);
            let ten = a.constant(10.0);
            a.binary(Binary::Mul, &t, &ten)
        };
        assert!(relative(sum, &exact) <= 1e-30);
    }

    /// The functions are the 256-bit ones rounded to double-double: sin, atan and exp of
    /// 0.7 within 2⁻¹⁰⁴ relative of their 256-bit values.
    #[test]
    fn functions_are_correctly_rounded_to_double_double() {
        let x = DoubleDouble::new(0.7);
        for (op, got) in [
            (Unary::Sin, x.sin()),
            (Unary::Atan, x.atan()),
            (Unary::Exp, x.exp()),
        ] {
            let mut a = BigArithmetic::new(FUNCTION_BITS);
            let seven = a.constant(0.7);
            let exact = a.unary(op, &seven);
            assert!(relative(got, &exact) <= f64::powi(2.0, -104), "{op:?}");
        }
    }

    /// Integers beyond 2⁵³ are exact: 2⁵³ + 1 is hi = 2⁵³, lo = 1.
    #[test]
    fn large_integers_are_exact() {
        let n = DoubleDouble::from_i64((1 << 53) + 1).unwrap();
        assert_eq!((n.hi, n.lo), (9_007_199_254_740_992.0, 1.0));
    }
}
