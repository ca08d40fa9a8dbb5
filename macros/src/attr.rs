//! The arguments of `#[derivatives(wrt = phi, order = 2)]`.

use proc_macro2::TokenStream;
use syn::Ident;
use syn::parse::Parser;

/// What the attribute asks for.
pub struct Arguments {
    /// The parameter to differentiate with respect to.
    pub wrt: Ident,
    /// The highest derivative order.
    pub order: usize,
    /// The name of the generated sibling, if given.
    pub name: Option<Ident>,
    /// The name of a generated function returning the value's s-expression, if asked.
    pub expression: Option<Ident>,
}

/// Parses the attribute's arguments.
pub fn parse(tokens: TokenStream) -> syn::Result<Arguments> {
    let (mut wrt, mut order, mut name, mut expression) = (None, None, None, None);
    let parser = syn::meta::parser(|meta| {
        if meta.path.is_ident("wrt") {
            wrt = Some(meta.value()?.parse::<Ident>()?);
        } else if meta.path.is_ident("order") {
            let literal: syn::LitInt = meta.value()?.parse()?;
            let value: usize = literal.base10_parse()?;
            if value == 0 {
                return Err(syn::Error::new_spanned(
                    literal,
                    "`order` must be at least 1",
                ));
            }
            order = Some(value);
        } else if meta.path.is_ident("name") {
            name = Some(meta.value()?.parse::<Ident>()?);
        } else if meta.path.is_ident("expression") {
            expression = Some(meta.value()?.parse::<Ident>()?);
        } else {
            return Err(
                meta.error("unknown argument; expected `wrt`, `order`, `name` or `expression`")
            );
        }
        Ok(())
    });
    parser.parse2(tokens.clone())?;
    let missing = |what: &str| {
        syn::Error::new(
            proc_macro2::Span::call_site(),
            format!("missing `{what}`: write `#[derivatives(wrt = <parameter>, order = <n>)]`"),
        )
    };
    Ok(Arguments {
        wrt: wrt.ok_or_else(|| missing("wrt"))?,
        order: order.ok_or_else(|| missing("order"))?,
        name,
        expression,
    })
}
