//! Finding the four-bar and slider-crank loops of a mechanism model, wherever they are.
//!
//! The link graph (links as nodes, joints as edges) is searched for cycles through the
//! ground:
//! - **four-bar**: ground – input – coupler – output – ground, four distinct links joined by
//!   four revolute joints, no two consecutive ones at the same point (no zero length);
//! - **slider-crank**: ground – crank – rod by two revolutes, then the rod's pin B on a
//!   straight path of the ground: a revolute to a slider that a prismatic joint guides along
//!   a line of the ground, or a pin-in-slot joint whose slot is on the ground.
//!
//! Which link is the input follows from the solver's loops (see [`crate::geometry::branch`]):
//! the input is placed by an earlier loop than the coupler and output (resp. rod and
//! slider), and those two are placed together by one loop of their own (a dyad). So a
//! four-bar inside a six-bar is found (a Watt's or Stephenson's first loop, or a second
//! four-bar driven by the first's output), and so is a loop driven through its input by
//! other links; its input is *driven* when its pivot is the mechanism's angle drive.
//!
//! Every solver loop whose links no recognised loop covers is reported as not applicable,
//! with why: a cycle found but whose input is not placed first (e.g. a slider-crank driven
//! at its slider, an engine), or no such cycle at all (slotted links, gears, racks, loops
//! of five or more links). Links welded by a rigid joint are two links to this search: draw
//! a ternary link as one link with three points to have its loops recognised.

use super::four_bar::{FourBarLoop, angle_from, sub};
use super::grashof::{FourBarLengths, SliderCrankLengths, length_tolerance};
use super::input_range::InputFrame;
use super::slider_crank::SliderCrankLoop;
use super::transmission::TransmissionAngle;
use crate::Error;
use crate::geometry::branch;
use crate::geometry::{DriveKind, Equations, JointKind, Mechanism, check_mobility};

/// Links that no recognised loop covers, and why they have no linkage metrics.
#[derive(Debug, Clone, PartialEq)]
pub struct NotApplicable {
    /// The links (one loop of the solver).
    pub links: Vec<String>,
    /// The joints of that loop (the drive named as "drive `O2`").
    pub joints: Vec<String>,
    /// Why no metrics apply.
    pub reason: String,
}

/// The loops of a mechanism: those recognised, and the rest.
#[derive(Debug, Clone, PartialEq)]
pub struct Loops {
    /// Four-bar loops.
    pub four_bars: Vec<FourBarLoop>,
    /// Slider-crank loops.
    pub slider_cranks: Vec<SliderCrankLoop>,
    /// Solver loops no recognised loop covers.
    pub not_applicable: Vec<NotApplicable>,
}

/// A revolute joint: index, the two links, the point.
#[derive(Clone, Copy)]
struct Hinge {
    joint: usize,
    links: [usize; 2],
    point: usize,
}

impl Hinge {
    /// The link across the hinge from `link`, if the hinge touches it.
    fn other(&self, link: usize) -> Option<usize> {
        match self.links {
            [a, b] if a == link => Some(b),
            [a, b] if b == link => Some(a),
            _ => None,
        }
    }
}

/// The link graph: the revolute joints, and the joints at each link.
struct Graph {
    hinges: Vec<Hinge>,
    /// Per link, indices into `hinges` of the revolutes at it.
    hinges_at: Vec<Vec<usize>>,
    /// Per link, indices of all the joints joining it to another link.
    joints_at: Vec<Vec<usize>>,
}

impl Graph {
    fn new(m: &Mechanism) -> Graph {
        let links = m.links().len();
        let (mut hinges, mut hinges_at, mut joints_at) =
            (Vec::new(), vec![Vec::new(); links], vec![Vec::new(); links]);
        for (joint, j) in m.joints().iter().enumerate() {
            let Some(joined) = j.kind.joined_links() else {
                continue;
            };
            for k in joined {
                joints_at[k].push(joint);
            }
            if let JointKind::Revolute {
                link_a,
                link_b,
                point,
            } = j.kind
            {
                for k in joined {
                    hinges_at[k].push(hinges.len());
                }
                hinges.push(Hinge {
                    joint,
                    links: [link_a, link_b],
                    point,
                });
            }
        }
        Graph {
            hinges,
            hinges_at,
            joints_at,
        }
    }

    /// The revolutes at `link` other than joint `except`, with the link across each.
    fn hinges_at(&self, link: usize, except: usize) -> impl Iterator<Item = (&Hinge, usize)> {
        (self.hinges_at[link].iter())
            .map(|&h| &self.hinges[h])
            .filter(move |h| h.joint != except)
            .filter_map(move |h| h.other(link).map(|other| (h, other)))
    }
}

