//! The facade crate's error type.

use std::fmt;
use std::path::PathBuf;
use std::sync::Arc;

use thiserror::Error;

/// A place in a scene file: `file:line:column` (1-based, columns in characters).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file as named on the command line (or as given to [`crate::scene::parse`]).
    pub file: Arc<str>,
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1.
    pub column: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.file, self.line, self.column)
    }
}

/// Everything that can go wrong when reading, checking or running a scene.
///
/// Errors found in the file carry its [`Location`]; errors found while solving carry the
/// drive position (in the scene's units) and the loop of joints involved.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum Error {
    /// The scene file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The scene file is larger than [`crate::files::MAX_SCENE_BYTES`].
    #[error(
        "cannot read {path}: the file is larger than {limit} bytes, the most a scene file may \
         have; is it a scene file? (a sweep of many positions is written with `from`, `to` and \
         `step`)"
    )]
    TooLarge {
        /// The file.
        path: PathBuf,
        /// The limit, in bytes.
        limit: u64,
    },
    /// The scene file is not UTF-8 text.
    #[error(
        "{location}: the file is not UTF-8 text (invalid byte 0x{byte:02x} at byte offset \
         {offset}); save the scene as UTF-8"
    )]
    NotUtf8 {
        /// The line and column of the first invalid byte.
        location: Location,
        /// Its offset from the start of the file (0-based).
        offset: usize,
        /// The byte.
        byte: u8,
    },
    /// An output file is one of the run's inputs (the scene, a cam file it names, an
    /// imported file), through any name: a link, `..` or a hard link.
    #[error(
        "refusing to write {output}: it is {role} {input} (the same file on disk); choose \
         another output file"
    )]
    OutputIsInput {
        /// The output path as given.
        output: PathBuf,
        /// What the input is: `the scene file`, `the cam file`, `the imported file`.
        role: &'static str,
        /// The input's path as it was read.
        input: PathBuf,
    },
    /// A file a scene names lies outside the scene's folder (after resolving links and
    /// `..`), and the user did not allow its folder.
    #[error(
        "{path} lies outside the scene's folder {folder} (it resolves to {resolved}); a scene \
         may name only files under its own folder: move the file there, or allow its folder \
         with `--allow-path DIR`"
    )]
    OutsideSceneFolder {
        /// The path as the scene's folder and the scene's text make it.
        path: PathBuf,
        /// The path with links and `..` resolved.
        resolved: PathBuf,
        /// The scene's folder, resolved.
        folder: PathBuf,
    },
    /// A file a scene names is not a regular file (a FIFO, a device, a folder, a file of
    /// `/proc`): refused before it is read, so the run neither hangs nor reads the kernel's
    /// data.
    #[error("cannot read {path}: it is {kind}, not a regular file; name a file holding the data")]
    NotRegularFile {
        /// The path.
        path: PathBuf,
        /// What it is instead.
        kind: &'static str,
    },
    /// The worker threads of a streamed run could not be started.
    #[error("cannot start {threads} worker threads: {reason}; try `--threads 1`")]
    Threads {
        /// The number asked for (0: one per core).
        threads: usize,
        /// The operating system's reason.
        reason: String,
    },
    /// An output file (CSV) could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The operating system's reason.
        source: std::io::Error,
    },
    /// The file is not valid TOML, or a key, type or value is not one the format knows
    /// (misspelt key, unknown joint type, unknown unit, wrong value type). The message says
    /// what was expected.
    #[error("{location}: {message}")]
    Syntax {
        /// Where.
        location: Location,
        /// What is wrong and what was expected.
        message: String,
    },
    /// A name refers to a point that is not defined in `[points]`.
    #[error("{location}: unknown point `{name}` in {context}; the points are: {known}")]
    UnknownPoint {
        /// Where the name is used.
        location: Location,
        /// The unknown name.
        name: String,
        /// What uses it, e.g. "link `crank`".
        context: String,
        /// The defined points, comma-separated.
        known: String,
    },
    /// A name refers to a link or joint that does not exist.
    #[error("{location}: unknown {what} `{name}` in {context}; expected one of: {known}")]
    UnknownName {
        /// Where the name is used.
        location: Location,
        /// "link" or "joint".
        what: &'static str,
        /// The unknown name.
        name: String,
        /// What uses it.
        context: String,
        /// The defined names, comma-separated.
        known: String,
    },
    /// A point is defined twice, or listed twice where it may appear once.
    #[error("{location}: point `{name}` appears twice in {context}")]
    DuplicatePoint {
        /// Where the second occurrence is.
        location: Location,
        /// The point.
        name: String,
        /// Where it may appear once, e.g. "`[points]`" or "link `rocker`".
        context: String,
    },
    /// A length (distance, radius, line between two points, sweep step) is zero or negative.
    #[error("{location}: {what} must be positive, found {value}")]
    NonPositiveLength {
        /// Where.
        location: Location,
        /// What the length is.
        what: String,
        /// The value found, in the file's units.
        value: f64,
    },
    /// A number is outside the range the engine accepts for its quantity (see
    /// `docs/scene-format.md`, "Ranges").
    #[error("{location}: {what} = {value} is out of range; expected {expected}")]
    OutOfRange {
        /// Where.
        location: Location,
        /// What the number is.
        what: String,
        /// The value found, with its unit.
        value: String,
        /// The accepted range, with its unit.
        expected: String,
    },
    /// A result is not a finite number: the computation overflowed (or divided by zero) for
    /// this combination of inputs.
    #[error(
        "{file}: {quantity} is {value} at drive position {position}: the computation left the \
         range of f64; the scene's numbers are too large or too small together (check the drive \
         speed, masses, lengths and ratios), or the position is singular"
    )]
    NotFinite {
        /// The scene file.
        file: String,
        /// The quantity (column name with its unit, or what it is).
        quantity: String,
        /// `inf`, `-inf` or `NaN` (or `not finite` when the engine found it).
        value: String,
        /// The drive position, with its unit.
        position: String,
    },
    /// A `--set NAME=VALUE` (or a `--sweep`) that names no parameter of the scene or whose
    /// value cannot be evaluated.
    #[error("{option} {setting}: {message}")]
    Setting {
        /// The option: `--set` or `--sweep`.
        option: &'static str,
        /// The setting as given.
        setting: String,
        /// What is wrong and what is expected.
        message: String,
    },
    /// A run of a parameter sweep (`--sweep`) failed at one of the parameter's values.
    #[error("with {setting} (of --sweep): {source}")]
    AtParameter {
        /// The parameter and the value, `NAME=VALUE`.
        setting: String,
        /// What went wrong at that value.
        source: Box<Error>,
    },
    /// A file given to `mechdiff import` (Pyslvs expression, PMKS text) is not in its format
    /// or holds what a scene cannot take.
    #[error("{location}: {message}")]
    Import {
        /// Where in the imported file.
        location: Location,
        /// What is wrong and what is expected.
        message: String,
    },
    /// A point built from lengths (two circles, a circle and a line) has no solution.
    #[error("{location}: {message}")]
    Unconstructible {
        /// The point's definition.
        location: Location,
        /// The construction, its lengths, why it has no point and how to fix it.
        message: String,
    },
    /// Any other inconsistency in the file (a field missing for a joint type, a point off
    /// its slot in the sketch, a link without points, ...).
    #[error("{location}: {message}")]
    Invalid {
        /// Where.
        location: Location,
        /// What is wrong and what is expected.
        message: String,
    },
    /// The machine moving under its motor (`[simulate]`) failed: the engine's error, placed
    /// at the part of the scene it concerns (the motor's characteristic for a motor that
    /// cannot start the machine, `turns` for a steady state not found within them, …),
    /// with the drive position in the scene's units.
    #[error("{location}: {analysis}{position}: {source}")]
    Motion {
        /// Where in the scene the cause is written.
        location: Location,
        /// The analysis that failed (`"start-up"`, `"steady state"`, …).
        analysis: &'static str,
        /// ` at drive position 12.5 deg, t = 0.31 s`, when the failure has a position.
        position: String,
        /// The engine's error (boxed: it carries the geometry's error at a position).
        #[source]
        source: Box<mechdiff_core::machine::MotionError>,
    },
    /// No friction forces consistent with the motion exist at a drive position: the
    /// mechanism is self-locking there (located at the drive, which would have to push
    /// through it).
    #[error("{location}: self-locking at drive position {position}: joints {joints} ({reason})")]
    SelfLocking {
        /// Where the drive is written.
        location: Location,
        /// The drive position, with its unit.
        position: String,
        /// The joints with friction, comma-separated.
        joints: String,
        /// Why no consistent friction forces were found.
        reason: String,
    },
    /// The mechanism as a whole is rejected by the geometry model (mobility, redundancy).
    #[error("{file}: {source}")]
    Model {
        /// The scene file.
        file: String,
        /// The model's reason.
        source: mechdiff_core::Error,
    },
    /// The mechanism cannot be assembled at a drive position of the sweep.
    #[error(
        "{file}: cannot assemble at drive position {position} (last assembled at {last}): \
         the loop of joints {loop_joints} does not close (residual {residual:e} m)"
    )]
    Unassemblable {
        /// The scene file.
        file: String,
        /// The drive position, with its unit.
        position: String,
        /// The last drive position that assembled, with its unit.
        last: String,
        /// The joints of the loop that does not close, comma-separated.
        loop_joints: String,
        /// The remaining constraint residual (m).
        residual: f64,
    },
    /// A loop stops closing between two drive positions of the sweep (a limit position
    /// lies between them). (Texts boxed: keeps `Error` small.)
    #[error(
        "{file}: cannot assemble between drive positions {from} and {to}: the loop of joints \
         {loop_joints} first fails at {limit} (a limit position: the drive must stop there; \
         `mechdiff check` prints the drive's motion range)"
    )]
    Blocked {
        /// The scene file.
        file: String,
        /// The last drive position that assembled, with its unit.
        from: Box<str>,
        /// The drive position asked for, with its unit.
        to: Box<str>,
        /// The limit position, to full precision, with its unit.
        limit: Box<str>,
        /// The joints of the loop that stops closing, comma-separated.
        loop_joints: Box<str>,
    },
    /// A loop reaches a change point (bifurcation) in the sweep.
    #[error(
        "{file}: change point (bifurcation) at drive position {position}: two assembly \
         branches of the loop of joints {loop_joints} meet there and the drive does not \
         decide which one the mechanism follows; end the sweep before it"
    )]
    ChangePoint {
        /// The scene file.
        file: String,
        /// The change point, to full precision, with its unit.
        position: String,
        /// The joints of the loop, comma-separated.
        loop_joints: String,
    },
    /// The position is singular: the drive cannot move the mechanism there (toggle).
    #[error(
        "{file}: singular position (toggle) at drive position {position}: the loop of joints \
         {loop_joints} locks the driven link (condition number {condition:e})"
    )]
    Singular {
        /// The scene file.
        file: String,
        /// The drive position, with its unit.
        position: String,
        /// The joints of the singular loop, comma-separated.
        loop_joints: String,
        /// Condition number of the constraint Jacobian there.
        condition: f64,
    },
    /// No drive position was found where an output takes a value asked for by
    /// `[sweep] of` (the value is out of the output's range, or at one of its dead positions).
    #[error(
        "{file}: no drive position found where `{output}` = {value} (searched by Newton from \
         the previous position; last assembled at {last}{beyond}); is the value within the \
         output's range and away from its dead positions?"
    )]
    NotReached {
        /// The scene file.
        file: String,
        /// The output named by `[sweep] of`.
        output: String,
        /// The value asked for, with its unit.
        value: String,
        /// The last drive position tried that assembled, with its unit.
        last: String,
        /// Why the search could go no further, when a step left the positions where the
        /// mechanism assembles (`"; beyond it: …"`), else empty (boxed: keeps `Error` small).
        beyond: Box<str>,
    },
    /// `mechdiff codegen` cannot generate the code: the formula is malformed or not finite
    /// (with its column), or its derivatives exceed the engine's limits.
    #[error("{origin}: {source}")]
    Codegen {
        /// Where the formula came from: `--expr`, the file, or standard input.
        origin: String,
        /// The engine's reason.
        source: mechdiff_core::Error,
    },
    /// `mechdiff run --evaluator program|interpreter|jit` cannot evaluate this scene.
    #[error(
        "{file}: --evaluator {evaluator} cannot evaluate this scene: {reason}; use --evaluator \
         solver (or auto, which chooses)"
    )]
    NoEvaluator {
        /// The scene file.
        file: String,
        /// The value of `--evaluator` asked for (`program`, `interpreter` or `jit`).
        evaluator: String,
        /// Why (a loop without a closed form, a cam drive, …).
        reason: String,
    },
    /// The solver would jump to the other assembly branch between two drive positions.
    #[error(
        "{file}: the loop of joints {loop_joints} would change assembly branch between drive \
         positions {from} and {to}; use a finer step or stop the sweep before"
    )]
    BranchFlip {
        /// The scene file.
        file: String,
        /// Last position on the sketch's branch, with its unit.
        from: String,
        /// Position where the flip was detected, with its unit.
        to: String,
        /// The joints of the loop, comma-separated.
        loop_joints: String,
    },
    /// The solver could not prove the mechanism's motion between two drive positions within
    /// its bound on checked sub-steps: the positions are far apart (many turns), or the
    /// sub-steps shrank to nothing because a loop's closure cannot be certified at the
    /// mechanism's scale (sizes many orders of magnitude apart).
    #[error(
        "{file}: the move from drive position {from} to {to} needs more than {steps} checked \
         steps of at most {longest}; ask for drive positions closer together, or, if they \
         are close already, check the mechanism's sizes (a loop whose lengths differ by many \
         orders of magnitude cannot be followed to full precision)"
    )]
    MoveTooLong {
        /// The scene file.
        file: String,
        /// The drive position the move started from, with its unit.
        from: String,
        /// The drive position asked for, with its unit.
        to: String,
        /// The sub-steps allowed per move.
        steps: usize,
        /// The longest sub-step, with its unit.
        longest: String,
    },
    /// A derivative method returned NaN or an infinite value in the accuracy report, where
    /// it claims a derivative: a silent failure of the method at that drive position.
    #[error(
        "accuracy: method `{method}` returned {value} for `{output}` (derivative order \
         {order}) at φ = {phi:e} rad; the method fails there (report it, or leave the \
         position out of the sweep)"
    )]
    MethodNotFinite {
        /// The method.
        method: String,
        /// The output.
        output: String,
        /// The derivative order (0: the value).
        order: usize,
        /// The drive position (rad).
        phi: f64,
        /// What it returned.
        value: f64,
    },
    /// A derivative method of the accuracy report failed at a drive position.
    #[error("accuracy: method `{method}` failed at φ = {phi} rad: {source}")]
    Method {
        /// The method.
        method: String,
        /// The drive position (rad).
        phi: f64,
        /// The engine's reason.
        source: mechdiff_core::Error,
    },
    /// The extended-precision reference of an accuracy case could not be computed.
    #[error("accuracy: no reference for {what}: {reason}")]
    Reference {
        /// What the reference was for.
        what: String,
        /// Why.
        reason: String,
    },
    /// A picture could not be drawn or rendered (module and feature `pictures`).
    #[error("cannot draw the picture: {message}")]
    Picture {
        /// What went wrong.
        message: String,
    },
    /// A sensitivity or tolerance study (`[sensitivity]`, `[tolerances]`) that cannot give a
    /// right answer for this scene: what is wrong and how to fix it.
    #[error("{file}: {message}")]
    Study {
        /// The scene file.
        file: String,
        /// What is wrong and what to do.
        message: String,
    },
    /// A run of a sensitivity or tolerance study failed with parameters moved from their
    /// values.
    #[error("with {settings} ({purpose}): {source}")]
    Perturbed {
        /// The parameters as moved, `NAME=VALUE, …`.
        settings: String,
        /// What the run was for (a derivative, a Monte-Carlo sample).
        purpose: String,
        /// What went wrong there.
        source: Box<Error>,
    },
    /// A formula scene's formulas have no value or derivatives at a drive position, not even
    /// as a limit (`mechdiff run` of a formula scene).
    #[error("{file}: at drive position φ = {phi} rad: {source}")]
    FormulaAt {
        /// The scene file.
        file: String,
        /// The drive position (rad).
        phi: f64,
        /// The engine's reason.
        source: mechdiff_core::Error,
    },
    /// A count given on the command line (threads, Monte-Carlo samples, timed repeats) over
    /// its documented limit: refused before any work starts.
    #[error("{option} {value} is over the limit of {limit} {what}; {advice}")]
    OverLimit {
        /// The option, as written on the command line (`--threads`).
        option: &'static str,
        /// The value given.
        value: u64,
        /// The largest value accepted.
        limit: u64,
        /// What is counted (`worker threads`).
        what: &'static str,
        /// What to do instead.
        advice: &'static str,
    },
    /// A scene's `[synthesize]` section that the synthesis engine refuses, or a search
    /// that found no usable mechanism: the engine's reason, placed at the part of the
    /// section it concerns.
    #[error("{location}: {source}")]
    Synthesis {
        /// Where in the `[synthesize]` section.
        location: Location,
        /// The engine's reason (it says what to change).
        #[source]
        source: mechdiff_core::synthesis::SynthesisError,
    },
    /// A command-line option that does not apply to this kind of scene.
    #[error("{option} does not apply to {scene}: {why}")]
    OptionNotApplicable {
        /// The option, as written on the command line.
        option: String,
        /// The scene path as given.
        scene: PathBuf,
        /// Why, and what to use instead.
        why: String,
    },
}

/// Result with the facade's [`enum@Error`].
pub type Result<T, E = Error> = std::result::Result<T, E>;

impl Error {
    /// Whether the error is one that only solving drive positions finds: the mechanism's
    /// motion (it cannot assemble, is blocked, reaches a change point or toggle, flips its
    /// branch, misses a value of `[sweep] of`, locks itself by friction) or an overflow at a
    /// position. `mechdiff check`
    /// solves no position, so these are the only errors `run` may give for a scene `check`
    /// accepts; every other error is given by both ([`crate::scene::any::read`]).
    pub fn is_found_by_solving(&self) -> bool {
        match self {
            Error::NotFinite { .. }
            | Error::Unassemblable { .. }
            | Error::Blocked { .. }
            | Error::ChangePoint { .. }
            | Error::Singular { .. }
            | Error::NotReached { .. }
            | Error::SelfLocking { .. }
            | Error::BranchFlip { .. }
            | Error::MoveTooLong { .. }
            | Error::FormulaAt { .. } => true,
            Error::AtParameter { source, .. } | Error::Perturbed { source, .. } => {
                source.is_found_by_solving()
            }
            _ => false,
        }
    }
}
