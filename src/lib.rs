//! # mechdiff
//!
//! Kinematics and dynamics of planar mechanisms in which nobody derives a derivative by hand.
//!
//! # The library: a scene in, columns out
//!
//! A scene file describes a mechanism by its geometry (see `docs/scene-format.md`). Read it
//! with [`load`] or [`parse`] (or [`load_with`] and [`parse_with`], with [`Setting`]s that
//! replace values of its `[parameters]`), [`run`] it to a [`Report`] of [`Column`]s and
//! rows ([`run_with`] and [`RunOptions`]: by the run-time evaluator), or stream its rows to
//! [`Sinks`] ([`stream::run`]); [`sensitivity::run`] adds the
//! derivative columns `d(COLUMN)/d(PARAMETER)` a `[sensitivity]` table asks for, exact where
//! the exact route reaches ([`Study`] says which). Every failure is an [`Error`] saying what
//! is wrong and where.
//!
//! ```
//! use mechdiff::{Report, Scene, Setting};
//!
//! // Norton's four-bar, its coupler b lengthened from 1.85 m to 1.9 m.
//! let b = Setting { name: "b".into(), value: "1.9".into() };
//! let scene: Scene = mechdiff::load_with("scenes/norton_four_bar.toml", &[b.clone()])?;
//! let report: Report = mechdiff::run(&scene)?;
//! assert_eq!(report.columns[0].name, "phi"); // the drive first, then the outputs
//! assert_eq!(report.rows.len(), 11); // 0° to 100° by 10°
//!
//! // The rocker's angle ψ from the triangle A–B–O4 solved by hand, B on the left of A → O4.
//! let psi_by_hand = |phi: f64, b: f64| {
//!     let (a, c, d) = (0.86, 0.86, 2.22);
//!     let (ax, ay) = (a * phi.cos(), a * phi.sin());
//!     let l = (d - ax).hypot(ay);
//!     let (ux, uy) = ((d - ax) / l, -ay / l);
//!     let x = (b * b - c * c + l * l) / (2.0 * l);
//!     let h = (b * b - x * x).sqrt();
//!     let (bx, by) = (ax + x * ux - h * uy, ay + x * uy + h * ux);
//!     by.atan2(bx - d)
//! };
//! let phi = report.column("phi").unwrap();
//! let psi = report.column("psi").unwrap();
//! for (&phi, &psi) in phi.iter().zip(&psi) {
//!     // The same to rounding: 1e-12 rad for lengths of order 1.
//!     assert!((psi - psi_by_hand(phi, 1.9)).abs() < 1e-12, "ψ = {psi} at φ = {phi}");
//! }
//!
//! // The exact dψ/db: the file's text with a `[sensitivity]` table added.
//! let text = std::fs::read_to_string("scenes/norton_four_bar.toml").unwrap()
//!     + "\n[sensitivity]\ncolumns = [\"d(psi)/d(b)\"]\n";
//! let options = mechdiff::sensitivity::Options::default();
//! let (_, report, study) = mechdiff::sensitivity::run("norton.toml", &text, &[b], &options)?;
//! assert!(study.unwrap().derivatives[0].is_exact());
//! let dpsi_db = report.column("d(psi)/d(b)").unwrap();
//! for (&phi, &exact) in phi.iter().zip(&dpsi_db) {
//!     // A central difference of the hand solution, step 1e-5 m: its truncation (h²/6 ψ‴)
//!     // and rounding (ε/h) are both about 1e-11; 1e-8 rad/m leaves room.
//!     let h = 1e-5;
//!     let difference = (psi_by_hand(phi, 1.9 + h) - psi_by_hand(phi, 1.9 - h)) / (2.0 * h);
//!     assert!((exact - difference).abs() < 1e-8, "dψ/db = {exact} at φ = {phi}");
//! }
//! # Ok::<(), mechdiff::Error>(())
//! ```
//!
//! # The rest
//!
//! The facade also re-exports the derivative core ([`core`]), the closed-form mechanisms
//! ([`mechanisms`]) and the [`derivatives`] attribute, and holds what the `mechdiff`
//! command-line tool does: scene files ([`scene`]), reports ([`report`]), code generation
//! ([`codegen`]) and the care of the user's files ([`files`]).
//!
//! # Features
//!
//! All on by default; a library user who needs none of them writes
//! `mechdiff = { version = "0.1", default-features = false }`.
//!
//! - `cli`: the `mechdiff` binary's command line (clap); implies `pictures`.
//! - `pictures`: diagrams, drawings, the HTML report and PNG files (plotters, resvg):
//!   `pictures`, `accuracy::plot`.
//! - `parallel`: streamed sweeps and Monte-Carlo samples on several threads (rayon); without
//!   it the same work runs in order, with the same bytes.
//! - `progress`: the progress bar of a long streamed run (indicatif).
#![cfg_attr(docsrs, feature(doc_cfg))]

pub mod accuracy;
pub mod codegen;

pub use mechdiff_core as core;
pub use mechdiff_mechanisms as mechanisms;

/// Symbolic derivatives generated at compile time (see `mechdiff_macros::derivatives`). The
/// generated code names `::mechdiff_core::Jet`, so the calling crate depends on
/// `mechdiff-core` as well.
pub use mechdiff_macros::derivatives;

pub mod error;
pub mod escape;
pub mod evaluator;
pub mod files;
pub mod import;
mod parallel;
#[cfg(feature = "pictures")]
pub mod pictures;
mod progress;
pub mod report;
pub mod scene;
pub mod sensitivity;
pub mod stream;

pub use error::{Error, Result};
pub use scene::launch::{run, run_between, run_with};
pub use scene::outputs::Column;
pub use scene::parameters::Setting;
pub use scene::{Report, RunOptions, Scene, load, load_with, parse, parse_with};
pub use sensitivity::Study;
pub use stream::{Sink, Sinks};

/// The Rust examples of `README.md`, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
