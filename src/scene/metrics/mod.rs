//! What a designer reads first about a scene's linkage, in the scene's units: the metrics
//! of its four-bar and slider-crank loops ([`mechdiff_core::metrics`]: Grashof class with
//! its inequality, the input's range, the transmission angle's extremes, the loop output's
//! quick return) and the quick return of every output whose dead positions are asked for.
//! `mechdiff check` and `mechdiff run` print [`SceneMetrics::lines`]; `--json` writes
//! [`SceneMetrics::json`].

use mechdiff_core::geometry::Kinematics;
use mechdiff_core::metrics::{
    FourBarLoop, InputEnd, InputPosition, InputRange, LinkageMetrics, MetricsError, QuickReturn,
    SliderCrankLoop, Stroke, TransmissionAt, TransmissionExtremes,
};
use serde_json::{Value, json};
use std::f64::consts::TAU;

use crate::error::Result;

use super::evaluate::{Resolved, evaluate};
use super::model::{DriveKind, JointKind, OutputKind, Scene};
use super::setup::{RunOptions, Setup};
use super::units::{Dimension, Units};

mod json;

/// The metrics of a scene: of its recognised loops, and of its outputs with dead positions.
#[derive(Debug, Clone)]
pub struct SceneMetrics {
    /// The loops' metrics, or why they could not be computed.
    pub linkage: std::result::Result<LinkageMetrics, MetricsError>,
    /// Per angle or slider output with `dead_positions = true`: its quick return over one
    /// turn of the crank, or why it has none.
    pub outputs: Vec<(
        String,
        Dimension,
        std::result::Result<QuickReturn, MetricsError>,
    )>,
}

impl SceneMetrics {
    /// The metrics of `scene`, or `None` when it has none to give: a cam-driven scene, or
    /// one with neither a four-bar or slider-crank loop nor an output whose dead positions
    /// are asked for.
    ///
    /// # Errors
    /// The model's errors ([`super::build::mechanism`]); a metric that cannot be computed is
    /// kept with why, not an error.
    pub fn of(scene: &Scene) -> Result<Option<SceneMetrics>> {
        if scene.drive.cam.is_some() {
            return Ok(None);
        }
        let setup = Setup::of(scene, &RunOptions::default())?;
        let (m, solver) = (&setup.mechanism, &setup.solver);
        let linkage = LinkageMetrics::of(m, solver);
        let mut outputs = Vec::new();
        for output in scene.outputs.iter().filter(|o| o.dead_positions) {
            if matches!(output.kind, OutputKind::Point(_)) {
                continue;
            }
            let resolved = Resolved::new(&setup, output)?;
            let value = |k: &Kinematics<'_, 3>| evaluate(k, &resolved, &mut None)[0];
            let found = QuickReturn::find(m, solver, value);
            outputs.push((output.name.clone(), output.kind.dimension(), found));
        }
        let loops = linkage
            .as_ref()
            .is_ok_and(|l| !l.four_bars.is_empty() || !l.slider_cranks.is_empty());
        Ok((loops || !outputs.is_empty()).then_some(SceneMetrics { linkage, outputs }))
    }

    /// The metrics in words, one line each, in the scene's units (see
    /// docs/scene-format.md, "Linkage metrics").
    pub fn lines(&self, scene: &Scene) -> Vec<String> {
        let w = Words::of(scene);
        let mut out = vec!["linkage metrics:".to_owned()];
        match &self.linkage {
            Err(why) => out.push(format!("  not computed: {}", error_words(why))),
            Ok(l) => {
                out.push(format!(
                    "  the drive {}",
                    l.drive.describe(|phi| w.drive(phi))
                ));
                for f in &l.four_bars {
                    out.extend(w.four_bar(f));
                }
                for s in &l.slider_cranks {
                    out.extend(w.slider_crank(s));
                }
                for n in &l.not_applicable {
                    out.push(format!(
                        "  no metrics for links {} (joints {}): {}",
                        n.links.join(", "),
                        n.joints.join(", "),
                        n.reason
                    ));
                }
            }
        }
        for (name, dimension, found) in &self.outputs {
            out.push(format!(
                "  output {name}: {}",
                w.quick_return(found, *dimension)
            ));
        }
        out
    }

