//! The one error type of the RideLab core. Every message names the field or
//! quantity at fault so the CLI and the page can show it next to that field.

use thiserror::Error;

/// Errors raised by the RideLab core.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum RideError {
    /// A named input field is missing, misspelt, of the wrong type or out of range.
    #[error("{field}: {reason}")]
    Field {
        /// Dotted path of the field, e.g. `front.spring`.
        field: String,
        /// Why it was rejected.
        reason: String,
    },
    /// No design in the box meets the design objectives: `field` names the binding
    /// objective's field (`sws_limit`, ...), `reason` says why (the closest any design came).
    #[error("{field}: {reason}")]
    Infeasible {
        /// The binding objective's field.
        field: String,
        /// Why nothing is feasible.
        reason: String,
    },
    /// A JSON document could not be parsed at all.
    #[error("invalid JSON: {0}")]
    Json(String),
    /// A computation cannot give a finite answer (for example an unstable model).
    #[error("{0}")]
    Numerical(String),
    /// The modal expansion does not apply to this model (repeated or unresolved modes, an
    /// asymmetric matrix): the exact Kronecker route does.
    #[error("modal: {0}")]
    ModalInapplicable(String),
    /// Independent tracks of unequal front and rear widths: the road warp makes the
    /// suspension deflections a random walk, unbounded in RMS over the whole band (the
    /// frequency route with ISO 8608's low cutoff applies).
    #[error("road warp: {0}")]
    RoadWarp(String),
    /// The GPU path cannot run: no adapter where one is required, a device or driver
    /// error, or a map larger than the device takes.
    #[error("GPU: {0}")]
    Gpu(String),
}

impl RideError {
    /// Shorthand for [`RideError::Field`].
    pub fn field(field: impl Into<String>, reason: impl Into<String>) -> Self {
        RideError::Field {
            field: field.into(),
            reason: reason.into(),
        }
    }
}

/// Result alias used across the crate.
pub type Result<T> = std::result::Result<T, RideError>;
