//! What can go wrong when a machine moves under its motor: each failure typed, with the drive
//! position (rad or m, SI) and the time where it happened.

/// A failure of the equation of motion, its integration or an analysis.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MotionError {
    /// A number of the data or the settings is out of its range.
    #[error("invalid {what}: {value}")]
    InvalidValue {
        /// What the number is and its range.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// A torque–speed table is malformed.
    #[error("invalid torque–speed table: {reason}")]
    Table {
        /// What is wrong, naming the point.
        reason: String,
    },
    /// The geometry or the kinetostatics failed at a drive position.
    #[error("at drive position {phi} (t = {time} s): {source}")]
    Mechanism {
        /// Drive position.
        phi: f64,
        /// Time (NaN in the drive-angle form before a time is known).
        time: f64,
        /// The error of the geometry or of the kinetostatics.
        #[source]
        source: crate::Error,
    },
    /// The reduced moment of inertia is not positive: the equation of motion has no
    /// acceleration to give.
    #[error(
        "the reduced moment of inertia is {inertia} at drive position {phi}: the equation of \
         motion needs masses (inertia in the effects), a rotor or a flywheel"
    )]
    NoInertia {
        /// Drive position.
        phi: f64,
        /// The reduced moment of inertia found.
        inertia: f64,
    },
    /// Friction or efficiency make the acceleration an implicit equation that did not settle.
    #[error(
        "no consistent acceleration at drive position {phi}, speed {omega}: friction or \
         efficiency signs do not settle (self-locking?)"
    )]
    NoConsistentAcceleration {
        /// Drive position.
        phi: f64,
        /// Drive speed.
        omega: f64,
    },
    /// A quantity of the equation of motion overflowed.
    #[error("{quantity} is not finite at drive position {phi}")]
    NonFinite {
        /// Drive position.
        phi: f64,
        /// The quantity.
        quantity: &'static str,
    },
    /// The motor cannot start the machine from rest at the start position.
    #[error(
        "the motor cannot start the machine at drive position {phi}: it gives \
         {motor_torque} N·m at standstill, the machine needs more (acceleration {alpha})"
    )]
    CannotStart {
        /// Drive position.
        phi: f64,
        /// The motor's torque at standstill (on its own shaft).
        motor_torque: f64,
        /// The acceleration the equation of motion gives there (≤ 0).
        alpha: f64,
    },
    /// The machine came to rest (or its speed reversed) before the run's goal.
    #[error("the machine stalls at drive position {phi} at t = {time} s")]
    Stalled {
        /// Drive position.
        phi: f64,
        /// Time (NaN in the drive-angle form).
        time: f64,
    },
    /// A run has nothing that ends it.
    #[error("a simulation needs a stop condition: a time, a number of turns or a speed")]
    NoStopCondition,
    /// The integrator took its largest number of steps.
    #[error(
        "{steps} integration steps reached at t = {time} s, drive position {phi}: raise the \
         step limit or loosen the tolerances"
    )]
    TooManySteps {
        /// Steps taken.
        steps: usize,
        /// Time.
        time: f64,
        /// Drive position.
        phi: f64,
    },
    /// The integrator failed (step size underflow, stiffness).
    #[error("the integrator failed near t = {time}: {message}")]
    Integrator {
        /// Independent variable where it failed (time, or drive position in the angle form).
        time: f64,
        /// The integrator's message.
        message: String,
    },
    /// A speed the run waits for is not reached within the run's limit.
    #[error("speed {speed} rad/s not reached within {limit}; {reached_as} {reached} rad/s")]
    NotReached {
        /// Speed asked for.
        speed: f64,
        /// The limit (time or turns) in words.
        limit: String,
        /// The speed that shows how far the run got: a start-up's highest, a coast-down's
        /// last.
        reached: f64,
        /// Which speed `reached` is, in words (`"the highest was"`, `"at the end it was"`).
        reached_as: &'static str,
    },
    /// No periodic steady state exists within the turns allowed.
    #[error(
        "no steady state found within {turns} turns: the energy gained over one turn is \
         {gain} J at the last start speed {omega} rad/s ({reason})"
    )]
    NoSteadyState {
        /// Turns integrated.
        turns: usize,
        /// Energy gained over the last turn integrated (J).
        gain: f64,
        /// The start speed of that turn.
        omega: f64,
        /// Why.
        reason: &'static str,
    },
    /// The flywheel iteration did not reach the requested fluctuation.
    #[error(
        "no flywheel gives δ = {target}: after {iterations} iterations δ = {reached} with \
         {inertia} kg·m²"
    )]
    Flywheel {
        /// Requested coefficient of speed fluctuation.
        target: f64,
        /// The last δ found.
        reached: f64,
        /// The last flywheel inertia tried.
        inertia: f64,
        /// Iterations.
        iterations: usize,
    },
    /// The analysis needs a number the data does not give.
    #[error("{what} needs {missing}")]
    MissingData {
        /// The analysis.
        what: &'static str,
        /// What to give.
        missing: &'static str,
    },
}
