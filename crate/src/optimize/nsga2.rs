//! NSGA-II (Deb, Pratap, Agarwal, Meyarivan 2002) with Deb's constraint domination.
//!
//! Each generation: binary tournaments on (rank, crowding distance) pick parents,
//! simulated binary crossover and polynomial mutation make `N` children, and the best
//! `N` of parents + children survive by non-dominated rank, ties in the last front
//! broken by crowding distance. Seeded with `ChaCha8Rng`, so a seed gives one front.

use super::problem::{check_bounds, dominates, feasible_front, Eval, Problem, Solution};
use crate::error::{Result, RideError};
use crate::math;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;

/// NSGA-II settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Nsga2Params {
    /// Population size `N` (even, >= 4).
    pub population: usize,
    /// Number of generations (>= 1); the run costs `N (generations + 1)` evaluations.
    pub generations: usize,
    /// Seed of the `ChaCha8Rng` stream.
    pub seed: u64,
    /// Probability that a pair of parents is crossed, -.
    pub crossover_probability: f64,
    /// SBX distribution index `eta_c` (larger: children closer to parents), -.
    pub eta_c: f64,
    /// Polynomial-mutation distribution index `eta_m`, -.
    pub eta_m: f64,
    /// Per-variable mutation probability; `None` means `1 / n` for `n` variables.
    pub mutation_probability: Option<f64>,
}

impl Default for Nsga2Params {
    fn default() -> Self {
        Nsga2Params {
            population: 100,
            generations: 100,
            seed: 1,
            crossover_probability: 0.9,
            eta_c: 15.0,
            eta_m: 20.0,
            mutation_probability: None,
        }
    }
}

/// Largest population accepted (a population is held twice over, parents and children).
const MAX_POPULATION: usize = 10_000;
/// Most generations accepted.
const MAX_GENERATIONS: usize = 10_000;

impl Nsga2Params {
    /// Checks every setting; errors name the field.
    pub(crate) fn validate(&self) -> Result<()> {
        if self.population < 4
            || !self.population.is_multiple_of(2)
            || self.population > MAX_POPULATION
        {
            return Err(RideError::field(
                "population",
                format!(
                    "must be an even number from 4 to {MAX_POPULATION} (got {})",
                    self.population
                ),
            ));
        }
        if self.generations == 0 || self.generations > MAX_GENERATIONS {
            return Err(RideError::field(
                "generations",
                format!("must be 1 to {MAX_GENERATIONS} (got {})", self.generations),
            ));
        }
        self.check_runs(1)?;
        let unit = |name: &str, p: f64| {
            if (0.0..=1.0).contains(&p) {
                Ok(())
            } else {
                Err(RideError::field(name, "must lie in 0..1"))
            }
        };
        unit("crossover_probability", self.crossover_probability)?;
        if let Some(p) = self.mutation_probability {
            unit("mutation_probability", p)?;
        }
        for (name, eta) in [("eta_c", self.eta_c), ("eta_m", self.eta_m)] {
            if !(eta.is_finite() && eta >= 0.0) {
                return Err(RideError::field(name, "must be a finite number >= 0"));
            }
        }
        Ok(())
    }
}

impl Nsga2Params {
    /// Refuses a run over `cases` cases whose `population (generations + 1)` runs each
    /// exceed the command's bound ([`crate::budget::MAX_RUNS`]); errors name `generations`.
    pub(crate) fn check_runs(&self, cases: usize) -> Result<()> {
        let runs = (self.population as u64)
            .saturating_mul(self.generations as u64 + 1)
            .saturating_mul(cases as u64);
        crate::budget::check(
            runs,
            "generations",
            &format!(
                "NSGA-II with population {} for {} generations{}",
                self.population,
                self.generations,
                if cases > 1 {
                    format!(" over {cases} cases")
                } else {
                    String::new()
                }
            ),
            "--population or --generations",
        )
    }
}

