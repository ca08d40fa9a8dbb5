//! `mechdiff_scene!("scenes/whitworth.toml")`: the compile-time back end of scene code
//! generation. The macro reads the scene file when the crate using it compiles and expands
//! to the items of the module `mechdiff codegen` prints for it (`OUTPUTS`, `ORDER`,
//! `LOOPS`, `LoopFailure`, `SINGULAR_THRESHOLD`, `pose`), without a build script.
//!
//! The stages are modules returning `syn::Result`: `expand` (the path → the scene → the
//! module's tokens). The scene reader and the emitter are those of the `mechdiff`
//! library, so the macro's code is `mechdiff codegen`'s, token for token.

use proc_macro::TokenStream;

mod expand;

/// Expands to the generated module of the scene file at the given path (relative to the
/// crate's `Cargo.toml`, as `include_str!` paths are not): put it inside a module.
///
/// ```
/// mod whitworth {
///     mechdiff_scene_macros::mechdiff_scene!("../scenes/whitworth.toml");
/// }
/// let [[psi, psi_1, _], _] = whitworth::pose(0.0).unwrap();
/// assert!(psi.abs() < 1e-15);
/// assert!((psi_1 - 0.6).abs() < 1e-15); // ψ′(0) = λ / (1 − λ), λ = 0.375
/// assert_eq!(whitworth::OUTPUTS, ["psi", "x_C"]);
/// ```
///
/// The generated code needs nothing but `core` and `std`. An edit of the scene file
/// recompiles the crate (the file is included as bytes). A scene with a loop that has no
/// closed form (a mixed plan) expands to a module with a `Tracker` instead of `pose`: it
/// solves that loop by Newton's method as the solver does, warm-started from the last
/// position (see `mechdiff codegen` in docs/). A scene the code generator refuses (a parse
/// error, a cam drive) is a compile error at the path, with the scene's message.
#[proc_macro]
pub fn mechdiff_scene(input: TokenStream) -> TokenStream {
    let path = syn::parse_macro_input!(input as syn::LitStr);
    expand::scene_module(&path)
        .unwrap_or_else(syn::Error::into_compile_error)
        .into()
}