    /// The metrics as a JSON object, every value in the scene's units (angles in its angle
    /// unit, lengths in its length unit, drive positions in the drive's unit), each quantity
    /// with its unit beside it.
    pub fn json(&self, scene: &Scene) -> Value {
        let w = Words::of(scene);
        let linkage = match &self.linkage {
            Err(why) => json!({ "error": error_words(why) }),
            Ok(l) => json!({
                "drive": l.drive.describe(|phi| w.drive(phi)),
                "four_bars": l.four_bars.iter().map(|f| w.four_bar_json(f)).collect::<Vec<_>>(),
                "slider_cranks": l.slider_cranks.iter().map(|s| w.slider_crank_json(s)).collect::<Vec<_>>(),
                "not_applicable": l.not_applicable.iter().map(|n| json!({
                    "links": n.links, "joints": n.joints, "reason": n.reason
                })).collect::<Vec<_>>(),
            }),
        };
        let outputs: Vec<Value> = (self.outputs.iter())
            .map(|(name, dimension, found)| {
                json!({ "output": name, "quick_return": w.quick_return_json(found, *dimension) })
            })
            .collect();
        json!({ "linkage": linkage, "outputs": outputs })
    }
}

/// A metric's error in words, with the solver's error behind it (drive positions in the
/// scene's units where [`Words::error`] words them).
fn error_words(e: &MetricsError) -> String {
    match std::error::Error::source(e) {
        Some(source) => format!("{e}: {source}"),
        None => e.to_string(),
    }
}

/// The scene's units for the metrics' numbers.
struct Words<'s> {
    scene: &'s Scene,
    units: Units,
}

impl<'s> Words<'s> {
    fn of(scene: &'s Scene) -> Self {
        Words {
            scene,
            units: scene.units.for_outputs(),
        }
    }

    /// A metric's error in words: a crank that stops, at its drive position in the scene's
    /// unit; the others as [`error_words`].
    fn error(&self, e: &MetricsError) -> String {
        match e {
            MetricsError::CrankDoesNotTurn { limit } => format!(
                "the crank does not turn fully: the drive stops at {} ({}), so there is no \
                 time ratio",
                self.drive(limit.phi),
                match limit.kind {
                    mechdiff_core::geometry::LimitKind::ChangePoint => "a change point",
                    mechdiff_core::geometry::LimitKind::Toggle => "a toggle",
                    _ => "a limit position",
                }
            ),
            other => error_words(other),
        }
    }

    /// A quantity (SI) in the scene's unit, as a number.
    fn number(&self, si: f64, dimension: Dimension) -> f64 {
        self.units.from_si(si, dimension) + 0.0
    }

    /// A quantity (SI) in the scene's unit, as text with its symbol.
    fn text(&self, si: f64, dimension: Dimension) -> String {
        format!(
            "{} {}",
            Units::tidy(round(self.number(si, dimension))),
            self.units.symbol(dimension)
        )
    }

    /// A drive position (SI) in the drive's unit, to ten significant digits.
    fn drive(&self, si: f64) -> String {
        let dimension = self.scene.drive.kind.dimension();
        format!(
            "{} {}",
            Units::tidy(round(self.scene.units.from_si(si, dimension) + 0.0)),
            self.scene.units.symbol(dimension)
        )
    }

    /// A stroke moved by whole turns so that it starts in the sweep's first turn (from its
    /// lowest drive position).
    fn in_first_turn(&self, s: &Stroke) -> Stroke {
        let (lo, _) = self.scene.positions.range();
        let turns = ((s.from - lo) / TAU).floor();
        Stroke {
            from: s.from - turns * TAU,
            to: s.to - turns * TAU,
            crank_angle: s.crank_angle,
        }
    }

    fn length(&self, si: f64) -> String {
        self.text(si, Dimension::Length)
    }

    fn angle(&self, si: f64) -> String {
        self.text(si, Dimension::Angle)
    }

    /// Where an input is: the drive position when the loop's input is the drive, else its
    /// angle θ from the loop's zero line.
    fn position(&self, at: &InputPosition) -> String {
        match at.drive {
            Some(phi) if self.scene.drive.kind == DriveKind::Angle => {
                format!("φ = {}", self.drive(phi))
            }
            _ => format!("θ = {}", self.angle(at.angle)),
        }
    }

