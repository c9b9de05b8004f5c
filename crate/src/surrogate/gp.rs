//! The Gaussian-process correction of the LoFi (`gp-mul`): a multiplicative response-based
//! correction whose tuning function is an ordinary Kriging model of the log ratio,
//!
//! ```text
//! S_k(x) = f~_k(x) exp(g_k(u, v)),   g_k ~ Kriging of  y_ik = ln(F_ik / f~_k(x_i))
//! ```
//!
//! one model per criterion `k`, each with its own maximum-likelihood correlation lengths
//! ([`super::kriging`]). The log ratio keeps `S_k > 0` and makes the correction
//! dimensionless. The model interpolates the samples (up to the nugget), and its predictive
//! variance `s_k^2(x)` of `ln S_k` is its own uncertainty estimate: `s_k` is the 1-sigma
//! relative error of `S_k` (`ln S = ln F + e` gives `S / F - 1 ~ e` for `|e| << 1`),
//! zero at the samples and growing away from them.

use super::fit::FitDiagnostics;
use super::kriging::Kriging;
use super::SurrogateLoFi;
use super::{
    check_samples, relative_cost, require_samples, Approach, Parameter, Sample, Scheme, Setting,
    Surrogate, SurrogateParams, SurrogateSpec,
};
use crate::design::DesignBox;
use crate::error::Result;
use crate::evaluate::{Criteria, Evaluator, CRITERIA_NAMES};
use crate::math;
use serde::{Deserialize, Serialize};

/// Fewest samples of a GP correction: a mean and a variance are estimated per criterion,
/// and leave-one-out needs one more.
const GP_MIN_SAMPLES: usize = 3;

/// Parameters of the GP correction (none beyond the samples: the correlation lengths
/// come from maximum likelihood).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct GpParams;

impl GpParams {
    /// The spec: `gp-mul`, one model per criterion.
    pub fn spec(&self) -> SurrogateSpec {
        SurrogateSpec {
            approach: Approach::Gp,
            scheme: Scheme::PerCriterion,
        }
    }
}

impl SurrogateParams for GpParams {
    type Model = Gp;

    fn check(&self, samples: &[Sample]) -> Result<()> {
        check_samples(samples)?;
        require_samples(samples, GP_MIN_SAMPLES, &self.spec().name())
    }

    fn fit(&self, setting: &Setting, samples: &[Sample]) -> Result<Gp> {
        self.check(samples)?;
        let mut x = Vec::with_capacity(samples.len());
        let mut y: [Vec<f64>; 3] = Default::default();
        for s in samples {
            let lofi = setting.lofi.evaluate(s.ks, s.cs)?.to_array();
            let (u, v) = setting.design_box.normalize(s.ks, s.cs);
            x.push([u, v]);
            for (k, yk) in y.iter_mut().enumerate() {
                yk.push(math::ln(s.hifi.to_array()[k] / lofi[k]));
            }
        }
        let models = y
            .iter()
            .map(|yk| Kriging::fit(&x, yk))
            .collect::<Result<Vec<_>>>()?;
        let mut model = Gp {
            lofi: setting.lofi.clone(),
            design_box: setting.design_box,
            models,
            diagnostics: Vec::new(),
        };
        for (k, name) in CRITERIA_NAMES.iter().enumerate() {
            let cost = relative_cost(&model, samples, &[k])?;
            let m = &model.models[k];
            let note = format!(
                "theta [{:.4e}, {:.4e}] by maximum likelihood (ln L {:.4}), mu {:.4e}, sigma^2 {:.4e}",
                m.theta()[0],
                m.theta()[1],
                m.ln_likelihood(),
                m.mu(),
                m.sigma2()
            );
            model.diagnostics.push(FitDiagnostics::direct(
                (*name).into(),
                "ordinary kriging of ln(HiFi / LoFi)",
                note,
                cost,
            ));
        }
        Ok(model)
    }
}

