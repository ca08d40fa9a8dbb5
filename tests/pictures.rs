//! Pictures of every scene: diagrams, drawings and the HTML report are produced, render to
//! pixels that are not blank, frame the whole mechanism, and draw each joint where the
//! solver puts it; `[plot]` errors are located; a long sweep is drawn within a bounded size;
//! names that look like markup or hold control characters stay text (issue 22).

use std::path::{Path, PathBuf};
use std::process::Command;

use mechdiff::pictures::raster::{self, Raster};
use mechdiff::pictures::report::{MAX_BYTES, html};
use mechdiff::pictures::run::{Animation, diagram, drawings};
use mechdiff::pictures::{Frame, scene::sketch_pose};
use mechdiff::scene::{self, Report, Scene};

fn scenes() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        // Linkage scenes only (a rotor scene has no mechanism; balancing_scenes.rs draws it).
        .filter(|p| scene::kind(&std::fs::read_to_string(p).unwrap()) == scene::Kind::Linkage)
        .collect();
    files.sort();
    assert!(files.len() >= 8, "the scenes folder has its scenes");
    files
}

fn load(path: &Path) -> (Scene, Report) {
    let scene = scene::load(path).unwrap();
    let report = scene::run(&scene).unwrap();
    (scene, report)
}

/// The value of attribute `name` in the element text `tag` (`name="value"`).
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    let end = tag[start..].find('"')? + start;
    Some(&tag[start..end])
}

fn number(tag: &str, name: &str) -> f64 {
    attribute(tag, name)
        .unwrap_or_else(|| panic!("{name} in {tag}"))
        .parse()
        .unwrap()
}

/// The frame written on the `<svg>` element of a drawing.
fn frame(svg: &str) -> Frame {
    let head = &svg[..svg.find('>').unwrap()];
    Frame {
        scale: number(head, "data-scale"),
        origin_x: number(head, "data-origin-x"),
        origin_y: number(head, "data-origin-y"),
        width: number(head, "width"),
        height: number(head, "height"),
    }
}

/// Every drawn joint: its name and its model position read back from its pixel centre.
fn joints(svg: &str) -> Vec<(String, [f64; 2])> {
    let f = frame(svg);
    svg.match_indices("<circle class=\"joint\"")
        .map(|(at, _)| {
            let tag = &svg[at..at + svg[at..].find("/>").unwrap()];
            let name = attribute(tag, "data-point").unwrap().to_owned();
            (name, f.model([number(tag, "cx"), number(tag, "cy")]))
        })
        .collect()
}

/// The share of pixels that are not white.
fn inked(r: &Raster) -> f64 {
    let n = r
        .rgba
        .chunks(4)
        .filter(|p| p[..3] != [255, 255, 255])
        .count();
    n as f64 / (r.width as f64 * r.height as f64)
}

/// Whether the outermost `band` pixels of every side are all white (nothing cut off).
fn clear_border(r: &Raster, band: u32) -> bool {
    (0..r.height).all(|y| {
        (0..r.width).all(|x| {
            let edge = x < band || y < band || x >= r.width - band || y >= r.height - band;
            !edge || r.pixel(x, y).unwrap()[..3] == [255, 255, 255]
        })
    })
}

/// For every scene: the diagram, each drawing and the report are produced; the diagram and
/// drawings render to pixels of which a fair share is ink (at least 0.5 %: axes, curves and
/// bars; a blank or failed render has none); every point of the mechanism at every drawn pose
/// maps inside the picture and the outer band of pixels is white (the mechanism is not cut
/// off); the report is self-contained (no address it would load) and under its stated bound.
#[test]
fn every_scene_gets_its_diagram_drawings_and_report() {
    for path in scenes() {
        let (scene, report) = load(&path);
        let name = path.display().to_string();
        let d = diagram(&scene, &report).unwrap();
        assert!(!d.panels.is_empty(), "{name}: panels");
        let svg = d.to_svg().unwrap();
        let pixels = raster::render(&svg).unwrap();
        assert!(inked(&pixels) > 0.005, "{name}: the diagram is blank");
        let animation = Animation::of(&scene, &report).unwrap();
        let drawn = drawings(&scene, &report, &animation).unwrap();
        assert_eq!(drawn.len(), 1 + scene.plot.positions.len(), "{name}");
        for (title, drawing) in &drawn {
            let svg = drawing.to_svg();
            let pixels = raster::render(&svg).unwrap();
            assert!(inked(&pixels) > 0.005, "{name} {title}: blank");
            assert!(
                clear_border(&pixels, 2),
                "{name} {title}: cut off at the border"
            );
            let f = frame(&svg);
            let sketch = sketch_pose(&scene);
            let poses = animation.poses.xy.iter().chain([&sketch]);
            for p in poses.flatten() {
                let [x, y] = f.pixel(*p);
                assert!(
                    x > 0.0 && x < f.width && y > 0.0 && y < f.height,
                    "{name} {title}"
                );
            }
        }
        let page = html(&scene, &report, &animation, &svg).unwrap();
        assert!(
            page.len() < MAX_BYTES,
            "{name}: report of {} bytes",
            page.len()
        );
        for network in ["src=", "<link", "@import", "url("] {
            assert!(
                !page.contains(network),
                "{name}: the report loads `{network}`"
            );
        }
        let addresses = page.matches("http").count();
        let namespaces = page.matches("http://www.w3.org/2000/svg").count();
        assert_eq!(
            addresses, namespaces,
            "{name}: only SVG namespaces, no addresses"
        );
    }
}

