//! Issue 14 item 7: `mechdiff import` reads a Pyslvs expression and a PMKS text file into
//! scenes that move as the same mechanisms written by hand.
//!
//! The files in `tests/data/import/` are written in each tool's format: Pyslvs's example
//! "Crank rocker" (pyslvs/example.py) and PMKS's example `crankNslider.txt` (PMKS
//! Examples/, with the `mech=` header and flags PMKS writes; the first joint marked as the
//! driving input).

use crate::common;

use std::process::Command;

use mechdiff::import;
use mechdiff::scene::{self, Report, Source};

fn imported(path: &str) -> (String, Report) {
    let text = std::fs::read_to_string(path).unwrap();
    let source = Source::new(path, text);
    let scene_text = import::read(&source)
        .and_then(|l| l.to_scene(&source))
        .unwrap_or_else(|e| panic!("{e}"));
    let scene =
        scene::parse("imported.toml", &scene_text).unwrap_or_else(|e| panic!("{e}\n{scene_text}"));
    (
        scene_text,
        scene::run(&scene).unwrap_or_else(|e| panic!("{e}")),
    )
}

fn run(text: &str) -> Report {
    common::run_text("hand.toml", text)
}

/// Every row of column `a` of `got` equals column `b` of `want` to 1e-12 relative (absolute
/// below 1): the same sketch and joints, solved the same way.
fn same_column(got: &Report, a: &str, want: &Report, b: &str) {
    let (x, y) = (got.column(a).unwrap(), want.column(b).unwrap());
    assert_eq!(x.len(), y.len());
    for (u, v) in x.iter().zip(&y) {
        assert!(
            (u - v).abs() <= 1e-12 * v.abs().max(1.0),
            "{a} vs {b}: {u} vs {v}"
        );
    }
}

#[test]
fn an_imported_pyslvs_four_bar_moves_as_the_hand_written_one() {
    let (_, got) = imported("tests/data/import/crank_rocker.pyslvs");
    let want = run(r#"
[units]
length = "mm"
angle = "deg"
[points]
O2 = [0, 0]
A = [12.92, 32.53]
B = [73.28, 67.97]
C = [33.3, 66.95]
O4 = [90, 0]
[links]
ground = ["O2", "O4"]
crank = ["O2", "A"]
coupler = ["A", "B", "C"]
rocker = ["O4", "B"]
[joints]
O2 = { type = "revolute", at = "O2", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "coupler"] }
B = { type = "revolute", at = "B", links = ["coupler", "rocker"] }
O4 = { type = "revolute", at = "O4", links = ["ground", "rocker"] }
[drive]
joint = "O2"
line = ["O2", "A"]
speed = 1
[sweep]
from = 0
to = 360
step = 5
[[output]]
point = "A"
quantities = ["position", "velocity_coefficient"]
[[output]]
point = "B"
quantities = ["position", "velocity_coefficient"]
[[output]]
point = "C"
quantities = ["position", "velocity_coefficient"]
"#);
    for (j, p) in [("J2", "A"), ("J3", "B"), ("J4", "C")] {
        for q in ["x", "y", "x", "y"].iter().zip(["", "", "'", "'"]) {
            same_column(
                &got,
                &format!("{}_{j}{}", q.0, q.1),
                &want,
                &format!("{}_{p}{}", q.0, q.1),
            );
        }
    }
    // An independent fact: the crank pin stays on its circle, |O2 J2| = |(12.92, 32.53)|
    // mm (1e-12 relative: the solver's tolerance).
    let r = 12.92f64.hypot(32.53) * 1e-3;
    let (x, y) = (got.column("x_J2").unwrap(), got.column("y_J2").unwrap());
    assert_eq!(x.len(), 73, "a full turn in 5° steps");
    for (x, y) in x.iter().zip(&y) {
        assert!((x.hypot(*y) - r).abs() < 1e-12 * r);
    }
}