/// A fitted GP correction of the LoFi.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Gp {
    lofi: SurrogateLoFi,
    design_box: DesignBox,
    /// One Kriging model of `ln(F_k / f~_k)` per criterion.
    models: Vec<Kriging>,
    diagnostics: Vec<FitDiagnostics>,
}

impl Evaluator for Gp {
    fn evaluate(&self, ks: f64, cs: f64) -> Result<Criteria> {
        let lofi = self.lofi.evaluate(ks, cs)?.to_array();
        let (u, v) = self.design_box.normalize(ks, cs);
        Ok(Criteria::from_array(std::array::from_fn(|k| {
            lofi[k] * math::exp(self.models[k].mean(u, v))
        })))
    }

    fn name(&self) -> String {
        GpParams.spec().name()
    }
}

impl Surrogate for Gp {
    fn spec(&self) -> SurrogateSpec {
        GpParams.spec()
    }

    /// Per criterion: `mu`, `sigma2`, `theta_u`, `theta_v` of its Kriging model.
    fn tuning(&self) -> Vec<Parameter> {
        self.models
            .iter()
            .zip(CRITERIA_NAMES)
            .flat_map(|(m, name)| {
                [
                    ("mu", m.mu()),
                    ("sigma2", m.sigma2()),
                    ("theta_u", m.theta()[0]),
                    ("theta_v", m.theta()[1]),
                ]
                .map(|(p, value)| Parameter {
                    name: format!("{name}.{p}"),
                    value,
                })
            })
            .collect()
    }

    fn diagnostics(&self) -> Vec<FitDiagnostics> {
        self.diagnostics.clone()
    }

    /// `s_k(x)`, the Kriging standard deviation of `ln S_k`.
    fn relative_std(&self, ks: f64, cs: f64) -> Result<Option<[f64; 3]>> {
        crate::car::check_design(ks, cs)?;
        let (u, v) = self.design_box.normalize(ks, cs);
        Ok(Some(std::array::from_fn(|k| {
            self.models[k].predict(u, v).1.sqrt()
        })))
    }

    fn on_measured_road(&self) -> bool {
        self.lofi.measured.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Car;
    use crate::doe::audze_eglais;
    use crate::road::Road;
    use crate::surrogate::sample_plan;
    use crate::HiFi;

    #[test]
    fn interpolates_the_hifi_and_is_sure_only_at_the_samples() {
        let (car, road, b) = (Car::datum(), Road::default(), DesignBox::default());
        let setting = Setting::new(&car, &road, &b).unwrap();
        let hifi = HiFi::new(&car, &road).unwrap();
        let samples = sample_plan(&hifi, &audze_eglais(8, 1).unwrap(), &b).unwrap();
        let gp = GpParams.fit(&setting, &samples).unwrap();
        assert_eq!(gp.spec().name(), "gp-mul");
        assert_eq!(gp.tuning().len(), 12);
        for s in &samples {
            let p = gp.evaluate(s.ks, s.cs).unwrap().to_array();
            let std = gp.relative_std(s.ks, s.cs).unwrap().unwrap();
            for k in 0..3 {
                assert!((p[k] / s.hifi.to_array()[k] - 1.0).abs() < 1e-7, "{k}");
                assert!(std[k] < 1e-6, "{k}: {}", std[k]);
            }
        }
        // Away from the samples (the box centre is 0.1 or more from each) it is unsure.
        let (ks, cs) = b.scale(0.5, 0.5);
        let std = gp.relative_std(ks, cs).unwrap().unwrap();
        assert!(std.iter().all(|s| *s > 1e-5), "{std:?}");
        assert!(gp
            .relative_std(-1.0, cs)
            .unwrap_err()
            .to_string()
            .starts_with("ks"));
        assert!(GpParams
            .fit(&setting, &samples[..2])
            .unwrap_err()
            .to_string()
            .starts_with("plan"));
    }
}
