//! Accuracy cases written as formulas of the drive: the hard cases of `scenes/hard/`.
//!
//! A formula scene is a small TOML file:
//!
//! ```toml
//! title = "Whitworth ψ with λ = 0.999999: near the frame, 1 − λ cos φ cancels"
//!
//! [parameters]            # name = number; each is rounded to f64 once, as the methods see it
//! lambda = 0.999999
//!
//! [outputs]               # name = formula of `phi` and the parameters (infix, see `mechdiff codegen`)
//! psi = "atan2(lambda*sin(phi), 1 - lambda*cos(phi))"
//!
//! [sweep]                 # from, to, step in `unit` ("deg", the default, or "rad")
//! from = 0
//! to = 350
//! step = 10
//! at = ["acos(lambda)"]   # extra drive positions (rad), formulas of the parameters
//! ```
//!
//! An optional top-level `error = "relative"` measures errors relative to each reference
//! value instead of scaled by the output's largest value over the sweep.
//!
//! Every output is differentiated to order 3 by the symbolic engine. The methods compared
//! are the engine's own evaluations of the same graph — the derivative formulas in `f64`
//! ("symbolic (evaluator)") and the formula in `Dual1`, `Dual2`, `HyperDual`, `Dual3`
//! (num-dual through the evaluator) — and finite differences of the formula in `f64`. The
//! reference is the derivative formulas at 256 bits; the condition numbers follow from their
//! gradients (see [`super::reference`]).
//!
//! At a position where a formula is 0/0 with a limit (sin φ/φ at 0), or where the chain rule
//! divides by zero (`cbrt(φ³)`, `φ^3.5` at 0: num-dual's `powf` is `exp(v·ln u)`), the
//! limit is taken by truncated Taylor series ([`Graph::limit_jets`]): the reference in
//! double-double, every method in `f64`; the case's title says "removable singularity at
//! φ = … rad: limit taken", or "one-sided limit at φ = … rad (real only for φ ≥ …)" where the
//! formula is real on one side only (`φ^3.5`). Where the series has no answer either
//! (`sqrt(φ²)` = |φ| at 0, `φ^2.5`'s ‴ at 0, `φ^3.5` at φ < 0), the case is refused with the
//! output, the position and the reason; a method that fails there is reported failing.

use std::collections::BTreeMap;
use std::sync::Arc;

use mechdiff_core::Scalar;
use mechdiff_core::error::Error as CoreError;
use mechdiff_core::num_dual::{Dual2_64, Dual3_64, Dual64, HyperDual64};
use mechdiff_core::symbolic::constants::is_named_constant;
use mechdiff_core::symbolic::taylor::{Limits, Side};
use mechdiff_core::symbolic::{Graph, Id};
use serde::Deserialize;

use super::reference::{Formulas, Reference};
use super::{Case, MAX_ORDER, Method, Values};
use crate::Error;
use crate::error::Location;

/// A formula scene as written in the file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FormulaScene {
    /// What the case shows.
    pub title: String,
    /// Parameter values.
    #[serde(default)]
    pub parameters: BTreeMap<String, f64>,
    /// Output formulas of `phi` and the parameters.
    pub outputs: BTreeMap<String, String>,
    /// The drive positions.
    pub sweep: Sweep,
    /// `"scaled"` (the default: |error| / max over the sweep of |reference|) or
    /// `"relative"` (|error| / |reference| at each position).
    #[serde(default)]
    pub error: Option<String>,
}

/// The drive positions of a formula scene.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sweep {
    /// First position (in `unit`).
    pub from: f64,
    /// Last position (in `unit`), included.
    pub to: f64,
    /// Step (in `unit`), positive.
    pub step: f64,
    /// `"deg"` (the default) or `"rad"`.
    #[serde(default)]
    pub unit: Option<String>,
    /// Extra positions (rad), formulas of the parameters.
    #[serde(default)]
    pub at: Vec<String>,
}

/// Whether a TOML text is a formula scene (it has `[outputs]` as a table of formulas)
/// rather than a mechanism scene.
pub fn is_formula_scene(text: &str) -> bool {
    crate::scene::kind(text) == crate::scene::Kind::Formula
}

fn syntax(file: &str, message: String) -> Error {
    Error::Syntax {
        location: Location {
            file: Arc::from(file),
            line: 1,
            column: 1,
        },
        message,
    }
}