/// The joints of the drawings are where the solver puts them: at the sketch pose, every point
/// at its sketch coordinates; at the first, a middle and the last frame of the sweep, every
/// `[[output]] point` at the run's own x and y columns. Read back from the pixel centres
/// through the frame on the `<svg>`, they agree to 1e-9 of the frame's width in model units
/// (the pixel coordinates are written with every digit; the mapping is a few f64 operations;
/// the run and the drawing solve the same positions on the same branch).
#[test]
fn drawn_joints_are_at_the_solver_positions() {
    for path in scenes() {
        let (scene, report) = load(&path);
        let name = path.display().to_string();
        let animation = Animation::of(&scene, &report).unwrap();
        let sketch = animation
            .drawing(&scene, "sketch", &sketch_pose(&scene))
            .to_svg();
        let tolerance = 1e-9 * frame(&sketch).width / frame(&sketch).scale;
        let drawn = joints(&sketch);
        assert_eq!(
            drawn.len(),
            scene.points.len(),
            "{name}: one ring per point"
        );
        for (point, at) in drawn {
            let p = scene.points.iter().find(|p| p.name == point).unwrap();
            let miss = (at[0] - p.sketch[0]).hypot(at[1] - p.sketch[1]);
            assert!(
                miss <= tolerance,
                "{name}: {point} off by {miss:e} at the sketch"
            );
        }
        let frames = animation.rows.len();
        for k in [0, frames / 2, frames - 1] {
            let svg = animation
                .drawing(&scene, "frame", &animation.poses.xy[k])
                .to_svg();
            let row = &report.rows[animation.rows[k]];
            for (point, at) in joints(&svg) {
                let column = |prefix: &str| {
                    let c =
                        (report.columns.iter()).position(|c| c.name == format!("{prefix}_{point}"));
                    c.map(|c| row[c])
                };
                if let (Some(x), Some(y)) = (column("x"), column("y")) {
                    let miss = (at[0] - x).hypot(at[1] - y);
                    assert!(
                        miss <= tolerance,
                        "{name}: {point} off by {miss:e} in frame {k}"
                    );
                }
            }
        }
    }
}

const FOUR_BAR: &str = include_str!("../scenes/four_bar.toml");

fn with_plot(plot: &str) -> mechdiff::Error {
    let text = format!("{FOUR_BAR}\n[plot]\n{plot}\n");
    let scene = match scene::parse("four_bar.toml", &text) {
        Err(e) => return e,
        Ok(scene) => scene,
    };
    let report = scene::run(&scene).unwrap();
    let animation = Animation::of(&scene, &report).unwrap();
    let error = drawings(&scene, &report, &animation).err();
    error
        .or_else(|| diagram(&scene, &report).err())
        .expect("an error")
}

/// The line of the `[plot]` entry in the test's text: after the scene's own lines.
fn plot_line() -> usize {
    FOUR_BAR.lines().count() + 3
}

/// Bad `[plot]` input is refused with `file:line:col` and what is wrong.
#[test]
fn bad_plot_input_is_located() {
    let line = plot_line();
    let cases = [
        (
            "trace = [\"P\", \"Z\"]",
            "unknown point `Z` in `[plot] trace`",
        ),
        ("trace = []", "`[plot] trace` is empty"),
        ("panels = []", "`[plot] panels` is empty"),
        (
            "panels = [\"psi\", \"speed\"]",
            "`speed`, which is neither an output nor a column",
        ),
        (
            "positions = [90, 400]",
            "drive position 400 deg is outside the sweep (0 deg to 360 deg)",
        ),
    ];
    for (plot, message) in cases {
        let text = with_plot(plot).to_string();
        assert!(
            text.starts_with(&format!("four_bar.toml:{line}:")),
            "{plot}: {text}"
        );
        assert!(text.contains(message), "{plot}: {text}");
    }
    let text = with_plot("colour = \"red\"").to_string();
    assert!(text.contains("unknown field `colour`"), "{text}");
}

/// A sweep of a million positions is drawn from at most `FRAMES` poses and decimated curves:
/// the diagram and the report stay under the stated bound whatever the length. (The rows are
/// the four-bar's, refined by interpolation: the pictures only read them.)
#[test]
fn a_million_positions_are_drawn_within_a_bounded_size() {
    let (scene, short) = load(&scenes()[0]);
    let n = 1_000_000;
    let width = short.rows[0].len();
    let (first, last) = (short.rows[0][0], short.rows[short.rows.len() - 1][0]);
    let rows: Vec<Vec<f64>> = (0..n)
        .map(|k| {
            let t = k as f64 / (n - 1) as f64;
            let phi = first + t * (last - first);
            let source = &short.rows[((short.rows.len() - 1) as f64 * t) as usize];
            std::iter::once(phi)
                .chain(source[1..width].iter().copied())
                .collect()
        })
        .collect();
    let report = Report { rows, ..short };
    let svg = diagram(&scene, &report).unwrap().to_svg().unwrap();
    let animation = Animation::of(&scene, &report).unwrap();
    assert_eq!(animation.rows.len(), mechdiff::pictures::run::FRAMES);
    let page = html(&scene, &report, &animation, &svg).unwrap();
    assert!(page.len() < MAX_BYTES, "report of {} bytes", page.len());
    assert!(svg.len() < MAX_BYTES / 2, "diagram of {} bytes", svg.len());
}

