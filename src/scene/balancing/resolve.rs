//! Checking the balancing sections: units applied, names resolved, every error located.

use mechdiff_core::balancing::{Counterweight, Rotor, RotorMass};
use toml::Spanned;

use crate::error::{Error, Result};
use crate::scene::context::{Context, Geometry};
use crate::scene::limits;
use crate::scene::units::{Dimension, Units};
use crate::scene::values::Number;

// The checked types are named here by the run side (`run.rs`) too.
pub(super) use super::model::{SceneBalancing, SceneRotor, SceneSliderCrank};

use super::format::{BalancingDef, RotorDef};

/// Checks `[rotor]` and `[balancing]`; `None` when the scene has neither.
pub(crate) fn resolve(
    cx: &Context,
    rotor: Option<&Spanned<RotorDef>>,
    balancing: Option<&Spanned<BalancingDef>>,
    geometry: &Geometry,
) -> Result<Option<SceneBalancing>> {
    if rotor.is_none() && balancing.is_none() {
        return Ok(None);
    }
    let rotor = rotor.map(|r| resolve_rotor(cx, r)).transpose()?;
    let mut counterweights = None;
    let mut slider_crank = None;
    if let Some(b) = balancing {
        let def = b.get_ref();
        if def.counterweights.is_none() && def.slider_crank.is_none() {
            return Err(cx.invalid(
                b,
                "`[balancing]` asks for nothing: give `counterweights` or `slider_crank`",
            ));
        }
        if let Some(list) = &def.counterweights {
            let mut out = Vec::new();
            for entry in list.get_ref() {
                let c = entry.get_ref();
                let link = cx.link(&c.link, geometry, "`[balancing]`")?;
                let line = cx.line(&c.line, link, geometry, "a counterweight's `line`")?;
                let radius =
                    cx.positive(&c.radius, "the counterweight's radius", Dimension::Length)?;
                // Its mass is the m·r found divided by this radius: a radius below the
                // smallest a scene may draw would overflow it.
                if radius < limits::SMALLEST_RADIUS {
                    let unit = cx.units.symbol(Dimension::Length);
                    return Err(Error::OutOfRange {
                        location: cx.at(&c.radius),
                        what: "the counterweight's radius".to_owned(),
                        value: format!("{} {unit}", Units::tidy(cx.value(&c.radius)?)),
                        expected: format!(
                            "at least {} {unit}",
                            Units::tidy(
                                cx.units.from_si(limits::SMALLEST_RADIUS, Dimension::Length)
                            )
                        ),
                    });
                }
                out.push((
                    Counterweight {
                        link: link.to_owned(),
                        line,
                        radius,
                    },
                    cx.at(entry),
                ));
            }
            if out.is_empty() {
                return Err(cx.invalid(
                    list,
                    "`[balancing] counterweights` is empty: name at least one link",
                ));
            }
            counterweights = Some((out, cx.at(b)));
        }
        if let Some(sc) = &def.slider_crank {
            let d = sc.get_ref();
            let context = "`[balancing] slider_crank`";
            let links = [
                cx.link(&d.crank, geometry, context)?.to_owned(),
                cx.link(&d.rod, geometry, context)?.to_owned(),
                cx.link(&d.slider, geometry, context)?.to_owned(),
            ];
            let fraction = match &d.fraction {
                Some(f) => {
                    let x = *f.get_ref();
                    if !(0.0..=1.0).contains(&x) {
                        return Err(
                            cx.invalid(f, format!("`fraction` must be in [0, 1], found {x}"))
                        );
                    }
                    x
                }
                None => 0.5,
            };
            slider_crank = Some(SceneSliderCrank {
                links,
                fraction,
                location: cx.at(sc),
            });
        }
    }
    Ok(Some(SceneBalancing {
        rotor,
        counterweights,
        slider_crank,
    }))
}

/// The largest `couple_mass_radius` (kg·m): the largest mass times the largest length.
pub const LARGEST_MASS_RADIUS: f64 = limits::MASS * limits::LENGTH;

/// A rotor mass (kg, no unit conversion, as documented): finite, > 0 and at most
/// [`limits::MASS`], so that every m·r·d stays finite.
fn rotor_mass(cx: &Context, value: &Spanned<Number>, n: usize) -> Result<f64> {
    let mass: f64 = cx.value(value)?;
    if mass.is_finite() && mass > 0.0 && mass <= limits::MASS {
        return Ok(mass);
    }
    Err(Error::OutOfRange {
        location: cx.at(value),
        what: format!("rotor mass {n}: `mass`"),
        value: format!("{} kg", Units::tidy(mass)),
        expected: format!("a number > 0 kg and ≤ {:e} kg", limits::MASS),
    })
}

pub(super) fn resolve_rotor(cx: &Context, r: &Spanned<RotorDef>) -> Result<SceneRotor> {
    let def = r.get_ref();
    let mut masses = Vec::new();
    for (i, m) in def.masses.get_ref().iter().enumerate() {
        let n = i + 1;
        let d = m.get_ref();
        let mass = rotor_mass(cx, &d.mass, n)?;
        let radius = cx.number(&d.radius, "the radius", Dimension::Length)?;
        if radius < 0.0 {
            return Err(cx.invalid(&d.radius, format!("rotor mass {n}: `radius` must be ≥ 0")));
        }
        masses.push(RotorMass {
            mass,
            radius,
            angle: cx.number(&d.angle, "the angle", Dimension::Angle)?,
            axial: cx.number(&d.plane, "the plane", Dimension::Length)?,
        });
    }
    if masses.is_empty() {
        return Err(cx.invalid(&def.masses, "`[rotor] masses` is empty"));
    }
    let rotor = Rotor::new(masses).map_err(|e| cx.invalid(&def.masses, e.to_string()))?;
    let planes = match &def.planes {
        Some(p) => {
            let [a, b] = p.get_ref();
            // Each is checked at the pair (as `planes`), its formula evaluated at its own place.
            let number = |v: &Spanned<Number>| {
                let written = Spanned::new(p.span(), Number::Literal(cx.value(v)?));
                cx.number(&written, "a plane", Dimension::Length)
            };
            let (a, b) = (number(a)?, number(b)?);
            if a == b {
                return Err(cx.invalid(
                    p,
                    "`planes` must be two different finite axial positions: two-plane balancing \
                     needs two distinct correction planes",
                ));
            }
            Some([a, b])
        }
        None => None,
    };
    let reference = match &def.reference {
        Some(v) => cx.number(v, "`reference`", Dimension::Length)?,
        None => 0.0,
    };
    let correction_radius = def
        .correction_radius
        .as_ref()
        .map(|v| cx.positive(v, "`correction_radius`", Dimension::Length))
        .transpose()?;
    let couple_mass_radius = match &def.couple_mass_radius {
        Some(v) => {
            let x: f64 = cx.value(v)?;
            if !(x.is_finite() && x > 0.0 && x <= LARGEST_MASS_RADIUS) {
                return Err(Error::OutOfRange {
                    location: cx.at(v),
                    what: "`couple_mass_radius`".to_owned(),
                    value: format!("{} kg m", Units::tidy(x)),
                    expected: format!(
                        "a number > 0 kg m and ≤ {LARGEST_MASS_RADIUS:e} kg m (the largest \
                         mass times the largest length)"
                    ),
                });
            }
            Some(x)
        }
        None => None,
    };
    Ok(SceneRotor {
        rotor,
        planes,
        reference,
        correction_radius,
        couple_mass_radius,
        location: cx.at(r),
        planes_at: def.planes.as_ref().map(|p| cx.at(p)),
    })
}