/// Parses a formula scene; `file` names it in errors.
///
/// # Errors
/// [`Error::Syntax`] for invalid TOML, an unknown key, a formula that does not parse or
/// names an unknown symbol, or a sweep that is empty or not finite.
pub fn parse(text: &str, file: &str) -> Result<FormulaScene, Error> {
    let scene: FormulaScene = toml::from_str(text).map_err(|e| {
        let (line, column) = e
            .span()
            .map(|span| {
                let before = &text[..span.start.min(text.len())];
                let line = before.matches('\n').count() + 1;
                let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
                (line, column)
            })
            .unwrap_or((1, 1));
        Error::Syntax {
            location: Location {
                file: Arc::from(file),
                line,
                column,
            },
            message: e.message().to_owned(),
        }
    })?;
    let s = &scene.sweep;
    let unit_ok = matches!(s.unit.as_deref(), None | Some("deg" | "rad"));
    if !unit_ok {
        return Err(syntax(
            file,
            "[sweep] unit: expected \"deg\" or \"rad\"".into(),
        ));
    }
    if !(s.from.is_finite() && s.to.is_finite() && s.step.is_finite() && s.step > 0.0)
        || s.to < s.from
        || (s.to - s.from) / s.step > 100_000.0
    {
        return Err(syntax(
            file,
            "[sweep]: expected finite from ≤ to and a positive step giving at most 100000 \
             positions"
                .into(),
        ));
    }
    if !matches!(scene.error.as_deref(), None | Some("scaled" | "relative")) {
        return Err(syntax(
            file,
            "error: expected \"scaled\" or \"relative\"".into(),
        ));
    }
    if scene.outputs.is_empty() {
        return Err(syntax(
            file,
            "[outputs]: at least one formula is needed".into(),
        ));
    }
    Ok(scene)
}

/// The accuracy case of a formula scene.
///
/// # Errors
/// [`Error::Syntax`] if a formula does not parse or uses a symbol that is neither `phi` nor
/// a parameter; [`Error::Reference`] if the reference does not evaluate.
pub fn case(scene: &FormulaScene, file: &str) -> Result<Case<'static>, Error> {
    let (evaluator, positions) = prepare(scene, file)?;
    let names: Vec<&str> = evaluator.names.iter().map(String::as_str).collect();
    let (formulas, values) = (&evaluator.formulas, &evaluator.values);
    let mut reference = Vec::new();
    let mut condition = Vec::new();
    let mut flags = String::new();
    let outputs: Vec<&String> = scene.outputs.keys().collect();
    for &phi in &positions {
        let (mut r, mut c) = formulas.reference(phi, values)?;
        let mut series_error = None;
        if r.iter().flatten().any(|x| !x.is_finite()) || evaluator.chain_rule_fails(phi) {
            // A 0/0 at this position, or a power at a zero of its base: the limit, in
            // double-double Taylor series (about 32 digits), if it exists. The condition
            // numbers' formulas are 0/0 there too: where not finite they are taken as 0 (the
            // bound is then 16 ε of the scale).
            match limit_jets::<Reference>(formulas, &names, values, phi) {
                Ok(limits) if limits.removed || limits.side.is_some() => {
                    for (o, jet) in limits.jets.iter().enumerate() {
                        r[o] = *jet;
                    }
                    for x in c.iter_mut().flatten().filter(|x| !x.is_finite()) {
                        *x = 0.0;
                    }
                    flags += &format!("; {}", limit_note(phi, &limits));
                }
                Ok(_) => {}
                // A reason found (|φ| at 0, not real): named; else a pole or a deeper 0/0.
                Err(e @ CoreError::NotDifferentiable { .. }) => series_error = Some(e),
                Err(_) => {}
            }
        }
        if let Some((o, k)) = (0..r.len())
            .flat_map(|o| (0..=MAX_ORDER).map(move |k| (o, k)))
            .find(|&(o, k)| !r[o][k].is_finite())
        {
            return Err(Error::Reference {
                what: file.to_owned(),
                reason: format!(
                    "output `{}`, derivative order {k}, is not finite at phi = {phi} even at \
                     256 bits, and has no limit there that a Taylor series to order 7 finds \
                     ({}); write the value there with `if`, e.g. \
                     \"if(phi == 0, 1, sin(phi)/phi)\" (scenes/hard/removable_sinc.toml), or \
                     leave the point out of the sweep",
                    outputs[o],
                    series_error.map_or_else(
                        || "a true singularity, or a 0/0 of higher order".to_owned(),
                        |e| e.to_string()
                    ),
                ),
            });
        }
        reference.push(r);
        condition.push(c);
    }
    let evaluator = Arc::new(evaluator);
    let methods = evaluator.methods();
    let f = evaluator.clone();
    Ok(Case {
        title: format!("{} (reference: 256-bit symbolic{flags})", scene.title),
        outputs: scene.outputs.keys().cloned().collect(),
        positions,
        reference,
        condition: Some(condition),
        relative: scene.error.as_deref() == Some("relative"),
        jumps: Vec::new(),
        notes: Vec::new(),
        methods,
        positions_f64: Box::new(move |phi, out| {
            let v = f.jets(phi, 0, |&x| [x, f64::NAN, f64::NAN, f64::NAN])?;
            for (o, jet) in out.iter_mut().zip(v) {
                *o = jet[0];
            }
            Ok(())
        }),
    })
}

