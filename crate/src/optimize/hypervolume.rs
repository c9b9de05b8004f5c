//! Front quality: exact 2-D hypervolume, the reference point it is measured from,
//! and the distance between a front and a reference front.

use super::problem::non_dominated;
use crate::math;
use serde::Serialize;

/// Exact hypervolume (minimisation) of `points` against `reference`: the area of
/// `{y : p <= y <= reference}` over all points `p`, in units of `f1 * f2`.
///
/// Sort-and-sweep on the non-dominated points `p_1 .. p_k` (increasing `f1`) that
/// strictly dominate the reference: `HV = sum_i (f1_{i+1} - f1_i) (r_2 - f2_i)`,
/// with `f1_{k+1} = r_1`. Points outside the reference box add nothing.
pub fn hypervolume(points: &[[f64; 2]], reference: [f64; 2]) -> f64 {
    let inside: Vec<[f64; 2]> = points
        .iter()
        .copied()
        .filter(|p| p[0] < reference[0] && p[1] < reference[1])
        .collect();
    let front: Vec<[f64; 2]> = non_dominated(&inside)
        .into_iter()
        .map(|i| inside[i])
        .collect();
    front
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let next_f1 = front.get(i + 1).map_or(reference[0], |q| q[0]);
            (next_f1 - p[0]) * (reference[1] - p[1])
        })
        .sum()
}

/// Ideal (component-wise minimum) and nadir (component-wise maximum) of a non-empty front.
pub(crate) fn ideal_nadir(front: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let mut ideal = [f64::INFINITY; 2];
    let mut nadir = [f64::NEG_INFINITY; 2];
    for p in front {
        for k in 0..2 {
            ideal[k] = ideal[k].min(p[k]);
            nadir[k] = nadir[k].max(p[k]);
        }
    }
    (ideal, nadir)
}

/// Reference point `r_k = nadir_k + margin (nadir_k - ideal_k)` of a (reference) front,
/// so the hypervolume measures the front in its own window whatever the units.
/// An objective with no spread gets `nadir_k + margin max(|nadir_k|, 1)`.
pub(crate) fn reference_point(front: &[[f64; 2]], margin: f64) -> [f64; 2] {
    let (ideal, nadir) = ideal_nadir(front);
    let mut r = [0.0; 2];
    for k in 0..2 {
        let span = nadir[k] - ideal[k];
        let span = if span > 0.0 {
            span
        } else {
            nadir[k].abs().max(1.0)
        };
        r[k] = nadir[k] + margin * span;
    }
    r
}

/// Distances between a front and a reference front, in objectives normalised by the
/// reference front's range: `f'_k = (f_k - ideal_k) / (nadir_k - ideal_k)`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FrontDistance {
    /// IGD: mean over reference points of the distance to the nearest front point, -.
    pub igd: f64,
    /// Largest distance from a reference point to the nearest front point (gaps), -.
    pub igd_max: f64,
    /// GD: mean over front points of the distance to the nearest reference point, -.
    pub gd: f64,
    /// Largest distance from a front point to the nearest reference point, -.
    pub gd_max: f64,
}

/// Nearest-point distances between `front` and `reference` (both non-empty), both ways.
pub(crate) fn front_distance(front: &[[f64; 2]], reference: &[[f64; 2]]) -> FrontDistance {
    let (ideal, nadir) = ideal_nadir(reference);
    let scale = [0, 1].map(|k| {
        let s = nadir[k] - ideal[k];
        if s > 0.0 {
            s
        } else {
            1.0
        }
    });
    let norm = |p: &[f64; 2]| [(p[0] - ideal[0]) / scale[0], (p[1] - ideal[1]) / scale[1]];
    let a: Vec<[f64; 2]> = front.iter().map(norm).collect();
    let b: Vec<[f64; 2]> = reference.iter().map(norm).collect();
    let (igd, igd_max) = mean_max_nearest(&b, &a);
    let (gd, gd_max) = mean_max_nearest(&a, &b);
    FrontDistance {
        igd,
        igd_max,
        gd,
        gd_max,
    }
}

/// Mean and maximum over `from` of the Euclidean distance to the nearest point of `to`.
fn mean_max_nearest(from: &[[f64; 2]], to: &[[f64; 2]]) -> (f64, f64) {
    let mut sum = 0.0;
    let mut max: f64 = 0.0;
    for p in from {
        let d = to
            .iter()
            .map(|q| math::hypot(p[0] - q[0], p[1] - q[1]))
            .fold(f64::INFINITY, f64::min);
        sum += d;
        max = max.max(d);
    }
    (sum / from.len() as f64, max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn staircase_of_three_points() {
        // 1*1 + 1*2 + 1*3 = 6
        let hv = hypervolume(&[[1.0, 3.0], [2.0, 2.0], [3.0, 1.0]], [4.0, 4.0]);
        assert!((hv - 6.0).abs() < 1e-12, "{hv}");
    }

    #[test]
    fn dominated_and_outside_points_add_nothing() {
        // (2.5,2.5) is dominated by (2,2); (5,0) lies beyond r1; (1,3) alone gives 3*1.
        let pts = [[1.0, 3.0], [2.0, 2.0], [2.5, 2.5], [5.0, 0.0], [3.0, 1.0]];
        assert!((hypervolume(&pts, [4.0, 4.0]) - 6.0).abs() < 1e-12);
        assert!((hypervolume(&[[1.0, 3.0]], [4.0, 4.0]) - 3.0).abs() < 1e-12);
        // a single point in a unit-offset box: 0.5 * 0.25
        assert!((hypervolume(&[[0.5, 0.75]], [1.0, 1.0]) - 0.125).abs() < 1e-12);
        assert_eq!(hypervolume(&[], [1.0, 1.0]), 0.0);
    }

    #[test]
    fn reference_point_adds_a_tenth_of_the_range() {
        let r = reference_point(&[[0.0, 1.0], [1.0, 0.0]], 0.1);
        assert_eq!(r, [1.1, 1.1]);
        let r = reference_point(&[[2.0, 10.0], [4.0, 6.0]], 0.1);
        assert!(
            (r[0] - 4.2).abs() < 1e-12 && (r[1] - 10.4).abs() < 1e-12,
            "{r:?}"
        );
    }

    #[test]
    fn distances_are_zero_on_the_same_front_and_see_a_gap() {
        let reference = [[0.0, 1.0], [0.5, 0.5], [1.0, 0.0]];
        let d = front_distance(&reference, &reference);
        assert_eq!((d.igd, d.igd_max, d.gd, d.gd_max), (0.0, 0.0, 0.0, 0.0));
        // missing the middle point: it is sqrt(0.5) away from either end
        let d = front_distance(&[[0.0, 1.0], [1.0, 0.0]], &reference);
        assert!((d.igd_max - 0.5f64.sqrt()).abs() < 1e-12);
        assert!((d.igd - 0.5f64.sqrt() / 3.0).abs() < 1e-12);
        assert_eq!(d.gd, 0.0);
    }
}
