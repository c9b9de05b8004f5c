//! Baselines that ignore the physics: a response model fitted to the HiFi samples alone,
//! `S_k(x) = c_k(u, v)`, one per criterion: the quadratic response surface (least squares on
//! the relative errors, pseudo-inverse) or an RBF interpolant (shape by leave-one-out).
//! This is the "surrogate replaces the physics" approach the tuned LoFi is compared with.

use super::fit::FitDiagnostics;
use super::response::{fit_affine, method, AffineSample, Response, ResponseKind};
use super::{
    check_samples, relative_cost, require_samples, Approach, Parameter, Sample, Scheme, Setting,
    Surrogate, SurrogateParams, SurrogateSpec,
};
use crate::design::DesignBox;
use crate::error::Result;
use crate::evaluate::{Criteria, Evaluator};
use serde::{Deserialize, Serialize};

/// Parameters of a data-fit baseline.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DataFitParams {
    /// Quadratic polynomial (`Poly(2)`, the response surface), linear, or RBF.
    pub response: ResponseKind,
}

impl DataFitParams {
    fn spec(&self) -> SurrogateSpec {
        SurrogateSpec {
            approach: Approach::Data(self.response),
            scheme: Scheme::PerCriterion,
        }
    }
}

impl SurrogateParams for DataFitParams {
    type Model = DataFit;

    fn check(&self, samples: &[Sample]) -> Result<()> {
        self.response.check()?;
        check_samples(samples)?;
        require_samples(samples, self.response.min_samples(), &self.spec().name())
    }

    /// Fits one response per criterion; `setting` supplies only the design box.
    fn fit(&self, setting: &Setting, samples: &[Sample]) -> Result<DataFit> {
        self.check(samples)?;
        let points: Vec<AffineSample> = samples
            .iter()
            .map(|s| {
                let (u, v) = setting.design_box.normalize(s.ks, s.cs);
                AffineSample {
                    u,
                    v,
                    a: [0.0; 3],
                    b: [1.0; 3],
                    f: s.hifi.to_array(),
                }
            })
            .collect();
        let groups = Scheme::PerCriterion.groups();
        let (responses, notes): (Vec<Response>, Vec<String>) =
            fit_affine(self.response, groups, &points)?
                .into_iter()
                .unzip();
        let mut model = DataFit {
            spec: self.spec(),
            design_box: setting.design_box,
            responses,
            diagnostics: Vec::new(),
        };
        for (g, note) in notes.into_iter().enumerate() {
            let cost = relative_cost(&model, samples, groups[g])?;
            model.diagnostics.push(FitDiagnostics::direct(
                Scheme::PerCriterion.label(g),
                method(self.response),
                note,
                cost,
            ));
        }
        Ok(model)
    }
}

/// A fitted data-fit baseline.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DataFit {
    spec: SurrogateSpec,
    design_box: DesignBox,
    /// One response per criterion.
    responses: Vec<Response>,
    diagnostics: Vec<FitDiagnostics>,
}

impl Evaluator for DataFit {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        // A data fit has no physics to refuse a bad design: check it as the models do.
        crate::car::check_design(ks, cs)?;
        let (u, v) = self.design_box.normalize(ks, cs);
        Ok(Criteria::from_array(std::array::from_fn(|k| {
            self.responses[k].value(u, v)
        })))
    }

    fn name(&self) -> String {
        self.spec.name()
    }
}

impl Surrogate for DataFit {
    fn spec(&self) -> SurrogateSpec {
        self.spec
    }

    fn tuning(&self) -> Vec<Parameter> {
        self.responses
            .iter()
            .enumerate()
            .flat_map(|(g, c)| c.parameters(&Scheme::PerCriterion.prefix(g)))
            .collect()
    }

    fn diagnostics(&self) -> Vec<FitDiagnostics> {
        self.diagnostics.clone()
    }

    fn on_measured_road(&self) -> bool {
        false
    }
}