/// What a limit taken at the drive `phi` is: "removable singularity at φ = … rad: limit
/// taken", or "one-sided limit at φ = … rad (real only for φ ≥ …)".
fn limit_note<T>(phi: f64, limits: &Limits<T>) -> String {
    match limits.side {
        None => format!("removable singularity at φ = {phi} rad: limit taken"),
        Some(side) => format!(
            "one-sided limit at φ = {phi} rad (real only for φ {} {phi})",
            if side == Side::Above { "≥" } else { "≤" }
        ),
    }
}

/// The formulas of `scene` ready to evaluate, and its drive positions (rad, sorted).
/// Checks what [`table`] needs before it evaluates anything: every formula compiles with
/// the scene's parameters and the drive positions are finite (`mechdiff check`).
///
/// # Errors
/// As [`table`] gives them before evaluating.
pub fn check(scene: &FormulaScene, file: &str) -> Result<usize, Error> {
    prepare(scene, file).map(|(_, positions)| positions.len())
}

fn prepare(scene: &FormulaScene, file: &str) -> Result<(Evaluator, Vec<f64>), Error> {
    let mut graph = Graph::new();
    let names: Vec<&str> = scene.parameters.keys().map(String::as_str).collect();
    let values: Vec<f64> = scene.parameters.values().copied().collect();
    let parse = |graph: &mut Graph, what: &str, text: &str| -> Result<Id, Error> {
        let id = graph
            .parse_infix_piecewise(text)
            .map_err(|e| syntax(file, format!("{what} = \"{text}\": {e}")))?;
        if let Some(unknown) = graph
            .symbols(&[id])
            .into_iter()
            .find(|s| *s != "phi" && !names.contains(s) && !is_named_constant(s))
        {
            return Err(syntax(
                file,
                format!(
                    "{what} = \"{text}\": unknown symbol `{unknown}`; the drive is `phi` and \
                     the parameters are: {}",
                    names.join(", ")
                ),
            ));
        }
        Ok(id)
    };
    let mut roots = Vec::new();
    for (name, text) in &scene.outputs {
        roots.push(parse(&mut graph, &format!("[outputs] {name}"), text)?);
    }
    let mut positions = sweep_positions(&scene.sweep);
    for text in &scene.sweep.at {
        let id = parse(&mut graph, "[sweep] at", text)?;
        let bindings: Vec<(&str, f64)> =
            names.iter().copied().zip(values.iter().copied()).collect();
        let phi = graph
            .evaluate_f64(&[id], &bindings)
            .map_err(|e| syntax(file, format!("[sweep] at = \"{text}\": {e}")))?[0];
        if !phi.is_finite() {
            return Err(syntax(file, format!("[sweep] at = \"{text}\" is {phi}")));
        }
        positions.push(phi);
    }
    positions.sort_by(f64::total_cmp);
    positions.dedup();
    let evaluator = Evaluator {
        formulas: Formulas::new(graph, &roots, "phi", &names),
        names: names.iter().map(|s| s.to_string()).collect(),
        values,
    };
    Ok((evaluator, positions))
}

/// The positions from, from + step, …, to (in radians).
fn sweep_positions(s: &Sweep) -> Vec<f64> {
    let to_rad = |x: f64| {
        if s.unit.as_deref() == Some("rad") {
            x
        } else {
            x.to_radians()
        }
    };
    let n = ((s.to - s.from) / s.step + 1e-9).floor() as usize;
    (0..=n)
        .map(|k| to_rad(s.from + k as f64 * s.step))
        .collect()
}

/// The formulas and parameter values, evaluated by each method.
struct Evaluator {
    formulas: Formulas,
    names: Vec<String>,
    values: Vec<f64>,
}

impl Evaluator {
    /// The outputs in `Dual3` at the drive `phi`.
    fn dual3(&self, phi: f64) -> Result<Vec<Dual3_64>, CoreError> {
        let roots: Vec<Id> = self.formulas.jets().iter().map(|j| j[0]).collect();
        let mut bindings: Vec<(&str, Dual3_64)> = vec![("phi", Dual3_64::from(phi).derivative())];
        bindings.extend(
            self.names
                .iter()
                .map(String::as_str)
                .zip(self.values.iter().map(|&v| Dual3_64::from(v))),
        );
        self.formulas.graph().evaluate_dual(&roots, &bindings)
    }

