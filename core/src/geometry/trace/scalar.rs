//! [`Traced`]: a scalar that records every operation into a symbolic [`Graph`] while it
//! computes the `f64` value at the point of the trace.
//!
//! The closed forms are generic over [`crate::Scalar`]; evaluated with `Traced` (inside
//! [`record`]) they leave their formulas in the graph. Each value also carries its `f64`
//! value at the traced drive position, so that the formulas' value-dependent choices (the
//! turn an angle is unwrapped to, a loop's assembly check at the sketch) are taken as the
//! solver takes them there; the choices that depend on the drive position in general are
//! recorded as nodes: `atan2` (see [`crate::atan2`]) and the loops' margins (guards).
//! An operation without a symbolic counterpart (`rem`, Bessel functions, …) marks the trace
//! as unsupported: [`record`] then reports it instead of returning a wrong graph.

use std::cell::RefCell;
use std::fmt;
use std::iter::{Product, Sum};
use std::ops::{
    Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Rem, RemAssign, Sub, SubAssign,
};

use num_dual::{DualNum, DualStruct, Mappable};
use num_traits::{FromPrimitive, Inv, Num, One, Signed, Zero};

use crate::symbolic::{Binary, Graph, Id, Unary};

/// The graph being recorded into, and the first operation that could not be recorded.
struct Tape {
    graph: Graph,
    unsupported: Option<&'static str>,
}

thread_local! {
    static TAPE: RefCell<Option<Tape>> = const { RefCell::new(None) };
}

/// A value computed while recording: its `f64` value at the traced point and its node.
///
/// Created only inside `record`; outside it, operations compute values only.
#[derive(Clone, Copy, Debug)]
pub struct Traced {
    value: f64,
    id: Id,
}

/// Records `f` into `graph`: every [`Traced`] operation inside adds its node. Returns the
/// graph, `f`'s result, or the name of the first operation that has no symbolic form.
pub(crate) fn record<R>(graph: Graph, f: impl FnOnce() -> R) -> (Graph, Result<R, &'static str>) {
    let previous = TAPE.with(|t| {
        t.borrow_mut().replace(Tape {
            graph,
            unsupported: None,
        })
    });
    let result = f();
    let tape = TAPE.with(|t| std::mem::replace(&mut *t.borrow_mut(), previous));
    let tape = tape.expect("the tape set above");
    let result = match tape.unsupported {
        Some(op) => Err(op),
        None => Ok(result),
    };
    (tape.graph, result)
}

/// Applies `f` to the graph being recorded (an id of no node outside [`record`]).
fn with_graph(f: impl FnOnce(&mut Graph) -> Id) -> Id {
    TAPE.with(|t| match t.borrow_mut().as_mut() {
        Some(tape) => f(&mut tape.graph),
        None => Id::default(),
    })
}

/// Marks the trace as unsupported by `op`.
fn unsupported(op: &'static str) -> Traced {
    TAPE.with(|t| {
        if let Some(tape) = t.borrow_mut().as_mut() {
            tape.unsupported.get_or_insert(op);
        }
    });
    Traced {
        value: f64::NAN,
        id: Id::default(),
    }
}

impl Traced {
    /// The symbol `name` with the value `value` at the traced point.
    pub(crate) fn symbol(name: &str, value: f64) -> Self {
        Traced {
            value,
            id: with_graph(|g| g.symbol(name)),
        }
    }

    /// The node of this value in the recorded graph.
    pub fn id(self) -> Id {
        self.id
    }

    /// The value at the traced point.
    pub fn value(self) -> f64 {
        self.value
    }

    /// The constant `value` (non-finite constants cannot be recorded).
    fn constant(value: f64) -> Self {
        if !value.is_finite() {
            return unsupported("a non-finite constant");
        }
        Traced {
            value,
            id: with_graph(|g| g.number(value)),
        }
    }

