//! What goes wrong reading or evaluating a formula, as data. `Display` gives LIGGGHTS's own
//! message where it has one; the variants let callers tell a value only a real run can know
//! (a dry run's check mode) and a feature regolith does not evaluate yet from a deck error,
//! without reading the text.

use thiserror::Error;

/// Why a value a formula asks for (a variable, compute, thermo keyword, group function, atom
/// value) is not available.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum VariableError {
    /// Only a real run can know this value (check mode does not build the state).
    #[error("value known only when the deck runs")]
    KnownWhenRun,
    /// Valid LIGGGHTS that regolith does not evaluate yet; the feature as the deck names it.
    #[error("{0}: not supported yet")]
    Unsupported(String),
    /// A variable name that does not exist.
    #[error("Variable name {0} does not exist")]
    NoSuchVariable(String),
    /// A variable of another style than the one asked for (`atom`, `equal`).
    #[error("Variable {name} is not {wanted}-style")]
    WrongStyle {
        /// The variable.
        name: String,
        /// The style asked for.
        wanted: &'static str,
    },
    /// A variable whose formula refers back to itself.
    #[error("Variable has circular dependency")]
    Circular,
    /// A `random()`/`normal()` seed LIGGGHTS refuses.
    #[error(transparent)]
    Seed(#[from] crate::util::random::SeedError),
    /// The formula of the variable asked for fails.
    #[error(transparent)]
    Formula(Box<ExprErrorKind>),
    /// Refused, in LIGGGHTS's words.
    #[error("{0}")]
    Invalid(String),
}

impl VariableError {
    /// Whether only a real run can know the value.
    pub fn is_known_when_run(&self) -> bool {
        matches!(self, VariableError::KnownWhenRun)
    }
}

impl From<String> for VariableError {
    /// A message from a layer that passes errors as text: invalid input.
    fn from(message: String) -> VariableError {
        VariableError::Invalid(message)
    }
}

/// The engine's refusal where a formula reads a value, variant for variant.
impl From<crate::engine::error::EngineError> for VariableError {
    fn from(e: crate::engine::error::EngineError) -> VariableError {
        use crate::engine::error::EngineError;
        match e {
            EngineError::Invalid(m) | EngineError::File(m) => VariableError::Invalid(m),
            EngineError::Unsupported(what) => VariableError::Unsupported(what),
            EngineError::KnownWhenRun => VariableError::KnownWhenRun,
        }
    }
}

impl From<&str> for VariableError {
    fn from(message: &str) -> VariableError {
        VariableError::from(message.to_string())
    }
}

/// A variable's failure where the engine reads it: "not supported yet" stays a variant;
/// everything else is invalid input with its message.
impl From<VariableError> for crate::engine::error::EngineError {
    fn from(e: VariableError) -> crate::engine::error::EngineError {
        use crate::engine::error::EngineError;
        match e {
            VariableError::Unsupported(what) => EngineError::Unsupported(what),
            VariableError::KnownWhenRun => EngineError::KnownWhenRun,
            other => EngineError::Invalid(other.to_string()),
        }
    }
}

impl From<VariableError> for String {
    /// The message, for layers that still pass errors as text.
    fn from(e: VariableError) -> String {
        e.to_string()
    }
}