    /// Whether the chain rule in `Dual3` fails at the drive `phi` (a 0/0, a power or root
    /// at a zero of its base): the Taylor series decides there.
    fn chain_rule_fails(&self, phi: f64) -> bool {
        matches!(self.dual3(phi), Err(e) if chain_rule_failure(&e))
    }

    /// `[f, f′, f″, f‴]` per output at the drive `seed` (a num-dual seed, or `f64`),
    /// through `to_values`; where the chain rule fails (0/0, a power or root at a zero of its
    /// base), the limit from truncated Taylor series instead, to order `order` (NaN above),
    /// or the series' error.
    fn jets<D: Scalar>(
        &self,
        seed: D,
        order: usize,
        to_values: impl Fn(&D) -> Values,
    ) -> Result<Vec<Values>, Error> {
        let roots: Vec<Id> = self.formulas.jets().iter().map(|j| j[0]).collect();
        let names: Vec<&str> = self.names.iter().map(String::as_str).collect();
        let mut bindings: Vec<(&str, D)> = vec![("phi", seed)];
        bindings.extend(
            names
                .iter()
                .copied()
                .zip(self.values.iter().map(|&v| D::from(v))),
        );
        match self.formulas.graph().evaluate_dual(&roots, &bindings) {
            Ok(v) => Ok(v.iter().map(to_values).collect()),
            Err(e) if chain_rule_failure(&e) => {
                let jets = limit_jets::<f64>(&self.formulas, &names, &self.values, seed.re())
                    .map_err(formulas_error)?
                    .jets;
                Ok(jets
                    .into_iter()
                    .map(|j| std::array::from_fn(|k| if k <= order { j[k] } else { f64::NAN }))
                    .collect())
            }
            Err(e) => Err(formulas_error(e)),
        }
    }

    fn methods(self: &Arc<Self>) -> Vec<Method<'static>> {
        let symbolic = self.clone();
        let ids: Vec<Id> = self.formulas.jets().iter().flatten().copied().collect();
        let d1 = self.clone();
        let d2 = self.clone();
        let hd = self.clone();
        let d3 = self.clone();
        vec![
            Method::exact("symbolic (evaluator)", MAX_ORDER, move |phi, out| {
                let names: Vec<&str> = symbolic.names.iter().map(String::as_str).collect();
                let mut bindings: Vec<(&str, f64)> = vec![("phi", phi)];
                bindings.extend(names.iter().copied().zip(symbolic.values.iter().copied()));
                match symbolic.formulas.graph().evaluate_f64(&ids, &bindings) {
                    Ok(v) => {
                        for (o, jet) in out.iter_mut().zip(v.chunks(MAX_ORDER + 1)) {
                            o.copy_from_slice(jet);
                        }
                    }
                    Err(CoreError::ZeroOverZero { .. }) => {
                        let limits =
                            limit_jets::<f64>(&symbolic.formulas, &names, &symbolic.values, phi)
                                .map_err(formulas_error)?;
                        write(out, limits.jets.into_iter());
                    }
                    Err(e) => return Err(formulas_error(e)),
                }
                Ok(())
            }),
            Method::exact("Dual1 (evaluator)", 1, move |phi, out| {
                let v = d1.jets(Dual64::from(phi).derivative(), 1, |x| {
                    [x.re, x.eps, f64::NAN, f64::NAN]
                })?;
                write(out, v.into_iter());
                Ok(())
            }),
            Method::exact("Dual2 (evaluator)", 2, move |phi, out| {
                let v = d2.jets(Dual2_64::from(phi).derivative(), 2, |x| {
                    [x.re, x.v1, x.v2, f64::NAN]
                })?;
                write(out, v.into_iter());
                Ok(())
            }),
            Method::exact("HyperDual (evaluator)", 2, move |phi, out| {
                let seed = HyperDual64::from(phi).derivative1().derivative2();
                let v = hd.jets(seed, 2, |x| [x.re, x.eps1, x.eps1eps2, f64::NAN])?;
                write(out, v.into_iter());
                Ok(())
            }),
            Method::exact("Dual3 (evaluator)", 3, move |phi, out| {
                let v = d3.jets(Dual3_64::from(phi).derivative(), 3, |x| {
                    [x.re, x.v1, x.v2, x.v3]
                })?;
                write(out, v.into_iter());
                Ok(())
            }),
        ]
    }
}