    fn unary(self, op: Unary, value: f64) -> Self {
        Traced {
            value,
            id: with_graph(|g| g.unary(op, self.id)),
        }
    }

    fn binary(self, op: Binary, other: Self, value: f64) -> Self {
        Traced {
            value,
            id: with_graph(|g| g.binary(op, self.id, other.id)),
        }
    }

    /// The four-quadrant arc tangent `atan2(self, x)`, recorded as one node (valid in
    /// every quadrant, not only the one of the traced point).
    pub fn atan2_node(self, x: Self) -> Self {
        self.binary(Binary::Atan2, x, self.value.atan2(x.value))
    }
}

impl PartialEq for Traced {
    fn eq(&self, other: &Self) -> bool {
        self.value == other.value
    }
}

impl PartialOrd for Traced {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        self.value.partial_cmp(&other.value)
    }
}

impl PartialEq<f64> for Traced {
    fn eq(&self, other: &f64) -> bool {
        self.value == *other
    }
}

impl PartialOrd<f64> for Traced {
    fn partial_cmp(&self, other: &f64) -> Option<std::cmp::Ordering> {
        self.value.partial_cmp(other)
    }
}

impl fmt::Display for Traced {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (node {})", self.value, self.id)
    }
}

macro_rules! arithmetic {
    ($($trait:ident $method:ident $assign:ident $assign_method:ident => $op:ident;)*) => {$(
        impl $trait for Traced {
            type Output = Traced;
            fn $method(self, rhs: Traced) -> Traced {
                self.binary(Binary::$op, rhs, $trait::$method(self.value, rhs.value))
            }
        }
        impl $trait<&Traced> for Traced {
            type Output = Traced;
            fn $method(self, rhs: &Traced) -> Traced {
                $trait::$method(self, *rhs)
            }
        }
        impl $trait<f64> for Traced {
            type Output = Traced;
            fn $method(self, rhs: f64) -> Traced {
                $trait::$method(self, Traced::constant(rhs))
            }
        }
        impl $assign for Traced {
            fn $assign_method(&mut self, rhs: Traced) {
                *self = $trait::$method(*self, rhs);
            }
        }
        impl $assign<f64> for Traced {
            fn $assign_method(&mut self, rhs: f64) {
                *self = $trait::$method(*self, rhs);
            }
        }
    )*};
}

arithmetic! {
    Add add AddAssign add_assign => Add;
    Sub sub SubAssign sub_assign => Sub;
    Mul mul MulAssign mul_assign => Mul;
    Div div DivAssign div_assign => Div;
}

impl Rem for Traced {
    type Output = Traced;
    fn rem(self, _: Traced) -> Traced {
        unsupported("rem")
    }
}

impl Rem<&Traced> for Traced {
    type Output = Traced;
    fn rem(self, _: &Traced) -> Traced {
        unsupported("rem")
    }
}

impl Rem<f64> for Traced {
    type Output = Traced;
    fn rem(self, _: f64) -> Traced {
        unsupported("rem")
    }
}

impl RemAssign for Traced {
    fn rem_assign(&mut self, _: Traced) {
        *self = unsupported("rem");
    }
}

impl RemAssign<f64> for Traced {
    fn rem_assign(&mut self, _: f64) {
        *self = unsupported("rem");
    }
}

impl Neg for Traced {
    type Output = Traced;
    fn neg(self) -> Traced {
        Traced {
            value: -self.value,
            id: with_graph(|g| g.neg(self.id)),
        }
    }
}

impl Inv for Traced {
    type Output = Traced;
    fn inv(self) -> Traced {
        self.recip()
    }
}

impl Sum for Traced {
    fn sum<I: Iterator<Item = Traced>>(iter: I) -> Traced {
        iter.fold(Traced::zero(), |a, b| a + b)
    }
}

impl Product for Traced {
    fn product<I: Iterator<Item = Traced>>(iter: I) -> Traced {
        iter.fold(Traced::one(), |a, b| a * b)
    }
}