/// What is wrong with a formula, without its position (see [`crate::lang::expr::ExprError`]).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum ExprErrorKind {
    /// Not a formula LIGGGHTS reads.
    #[error("Invalid syntax in variable formula")]
    Syntax,
    /// A math function with the wrong arguments (or a bad `random()` seed).
    #[error("Invalid math function in variable formula")]
    BadMath,
    /// A word followed by `(` that is no math, group or special function.
    #[error("Invalid math/group/special function in variable formula")]
    UnknownFunction,
    /// A value that needs the simulation box, asked for before `create_box`.
    #[error("Variable evaluation before simulation box is defined")]
    NoBox,
    /// Not a condition the `if` command reads.
    #[error("Invalid Boolean syntax in if command")]
    Boolean,
    /// Deeper nesting than regolith accepts (not a LIGGGHTS message: LIGGGHTS has no limit
    /// but crashes long before this one).
    #[error("Variable formula is nested too deeply")]
    TooDeep,
    /// A number too large for a double (`1e400`).
    #[error("Number {0} in variable formula is out of range (largest: 1.79769e+308)")]
    OutOfRange(String),
    /// `x / 0`.
    #[error("Divide by 0 in variable formula")]
    DivideByZero,
    /// `x % 0`.
    #[error("Modulo 0 in variable formula")]
    ModuloZero,
    /// `x ^ 0` (LIGGGHTS refuses it).
    #[error("Power by 0 in variable formula")]
    PowerByZero,
    /// `sqrt` of a negative value.
    #[error("Sqrt of negative value in variable formula")]
    SqrtNegative,
    /// `ln`/`log` of a value <= 0.
    #[error("Log of zero/negative value in variable formula")]
    LogNonPositive,
    /// `asin` outside [-1, 1].
    #[error("Arcsin of invalid value in variable formula")]
    ArcsinRange,
    /// `acos` outside [-1, 1].
    #[error("Arccos of invalid value in variable formula")]
    ArccosRange,
    /// A function that needs a run in progress (`ramp`, `vdisplace`, ...) between runs.
    #[error("Cannot use {0} in variable formula between runs")]
    NeedsRun(&'static str),
    /// A mask function (`gmask`, ...) outside atom style.
    #[error("{0} function in equal-style variable formula")]
    MaskInEqual(&'static str),
    /// A per-atom keyword (`x`, `mass`, ...) in an equal-style formula.
    #[error("Atom vector in equal-style variable formula")]
    AtomVectorInEqual,
    /// A bracket index with something else than digits.
    #[error("Non digit character between brackets in variable")]
    NonDigitIndex,
    /// A `[` without its `]`.
    #[error("Mismatched brackets in variable")]
    MismatchedBrackets,
    /// `[]`.
    #[error("Empty brackets in variable")]
    EmptyBrackets,
    /// `[0]`.
    #[error("Index between variable brackets must be positive")]
    IndexNotPositive,
    /// A piece the all-atoms-at-once evaluator does not take (the atom-by-atom walk then
    /// evaluates it and reports its errors); never reported.
    #[error("not columnar")]
    NotColumnar,
    /// A value looked up while evaluating (a variable, compute, thermo keyword, ...).
    #[error(transparent)]
    Lookup(#[from] VariableError),
}

/// A file or counter the deck's commands read or write that cannot be used.
#[derive(Debug, Error)]
pub enum SystemError {
    /// Check mode: the deck removed this file earlier.
    #[error("{0}: no such file")]
    NoSuchFile(String),
    /// The system refused to read or write the file.
    #[error("{name}: {source}")]
    File {
        /// The file (or folder) as named.
        name: String,
        /// What the system said.
        source: std::io::Error,
    },
    /// The shared universe counter (`tmp.lammps.variable`) cannot be read.
    #[error("universe counter: {0}")]
    CounterUnreadable(Box<SystemError>),
    /// The shared universe counter holds no count.
    #[error("universe counter holds '{0}'")]
    CounterText(String),
}

/// Why a `variable` or `next` command is refused.
#[derive(Debug, Error)]
pub enum VariableCommandError {
    /// LIGGGHTS's catch-all for a malformed `variable` command.
    #[error("Illegal variable command")]
    Illegal,
    /// A word that is not an integer where one is needed.
    #[error("Expected integer parameter in input script or data file, got '{0}'")]
    ExpectedInteger(String),
    /// An integer beyond 64 bits.
    #[error("Integer '{0}' is out of range")]
    IntegerRange(String),
    /// A `world` variable with another value count than partitions.
    #[error("World variable count doesn't match # of partitions")]
    WorldCount,
    /// An existing variable given again with another style.
    #[error("Cannot redefine variable as a different style")]
    Redefined,
    /// The file of a `file` variable cannot be read.
    #[error("Cannot open file variable file {0}")]
    CannotOpen(String),
    /// A `file` variable whose file holds no value.
    #[error("File variable could not read value")]
    EmptyFile,
    /// Valid LIGGGHTS that regolith does not run yet (`variable atomfile`).
    #[error("{0}: not supported yet")]
    Unsupported(String),
    /// A name with other characters than letters, digits and `_`.
    #[error("Variable name must be alphanumeric or underscore characters")]
    BadName,
    /// Fewer universe/uloop values than partitions.
    #[error("Universe/uloop variable count < # of partitions")]
    UniverseCount,
    /// Universe/uloop variables with different value counts.
    #[error("All universe/uloop variables must have same # of values")]
    UniverseMismatch,
    /// `next` without a variable.
    #[error("Illegal next command")]
    IllegalNext,
    /// `next` naming a variable that does not exist.
    #[error("Invalid variable in next command")]
    NextUnknown,
    /// `next` over variables of different styles.
    #[error("All variables in next command must be same style")]
    NextMixed,
    /// `next` over a style that has no next value.
    #[error("Invalid variable style with next command")]
    NextStyle,
    /// The universe counter file.
    #[error(transparent)]
    System(#[from] SystemError),
}
