//! Stage 2: the derivatives, by the engine's rule table. Simplification and
//! common-subexpression elimination happen in the engine as the nodes are built.

use mechdiff_core::symbolic::Id;

use crate::ast::Lowered;
use crate::attr::Arguments;

/// `[value, d1, …, d_order]` with respect to `arguments.wrt`, in `lowered.graph`.
pub fn derivatives(lowered: &mut Lowered, arguments: &Arguments) -> syn::Result<Vec<Id>> {
    if !lowered.parameters.contains(&arguments.wrt) {
        let names: Vec<String> = lowered.parameters.iter().map(ToString::to_string).collect();
        return Err(syn::Error::new_spanned(
            &arguments.wrt,
            format!(
                "`{}` is not a parameter of the function; differentiate with respect to one of: {}",
                arguments.wrt,
                names.join(", ")
            ),
        ));
    }
    let variable = arguments.wrt.to_string();
    Ok(lowered
        .graph
        .derivatives(lowered.value, &variable, arguments.order))
}
