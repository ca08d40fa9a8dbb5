//! The metrics as JSON ([`super::SceneMetrics::json`]): every number in the scene's units,
//! each quantity with its unit beside it.

use mechdiff_core::metrics::{
    FourBarLoop, FourBarMetrics, InputEnd, InputPosition, InputRange, LengthTerm, MetricsError,
    QuickReturn, SliderCrankLoop, SliderCrankMetrics, Stroke, TransmissionAt, TransmissionExtremes,
};
use serde_json::{Value, json};

use super::{SweepExtremes, Words};
use crate::scene::units::Dimension;

impl Words<'_> {
    pub(super) fn position_json(&self, at: &InputPosition) -> Value {
        let angle = self.units.symbol(Dimension::Angle);
        let drive = self.scene.drive.kind.dimension();
        json!({
            "theta": self.number(at.angle, Dimension::Angle),
            "phi": at.drive.map(|phi| self.scene.units.from_si(phi, drive) + 0.0),
            "unit": angle,
            "phi_unit": self.scene.units.symbol(drive),
        })
    }

    pub(super) fn range_json(&self, range: &InputRange) -> Value {
        let points = |p: &[InputPosition]| -> Vec<Value> {
            p.iter().map(|p| self.position_json(p)).collect()
        };
        match range {
            InputRange::Full { change_points } => json!({
                "turns_fully": true, "change_points": points(change_points)
            }),
            InputRange::Rocks {
                lower,
                upper,
                change_points,
            } => {
                let end = |e: &InputEnd| {
                    let mut v = self.position_json(&e.at);
                    v["toggle"] = json!(e.toggle.name());
                    v
                };
                json!({
                    "turns_fully": false, "lower": end(lower), "upper": end(upper),
                    "change_points": points(change_points)
                })
            }
        }
    }

    pub(super) fn sweep_json(&self, s: Option<SweepExtremes>) -> Value {
        let Some(s) = s else {
            return Value::Null;
        };
        let drive = self.scene.drive.kind.dimension();
        let at = |(phi, mu): (f64, f64)| {
            json!({
                "phi": self.scene.units.from_si(phi, drive) + 0.0,
                "mu": self.number(mu, Dimension::Angle),
            })
        };
        json!({
            "min": at(s.min),
            "max": at(s.max),
            "worst_effective": self.number(s.worst_effective(), Dimension::Angle),
        })
    }

    pub(super) fn transmission_json(
        &self,
        formula: &str,
        t: &TransmissionExtremes,
        sweep: Option<SweepExtremes>,
    ) -> Value {
        let at = |a: &TransmissionAt| {
            let mut v = self.position_json(&a.at);
            v["mu"] = json!(self.number(a.angle, Dimension::Angle));
            v
        };
        let effective = t.worst.angle.min(std::f64::consts::PI - t.worst.angle);
        let mut worst = at(&t.worst);
        worst["effective"] = json!(self.number(effective, Dimension::Angle));
        worst["deviation"] =
            json!(self.number(std::f64::consts::FRAC_PI_2 - effective, Dimension::Angle));
        json!({
            "formula": formula, "min": at(&t.min), "max": at(&t.max), "worst": worst,
            "over_sweep": self.sweep_json(sweep),
        })
    }

    pub(super) fn quick_return_json(
        &self,
        found: &std::result::Result<QuickReturn, MetricsError>,
        dimension: Dimension,
    ) -> Value {
        let q = match found {
            Ok(q) => q,
            Err(why) => return json!({ "error": self.error(why) }),
        };
        let drive = self.scene.drive.kind.dimension();
        let stroke = |s: &Stroke| {
            let s = self.in_first_turn(s);
            json!({
                "from": self.scene.units.from_si(s.from, drive) + 0.0,
                "to": self.scene.units.from_si(s.to, drive) + 0.0,
                "crank_angle": self.number(s.crank_angle, Dimension::Angle),
            })
        };
        json!({
            "time_ratio": q.time_ratio,
            "forward": stroke(&q.forward),
            "return": stroke(&q.back),
            "travel": self.number(q.travel, dimension),
            "travel_unit": self.units.symbol(dimension),
            "angle_unit": self.units.symbol(Dimension::Angle),
            "phi_unit": self.scene.units.symbol(drive),
        })
    }

    pub(super) fn four_bar_json(&self, f: &FourBarMetrics) -> Value {
        let (l, g) = (&f.linkage, &f.grashof);
        let term = |t: &LengthTerm| json!({ "link": t.link, "role": t.role.name(), "length": self.number(t.length, Dimension::Length) });
        json!({
            "links": l.links,
            "joints": l.joints,
            "length_unit": self.units.symbol(Dimension::Length),
            "grashof": {
                "class": g.class.name(),
                "shortest": term(&g.shortest),
                "longest": term(&g.longest),
                "others": [term(&g.others[0]), term(&g.others[1])],
                "s_plus_l": self.number(g.s_plus_l, Dimension::Length),
                "p_plus_q": self.number(g.p_plus_q, Dimension::Length),
            },
            "input_range": self.range_json(&f.input_range),
            "transmission_angle": self.transmission_json(
                FourBarLoop::TRANSMISSION_FORMULA, &f.transmission, self.four_bar_sweep(l)
            ),
            "quick_return": self.quick_return_json(&f.quick_return, Dimension::Angle),
        })
    }

    pub(super) fn slider_crank_json(&self, s: &SliderCrankMetrics) -> Value {
        let (l, c) = (&s.linkage, &s.criterion);
        json!({
            "frame": l.frame, "crank": l.crank, "rod": l.rod, "slider": l.slider,
            "joints": l.joints,
            "length_unit": self.units.symbol(Dimension::Length),
            "criterion": {
                "class": c.class.name(),
                "r": self.number(l.lengths.crank, Dimension::Length),
                "l": self.number(l.lengths.rod, Dimension::Length),
                "e": self.number(l.lengths.offset, Dimension::Length),
                "r_plus_abs_e": self.number(c.crank_plus_offset, Dimension::Length),
            },
            "input_range": self.range_json(&s.input_range),
            "transmission_angle": self.transmission_json(
                SliderCrankLoop::TRANSMISSION_FORMULA, &s.transmission, self.slider_crank_sweep(l)
            ),
            "quick_return": self.quick_return_json(&s.quick_return, Dimension::Length),
        })
    }
}
