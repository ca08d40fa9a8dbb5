//! The errors of mechdiff-core.

use thiserror::Error;

/// Everything that can go wrong in mechdiff-core.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A sweep over the drive variable is not a finite, non-empty range with a positive step.
    #[error("invalid sweep from {start} to {end} with step {step}: {reason}")]
    InvalidSweep {
        /// First drive position.
        start: f64,
        /// Last drive position.
        end: f64,
        /// Step between drive positions.
        step: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A computed quantity is NaN or infinite at a drive position where it should be finite.
    #[error("{quantity} is not finite at drive position φ = {phi}")]
    NonFinite {
        /// The drive position.
        phi: f64,
        /// Which quantity.
        quantity: &'static str,
    },
    // ---- geometry-only mechanisms (`geometry` module) ----
    /// Two items of the same kind share a name.
    #[error("duplicate {what} name `{name}`")]
    DuplicateName {
        /// "point", "link" or "joint".
        what: &'static str,
        /// The repeated name.
        name: String,
    },
    /// A name refers to nothing declared.
    #[error("unknown {what} `{name}` (in {context})")]
    UnknownName {
        /// "point", "link" or "joint".
        what: &'static str,
        /// The unknown name.
        name: String,
        /// Where it was used, e.g. "joint `A`".
        context: String,
    },
    /// A joint uses a point that the link it names does not carry.
    #[error("point `{point}` is not on link `{link}` (in {context})")]
    PointNotOnLink {
        /// The point.
        point: String,
        /// The link.
        link: String,
        /// Where, e.g. "joint `A`".
        context: String,
    },
    /// A length that must be positive is not (coincident line points, zero radius, ...).
    #[error("{what} must have a positive length, got {length} m")]
    NonPositiveLength {
        /// What the length belongs to, e.g. "slot line of joint `S`".
        what: String,
        /// The offending length (m).
        length: f64,
    },
    /// A number given in the model is NaN or infinite, or out of its range.
    #[error("invalid value {value} for {what}")]
    InvalidValue {
        /// What the value is, e.g. "x of point `A`".
        what: String,
        /// The value.
        value: f64,
    },
    /// A joint refers to a joint of the wrong kind, or joins a link to itself.
    #[error("joint `{joint}`: {problem}")]
    InvalidJoint {
        /// The joint.
        joint: String,
        /// What is wrong with it.
        problem: String,
    },
    /// The sketch does not satisfy a joint (e.g. a pin drawn off its slot line).
    #[error("the sketch does not satisfy joint `{joint}` (residual {residual:e} m)")]
    SketchNotAssembled {
        /// The joint.
        joint: String,
        /// The constraint residual at the sketch pose.
        residual: f64,
    },
    /// The model has no drive.
    #[error("the mechanism has no drive")]
    MissingDrive,
    /// More independent equations than coordinates, or dependent equations.
    #[error(
        "over-constrained: the equations of joint(s) {} are redundant at the sketch pose \
         ({equations} equations for {coordinates} coordinates)",
        .redundant.join(", ")
    )]
    Overconstrained {
        /// Joints whose equations depend on the others' (the drive is named `drive <joint>`).
        redundant: Vec<String>,
        /// Number of equations, drive included.
        equations: usize,
        /// Number of pose coordinates.
        coordinates: usize,
    },
    /// The mechanism is larger than the mobility check holds in memory (its Jacobian is
    /// dense): refused before any work.
    #[error(
        "the mechanism has {count} {what}, over the limit of {limit}; split it into \
         smaller mechanisms"
    )]
    TooLarge {
        /// What is counted (`pose coordinates (3 per moving link)`).
        what: &'static str,
        /// How many the mechanism has.
        count: usize,
        /// The largest number accepted.
        limit: usize,
    },
    /// The drive does not fix the pose: some links can still move.
    #[error(
        "under-constrained: {free} degree(s) of freedom left with the drive fixed; \
         links {} can move, joints involved: {}",
        .links.join(", "), .joints.join(", ")
    )]
    Underconstrained {
        /// Number of free motions with the drive fixed.
        free: usize,
        /// Links that move in a free motion.
        links: Vec<String>,
        /// Joints attached to those links.
        joints: Vec<String>,
    },
    /// No assembly exists (or none was found near the previous one) at drive position `phi`.
    #[error(
        "cannot assemble at drive position φ = {phi} (last assembled at φ = {last_assembled}); \
         loop of joints {} fails (residual {residual:e})",
        .joints.join(", ")
    )]
    Unassemblable {
        /// Drive position that could not be reached.
        phi: f64,
        /// Last drive position that assembled.
        last_assembled: f64,
        /// Joints of the loop whose equations could not be satisfied.
        joints: Vec<String>,
        /// Remaining constraint residual (m).
        residual: f64,
    },
    /// A loop stops closing between two drive positions: the drive cannot move from `from`
    /// to `to`. `limit` is the limit position (to full precision) where the loop's
    /// assembly condition first fails: the drive must stop (or turn back) there.
    #[error(
        "cannot assemble between drive positions φ = {from} and φ = {to}: the loop of joints \
         {} first fails at φ = {limit} (a limit position: the drive must stop there)",
        .joints.join(", ")
    )]
    Blocked {
        /// Drive position the move started from (it assembles).
        from: f64,
        /// Drive position asked for.
        to: f64,
        /// The limit position: the first drive position from `from` towards `to` where the
        /// loop's assembly condition (its discriminant) vanishes.
        limit: f64,
        /// Joints of the loop that stops closing.
        joints: Vec<String>,
    },
    /// A move between two drive positions needs more checked sub-steps than allowed (steps
    /// are at most 1/8 rad, or 1/8 of the mechanism's size, so a move of 1e12 rad would
    /// never end).
    #[error(
        "the move from drive position φ = {from} to φ = {to} needs more than {steps} checked \
         steps of at most {longest}; ask for drive positions closer together"
    )]
    MoveTooLong {
        /// Drive position the move started from.
        from: f64,
        /// Drive position asked for.
        to: f64,
        /// The sub-steps allowed per move.
        steps: usize,
        /// The longest sub-step (rad or m).
        longest: f64,
    },
    /// A loop reaches a change point (bifurcation): two of its assembly branches meet there
    /// (the Jacobian drops rank with a finite limit, e.g. a parallelogram or kite four-bar
    /// folded flat), so the drive alone does not say how the mechanism moves on.
    #[error(
        "change point (bifurcation) at drive position φ = {phi}: two assembly branches of \
         the loop of joints {} meet there, and the drive does not decide which one the \
         mechanism follows beyond it; stop the sweep before it, or add a joint or drive \
         that fixes the branch",
        .joints.join(", ")
    )]
    ChangePoint {
        /// The drive position of the change point (to full precision).
        phi: f64,
        /// Joints of the loop whose branches meet.
        joints: Vec<String>,
    },
    /// The constraint Jacobian is singular (toggle position of the driven chain).
    #[error(
        "singular position at drive position φ = {phi} (condition number {condition:e}); \
         loop of joints {}",
        .joints.join(", ")
    )]
    Singular {
        /// Drive position.
        phi: f64,
        /// Estimated condition number of the scaled Jacobian Φ_q.
        condition: f64,
        /// Joints of the loop that is singular.
        joints: Vec<String>,
    },
    /// An expression evaluated to 0/0 where its value is used: undefined as written (a
    /// removable singularity if the quotient has a limit there, e.g. sin x / x at 0).
    #[error(
        "0/0 in `{expression}` at the values given: the formula is undefined there as \
         written; if it has a limit (a removable singularity such as sin(x)/x at 0), write \
         the limit as a piecewise formula or evaluate beside the point"
    )]
    ZeroOverZero {
        /// The quotient, as an S-expression (shortened).
        expression: String,
    },
    /// `powf` with a base of exactly 0 in dual numbers: num-dual forms `u^v` as
    /// `exp(v·ln u)`, whose derivatives at `u = 0` are NaN even where the true ones are
    /// finite limits (`x^3.5` at 0: 0, 0, 0, 0, one-sided).
    #[error(
        "powf with base 0 in `{expression}`: the chain rule through exp(v·ln u) is undefined \
         there; its derivatives, where they exist, are limits (x^3.5 at 0: 0, 0, 0, 0 from \
         above), which `mechdiff accuracy` takes by Taylor series; elsewhere move the point \
         off the zero of the base"
    )]
    PowerOfZero {
        /// The power, as an S-expression (shortened).
        expression: String,
    },
    /// A formula has no value and derivatives to order 3 at a point, not even as a limit:
    /// its series there is not a Taylor series (`|x|` at 0, `x^2.5` at 0 to order 3), or it
    /// is not real on either side of the point.
    #[error("`{expression}` has no derivatives to order 3 at the point: {reason}")]
    NotDifferentiable {
        /// The output, as an S-expression (shortened).
        expression: String,
        /// Why, naming the function and the order of the zero that causes it.
        reason: String,
    },
    /// A derivative is infinite where it is used: `function` at the edge of its domain.
    #[error(
        "the derivative of {function} is infinite at {at} (in `{expression}`): a true \
         singularity of the derivatives; move the point off the domain's edge"
    )]
    InfiniteDerivative {
        /// The function (asin, acos, sqrt).
        function: String,
        /// Its argument.
        at: f64,
        /// The function's node, as an S-expression (shortened).
        expression: String,
    },
    /// A computation that needs every loop in closed form met a loop the solver closes by
    /// Newton's method (no closed-form pattern matches it).
    #[error(
        "{what} needs every loop in closed form; the loop of joints {} has none (it is \
         solved by Newton's method)",
        .joints.join(", ")
    )]
    NoClosedForm {
        /// What needed the closed forms.
        what: String,
        /// Joints of the loop without a closed form.
        joints: Vec<String>,
    },
    /// A step would switch a loop to its other assembly branch, and subdividing did not help.
    #[error(
        "assembly branch of the loop of joints {} would flip between φ = {from} and φ = {to}",
        .joints.join(", ")
    )]
    BranchFlip {
        /// Last drive position on the sketch's branch.
        from: f64,
        /// Drive position where the flip was detected.
        to: f64,
        /// Joints of the loop.
        joints: Vec<String>,
    },
    /// A name given to an output or query is unknown or of the wrong kind.
    #[error("output `{name}`: {problem}")]
    InvalidOutput {
        /// The name asked for.
        name: String,
        /// What is wrong.
        problem: String,
    },
    /// Data given for the exact parameter sensitivities (`geometry::parametric`) does not
    /// fit the mechanism: a [`crate::geometry::DataTangent`] of the wrong shape, or a pose
    /// of another mechanism.
    #[error("{what} does not fit the mechanism: {problem}")]
    ParametricMismatch {
        /// What was given, e.g. "the data tangent's points".
        what: String,
        /// What is wrong, and what would fit.
        problem: String,
    },
    // ---- dynamics (`dynamics` module) ----
    /// No friction forces consistent with the relative velocities exist at this drive
    /// position (the mechanism is self-locking there), or the iteration on the normal forces
    /// does not settle.
    #[error(
        "self-locking at drive position φ = {phi}: no friction forces in joint(s) {} are \
         consistent with the relative velocities ({reason})",
        .joints.join(", ")
    )]
    SelfLocking {
        /// Drive position.
        phi: f64,
        /// Joints with friction or efficiency whose forces could not be made consistent.
        joints: Vec<String>,
        /// Why: a singular equilibrium system, or signs that keep changing.
        reason: String,
    },
    /// The equilibrium equations of the links are singular at this drive position (the
    /// reactions are not determined by the equations, e.g. at a toggle).
    #[error("the equilibrium equations are singular at drive position φ = {phi}")]
    SingularEquilibrium {
        /// Drive position.
        phi: f64,
    },
    /// An effect or output needs data the model does not have.
    #[error("{what} needs {missing}")]
    MissingData {
        /// What asked for it, e.g. "the shaking force".
        what: String,
        /// What is missing, e.g. "mass properties of at least one link".
        missing: String,
    },
    // ---- balancing (`balancing` module) ----
    /// The two correction planes of a two-plane balance are at the same axial position (or
    /// too close to determine the corrections).
    #[error(
        "the correction planes at axial positions {left} m and {right} m coincide: two-plane \
         balancing needs two distinct planes (move one of them along the shaft)"
    )]
    CoincidentPlanes {
        /// Axial position of the first plane (m).
        left: f64,
        /// Axial position of the second plane (m).
        right: f64,
    },
    /// A balancing question has no answer because there is nothing to balance.
    #[error("{what} is already zero: no correction is determined")]
    AlreadyBalanced {
        /// What is already balanced, e.g. "the couple about the reference plane".
        what: String,
    },
    /// A counterweight is asked for on a link that does not turn about a fixed pivot at the
    /// given point.
    #[error(
        "counterweight on link `{link}`: it must turn about a fixed pivot, and `{point}` is not \
         a revolute joint between `{link}` and the ground (give the line from the link's \
         ground pivot)"
    )]
    NotPivoted {
        /// The link.
        link: String,
        /// The point named as its pivot.
        point: String,
    },
    // ---- cams (`cams` module) ----
    /// The segments of a cam program do not add up to one turn.
    #[error(
        "the cam segments cover {total_deg}° instead of 360°; adjust the extents so that they \
         add up to one turn"
    )]
    CamTurn {
        /// Sum of the segments' extents (degrees).
        total_deg: f64,
    },
    /// A segment of a cam program is not valid (extent not positive, lift not finite, a
    /// dwell with a lift, a formula that does not evaluate).
    #[error("cam segment {segment} (starting at cam angle {start_deg}°): {problem}")]
    CamSegment {
        /// Index of the segment, from 1.
        segment: usize,
        /// Cam angle where the segment starts (degrees).
        start_deg: f64,
        /// What is wrong and how to fix it.
        problem: String,
    },
    /// Two consecutive segments do not meet in displacement.
    #[error(
        "the follower displacement does not join at cam angle {angle_deg}° between segment \
         {before} (ends at {left}) and segment {after} (starts at {right})"
    )]
    CamJoin {
        /// Cam angle of the boundary (degrees).
        angle_deg: f64,
        /// The segment that ends there, from 1.
        before: usize,
        /// The segment that starts there, from 1.
        after: usize,
        /// Displacement at the end of `before`.
        left: f64,
        /// Displacement at the start of `after`.
        right: f64,
    },
    /// A dimension of the cam or follower is out of its range (roller radius not positive,
    /// offset not smaller than the prime circle radius, ...).
    #[error("{what} = {value}: {problem}")]
    CamDimension {
        /// Which dimension.
        what: String,
        /// Its value.
        value: f64,
        /// What is wrong and how to fix it.
        problem: String,
    },
    // ---- symbolic engine (`symbolic` module) ----
    /// A formula (s-expression or infix) is malformed; `position` is the character offset of
    /// the problem in `input`.
    #[error("{}", show_position(input, *position, message))]
    Formula {
        /// The formula as given.
        input: String,
        /// Character offset (0-based) of the problem.
        position: usize,
        /// What is wrong there.
        message: String,
    },
    /// A symbolic evaluation needs the value of a symbol that was not given.
    #[error("no value given for `{symbol}`")]
    UnboundSymbol {
        /// The symbol without a value.
        symbol: String,
    },
    /// A decimal string is not a number.
    #[error("`{text}` is not a decimal number")]
    BadDecimal {
        /// The string as given.
        text: String,
    },
    /// A derivative order above the engine's limit was asked for.
    #[error(
        "derivative order {order} is above the limit of {limit}; ask for order {limit} or less"
    )]
    DerivativeOrderTooHigh {
        /// The order asked for.
        order: usize,
        /// The highest order the engine computes.
        limit: usize,
    },
    /// The derivatives grew beyond the size limit of the expression graph.
    #[error(
        "the derivative of order {order} needs more than {limit} expression nodes; ask for a \
         lower order or split the formula into smaller parts"
    )]
    ExpressionTooLarge {
        /// The order whose derivative outgrew the limit.
        order: usize,
        /// The largest number of nodes the graph may hold.
        limit: usize,
    },
    /// A derivative has a part without variables whose value is not finite (`0 / 0`).
    #[error(
        "the derivative of order {order} has a constant part equal to {value}: the formula is \
         not differentiable as written; rewrite it"
    )]
    NonFiniteConstant {
        /// The derivative order (0: the value).
        order: usize,
        /// The constant's `f64` value.
        value: f64,
    },
    /// Tracing the position solution met an operation without a symbolic form.
    #[error("code generation cannot trace `{operation}` into the symbolic engine")]
    Untraceable {
        /// The operation.
        operation: String,
    },
    /// Emitted Rust did not parse back (a bug in the emitter).
    #[error("emitted Rust is not valid: {reason}")]
    InvalidEmittedRust {
        /// The parser's message.
        reason: String,
    },
    /// The run-time evaluator cannot be compiled to native code here (`JitProgram`): the
    /// host's instruction set is not one cranelift generates code for, code generation
    /// failed, or mechdiff-core is built without its `jit` feature. The interpreter
    /// (`Program`) computes the same values.
    #[error(
        "the run-time evaluator cannot be compiled to native code: {reason} (interpret it \
         instead)"
    )]
    JitUnavailable {
        /// What cranelift said (or that the feature is off).
        reason: String,
    },
}

/// `message` followed by the input with a caret under character `position` (a long input is
/// shown as the 60 characters either side of the position).
fn show_position(input: &str, position: usize, message: &str) -> String {
    const CONTEXT: usize = 60;
    let column = position + 1;
    let chars: Vec<char> = input.chars().collect();
    let start = position.saturating_sub(CONTEXT).min(chars.len());
    let end = (position + CONTEXT).min(chars.len());
    let (before, after) = (
        if start > 0 { "…" } else { "" },
        if end < chars.len() { "…" } else { "" },
    );
    let shown: String = chars[start..end].iter().collect();
    let caret = position - start + 1 + before.chars().count();
    format!(
        "{message} (column {column})\n  {before}{shown}{after}\n  {:>caret$}",
        "^"
    )
}

impl Error {
    /// A formula error at character `position` of `input`.
    pub(crate) fn formula(input: &str, position: usize, message: impl Into<String>) -> Self {
        Error::Formula {
            input: input.to_owned(),
            position,
            message: message.into(),
        }
    }
}

/// The result type of mechdiff-core.
pub type Result<T, E = Error> = std::result::Result<T, E>;
