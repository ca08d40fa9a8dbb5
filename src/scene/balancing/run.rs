//! Running the balancing sections: the rotor's corrections, the linkage's counterweights,
//! and what they change.

use mechdiff_core::DriveState;
use mechdiff_core::balancing::{
    Counterweight, LinkageBalance, LinkageBalancing, Rotor, SliderCrankUnbalance,
    check_balance_request,
};
use mechdiff_core::dynamics::Dynamics;
use mechdiff_core::geometry::{Mechanism, Tracker};
use mechdiff_core::sweep::Consumer;

use crate::error::{Error, Location, Result};
use crate::scene::dynamics::SceneDynamics;
use crate::scene::error_context::ErrorContext;
use crate::scene::model::DriveKind;
use crate::scene::outputs::Column;
use crate::scene::units::{Dimension, Units};

use super::resolve::{SceneBalancing, SceneRotor};

/// The balancing answers: lines printed after the table, and the linkage's columns after
/// balancing (one row per drive position).
#[derive(Debug, Clone, PartialEq)]
pub struct BalancingReport {
    /// Columns (SI, factor 1): shaking force, moment and drive torque with counterweights.
    pub columns: Vec<Column>,
    /// One row per drive position (empty without `[balancing]`).
    pub rows: Vec<Vec<f64>>,
    /// Lines printed after the table.
    pub lines: Vec<String>,
    /// The counterweights and the sweeps before and after.
    pub linkage: Option<LinkageBalance>,
}

fn column(name: &str, unit: &str) -> Column {
    Column {
        name: name.to_owned(),
        unit: unit.to_owned(),
        factor: 1.0,
    }
}

fn core_error(location: &Location, e: mechdiff_core::Error) -> Error {
    Error::Invalid {
        location: location.clone(),
        message: e.to_string(),
    }
}

/// The columns the balancing sections `b` of a scene (its words `cx`) add to the table
/// (those of the counterweights' linkage balance), known before anything is solved.
pub(crate) fn columns(cx: &ErrorContext<'_>, b: &SceneBalancing) -> Vec<Column> {
    if b.counterweights.is_none() {
        return Vec::new();
    }
    let torque = if cx.drive.kind == DriveKind::Angle {
        ("M_drive_bal", "N m")
    } else {
        ("F_drive_bal", "N")
    };
    vec![
        column("SumF_x_bal", "N"),
        column("SumF_y_bal", "N"),
        column("M_shaking_bal", "N m"),
        column(torque.0, torque.1),
    ]
}

/// A core error of the counterweights' sizing, in the scene's terms: the solver's errors
/// with drive positions in the scene's units; one naming a counterweight's link located at
/// that counterweight; any other at `[balancing]` (`location`).
fn balance_error(
    cx: &ErrorContext<'_>,
    counterweights: &[(Counterweight, Location)],
    location: &Location,
    e: mechdiff_core::Error,
) -> Error {
    let at = |link: &str| {
        counterweights
            .iter()
            .rfind(|(c, _)| c.link == link)
            .map_or(location, |(_, at)| at)
    };
    match e {
        mechdiff_core::Error::Unassemblable { .. }
        | mechdiff_core::Error::Singular { .. }
        | mechdiff_core::Error::BranchFlip { .. } => cx.solver_error(e),
        mechdiff_core::Error::NotPivoted { ref link, .. } => core_error(at(link), e),
        mechdiff_core::Error::DuplicateName { ref name, .. } => core_error(at(name), e),
        other => core_error(location, other),
    }
}

