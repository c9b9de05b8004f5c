//! Surrogate quality on a validation set (METHOD.md section 5), per criterion, for true
//! (HiFi) values `y_i` and predictions `p_i`, `i = 1..n`:
//!
//! ```text
//! R^2  = 1 - sum (y_i - p_i)^2 / sum (y_i - mean y)^2
//! RMSE = sqrt(sum (y_i - p_i)^2 / n)                     (units of the criterion)
//! MAE  = max |y_i - p_i|                                 (maximum absolute error, as the thesis defines it)
//! RTE  = 100 |y_i - p_i| / |y_i|, its max and its mean   (relative true error, %)
//! ```
//!
//! and the error map: the signed relative error `100 (p_i - y_i) / y_i` (%) at each point.

use crate::error::{Result, RideError};
use crate::evaluate::Criteria;
use serde::Serialize;

/// One value per criterion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ByCriterion<T> {
    /// Body acceleration.
    pub bacc: T,
    /// Dynamic tyre load.
    pub dtl: T,
    /// Suspension working space.
    pub sws: T,
}

impl<T> ByCriterion<T> {
    /// Builds from `f(k)`, `k` = 0 BAcc, 1 DTL, 2 SWS.
    pub fn from_fn(mut f: impl FnMut(usize) -> T) -> Self {
        ByCriterion {
            bacc: f(0),
            dtl: f(1),
            sws: f(2),
        }
    }

    /// The values as an array `[bacc, dtl, sws]`.
    pub fn to_array(&self) -> [&T; 3] {
        [&self.bacc, &self.dtl, &self.sws]
    }
}

/// Quality measures of one criterion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Metrics {
    /// Coefficient of determination, -.
    pub r2: f64,
    /// Root-mean-square error, units of the criterion.
    pub rmse: f64,
    /// Maximum absolute error, units of the criterion (JSON `max_abs_error`).
    #[serde(rename = "max_abs_error")]
    pub mae: f64,
    /// Largest relative true error, % (JSON `rte_max_percent`).
    #[serde(rename = "rte_max_percent")]
    pub rte_max: f64,
    /// Mean relative true error, % (JSON `rte_mean_percent`).
    #[serde(rename = "rte_mean_percent")]
    pub rte_mean: f64,
}

/// The measures of predictions `p` against true values `y` (same length, at least one,
/// every `y_i != 0`). A constant `y` has no variance: `R^2` is then 1 for a perfect
/// prediction and `-inf` otherwise.
pub fn metrics(y: &[f64], p: &[f64]) -> Result<Metrics> {
    if y.is_empty() || y.len() != p.len() {
        return Err(RideError::Numerical(format!(
            "metrics need equal, non-empty sets ({} true, {} predicted values)",
            y.len(),
            p.len()
        )));
    }
    if y.contains(&0.0) {
        return Err(RideError::Numerical(
            "a true value of 0 has no relative error".into(),
        ));
    }
    let n = y.len() as f64;
    let mean = y.iter().sum::<f64>() / n;
    let ss_res: f64 = y.iter().zip(p).map(|(a, b)| (a - b).powi(2)).sum();
    let ss_tot: f64 = y.iter().map(|a| (a - mean).powi(2)).sum();
    let r2 = match (ss_tot > 0.0, ss_res > 0.0) {
        (true, _) => 1.0 - ss_res / ss_tot,
        (false, false) => 1.0,
        (false, true) => f64::NEG_INFINITY,
    };
    let rte: Vec<f64> = y
        .iter()
        .zip(p)
        .map(|(a, b)| 100.0 * ((a - b) / a).abs())
        .collect();
    Ok(Metrics {
        r2,
        rmse: (ss_res / n).sqrt(),
        mae: y
            .iter()
            .zip(p)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max),
        rte_max: rte.iter().copied().fold(0.0, f64::max),
        rte_mean: rte.iter().sum::<f64>() / n,
    })
}

