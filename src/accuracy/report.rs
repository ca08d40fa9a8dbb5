//! The measured report: per method, errors per order and time per drive position; the text
//! table, the CSV and the Pareto front.

use std::fmt::Write as _;

use super::differences::StepScan;
use super::method::{EPSILON, Failure, Kind, MAX_ORDER, Method, Values};
use crate::Error;
use crate::report::Table;
use crate::stream::record::csv_quoted;

/// One method's errors and time.
#[derive(Clone, Debug, PartialEq)]
pub struct Measurement {
    /// The method's name.
    pub name: String,
    /// Exact, or approximate with its step.
    pub kind: Kind,
    /// The highest order computed.
    pub order: usize,
    /// `errors[position][order]`: the scaled error, max over the outputs (NaN above
    /// [`Measurement::order`]).
    pub errors: Vec<Values>,
    /// Per order: the max scaled error over the sweep (NaN above the order).
    pub max: Values,
    /// Per order: the root mean square of the scaled error over the sweep.
    pub rms: Values,
    /// Per order: the index of the drive position where the error is largest.
    pub worst: [usize; MAX_ORDER + 1],
    /// Time per drive position (s): median, fastest and slowest repeat.
    pub time: [f64; 3],
    /// Where the method first returned NaN or an infinite value, if it did.
    pub failure: Option<Failure>,
}

impl Measurement {
    pub(super) fn new(
        method: &Method<'_>,
        errors: Vec<Values>,
        failure: Option<Failure>,
        time: [f64; 3],
    ) -> Self {
        let mut max = [f64::NAN; MAX_ORDER + 1];
        let mut rms = [f64::NAN; MAX_ORDER + 1];
        let mut worst = [0; MAX_ORDER + 1];
        for k in 0..=method.order.min(MAX_ORDER) {
            let mut m = 0.0f64;
            for (i, e) in errors.iter().enumerate() {
                if e[k] > m {
                    (m, worst[k]) = (e[k], i);
                }
            }
            max[k] = m;
            // Scaled by the max, so that errors near 1e160 do not overflow their squares; NaN
            // (not counted: a jump of the function under a finite difference) left out.
            let counted = errors.iter().filter(|e| !e[k].is_nan());
            rms[k] = if m > 0.0 && m.is_finite() {
                let (sum, count) = counted.fold((0.0, 0usize), |(s, c), e| {
                    (s + (e[k] / m) * (e[k] / m), c + 1)
                });
                m * (sum / count.max(1) as f64).sqrt()
            } else {
                m
            };
        }
        Measurement {
            name: method.name.clone(),
            kind: method.kind,
            order: method.order,
            errors,
            max,
            rms,
            worst,
            time,
            failure,
        }
    }

    /// The max scaled error over the orders 0 … `order` (or over all the method computes if
    /// it computes fewer).
    pub fn max_error_to(&self, order: usize) -> f64 {
        self.max[..=order.min(self.order)]
            .iter()
            .fold(0.0, |a: f64, &b| a.max(b))
    }

    /// Digits lost: log₁₀(max error / ε) over every order computed, at least 0.
    pub fn digits_lost(&self) -> f64 {
        (self.max_error_to(MAX_ORDER) / EPSILON).log10().max(0.0)
    }

    /// Whether the method is exact (not a finite difference).
    pub fn is_exact(&self) -> bool {
        self.kind == Kind::Exact
    }
}

/// Everything `mechdiff accuracy` prints and plots for one case.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// What was measured.
    pub title: String,
    /// Lines under the title: the reference, what was left out and why.
    pub notes: Vec<String>,
    /// The drive positions (rad).
    pub positions: Vec<f64>,
    /// One per method, exact methods first.
    pub measurements: Vec<Measurement>,
    /// The finite-difference step scans.
    pub scans: Vec<StepScan>,
}

/// Orders a Pareto comparison is made over: value, ′ and ″ (what forces need).
pub const PARETO_ORDER: usize = 2;

