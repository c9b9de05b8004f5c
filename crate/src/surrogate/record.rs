//! A fitted surrogate's model, by approach: what a fit holds ([`super::Guarded`] wraps
//! it), and as data what lets a fit made in one place serve another without fitting
//! again. The page fits once per scenario change on its main thread and its workers adopt
//! that fit (issue #28). The data crosses as postcard bytes (`explorer::FitRecord`): every
//! `f64` as its 8 bytes, so the adopted model predicts the same bits as the fit it came
//! from. Postcard is not self-describing, so the types in a record use no
//! `skip_serializing_if` or internally tagged enums.
//!
//! The models know nothing of this enum (it names them, they do not name it), so the
//! module graph stays one way: the approaches below, the record above them, the dispatch
//! from a name ([`super::dispatch`]) and the guard above that.

use super::datafit::DataFit;
use super::gp::Gp;
use super::pba::ParameterTuning;
use super::rba::Rba;
use super::tuned::Tuned;
use super::vba::VariableTuning;
use super::Surrogate;
use serde::{Deserialize, Serialize};

/// One fitted surrogate's model, by approach.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub enum ModelRecord {
    /// A variable-based tuning (VBA).
    Vba(Tuned<VariableTuning>),
    /// A parameter-based tuning (PBA).
    Pba(Tuned<ParameterTuning>),
    /// A response-based correction (RBA).
    Rba(Rba),
    /// A data fit (no LoFi).
    Data(DataFit),
    /// The GP correction.
    Gp(Gp),
}

impl ModelRecord {
    /// The model, whichever its approach.
    pub(crate) fn model(&self) -> &dyn Surrogate {
        match self {
            ModelRecord::Vba(m) => m,
            ModelRecord::Pba(m) => m,
            ModelRecord::Rba(m) => m,
            ModelRecord::Data(m) => m,
            ModelRecord::Gp(m) => m,
        }
    }
}