    fn range(&self, name: &str, range: &InputRange) -> String {
        let changes = |points: &[InputPosition]| {
            let list: Vec<String> = points.iter().map(|p| self.position(p)).collect();
            match list.is_empty() {
                true => String::new(),
                false => format!("; change point at {}", list.join(", ")),
            }
        };
        match range {
            InputRange::Full { change_points } => {
                format!("    input {name} turns fully{}", changes(change_points))
            }
            InputRange::Rocks {
                lower,
                upper,
                change_points,
            } => {
                let end = |e: &InputEnd| format!("{} ({})", self.position(&e.at), e.toggle.name());
                format!(
                    "    input {name} rocks from {} to {}{}",
                    end(lower),
                    end(upper),
                    changes(change_points)
                )
            }
        }
    }

    fn transmission(
        &self,
        formula: &str,
        t: &TransmissionExtremes,
        sweep: Option<SweepExtremes>,
    ) -> Vec<String> {
        let at =
            |a: &TransmissionAt| format!("{} at {}", self.angle(a.angle), self.position(&a.at));
        let effective = t.worst.angle.min(std::f64::consts::PI - t.worst.angle);
        let mut lines = vec![format!(
            "    transmission angle μ ({formula}), over the input's range: min {}, max {}; \
             worst effective μ {} (deviation from 90° {}) at {}",
            at(&t.min),
            at(&t.max),
            self.angle(effective),
            self.angle(std::f64::consts::FRAC_PI_2 - effective),
            self.position(&t.worst.at)
        )];
        if let Some(s) = sweep {
            lines.push(format!(
                "    over the sweep: min μ {} at φ = {}, max μ {} at φ = {}; worst effective μ {} \
                 (deviation from 90° {})",
                self.angle(s.min.1),
                self.drive(s.min.0),
                self.angle(s.max.1),
                self.drive(s.max.0),
                self.angle(s.worst_effective()),
                self.angle(std::f64::consts::FRAC_PI_2 - s.worst_effective()),
            ));
        }
        lines
    }

    /// μ's extremes over the sweep's drive positions, from the loop's closed form `mu` of
    /// its input angle θ: for a loop whose input is the drive (its pivot `pivot` turning
    /// `input`), θ = θ_sketch ± (φ − φ_sketch). `None` for a loop not driven, a `[sweep] of`
    /// scene (its drive positions are found by the run), or a sweep longer than
    /// [`SWEEP_EXTREMES_UP_TO`].
    fn over_sweep(
        &self,
        driven: bool,
        pivot: &str,
        input: &str,
        sketch: f64,
        mu: impl Fn(f64) -> f64,
    ) -> Option<SweepExtremes> {
        let scene = self.scene;
        let positions = &scene.positions;
        if !driven || scene.sweep_of.is_some() || positions.len() > SWEEP_EXTREMES_UP_TO {
            return None;
        }
        let joint = scene.joints.iter().find(|j| j.name == pivot)?;
        let sign = match &joint.kind {
            JointKind::Revolute { links, .. } if links[1] == input => 1.0,
            JointKind::Revolute { .. } => -1.0,
            _ => return None,
        };
        let at_sketch = scene.drive.at_sketch;
        let (mut min, mut max) = ((f64::NAN, f64::INFINITY), (f64::NAN, f64::NEG_INFINITY));
        for phi in positions.iter() {
            let m = mu(sketch + sign * (phi - at_sketch));
            if m < min.1 {
                min = (phi, m);
            }
            if m > max.1 {
                max = (phi, m);
            }
        }
        (min.1.is_finite() && max.1.is_finite()).then_some(SweepExtremes { min, max })
    }

    /// μ's extremes over the sweep for a four-bar loop.
    fn four_bar_sweep(&self, l: &FourBarLoop) -> Option<SweepExtremes> {
        let (pivot, input) = (&l.joints[0], &l.links[1]);
        self.over_sweep(l.driven, pivot, input, l.sketch_angle(), |theta| {
            l.transmission_angle(theta)
        })
    }

    /// μ's extremes over the sweep for a slider-crank loop.
    fn slider_crank_sweep(&self, l: &SliderCrankLoop) -> Option<SweepExtremes> {
        self.over_sweep(
            l.driven,
            &l.joints[0],
            &l.crank,
            l.sketch_angle(),
            |theta| l.transmission_angle(theta),
        )
    }

