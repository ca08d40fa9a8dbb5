//! The dynamic sections checked: mass properties in SI, the effects' data for
//! mechdiff-core, and the `[[dynamics]]` outputs (see `resolve`).

use mechdiff_core::dynamics::{Dynamics, Plan, Request};
use mechdiff_core::geometry::{Inertia, Mechanism};

use crate::error::Location;

use super::format::DynamicQuantity;

/// One checked `[[dynamics]]` output.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicsOutput {
    /// What it reports.
    pub quantity: DynamicQuantity,
    /// Joints (reactions) or links (inertial forces) it names; empty: all.
    pub names: Vec<String>,
    /// Where it is defined.
    pub location: Location,
}

/// The checked dynamic data and outputs of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneDynamics {
    /// Mass properties by link (SI).
    pub masses: Vec<(String, Inertia)>,
    /// The effects' data for mechdiff-core.
    pub data: Dynamics,
    /// The outputs, in column order.
    pub outputs: Vec<DynamicsOutput>,
}

impl SceneDynamics {
    /// The requests of the outputs.
    pub fn requests(&self) -> Vec<Request> {
        self.outputs
            .iter()
            .map(|o| match o.quantity {
                DynamicQuantity::ShakingForce | DynamicQuantity::InertialForces => {
                    Request::ShakingForce
                }
                DynamicQuantity::Reactions => Request::Reactions,
                DynamicQuantity::DriveTorque => Request::DriveTorque,
                DynamicQuantity::KineticEnergy => Request::KineticEnergy,
                DynamicQuantity::ReducedInertia => Request::ReducedInertia,
                DynamicQuantity::PowerBalance => Request::PowerBalance,
            })
            .collect()
    }

    /// The plan for `mechanism` (built with the masses).
    pub fn plan(&self, mechanism: &Mechanism) -> Plan {
        Plan::for_requests(&self.requests(), self.data.available(mechanism))
    }
}
