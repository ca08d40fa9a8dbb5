//! The pictures of one run of a scene: the diagram of its columns, the drawings of its
//! mechanism, written to a folder (`mechdiff run scene.toml --plot DIR`).

use std::path::{Path, PathBuf};

use super::decimate::{decimate, sample};
use super::diagram::{Diagram, Marker, MarkerKind, Panel, Polar, Series};
use super::drawing::Drawing;
use super::scene::{Poses, Rig, plot_positions, poses, sketch_pose};
use super::symbols::symbol;
use super::vectors::Vectors;
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::scene::build::mechanism;
use crate::scene::model::OutputKind;
use crate::scene::outputs::Column;
use crate::scene::run::Report;

/// Drawn points per curve: about four per bucket, one bucket per pixel column or two.
pub const BUCKETS: usize = 800;
/// Poses solved for the traced paths and the report's animation, at most.
pub const FRAMES: usize = 721;

/// A group of columns drawn in one panel, with the names that select it in `[plot] panels`.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// Column indices (into the report's columns).
    pub columns: Vec<usize>,
    /// The output (or dynamic output) it belongs to.
    pub output: String,
}

/// The report's columns after the drive, grouped into panels: one per quantity of each output
/// (x and y of a point together), then the dynamic columns, consecutive columns of one unit
/// together.
pub fn groups(scene: &Scene, report: &Report) -> Vec<Group> {
    let mut groups = Vec::new();
    let mut k = 1;
    for output in &scene.outputs {
        let per = if matches!(output.kind, OutputKind::Point(_)) {
            2
        } else {
            1
        };
        for _ in &output.quantities {
            groups.push(Group {
                columns: (k..k + per).collect(),
                output: output.name.clone(),
            });
            k += per;
        }
    }
    let columns = &report.columns;
    while k < columns.len() {
        let start = k;
        while k + 1 < columns.len()
            && columns[k + 1].unit == columns[start].unit
            && k + 1 - start < 3
        {
            k += 1;
        }
        groups.push(Group {
            columns: (start..=k).collect(),
            output: "dynamics".to_owned(),
        });
        k += 1;
    }
    groups
}

/// The groups chosen by `[plot] panels`: a name selects the groups of the output of that
/// name, or the column of that name alone. Without `[plot] panels`, every group, less the
/// columns that are zero at every row (a picture-only rule: the table and CSV keep them).
pub fn selected(scene: &Scene, report: &Report) -> Result<Vec<Group>> {
    let all = groups(scene, report);
    let Some(panels) = &scene.plot.panels else {
        let zero = |c: usize| report.rows.iter().all(|r| r[c] == 0.0);
        return Ok(all
            .into_iter()
            .filter_map(|mut g| {
                g.columns.retain(|&c| !zero(c));
                (!g.columns.is_empty()).then_some(g)
            })
            .collect());
    };
    let mut chosen: Vec<Group> = Vec::new();
    for (name, location) in panels {
        let by_output: Vec<Group> = all.iter().filter(|g| g.output == *name).cloned().collect();
        let matching: Vec<Group> = if by_output.is_empty() {
            all.iter()
                .filter_map(|g| {
                    let c = g
                        .columns
                        .iter()
                        .find(|&&c| report.columns[c].name == *name)?;
                    Some(Group {
                        columns: vec![*c],
                        output: g.output.clone(),
                    })
                })
                .collect()
        } else {
            by_output
        };
        if matching.is_empty() {
            let mut known: Vec<String> = scene.outputs.iter().map(|o| o.name.clone()).collect();
            known.extend(report.columns.iter().skip(1).map(|c| c.name.clone()));
            known.dedup();
            return Err(Error::Invalid {
                location: location.clone(),
                message: format!(
                    "`[plot] panels` names `{name}`, which is neither an output nor a column; \
                     the outputs and columns are: {}",
                    known.join(", ")
                ),
            });
        }
        for g in matching {
            if !chosen.contains(&g) {
                chosen.push(g);
            }
        }
    }
    Ok(chosen)
}

