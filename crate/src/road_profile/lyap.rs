//! Lyapunov equations `A X + X A^T + M = 0` by the Bartels-Stewart method.
//!
//! With the real Schur form `A = Q T Q^T` (`T` quasi upper triangular, 1 x 1 and 2 x 2
//! diagonal blocks) the equation becomes `T Y + Y T^T = F`, `F = -Q^T M Q`, `X = Q Y Q^T`,
//! solved block by block from the bottom-right corner:
//!
//! ```text
//! T_ii Y_ij + Y_ij T_jj^T = F_ij - sum_{k > i} T_ik Y_kj - sum_{l > j} Y_il T_jl^T
//! ```
//!
//! each a system of at most 4 unknowns. Written here because `criteria::exact` solves the
//! Kronecker form `(I (x) A + A (x) I) vec X = -vec M`, whose LU costs `n^6 / 3`: fine for
//! 14 states, seconds for the 46 states of a full car with a shaping filter on each of its
//! four wheel groups; this costs `O(n^3)` per equation after one Schur decomposition.

use crate::error::{Result, RideError};
use nalgebra::{DMatrix, Schur};

/// The Schur form of `A`, ready for any number of right-hand sides.
pub(crate) struct Lyapunov {
    q: DMatrix<f64>,
    t: DMatrix<f64>,
    /// `(first index, size)` of each diagonal block of `T`.
    blocks: Vec<(usize, usize)>,
}

impl Lyapunov {
    /// Decomposes `a` (square).
    pub(crate) fn new(a: &DMatrix<f64>) -> Result<Lyapunov> {
        let n = a.nrows();
        let schur = Schur::try_new(a.clone(), f64::EPSILON, 1000 * n.max(1))
            .ok_or_else(|| RideError::Numerical("Schur decomposition did not converge".into()))?;
        let (q, t) = schur.unpack();
        let mut blocks = Vec::new();
        let mut i = 0;
        while i < n {
            let scale = t[(i, i)].abs()
                + if i + 1 < n {
                    t[(i + 1, i + 1)].abs()
                } else {
                    0.0
                };
            if i + 1 < n && t[(i + 1, i)].abs() > 1e-14 * scale.max(f64::MIN_POSITIVE) {
                blocks.push((i, 2));
                i += 2;
            } else {
                blocks.push((i, 1));
                i += 1;
            }
        }
        Ok(Lyapunov { q, t, blocks })
    }

    /// `X` with `A X + X A^T + M = 0`.
    pub(crate) fn solve(&self, m: &DMatrix<f64>) -> Result<DMatrix<f64>> {
        let n = self.t.nrows();
        let f = -(self.q.transpose() * m * &self.q);
        let mut y = DMatrix::<f64>::zeros(n, n);
        for &(r0, p) in self.blocks.iter().rev() {
            for &(c0, q) in self.blocks.iter().rev() {
                let mut rhs = f.view((r0, c0), (p, q)).into_owned();
                let below = n - r0 - p;
                if below > 0 {
                    rhs -= self.t.view((r0, r0 + p), (p, below)) * y.view((r0 + p, c0), (below, q));
                }
                let right = n - c0 - q;
                if right > 0 {
                    rhs -= y.view((r0, c0 + q), (p, right))
                        * self.t.view((c0, c0 + q), (q, right)).transpose();
                }
                // (I_q (x) T_ii + T_jj (x) I_p) vec Y = vec rhs (column-major vec).
                let tii = self.t.view((r0, r0), (p, p));
                let tjj = self.t.view((c0, c0), (q, q));
                let mut k = DMatrix::<f64>::zeros(p * q, p * q);
                for b in 0..q {
                    for a in 0..p {
                        let row = b * p + a;
                        for a2 in 0..p {
                            k[(row, b * p + a2)] += tii[(a, a2)];
                        }
                        for b2 in 0..q {
                            k[(row, b2 * p + a)] += tjj[(b, b2)];
                        }
                    }
                }
                let sol = k
                    .lu()
                    .solve(&nalgebra::DVector::from_column_slice(rhs.as_slice()))
                    .ok_or_else(|| {
                        RideError::Numerical(
                            "Lyapunov equation is singular: is the model stable?".into(),
                        )
                    })?;
                y.view_mut((r0, c0), (p, q))
                    .copy_from(&DMatrix::from_column_slice(p, q, sol.as_slice()));
            }
        }
        Ok(&self.q * y * self.q.transpose())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::car::Car;
    use crate::model::full_car;

    /// The residual of the full car's Lyapunov equation is at rounding level, also for a
    /// right-hand side that is not symmetric (a Sylvester pair).
    #[test]
    fn solves_the_full_car_equation() {
        let ss = full_car(&Car::datum()).state_space().unwrap();
        let a = ss.a;
        let n = a.nrows();
        let lyap = Lyapunov::new(&a).unwrap();
        let b1 = ss.bd.column(0).into_owned();
        let b2 = ss.bd.column(2).into_owned() + ss.bv.column(1);
        for m in [&b1 * b1.transpose(), &b1 * b2.transpose()] {
            let x = lyap.solve(&m).unwrap();
            let r = &a * &x + &x * a.transpose() + &m;
            let scale = a.amax() * x.amax() + m.amax();
            assert!(r.amax() < 1e-12 * scale, "{} of {scale}", r.amax());
        }
        // Repeated eigenvalues (two identical decoupled blocks) are no trouble.
        let mut big = DMatrix::zeros(2 * n, 2 * n);
        big.view_mut((0, 0), (n, n)).copy_from(&a);
        big.view_mut((n, n), (n, n)).copy_from(&a);
        let bb = DMatrix::from_fn(2 * n, 1, |i, _| (i as f64 * 0.37).sin());
        let m = &bb * bb.transpose();
        let x = Lyapunov::new(&big).unwrap().solve(&m).unwrap();
        let r = &big * &x + &x * big.transpose() + &m;
        assert!(r.amax() < 1e-10 * (big.amax() * x.amax() + m.amax()));
    }
}