/// What `[rotor]` and `[balancing]` check before anything is solved (`mechdiff check` runs
/// it too): the rotor's answers are finite; counterweights sit on pivoted links of a linkage
/// with mass data, one each ([`check_balance_request`]), and have a shaking force to size
/// them from (a drive `speed`, or an acceleration, that is not zero).
pub(crate) fn before_solving(
    cx: &ErrorContext<'_>,
    b: &SceneBalancing,
    mechanism: &Mechanism,
) -> Result<()> {
    if let Some(r) = &b.rotor {
        r.answers()?;
    }
    if let Some((counterweights, location)) = &b.counterweights {
        let requests: Vec<_> = counterweights.iter().map(|(c, _)| c.clone()).collect();
        check_balance_request(mechanism, &requests)
            .map_err(|e| balance_error(cx, counterweights, location, e))?;
        let alpha = cx.drive.acceleration;
        let message = match cx.drive.speed {
            None => "`[balancing]` sizes counterweights from the shaking force: give the \
                     drive's `speed`"
                .to_owned(),
            Some(omega) if omega == 0.0 && alpha == 0.0 => {
                "`[balancing]` sizes counterweights from the shaking force, which is zero at a \
                 drive `speed` of 0 (and no acceleration): give a non-zero `speed`"
                    .to_owned()
            }
            // The shaking force scales with ω² and α: below the smallest normal f64 it is
            // zero or a few bits at every position, and determines nothing.
            Some(omega) if omega * omega + alpha.abs() < f64::MIN_POSITIVE => format!(
                "`[balancing]` sizes counterweights from the shaking force, which scales with \
                 the drive's speed squared: at a speed of {omega:e} rad/s (and acceleration \
                 {alpha:e}) it underflows to zero in f64 arithmetic; give a speed above \
                 1e-150 rad/s (any speed gives the same counterweights)"
            ),
            Some(_) => return Ok(()),
        };
        return Err(Error::Invalid {
            location: location.clone(),
            message,
        });
    }
    Ok(())
}

/// The counterweights of `[balancing]` sized from a sweep, one drive position at a time: at
/// each position the sweep's tracker has solved (nothing is solved here) the pose is read
/// and kept ([`LinkageBalancing`]); [`BalancingSweep::finish`] sizes them and evaluates
/// the balanced linkage at the same poses.
#[derive(Debug, Clone)]
pub(crate) struct BalancingSweep<'s> {
    balancing: LinkageBalancing<'s>,
    counterweights: &'s [(Counterweight, Location)],
    location: &'s Location,
}

impl<'s> BalancingSweep<'s> {
    /// The counterweights of `b` ready for a sweep of a scene (its words `cx`, its masses
    /// and effects `dynamics`), after [`before_solving`]'s checks; `None` without
    /// counterweights.
    pub(crate) fn new(
        cx: &ErrorContext<'_>,
        dynamics: Option<&SceneDynamics>,
        b: &'s SceneBalancing,
        mechanism: &'s Mechanism,
    ) -> Result<Option<Self>> {
        let Some((counterweights, location)) = &b.counterweights else {
            return Ok(None);
        };
        let omega = cx.drive.speed.unwrap_or(0.0);
        let data = dynamics.map_or_else(Dynamics::new, |d| d.data.clone());
        let drive = DriveState::accelerating(omega, cx.drive.acceleration);
        let requests: Vec<_> = counterweights.iter().map(|(c, _)| c.clone()).collect();
        let balancing = LinkageBalancing::new(mechanism, &data, &requests, drive)
            .map_err(|e| balance_error(cx, counterweights, location, e))?;
        Ok(Some(Self {
            balancing,
            counterweights,
            location,
        }))
    }

    /// The scene's error for an error of the counterweights' sizing (see [`balance_error`]).
    pub(crate) fn error(&self, cx: &ErrorContext<'_>, e: mechdiff_core::Error) -> Error {
        balance_error(cx, self.counterweights, self.location, e)
    }

    /// Sizes the counterweights and evaluates the balanced linkage.
    pub(crate) fn finish(self, cx: &ErrorContext<'_>) -> Result<LinkageBalance> {
        (self.balancing.finish())
            .map_err(|e| balance_error(cx, self.counterweights, self.location, e))
    }
}