/// `mechdiff run --plot DIR --report FILE --json FILE`: the files are written; the JSON has
/// every row of the CSV with the same numbers (both print the shortest round-trip form).
#[test]
fn the_command_writes_pictures_report_and_json() {
    let dir = std::env::temp_dir().join(format!("mechdiff-pictures-{}", std::process::id()));
    let (plot, report, json, csv) = (
        dir.join("plot"),
        dir.join("run.html"),
        dir.join("run.json"),
        dir.join("run.csv"),
    );
    std::fs::create_dir_all(&dir).unwrap();
    let output = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args(["run", "scenes/four_bar.toml", "--plot"])
        .args([
            &plot,
            Path::new("--report"),
            &report,
            Path::new("--json"),
            &json,
        ])
        .args([Path::new("--csv"), &csv])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    for file in [
        "diagram.svg",
        "diagram.png",
        "mechanism_sketch.svg",
        "report.html",
    ] {
        assert!(plot.join(file).is_file(), "{file}");
    }
    assert!(report.is_file());
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let csv = std::fs::read_to_string(&csv).unwrap();
    let rows = json["rows"].as_array().unwrap();
    assert_eq!(rows.len(), csv.lines().count() - 1);
    for (row, line) in rows.iter().zip(csv.lines().skip(1)) {
        let from_csv: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
        let from_json: Vec<f64> = row
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(from_csv, from_json);
    }
    assert_eq!(json["dead_positions"].as_array().unwrap().len(), 2);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Issue 22: a title holding ESC, BEL, `<!--<script>`, `&` and quotes, and an output named
/// `<!--<script>` (which disabled the report's script): every SVG is well-formed XML
/// (roxmltree) and renders (resvg); the report has exactly its two `<script>` elements, its
/// data parses as JSON and holds the name as written, and no control character and no
/// `<!--` is left in the page.
#[test]
fn names_that_look_like_markup_or_hold_control_characters_stay_text() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/slider_crank.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let line = "title = \"Offset slider-crank, r = 100 mm, l = 400 mm, e = -12 mm\"";
    assert!(text.contains(line) && text.contains("name = \"s\"\n"));
    let text = text
        .replace(
            line,
            r#"title = "T\u001b[31mRED\u0007 <!--<script> & 'q' \"d\"""#,
        )
        .replace("name = \"s\"\n", "name = \"<!--<script>\"\n")
        .replace("step = 5\n", "step = 30\n");
    let scene = scene::parse("markup.toml", &text).unwrap();
    assert_eq!(
        scene.title.as_deref(),
        Some("T\u{1b}[31mRED\u{7} <!--<script> & 'q' \"d\"")
    );
    let report = scene::run(&scene).unwrap();
    let animation = Animation::of(&scene, &report).unwrap();
    let svg = diagram(&scene, &report).unwrap().to_svg().unwrap();
    let mut svgs = vec![svg.clone()];
    svgs.extend(
        drawings(&scene, &report, &animation)
            .unwrap()
            .into_iter()
            .map(|(_, drawing)| drawing.to_svg()),
    );
    for svg in &svgs {
        if let Err(e) = roxmltree::Document::parse(svg) {
            panic!("not well-formed: {e}");
        }
        raster::render(svg).unwrap();
        assert!(!svg.contains(['\u{1b}', '\u{7}']));
    }
    assert!(
        svgs.iter()
            .any(|s| s.contains(r"T\u{1b}[31mRED\u{7} &lt;!--&lt;script&gt;"))
    );
    let page = html(&scene, &report, &animation, &svg).unwrap();
    assert_eq!(
        page.matches("<script").count(),
        2,
        "the data and the program"
    );
    assert_eq!(page.matches("</script>").count(), 2);
    assert!(!page.contains("<!--"));
    assert!(!page.contains(['\u{1b}', '\u{7}']));
    let open = r#"<script type="application/json" id="data">"#;
    let start = page.find(open).unwrap() + open.len();
    let end = start + page[start..].find("</script>").unwrap();
    let data: serde_json::Value = serde_json::from_str(&page[start..end]).unwrap();
    let names: Vec<&str> = data["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    assert!(names.contains(&"<!--<script>"), "{names:?}");
    assert!(names.contains(&"<!--<script>''"), "{names:?}");
}

/// The numbers printed under the x axis of each panel of a diagram's SVG (the tick labels:
/// texts within 24 px below a plot frame's bottom edge that parse as numbers), per panel.
fn x_ticks(doc: &roxmltree::Document) -> Vec<Vec<f64>> {
    let frames: Vec<(f64, f64, f64)> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("plot-frame"))
        .map(|n| {
            let at = |a| n.attribute(a).unwrap().parse::<f64>().unwrap();
            (at("x"), at("x") + at("width"), at("y") + at("height"))
        })
        .collect();
    frames
        .iter()
        .map(|&(left, right, bottom)| {
            doc.descendants()
                .filter(|n| n.has_tag_name("text"))
                .filter_map(|n| {
                    let x: f64 = n.attribute("x")?.parse().ok()?;
                    let y: f64 = n.attribute("y")?.parse().ok()?;
                    let v: f64 = n.text()?.trim().parse().ok()?;
                    (y > bottom && y < bottom + 24.0 && x >= left - 2.0 && x <= right + 2.0)
                        .then_some(v)
                })
                .collect()
        })
        .collect()
}

/// Issue 24, item 4: every shipped scene's diagram, parsed from its SVG, has angle ticks at
/// multiples of 15° (4 to 9 per panel; before: every 50°), labels with symbols (no `''`
/// left; before: `psi''`), dead-position labels that do not overlap (their boxes estimated
/// at 0.62 em per character, 11 px font, one row 13 px; before: printed at one height over
/// each other), no panel of an all-zero column (before: seven zero friction torques), and
/// files no higher than `MAX_HEIGHT` (before: one 9690 px strip).
#[test]
fn diagrams_hold_up() {
    use mechdiff::pictures::diagram::MAX_HEIGHT;
    let mut primes = 0;
    for path in scenes() {
        let (scene, report) = load(&path);
        let d = diagram(&scene, &report).unwrap();
        for panel in &d.panels {
            if scene.plot.panels.is_none() {
                assert!(
                    panel
                        .series
                        .iter()
                        .all(|s| s.points.iter().any(|p| p[1] != 0.0)),
                    "{path:?}: a zero column is drawn in `{}`",
                    panel.y_label
                );
            }
        }
        for page in d.pages() {
            let svg = page.to_svg().unwrap();
            let doc = roxmltree::Document::parse(&svg).unwrap();
            let root = doc.root_element();
            let height: f64 = root.attribute("height").unwrap().parse().unwrap();
            assert!(height <= f64::from(MAX_HEIGHT), "{path:?}: {height}");
            let texts: Vec<&str> = doc
                .descendants()
                .filter(|n| n.has_tag_name("text"))
                .filter_map(|n| n.text())
                .collect();
            assert!(
                texts.iter().all(|t| !t.contains("''")),
                "{path:?}: {texts:?}"
            );
            primes += texts.iter().filter(|t| t.contains('″')).count();
            if page.x_label.ends_with("[deg]") {
                for ticks in x_ticks(&doc) {
                    assert!((4..=9).contains(&ticks.len()), "{path:?}: {ticks:?}");
                    let step = ticks[1] - ticks[0];
                    assert!(
                        ticks.iter().all(|t| (t / 15.0).fract().abs() < 1e-9) || step < 15.0,
                        "{path:?}: {ticks:?}"
                    );
                }
            }
            // Marker labels: the texts painted in a marker colour.
            let boxes: Vec<[f64; 4]> = doc
                .descendants()
                .filter(|n| n.has_tag_name("text"))
                .filter(|n| matches!(n.attribute("fill"), Some("#D62728") | Some("#9467BD")))
                .map(|n| {
                    let x: f64 = n.attribute("x").unwrap().parse().unwrap();
                    let y: f64 = n.attribute("y").unwrap().parse().unwrap();
                    let w = 0.62 * 11.0 * n.text().unwrap().trim().chars().count() as f64;
                    [x, y, x + w, y + 11.0]
                })
                .collect();
            for (i, a) in boxes.iter().enumerate() {
                for b in &boxes[i + 1..] {
                    let apart = a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1];
                    assert!(apart, "{path:?}: marker labels overlap: {a:?} {b:?}");
                }
            }
        }
    }
    assert!(primes > 0, "some diagram labels a coefficient with ″");
}