impl Report {
    pub(super) fn new(
        title: String,
        notes: Vec<String>,
        positions: Vec<f64>,
        measurements: Vec<Measurement>,
        scans: Vec<StepScan>,
    ) -> Self {
        Report {
            title,
            notes,
            positions,
            measurements,
            scans,
        }
    }

    /// The median time per position of the fastest exact method (s).
    pub fn fastest_exact(&self) -> Option<f64> {
        self.measurements
            .iter()
            .filter(|m| m.is_exact())
            .map(|m| m.time[0])
            .min_by(f64::total_cmp)
    }

    /// `Ok` if no method returned NaN or an infinite value, else the first that did.
    ///
    /// # Errors
    /// [`Error::MethodNotFinite`] naming the method, output, order and drive position.
    pub fn check_finite(&self) -> Result<(), Error> {
        match self
            .measurements
            .iter()
            .find_map(|m| Some((m, m.failure.as_ref()?)))
        {
            None => Ok(()),
            Some((m, f)) => Err(Error::MethodNotFinite {
                method: m.name.clone(),
                output: f.output.clone(),
                order: f.order,
                phi: f.phi,
                value: f.value,
            }),
        }
    }

    /// The methods (indices) on the Pareto front of time against the max error over value,
    /// ′ and ″, among the methods computing at least ″ that were timed: no other is both
    /// faster and more accurate.
    pub fn pareto_front(&self) -> Vec<usize> {
        let candidates: Vec<usize> = (0..self.measurements.len())
            .filter(|&i| {
                let m = &self.measurements[i];
                m.order >= PARETO_ORDER && m.time[0].is_finite()
            })
            .collect();
        let point = |i: usize| {
            let m = &self.measurements[i];
            (m.time[0], m.max_error_to(PARETO_ORDER))
        };
        candidates
            .iter()
            .copied()
            .filter(|&i| {
                let (t, e) = point(i);
                !candidates.iter().any(|&j| {
                    let (tj, ej) = point(j);
                    j != i && tj <= t && ej <= e && (tj < t || ej < e)
                })
            })
            .collect()
    }

    /// The aligned text table: method, time per position (median, spread), ratio to the
    /// fastest exact method, max/RMS scaled error per order, digits lost and where; then
    /// the finite-difference step scans with their minima.
    pub fn table(&self) -> String {
        let fastest = self.fastest_exact().unwrap_or(f64::NAN);
        let front = self.pareto_front();
        let mut table = Table::new(
            1,
            [
                "method",
                "ns/position",
                "spread",
                "ratio",
                "value max/rms",
                "′ max/rms",
                "″ max/rms",
                "‴ max/rms",
                "digits lost",
                "worst at φ [°]",
            ]
            .map(String::from)
            .to_vec(),
        );
        for (i, m) in self.measurements.iter().enumerate() {
            let worst_order = (0..=m.order)
                .max_by(|&a, &b| m.max[a].total_cmp(&m.max[b]))
                .unwrap_or(0);
            let mut name = m.name.clone();
            if front.contains(&i) {
                name.push_str(" *");
            }
            let mut row = vec![
                name,
                format!("{:.1}", m.time[0] * 1e9),
                format!("{:.1}–{:.1}", m.time[1] * 1e9, m.time[2] * 1e9),
                format!("{:.2}", m.time[0] / fastest),
            ];
            row.extend((0..=MAX_ORDER).map(|k| {
                if k <= m.order {
                    format!("{:.1e}/{:.1e}", m.max[k], m.rms[k])
                } else {
                    "—".into()
                }
            }));
            row.push(format!("{:.1}", m.digits_lost()));
            let worst = self.positions[m.worst[worst_order]].to_degrees();
            row.push(if worst.abs() < 1e7 {
                format!("{worst:.2}")
            } else {
                format!("{worst:.3e}")
            });
            table.row(row);
        }
        let mut out = format!("{}\n", self.title);
        for note in &self.notes {
            let _ = writeln!(out, "  {note}");
        }
        out.push('\n');
        out.push_str(&table.render());
        out.push_str(
            "\nscaled error: |x − x_ref| / max over the sweep of |x_ref| (reference: extended \
             precision, see the title); digits lost: log10(max error / 2.2e-16); * on the Pareto \
             front of time against the error of value, ′, ″; ratio: time / fastest exact \
             method's time, all timed in this one process.\n",
        );
        for m in &self.measurements {
            match &m.failure {
                Some(Failure {
                    reason: Some(reason),
                    phi,
                    ..
                }) => {
                    let _ = writeln!(
                        out,
                        "FAILED: {} at φ = {phi:e} rad: {reason}; its errors there count as \
                         infinite, and it is not timed",
                        m.name
                    );
                }
                Some(f) => {
                    let _ = writeln!(
                        out,
                        "FAILED: {} returned {} for {} (order {}) at φ = {:e} rad; its errors \
                         there count as infinite",
                        m.name, f.value, f.output, f.order, f.phi
                    );
                }
                None => {}
            }
        }
        out.push_str(&self.scan_table());
        out
    }

