//! PBA, the parameter-based approach: `S = f~(x; p(a))`, the LoFi quarter car with scaled
//! parameters
//!
//! ```text
//! SMTS  ms' = a_ms ms      (sprung mass)
//! UMTS  mu' = a_mu mu      (unsprung mass)
//! KT    kt' = a_kt kt      (tyre rate, optional third option)
//! ```
//!
//! in any combination; the design `(ks, cs)` is passed through unchanged. Admissible: every
//! scale factor > 0.

use super::fit::{check_tuning, LmOptions, Tuning};
use super::tuned::Tuned;
use super::{Approach, Sample, Scaling, Scheme, Setting, SurrogateParams, SurrogateSpec};
use crate::car::QuarterCar;
use crate::error::Result;
use serde::{Deserialize, Serialize};

/// The PBA tuning: `a` holds the scale factors of the scaled parameters, in the order
/// ms, mu, kt.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ParameterTuning {
    scaling: Scaling,
    base: QuarterCar,
}

impl ParameterTuning {
    /// The tuning of `base` (the car's front quarter car).
    pub fn new(scaling: Scaling, base: QuarterCar) -> Self {
        ParameterTuning { scaling, base }
    }
}

impl Tuning for ParameterTuning {
    fn names(&self) -> Vec<String> {
        Scaling::TOKENS
            .iter()
            .zip(self.scaling.flags())
            .filter(|(_, on)| *on)
            .map(|((_, n), _)| n.to_string())
            .collect()
    }

    fn neutral(&self) -> Vec<f64> {
        vec![1.0; self.scaling.count()]
    }

    fn spread(&self) -> Vec<f64> {
        vec![0.3; self.scaling.count()]
    }

    fn admissible(&self, a: &[f64]) -> bool {
        a.iter().all(|&x| x.is_finite() && x > 0.0)
    }

    fn quarter(&self, a: &[f64], ks: f64, cs: f64) -> Result<QuarterCar> {
        let mut q = QuarterCar {
            ks,
            cs,
            ..self.base
        };
        let mut a = a.iter();
        for (on, p) in self
            .scaling
            .flags()
            .into_iter()
            .zip([&mut q.ms, &mut q.mu, &mut q.kt])
        {
            if on {
                *p *= a.next().copied().unwrap_or(1.0);
            }
        }
        Ok(q)
    }
}

/// Parameters of a PBA surrogate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PbaParams {
    /// Which parameters are scaled.
    pub scaling: Scaling,
    /// Shared or per-criterion tuning.
    pub scheme: Scheme,
    /// Levenberg-Marquardt settings.
    pub options: LmOptions,
}

impl PbaParams {
    fn spec(&self) -> SurrogateSpec {
        SurrogateSpec {
            approach: Approach::Pba(self.scaling),
            scheme: self.scheme,
        }
    }
}

impl SurrogateParams for PbaParams {
    type Model = Tuned<ParameterTuning>;

    fn check(&self, samples: &[Sample]) -> Result<()> {
        self.options.check()?;
        if self.scaling.count() == 0 {
            return Err(crate::error::RideError::field(
                "approach",
                "PBA needs at least one scaled parameter (smts, umts, kt)",
            ));
        }
        check_tuning(
            self.scaling.count(),
            [1, 1],
            samples,
            self.scheme,
            &self.spec().name(),
        )
    }

    fn fit(&self, setting: &Setting, samples: &[Sample]) -> Result<Self::Model> {
        self.check(samples)?;
        let tuning = ParameterTuning::new(self.scaling, setting.lofi.car.quarter());
        Tuned::fit(
            self.spec(),
            tuning,
            &setting.lofi,
            samples,
            self.scheme,
            &self.options,
        )
    }
}