/// Runs NSGA-II on `problem` and returns the feasible non-dominated members of the
/// final population, sorted by increasing `f1`; errors with [`Problem::infeasible`]
/// when none is feasible.
pub fn nsga2<P: Problem>(problem: &P, params: &Nsga2Params) -> Result<Vec<Solution<P::Info>>> {
    params.validate()?;
    let bounds = problem.bounds();
    check_bounds(&bounds)?;
    let n = params.population;
    let pm = params
        .mutation_probability
        .unwrap_or(1.0 / bounds.len() as f64);
    let mut rng = ChaCha8Rng::seed_from_u64(params.seed);

    let mut pop = Vec::with_capacity(2 * n);
    for _ in 0..n {
        let x: Vec<f64> = bounds
            .iter()
            .map(|&(lo, hi)| rng.random_range(lo..=hi))
            .collect();
        pop.push(Solution {
            eval: problem.evaluate(&x)?,
            x,
        });
    }
    let mut fitness = survive(&mut pop, n);

    for _ in 0..params.generations {
        let mut children = Vec::with_capacity(n);
        while children.len() < n {
            let a = &pop[tournament(&fitness, &mut rng)].x;
            let b = &pop[tournament(&fitness, &mut rng)].x;
            let (mut c1, mut c2) = if rng.random::<f64>() < params.crossover_probability {
                sbx(a, b, &bounds, params.eta_c, &mut rng)
            } else {
                (a.clone(), b.clone())
            };
            mutate(&mut c1, &bounds, pm, params.eta_m, &mut rng);
            mutate(&mut c2, &bounds, pm, params.eta_m, &mut rng);
            children.push(c1);
            children.push(c2);
        }
        for x in children {
            pop.push(Solution {
                eval: problem.evaluate(&x)?,
                x,
            });
        }
        fitness = survive(&mut pop, n);
    }

    let front = feasible_front(&pop);
    if front.is_empty() {
        return Err(problem.infeasible());
    }
    Ok(front)
}

/// Non-dominated rank (0 is best) and crowding distance of one population member.
#[derive(Debug, Clone, Copy)]
struct Fitness {
    rank: usize,
    crowding: f64,
}

/// Deb's constraint domination between `a` and `b`: `Less` when `a` dominates, `Greater`
/// when `b` does, `Equal` when neither. A feasible point beats an infeasible one, of two
/// infeasible points the smaller violation wins, of two feasible ones Pareto dominance.
fn constrained_domination<I>(a: &Eval<I>, b: &Eval<I>) -> Ordering {
    let (va, vb) = (a.violation, b.violation);
    match (va > 0.0, vb > 0.0) {
        (false, true) => Ordering::Less,
        (true, false) => Ordering::Greater,
        (true, true) => va.total_cmp(&vb),
        (false, false) if dominates(a.f, b.f) => Ordering::Less,
        (false, false) if dominates(b.f, a.f) => Ordering::Greater,
        (false, false) => Ordering::Equal,
    }
}

/// Fast non-dominated sort (Deb 2002, O(M N^2)) under constraint domination: the
/// fronts as lists of indices.
fn fronts<I>(pop: &[Solution<I>]) -> Vec<Vec<usize>> {
    let n = pop.len();
    let mut dominated_by: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut count = vec![0usize; n];
    for p in 0..n {
        for q in p + 1..n {
            match constrained_domination(&pop[p].eval, &pop[q].eval) {
                Ordering::Less => {
                    dominated_by[p].push(q);
                    count[q] += 1;
                }
                Ordering::Greater => {
                    dominated_by[q].push(p);
                    count[p] += 1;
                }
                Ordering::Equal => {}
            }
        }
    }
    let mut current: Vec<usize> = (0..n).filter(|&p| count[p] == 0).collect();
    let mut all = Vec::new();
    while !current.is_empty() {
        let mut next = Vec::new();
        for &p in &current {
            for &q in &dominated_by[p] {
                count[q] -= 1;
                if count[q] == 0 {
                    next.push(q);
                }
            }
        }
        next.sort_unstable();
        all.push(std::mem::replace(&mut current, next));
    }
    all
}

/// Crowding distance of each member of one front: the sum over objectives of the
/// normalised side lengths `(f_k[next] - f_k[prev]) / (f_k max - f_k min)` of the
/// cuboid around it; the extremes of each objective get infinity.
fn crowding<I>(pop: &[Solution<I>], front: &[usize]) -> Vec<f64> {
    let m = front.len();
    let mut d = vec![0.0; m];
    for k in 0..2 {
        let keys: Vec<f64> = front.iter().map(|&i| pop[i].eval.f[k]).collect();
        let order = crate::order::sorted_order(&keys);
        let f = |i: usize| pop[front[order[i]]].eval.f[k];
        let span = f(m - 1) - f(0);
        d[order[0]] = f64::INFINITY;
        d[order[m - 1]] = f64::INFINITY;
        if span > 0.0 {
            for i in 1..m.saturating_sub(1) {
                d[order[i]] += (f(i + 1) - f(i - 1)) / span;
            }
        }
    }
    d
}

