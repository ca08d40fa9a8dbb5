//! `mechdiff codegen <scene.toml>`: a scene's position solution as generated code.
//!
//! The scene is built and tracked as `mechdiff run` does; its loops' closed forms and its
//! outputs are traced into one expression graph ([`mechdiff_core::trace`]),
//! differentiated to the order the scene's plan needs (at least 2: ψ, ψ′, ψ″), and
//! either emitted as a Rust module ([`module`]: no dependency, drop it into any crate) or
//! compiled for the run-time evaluator ([`SceneCode::program`]).
//!
//! The module has one function, `pose(phi: f64) -> Result<[[f64; ORDER + 1]; N], LoopFailure>`:
//! every output (a point gives two, `x` and `y`) with its derivatives with respect to the
//! drive position, in SI units (rad, m), after checking each loop's guard as the solver
//! checks it. Angles agree with the solver's modulo 2π (the solver keeps them continuous
//! along a sweep; the module has no sweep).
//!
//! A scene with a loop that has no closed form (a mixed plan) gets a `Tracker` instead
//! (`Tracker::new()`, `tracker.pose(phi)`): it keeps the Newton loops' state between calls
//! and solves them as the solver does (see `mixed`).

use mechdiff_core::symbolic::{Id, format_rust};
use mechdiff_core::trace::{self, GuardKind, Program};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};
use std::path::Path;

use crate::error::{Error, Result};
use crate::evaluator::code::refuse_a_cam_drive;
use crate::scene::model::Scene;
use crate::scene::setup::{RunOptions, Setup};

pub use crate::evaluator::code::SceneCode;

mod mixed;

impl SceneCode {
    /// Traces `scene` ([`SceneCode::trace`], its model built as a run builds it).
    ///
    /// # Errors
    /// The scene's model and sketch errors; the symbolic engine's limits (as
    /// [`Error::Codegen`]).
    pub fn of(scene: &Scene) -> Result<Self> {
        refuse_a_cam_drive(&scene.error_context())?;
        Self::trace(&Setup::of(scene, &RunOptions::default())?)
    }

    /// Every node the code computes: the jets, output by output, then the guards.
    fn roots(&self) -> Vec<Id> {
        let mut roots: Vec<Id> = self.jets.iter().flatten().copied().collect();
        roots.extend(self.position.guard_nodes());
        roots
    }

    /// The run-time program: [`SceneCode::read`] reads its outputs.
    ///
    /// # Errors
    /// [`Error::Codegen`] if the graph has a symbol other than φ: a mixed plan's coordinate
    /// symbols (run it with [`mechdiff_core::trace::MixedTracker`]), else a bug.
    pub fn program(&self, scene: &Scene) -> Result<Program> {
        Program::compile(&self.position.graph, &self.roots(), trace::DRIVE).map_err(|source| {
            Error::Codegen {
                origin: scene.file.clone(),
                source,
            }
        })
    }

    /// Reads one evaluation of [`SceneCode::program`] (`out`: jets, then guards): the jets
    /// `[x, x′, …]` output by output, or the loop whose guard fails and why.
    pub fn read<'o>(
        &self,
        out: &'o [f64],
    ) -> std::result::Result<&'o [f64], (usize, trace::GuardFailure)> {
        let jets = self.jets.len() * (self.order + 1);
        match self.position.first_failure(&out[jets..]) {
            Some(failure) => Err(failure),
            None => Ok(&out[..jets]),
        }
    }
}

/// The error the solver gives for `scene` at drive position `phi` (SI), when the
/// generated code's guard fails there: the solver's closed forms evaluated at `phi`
/// (`None` for a mixed plan: its failures depend on the route, walk the solver's tracker).
///
/// # Errors
/// The scene's model errors.
pub fn guard_error(scene: &Scene, phi: f64) -> Result<Option<Error>> {
    let m = crate::scene::build::mechanism(scene)?;
    let cx = scene.error_context();
    let tracker = scene.solver.track(&m).map_err(|e| cx.solver_error(e))?;
    Ok(trace::closed_form_error(&tracker, phi).map(|e| cx.solver_error(e)))
}

/// A name as a Rust identifier: other characters become `_`.
fn identifier(name: &str) -> String {
    let mut id: String = name
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if !id.starts_with(|c: char| c.is_alphabetic() || c == '_') {
        id.insert(0, '_');
    }
    id
}

