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
    /// Emitted Rust did not parse back (a bug in the emitter).
    #[error("emitted Rust is not valid: {reason}")]
    InvalidEmittedRust {
        /// The parser's message.
        reason: String,
    },
}

/// `message` followed by the input with a caret under character `position`.
fn show_position(input: &str, position: usize, message: &str) -> String {
    let column = position + 1;
    format!("{message} (column {column})\n  {input}\n  {:>column$}", "^")
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
