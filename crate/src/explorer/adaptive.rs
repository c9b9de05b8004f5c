//! The page's "next HiFi run" (issue #15): the adaptive loop of
//! [`crate::study::adaptive`] on the state's scenario, one HiFi run per step, with what
//! the page draws after each: where the run went and why, the surrogate's new front and
//! pick, the pick's HiFi re-check, and the uncertainty map with how well it predicts the
//! true error on a HiFi validation grid.
//!
//! The loop starts from the state's surrogate and plan and judges fronts by the state's
//! design objectives against the datum's HiFi criteria, with STM on a 201 x 201 grid refined
//! 3 times: for the default objectives this is `ridelab surrogate --approach A --plan P
//! --adaptive K`, sample for sample.

use super::state::Scenario;
use crate::analysis::ModelKind;
use crate::comfort::Comfort;
use crate::dos::DosContext;
use crate::error::{Result, RideError};
use crate::evaluate::Evaluator;
use crate::maps::Grid;
use crate::optimize::{recheck, FrontPoint, Recheck, StmParams};
use crate::study::adaptive::{
    AdaptiveLoop, AdaptiveOptions, AdaptiveReport, Added, Decision, Proposal, Step,
};
use crate::surrogate::metrics::ByCriterion;
use crate::surrogate::sample_plan;
use crate::surrogate::uncertainty::{check, UncertaintyCheck};
use crate::surrogate::{Setting, ValidationSet};
use serde::Serialize;

/// What one "next HiFi run" gives the page.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PageStep {
    /// The sample added, its scores and the reason.
    pub added: Added,
    /// The surrogate's front and pick after it.
    pub step: Step,
    /// The new pick re-run on the HiFi (one HiFi run).
    pub recheck: Recheck,
}

/// Most levels per axis of the page's validation grid (`40 x 40` = 1600 HiFi runs).
pub const MAX_CHECK_LEVELS: usize = 40;

/// How the page's uncertainty map reads against the truth.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PageUncertainty {
    /// Levels per axis of the HiFi validation grid.
    pub levels: usize,
    /// The loop's current estimate against the true relative error of its surrogate on
    /// the grid (`uncertainty::check`: Pearson and Spearman correlation of `sigma_k` with
    /// `|S_k / F_k - 1|`, the means, and the estimate at the grid's points).
    pub check: UncertaintyCheck,
    /// The largest estimate at the loop's HiFi samples, %, per criterion: its noise
    /// floor (0 for an interpolating surrogate up to the Kriging nugget's share, the fit's
    /// own residual for a least-squares one such as VBA).
    pub at_samples_percent: ByCriterion<f64>,
}

/// An adaptive loop on one scenario, with the HiFi it runs (the full car on the
/// scenario's road, measured or ISO).
pub struct PageLoop {
    state: AdaptiveLoop,
    hifi: Box<dyn Evaluator + Sync>,
    /// The HiFi validation grid, kept once run (it does not change as samples are added).
    validation: Option<ValidationSet>,
}

impl PageLoop {
    /// Runs the scenario's plan on the HiFi, fits its surrogate and finds the front.
    /// `options.runs` is only recorded in the report (the page steps); the rest are
    /// checked, naming the field.
    ///
    /// On a measured road it is `ridelab surrogate --road FILE --adaptive K`'s loop: the
    /// HiFi the full car there, the surrogate's LoFi the quarter car there.
    pub fn new(s: &Scenario, options: AdaptiveOptions) -> Result<PageLoop> {
        let setting = match &s.measured {
            Some(m) => m.0.setting(&s.datum, &s.dbox)?,
            None => Setting::new(&s.datum, &s.road, &s.dbox)?,
        };
        let hifi = s.evaluator_with(ModelKind::Full, Comfort::Bacc)?;
        let decision = Decision {
            objectives: s.objectives.clone(),
            ctx: DosContext::of_model(&s.datum, &hifi)?,
            stm: StmParams::default(),
        };
        let points = s.plan.plan()?;
        options.check(points.unit.len())?;
        let initial = sample_plan(&hifi, &points, &s.dbox)?;
        let state = AdaptiveLoop::new(
            s.surrogate,
            setting,
            decision,
            s.plan.name(),
            initial,
            options,
        )?;
        Ok(PageLoop {
            state,
            hifi,
            validation: None,
        })
    }

    /// Where the next HiFi run would go, and why (the marker before the run).
    pub fn propose(&self) -> Result<Proposal> {
        self.state.propose()
    }

    /// Runs the HiFi at the proposal, refits, and re-checks the new pick on the HiFi.
    pub fn step(&mut self) -> Result<PageStep> {
        let added = self.state.step(&self.hifi)?.clone();
        let step = self
            .state
            .report()
            .history
            .pop()
            .ok_or_else(|| RideError::Numerical("the loop kept no history".into()))?;
        let datum = self.state.decision().ctx.datum;
        let recheck = recheck(self.state.pick(), &self.hifi, &datum)?;
        Ok(PageStep {
            added,
            step,
            recheck,
        })
    }

    /// The loop so far: samples in order with reasons, and the history of fronts.
    pub fn report(&self) -> AdaptiveReport {
        self.state.report()
    }

    /// The surrogate's current feasible front.
    pub fn front(&self) -> &[FrontPoint] {
        self.state.front()
    }

    /// The uncertainty estimate `sigma_k`, %, at the centres of `nx` x `ny` cells of the
    /// design box ([`Grid::cells`]), as `[bacc plane, dtl plane, sws plane]`: index
    /// `k nx ny + j nx + i` (the maps' layout). Errors name `nx` or `ny`.
    pub fn uncertainty_map(&self, nx: usize, ny: usize) -> Result<Vec<f64>> {
        let grid = Grid::cells(&self.state.setting().design_box, nx, ny)?;
        let n = grid.len();
        let mut out = vec![0.0; 3 * n];
        for j in 0..ny {
            for i in 0..nx {
                let (ks, cs) = grid.point(i, j);
                let s = self.state.uncertain().relative_std(ks, cs)?;
                let at = grid.index(i, j);
                for k in 0..3 {
                    out[k * n + at] = 100.0 * s[k];
                }
            }
        }
        Ok(out)
    }

    /// How well the uncertainty estimate predicts the true error of the loop's current
    /// surrogate on the `levels x levels` HiFi validation grid over the design box (run
    /// on the HiFi once, `levels^2` runs, and kept), and the estimate at the samples.
    /// Errors name `levels` outside `2..=`[`MAX_CHECK_LEVELS`].
    pub fn uncertainty_check(&mut self, levels: usize) -> Result<PageUncertainty> {
        if !(2..=MAX_CHECK_LEVELS).contains(&levels) {
            return Err(RideError::field(
                "levels",
                format!("the validation grid needs 2 to {MAX_CHECK_LEVELS} levels per axis, got {levels}"),
            ));
        }
        if self.validation.as_ref().is_none_or(|v| v.levels != levels) {
            let b = self.state.setting().design_box;
            self.validation = Some(ValidationSet::new(&self.hifi, &b, levels)?);
        }
        let validation = self.validation.as_ref().expect("set above");
        let est = self.state.uncertain();
        let mut floor = [0.0f64; 3];
        for smp in self.state.samples() {
            let s = est.relative_std(smp.ks, smp.cs)?;
            for k in 0..3 {
                floor[k] = floor[k].max(100.0 * s[k]);
            }
        }
        Ok(PageUncertainty {
            levels,
            check: check(est, validation)?,
            at_samples_percent: ByCriterion::from_fn(|k| floor[k]),
        })
    }
}