/// The values of column `c` against the drive, in printed units, decimated for drawing, with
/// their exact slopes where the table has the column's derivative with respect to the drive
/// (`psi'` beside `psi`, `x_C''` beside `x_C'`, `J_red'` beside `J_red`).
pub(crate) fn curve(report: &Report, c: usize) -> (Vec<[f64; 2]>, Option<Vec<f64>>) {
    let (x, y) = (&report.columns[0], &report.columns[c]);
    // Row indices of the decimated points (exact in f64 below 2⁵³ rows).
    let kept = decimate(
        report
            .rows
            .iter()
            .enumerate()
            .map(|(k, r)| [k as f64, r[c] / y.factor]),
        report.rows.len(),
        BUCKETS,
    );
    let rows = || kept.iter().map(|p| &report.rows[p[0] as usize]);
    let points = rows().map(|r| [r[0] / x.factor, r[c] / y.factor]).collect();
    let slopes = derivative_column(report, c).map(|d| {
        // dy/dx in printed units: (dY/dφ in SI) · (SI per printed x) / (SI per printed y).
        rows().map(|r| r[d] * x.factor / y.factor).collect()
    });
    (points, slopes)
}

/// The column holding column `c`'s derivative with respect to the drive, if the table has it
/// and the first column is the drive (`phi`, or a cam drive's `theta`).
fn derivative_column(report: &Report, c: usize) -> Option<usize> {
    let columns = &report.columns;
    if !matches!(columns[0].name.as_str(), "phi" | "theta") {
        return None;
    }
    let name = format!("{}'", columns[c].name);
    columns.iter().position(|d| d.name == name)
}

/// `name [unit]` for a panel's y axis: the columns' symbols joined, one unit.
fn label(columns: &[&Column]) -> String {
    let names: Vec<String> = columns.iter().map(|c| symbol(&c.name)).collect();
    format!("{} [{}]", names.join(", "), columns[0].unit)
}

/// The diagram of a run: the selected panels against the drive position, the dead positions
/// and the limits the sweep reaches marked, and polar panels for every force given by its x
/// and y components (joint reactions `Fx_j`/`Fy_j`, inertial forces, the shaking force
/// `SumF_x`/`SumF_y`).
pub fn diagram(scene: &Scene, report: &Report) -> Result<Diagram> {
    let drive = &report.columns[0];
    let title = scene.title.clone().unwrap_or_else(|| scene.file.clone());
    let mut d = Diagram::new(&title, &format!("φ [{}]", drive.unit));
    let chosen = selected(scene, report)?;
    for g in &chosen {
        let columns: Vec<&Column> = g.columns.iter().map(|&c| &report.columns[c]).collect();
        let mut panel = Panel::new(&label(&columns));
        for &c in &g.columns {
            let name = symbol(&report.columns[c].name);
            panel = match curve(report, c) {
                (points, Some(slopes)) => panel.series_with_slopes(&name, points, slopes),
                (points, None) => panel.series(&name, points),
            };
        }
        d = d.panel(panel);
    }
    for dead in &report.dead_positions {
        for p in &dead.positions {
            let label = format!("{}: dead", symbol(&dead.output));
            d = d.marker(Marker::new(p.phi / drive.factor, &label, MarkerKind::Dead));
        }
    }
    for l in &report.limits {
        let label = crate::scene::sweep_limits::kind_words(l.limit.kind);
        d = d.marker(Marker::new(
            l.limit.phi / drive.factor,
            label,
            MarkerKind::Limit,
        ));
    }
    // Polar panels pair the x and y columns of a force, zero or not.
    let pairs = if scene.plot.panels.is_none() {
        groups(scene, report)
    } else {
        chosen
    };
    for g in &pairs {
        for pair in g.columns.windows(2) {
            let (a, b) = (&report.columns[pair[0]], &report.columns[pair[1]]);
            let title = if a.name == "SumF_x" && b.name == "SumF_y" {
                Some("shaking force ΣF on the frame".to_owned())
            } else {
                match (a.name.strip_prefix("Fx_"), b.name.strip_prefix("Fy_")) {
                    (Some(s), Some(t)) if s == t => Some(format!("force {s}")),
                    _ => None,
                }
            };
            if let Some(title) = title {
                let points = decimate(
                    report
                        .rows
                        .iter()
                        .map(|r| [r[pair[0]] / a.factor, r[pair[1]] / b.factor]),
                    report.rows.len(),
                    BUCKETS,
                );
                d = d.polar(Polar {
                    title,
                    unit: a.unit.clone(),
                    series: vec![Series::new(&a.name, points)],
                });
            }
        }
    }
    Ok(d)
}

