//! RBA, the response-based approach: correct the LoFi *output*,
//!
//! ```text
//! multiplicative  S_k(x) = f~_k(x) tau_k(u, v)
//! additive        S_k(x) = f~_k(x) + d_k(u, v)
//! ```
//!
//! with `tau_k` / `d_k` a polynomial of degree 1 or 2 in the normalised design (least squares
//! on the relative errors, pseudo-inverse) or an RBF model (interpolation, shape by
//! leave-one-out), one per criterion. A multiplicative polynomial may also be shared by all
//! three criteria (`tau_k = tau`, a dimensionless gain); an additive correction carries the
//! units of its criterion and an RBF interpolates one criterion, so those are per criterion.

use super::fit::FitDiagnostics;
use super::response::{fit_affine, method, AffineSample, Response, ResponseKind};
use super::SurrogateLoFi;
use super::{
    check_samples, relative_cost, require_samples, Approach, Form, Parameter, Sample, Scheme,
    Setting, Surrogate, SurrogateParams, SurrogateSpec,
};
use crate::design::DesignBox;
use crate::error::{Result, RideError};
use crate::evaluate::{Criteria, Evaluator};
use serde::{Deserialize, Serialize};

impl Form {
    /// Offsets and gains `(a, b)` of `S = a + b c` for LoFi values `lofi`.
    fn affine(self, lofi: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        match self {
            Form::Multiplicative => ([0.0; 3], lofi),
            Form::Additive => (lofi, [1.0; 3]),
        }
    }
}

/// Parameters of an RBA surrogate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RbaParams {
    /// Multiplicative or additive.
    pub form: Form,
    /// Polynomial or RBF correction.
    pub response: ResponseKind,
    /// Shared (multiplicative polynomials only) or per criterion.
    pub scheme: Scheme,
}

impl RbaParams {
    fn spec(&self) -> SurrogateSpec {
        SurrogateSpec {
            approach: Approach::Rba {
                form: self.form,
                response: self.response,
            },
            scheme: self.scheme,
        }
    }
}

impl SurrogateParams for RbaParams {
    type Model = Rba;

    fn check(&self, samples: &[Sample]) -> Result<()> {
        if self.scheme == Scheme::Shared && !self.form.shareable(self.response) {
            return Err(RideError::field(
                "scheme",
                "only a multiplicative polynomial correction can be shared by the criteria",
            ));
        }
        self.response.check()?;
        check_samples(samples)?;
        require_samples(samples, self.response.min_samples(), &self.spec().name())
    }

    fn fit(&self, setting: &Setting, samples: &[Sample]) -> Result<Rba> {
        self.check(samples)?;
        let points = samples
            .iter()
            .map(|s| {
                let (a, b) = self
                    .form
                    .affine(setting.lofi.evaluate(s.ks, s.cs)?.to_array());
                let (u, v) = setting.design_box.normalize(s.ks, s.cs);
                Ok(AffineSample {
                    u,
                    v,
                    a,
                    b,
                    f: s.hifi.to_array(),
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let groups = self.scheme.groups();
        let (corrections, notes): (Vec<Response>, Vec<String>) =
            fit_affine(self.response, groups, &points)?
                .into_iter()
                .unzip();
        let mut model = Rba {
            spec: self.spec(),
            lofi: setting.lofi.clone(),
            design_box: setting.design_box,
            form: self.form,
            scheme: self.scheme,
            corrections,
            diagnostics: Vec::new(),
        };
        for (g, note) in notes.into_iter().enumerate() {
            let cost = relative_cost(&model, samples, groups[g])?;
            model.diagnostics.push(FitDiagnostics::direct(
                self.scheme.label(g),
                method(self.response),
                note,
                cost,
            ));
        }
        Ok(model)
    }
}

/// A fitted RBA surrogate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Rba {
    spec: SurrogateSpec,
    lofi: SurrogateLoFi,
    design_box: DesignBox,
    form: Form,
    scheme: Scheme,
    /// One correction (shared) or three (per criterion).
    corrections: Vec<Response>,
    diagnostics: Vec<FitDiagnostics>,
}

impl Evaluator for Rba {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let (a, b) = self.form.affine(self.lofi.evaluate(ks, cs)?.to_array());
        let (u, v) = self.design_box.normalize(ks, cs);
        let last = self.corrections.len() - 1;
        let c = std::array::from_fn(|k| a[k] + b[k] * self.corrections[k.min(last)].value(u, v));
        Ok(Criteria::from_array(c))
    }

    fn name(&self) -> String {
        self.spec.name()
    }
}

impl Surrogate for Rba {
    fn spec(&self) -> SurrogateSpec {
        self.spec
    }

    fn tuning(&self) -> Vec<Parameter> {
        self.corrections
            .iter()
            .enumerate()
            .flat_map(|(g, c)| c.parameters(&self.scheme.prefix(g)))
            .collect()
    }

    fn diagnostics(&self) -> Vec<FitDiagnostics> {
        self.diagnostics.clone()
    }

    fn on_measured_road(&self) -> bool {
        self.lofi.measured.is_some()
    }
}
