//! The primitives of the expression IR and their names.
//!
//! The name of a primitive is the same in the s-expression syntax, in the infix syntax
//! (`sin(x)`, `atan2(y, x)`) and as the `f64` method the emitted Rust calls (`x.sin()`,
//! `y.atan2(x)`). The derivative rule of each primitive is in [`super::rules`].

use std::fmt;

macro_rules! named_enum {
    ($(#[$doc:meta])* $name:ident { $($(#[$vdoc:meta])* $variant:ident => $text:literal,)* }) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum $name {
            $($(#[$vdoc])* $variant,)*
        }

        impl $name {
            /// Every variant, in declaration order.
            pub const ALL: &'static [$name] = &[$($name::$variant,)*];

            /// The name in s-expressions, in infix formulas and as an `f64` method.
            pub fn name(self) -> &'static str {
                match self {
                    $($name::$variant => $text,)*
                }
            }

            /// The primitive called `name`, if there is one.
            pub fn from_name(name: &str) -> Option<Self> {
                match name {
                    $($text => Some($name::$variant),)*
                    _ => None,
                }
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}

named_enum! {
    /// A primitive of one argument.
    Unary {
        /// Negation `-u`.
        Neg => "neg",
        /// Square root.
        Sqrt => "sqrt",
        /// Cube root.
        Cbrt => "cbrt",
        /// Exponential.
        Exp => "exp",
        /// Natural logarithm.
        Ln => "ln",
        /// Sine.
        Sin => "sin",
        /// Cosine.
        Cos => "cos",
        /// Tangent.
        Tan => "tan",
        /// Arc sine.
        Asin => "asin",
        /// Arc cosine.
        Acos => "acos",
        /// Arc tangent.
        Atan => "atan",
        /// Hyperbolic sine.
        Sinh => "sinh",
        /// Hyperbolic cosine.
        Cosh => "cosh",
        /// Hyperbolic tangent.
        Tanh => "tanh",
        /// Absolute value.
        Abs => "abs",
    }
}

named_enum! {
    /// A primitive of two arguments.
    Binary {
        /// Sum `a + b`.
        Add => "+",
        /// Difference `a - b`.
        Sub => "-",
        /// Product `a * b`.
        Mul => "*",
        /// Quotient `a / b`.
        Div => "/",
        /// Real power `a.powf(b)`.
        Powf => "powf",
        /// Four-quadrant arc tangent `a.atan2(b)` = angle of the point (b, a).
        Atan2 => "atan2",
        /// `a.hypot(b)` = √(a² + b²).
        Hypot => "hypot",
    }
}

named_enum! {
    /// The comparison that selects a branch of a piecewise expression.
    Comparison {
        /// `a < b`.
        Less => "<",
        /// `a <= b`.
        LessEqual => "<=",
        /// `a > b`.
        Greater => ">",
        /// `a >= b`.
        GreaterEqual => ">=",
        /// `a == b`.
        Equal => "==",
        /// `a != b`.
        NotEqual => "!=",
    }
}

impl Binary {
    /// Whether the primitive is written between its operands (`a + b`) rather than as a
    /// method call (`a.powf(b)`).
    pub fn is_infix(self) -> bool {
        matches!(self, Binary::Add | Binary::Sub | Binary::Mul | Binary::Div)
    }
}

impl Comparison {
    /// Applies the comparison to two ordered values.
    pub fn holds<T: PartialOrd>(self, a: &T, b: &T) -> bool {
        match self {
            Comparison::Less => a < b,
            Comparison::LessEqual => a <= b,
            Comparison::Greater => a > b,
            Comparison::GreaterEqual => a >= b,
            Comparison::Equal => a == b,
            Comparison::NotEqual => a != b,
        }
    }
}