/// Whether `e` is a failure of the chain rule that a Taylor series may resolve (a 0/0, a
/// power or root at a zero of its base).
fn chain_rule_failure(e: &CoreError) -> bool {
    matches!(
        e,
        CoreError::ZeroOverZero { .. }
            | CoreError::PowerOfZero { .. }
            | CoreError::InfiniteDerivative { .. }
    )
}

/// A formula scene's outputs and their derivatives to order 3 at its drive positions, as
/// `mechdiff run` prints them.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The outputs' names, in the file's (alphabetical) order.
    pub outputs: Vec<String>,
    /// The drive positions (rad).
    pub positions: Vec<f64>,
    /// `rows[position][output]`: `[f, f′, f″, f‴]`.
    pub rows: Vec<Vec<Values>>,
    /// One note per position where a limit was taken ("removable singularity at φ = 0 rad:
    /// limit taken", "one-sided limit at φ = 0 rad (real only for φ ≥ 0)").
    pub notes: Vec<String>,
}

/// The outputs of a formula scene and their derivatives to order 3 (`Dual3` through the
/// evaluator) at every drive position; where the chain rule fails (0/0, a power or root at a
/// zero of its base), the limit by truncated Taylor series ([`Graph::limit_jets`]), with a
/// note naming the position.
///
/// # Errors
/// [`Error::Syntax`] as [`case`]; [`Error::FormulaAt`] where the formulas have no value or
/// derivatives, not even as a limit (a true pole, `sqrt(phi^2)` at 0, `phi^3.5` below 0),
/// naming the position and the reason.
pub fn table(scene: &FormulaScene, file: &str) -> Result<Table, Error> {
    let (evaluator, positions) = prepare(scene, file)?;
    let names: Vec<&str> = evaluator.names.iter().map(String::as_str).collect();
    let at = |phi: f64| {
        move |source: CoreError| Error::FormulaAt {
            file: file.to_owned(),
            phi,
            source,
        }
    };
    let mut rows = Vec::with_capacity(positions.len());
    let mut notes = Vec::new();
    for &phi in &positions {
        let row: Vec<Values> = match evaluator.dual3(phi) {
            Ok(v) => v.iter().map(|x| [x.re, x.v1, x.v2, x.v3]).collect(),
            Err(e) if chain_rule_failure(&e) => {
                let limits = limit_jets::<f64>(&evaluator.formulas, &names, &evaluator.values, phi)
                    .map_err(at(phi))?;
                if limits.removed || limits.side.is_some() {
                    notes.push(limit_note(phi, &limits));
                }
                limits.jets
            }
            Err(e) => return Err(at(phi)(e)),
        };
        if let Some((o, k)) = (0..row.len())
            .flat_map(|o| (0..=MAX_ORDER).map(move |k| (o, k)))
            .find(|&(o, k)| !row[o][k].is_finite())
        {
            return Err(Error::NotFinite {
                file: file.to_owned(),
                quantity: format!("`{}`, derivative order {k},", scene_output(scene, o)),
                value: row[o][k].to_string(),
                position: format!("φ = {phi} rad"),
            });
        }
        rows.push(row);
    }
    Ok(Table {
        outputs: scene.outputs.keys().cloned().collect(),
        positions,
        rows,
        notes,
    })
}

fn scene_output(scene: &FormulaScene, o: usize) -> &str {
    scene.outputs.keys().nth(o).map_or("?", String::as_str)
}

fn formulas_error(e: CoreError) -> Error {
    Error::Reference {
        what: "the formulas".into(),
        reason: e.to_string(),
    }
}

/// The limit jets `[f, f′, f″, f‴]` in `T` of every output at the drive `phi`, through a
/// removable singularity there (see [`Graph::limit_jets`]), with whether a 0/0 was resolved
/// and whether the limit is one-sided.
fn limit_jets<T: Scalar>(
    formulas: &Formulas,
    names: &[&str],
    values: &[f64],
    phi: f64,
) -> Result<Limits<T>, CoreError> {
    let roots: Vec<Id> = formulas.jets().iter().map(|j| j[0]).collect();
    let mut bindings: Vec<(&str, T)> = vec![("phi", T::from(phi))];
    bindings.extend(
        names
            .iter()
            .copied()
            .zip(values.iter().map(|&v| T::from(v))),
    );
    formulas.graph().limit_jets(&roots, "phi", &bindings)
}

fn write(out: &mut [Values], values: impl Iterator<Item = Values>) {
    for (o, v) in out.iter_mut().zip(values) {
        *o = v;
    }
}
