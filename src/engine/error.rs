//! Why the engine refuses a setting: invalid input, in LIGGGHTS's words, or a valid feature
//! regolith does not run yet. The command layer reports the two differently.

use thiserror::Error;

/// A setting the engine refuses.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
pub enum EngineError {
    /// Invalid input; the message is LIGGGHTS's.
    #[error("{0}")]
    Invalid(String),
    /// Valid LIGGGHTS that regolith does not run yet; the feature as the deck names it.
    #[error("{0}: not supported yet")]
    Unsupported(String),
    /// A file the command names that cannot be opened or read; the message is LIGGGHTS's.
    #[error("{0}")]
    File(String),
    /// A value only a real run can know (`check` does not build the state).
    #[error("value known only when the deck runs")]
    KnownWhenRun,
}

impl From<String> for EngineError {
    fn from(message: String) -> EngineError {
        EngineError::Invalid(message)
    }
}

impl From<crate::util::numbers::NumberError> for EngineError {
    fn from(e: crate::util::numbers::NumberError) -> EngineError {
        EngineError::Invalid(e.into())
    }
}

impl From<&str> for EngineError {
    fn from(message: &str) -> EngineError {
        EngineError::Invalid(message.to_string())
    }
}

/// Lower layers' typed refusals reach the command layer as invalid input with their message.
macro_rules! invalid_from {
    ($($t:ty),+ $(,)?) => {$(
        impl From<$t> for EngineError {
            fn from(e: $t) -> EngineError {
                EngineError::Invalid(e.to_string())
            }
        }
    )+};
}

invalid_from!(
    crate::util::random::SeedError,
    crate::state::limits::LimitError,
    crate::state::domain::BoxError,
    crate::io::restart_values::RestartValueError,
    crate::engine::tet_mesh::TetMeshError,
    crate::engine::procmap::GridError,
);