    /// A quick return in words: the time ratio, the forward and return crank angles and
    /// where they run, the travel (stroke or swing) of an output of `dimension`.
    fn quick_return(
        &self,
        found: &std::result::Result<QuickReturn, MetricsError>,
        dimension: Dimension,
    ) -> String {
        let q = match found {
            Ok(q) => q,
            Err(why) => return format!("no time ratio ({})", self.error(why)),
        };
        let (forward, back) = (self.in_first_turn(&q.forward), self.in_first_turn(&q.back));
        let travel = match dimension {
            Dimension::Angle => "swing",
            _ => "stroke",
        };
        format!(
            "time ratio Q = {:.9} (forward stroke {} of crank from φ = {} to {}, return {} \
             from φ = {} to {}); {travel} {}",
            q.time_ratio,
            self.angle(forward.crank_angle),
            self.drive(forward.from),
            self.drive(forward.to),
            self.angle(back.crank_angle),
            self.drive(back.from),
            self.drive(back.to),
            self.text(q.travel, dimension)
        )
    }

    fn four_bar(&self, f: &mechdiff_core::metrics::FourBarMetrics) -> Vec<String> {
        let l = &f.linkage;
        let g = &f.grashof;
        let term = |t: &mechdiff_core::metrics::LengthTerm| {
            format!("{} {}", t.link, self.length(t.length))
        };
        let relation = match g.class {
            mechdiff_core::metrics::GrashofClass::ChangePoint => "=",
            mechdiff_core::metrics::GrashofClass::TripleRocker => ">",
            _ => "<",
        };
        let mut lines = vec![
            format!(
                "  four-bar {} (joints {}):",
                l.links.join("–"),
                l.joints.join(", ")
            ),
            format!(
                "    Grashof: {}: s + l = {} + {} = {} {relation} p + q = {} + {} = {}",
                g.class.name(),
                term(&g.shortest),
                term(&g.longest),
                self.length(g.s_plus_l),
                term(&g.others[0]),
                term(&g.others[1]),
                self.length(g.p_plus_q)
            ),
            self.range(&l.links[1], &f.input_range),
        ];
        let sweep = self.four_bar_sweep(l);
        lines.extend(self.transmission(FourBarLoop::TRANSMISSION_FORMULA, &f.transmission, sweep));
        lines.push(format!(
            "    output {}: {}",
            l.links[3],
            self.quick_return(&f.quick_return, Dimension::Angle)
        ));
        lines
    }

    fn slider_crank(&self, s: &mechdiff_core::metrics::SliderCrankMetrics) -> Vec<String> {
        let l = &s.linkage;
        let c = &s.criterion;
        let relation = match c.class {
            mechdiff_core::metrics::SliderCrankClass::Crank => "<",
            mechdiff_core::metrics::SliderCrankClass::ChangePoint => "=",
            mechdiff_core::metrics::SliderCrankClass::Rocker => ">",
        };
        let mut links = vec![l.frame.clone(), l.crank.clone(), l.rod.clone()];
        links.extend(l.slider.clone());
        let mut lines = vec![
            format!(
                "  slider-crank {} (joints {}):",
                links.join("–"),
                l.joints.join(", ")
            ),
            format!(
                "    {}: r + |e| = {} + {} = {} {relation} l = {}",
                c.class.name(),
                self.length(l.lengths.crank),
                self.length(l.lengths.offset.abs()),
                self.length(c.crank_plus_offset),
                self.length(c.rod)
            ),
            self.range(&l.crank, &s.input_range),
        ];
        let sweep = self.slider_crank_sweep(l);
        lines.extend(self.transmission(
            SliderCrankLoop::TRANSMISSION_FORMULA,
            &s.transmission,
            sweep,
        ));
        lines.push(format!(
            "    {}: {}",
            l.slider.as_deref().unwrap_or(&l.rod),
            self.quick_return(&s.quick_return, Dimension::Length)
        ));
        lines
    }
}

/// The longest sweep whose transmission-angle extremes are evaluated (one closed form per
/// drive position: a few milliseconds for this many).
pub const SWEEP_EXTREMES_UP_TO: usize = 10_000_000;

/// μ's smallest and largest value over the sweep: `(φ, μ)` each (rad).
#[derive(Debug, Clone, Copy)]
struct SweepExtremes {
    min: (f64, f64),
    max: (f64, f64),
}

impl SweepExtremes {
    /// The worst effective μ = min(μ, 180° − μ) over the sweep: at the smallest or the
    /// largest μ.
    fn worst_effective(&self) -> f64 {
        self.min.1.min(std::f64::consts::PI - self.max.1)
    }
}

/// `x` to ten significant digits: the metrics' words show what their numbers rest on, not
/// the last bits of a unit conversion.
fn round(x: f64) -> f64 {
    match format!("{x:.9e}").parse::<f64>() {
        Ok(v) => v,
        Err(_) => x,
    }
}