/// The solver's loops as link sets, and which loop places each link.
struct Order {
    /// Per link, the index of the solver loop placing it (`usize::MAX` for the ground).
    of_link: Vec<usize>,
    /// Per solver loop, its links and the joints its rows come from.
    loops: Vec<(Vec<usize>, Vec<usize>)>,
}

impl Order {
    fn new(m: &Mechanism) -> Option<Order> {
        let eq = Equations::new(m);
        let loops = branch::loops(&eq)?;
        let mut of_link = vec![usize::MAX; m.links().len()];
        let mut sets = Vec::new();
        for (i, l) in loops.iter().enumerate() {
            let mut links: Vec<usize> = l.columns.iter().map(|&c| c / 3 + 1).collect();
            links.sort_unstable();
            links.dedup();
            for &k in &links {
                of_link[k] = i;
            }
            let mut joints: Vec<usize> = l.rows.iter().map(|&r| eq.row_joint[r]).collect();
            joints.sort_unstable();
            joints.dedup();
            sets.push((links, joints));
        }
        Some(Order {
            of_link,
            loops: sets,
        })
    }

    /// Whether `input` is placed before `dyad`, and `dyad` is exactly one solver loop.
    fn input_first(&self, input: usize, dyad: &[usize]) -> bool {
        let l = self.of_link[dyad[0]];
        let mut want = dyad.to_vec();
        want.sort_unstable();
        self.of_link[input] < l && self.loops[l].0 == want
    }
}

impl Loops {
    /// The four-bar and slider-crank loops of `m` (see the module documentation).
    ///
    /// # Errors
    /// The errors of [`check_mobility`] (too large a model, over- or under-constrained);
    /// [`Error::Underconstrained`] when the equations split into no loops.
    pub fn find(m: &Mechanism) -> Result<Loops, Error> {
        // Bounds the mechanism's size (and says what is wrong with its mobility) before
        // the search.
        check_mobility(m)?;
        let order = Order::new(m).ok_or_else(|| Error::Underconstrained {
            free: 0,
            links: Vec::new(),
            joints: m.joints().iter().map(|j| j.name.clone()).collect(),
        })?;
        let graph = Graph::new(m);
        let mut found = Loops {
            four_bars: Vec::new(),
            slider_cranks: Vec::new(),
            not_applicable: Vec::new(),
        };
        // Cycles found whose input is not placed first: (links, description).
        let mut rejected: Vec<(Vec<usize>, String)> = Vec::new();
        for (pivot, input) in graph.hinges_at(0, usize::MAX) {
            for (pin, coupler) in graph.hinges_at(input, pivot.joint) {
                if coupler == 0 || coupler == input {
                    continue;
                }
                four_bars(m, &order, &graph, [pivot, pin], &mut found, &mut rejected);
                slider_cranks(m, &order, &graph, [pivot, pin], &mut found, &mut rejected);
            }
        }
        found.not_applicable = not_applicable(m, &order, &found, &rejected);
        Ok(found)
    }
}

/// The four-bars through `pivot` (ground–input) and `pin` (input–coupler).
fn four_bars(
    m: &Mechanism,
    order: &Order,
    graph: &Graph,
    [pivot, pin]: [&Hinge; 2],
    found: &mut Loops,
    rejected: &mut Vec<(Vec<usize>, String)>,
) {
    let Some(input) = pivot.other(0) else {
        return;
    };
    let Some(coupler) = pin.other(input) else {
        return;
    };
    for (joint, output) in graph.hinges_at(coupler, pin.joint) {
        if [0, input, coupler].contains(&output) {
            continue;
        }
        let frame_pivots = graph.hinges_at(output, joint.joint);
        for (out_pivot, _) in frame_pivots.filter(|&(_, other)| other == 0) {
            let points = [pivot.point, pin.point, joint.point, out_pivot.point];
            let links = vec![input, coupler, output];
            if !order.input_first(input, &[coupler, output]) {
                let names = links.iter().map(|&k| m.links()[k].name.as_str());
                let names: Vec<&str> = names.collect();
                let text = format!(
                    "four-bar loop ground–{}: its input is not placed before its coupler and \
                     output (driven elsewhere, or its links are solved together with others)",
                    names.join("–")
                );
                rejected.push((links, text));
                continue;
            }
            let joints = [pivot, pin, joint, out_pivot].map(|h| h.joint);
            if let Some(l) = four_bar(m, [0, input, coupler, output], joints, points) {
                found.four_bars.push(l);
            }
        }
    }
}

