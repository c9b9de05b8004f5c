//! The tuned LoFi model shared by VBA and PBA: a real quarter car whose design variables
//! ([`super::vba`]) or parameters ([`super::pba`]) follow the fitted tuning, one tuning for
//! all criteria or one per criterion.

use super::fit::{fit_scheme, tuned_criteria, FitDiagnostics, LmOptions, Tuning};
use super::SurrogateLoFi;
use super::{Parameter, Sample, Scheme, Surrogate, SurrogateSpec};
use crate::car::QuarterCar;
use crate::error::Result;
use crate::evaluate::{Criteria, Evaluator};
use serde::{Deserialize, Serialize};

/// A fitted tuned LoFi: `S_k(x) = f~_k(x; tuning a_k)`, `a_k` shared or per criterion.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tuned<T> {
    spec: SurrogateSpec,
    tuning: T,
    lofi: SurrogateLoFi,
    scheme: Scheme,
    /// One parameter vector (shared) or three (per criterion).
    params: Vec<Vec<f64>>,
    diagnostics: Vec<FitDiagnostics>,
}

impl<T: Tuning> Tuned<T> {
    /// Fits `tuning` to `samples` on `lofi`'s road (the caller has checked the samples).
    pub(crate) fn fit(
        spec: SurrogateSpec,
        tuning: T,
        lofi: &SurrogateLoFi,
        samples: &[Sample],
        scheme: Scheme,
        options: &LmOptions,
    ) -> Result<Self> {
        let fits = fit_scheme(&tuning, lofi, samples, scheme, options)?;
        let (params, diagnostics): (Vec<_>, Vec<_>) =
            fits.into_iter().map(|f| (f.params, f.diagnostics)).unzip();
        Ok(Tuned {
            spec,
            tuning,
            lofi: lofi.clone(),
            scheme,
            params,
            diagnostics,
        })
    }

    /// Parameters of the fit serving criterion `k`.
    fn params_for(&self, k: usize) -> &[f64] {
        &self.params[k.min(self.params.len() - 1)]
    }
}

impl<T: Tuning> Evaluator for Tuned<T> {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        // The design first, so errors name ks or cs rather than the transformed design.
        crate::car::check_design(ks, cs)?;
        if let [a] = self.params.as_slice() {
            return tuned_criteria(&self.tuning, &self.lofi, a, ks, cs);
        }
        let mut out = [0.0; 3];
        for (k, o) in out.iter_mut().enumerate() {
            *o =
                tuned_criteria(&self.tuning, &self.lofi, self.params_for(k), ks, cs)?.to_array()[k];
        }
        Ok(Criteria::from_array(out))
    }

    fn name(&self) -> String {
        self.spec.name()
    }
}

impl<T: Tuning> Surrogate for Tuned<T> {
    fn spec(&self) -> SurrogateSpec {
        self.spec
    }

    fn tuning(&self) -> Vec<Parameter> {
        let names = self.tuning.names();
        self.params
            .iter()
            .enumerate()
            .flat_map(|(g, a)| {
                let prefix = self.scheme.prefix(g);
                names.iter().zip(a).map(move |(n, &value)| Parameter {
                    name: format!("{prefix}{n}"),
                    value,
                })
            })
            .collect()
    }

    fn diagnostics(&self) -> Vec<FitDiagnostics> {
        self.diagnostics.clone()
    }

    fn tuned_quarters(&self, ks: f64, cs: f64) -> Result<Option<[QuarterCar; 3]>> {
        let q = |k| self.tuning.quarter(self.params_for(k), ks, cs);
        Ok(Some([q(0)?, q(1)?, q(2)?]))
    }

    fn on_measured_road(&self) -> bool {
        self.lofi.measured.is_some()
    }
}
