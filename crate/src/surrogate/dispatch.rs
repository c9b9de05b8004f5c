//! From a surrogate's name to its fit: [`SurrogateSpec::check`] and [`SurrogateSpec::fit`]
//! hand the parsed approach and scheme to the approach's parameters
//! ([`super::SurrogateParams`]) and hold the fitted model as a [`ModelRecord`], guarded.

use super::datafit::DataFitParams;
use super::fit::LmOptions;
use super::gp::GpParams;
use super::guard::Guarded;
use super::pba::PbaParams;
use super::rba::RbaParams;
use super::record::ModelRecord;
use super::spec::{Approach, SurrogateSpec};
use super::vba::VbaParams;
use super::{Sample, Scheme, Setting, SurrogateParams};
use crate::error::{Result, RideError};

impl SurrogateSpec {
    /// Checks the spec against `samples` without fitting (errors name the field).
    pub fn check(&self, samples: &[Sample]) -> Result<()> {
        let options = LmOptions::default();
        match self.approach {
            Approach::Rba { form, response } => RbaParams {
                form,
                response,
                scheme: self.scheme,
            }
            .check(samples),
            Approach::Vba(transform) => VbaParams {
                transform,
                scheme: self.scheme,
                options,
            }
            .check(samples),
            Approach::Pba(scaling) => PbaParams {
                scaling,
                scheme: self.scheme,
                options,
            }
            .check(samples),
            Approach::Data(response) if self.scheme == Scheme::PerCriterion => {
                DataFitParams { response }.check(samples)
            }
            Approach::Data(_) => Err(RideError::field(
                "scheme",
                "a data fit has one response per criterion",
            )),
            Approach::Gp if self.scheme == Scheme::PerCriterion => GpParams.check(samples),
            Approach::Gp => Err(RideError::field(
                "scheme",
                "a GP correction has one model per criterion",
            )),
        }
    }

    /// Checks, then fits with `options` for the Levenberg-Marquardt fits: the fitted
    /// model, its predictions checked ([`Guarded`]).
    pub fn fit(
        &self,
        setting: &Setting,
        samples: &[Sample],
        options: &LmOptions,
    ) -> Result<Guarded> {
        self.check(samples)?;
        let scheme = self.scheme;
        let fitted = match self.approach {
            Approach::Rba { form, response } => ModelRecord::Rba(
                RbaParams {
                    form,
                    response,
                    scheme,
                }
                .fit(setting, samples)?,
            ),
            Approach::Vba(transform) => ModelRecord::Vba(
                VbaParams {
                    transform,
                    scheme,
                    options: *options,
                }
                .fit(setting, samples)?,
            ),
            Approach::Pba(scaling) => ModelRecord::Pba(
                PbaParams {
                    scaling,
                    scheme,
                    options: *options,
                }
                .fit(setting, samples)?,
            ),
            Approach::Data(response) => {
                ModelRecord::Data(DataFitParams { response }.fit(setting, samples)?)
            }
            Approach::Gp => ModelRecord::Gp(GpParams.fit(setting, samples)?),
        };
        // Every prediction is checked: an RMS > 0, not too far beyond the fitted box.
        Ok(Guarded::new(fitted, setting.design_box))
    }
}