/// Keeps the best `n` of `pop` (whole fronts, then the most crowded-apart of the
/// last front) and returns their rank and crowding, aligned with the new `pop`.
fn survive<I: Clone>(pop: &mut Vec<Solution<I>>, n: usize) -> Vec<Fitness> {
    let mut keep = Vec::with_capacity(n);
    let mut fitness = Vec::with_capacity(n);
    for (rank, front) in fronts(pop).into_iter().enumerate() {
        let d = crowding(pop, &front);
        let mut order: Vec<usize> = (0..front.len()).collect();
        if keep.len() + front.len() > n {
            // Most crowded-apart first: the negated distances' ascending order (crate::order).
            let apart: Vec<f64> = d.iter().map(|x| -x).collect();
            order = crate::order::sorted_order(&apart);
            order.truncate(n - keep.len());
        }
        for i in order {
            keep.push(front[i]);
            fitness.push(Fitness {
                rank,
                crowding: d[i],
            });
        }
        if keep.len() == n {
            break;
        }
    }
    *pop = keep.into_iter().map(|i| pop[i].clone()).collect();
    fitness
}

/// Binary tournament with the crowded-comparison operator: lower rank wins, then
/// larger crowding distance, then the first drawn.
fn tournament(fitness: &[Fitness], rng: &mut ChaCha8Rng) -> usize {
    let a = rng.random_range(0..fitness.len());
    let b = rng.random_range(0..fitness.len());
    let (fa, fb) = (fitness[a], fitness[b]);
    if fb.rank < fa.rank || (fb.rank == fa.rank && fb.crowding > fa.crowding) {
        b
    } else {
        a
    }
}

/// Simulated binary crossover with bounds (Deb and Agrawal 1995, as in Deb's NSGA-II
/// code): each variable is crossed with probability 0.5, the spread factor `beta_q`
/// drawn from the polynomial density of index `eta_c` truncated to the bounds.
fn sbx(
    a: &[f64],
    b: &[f64],
    bounds: &[(f64, f64)],
    eta: f64,
    rng: &mut ChaCha8Rng,
) -> (Vec<f64>, Vec<f64>) {
    let (mut c1, mut c2) = (a.to_vec(), b.to_vec());
    for (i, &(lo, hi)) in bounds.iter().enumerate() {
        if rng.random::<f64>() > 0.5 || (a[i] - b[i]).abs() <= 1e-14 {
            continue;
        }
        let (y1, y2) = (a[i].min(b[i]), a[i].max(b[i]));
        let u: f64 = rng.random();
        let beta_q = |beta: f64| {
            let alpha = 2.0 - math::powf(beta, -(eta + 1.0));
            if u <= 1.0 / alpha {
                math::powf(u * alpha, 1.0 / (eta + 1.0))
            } else {
                math::powf(1.0 / (2.0 - u * alpha), 1.0 / (eta + 1.0))
            }
        };
        let lower = 0.5 * ((y1 + y2) - beta_q(1.0 + 2.0 * (y1 - lo) / (y2 - y1)) * (y2 - y1));
        let upper = 0.5 * ((y1 + y2) + beta_q(1.0 + 2.0 * (hi - y2) / (y2 - y1)) * (y2 - y1));
        let (lower, upper) = (lower.clamp(lo, hi), upper.clamp(lo, hi));
        if rng.random::<f64>() < 0.5 {
            (c1[i], c2[i]) = (upper, lower);
        } else {
            (c1[i], c2[i]) = (lower, upper);
        }
    }
    (c1, c2)
}