#[test]
fn an_imported_pmks_slider_crank_moves_as_the_hand_written_one() {
    let (text, got) = imported("tests/data/import/crank_slider.pmks");
    assert!(
        text.contains("joint = \"J1\""),
        "the driving input (flag tfft) is driven:\n{text}"
    );
    let want = run(r#"
[units]
length = "mm"
angle = "deg"
[points]
O = [0, 0]
A = [0, 10]
B = [12, 2]
S = [12, 0]
G = [12, 0]
H = [20, 0]
[links]
ground = ["O", "G", "H"]
crank = ["O", "A"]
rod = ["A", "B"]
slider = ["B", "S"]
[joints]
O = { type = "revolute", at = "O", links = ["ground", "crank"] }
A = { type = "revolute", at = "A", links = ["crank", "rod"] }
B = { type = "revolute", at = "B", links = ["rod", "slider"] }
S = { type = "prismatic", links = ["ground", "slider"], line = ["G", "H"], point = "S" }
[drive]
joint = "O"
line = ["O", "A"]
speed = 1
[sweep]
from = 0
to = 360
step = 5
[[output]]
point = "B"
quantities = ["position", "velocity_coefficient"]
[[output]]
point = "S"
quantities = ["position", "velocity_coefficient"]
"#);
    for (j, p) in [("J3", "B"), ("J4", "S")] {
        for (c, d) in [("x", ""), ("y", ""), ("x", "'"), ("y", "'")] {
            same_column(&got, &format!("{c}_{j}{d}"), &want, &format!("{c}_{p}{d}"));
        }
    }
    // Independent: the slider stays on y = 0, and the rod J2–J3 keeps its length
    // |(12, 2) − (0, 10)| = √208 mm (1e-12 relative: the solver's tolerance).
    let rod = 208f64.sqrt() * 1e-3;
    let (xa, ya) = (got.column("x_J2").unwrap(), got.column("y_J2").unwrap());
    let (xb, yb) = (got.column("x_J3").unwrap(), got.column("y_J3").unwrap());
    let ys = got.column("y_J4").unwrap();
    for k in 0..ys.len() {
        assert!(ys[k].abs() < 1e-15, "row {k}: y_J4 = {}", ys[k]);
        let length = (xb[k] - xa[k]).hypot(yb[k] - ya[k]);
        assert!((length - rod).abs() < 1e-12 * rod, "row {k}: {length}");
    }
}

/// Pyslvs's own documentation solves this example at input angle 0 and prints the foot
/// (joint 7, `J8` here) at (-43.170055, -91.753226): `expr_solving` of this example with
/// input angle 0, "print(x, y)  # -43.170055 -91.753226", in Pyslvs's usage example (as
/// copied in qunat/Pythonocc-CAD, module/slove_test.py). The imported scene, with its
/// three-link joints, gives the same foot to the 6 decimals printed (1e-6 mm).
#[test]
fn an_imported_jansen_leg_puts_the_foot_where_pyslvs_does() {
    let (_, got) = imported("tests/data/import/jansen.pyslvs");
    let (phi, x, y) = (
        got.column("phi").unwrap(),
        got.column("x_J8").unwrap(),
        got.column("y_J8").unwrap(),
    );
    assert_eq!(phi[0], 0.0);
    assert!((x[0] * 1e3 + 43.170055).abs() < 1e-6, "{}", x[0] * 1e3);
    assert!((y[0] * 1e3 + 91.753226).abs() < 1e-6, "{}", y[0] * 1e3);
}

fn import_error(name: &str, text: &str) -> String {
    let source = Source::new(name, text);
    let e = import::read(&source)
        .and_then(|l| l.to_scene(&source))
        .unwrap_err();
    assert!(matches!(e, mechdiff::Error::Import { .. }), "{e:?}");
    e.to_string()
}

#[test]
fn what_cannot_be_imported_is_refused_at_its_line_and_column() {
    // Line 2, column 3: the `RP` of the second joint.
    let e = import_error(
        "m.pyslvs",
        "M[J[R, P[0, 0], L[ground, L1]],\nJ[RP, A[0.0], P[1, 0], L[L1, L2]]]",
    );
    assert!(e.starts_with("m.pyslvs:2:3: an `RP` joint"), "{e}");
    let e = import_error("m.pyslvs", "M[J[R, P[0, 0 L[ground, L1]]]");
    assert!(
        e.starts_with("m.pyslvs:1:15: expected `]` after the coordinates, found `L`"),
        "{e}"
    );
    let e = import_error("m.pyslvs", "M[J[P, P[0, 0], L[ground, L1]]]");
    assert!(e.contains("a `P` joint needs its angle"), "{e}");
    let e = import_error("m.txt", "ground,input,R,0,0\ninput,coupler,X,1,1\n");
    assert!(e.starts_with("m.txt:2:1: no joint type"), "{e}");
    let e = import_error("m.txt", "ground,input,R,0,zero\n");
    assert!(
        e.starts_with("m.txt:1:18: y coordinate: `zero` is not a number"),
        "{e}"
    );
    let e = import_error(
        "m.txt",
        "ground,a,R,0,0,tfft\na,b,R,1,0,tfft\nb,ground,R,2,0\n",
    );
    assert!(e.starts_with("m.txt:2:11: a second driving input"), "{e}");
    let e = import_error("m.txt", "a,b,G,0,0\n");
    assert!(e.contains("a `G` joint is not imported yet"), "{e}");
    let e = import_error("m.txt", "a,b,R,0,0\nb,c,R,1,0\n");
    assert!(e.contains("no joint is on `ground`"), "{e}");
}

#[test]
fn import_writes_with_out_and_never_replaces_a_file_without_force() {
    let dir = std::env::temp_dir().join(format!("mechdiff-import-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("scene.toml");
    let mechdiff = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_mechdiff"))
            .args(args)
            .current_dir(env!("CARGO_MANIFEST_DIR"))
            .output()
            .unwrap()
    };
    let input = "tests/data/import/crank_rocker.pyslvs";
    let o = out.to_str().unwrap();
    let first = mechdiff(&["import", input, "--out", o]);
    assert!(
        first.status.success(),
        "{}",
        String::from_utf8_lossy(&first.stderr)
    );
    let written = std::fs::read_to_string(&out).unwrap();
    assert!(scene::parse("s.toml", &written).is_ok());
    std::fs::write(&out, "kept").unwrap();
    let again = mechdiff(&["import", input, "--out", o]);
    assert!(!again.status.success());
    assert!(String::from_utf8_lossy(&again.stderr).contains("give --force"));
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "kept");
    let forced = mechdiff(&["import", input, "--out", o, "--force"]);
    assert!(forced.status.success());
    assert_eq!(std::fs::read_to_string(&out).unwrap(), written);
    let onto_input = mechdiff(&["import", input, "--out", input, "--force"]);
    assert!(String::from_utf8_lossy(&onto_input.stderr).contains("refusing to write"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A PMKS chain of `k` four-bars in a row (2k + 1 moving links): rocker `Ri` pinned to the
/// ground at (i, 0), its top at (i, 1 + 0.1 sin i) pinned to couplers `C(i-1)` and `Ci`;
/// the first rocker drives. Each four-bar adds 6 coordinates and 6 equations: one degree of
/// freedom in all, with loops of 6 coordinates. With `toggle = Some(m)`, the tops of rockers
/// m − 1 and m are drawn at (m, 2) and (m, 1): coupler m − 1 in line with rocker m, a toggle
/// of the m-th four-bar.
fn chain_of_four_bars(k: usize, toggle: Option<usize>) -> String {
    let mut text = String::from("mech=\n");
    for i in 0..=k {
        let (x, y) = (i as f64, 1.0 + 0.1 * (i as f64).sin());
        let top = match toggle {
            Some(m) if i + 1 == m => (m as f64, 2.0),
            Some(m) if i == m => (m as f64, 1.0),
            _ => (x, y),
        };
        let drive = if i == 0 { 't' } else { 'f' };
        text.push_str(&format!("ground,R{i},R,{x},0,tff{drive}\n"));
        let mut links = vec![format!("R{i}")];
        if i > 0 {
            links.push(format!("C{}", i - 1));
        }
        if i < k {
            links.push(format!("C{i}"));
        }
        text.push_str(&format!(
            "{},R,{},{:.6},tfff\n",
            links.join(","),
            top.0,
            top.1
        ));
    }
    text
}

/// Issue 22: `check` of an 800-link chain from `import` ran past a minute (one SVD of the
/// whole 2403×2403 Jacobian); the loops are now judged one by one, so it is checked with
/// the same counts (rank = coordinates = 3 × 801 moving links), and a chain past the
/// documented limit of 3000 coordinates is refused with the limit named, before any work.
#[test]
fn an_800_link_chain_is_checked_and_a_larger_one_refused_at_the_limit() {
    let checked = |k: usize, toggle: Option<usize>| {
        let source = Source::new("chain.pmks", chain_of_four_bars(k, toggle));
        let text = import::read(&source)
            .and_then(|l| l.to_scene(&source))
            .unwrap_or_else(|e| panic!("{e}"));
        // The import's full turn passes the chain's limit positions (the first at 4.62°),
        // which `check` refuses as `run` does; the mobility is judged at the sketch (90°).
        let full_turn = "from = 0\nto = 360\nstep = 5\n";
        assert!(text.contains(full_turn));
        let text = text.replace(full_turn, "positions = [90]\n");
        let scene = scene::parse("chain.toml", &text).unwrap_or_else(|e| panic!("{e}"));
        scene::check(&scene)
    };
    let chain = checked(400, None).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(chain.mechanism.links().len(), 802);
    let m = chain.mobility;
    assert_eq!(
        (m.coordinates, m.rank, m.degrees_of_freedom),
        (2403, 2403, 1)
    );
    let e = checked(500, None).map(|_| ()).unwrap_err().to_string();
    assert!(
        e.contains("3003 pose coordinates (3 per moving link), over the limit of 3000"),
        "{e}"
    );
    // Judged loop by loop, a chain drawn at a toggle of its 30th four-bar (coupler C29 in
    // line with rocker R30) is still a singular sketch, naming that loop's joints (the
    // joints at the pivot and top of R30 are J61 and J62).
    let e = checked(100, Some(30)).map(|_| ()).unwrap_err().to_string();
    assert!(
        e.contains("singular") && e.contains("J61") && e.contains("J62"),
        "{e}"
    );
}