/// The body of `pose` (tokens), for the module and the proc-macro.
pub fn pose_function(code: &SceneCode) -> TokenStream {
    let graph = &code.position.graph;
    let mut names: Vec<String> = Vec::new();
    for name in &code.names {
        let base = identifier(name);
        names.push(base.clone());
        names.extend((1..=code.order).map(|k| format!("{base}_d{k}")));
    }
    for l in 0..code.position.guards.len() {
        names.push(format!("discriminant_{l}"));
        names.push(format!("condition_{l}"));
    }
    let name_refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let roots = code.roots();
    let body = graph.emit_body(&roots, &name_refs);
    let bound: Vec<_> = names.iter().map(|n| format_ident!("{n}")).collect();
    let count = Literal::usize_unsuffixed(roots.len());
    let width = code.order + 1;
    let rows = bound[..code.jets.len() * width].chunks(width).map(|row| {
        quote! { [#(#row),*] }
    });
    let limit = Literal::f64_unsuffixed(code.position.limit);
    let guards = code
        .position
        .guards
        .iter()
        .enumerate()
        .filter(|(_, g)| g.kind != GuardKind::Always)
        .map(|(l, g)| {
            let l = Literal::usize_unsuffixed(l);
            let (disc, cond) = (
                format_ident!("discriminant_{l}"),
                format_ident!("condition_{l}"),
            );
            let unassemblable = (g.kind == GuardKind::Root).then(|| {
                quote! {
                    if #disc < 0.0 {
                        return Err(LoopFailure::Unassemblable { phi, loop_index: #l });
                    }
                }
            });
            quote! {
                if !(#cond <= SINGULAR_THRESHOLD) {
                    return Err(LoopFailure::Singular { phi, loop_index: #l, condition: #cond });
                }
                #unassemblable
            }
        });
    let (n, width) = (
        Literal::usize_unsuffixed(code.jets.len()),
        Literal::usize_unsuffixed(width),
    );
    quote! {
        /// The solver's singular threshold: a loop whose condition estimate exceeds it is
        /// at (or too near) a toggle.
        pub const SINGULAR_THRESHOLD: f64 = #limit;

        /// Every output and its derivatives with respect to the drive position at `phi`
        /// (SI: rad or m), row by row in the order of `OUTPUTS`, after every loop's guard.
        #[allow(clippy::all, unused_variables, non_snake_case)]
        pub fn pose(phi: f64) -> Result<[[f64; #width]; #n], LoopFailure> {
            let [#(#bound),*]: [f64; #count] = { #body };
            #(#guards)*
            Ok([#(#rows),*])
        }
    }
}

/// The generated Rust module for `scene` (formatted source).
///
/// # Errors
/// See [`SceneCode::of`]; [`Error::Codegen`] if the emitted code does not parse (a bug).
pub fn module(scene: &Scene, shown_path: &str) -> Result<String> {
    let code = SceneCode::of(scene)?;
    if !code.position.newton.is_empty() {
        return mixed_module(scene, shown_path, &code);
    }
    let outputs = &code.names;
    let loops: Vec<String> = code
        .position
        .guards
        .iter()
        .map(|g| g.joints.join(", "))
        .collect();
    let [n, l, order] = [outputs.len(), loops.len(), code.order].map(Literal::usize_unsuffixed);
    let pose = pose_function(&code);
    let tokens = quote! {
        /// The outputs, in the order of the rows `pose` returns.
        pub const OUTPUTS: [&str; #n] = [#(#outputs),*];
        /// The highest derivative with respect to the drive position in each row.
        pub const ORDER: usize = #order;
        /// The loops (their joints), in solving order.
        pub const LOOPS: [&str; #l] = [#(#loops),*];

        /// Why `pose` has no answer at a drive position: the loop `LOOPS[loop_index]`.
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum LoopFailure {
            /// The loop cannot assemble at `phi`.
            Unassemblable {
                /// The drive position (SI).
                phi: f64,
                /// The loop, in `LOOPS`.
                loop_index: usize,
            },
            /// The loop is at (or too near) a toggle at `phi`: its condition estimate.
            Singular {
                /// The drive position (SI).
                phi: f64,
                /// The loop, in `LOOPS`.
                loop_index: usize,
                /// The condition estimate (above `SINGULAR_THRESHOLD`).
                condition: f64,
            },
        }

        #pose
    };
    let source = format_rust(tokens).map_err(|source| Error::Codegen {
        origin: scene.file.clone(),
        source,
    })?;
    let ops = code.position.graph.operation_count(&code.roots());
    Ok(format!(
        "// Generated by `mechdiff codegen {}`: the scene's position solution\n\
         // (every loop in closed form, traced at the sketch) and derivatives 1 to {order}.\n\
         // operations: {ops}\n{source}",
        crate::escape::rust_comment(shown_path),
        order = code.order
    ))
}

/// The generated module of a mixed plan (some loop solved by Newton): a `Tracker` that
/// walks the drive as the solver does (see `mixed`).
fn mixed_module(scene: &Scene, shown_path: &str, code: &SceneCode) -> Result<String> {
    let outputs = &code.names;
    let mut loops: Vec<(usize, String)> = (code.position.guards.iter())
        .map(|g| (g.loop_index, g.joints.join(", ")))
        .chain((code.position.newton.iter()).map(|b| (b.loop_index, b.joints.join(", "))))
        .collect();
    loops.sort();
    let paths: Vec<String> = (0..loops.len())
        .map(|l| {
            let newton = code.position.newton.iter().any(|b| b.loop_index == l);
            if newton { "Newton" } else { "closed form" }.to_owned()
        })
        .collect();
    let loops: Vec<String> = loops.into_iter().map(|(_, joints)| joints).collect();
    let [n, l, order] = [outputs.len(), loops.len(), code.order].map(Literal::usize_unsuffixed);
    let tracker = mixed::tracker(code);
    let tokens = quote! {
        /// The outputs, in the order of the rows `Tracker::pose` returns.
        pub const OUTPUTS: [&str; #n] = [#(#outputs),*];
        /// The highest derivative with respect to the drive position in each row.
        pub const ORDER: usize = #order;
        /// The loops (their joints), in solving order.
        pub const LOOPS: [&str; #l] = [#(#loops),*];
        /// How each loop of `LOOPS` is solved: its closed form, or Newton's method.
        pub const PATHS: [&str; #l] = [#(#paths),*];

        /// Why `Tracker::pose` has no answer at a drive position (the solver's errors).
        #[derive(Debug, Clone, Copy, PartialEq)]
        pub enum LoopFailure {
            /// The loop `LOOPS[loop_index]` cannot assemble at `phi` (or on the way there).
            Unassemblable {
                /// The drive position asked for (SI).
                phi: f64,
                /// The loop, in `LOOPS`.
                loop_index: usize,
            },
            /// The loop `LOOPS[loop_index]` is at (or too near) a toggle at `phi`.
            Singular {
                /// The drive position (SI).
                phi: f64,
                /// The loop, in `LOOPS`.
                loop_index: usize,
                /// The condition estimate (above `SINGULAR_THRESHOLD`).
                condition: f64,
            },
            /// Newton's method would switch the loop `LOOPS[loop_index]` to its other
            /// assembly branch between `from` and `to`, and halving the step did not help.
            BranchFlip {
                /// The last position reached (SI).
                from: f64,
                /// The end of the step (SI).
                to: f64,
                /// The loop, in `LOOPS`.
                loop_index: usize,
            },
            /// The move from `from` to `to` needs more than `MAX_SUBSTEPS` sub-steps.
            MoveTooLong {
                /// Where the move started (SI).
                from: f64,
                /// The drive position asked for (SI).
                to: f64,
            },
            /// The drive position is not a finite number.
            NonFinite {
                /// The drive position.
                phi: f64,
            },
        }

        #tracker
    };
    let source = format_rust(tokens).map_err(|source| Error::Codegen {
        origin: scene.file.clone(),
        source,
    })?;
    let mut roots = code.roots();
    for b in &code.position.newton {
        roots.extend(&b.residual);
        roots.extend(&b.jacobian);
        roots.extend(b.derivatives.iter().flatten());
    }
    let ops = code.position.graph.operation_count(&roots);
    Ok(format!(
        "// Generated by `mechdiff codegen {}`: the scene's position solution\n\
         // (loops in closed form traced at the sketch, the others solved by Newton's method\n\
         // as the solver solves them) and derivatives 1 to {order}.\n\
         // operations: {ops}\n{source}",
        crate::escape::rust_comment(shown_path),
        order = code.order
    ))
}

/// The compile-time back end: writes the module generated for the scene file `scene` to
/// `out` (whole or not at all), for a build script; the module is then included where it
/// is used. With `scenes/whitworth.toml` in the crate:
///
/// ```no_run
/// // build.rs
/// let out = std::path::Path::new(&std::env::var("OUT_DIR").unwrap()).join("whitworth.rs");
/// mechdiff::codegen::scene::write_module("scenes/whitworth.toml", &out).unwrap();
/// println!("cargo::rerun-if-changed=scenes/whitworth.toml");
/// // src/lib.rs:
/// // mod whitworth { include!(concat!(env!("OUT_DIR"), "/whitworth.rs")); }
/// // let [[psi, psi_1, psi_2], _] = whitworth::pose(1.0)?;
/// ```
///
/// # Errors
/// The scene's errors (see [`module`]); [`Error::Write`] if `out` cannot be written.
pub fn write_module(scene: impl AsRef<Path>, out: impl AsRef<Path>) -> Result<()> {
    let path = scene.as_ref();
    let text = module(&load(path)?, &path.display().to_string())?;
    crate::files::write_atomically(out.as_ref(), |w| w.write_all(text.as_bytes()))
}

/// Reads the scene file at `path` for code generation: a linkage scene (a cam scene is
/// or rotor scene is refused with a clear error).
///
/// # Errors
/// The scene reader's errors; [`Error::Codegen`] for a cam or rotor scene.
pub fn load(path: &Path) -> Result<Scene> {
    let text = crate::files::read_scene(path)?;
    let file = path.display().to_string();
    if matches!(
        crate::scene::kind(&text),
        crate::scene::Kind::Cam | crate::scene::Kind::Rotor
    ) {
        return Err(Error::Codegen {
            origin: file,
            source: mechdiff_core::Error::Untraceable {
                operation: "a cam or rotor scene (code generation covers linkage scenes)"
                    .to_owned(),
            },
        });
    }
    crate::scene::parse(&file, &text)
}
