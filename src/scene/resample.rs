//! A scene with its sweep replaced by a list of positions (the Python package's
//! `Scene.run(positions=...)`): above the reading modules, which it uses, so that none of
//! them depends on it.

use crate::error::{Error, Result};

use super::Scene;
use super::drive::nearest_turn;
use super::limits;
use super::model::DriveKind;
use super::positions::{MAX_IN_MEMORY, Positions};

impl Scene {
    /// The scene with its sweep replaced by `positions`, given in the scene's units of the
    /// sweep variable (the drive's unit, or the unit of the `[sweep] of` output), as a
    /// `positions = [...]` list in the file would give them (the Python package's
    /// `Scene.run(positions=...)`).
    ///
    /// ```
    /// let scene = mechdiff::load("scenes/norton_four_bar.toml")?;
    /// let two = scene.with_positions(&[5.0, 15.0])?; // the file's unit: deg
    /// let report = mechdiff::run(&two)?;
    /// assert_eq!(report.rows.len(), 2);
    /// // 15 deg in rad, to rounding of the conversion (1e-15 rad).
    /// assert!((report.rows[1][0] - 15f64.to_radians()).abs() < 1e-15);
    /// # Ok::<(), mechdiff::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::OverLimit`] for more than 10⁶ positions (a run in memory holds every row);
    /// [`Error::Invalid`] (at `[drive]`) for no position or one that is not finite, naming
    /// its index, or for a single position where an output searches its dead positions.
    pub fn with_positions(&self, positions: &[f64]) -> Result<Scene> {
        if positions.len() > MAX_IN_MEMORY {
            return Err(Error::OverLimit {
                option: "positions",
                value: positions.len() as u64,
                limit: MAX_IN_MEMORY as u64,
                what: "drive positions in one run in memory",
                advice: "run the positions in several parts, or stream them with the \
                         command line's `--csv`",
            });
        }
        let invalid = |message: String| Error::Invalid {
            location: self.drive.location.clone(),
            message,
        };
        if positions.is_empty() {
            return Err(invalid(
                "no drive position given; expected at least one".to_owned(),
            ));
        }
        let dimension = match self.sweep_of {
            Some(k) => self.outputs[k].kind.dimension(),
            None => self.drive.kind.dimension(),
        };
        let mut si = Vec::with_capacity(positions.len());
        for (i, &p) in positions.iter().enumerate() {
            if !p.is_finite() {
                return Err(invalid(format!(
                    "drive position {i} (from 0) is {p}; expected a finite number in {}",
                    self.units.symbol(dimension)
                )));
            }
            let value = self.units.to_si(p, dimension);
            let largest = limits::largest(dimension);
            if value.abs() > largest {
                let unit = self.units.symbol(dimension);
                return Err(invalid(format!(
                    "drive position {i} (from 0) is {p} {unit}, out of range; expected at \
                     most {} {unit} in size",
                    largest / self.units.factor(dimension)
                )));
            }
            si.push(value);
        }
        let mut scene = self.clone();
        if let Some(output) = scene.outputs.iter().find(|o| o.dead_positions)
            && si.iter().all(|&p| p == si[0])
        {
            return Err(invalid(format!(
                "output `{}` searches its dead positions, which needs a range of drive \
                 positions; give at least two different positions",
                output.name
            )));
        }
        if scene.drive.kind == DriveKind::Angle
            && scene.sweep_of.is_none()
            && scene.drive.cam.is_none()
        {
            scene.drive.at_sketch = nearest_turn(scene.drive.at_sketch, si[0]);
        }
        scene.positions = Positions::List(si);
        Ok(scene)
    }
}