/// The counterweights read the pose of every position the sweep solves (no values in its
/// rows: their columns are known at the end, [`BalancingSweep::finish`]).
impl Consumer for BalancingSweep<'_> {
    fn at(
        &mut self,
        tracker: &Tracker<'_>,
        phi: f64,
        row: &mut Vec<f64>,
    ) -> std::result::Result<(), mechdiff_core::Error> {
        self.balancing.at(tracker, phi, row)
    }
}

/// The balancing answers of a scene (its words `cx`): the rotor's and the slider-crank's
/// lines, and the counterweights `linkage` sized over the sweep ([`BalancingSweep`]) with
/// their columns.
pub(crate) fn report(
    cx: &ErrorContext<'_>,
    b: &SceneBalancing,
    mechanism: &Mechanism,
    linkage: Option<LinkageBalance>,
) -> Result<BalancingReport> {
    before_solving(cx, b, mechanism)?;
    let mut report = BalancingReport {
        columns: Vec::new(),
        rows: Vec::new(),
        lines: Vec::new(),
        linkage: None,
    };
    if let Some(r) = &b.rotor {
        report
            .lines
            .extend(rotor_lines(&cx.units.for_outputs(), r)?);
    }
    if let Some(sc) = &b.slider_crank {
        let [crank, rod, slider] = &sc.links;
        let u = SliderCrankUnbalance::from_mechanism(mechanism, crank, rod, slider)
            .map_err(|e| core_error(&sc.location, e))?;
        let omega = cx.drive.speed.unwrap_or(0.0);
        let units = cx.units.for_outputs();
        let p = u
            .partial_balance(sc.fraction, omega)
            .map_err(|e| core_error(&sc.location, e))?;
        report.lines.push(String::new());
        report.lines.push(format!(
            "slider-crank `{crank}`–`{rod}`–`{slider}`: r = {}, l = {}, reciprocating mass {:.9} kg, \
             rotating m r {:.9} kg m (rod split between its pins by its centre of gravity)",
            length_text(&units, u.crank),
            length_text(&units, u.rod),
            u.reciprocating_mass,
            u.rotating_mass_radius
        ));
        report.lines.push(format!(
            "  at ω = {omega:.6} rad/s: primary unbalance {:.6} N (cos φ), secondary {:.6} N (cos 2φ)",
            u.primary(omega),
            u.secondary(omega)
        ));
        report.lines.push(format!(
            "  partial balance of {} of the reciprocating mass: crank counterweight m r = {:.9} kg m \
             opposite the crank pin; primary left {:.6} N along the line, {:.6} N across it",
            p.fraction, p.counterweight_mass_radius, p.primary_along, p.primary_across
        ));
    }
    if let Some(result) = linkage {
        report.columns = columns(cx, b);
        let torque = &report.columns[3].unit;
        let a = &result.after;
        report.rows = (0..a.phi.len())
            .map(|j| vec![a.force[j][0], a.force[j][1], a.moment[j], a.drive_torque[j]])
            .collect();
        report
            .lines
            .extend(linkage_lines(&cx.units, &result, torque));
        report.linkage = Some(result);
    }
    Ok(report)
}

fn angle_text(u: &Units, rad: f64) -> String {
    format!(
        "{:.6} {}",
        u.from_si(rad, Dimension::Angle),
        u.symbol(Dimension::Angle)
    )
}

fn length_text(u: &Units, m: f64) -> String {
    format!(
        "{} {}",
        Units::tidy(u.from_si(m, Dimension::Length)),
        u.symbol(Dimension::Length)
    )
}

fn polar(v: [f64; 2]) -> (f64, f64) {
    (v[0].hypot(v[1]), v[1].atan2(v[0]))
}

