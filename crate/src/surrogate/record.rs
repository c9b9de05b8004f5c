//! A fitted surrogate as data: its fitted numbers, so a fit made in one place serves
//! another without fitting again. The page fits once per scenario change on its main
//! thread and its workers adopt that fit (issue #28). The data crosses as postcard bytes
//! (`explorer::FitRecord`): every `f64` as its 8 bytes, so the adopted model predicts the
//! same bits as the fit it came from. Postcard is not self-describing, so the types in a
//! record use no `skip_serializing_if` or internally tagged enums.

use super::datafit::DataFit;
use super::gp::Gp;
use super::guard::Guarded;
use super::pba::ParameterTuning;
use super::rba::Rba;
use super::tuned::Tuned;
use super::vba::VariableTuning;
use super::Surrogate;
use crate::design::DesignBox;
use serde::{Deserialize, Serialize};

/// One fitted surrogate's model, by approach (the [`Surrogate`] a fit returns, without the
/// reach check that [`ModelRecord::into_surrogate`] puts back).
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
    /// The surrogate again, its predictions checked against `fitted` (the design box it
    /// was fitted over) as [`super::SurrogateSpec::fit`] checks them.
    pub(crate) fn into_surrogate(self, fitted: DesignBox) -> Box<dyn Surrogate> {
        let inner: Box<dyn Surrogate> = match self {
            ModelRecord::Vba(m) => Box::new(m),
            ModelRecord::Pba(m) => Box::new(m),
            ModelRecord::Rba(m) => Box::new(m),
            ModelRecord::Data(m) => Box::new(m),
            ModelRecord::Gp(m) => Box::new(m),
        };
        Box::new(Guarded::new(inner, fitted))
    }
}