/// The measures of each criterion of `predicted` against `truth`.
pub(crate) fn metrics_by_criterion(
    truth: &[Criteria],
    predicted: &[Criteria],
) -> Result<ByCriterion<Metrics>> {
    let column =
        |set: &[Criteria], k: usize| -> Vec<f64> { set.iter().map(|c| c.to_array()[k]).collect() };
    let m: Vec<Metrics> = (0..3)
        .map(|k| metrics(&column(truth, k), &column(predicted, k)))
        .collect::<Result<_>>()?;
    Ok(ByCriterion::from_fn(|k| m[k]))
}

/// Signed relative error of the predictions at each validation point, per criterion.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorMap {
    /// Front spring rate of each point, N/m.
    pub ks: Vec<f64>,
    /// Front damper rate of each point, N s/m.
    pub cs: Vec<f64>,
    /// `100 (p_i - y_i) / y_i` at each point, %.
    pub relative_error: ByCriterion<Vec<f64>>,
}

impl ErrorMap {
    /// The map of `predicted` against `truth` at `points` `(ks, cs)` (same order).
    pub fn new(points: &[(f64, f64)], truth: &[Criteria], predicted: &[Criteria]) -> ErrorMap {
        ErrorMap {
            ks: points.iter().map(|p| p.0).collect(),
            cs: points.iter().map(|p| p.1).collect(),
            relative_error: ByCriterion::from_fn(|k| {
                truth
                    .iter()
                    .zip(predicted)
                    .map(|(y, p)| {
                        let (y, p) = (y.to_array()[k], p.to_array()[k]);
                        100.0 * (p - y) / y
                    })
                    .collect()
            }),
        }
    }
}

/// Pearson's correlation `sum (x_i - mean x)(y_i - mean y) / sqrt(sum (x_i - mean x)^2 sum (y_i - mean y)^2)`
/// of two equally long sets; `None` when they differ in length, hold fewer than 2 values,
/// a non-finite value, or one of them has no spread.
pub(crate) fn pearson(x: &[f64], y: &[f64]) -> Option<f64> {
    if x.len() != y.len() || x.len() < 2 || !x.iter().chain(y).all(|v| v.is_finite()) {
        return None;
    }
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in x.iter().zip(y) {
        sxy += (a - mx) * (b - my);
        sxx += (a - mx) * (a - mx);
        syy += (b - my) * (b - my);
    }
    (sxx > 0.0 && syy > 0.0).then(|| sxy / (sxx * syy).sqrt())
}

/// Spearman's rank correlation: Pearson's correlation of the ranks, tied values sharing
/// their mean rank; `None` as for [`pearson`].
pub(crate) fn spearman(x: &[f64], y: &[f64]) -> Option<f64> {
    if x.len() != y.len() || !x.iter().chain(y).all(|v| v.is_finite()) {
        return None;
    }
    pearson(&ranks(x), &ranks(y))
}

