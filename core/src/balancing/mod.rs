//! Balancing: rotors in one and two planes ([`rotor`]), counterweights for linkages from
//! the shaking force ([`linkage`]), and the slider-crank's primary and secondary unbalance
//! ([`slider_crank`]).

pub mod linkage;
pub mod rotor;
pub mod slider_crank;

pub use linkage::{
    Counterweight, LinkageBalance, LinkageBalancing, LinkageSweep, PlacedCounterweight,
    balance_linkage, check_balance_request,
};
pub use rotor::{Correction, CouplePlane, Polygons, Rotor, RotorMass, TwoPlaneBalance};
pub use slider_crank::{PartialBalance, SliderCrankUnbalance};