/// The four-bar loop of `links` (frame, input, coupler, output), `joints` and `points`
/// (O_in, A, B, O_out); `None` when a length is zero.
fn four_bar(
    m: &Mechanism,
    links: [usize; 4],
    joints: [usize; 4],
    points: [usize; 4],
) -> Option<FourBarLoop> {
    let [o_in, a, b, o_out] = points.map(|p| m.points()[p].sketch);
    let length = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
    let lengths = FourBarLengths {
        frame: length(o_in, o_out),
        input: length(o_in, a),
        coupler: length(a, b),
        output: length(b, o_out),
    };
    let all = [
        lengths.frame,
        lengths.input,
        lengths.coupler,
        lengths.output,
    ];
    if all.contains(&0.0) {
        return None;
    }
    let name = |k: usize| m.links()[k].name.clone();
    let point = |link: usize, p: usize| {
        let (l, q) = (&m.links()[link].name, &m.points()[p].name);
        m.point_output(l, q).ok()
    };
    let (input, coupler, output) = (links[1], links[2], links[3]);
    let outputs = [
        point(coupler, points[1])?,
        point(coupler, points[2])?,
        point(output, points[3])?,
    ];
    let sketch = TransmissionAngle::between(sub(a, b), sub(o_out, b));
    Some(FourBarLoop {
        links: links.map(name),
        joints: joints.map(|j| m.joints()[j].name.clone()),
        lengths,
        driven: drive_sign(m, joints[0], input).is_some(),
        tolerance: length_tolerance(&all, magnitude([o_in, a, b, o_out])),
        branch: if sketch.signed >= 0.0 { 1.0 } else { -1.0 },
        input: InputFrame {
            sketch: angle_from(sub(o_out, o_in), o_in, a),
            drive: drive_sign(m, joints[0], input).map(|s| (m.drive_at_sketch(), s)),
        },
        points: outputs,
        output_rotation: m.rotation_output(&m.links()[output].name).ok()?,
    })
}

/// How a rod's pin B runs on a straight path of the ground.
struct Path {
    /// The slider link (`None`: the pin runs in a slot of the ground).
    slider: Option<usize>,
    /// The pin B (a point of the rod).
    pin: usize,
    /// The joints after the crank pin: rod–slider and the guide, or the pin-in-slot.
    joints: Vec<usize>,
    /// The path's line: two points of the ground.
    line: [usize; 2],
}

/// The slider-cranks through `pivot` (ground–crank) and `pin` (crank–rod).
fn slider_cranks(
    m: &Mechanism,
    order: &Order,
    graph: &Graph,
    [pivot, pin]: [&Hinge; 2],
    found: &mut Loops,
    rejected: &mut Vec<(Vec<usize>, String)>,
) {
    let Some(crank) = pivot.other(0) else {
        return;
    };
    let Some(rod) = pin.other(crank) else {
        return;
    };
    let name = |k: usize| m.links()[k].name.clone();
    let mut paths: Vec<Path> = Vec::new();
    for &j in &graph.joints_at[rod] {
        if let JointKind::PinInSlot {
            slot_link: 0,
            line,
            pin_link,
            pin: point,
        } = m.joints()[j].kind
            && pin_link == rod
        {
            paths.push(Path {
                slider: None,
                pin: point,
                joints: vec![j],
                line,
            });
        }
    }
    for (hinge, slider) in graph.hinges_at(rod, pin.joint) {
        if [0, crank, rod].contains(&slider) {
            continue;
        }
        for &j in &graph.joints_at[slider] {
            if let JointKind::Prismatic {
                guide: 0,
                line,
                slider: moving,
                ..
            } = m.joints()[j].kind
                && moving == slider
            {
                paths.push(Path {
                    slider: Some(slider),
                    pin: hinge.point,
                    joints: vec![hinge.joint, j],
                    line,
                });
            }
        }
    }
    for Path {
        slider,
        pin: point,
        joints: rest,
        line,
    } in paths
    {
        let dyad: Vec<usize> = [rod].into_iter().chain(slider).collect();
        let mut links = vec![crank];
        links.extend(&dyad);
        if !order.input_first(crank, &dyad) {
            let names: Vec<String> = links.iter().map(|&k| name(k)).collect();
            let text = format!(
                "slider-crank loop ground–{}: its crank is not placed before its rod (driven \
                 at the slider, or solved together with other links)",
                names.join("–")
            );
            rejected.push((links, text));
            continue;
        }
        let p = |i: usize| m.points()[i].sketch;
        let (o, a, b) = (p(pivot.point), p(pin.point), p(point));
        let (g0, g1) = (p(line[0]), p(line[1]));
        let d = sub(g1, g0);
        let norm = d[0].hypot(d[1]);
        let u = [d[0] / norm, d[1] / norm];
        let ob = sub(b, o);
        let lengths = SliderCrankLengths {
            crank: (a[0] - o[0]).hypot(a[1] - o[1]),
            rod: (b[0] - a[0]).hypot(b[1] - a[1]),
            offset: u[0] * ob[1] - u[1] * ob[0],
        };
        if lengths.crank == 0.0 || lengths.rod == 0.0 {
            continue;
        }
        let on_rod = |q: usize| m.point_output(&name(rod), &m.points()[q].name).ok();
        let (Some(pa), Some(pb)) = (on_rod(pin.point), on_rod(point)) else {
            continue;
        };
        let mut joints = vec![pivot.joint, pin.joint];
        joints.extend(rest);
        let sketch = TransmissionAngle::between(sub(a, b), [-u[1], u[0]]);
        let all = [lengths.crank, lengths.rod, lengths.offset];
        found.slider_cranks.push(SliderCrankLoop {
            frame: name(0),
            crank: name(crank),
            rod: name(rod),
            slider: slider.map(name),
            joints: joints.iter().map(|&j| m.joints()[j].name.clone()).collect(),
            lengths,
            driven: drive_sign(m, pivot.joint, crank).is_some(),
            tolerance: length_tolerance(&all, magnitude([o, a, b, g0])),
            branch: if sketch.signed >= 0.0 { 1.0 } else { -1.0 },
            direction: u,
            input: InputFrame {
                sketch: angle_from(u, o, a),
                drive: drive_sign(m, pivot.joint, crank).map(|s| (m.drive_at_sketch(), s)),
            },
            points: [pa, pb],
            pivot: o,
        });
    }
}