    /// The step scans as a table: h, then each scheme's max scaled error for ′, ″, ‴, with
    /// the minimum of each column marked `<`.
    pub fn scan_table(&self) -> String {
        let Some(first) = self.scans.first() else {
            return String::new();
        };
        let mut header = vec!["h".to_owned()];
        for scan in &self.scans {
            for p in ["′", "″", "‴"] {
                header.push(format!("{} {p}", scan.scheme.name()));
            }
        }
        let mut table = Table::new(1, header);
        for (j, h) in first.steps.iter().enumerate() {
            let mut row = vec![format!("{h:.2e}")];
            for scan in &self.scans {
                for k in 0..MAX_ORDER {
                    let e = scan.errors[j][k];
                    let mark = if scan.best[k].0 == *h { " <" } else { "  " };
                    row.push(format!("{e:.1e}{mark}"));
                }
            }
            table.row(row);
        }
        let mut out = String::from(
            "\nfinite differences: max scaled error against the step h (< marks the minimum \
             of each column, found on this grid)\n",
        );
        out.push_str(&table.render());
        for scan in &self.scans {
            let _ = writeln!(
                out,
                "{}: best h {}",
                scan.scheme.name(),
                scan.best
                    .iter()
                    .zip(["′", "″", "‴"])
                    .map(|((h, e), p)| format!("{p} {h:.1e} (error {e:.1e})"))
                    .collect::<Vec<_>>()
                    .join(", ")
            );
        }
        out
    }

    /// The report as CSV: one row per method (kind `exact` or `difference`), then one per
    /// scanned step (kind `scan`, no time). Errors are scaled; times in seconds per position.
    pub fn csv(&self) -> String {
        let fastest = self.fastest_exact().unwrap_or(f64::NAN);
        let mut out = String::from(
            "method,kind,step,order,time_median_s,time_min_s,time_max_s,ratio,\
             max_value,max_d1,max_d2,max_d3,rms_value,rms_d1,rms_d2,rms_d3,digits_lost\n",
        );
        let number = |x: f64| {
            if x.is_nan() {
                String::new()
            } else {
                format!("{x:e}")
            }
        };
        for m in &self.measurements {
            let (kind, step) = match m.kind {
                Kind::Exact => ("exact", String::new()),
                Kind::Approximate { step } => ("difference", format!("{step:e}")),
            };
            let _ = writeln!(
                out,
                "{},{kind},{step},{},{},{},{},{},{},{},{}",
                csv_quoted(&m.name),
                m.order,
                number(m.time[0]),
                number(m.time[1]),
                number(m.time[2]),
                number(m.time[0] / fastest),
                m.max.map(number).join(","),
                m.rms.map(number).join(","),
                number(m.digits_lost()),
            );
        }
        for scan in &self.scans {
            for (h, e) in scan.steps.iter().zip(&scan.errors) {
                let _ = writeln!(
                    out,
                    "{},scan,{h:e},3,,,,,,{},,,,,",
                    csv_quoted(&format!("{} h={h:.2e}", scan.scheme.name())),
                    e.map(number).join(","),
                );
            }
        }
        out
    }
}
