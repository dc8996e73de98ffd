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

impl From<crate::util::random::SeedError> for EngineError {
    fn from(e: crate::util::random::SeedError) -> EngineError {
        EngineError::Invalid(e.to_string())
    }
}

impl From<&str> for EngineError {
    fn from(message: &str) -> EngineError {
        EngineError::Invalid(message.to_string())
    }
}

impl From<crate::state::limits::LimitError> for EngineError {
    fn from(e: crate::state::limits::LimitError) -> EngineError {
        EngineError::Invalid(e.to_string())
    }
}

impl From<crate::state::domain::BoxError> for EngineError {
    fn from(e: crate::state::domain::BoxError) -> EngineError {
        EngineError::Invalid(e.to_string())
    }
}

impl From<crate::io::restart_values::RestartValueError> for EngineError {
    fn from(e: crate::io::restart_values::RestartValueError) -> EngineError {
        EngineError::Invalid(e.to_string())
    }
}

impl From<crate::engine::tet_mesh::TetMeshError> for EngineError {
    fn from(e: crate::engine::tet_mesh::TetMeshError) -> EngineError {
        EngineError::Invalid(e.to_string())
    }
}