/// dφ/dθ (±1) when joint `pivot` is the angle drive and θ is `input`'s rotation.
fn drive_sign(m: &Mechanism, pivot: usize, input: usize) -> Option<f64> {
    if m.drive_joint() != pivot || *m.drive_kind() != DriveKind::Angle {
        return None;
    }
    match m.joints()[pivot].kind {
        JointKind::Revolute { link_b, .. } => Some(if link_b == input { 1.0 } else { -1.0 }),
        _ => None,
    }
}

/// The largest coordinate magnitude of `points` (what their rounding is relative to).
fn magnitude<const K: usize>(points: [[f64; 2]; K]) -> f64 {
    (points.iter().flatten()).fold(0.0, |m, x| m.max(x.abs()))
}

/// The solver loops no recognised loop covers.
fn not_applicable(
    m: &Mechanism,
    order: &Order,
    found: &Loops,
    rejected: &[(Vec<usize>, String)],
) -> Vec<NotApplicable> {
    let mut covered = vec![false; m.links().len()];
    let index = |name: &str| m.link_index(name).ok();
    for l in &found.four_bars {
        for k in l.links.iter().filter_map(|n| index(n)) {
            covered[k] = true;
        }
    }
    for l in &found.slider_cranks {
        let names = [&l.crank, &l.rod].into_iter().chain(l.slider.as_ref());
        for k in names.filter_map(|n| index(n)) {
            covered[k] = true;
        }
    }
    let mut out = Vec::new();
    for (links, joints) in &order.loops {
        if links.iter().all(|&k| covered[k]) {
            continue;
        }
        // A rejected cycle all of whose links a recognised loop covers is that loop taken
        // the other way round.
        let reason = (rejected.iter())
            .filter(|(cycle, _)| !cycle.iter().all(|&k| covered[k]))
            .find(|(cycle, _)| links.iter().any(|k| cycle.contains(k)))
            .map(|(_, text)| text.clone())
            .unwrap_or_else(|| {
                let mut kinds: Vec<&str> = (joints.iter())
                    .filter(|&&j| j < m.joints().len())
                    .map(|&j| m.joints()[j].kind.kind_name())
                    .collect();
                kinds.dedup();
                format!(
                    "no four-bar (four revolute joints) or slider-crank loop through the \
                     ground contains these links (their joints: {})",
                    kinds.join(", ")
                )
            });
        out.push(NotApplicable {
            links: links.iter().map(|&k| m.links()[k].name.clone()).collect(),
            joints: (joints.iter())
                .map(|&j| match m.joints().get(j) {
                    Some(joint) => joint.name.clone(),
                    None => format!("drive `{}`", m.joints()[m.drive_joint()].name),
                })
                .collect(),
            reason,
        });
    }
    out
}