/// `panels = ["M_drive"]` draws the drive torque alone (before: beside a zero column of the
/// same unit); the SVG has one plot frame and its y label names M_drive only.
#[test]
fn a_column_asked_by_name_is_drawn_alone() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/rack_slotted_link_dynamics.toml");
    let text = std::fs::read_to_string(&path).unwrap();
    let (_, report) = load(&path);
    let name = &report
        .columns
        .iter()
        .find(|c| c.name.starts_with("M_"))
        .expect("a drive torque column")
        .name;
    let scene = scene::parse(
        "s.toml",
        &format!("{text}\n[plot]\npanels = [\"{name}\"]\n"),
    )
    .unwrap();
    let report = scene::run(&scene).unwrap();
    let svg = diagram(&scene, &report).unwrap().to_svg().unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let frames = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("plot-frame"))
        .count();
    assert_eq!(frames, 1);
    let d = diagram(&scene, &report).unwrap();
    assert_eq!(d.panels[0].series.len(), 1, "{:?}", d.panels[0].y_label);
}

/// Issue 24, item 5: a drawing of a scene with masses, parsed from its SVG, has a grid and a
/// scale bar of a round length in the scene's unit (1, 2 or 5 × 10ⁿ), traced paths in
/// distinct colours named in a legend, each centre of mass drawn as a quartered circle (not a
/// joint ring) at the solver-free rigid position of the sketch (the `[masses]` centre itself,
/// to 1e-9 of the frame width: a few f64 operations), and labels set off away from their
/// links. Before: no grid, no scale, one colour, no legend, no centre of mass, labels at a
/// fixed up-right offset whatever the links.
#[test]
fn drawings_have_axes_scale_legend_and_mass_centres() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/whitworth_forces.toml");
    let (scene, report) = load(&path);
    let animation = Animation::of(&scene, &report).unwrap();
    let drawn = drawings(&scene, &report, &animation).unwrap();
    let (_, sketch) = &drawn[0];
    let sketch = sketch
        .clone()
        .path("first", &[[0.0, 0.0], [0.01, -0.01], [0.02, 0.0]])
        .path("second", &[[0.0, 0.0], [0.01, 0.01], [0.02, 0.0]]);
    let svg = sketch.to_svg();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let class = |c: &str| {
        doc.descendants()
            .filter(|n| n.attribute("class") == Some(c))
            .collect::<Vec<_>>()
    };
    assert_eq!(class("grid").len(), 1);
    let bar = class("scale-bar");
    assert_eq!(bar.len(), 1);
    let length: f64 = bar[0].attribute("data-length").unwrap().parse().unwrap();
    let mantissa = length / 10f64.powf(length.log10().floor());
    assert!(
        [1.0, 2.0, 5.0].iter().any(|m| (mantissa - m).abs() < 1e-9),
        "{length}"
    );
    assert_eq!(
        bar[0].attribute("data-unit"),
        Some(scene.units.symbol(scene::units::Dimension::Length))
    );
    let colours: Vec<&str> = doc
        .descendants()
        .filter(|n| n.attribute("class").is_some_and(|c| c.starts_with("path ")))
        .map(|n| n.attribute("stroke").unwrap())
        .collect();
    assert!(colours.len() >= 2, "{colours:?}");
    let mut distinct = colours.clone();
    distinct.sort_unstable();
    distinct.dedup();
    assert_eq!(distinct.len(), colours.len(), "{colours:?}");
    let legend: Vec<String> = class("legend")[0]
        .descendants()
        .filter_map(|n| n.text())
        .map(str::to_owned)
        .collect();
    assert!(legend.iter().any(|t| t == "path of second"), "{legend:?}");
    let masses = class("mass-centre");
    let centres = &scene.dynamics.as_ref().unwrap().masses;
    assert_eq!(masses.len(), centres.len());
    let f = frame(&svg);
    for (node, (_, inertia)) in masses.iter().zip(centres) {
        let circle = node.children().find(|n| n.has_tag_name("circle")).unwrap();
        let at = |a| circle.attribute(a).unwrap().parse::<f64>().unwrap();
        let [x, y] = f.pixel(inertia.center);
        // Written with three decimals: half a thousandth of a pixel.
        assert!((at("cx") - x).abs() < 6e-4 && (at("cy") - y).abs() < 6e-4);
        assert!(node.descendants().any(|n| n.has_tag_name("path")));
    }
}

/// Arrows of a drawing are drawn to their stated scale: a velocity of (1, 0) m/s at 0.05 m
/// per m/s is 0.05 m long in model units (to 1e-3 px: three written decimals), and the
/// legend states the scale in the drawing's unit.
#[test]
fn vectors_are_drawn_to_their_stated_scale() {
    use mechdiff::pictures::{Drawing, VectorKind};
    let d = Drawing::new("v")
        .unit("mm", 1e-3)
        .polyline(&[[0.0, 0.0], [0.1, 0.0]], mechdiff::pictures::Style::link())
        .vector(VectorKind::Velocity, [0.1, 0.0], [1.0, 0.0], 0.05);
    let svg = d.to_svg();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let arrow = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("vector"))
        .unwrap();
    let line = arrow.children().find(|n| n.has_tag_name("line")).unwrap();
    let head = arrow
        .children()
        .find(|n| n.has_tag_name("polygon"))
        .unwrap();
    let tip: Vec<f64> = head
        .attribute("points")
        .unwrap()
        .split([' ', ','])
        .take(2)
        .map(|v| v.parse().unwrap())
        .collect();
    let f = frame(&svg);
    let x0: f64 = line.attribute("x1").unwrap().parse().unwrap();
    assert!((tip[0] - x0 - 0.05 * f.scale).abs() < 2e-3);
    let legend: String = doc.descendants().filter_map(|n| n.text()).collect();
    assert!(legend.contains("v: 1 m/s ≙ 50 mm"), "{legend}");
}

/// The numbers of an SVG path's `d` attribute, in order.
fn path_numbers(d: &str) -> Vec<f64> {
    d.split(|c: char| c == ' ' || c == ',' || c.is_ascii_alphabetic())
        .filter_map(|t| t.parse().ok())
        .collect()
}

/// The plot frames of a diagram's SVG: `(x, y, width, height, x0, x1, y0, y1)`, in order.
fn plot_frames(doc: &roxmltree::Document) -> Vec<[f64; 8]> {
    doc.descendants()
        .filter(|n| n.attribute("class") == Some("plot-frame"))
        .map(|n| {
            [
                "x", "y", "width", "height", "data-x0", "data-x1", "data-y0", "data-y1",
            ]
            .map(|a| n.attribute(a).unwrap().parse::<f64>().unwrap())
        })
        .collect()
}