/// Everything the pictures of a run need: the poses over the sweep (at most [`FRAMES`]), the
/// rig, the traced points, the framing extent.
#[derive(Debug, Clone)]
pub struct Animation {
    /// Row indices of the report that are drawn.
    pub rows: Vec<usize>,
    /// The poses at those rows.
    pub poses: Poses,
    /// How the mechanism is drawn.
    pub rig: Rig,
    /// Traced points (indices into the scene's points).
    pub traced: Vec<usize>,
}

impl Animation {
    /// Solves the poses of the run at up to [`FRAMES`] rows spread over the sweep.
    pub fn of(scene: &Scene, report: &Report) -> Result<Animation> {
        let m = mechanism(scene)?;
        let rows = sample(report.rows.len(), FRAMES);
        let phi: Vec<f64> = rows.iter().map(|&r| report.rows[r][0]).collect();
        let poses = poses(scene, &m, &phi)?;
        let index = |name: &str| scene.points.iter().position(|p| p.name == name);
        let traced = match &scene.plot.trace {
            Some(names) => names.iter().filter_map(|n| index(n)).collect(),
            None => scene
                .outputs
                .iter()
                .filter_map(|o| match &o.kind {
                    OutputKind::Point(p) => index(p),
                    _ => None,
                })
                .collect(),
        };
        Ok(Animation {
            rows,
            poses,
            rig: Rig::of(scene),
            traced,
        })
    }

    /// Every point of every pose and of the sketch: the extent every drawing is framed to.
    pub fn extent(&self, scene: &Scene) -> Vec<[f64; 2]> {
        let mut all: Vec<[f64; 2]> = self.poses.xy.iter().flatten().copied().collect();
        all.extend(sketch_pose(scene));
        all
    }

    /// The traced paths over the sweep.
    pub fn paths(&self) -> Vec<(usize, Vec<[f64; 2]>)> {
        self.traced
            .iter()
            .map(|&k| (k, self.poses.path(k)))
            .collect()
    }

    /// The drawing of the mechanism at `pose`, with the traced paths, titled `title`.
    pub fn drawing(&self, scene: &Scene, title: &str, pose: &[[f64; 2]]) -> Drawing {
        self.rig
            .drawing(scene, title, pose, &self.extent(scene), &self.paths())
    }
}

/// The drawings of a run: at the sketch pose, then at each `[plot]` position (checked to lie
/// inside the sweep), each with the traced paths; with the names of their files.
pub fn drawings(
    scene: &Scene,
    report: &Report,
    animation: &Animation,
) -> Result<Vec<(String, Drawing)>> {
    let name = scene.title.clone().unwrap_or_else(|| scene.file.clone());
    let sketch = sketch_pose(scene);
    let mut out = vec![(
        "mechanism_sketch".to_owned(),
        with_mass_centres(
            animation.drawing(scene, &format!("{name} — sketch pose"), &sketch),
            scene,
            &sketch,
        ),
    )];
    let (lo, hi) = report
        .rows
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), r| {
            (lo.min(r[0]), hi.max(r[0]))
        });
    let positions = plot_positions(scene, lo, hi)?;
    if let Some((_, location)) = &scene.plot.vectors
        && positions.is_empty()
    {
        return Err(Error::Invalid {
            location: location.clone(),
            message: "`[plot] vectors` are drawn at the `[plot] positions`; name at least one \
                      position there"
                .to_owned(),
        });
    }
    if !positions.is_empty() {
        let m = mechanism(scene)?;
        // Solved in sweep order from the sketch, as the run went.
        let mut order: Vec<usize> = (0..positions.len()).collect();
        order.sort_by(|&a, &b| positions[a].total_cmp(&positions[b]));
        let sorted: Vec<f64> = order.iter().map(|&k| positions[k]).collect();
        let poses = poses(scene, &m, &sorted)?;
        let vectors = Vectors::of(scene, &m, &sorted, &animation.extent(scene))?;
        for (k, pose) in poses.xy.iter().enumerate() {
            let text = scene.drive_text(sorted[k]);
            let drawing = with_mass_centres(
                animation.drawing(scene, &format!("{name} — φ = {text}"), pose),
                scene,
                pose,
            );
            out.push((
                format!("mechanism_at_{}", text.replace(' ', "_")),
                match &vectors {
                    Some(v) => v.drawn(drawing, k, pose),
                    None => drawing,
                },
            ));
        }
    }
    Ok(out)
}