/// The printed answers of a rotor, numbers in the output units `units`.
pub(crate) fn rotor_lines(units: &Units, r: &SceneRotor) -> Result<Vec<String>> {
    let answers = r.answers()?;
    let [force_scale, couple_scale] = answers.scale;
    // A vector as magnitude and angle, or as zero when it is rounding noise.
    let vector = |v: [f64; 2], scale: f64, unit: &str| {
        let (m, a) = polar(v);
        if m <= Rotor::NEGLIGIBLE * scale {
            format!("0 {unit}")
        } else {
            format!("{m:.12} {unit} at {}", angle_text(units, a))
        }
    };
    let mut lines = vec![String::new()];
    let p = &answers.polygons;
    lines.push(format!(
        "rotor polygons (couple about the plane at {}): mass, m r [kg m], angle, m r d [kg m^2], angle",
        length_text(units, r.reference)
    ));
    for (i, (f, c)) in p.force.iter().zip(&p.couple).enumerate() {
        lines.push(format!(
            "  {}: {}; {}",
            i + 1,
            vector(*f, force_scale, "kg m"),
            vector(*c, couple_scale, "kg m^2")
        ));
    }
    let [force_gap, couple_gap] = answers.resultant;
    lines.push(format!(
        "  gap: {}; {}",
        vector(force_gap, force_scale, "kg m"),
        vector(couple_gap, couple_scale, "kg m^2")
    ));
    let with_mass = |mr: f64| match r.correction_radius {
        Some(radius) => format!(
            " ({:.9} kg at radius {})",
            mr / radius,
            length_text(units, radius)
        ),
        None => String::new(),
    };
    let s = answers.static_balance;
    lines.push(if s.mass_radius <= Rotor::NEGLIGIBLE * force_scale {
        "rotor static balance: none needed (the mr polygon closes)".to_owned()
    } else {
        format!(
            "rotor static balance: m r = {}{}",
            vector(s.vector, force_scale, "kg m"),
            with_mass(s.mass_radius)
        )
    });
    if let Some(two) = answers.two_plane {
        for c in two.corrections() {
            lines.push(format!(
                "rotor two-plane balance, plane at {}: m r = {}{}",
                length_text(units, c.axial),
                vector(c.vector, force_scale, "kg m"),
                with_mass(c.mass_radius)
            ));
        }
    }
    if let (Some(mr), Some(c)) = (r.couple_mass_radius, answers.couple_plane) {
        lines.push(format!(
            "rotor couple balance with one m r = {mr} kg m: plane at {} ({} from the reference), \
             angle {}; force polygon gap after: {}",
            length_text(units, c.correction.axial),
            length_text(units, c.distance),
            angle_text(units, c.correction.angle),
            vector(c.force_after, force_scale.max(mr), "kg m")
        ));
    }
    Ok(lines)
}

fn linkage_lines(units: &Units, r: &LinkageBalance, torque_unit: &str) -> Vec<String> {
    let units = units.for_outputs();
    let mut lines = vec![String::new()];
    for c in &r.counterweights {
        lines.push(format!(
            "counterweight on `{}`: m r = {:.9} kg m at {} from {}→{}; {:.9} kg at radius {}",
            c.request.link,
            c.mass_radius,
            angle_text(&units, c.angle),
            c.request.line[0],
            c.request.line[1],
            c.mass,
            length_text(&units, c.request.radius)
        ));
    }
    let kind = if r.full_force_balance() {
        "full force balance"
    } else {
        "least squares over the sweep (full force balance is not possible with these links)"
    };
    let (b, a) = (&r.before, &r.after);
    lines.push(format!("balancing: {kind}"));
    lines.push(format!(
        "  largest |SumF| (foundation load): {:.6} N before, {:.6} N after; rms {:.6} N → {:.6} N",
        b.max_force(),
        a.max_force(),
        b.rms_force(),
        a.rms_force()
    ));
    lines.push(format!(
        "  largest |M_shaking|: {:.6} N m before, {:.6} N m after",
        b.max_moment(),
        a.max_moment()
    ));
    lines.push(format!(
        "  largest |drive torque|: {:.6} {torque_unit} before, {:.6} {torque_unit} after",
        b.max_drive_torque(),
        a.max_drive_torque()
    ));
    lines
}