/// Issue 24, item 4: a diagram's curves are cubic Hermite segments with the exact slopes of
/// the table's derivative columns (ψ′ for ψ, x_P′ for x_P, ψ″ for ψ′): at the middle of every
/// segment of a 5° sweep (the four-bar's, and the Whitworth's over 0°…360°, where the sweep
/// ends), the drawn curve (the Bézier point at t = ½, whose x is the middle drive position)
/// is within 0.5 px of the solver's value there, from a second run at the middle positions
/// mapped through the plot frame. Before: straight lines between points (5° polylines with
/// kinks), and no `C` command in the SVG.
#[test]
fn diagram_curves_follow_the_exact_derivatives() {
    use mechdiff::scene::Positions;
    for name in ["four_bar.toml", "whitworth.toml"] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("scenes")
            .join(name);
        let mut scene = scene::load(&path).unwrap();
        scene.plot = Default::default();
        scene.positions =
            Positions::List((0..=72).map(|k| f64::from(k) * 5f64.to_radians()).collect());
        let report = scene::run(&scene).unwrap();
        let phi: Vec<f64> = report.rows.iter().map(|r| r[0]).collect();
        let mids: Vec<f64> = phi.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
        let mut middle = scene.clone();
        middle.positions = Positions::List(mids.clone());
        let exact = scene::run(&middle).unwrap();
        let d = diagram(&scene, &report).unwrap();
        let svg = d.to_svg().unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let frames = plot_frames(&doc);
        let curves: Vec<&str> = doc
            .descendants()
            .filter(|n| n.attribute("class") == Some("curve"))
            .map(|n| n.attribute("d").unwrap())
            .collect();
        let series: Vec<(usize, &str)> = (d.panels.iter().enumerate())
            .flat_map(|(k, p)| p.series.iter().map(move |s| (k, s.name.as_str())))
            .collect();
        assert_eq!(curves.len(), series.len(), "{name}: one path per curve");
        let mut checked = 0;
        for (&(k, label), d_attr) in series.iter().zip(&curves) {
            let column = report
                .columns
                .iter()
                .position(|c| mechdiff::pictures::symbols::symbol(&c.name) == label)
                .unwrap();
            let derivative = format!("{}'", report.columns[column].name);
            if !report.columns.iter().any(|c| c.name == derivative) {
                continue;
            }
            let n = path_numbers(d_attr);
            // M x y, then per segment: C c1x c1y c2x c2y x y.
            assert_eq!(n.len(), 2 + 6 * mids.len(), "{name} {label}: {d_attr:.80}");
            let [fx, fy, fw, fh, x0, x1, y0, y1] = frames[k];
            let (xf, yf) = (report.columns[0].factor, report.columns[column].factor);
            for (s, row) in exact.rows.iter().enumerate() {
                let p = &n[6 * s..6 * s + 8];
                let bezier = |a: f64, b: f64, c: f64, e: f64| (a + 3.0 * b + 3.0 * c + e) / 8.0;
                let (bx, by) = (
                    bezier(p[0], p[2], p[4], p[6]),
                    bezier(p[1], p[3], p[5], p[7]),
                );
                let want_x = fx + (row[0] / xf - x0) / (x1 - x0) * fw;
                let want_y = fy + fh - (row[column] / yf - y0) / (y1 - y0) * fh;
                // x: the middle drive position (the written 1e-3 px digits); y: 0.5 px.
                assert!(
                    (bx - want_x).abs() < 0.01,
                    "{name} {label} segment {s}: x {bx} vs {want_x}"
                );
                assert!(
                    (by - want_y).abs() <= 0.5,
                    "{name} {label} at {:.3}°: {by} px vs {want_y} px",
                    row[0].to_degrees()
                );
                checked += 1;
            }
        }
        assert!(
            checked >= 2 * mids.len(),
            "{name}: {checked} points checked"
        );
    }
}

/// Issue 24, item 4: marker labels stay inside the picture and clear of their own lines, and
/// never overlap: dead and limit positions crowded at both ends of the sweep and in the
/// middle, their boxes estimated at 0.62 em per character (11 px font, 11 px high). Before:
/// a label near the right end ran off the picture (it always stood right of its line).
#[test]
fn marker_labels_stay_inside_and_clear_of_their_lines() {
    use mechdiff::pictures::{Diagram, Marker, MarkerKind, Panel};
    let points: Vec<[f64; 2]> = (0..=72)
        .map(|k| [f64::from(k) * 5.0, f64::from(k).sin()])
        .collect();
    let mut d = Diagram::new("crowded", "φ [deg]").panel(Panel::new("y [1]").series("y", points));
    let at = [
        0.0, 1.0, 3.0, 178.0, 180.0, 181.0, 352.0, 356.0, 359.0, 360.0,
    ];
    for (k, x) in at.iter().enumerate() {
        let kind = if k % 3 == 0 {
            MarkerKind::Limit
        } else {
            MarkerKind::Dead
        };
        d = d.marker(Marker::new(*x, &format!("x_C{k}: dead at {x}"), kind));
    }
    let svg = d.to_svg().unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let width: f64 = doc
        .root_element()
        .attribute("width")
        .unwrap()
        .parse()
        .unwrap();
    let [fx, _, fw, _, x0, x1, _, _] = plot_frames(&doc)[0];
    let boxes: Vec<([f64; 4], f64)> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter(|n| matches!(n.attribute("fill"), Some("#D62728") | Some("#9467BD")))
        .map(|n| {
            let text = n.text().unwrap().trim();
            let x: f64 = n.attribute("x").unwrap().parse().unwrap();
            let y: f64 = n.attribute("y").unwrap().parse().unwrap();
            let w = 0.62 * 11.0 * text.chars().count() as f64;
            let own: f64 = text.rsplit(' ').next().unwrap().parse().unwrap();
            ([x, y, x + w, y + 11.0], fx + (own - x0) / (x1 - x0) * fw)
        })
        .collect();
    assert_eq!(boxes.len(), at.len(), "one label per marker");
    for (i, (a, line)) in boxes.iter().enumerate() {
        assert!(
            a[0] >= 0.0 && a[2] <= width,
            "label {a:?} outside 0..{width}"
        );
        assert!(
            a[2] <= line - 1.0 || a[0] >= line + 1.0,
            "label {a:?} crosses its line at {line}"
        );
        for (b, _) in &boxes[i + 1..] {
            let apart = a[2] <= b[0] || b[2] <= a[0] || a[3] <= b[1] || b[3] <= a[1];
            assert!(apart, "marker labels overlap: {a:?} {b:?}");
        }
    }
}

