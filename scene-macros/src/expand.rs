//! The scene file named by the macro's path, read and expanded to the generated module.

use std::path::{Path, PathBuf};

use proc_macro2::TokenStream;
use quote::quote;
use syn::LitStr;

/// The file at `path`, relative to the folder of the `Cargo.toml` being compiled
/// (`CARGO_MANIFEST_DIR`; the current folder when that is not set, as in unit tests).
fn scene_file(path: &LitStr) -> PathBuf {
    let base = std::env::var_os("CARGO_MANIFEST_DIR").map_or_else(PathBuf::new, PathBuf::from);
    base.join(path.value())
}

/// The module `mechdiff codegen <path>` prints, as tokens, preceded by the scene file's
/// bytes in an unnamed constant (so that cargo rebuilds the crate when the file changes).
///
/// # Errors
/// The scene reader's or the code generator's error, at `path`.
pub fn scene_module(path: &LitStr) -> syn::Result<TokenStream> {
    let file = scene_file(path);
    // Messages name the file as the macro's path names it, not as found on this machine.
    let shown = file.display().to_string();
    let fail =
        |message: String| syn::Error::new_spanned(path, message.replace(&shown, &path.value()));
    let scene = mechdiff::codegen::scene::load(&file).map_err(|e| fail(e.to_string()))?;
    let source =
        mechdiff::codegen::scene::module(&scene, &path.value()).map_err(|e| fail(e.to_string()))?;
    let module: TokenStream = source
        .parse()
        .map_err(|e| fail(format!("the generated module does not parse (a bug): {e}")))?;
    let tracked = absolute(&file).display().to_string();
    Ok(quote! {
        const _: &[u8] = include_bytes!(#tracked);
        #module
    })
}

/// `file` made absolute, so `include_bytes!` finds it from any source file.
fn absolute(file: &Path) -> PathBuf {
    std::path::absolute(file).unwrap_or_else(|_| file.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn literal(path: &str) -> LitStr {
        LitStr::new(path, proc_macro2::Span::call_site())
    }

    #[test]
    fn a_missing_scene_file_is_an_error_naming_it_as_written() {
        let message = scene_module(&literal("scenes/no_such_scene.toml"))
            .unwrap_err()
            .to_string();
        assert!(
            message.contains("cannot read scenes/no_such_scene.toml:"),
            "{message}"
        );
    }

    #[test]
    fn the_expansion_is_the_printed_module_and_tracks_the_file() {
        let tokens = scene_module(&literal("../scenes/slider_crank.toml"))
            .unwrap()
            .to_string();
        let (tracked, module) = tokens.split_once(';').unwrap();
        assert!(tracked.contains("include_bytes"), "{tracked}");
        assert!(tracked.contains("slider_crank.toml"), "{tracked}");
        assert!(
            Path::new(tracked.split('"').nth(1).unwrap()).is_absolute(),
            "{tracked}"
        );
        let tokens = module;
        for item in ["OUTPUTS", "ORDER", "LOOPS", "LoopFailure", "fn pose"] {
            assert!(tokens.contains(item), "{item} missing");
        }
    }
}
