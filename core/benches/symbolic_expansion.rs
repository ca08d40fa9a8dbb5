//! How long does the symbolic engine take to expand the Whitworth functions, i.e. the work
//! `#[derivatives(wrt = phi, order = 2)]` does at compile time for ψ and x_C (the macro's
//! own step, turning the `syn` tree into the IR, is a walk over a dozen tokens)?
//!
//! `cargo bench -p mechdiff-core --bench symbolic_expansion -- --warm-up-time 1 --measurement-time 3`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use mechdiff_core::symbolic::{Graph, format_rust};

const PSI: &str = "atan2(lambda*sin(phi), 1 - lambda*cos(phi))";
const X_C: &str = "h*tan(atan2(lambda*sin(phi), 1 - lambda*cos(phi)))";

/// Parse, differentiate to `order`, emit tokens: what the macro does for one function.
fn expand(formula: &str, order: usize) -> proc_macro2::TokenStream {
    let mut graph = Graph::new();
    let value = graph.parse_infix(formula).expect("a valid formula");
    let outputs = graph.derivatives(value, "phi", order);
    let names: Vec<String> = (0..=order).map(|k| format!("d{k}")).collect();
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    graph.emit_function("expanded", &["phi", "lambda", "h"], &outputs, &names)
}

fn whitworth_expansion(c: &mut Criterion) {
    let mut group = c.benchmark_group("whitworth expansion: ψ and x_C");
    for order in [2, 3] {
        group.bench_function(
            format!("parse + differentiate (order {order}) + emit tokens"),
            |b| b.iter(|| (expand(black_box(PSI), order), expand(black_box(X_C), order))),
        );
    }
    group.bench_function(
        "… order 2 + format with prettyplease (mechdiff codegen)",
        |b| {
            b.iter(|| {
                (
                    format_rust(expand(black_box(PSI), 2)).expect("valid Rust"),
                    format_rust(expand(black_box(X_C), 2)).expect("valid Rust"),
                )
            })
        },
    );
    group.finish();
}

criterion_group!(benches, whitworth_expansion);
criterion_main!(benches);