/// Ranks `1..=n` of `x` (finite values), ties given the mean of their ranks.
fn ranks(x: &[f64]) -> Vec<f64> {
    let order = crate::order::sorted_order(x);
    let mut rank = vec![0.0; x.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && x[order[j + 1]] == x[order[i]] {
            j += 1;
        }
        // positions i..=j (0-based) share the mean rank (i + j) / 2 + 1
        for &k in &order[i..=j] {
            rank[k] = (i + j) as f64 / 2.0 + 1.0;
        }
        i = j + 1;
    }
    rank
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hand_computed_example() {
        // y = [1, 2, 4], p = [1.1, 1.8, 4.4]: errors -0.1, 0.2, -0.4.
        // mean y = 7/3; SS_tot = (4/3)^2 + (1/3)^2 + (5/3)^2 = 42/9; SS_res = 0.01 + 0.04 + 0.16 = 0.21.
        // R^2 = 1 - 0.21 / (42/9) = 1 - 0.045 = 0.955; RMSE = sqrt(0.07); MAE = 0.4;
        // RTE = [10, 10, 10] %: max 10, mean 10.
        let m = metrics(&[1.0, 2.0, 4.0], &[1.1, 1.8, 4.4]).unwrap();
        assert!((m.r2 - 0.955).abs() < 1e-12, "{}", m.r2);
        assert!((m.rmse - 0.07f64.sqrt()).abs() < 1e-12);
        assert!((m.mae - 0.4).abs() < 1e-12);
        assert!((m.rte_max - 10.0).abs() < 1e-12 && (m.rte_mean - 10.0).abs() < 1e-12);

        // y = [2, 5], p = [2.5, 5]: RTE = [25, 0] %, max 25, mean 12.5; SS_tot = 4.5,
        // SS_res = 0.25, R^2 = 1 - 0.25/4.5 = 17/18; RMSE = sqrt(0.125); MAE = 0.5.
        let m = metrics(&[2.0, 5.0], &[2.5, 5.0]).unwrap();
        assert!((m.r2 - 17.0 / 18.0).abs() < 1e-12);
        assert!((m.rmse - 0.125f64.sqrt()).abs() < 1e-12);
        assert!((m.mae - 0.5).abs() < 1e-12);
        assert!((m.rte_max - 25.0).abs() < 1e-12 && (m.rte_mean - 12.5).abs() < 1e-12);

        assert_eq!(metrics(&[3.0, 3.0], &[3.0, 3.0]).unwrap().r2, 1.0);
        assert!(metrics(&[1.0], &[]).is_err());
        assert!(metrics(&[0.0], &[1.0]).is_err());
    }

    #[test]
    fn per_criterion_and_error_map() {
        let y = [
            Criteria::from_array([1.0, 100.0, 0.01]),
            Criteria::from_array([2.0, 200.0, 0.02]),
        ];
        let p = [
            Criteria::from_array([1.1, 100.0, 0.009]),
            Criteria::from_array([2.0, 190.0, 0.02]),
        ];
        let m = metrics_by_criterion(&y, &p).unwrap();
        assert!((m.bacc.rte_max - 10.0).abs() < 1e-12);
        assert!((m.dtl.mae - 10.0).abs() < 1e-12);
        assert!((m.sws.rte_mean - 5.0).abs() < 1e-9);
        let map = ErrorMap::new(&[(1.0, 2.0), (3.0, 4.0)], &y, &p);
        assert_eq!(map.cs, vec![2.0, 4.0]);
        assert!((map.relative_error.bacc[0] - 10.0).abs() < 1e-12);
        assert!((map.relative_error.dtl[1] + 5.0).abs() < 1e-12);
        assert!((map.relative_error.sws[0] + 10.0).abs() < 1e-9);
    }

    #[test]
    fn correlations_by_hand() {
        // x = [1, 2, 3, 4], y = [2, 1, 4, 3]: means 2.5; deviations (-1.5, -0.5, 0.5, 1.5)
        // and (-0.5, -1.5, 1.5, 0.5); Sxy = 0.75 + 0.75 + 0.75 + 0.75 = 3, Sxx = Syy = 5,
        // r = 0.6. The values are their own ranks, so Spearman is 0.6 too.
        let (x, y) = ([1.0, 2.0, 3.0, 4.0], [2.0, 1.0, 4.0, 3.0]);
        assert!((pearson(&x, &y).unwrap() - 0.6).abs() < 1e-12);
        assert!((spearman(&x, &y).unwrap() - 0.6).abs() < 1e-12);
        // A monotone but nonlinear y: Spearman 1, Pearson below 1.
        let y3 = [1.0, 8.0, 27.0, 1000.0];
        assert!((spearman(&x, &y3).unwrap() - 1.0).abs() < 1e-12);
        assert!(pearson(&x, &y3).unwrap() < 0.9);
        // Ties share their mean rank: [1, 1, 2] -> [1.5, 1.5, 3].
        assert_eq!(ranks(&[1.0, 1.0, 2.0]), vec![1.5, 1.5, 3.0]);
        assert_eq!(ranks(&[3.0, 1.0, 3.0, 2.0]), vec![3.5, 1.0, 3.5, 2.0]);
        assert!(pearson(&[1.0, 1.0], &[1.0, 2.0]).is_none());
        assert!(pearson(&[1.0], &[1.0]).is_none());
        assert!(spearman(&[1.0, f64::NAN], &[1.0, 2.0]).is_none());
    }
}