/// The drawing with the centres of mass of `[masses]` at `pose` (the still drawings only: the
/// report's animation does not move them yet).
fn with_mass_centres(drawing: Drawing, scene: &Scene, pose: &[[f64; 2]]) -> Drawing {
    Rig::mass_centres(scene, pose)
        .into_iter()
        .fold(drawing, Drawing::mass_centre)
}

/// Writes the pictures of a run into `dir` (created if missing): `diagram.svg/png` (and
/// `diagram_2.svg/png`, … when the diagram is higher than [`super::diagram::MAX_HEIGHT`]),
/// one `mechanism_*.svg/png` per drawing, one `path_<point>.svg/png/csv` per traced point
/// (its coupler curve, [`super::path`]), and `report.html` (with the whole diagram). Returns the files written. If any
/// of them is one of the run's inputs (a scene named `report.html`), nothing is written.
pub fn write_dir(scene: &Scene, report: &Report, dir: &Path) -> Result<Vec<PathBuf>> {
    let diagram = diagram(scene, report)?;
    let whole = diagram.to_svg()?;
    let pages = diagram.named_pages("diagram");
    let animation = Animation::of(scene, report)?;
    let mut pictures = drawings(scene, report, &animation)?
        .into_iter()
        .map(|(name, drawing)| (name, drawing.to_svg()))
        .collect::<Vec<_>>();
    pictures.extend(super::balancing::pictures(scene, report)?);
    let paths = super::path::plots(scene, report, &animation.poses, &animation.traced)?;
    pictures.extend(paths.iter().map(|p| (p.name.clone(), p.drawing.to_svg())));
    let html = super::report::html(scene, report, &animation, &whole)?;
    for (name, page) in pages.iter().rev() {
        let svg = if pages.len() == 1 {
            whole.clone()
        } else {
            page.to_svg()?
        };
        pictures.insert(0, (name.clone(), svg));
    }
    write_folder(dir, &pictures, &html, &paths)
}

/// Writes a `--plot` folder: each picture as SVG and PNG, `report.html`, and each coupler
/// curve's CSV, after refusing any of those names that is an input of the run. Returns the
/// files written.
pub(crate) fn write_folder(
    dir: &Path,
    pictures: &[(String, String)],
    html: &str,
    paths: &[super::path::PathPlot],
) -> Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (name, _) in pictures {
        written.push(dir.join(format!("{name}.svg")));
        written.push(dir.join(format!("{name}.png")));
    }
    let pngs = written.len();
    written.push(dir.join("report.html"));
    written.extend(paths.iter().map(|p| dir.join(format!("{}.csv", p.name))));
    crate::files::refuse_inputs(written.iter().map(PathBuf::as_path))?;
    crate::files::create_output_folder(dir)?;
    for ((_, svg), files) in pictures.iter().zip(written[..pngs].chunks(2)) {
        super::write_file(&files[0], svg.as_bytes())?;
        super::raster::write_png(svg, &files[1])?;
    }
    super::write_file(&dir.join("report.html"), html.as_bytes())?;
    for p in paths {
        super::write_file(&dir.join(format!("{}.csv", p.name)), p.csv.as_bytes())?;
    }
    Ok(written)
}
