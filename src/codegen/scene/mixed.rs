//! The generated module of a *mixed plan*: a scene with loops the closed forms do not match
//! ([`mechdiff_core::trace::NewtonBlock`]), solved by Newton's method inside the
//! generated code as the solver solves them.
//!
//! The module's `Tracker` keeps, between calls, the drive position reached and each Newton
//! loop's coordinates with their derivatives and its branch (the sign of det Φ_q). Its
//! `pose(phi)` walks there as the solver's Newton path does (`geometry::solver`), with the
//! solver's own step-halving walk (`geometry::halving`, its source emitted into the module):
//! sub-steps of at most `LONGEST_STEP`; at each, the Taylor predictor `q + h q′ + h²/2 q″`,
//! Newton until max |Φ| ≤ `RESIDUAL_TOLERANCE` (at most `MAX_ITERATIONS` iterations), the
//! condition of the loop's scaled Φ_q (above `SINGULAR_THRESHOLD`: `Singular`, at once), the
//! branch (a flip, or Newton failing, halves the step, at most `MAX_SUBDIVISIONS` times,
//! then `BranchFlip` or `Unassemblable`); then one polishing Newton step, Φ_q factorised
//! again at the polished pose, and q′, q″ (q‴) by implicit differentiation with that one
//! factorisation. The closed-form loops' formulas and guards, and the outputs, read the
//! Newton loops' coordinates and derivatives.

use mechdiff_core::geometry::halving;
use mechdiff_core::trace::{GuardKind, NewtonBlock, coordinate_symbol};
use proc_macro2::{Literal, TokenStream};
use quote::{format_ident, quote};

use super::{SceneCode, identifier};