/// Polynomial mutation with bounds (Deb and Goyal 1996): each variable mutates with
/// probability `pm` by `delta_q (hi - lo)`, `delta_q` from the density of index `eta_m`
/// truncated so the child stays inside the bounds.
fn mutate(x: &mut [f64], bounds: &[(f64, f64)], pm: f64, eta: f64, rng: &mut ChaCha8Rng) {
    for (xi, &(lo, hi)) in x.iter_mut().zip(bounds) {
        if rng.random::<f64>() >= pm {
            continue;
        }
        let span = hi - lo;
        let u: f64 = rng.random();
        let power = 1.0 / (eta + 1.0);
        let delta_q = if u < 0.5 {
            let xy = 1.0 - (*xi - lo) / span;
            math::powf(2.0 * u + (1.0 - 2.0 * u) * math::powf(xy, eta + 1.0), power) - 1.0
        } else {
            let xy = 1.0 - (hi - *xi) / span;
            1.0 - math::powf(
                2.0 * (1.0 - u) + 2.0 * (u - 0.5) * math::powf(xy, eta + 1.0),
                power,
            )
        };
        *xi = (*xi + delta_q * span).clamp(lo, hi);
    }
}

#[cfg(test)]
mod tests {
    use super::super::hypervolume::hypervolume;
    use super::super::test_problems::{Bnh, Zdt1};
    use super::*;

    fn objectives<I>(front: &[Solution<I>]) -> Vec<[f64; 2]> {
        front.iter().map(|s| s.eval.f).collect()
    }

    #[test]
    fn zdt1_reaches_99_percent_of_the_true_hypervolume() {
        let params = Nsga2Params {
            generations: 250,
            ..Default::default()
        };
        let front = nsga2(&Zdt1 { n: 30 }, &params).unwrap();
        let r = [1.1, 1.1];
        let hv = hypervolume(&objectives(&front), r);
        let hv_true = hypervolume(&Zdt1::true_front(100_001), r);
        let ratio = hv / hv_true;
        println!(
            "ZDT1: {} points, HV {hv:.5} of {hv_true:.5} = {ratio:.5}",
            front.len()
        );
        assert!(ratio >= 0.99, "HV ratio {ratio}");
    }

    #[test]
    fn bnh_reaches_99_percent_of_the_true_hypervolume() {
        let params = Nsga2Params {
            generations: 100,
            ..Default::default()
        };
        let front = nsga2(&Bnh, &params).unwrap();
        let truth = Bnh::true_front(100_001);
        let r = super::super::hypervolume::reference_point(&truth, 0.1);
        let hv = hypervolume(&objectives(&front), r);
        let hv_true = hypervolume(&truth, r);
        let ratio = hv / hv_true;
        println!(
            "BNH: {} points, ref {r:?}, HV {hv:.4} of {hv_true:.4} = {ratio:.5}",
            front.len()
        );
        assert!(ratio >= 0.99, "HV ratio {ratio}");
        assert!(front.iter().all(|s| s.eval.feasible()));
    }

    #[test]
    fn same_seed_same_front_bit_for_bit() {
        let params = Nsga2Params {
            generations: 30,
            seed: 7,
            ..Default::default()
        };
        let a = nsga2(&Zdt1 { n: 30 }, &params).unwrap();
        let b = nsga2(&Zdt1 { n: 30 }, &params).unwrap();
        assert_eq!(a, b);
        let c = nsga2(&Zdt1 { n: 30 }, &Nsga2Params { seed: 8, ..params }).unwrap();
        assert_ne!(a, c);
    }

    #[test]
    fn bad_settings_name_the_field() {
        let bad = |p: Nsga2Params| nsga2(&Bnh, &p).unwrap_err().to_string();
        assert!(bad(Nsga2Params {
            population: 7,
            ..Default::default()
        })
        .starts_with("population"));
        assert!(bad(Nsga2Params {
            generations: 0,
            ..Default::default()
        })
        .starts_with("generations"));
        assert!(bad(Nsga2Params {
            eta_c: -1.0,
            ..Default::default()
        })
        .starts_with("eta_c"));
        let p = Nsga2Params {
            mutation_probability: Some(2.0),
            ..Default::default()
        };
        assert!(bad(p).starts_with("mutation_probability"));
    }

    #[test]
    fn operators_stay_inside_the_bounds() {
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let bounds = [(0.0, 1.0), (-5.0, 5.0)];
        for _ in 0..1000 {
            let (mut a, b) = sbx(&[0.0, 4.9], &[1.0, -5.0], &bounds, 15.0, &mut rng);
            mutate(&mut a, &bounds, 1.0, 20.0, &mut rng);
            for (v, &(lo, hi)) in a.iter().chain(&b).zip(bounds.iter().cycle()) {
                assert!((lo..=hi).contains(v), "{v}");
            }
        }
    }
}
