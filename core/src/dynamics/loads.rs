//! External loads: forces on points of links and torques on links, constant or active over a
//! range of the drive (a cutting force on the forward stroke).

use super::state::{Generalized, LinkState, dot, of};
use crate::geometry::{DriveKind, Mechanism};
use crate::{Error, Scalar};

/// What an external load is (in a [`super::EffectsTangent`], its derivative with respect to a
/// parameter).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LoadKind<T = f64> {
    /// A force (N, global components) at a point of the link.
    Force([T; 2]),
    /// A torque (N·m, counter-clockwise positive) on the link.
    Torque(T),
}

/// An external load on a link.
///
/// ```
/// use mechdiff_core::dynamics::Load;
/// // 1 kN against the ram's motion at point C, on the forward stroke only.
/// let cut = Load::force("ram", "C", [-1000.0, 0.0]).active_between(0.0, 4.0);
/// assert_eq!(cut.active, Some([0.0, 4.0]));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Load {
    /// The loaded link.
    pub link: String,
    /// The point of application: a named point carried by the link (ignored for a torque).
    pub point: Option<String>,
    /// Force or torque.
    pub kind: LoadKind,
    /// Drive range `[from, to]` where the load acts; `None`: always. For an angle drive the
    /// range is taken modulo one revolution (from `from` counter-clockwise to `to`).
    pub active: Option<[f64; 2]>,
}

impl Load {
    /// A constant force at a named point of a link.
    pub fn force(link: impl Into<String>, point: impl Into<String>, force: [f64; 2]) -> Self {
        Load {
            link: link.into(),
            point: Some(point.into()),
            kind: LoadKind::Force(force),
            active: None,
        }
    }

    /// A constant torque on a link.
    pub fn torque(link: impl Into<String>, torque: f64) -> Self {
        Load {
            link: link.into(),
            point: None,
            kind: LoadKind::Torque(torque),
            active: None,
        }
    }

    /// Makes the load act only for drive positions in `[from, to]`.
    pub fn active_between(mut self, from: f64, to: f64) -> Self {
        self.active = Some([from, to]);
        self
    }
}

/// A load compiled to indices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct CompiledLoad<T = f64> {
    pub link: usize,
    /// The point of application (a force's), by index.
    pub point: Option<usize>,
    /// Point of application relative to the link's reference point, unrotated.
    pub local: [T; 2],
    pub kind: LoadKind<T>,
    pub active: Option<[f64; 2]>,
    /// Whether the drive is an angle (ranges wrap modulo 2π).
    pub periodic: bool,
}

pub(crate) fn compile(m: &Mechanism, load: &Load, index: usize) -> Result<CompiledLoad, Error> {
    let context = format!("load {}", index + 1);
    let link = m.link_index(&load.link).map_err(|_| Error::UnknownName {
        what: "link",
        name: load.link.clone(),
        context: context.clone(),
    })?;
    let mut point = None;
    let local = match (&load.kind, &load.point) {
        (LoadKind::Force(_), None) => {
            return Err(Error::MissingData {
                what: format!("{context} (a force on link `{}`)", load.link),
                missing: "a point of application".to_owned(),
            });
        }
        (LoadKind::Force(_), Some(p)) => {
            let pi = m.point_index(p).map_err(|_| Error::UnknownName {
                what: "point",
                name: p.clone(),
                context: context.clone(),
            })?;
            if !m.carries(link, pi) {
                return Err(Error::PointNotOnLink {
                    point: p.clone(),
                    link: load.link.clone(),
                    context,
                });
            }
            point = Some(pi);
            m.local(link, m.points[pi].sketch)
        }
        (LoadKind::Torque(_), _) => [0.0, 0.0],
    };
    let values: Vec<f64> = match load.kind {
        LoadKind::Force(f) => f.to_vec(),
        LoadKind::Torque(t) => vec![t],
    };
    for v in values.into_iter().chain(load.active.into_iter().flatten()) {
        if !v.is_finite() {
            return Err(Error::InvalidValue {
                what: format!("{context} on link `{}`", load.link),
                value: v,
            });
        }
    }
    Ok(CompiledLoad {
        link,
        point,
        local,
        kind: load.kind,
        active: load.active,
        periodic: m.drive_kind == DriveKind::Angle,
    })
}

impl<T> CompiledLoad<T> {
    /// Whether the load acts at drive position `phi`.
    pub fn acts_at(&self, phi: f64) -> bool {
        match self.active {
            None => true,
            Some([from, to]) if self.periodic => {
                let tau = std::f64::consts::TAU;
                let span = to - from;
                span >= tau || (phi - from).rem_euclid(tau) <= span.rem_euclid(tau)
            }
            Some([from, to]) => from <= phi && phi <= to,
        }
    }
}

/// Adds the loads acting at `phi` to the generalized loads.
pub(crate) fn load<T: Scalar>(
    loads: &[CompiledLoad<T>],
    phi: f64,
    states: &[LinkState<T>],
    q: &mut Generalized<T>,
) {
    for l in loads.iter().filter(|l| l.acts_at(phi)) {
        match l.kind {
            LoadKind::Force(f) => q.force(states, l.link, of(states, l.link).position(l.local), f),
            LoadKind::Torque(t) => q.couple(l.link, t),
        }
    }
}

/// Power of the loads acting at `phi` (W).
pub(crate) fn power<T: Scalar>(loads: &[CompiledLoad<T>], phi: f64, states: &[LinkState<T>]) -> T {
    loads
        .iter()
        .filter(|l| l.acts_at(phi))
        .map(|l| {
            let s = of(states, l.link);
            match l.kind {
                LoadKind::Force(f) => dot(f, s.velocity_at(s.position(l.local))),
                LoadKind::Torque(t) => t * s.omega,
            }
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn load(active: [f64; 2], periodic: bool) -> CompiledLoad {
        CompiledLoad {
            link: 1,
            point: None,
            local: [0.0; 2],
            kind: LoadKind::Torque(1.0),
            active: Some(active),
            periodic,
        }
    }

    /// A forward stroke from 292° to 68° wraps through 0°: active at 300°, 0°, 60° and
    /// 360° + 10°, not at 100° or 200°.
    #[test]
    fn angle_ranges_wrap_around_a_turn() {
        let l = load([292f64.to_radians(), 68f64.to_radians()], true);
        for deg in [300.0f64, 0.0, 60.0, 370.0, -50.0] {
            assert!(l.acts_at(deg.to_radians()), "{deg}°");
        }
        for deg in [100.0f64, 200.0, 460.0] {
            assert!(!l.acts_at(deg.to_radians()), "{deg}°");
        }
    }

    /// A displacement range does not wrap.
    #[test]
    fn displacement_ranges_are_plain_intervals() {
        let l = load([0.1, 0.2], false);
        assert!(l.acts_at(0.1) && l.acts_at(0.15) && l.acts_at(0.2));
        assert!(!l.acts_at(0.0) && !l.acts_at(0.25) && !l.acts_at(0.1 + std::f64::consts::TAU));
    }
}