/// `[a, b, …]`: identifiers as an array pattern or expression.
fn array(names: &[String]) -> TokenStream {
    let names = names.iter().map(|n| format_ident!("{n}"));
    quote! { [#(#names),*] }
}

/// The symbols of block `b`'s coordinates of derivative order `k`.
fn symbols(b: &NewtonBlock, k: usize) -> Vec<String> {
    b.columns.iter().map(|&c| coordinate_symbol(c, k)).collect()
}

/// The checks of the closed-form loops' guards `guards` (indices into the position's
/// guards), evaluated where every symbol they read is bound.
fn guard_checks(code: &SceneCode, guards: &[usize]) -> TokenStream {
    let checked: Vec<usize> = (guards.iter().copied())
        .filter(|&g| code.position.guards[g].kind != GuardKind::Always)
        .collect();
    if checked.is_empty() {
        return quote! {};
    }
    let mut roots = Vec::new();
    let mut names = Vec::new();
    for &g in &checked {
        let guard = &code.position.guards[g];
        roots.extend([guard.discriminant, guard.condition]);
        names.extend([format!("discriminant_{g}"), format!("condition_{g}")]);
    }
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let body = code.position.graph.emit_body(&roots, &refs);
    let bound = array(&names);
    let count = Literal::usize_unsuffixed(roots.len());
    let checks = checked.iter().map(|&g| {
        let guard = &code.position.guards[g];
        let l = Literal::usize_unsuffixed(guard.loop_index);
        let (disc, cond) = (
            format_ident!("discriminant_{g}"),
            format_ident!("condition_{g}"),
        );
        let unassemblable = (guard.kind == GuardKind::Root).then(|| {
            quote! {
                if #disc < 0.0 {
                    return Err(LoopFailure::Unassemblable { phi: requested, loop_index: #l });
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
    quote! {
        let #bound: [f64; #count] = { #body };
        #(#checks)*
    }
}

/// The Newton solve of block `b` in `step`: binds its coordinates' symbols and derivatives'
/// symbols, and `q_<l>`, `derivatives_<l>`, `branch_<l>` for the new state.
fn newton_stage(code: &SceneCode, b: &NewtonBlock) -> TokenStream {
    let graph = &code.position.graph;
    let k = b.columns.len();
    let kk = Literal::usize_unsuffixed(k);
    let l = Literal::usize_unsuffixed(b.loop_index);
    let field = format_ident!("newton_{}", b.loop_index);
    let (q, derivatives, branch, lu) = (
        format_ident!("q_{}", b.loop_index),
        format_ident!("derivatives_{}", b.loop_index),
        format_ident!("branch_{}", b.loop_index),
        format_ident!("lu_{}", b.loop_index),
    );
    let system = format_ident!("system_{}", b.loop_index);
    let coordinates = array(&symbols(b, 0));
    // Φ and Φ_q in the coordinates' symbols.
    let mut roots = b.residual.clone();
    roots.extend(&b.jacobian);
    let names: Vec<String> = (0..k)
        .map(|i| format!("residual_{i}"))
        .chain((0..k * k).map(|i| format!("jacobian_{i}")))
        .collect();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let body = graph.emit_body(&roots, &refs);
    let count = Literal::usize_unsuffixed(roots.len());
    let residual = (0..k).map(|i| format_ident!("residual_{i}"));
    let jacobian = (0..k).map(|r| {
        let row = (0..k).map(|c| format_ident!("jacobian_{}", r * k + c));
        quote! { [#(#row),*] }
    });
    let bound = array(&names);
    let scales = |s: &[f64]| {
        let s = s.iter().map(|&x| Literal::f64_unsuffixed(x));
        quote! { [#(#s),*] }
    };
    let (rows, columns) = (scales(&b.row_scales), scales(&b.column_scales));
    // q′, q″, …: Φ_q q⁽ᵏ⁾ = −R_k, R_k in the symbols of orders below k.
    let lifts = b.derivatives.iter().enumerate().map(|(j, rhs)| {
        let names: Vec<String> = (0..k).map(|i| format!("rhs_{i}")).collect();
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        let body = graph.emit_body(rhs, &refs);
        let order = array(&symbols(b, j + 1));
        let j = Literal::usize_unsuffixed(j);
        quote! {
            let rhs: [f64; #kk] = { #body };
            #derivatives[#j] = #lu.solve(rhs.map(|x| -x));
            let #order = #derivatives[#j];
        }
    });
    quote! {
        let #system = |q: &[f64; #kk]| -> ([f64; #kk], [[f64; #kk]; #kk]) {
            let #coordinates = *q;
            let #bound: [f64; #count] = { #body };
            ([#(#residual),*], [#(#jacobian),*])
        };
        // The solver's predictor, then Newton.
        let last = &self.#field;
        let mut #q = last.q;
        for i in 0..#kk {
            #q[i] += h * (last.derivatives[0][i] + 0.5 * h * last.derivatives[1][i]);
        }
        if !newton(&#system, &mut #q) {
            return Err(LoopFailure::Unassemblable { phi: requested, loop_index: #l });
        }
        let (residual, jacobian) = #system(&#q);
        let condition = condition(&jacobian, &#rows, &#columns);
        if !(condition <= SINGULAR_THRESHOLD) {
            return Err(LoopFailure::Singular { phi, loop_index: #l, condition });
        }
        let singular = LoopFailure::Singular { phi, loop_index: #l, condition: f64::INFINITY };
        let #lu = Lu::factor(jacobian).ok_or(singular)?;
        let #branch = #lu.determinant.signum();
        if last.branch != 0.0 && #branch != last.branch {
            return Err(LoopFailure::BranchFlip { from: self.phi, to: phi, loop_index: #l });
        }
        // Polish with the factorisation at the converged pose, factorise again there.
        let polish = #lu.solve(residual);
        for i in 0..#kk {
            #q[i] -= polish[i];
        }
        let #lu = Lu::factor(#system(&#q).1).ok_or(singular)?;
        let #coordinates = #q;
        let mut #derivatives = [[0.0; #kk]; ORDER];
        #(#lifts)*
    }
}

/// The `Tracker` of a mixed plan and its helpers (see the module documentation).
pub(super) fn tracker(code: &SceneCode) -> TokenStream {
    let position = &code.position;
    let graph = &position.graph;
    let blocks = &position.newton;
    let width = code.order + 1;
    // Guards before each Newton loop (in solving order), and after the last.
    let mut stages = Vec::new();
    let mut pending: Vec<usize> = (0..position.guards.len()).collect();
    for b in blocks {
        let (before, after): (Vec<usize>, Vec<usize>) = pending
            .iter()
            .partition(|&&g| position.guards[g].loop_index < b.loop_index);
        stages.push(guard_checks(code, &before));
        stages.push(newton_stage(code, b));
        pending = after;
    }
    stages.push(guard_checks(code, &pending));
    let fields = blocks.iter().map(|b| {
        let field = format_ident!("newton_{}", b.loop_index);
        let k = Literal::usize_unsuffixed(b.columns.len());
        quote! { #field: NewtonLoop<#k> }
    });
    let initial = blocks.iter().map(|b| {
        let field = format_ident!("newton_{}", b.loop_index);
        let sketch = b.sketch.iter().map(|&x| Literal::f64_unsuffixed(x));
        let k = Literal::usize_unsuffixed(b.columns.len());
        quote! {
            #field: NewtonLoop { q: [#(#sketch),*], derivatives: [[0.0; #k]; ORDER], branch: 0.0 }
        }
    });
    let commit = blocks.iter().map(|b| {
        let field = format_ident!("newton_{}", b.loop_index);
        let (q, derivatives, branch) = (
            format_ident!("q_{}", b.loop_index),
            format_ident!("derivatives_{}", b.loop_index),
            format_ident!("branch_{}", b.loop_index),
        );
        quote! {
            self.#field = NewtonLoop { q: #q, derivatives: #derivatives, branch: #branch };
        }
    });
    // The outputs from the state.
    let state = blocks.iter().map(|b| {
        let field = format_ident!("newton_{}", b.loop_index);
        let orders = (1..=code.order).map(|k| {
            let symbols = array(&symbols(b, k));
            let j = Literal::usize_unsuffixed(k - 1);
            quote! { let #symbols = self.#field.derivatives[#j]; }
        });
        let coordinates = array(&symbols(b, 0));
        quote! {
            let #coordinates = self.#field.q;
            #(#orders)*
        }
    });
    let mut names: Vec<String> = Vec::new();
    for name in &code.names {
        let base = identifier(name);
        names.push(base.clone());
        names.extend((1..=code.order).map(|k| format!("{base}_d{k}")));
    }
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let roots: Vec<_> = code.jets.iter().flatten().copied().collect();
    let body = graph.emit_body(&roots, &refs);
    let bound: Vec<_> = names.iter().map(|n| format_ident!("{n}")).collect();
    let rows = bound.chunks(width).map(|row| quote! { [#(#row),*] });
    let (n, width, count) = (
        Literal::usize_unsuffixed(code.jets.len()),
        Literal::usize_unsuffixed(width),
        Literal::usize_unsuffixed(roots.len()),
    );
    let f = Literal::f64_unsuffixed;
    let u = Literal::usize_unsuffixed;
    let (limit, tolerance, longest, sketch) = (
        f(position.limit),
        f(position.newton_tolerance),
        f(position.longest_step),
        f(position.sketch_drive),
    );
    let (iterations, subdivisions, substeps) = (
        u(position.max_iterations),
        u(position.max_subdivisions),
        u(position.max_substeps),
    );
    let walk: TokenStream =
        (halving::SOURCE.parse()).expect("the walk's source parses: mechdiff-core compiles it");
    quote! {
        /// The solver's singular threshold: a loop whose condition estimate exceeds it is
        /// at (or too near) a toggle.
        pub const SINGULAR_THRESHOLD: f64 = #limit;
        /// Newton converges when max |Φ| is at most this (m or rad): the solver's
        /// tolerance times the sketch's size.
        pub const RESIDUAL_TOLERANCE: f64 = #tolerance;
        /// Newton iterations per attempt (the solver's).
        pub const MAX_ITERATIONS: usize = #iterations;
        /// Halvings of a failing step before the failure is reported (the solver's).
        pub const MAX_SUBDIVISIONS: usize = #subdivisions;
        /// The longest step of the drive (SI), as the solver's.
        pub const LONGEST_STEP: f64 = #longest;
        /// The most sub-steps of one move (the solver's).
        pub const MAX_SUBSTEPS: usize = #substeps;
        /// The drive position of the sketch, where a `Tracker` starts (SI).
        #[allow(clippy::approx_constant)]
        pub const SKETCH_DRIVE: f64 = #sketch;

        /// The solver's step-halving walk (`mechdiff_core::geometry::halving`), as its
        /// source: the generated code depends on nothing.
        #[allow(dead_code, clippy::all)]
        mod step_halving {
            #walk
        }
        use step_halving::{Attempt, StepHalving, Stop};

        /// The walk's limits (the solver's).
        const HALVING: StepHalving = StepHalving {
            longest: LONGEST_STEP,
            max_subdivisions: MAX_SUBDIVISIONS,
            max_substeps: MAX_SUBSTEPS,
        };

        /// A Newton loop's state: its coordinates, their derivatives 1 to `ORDER`, and its
        /// branch (the sign of det Φ_q; 0 before the first pose).
        #[derive(Debug, Clone, Copy, PartialEq)]
        struct NewtonLoop<const K: usize> {
            q: [f64; K],
            derivatives: [[f64; K]; ORDER],
            branch: f64,
        }

        /// The position solution walking the drive: where it stands and every Newton
        /// loop's state (warm start and branch for the next call).
        #[derive(Debug, Clone, PartialEq)]
        pub struct Tracker {
            phi: f64,
            #(#fields,)*
        }

        #[allow(clippy::all, unused_variables, non_snake_case)]
        impl Tracker {
            /// The tracker at the sketch.
            pub fn new() -> Result<Self, LoopFailure> {
                let mut tracker = Tracker { phi: SKETCH_DRIVE, #(#initial,)* };
                tracker.step(SKETCH_DRIVE, SKETCH_DRIVE)?;
                Ok(tracker)
            }

            /// The drive position reached (SI).
            pub fn phi(&self) -> f64 {
                self.phi
            }

            /// Moves to `phi` as the solver does and returns every output and its
            /// derivatives with respect to the drive position there (SI: rad or m), row by
            /// row in the order of `OUTPUTS`. On failure the tracker stays at the last
            /// position it reached.
            pub fn pose(&mut self, phi: f64) -> Result<[[f64; #width]; #n], LoopFailure> {
                if !phi.is_finite() {
                    return Err(LoopFailure::NonFinite { phi });
                }
                let start = self.phi;
                if start != phi {
                    let walked = HALVING.walk(
                        self,
                        start,
                        phi,
                        |tracker, target, _| match tracker.step(target, phi) {
                            Ok(()) => Ok(Attempt::Accepted),
                            Err(failure @ LoopFailure::Singular { .. }) => Err(failure),
                            Err(failure) => Ok(Attempt::Failed(failure)),
                        },
                        |_, _, failure| Err(failure),
                    );
                    walked.map_err(|stop| match stop {
                        Stop::TooLong => LoopFailure::MoveTooLong { from: start, to: phi },
                        Stop::Failed(failure) => failure,
                    })?;
                }
                Ok(self.outputs())
            }

            /// One sub-step to `phi` (of a move to `requested`): every loop solved and
            /// checked, then the state updated.
            fn step(&mut self, phi: f64, requested: f64) -> Result<(), LoopFailure> {
                let h = phi - self.phi;
                #(#stages)*
                #(#commit)*
                self.phi = phi;
                Ok(())
            }

            /// The outputs at the position reached.
            fn outputs(&self) -> [[f64; #width]; #n] {
                let phi = self.phi;
                #(#state)*
                let [#(#bound),*]: [f64; #count] = { #body };
                [#(#rows),*]
            }
        }

        /// Newton on `system` (Φ and Φ_q) from `q`, until max |Φ| ≤ `RESIDUAL_TOLERANCE`:
        /// `false` if it does not converge in `MAX_ITERATIONS` (or Φ_q is singular).
        #[allow(clippy::all)]
        fn newton<const K: usize>(
            system: &impl Fn(&[f64; K]) -> ([f64; K], [[f64; K]; K]),
            q: &mut [f64; K],
        ) -> bool {
            for iteration in 0..=MAX_ITERATIONS {
                let (residual, jacobian) = system(q);
                let norm = residual.iter().fold(0.0f64, |m, &v| {
                    if v.abs() > m || v.is_nan() { v.abs() } else { m }
                });
                if norm <= RESIDUAL_TOLERANCE {
                    return true;
                }
                if !norm.is_finite() || iteration == MAX_ITERATIONS {
                    return false;
                }
                let Some(lu) = Lu::factor(jacobian) else {
                    return false;
                };
                let step = lu.solve(residual);
                for i in 0..K {
                    q[i] -= step[i];
                }
            }
            false
        }

        /// A square matrix factorised by Gaussian elimination with partial pivoting.
        #[derive(Debug, Clone, Copy)]
        struct Lu<const K: usize> {
            a: [[f64; K]; K],
            pivots: [usize; K],
            determinant: f64,
        }

        #[allow(clippy::all)]
        impl<const K: usize> Lu<K> {
            /// `None` if a pivot is zero or not finite.
            fn factor(mut a: [[f64; K]; K]) -> Option<Self> {
                let (mut pivots, mut determinant) = ([0; K], 1.0);
                for k in 0..K {
                    let mut p = k;
                    for i in k + 1..K {
                        if a[i][k].abs() > a[p][k].abs() {
                            p = i;
                        }
                    }
                    if !(a[p][k] != 0.0 && a[p][k].is_finite()) {
                        return None;
                    }
                    if p != k {
                        a.swap(p, k);
                        determinant = -determinant;
                    }
                    pivots[k] = p;
                    determinant *= a[k][k];
                    for i in k + 1..K {
                        let m = a[i][k] / a[k][k];
                        a[i][k] = m;
                        for j in k + 1..K {
                            a[i][j] -= m * a[k][j];
                        }
                    }
                }
                Some(Lu { a, pivots, determinant })
            }

            /// The solution x of A x = b.
            fn solve(&self, mut b: [f64; K]) -> [f64; K] {
                for k in 0..K {
                    b.swap(k, self.pivots[k]);
                }
                for i in 0..K {
                    for j in 0..i {
                        b[i] -= self.a[i][j] * b[j];
                    }
                }
                for i in (0..K).rev() {
                    for j in i + 1..K {
                        b[i] -= self.a[i][j] * b[j];
                    }
                    b[i] /= self.a[i][i];
                }
                b
            }
        }

        /// The condition number of Φ_q scaled as the solver scales it (`rows`, `columns`:
        /// angular rows and angle columns by the sketch size), its columns then of unit
        /// length: the Hadamard bound k^(k/2) / |det| where it is below
        /// `SINGULAR_THRESHOLD`, else σ_max / σ_min (one-sided Jacobi).
        #[allow(clippy::all)]
        fn condition<const K: usize>(
            jacobian: &[[f64; K]; K],
            rows: &[f64; K],
            columns: &[f64; K],
        ) -> f64 {
            // Column by column.
            let mut b = [[0.0; K]; K];
            for c in 0..K {
                for r in 0..K {
                    b[c][r] = jacobian[r][c] * rows[r] * columns[c];
                }
                let norm = b[c].iter().map(|x| x * x).sum::<f64>().sqrt();
                if norm > 0.0 {
                    for x in &mut b[c] {
                        *x /= norm;
                    }
                }
            }
            let determinant = Lu::factor(b).map_or(0.0, |lu| lu.determinant);
            let bound = (K as f64).powf(0.5 * K as f64) / determinant.abs();
            if bound <= SINGULAR_THRESHOLD {
                return bound;
            }
            let dot = |x: &[f64; K], y: &[f64; K]| (0..K).map(|i| x[i] * y[i]).sum::<f64>();
            for _sweep in 0..60 {
                let mut rotated = false;
                for p in 0..K {
                    for q in p + 1..K {
                        let (alpha, beta, gamma) = (dot(&b[p], &b[p]), dot(&b[q], &b[q]), dot(&b[p], &b[q]));
                        if gamma.abs() <= f64::EPSILON * (alpha * beta).sqrt() {
                            continue;
                        }
                        rotated = true;
                        let zeta = (beta - alpha) / (2.0 * gamma);
                        let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                        let c = 1.0 / (1.0 + t * t).sqrt();
                        let s = c * t;
                        for i in 0..K {
                            let (x, y) = (b[p][i], b[q][i]);
                            b[p][i] = c * x - s * y;
                            b[q][i] = s * x + c * y;
                        }
                    }
                }
                if !rotated {
                    break;
                }
            }
            let sigma = b.map(|column| dot(&column, &column).sqrt());
            let (max, min) = sigma.iter().fold((0.0f64, f64::INFINITY), |(a, z), &s| (a.max(s), z.min(s)));
            let condition = max / min;
            if condition.is_nan() { f64::INFINITY } else { condition }
        }
    }
}
