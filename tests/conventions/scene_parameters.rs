//! Which functions of a file take the whole scene (issue 23: "`&Scene` appears in no
//! function of the runner or the effects"; they take a resolved `Setup` or its parts).
//!
//! A function **takes the scene** when a parameter's type names the type `Scene` anywhere
//! (`&Scene`, `&'s crate::scene::Scene`, `Option<&Scene>`, `Scene` by value), or when it is
//! a method of an `impl … Scene` with a `self` receiver. A struct or enum whose field's type
//! names `Scene` **holds the scene** (a context object kept for later calls), and is
//! reported the same way. A return type is neither: building a scene is reading, not
//! running. `SceneDynamics`, `SceneCode`, … are other types (the name is compared whole).
//!
//! Parsed with syn: every function of the file is visited — free, in `impl` and `trait`
//! blocks, in inline modules (`mod tests`), and functions declared inside a function's body
//! (its top-level statements). Closures' parameters are not visited (a closure is not
//! called from elsewhere); neither are macro bodies.

use proc_macro2::{TokenStream, TokenTree};
use quote::ToTokens;
use syn::{Block, FnArg, ImplItem, Item, Signature, Stmt, TraitItem};

/// Whether `tokens` name the type `Scene`: an identifier `Scene` not followed by `::`
/// (then it would be a module path such as `Scene::new` — a path, not a type).
fn names_scene(tokens: TokenStream) -> bool {
    let flat = flatten(tokens);
    flat.iter().enumerate().any(|(i, t)| {
        matches!(t, TokenTree::Ident(id) if id == "Scene")
            && !matches!(
                (flat.get(i + 1), flat.get(i + 2)),
                (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b)))
                    if a.as_char() == ':' && b.as_char() == ':'
            )
    })
}

/// The token trees of `tokens` with every group opened (its delimiters dropped).
fn flatten(tokens: TokenStream) -> Vec<TokenTree> {
    let mut out = Vec::new();
    for t in tokens {
        match t {
            TokenTree::Group(g) => out.extend(flatten(g.stream())),
            other => out.push(other),
        }
    }
    out
}

/// Collects, into `found`, each function or type of `items` (in the module `path`) that
/// takes or holds the scene.
fn visit_items(items: &[Item], path: &str, found: &mut Vec<String>) {
    for item in items {
        match item {
            Item::Fn(f) => visit_fn(&f.sig, Some(&f.block), false, path, found),
            Item::Impl(i) => {
                let scene_self = names_scene(i.self_ty.to_token_stream());
                for item in &i.items {
                    if let ImplItem::Fn(f) = item {
                        visit_fn(&f.sig, Some(&f.block), scene_self, path, found);
                    }
                }
            }
            Item::Trait(t) => {
                for item in &t.items {
                    if let TraitItem::Fn(f) = item {
                        visit_fn(&f.sig, f.default.as_ref(), false, path, found);
                    }
                }
            }
            Item::Mod(m) => {
                if let Some((_, items)) = &m.content {
                    visit_items(items, &format!("{path}{}::", m.ident), found);
                }
            }
            Item::Struct(s) if names_scene(s.fields.to_token_stream()) => {
                found.push(format!("struct {path}{} holds the scene", s.ident));
            }
            Item::Enum(e)
                if e.variants
                    .iter()
                    .any(|v| names_scene(v.fields.to_token_stream())) =>
            {
                found.push(format!("enum {path}{} holds the scene", e.ident));
            }
            _ => {}
        }
    }
}

/// Collects the function `sig` if it takes the scene (its `self` the scene when
/// `scene_self`), then the functions declared in its `body`.
fn visit_fn(
    sig: &Signature,
    body: Option<&Block>,
    scene_self: bool,
    path: &str,
    found: &mut Vec<String>,
) {
    let takes = sig.inputs.iter().any(|input| match input {
        FnArg::Receiver(_) => scene_self,
        FnArg::Typed(t) => names_scene(t.ty.to_token_stream()),
    });
    if takes {
        found.push(format!("fn {path}{} takes the scene", sig.ident));
    }
    let inner: Vec<Item> = (body.into_iter())
        .flat_map(|b| &b.stmts)
        .filter_map(|s| match s {
            Stmt::Item(item) => Some(item.clone()),
            _ => None,
        })
        .collect();
    visit_items(&inner, &format!("{path}{}::", sig.ident), found);
}

/// Every function of the Rust source `text` that takes the scene, and every type that holds
/// it, in file order (`fn run takes the scene`, `struct Sweeper holds the scene`, with the
/// inline modules and enclosing functions they are in).
///
/// # Errors
/// The parser's, for a file that is not Rust.
pub fn taking_the_scene(text: &str) -> syn::Result<Vec<String>> {
    let file = syn::parse_file(text)?;
    let mut found = Vec::new();
    visit_items(&file.items, "", &mut found);
    Ok(found)
}