/// Issue 24, item 4: diagrams of cams and balancing are paged like a run's: a diagram of 12
/// panels becomes `svaj.svg` and `svaj_2.svg`, each at most `MAX_HEIGHT` px high, and a cam
/// scene's `--plot` folder holds only pages of at most that height.
#[test]
fn cam_and_balancing_diagrams_are_paged() {
    use mechdiff::pictures::diagram::MAX_HEIGHT;
    use mechdiff::pictures::{Diagram, Panel};
    let mut d = Diagram::new("tall", "θ [deg]");
    for k in 0..12 {
        d = d.panel(Panel::new(&format!("s{k} [mm]")).series("s", vec![[0.0, 0.0], [1.0, 1.0]]));
    }
    assert!(d.height() > MAX_HEIGHT);
    let pages = d.named_pages("svaj");
    let names: Vec<&str> = pages.iter().map(|(n, _)| n.as_str()).collect();
    assert_eq!(names, ["svaj", "svaj_2"]);
    assert!(pages.iter().all(|(_, p)| p.height() <= MAX_HEIGHT));
    let cam =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cams/rise_dwell_return_dwell.toml");
    let dir = std::env::temp_dir().join(format!("mechdiff-cam-pages-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args([
            "run",
            cam.to_str().unwrap(),
            "--plot",
            dir.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "svg") {
            let svg = std::fs::read_to_string(&path).unwrap();
            let doc = roxmltree::Document::parse(&svg).unwrap();
            let height: f64 = doc
                .root_element()
                .attribute("height")
                .unwrap()
                .parse()
                .unwrap();
            assert!(height <= f64::from(MAX_HEIGHT), "{path:?}: {height}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let balancing = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/whitworth_balancing.toml");
    let (scene, report) = load(&balancing);
    for (name, svg) in mechdiff::pictures::balancing::pictures(&scene, &report).unwrap() {
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let height: f64 = doc
            .root_element()
            .attribute("height")
            .unwrap()
            .parse()
            .unwrap();
        assert!(height <= f64::from(MAX_HEIGHT), "{name}: {height}");
    }
}

/// Issue 24, item 5: `[plot] vectors = ["P"]` draws the velocity and acceleration of the
/// four-bar's coupler point at the `[plot] positions`, to the scale the legend states: each
/// arrow starts at P and its length over the stated scale is the run's |v_P| (from `vx_P`,
/// `vy_P`) and |a_P| (`ax_P`, `ay_P`, with the scene's α = 5 rad/s²) at φ = 30°, to 0.01 px
/// (three written decimals of each end); the direction agrees to 1e-3 rad. Before: no
/// `[plot] vectors` (an unknown field).
#[test]
fn plot_vectors_are_drawn_to_the_stated_scale() {
    let text = format!("{FOUR_BAR}\n[plot]\npositions = [30]\nvectors = [\"P\"]\n");
    let scene = scene::parse("four_bar.toml", &text).unwrap();
    let report = scene::run(&scene).unwrap();
    let animation = Animation::of(&scene, &report).unwrap();
    let drawn = drawings(&scene, &report, &animation).unwrap();
    let (_, at30) = drawn.iter().find(|(n, _)| n.contains("30")).unwrap();
    let svg = at30.to_svg();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let f = frame(&svg);
    let legend: Vec<&str> = doc.descendants().filter_map(|n| n.text()).collect();
    // `v: 1 m/s ≙ 20 mm`: model metres per unit of the quantity.
    let stated = |prefix: &str| -> f64 {
        let line = legend.iter().find(|t| t.starts_with(prefix)).unwrap();
        let rest = line.split('≙').nth(1).unwrap().trim();
        let (number, unit) = rest.split_once(' ').unwrap();
        let per = match unit {
            "mm" => 1e-3,
            "m" => 1.0,
            other => panic!("unit {other}"),
        };
        number.parse::<f64>().unwrap() * per
    };
    let scales = [stated("v: 1 m/s"), stated("a: 1 m/s²")];
    let row = report
        .rows
        .iter()
        .find(|r| (r[0] - 30f64.to_radians()).abs() < 1e-9)
        .unwrap();
    let value = |name: &str| row[report.columns.iter().position(|c| c.name == name).unwrap()];
    let want = [
        [value("vx_P"), value("vy_P")],
        [value("ax_P"), value("ay_P")],
    ];
    let p = joints(&svg).into_iter().find(|(n, _)| n == "P").unwrap().1;
    let arrows: Vec<roxmltree::Node> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("vector"))
        .collect();
    assert_eq!(arrows.len(), 2, "a velocity and an acceleration arrow");
    for (arrow, (w, scale)) in arrows.iter().zip(want.iter().zip(scales)) {
        let line = arrow.children().find(|n| n.has_tag_name("line")).unwrap();
        let head = arrow
            .children()
            .find(|n| n.has_tag_name("polygon"))
            .unwrap();
        let at = |a: &str| line.attribute(a).unwrap().parse::<f64>().unwrap();
        let tail = f.model([at("x1"), at("y1")]);
        let tip: Vec<f64> = head
            .attribute("points")
            .unwrap()
            .split([' ', ','])
            .take(2)
            .map(|v| v.parse().unwrap())
            .collect();
        let tip = f.model([tip[0], tip[1]]);
        let tol = 0.01 / f.scale;
        assert!(
            (tail[0] - p[0]).abs() < tol && (tail[1] - p[1]).abs() < tol,
            "tail {tail:?} vs P {p:?}"
        );
        let drawn = [(tip[0] - tail[0]) / scale, (tip[1] - tail[1]) / scale];
        let length = drawn[0].hypot(drawn[1]);
        let expected = w[0].hypot(w[1]);
        assert!(
            (length - expected).abs() <= 2.0 * tol / scale,
            "{length} vs {expected}"
        );
        let turn = (drawn[1].atan2(drawn[0]) - w[1].atan2(w[0])).sin().abs();
        assert!(turn < 1e-3, "direction {drawn:?} vs {w:?}");
    }
}

/// `[plot] vectors` without a drive speed, without positions, or naming an unknown point is
/// refused at its `file:line:col` with what to do.
#[test]
fn bad_plot_vectors_are_located() {
    let line = plot_line();
    let cases = [
        ("vectors = [\"Z\"]", "unknown point `Z` in `[plot] vectors`"),
        ("vectors = []", "`[plot] vectors` is empty"),
        ("vectors = [\"P\"]", "are drawn at the `[plot] positions`"),
    ];
    for (plot, message) in cases {
        let text = with_plot(plot).to_string();
        assert!(
            text.starts_with(&format!("four_bar.toml:{line}:")),
            "{plot}: {text}"
        );
        assert!(text.contains(message), "{plot}: {text}");
    }
    let still = FOUR_BAR
        .replace("speed = 10           # rad/s\n", "")
        .replace("acceleration = 5     # rad/s²\n", "")
        .replace("\"velocity\", \"acceleration\"", "")
        .replace(
            "point = \"P\"",
            "point = \"P\"\nquantities = [\"position\"]",
        );
    let text = format!("{still}\n[plot]\npositions = [30]\nvectors = [\"P\"]\n");
    let scene = scene::parse("four_bar.toml", &text).unwrap();
    let report = scene::run(&scene).unwrap();
    let animation = Animation::of(&scene, &report).unwrap();
    let error = drawings(&scene, &report, &animation)
        .err()
        .unwrap()
        .to_string();
    assert!(error.contains("needs the drive speed"), "{error}");
}

/// Issue 24, item 4, for cams: the SVAJ diagram's s, s′ and s″ curves are Hermite segments
/// with the exact slopes s′, s″, s‴: at the middle of every segment (cam angles from the
/// path's own ends, read back through the plot frame), the drawn curve is within 0.5 px of the
/// cam program's value there. Before: polylines refined by estimated slopes.
#[test]
fn cam_curves_follow_the_exact_derivatives() {
    use mechdiff::scene::units::Dimension;
    use mechdiff_core::cams::Side;
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cams/rise_dwell_return_dwell.toml");
    let cam = mechdiff::scene::cam::load(&path).unwrap();
    let svg = mechdiff::pictures::cam::svaj_diagram(&cam)
        .to_svg()
        .unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let frames = plot_frames(&doc);
    let curves: Vec<&str> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("curve"))
        .map(|n| n.attribute("d").unwrap())
        .collect();
    let u = &cam.units;
    let length = u.factor(Dimension::Length);
    let mut checked = 0;
    for (k, d) in curves.iter().enumerate().take(3) {
        let [fx, fy, fw, fh, x0, x1, y0, y1] = frames[k];
        for run in d.split('M').filter(|r| !r.trim().is_empty()) {
            let n = path_numbers(run);
            for s in 0..(n.len() - 2) / 6 {
                let p = &n[6 * s..6 * s + 8];
                let bezier = |a: f64, b: f64, c: f64, e: f64| (a + 3.0 * b + 3.0 * c + e) / 8.0;
                let (bx, by) = (
                    bezier(p[0], p[2], p[4], p[6]),
                    bezier(p[1], p[3], p[5], p[7]),
                );
                let theta = u.to_si(x0 + (bx - fx) / fw * (x1 - x0), Dimension::Angle);
                let j = cam.mechanism.program.svaj(theta, Side::Left);
                let value = [j.value / length, j.d1() / length, j.d2() / length][k];
                let want = fy + fh - (value - y0) / (y1 - y0) * fh;
                assert!(
                    (by - want).abs() <= 0.5,
                    "panel {k} at θ = {theta}: {by} vs {want}"
                );
                checked += 1;
            }
        }
    }
    assert!(checked > 3000, "{checked} segments checked");
}