impl Zero for Traced {
    fn zero() -> Self {
        Traced::constant(0.0)
    }
    fn is_zero(&self) -> bool {
        self.value == 0.0
    }
}

impl One for Traced {
    fn one() -> Self {
        Traced::constant(1.0)
    }
}

impl Num for Traced {
    type FromStrRadixErr = <f64 as Num>::FromStrRadixErr;
    fn from_str_radix(text: &str, radix: u32) -> Result<Self, Self::FromStrRadixErr> {
        f64::from_str_radix(text, radix).map(Traced::constant)
    }
}

impl Signed for Traced {
    fn abs(&self) -> Self {
        self.unary(Unary::Abs, self.value.abs())
    }
    fn abs_sub(&self, _: &Self) -> Self {
        unsupported("abs_sub")
    }
    fn signum(&self) -> Self {
        unsupported("signum")
    }
    fn is_positive(&self) -> bool {
        self.value.is_sign_positive()
    }
    fn is_negative(&self) -> bool {
        self.value.is_sign_negative()
    }
}

impl FromPrimitive for Traced {
    fn from_i64(n: i64) -> Option<Self> {
        Some(Traced::constant(n as f64))
    }
    fn from_u64(n: u64) -> Option<Self> {
        Some(Traced::constant(n as f64))
    }
    fn from_f64(n: f64) -> Option<Self> {
        Some(Traced::constant(n))
    }
}

impl From<f64> for Traced {
    fn from(value: f64) -> Self {
        Traced::constant(value)
    }
}

impl DualStruct for Traced {
    type Real = f64;
    type Inner = f64;
    fn re(&self) -> f64 {
        self.value
    }
    fn from_inner(inner: &f64) -> Self {
        Traced::constant(*inner)
    }
}

impl Mappable<Traced> for Traced {
    type Output<O> = O;
    fn map_dual<M: FnOnce(Traced) -> O, O>(self, f: M) -> O {
        f(self)
    }
}

macro_rules! unary_methods {
    ($($method:ident => $op:ident,)*) => {$(
        fn $method(&self) -> Self {
            self.unary(Unary::$op, self.value.$method())
        }
    )*};
}

macro_rules! unsupported_methods {
    ($($method:ident,)*) => {$(
        fn $method(&self) -> Self {
            unsupported(stringify!($method))
        }
    )*};
}

impl DualNum for Traced {
    type Primitive = f64;
    const NDERIV: usize = 0;
    type InnerDual = f64;

    fn from_re(re: f64) -> Self {
        Traced::constant(re)
    }

    fn scale(self, factor: &f64) -> Self {
        self * *factor
    }

    fn recip(&self) -> Self {
        Traced::constant(1.0) / *self
    }

    fn powi(&self, n: i32) -> Self {
        Traced {
            value: self.value.powi(n),
            id: with_graph(|g| g.powi(self.id, n)),
        }
    }

    fn powf(&self, n: f64) -> Self {
        self.binary(Binary::Powf, Traced::constant(n), self.value.powf(n))
    }

    unary_methods! {
        sqrt => Sqrt, cbrt => Cbrt, exp => Exp, ln => Ln, sin => Sin, cos => Cos,
        tan => Tan, asin => Asin, acos => Acos, atan => Atan, sinh => Sinh, cosh => Cosh,
        tanh => Tanh,
    }

    unsupported_methods! {
        exp2, exp_m1, log2, log10, ln_1p, asinh, acosh, atanh, sph_j0, sph_j1, sph_j2,
    }

    fn log(&self, base: f64) -> Self {
        self.ln() / base.ln()
    }

    fn sin_cos(&self) -> (Self, Self) {
        (self.sin(), self.cos())
    }

    fn atan2(&self, other: Self) -> Self {
        self.atan2_node(other)
    }
}
