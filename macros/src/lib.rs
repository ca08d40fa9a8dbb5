//! Proc-macros of mechdiff: derivatives generated at compile time by the symbolic engine of
//! `mechdiff_core::symbolic`.
//!
//! The stages are modules, each returning `syn::Result`: `attr` (the attribute's
//! arguments) → `ast` (the function's Rust into the engine's IR) → `differentiate`
//! (derivatives; simplification and CSE happen in the engine as nodes are built) →
//! `expand` (straight-line Rust).

use proc_macro::TokenStream;

mod ast;
mod attr;
mod differentiate;
mod expand;
#[cfg(test)]
mod unsupported;

/// Generates, next to a plain `f64` function, a sibling that returns its value and its
/// derivatives up to `order` with respect to the parameter `wrt`, as straight-line code.
///
/// ```
/// use mechdiff_macros::derivatives;
///
/// /// Rocker angle ψ of the Whitworth mechanism.
/// #[derivatives(wrt = phi, order = 2)]
/// fn psi(phi: f64, lambda: f64) -> f64 {
///     (lambda * phi.sin()).atan2(1.0 - lambda * phi.cos())
/// }
///
/// let jet = psi_derivatives(0.0, 0.375); // a mechdiff_core::Jet<2>
/// assert_eq!(jet.value, psi(0.0, 0.375));
/// assert!((jet.d1() - 0.375 / 0.625).abs() < 1e-15); // ψ′(0) = λ / (1 − λ)
/// assert!(jet.d2().abs() < 1e-15); // ψ is odd in φ
/// ```
///
/// Arguments: `wrt = <parameter>` and `order = <1..>` (required); `name = <ident>` for the
/// sibling (default `<function>_derivatives`); `expression = <ident>` to also generate a
/// function returning the value's s-expression. The sibling has the original parameters and
/// returns a `mechdiff_core::Jet<order>` (value and derivatives 1 to `order`), so the crate
/// using the macro depends on `mechdiff-core`.
///
/// The function may use `let` bindings, `+ - * /` and negation, the methods `sqrt cbrt exp
/// ln sin cos tan asin acos atan sinh cosh tanh abs`, `powi(<integer>)`, `powf(x)`,
/// `atan2(x)`, `hypot(x)`, `recip()`, `f64` literals, its parameters, named constants
/// (`L0`, `std::f64::consts::PI`, differentiated as constants) and `if`/`else` on comparisons
/// (the derivative is that of the branch taken). Anything else is a compile error that
/// points at the construct.
#[proc_macro_attribute]
pub fn derivatives(args: TokenStream, input: TokenStream) -> TokenStream {
    let function = syn::parse_macro_input!(input as syn::ItemFn);
    expand::derivatives(args.into(), function).into()
}