/// Issue 24, item 2: `--plot` draws the coupler curve of each traced point to scale. Parsed
/// from `path_P.svg` of scenes/four_bar.toml: the grid's vertical and horizontal lines are
/// the same number of pixels per metre (equal axes, to 1e-5 relative: the lines' positions
/// are written to 3 decimals and lie hundreds of pixels apart); every point of the curve maps back, through the
/// picture's frame, to the solver's position of P at the drive position of its CSV row
/// (≤ 0.5 px); the CSV holds the solver's x, y to full digits (1e-12 m); and the drive
/// position is marked along the curve at multiples of 45° (0° and 360° at one place, one
/// label).
#[test]
fn a_coupler_curve_is_drawn_to_scale_where_the_solver_puts_the_point() {
    let dir = std::env::temp_dir().join(format!("mechdiff-paths-{}", std::process::id()));
    let out = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args([
            "run",
            "scenes/four_bar.toml",
            "--plot",
            dir.to_str().unwrap(),
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svg = std::fs::read_to_string(dir.join("path_P.svg")).unwrap();
    let csv = std::fs::read_to_string(dir.join("path_P.csv")).unwrap();
    assert!(dir.join("path_P.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let root = doc.root_element();
    let number = |n: roxmltree::Node, a: &str| n.attribute(a).unwrap().parse::<f64>().unwrap();
    let frame = Frame {
        scale: number(root, "data-scale"),
        origin_x: number(root, "data-origin-x"),
        origin_y: number(root, "data-origin-y"),
        width: number(root, "width"),
        height: number(root, "height"),
    };
    // The grid: each line followed by the value it stands at (in metres here).
    let grid = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("grid"))
        .unwrap();
    let (mut across, mut up) = (Vec::new(), Vec::new());
    let children: Vec<_> = grid.children().filter(|n| n.is_element()).collect();
    for pair in children.windows(2) {
        let (line, text) = (pair[0], pair[1]);
        let Some(value) = (text.has_tag_name("text") && line.has_tag_name("line"))
            .then(|| text.text()?.trim().parse::<f64>().ok())
            .flatten()
        else {
            continue;
        };
        if number(line, "x1") == number(line, "x2") {
            across.push((value, number(line, "x1")));
        } else {
            up.push((value, number(line, "y1")));
        }
    }
    let per_metre = |lines: &[(f64, f64)]| {
        let (first, last) = (lines[0], lines[lines.len() - 1]);
        (last.1 - first.1) / (last.0 - first.0)
    };
    assert!(across.len() >= 2 && up.len() >= 2, "{across:?} {up:?}");
    let (sx, sy) = (per_metre(&across), -per_metre(&up));
    assert!((sx - sy).abs() <= 1e-5 * sx, "x {sx} px/m, y {sy} px/m");
    assert!(
        (sx - frame.scale).abs() <= 1e-5 * sx,
        "{sx} vs {}",
        frame.scale
    );
    // The curve against the solver: P's position at each CSV row's drive position.
    let scene =
        scene::load(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/four_bar.toml")).unwrap();
    let report = scene::run(&scene).unwrap();
    let (phi, x, y) = (
        report.column("phi").unwrap(),
        report.column("x_P").unwrap(),
        report.column("y_P").unwrap(),
    );
    let curve = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("path path-P"))
        .unwrap();
    let drawn: Vec<[f64; 2]> = (curve.attribute("points").unwrap().split(' '))
        .map(|p| {
            let (a, b) = p.split_once(',').unwrap();
            [a.parse().unwrap(), b.parse().unwrap()]
        })
        .collect();
    let rows: Vec<Vec<f64>> = (csv.lines().skip(1))
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(csv.lines().next().unwrap(), "phi [deg],x_P [m],y_P [m]");
    assert_eq!(rows.len(), drawn.len());
    assert_eq!(rows.len(), phi.len(), "a 73-row sweep is drawn whole");
    for ((row, pixel), k) in rows.iter().zip(&drawn).zip(0..) {
        assert!((row[0].to_radians() - phi[k]).abs() <= 1e-12, "{row:?}");
        assert!((row[1] - x[k]).abs() <= 1e-12 && (row[2] - y[k]).abs() <= 1e-12);
        let want = frame.pixel([x[k], y[k]]);
        let off = (want[0] - pixel[0]).hypot(want[1] - pixel[1]);
        assert!(off <= 0.5, "φ = {}: {pixel:?} vs {want:?}", row[0]);
    }
    let ticks: Vec<&str> = (doc.descendants())
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .filter(|t| t.starts_with("φ = "))
        .collect();
    assert_eq!(
        ticks,
        [
            "φ = 0, 360 deg",
            "φ = 45 deg",
            "φ = 90 deg",
            "φ = 135 deg",
            "φ = 180 deg",
            "φ = 225 deg",
            "φ = 270 deg",
            "φ = 315 deg"
        ]
    );
    // The rocker's two dead positions are marked on the curve.
    assert_eq!(svg.matches("dead: psi").count(), 2, "{svg}");
}

/// The data block of an HTML report.
fn report_data(page: &str) -> serde_json::Value {
    let open = r#"<script type="application/json" id="data">"#;
    let start = page.find(open).unwrap() + open.len();
    let end = start + page[start..].find("</script>").unwrap();
    serde_json::from_str(&page[start..end]).unwrap()
}

/// Issue 24: cam and rotor scenes get a report (`--report` was refused for them). The cam's
/// page has a frame every half degree, and at every row of the SVAJ table (`--csv`, written
/// by another path) its s, s′, s″, s‴ and pressure angle are the table's to 1e-9 relative
/// (the same dual-number evaluation; the page's cam angle is k·2π/720, the table's the file's
/// degrees converted: they differ by rounding, so values agree to about 1e-14, and a jerk
/// near zero is compared with 1e-9 of the column's largest). The rotor's page holds the m r of
/// each row of the CSV. Both are self-contained and under [`MAX_BYTES`].
#[test]
fn cam_and_rotor_scenes_write_their_reports() {
    let dir = tempfile::tempdir().unwrap();
    let run = |scene: &str, report: &Path, csv: &Path| {
        let output = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
            .args(["run", scene, "--report"])
            .args([report, Path::new("--csv"), csv])
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .unwrap();
        assert!(
            output.status.success(),
            "{scene}: {}",
            String::from_utf8_lossy(&output.stderr)
        );
        let page = std::fs::read_to_string(report).unwrap();
        assert!(page.len() < MAX_BYTES && !page.contains("src=") && !page.contains("<link"));
        let csv = std::fs::read_to_string(csv).unwrap();
        (report_data(&page), csv)
    };
    let (cam, csv) = run(
        "scenes/cams/rise_dwell_return_dwell.toml",
        &dir.path().join("cam.html"),
        &dir.path().join("cam.csv"),
    );
    let values = cam["values"].as_array().unwrap();
    assert_eq!(values.len(), 721);
    assert_eq!(cam["xy"].as_array().unwrap().len(), 721);
    let number = |v: &serde_json::Value| v.as_f64().unwrap();
    let largest: Vec<f64> = (0..6)
        .map(|c| {
            values
                .iter()
                .map(|r| number(&r[c]).abs())
                .fold(0.0, f64::max)
        })
        .collect();
    let mut compared = 0;
    for line in csv.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let theta: f64 = cells[0].parse().unwrap();
        if cells[1] == "left" || theta >= 360.0 {
            continue;
        }
        let frame = (theta * 2.0).round() as usize;
        let row = &values[frame];
        assert!((number(&row[0]) - theta).abs() <= 1e-9, "{theta}");
        for (c, cell) in [(1, 2), (2, 3), (3, 4), (4, 5), (5, 9)] {
            let want: f64 = cells[cell].parse().unwrap();
            let got = number(&row[c]);
            assert!(
                (got - want).abs() <= 1e-9 * want.abs().max(largest[c]),
                "θ = {theta}: column {c}: {got} on the page, {want} in the table"
            );
        }
        compared += 1;
    }
    assert!(compared >= 24, "{compared} rows compared");

    let (rotor, csv) = run(
        "scenes/rotor_balancing.toml",
        &dir.path().join("rotor.html"),
        &dir.path().join("rotor.csv"),
    );
    let names: Vec<&str> = rotor["columns"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["name"].as_str().unwrap())
        .collect();
    let shown = &rotor["values"][0];
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let mr = header.iter().position(|h| *h == "m r [kg m]").unwrap();
    for line in csv.lines().skip(1) {
        let cells: Vec<&str> = line.split(',').collect();
        let name = match cells[1] {
            "" => format!("{}: m r", cells[0]),
            index => format!("{} {index}: m r", cells[0]),
        };
        let k = names.iter().position(|n| *n == name).unwrap();
        let want: f64 = cells[mr].parse().unwrap();
        assert_eq!(number(&shown[k]), want, "{name}");
    }
}

/// A sweep that starts a step from a limit position (the rack's travel of reference 001,
/// limit 0.2966 m, sweep from 0.30 m) draws its coupler curves: the limit's pose is a toggle
/// whose velocity coefficients are infinite, so it is marked at the curve's end next to it,
/// and the label says so (the plot used to fail with "singular position").
#[test]
fn a_limit_just_outside_the_sweep_is_marked_at_the_curves_end() {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_mechdiff"))
        .args(["run", "scenes/rack_slotted_link_travel.toml", "--plot"])
        .arg(dir.path())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for point in ["C", "D", "G1"] {
        let svg = std::fs::read_to_string(dir.path().join(format!("path_{point}.svg"))).unwrap();
        assert!(
            svg.contains("limit position at φ = 0.296595 m (marked at the nearest drawn position)"),
            "{point}"
        );
    }
}
