//! The residue route's algebra: real polynomials of fixed capacity, determinants and
//! adjugates of small polynomial matrices, and the roots of a real polynomial whose
//! coefficients are all positive (a stable characteristic polynomial).

use super::hqr;
use crate::math;
use num_complex::Complex64 as C64;

/// Most coordinates of a polynomial matrix (the symmetric half car has 4).
pub(super) const MAX_N: usize = 4;
/// Most roots of a characteristic polynomial `det(M s^2 + C s + K)`, `2 MAX_N`.
pub(super) const MAX_ROOTS: usize = 2 * MAX_N;
/// Capacity of a polynomial: degree 11 (an output row of degree 2 times a cofactor of
/// degree `2 (MAX_N - 1)` times an input of degree 1 is degree 9).
const CAP: usize = 12;

/// A real polynomial `sum_i c[i] s^i`, `len` coefficients in use.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Poly {
    c: [f64; CAP],
    len: usize,
}

impl Poly {
    /// The zero polynomial.
    pub(crate) fn zero() -> Poly {
        Poly {
            c: [0.0; CAP],
            len: 0,
        }
    }

    /// The polynomial with coefficients `c` (ascending powers, at most 12).
    pub(crate) fn new(c: &[f64]) -> Poly {
        let mut p = Poly::zero();
        p.len = c.len().min(CAP);
        p.c[..p.len].copy_from_slice(&c[..p.len]);
        p
    }

    /// Coefficient of `s^i` (0 beyond the polynomial).
    pub(crate) fn coef(&self, i: usize) -> f64 {
        if i < self.len {
            self.c[i]
        } else {
            0.0
        }
    }

    /// Number of coefficients in use (degree + 1, or 0).
    #[cfg(test)]
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// The product (degrees must add up to at most 11; the matrices here stay within it).
    pub(crate) fn mul(&self, o: &Poly) -> Poly {
        let mut p = Poly::zero();
        if self.len == 0 || o.len == 0 {
            return p;
        }
        p.len = (self.len + o.len - 1).min(CAP);
        for i in 0..self.len {
            for j in 0..o.len.min(CAP - i) {
                p.c[i + j] += self.c[i] * o.c[j];
            }
        }
        p
    }

    /// `self + f o`.
    pub(crate) fn add_scaled(&self, o: &Poly, f: f64) -> Poly {
        let mut p = *self;
        p.len = self.len.max(o.len);
        for i in 0..o.len {
            p.c[i] += f * o.c[i];
        }
        p
    }

    /// `f self`.
    pub(crate) fn scaled(&self, f: f64) -> Poly {
        let mut p = *self;
        for v in p.c[..p.len].iter_mut() {
            *v *= f;
        }
        p
    }
}

/// A square polynomial matrix of at most [`MAX_N`] rows, as rows of entries.
pub(super) type PolyMatrix = [[Poly; MAX_N]; MAX_N];

/// Determinant of the submatrix of `m` on `rows` x `cols` (equal lengths), by cofactor
/// expansion along its first row.
pub(super) fn minor_det(m: &PolyMatrix, rows: &[usize], cols: &[usize]) -> Poly {
    match rows.len() {
        0 => Poly::new(&[1.0]),
        1 => m[rows[0]][cols[0]],
        n => {
            let mut acc = Poly::zero();
            let mut rest = [0; MAX_N];
            for (ci, &c) in cols.iter().enumerate() {
                let mut len = 0;
                for &x in cols.iter().filter(|&&x| x != c) {
                    rest[len] = x;
                    len += 1;
                }
                let term = m[rows[0]][c].mul(&minor_det(m, &rows[1..n], &rest[..len]));
                acc = acc.add_scaled(&term, if ci % 2 == 0 { 1.0 } else { -1.0 });
            }
            acc
        }
    }
}

/// Adjugate of the leading `n x n` block: `adj_rs = (-1)^(r+s) det(m without row s, column r)`.
pub(super) fn adjugate(m: &PolyMatrix, n: usize) -> PolyMatrix {
    let mut adj = [[Poly::zero(); MAX_N]; MAX_N];
    let all: Vec<usize> = (0..n).collect();
    for r in 0..n {
        for s in 0..n {
            let rows: Vec<usize> = all.iter().copied().filter(|&i| i != s).collect();
            let cols: Vec<usize> = all.iter().copied().filter(|&i| i != r).collect();
            let sign = if (r + s) % 2 == 0 { 1.0 } else { -1.0 };
            adj[r][s] = minor_det(m, &rows, &cols).scaled(sign);
        }
    }
    adj
}

/// The roots of a real polynomial: one root of each complex pair (positive imaginary part)
/// and every real root.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Roots {
    /// Number of roots kept.
    pub n: usize,
    /// The roots kept.
    pub z: [C64; MAX_ROOTS],
    /// True where the root is complex (its conjugate is a root too).
    pub pair: [bool; MAX_ROOTS],
}

/// Most Aberth iterations before the QR route takes over.
const ABERTH_ITERATIONS: usize = 24;

/// The roots of `d` (ascending coefficients, degree `d.len() - 1 <= 8`, all positive).
///
/// With `start` (one root of each of `deg / 2` complex pairs, e.g. the roots of a nearby
/// polynomial), the Aberth-Ehrlich iteration on the upper half plane,
/// `z_k -= w / (1 - w sum_{j != k} (1 / (z_k - z_j)))` over every other root and conjugate,
/// `w = p(z_k) / p'(z_k)`, until every correction is below `1e-8 |z_k|` (the iteration
/// converges cubically: the next error is at the rounding level; the caller measures the
/// roots' backward error). Otherwise, or if
/// it does not converge (a pair turning real), the eigenvalues of the balanced companion
/// matrix of `d(omega0 x)` by Francis QR ([`super::hqr`]), `omega0 = (d_0 / d_deg)^(1/deg)`,
/// then one Newton step on `d`. `None` if neither converges.
pub(super) fn roots(d: &[f64], start: Option<&Roots>) -> Option<Roots> {
    if let Some(s) = start {
        if let Some(r) = aberth(d, s) {
            return Some(r);
        }
    }
    companion_roots(d)
}

fn aberth(d: &[f64], start: &Roots) -> Option<Roots> {
    let deg = d.len() - 1;
    let m = start.n;
    if 2 * m != deg || start.pair[..m].iter().any(|p| !p) {
        return None;
    }
    let mut z = start.z;
    for _ in 0..ABERTH_ITERATIONS {
        // Every correction from the current roots (independent, so they overlap).
        let mut step = [C64::new(0.0, 0.0); MAX_ROOTS];
        for k in 0..m {
            let zk = z[k];
            let (p, dp) = value_and_slope(d, zk);
            let w = p * recip(dp);
            // 1 / (z - z_j) + 1 / (z - conj z_j) = 2 (z - x_j) / ((z - x_j)^2 + y_j^2).
            let mut s = recip(zk - zk.conj());
            for j in (0..m).filter(|&j| j != k) {
                let x = zk - z[j].re;
                s += 2.0 * x * recip(x * x + z[j].im * z[j].im);
            }
            step[k] = w * recip(C64::new(1.0, 0.0) - w * s);
        }
        let mut converged = true;
        for k in 0..m {
            if !(step[k].re.is_finite() && step[k].im.is_finite()) {
                return None;
            }
            z[k] -= step[k];
            if z[k].im.is_nan() || z[k].im <= 1e-6 * l1(z[k]) {
                return None;
            }
            converged &= l1(step[k]) <= 1e-8 * l1(z[k]);
        }
        if converged {
            return Some(Roots {
                n: m,
                z,
                pair: start.pair,
            });
        }
    }
    None
}

fn companion_roots(d: &[f64]) -> Option<Roots> {
    let deg = d.len() - 1;
    if !(1..=MAX_ROOTS).contains(&deg) {
        return None;
    }
    // Companion matrix of the monic polynomial in x = s / omega0: first row
    // -d_i omega0^i / (d_deg omega0^deg), i = deg-1 .. 0, ones below the diagonal.
    let omega0 = math::powf(d[0] / d[deg], 1.0 / deg as f64);
    let mut a = [0.0; MAX_ROOTS * MAX_ROOTS];
    let mut pw = 1.0;
    for i in 0..deg {
        a[deg - 1 - i] = -d[i] * pw / d[deg];
        pw *= omega0;
    }
    for v in a[..deg].iter_mut() {
        *v /= pw;
    }
    for i in 1..deg {
        a[i * deg + i - 1] = 1.0;
    }
    let (mut wr, mut wi) = ([0.0; MAX_ROOTS], [0.0; MAX_ROOTS]);
    if !hqr::hessenberg_eigenvalues(&mut a[..deg * deg], deg, &mut wr, &mut wi) {
        return None;
    }
    let mut r = Roots {
        n: 0,
        z: [C64::new(0.0, 0.0); MAX_ROOTS],
        pair: [false; MAX_ROOTS],
    };
    for i in (0..deg).filter(|&i| wi[i] >= 0.0) {
        // One Newton step on d itself (a real root stays real).
        let mut l = C64::new(wr[i], wi[i]) * omega0;
        let (p, dp) = value_and_slope(d, l);
        let step = p * recip(dp);
        if step.re.is_finite() && step.im.is_finite() {
            l -= step;
        }
        r.z[r.n] = l;
        r.pair[r.n] = wi[i] > 0.0;
        r.n += 1;
    }
    Some(r)
}

/// `p(z)` and `p'(z)` by Horner's rule, real coefficients `c` (ascending).
pub(super) fn value_and_slope(c: &[f64], z: C64) -> (C64, C64) {
    let mut v = C64::new(0.0, 0.0);
    let mut dv = C64::new(0.0, 0.0);
    for &ci in c.iter().rev() {
        dv = dv * z + v;
        v = v * z + ci;
    }
    (v, dv)
}

/// `1 / z` with one division.
pub(super) fn recip(z: C64) -> C64 {
    let f = 1.0 / z.norm_sqr();
    C64::new(z.re * f, -z.im * f)
}

/// `|re| + |im|`: between `|z|` and `sqrt(2) |z|`, with no square root.
pub(super) fn l1(z: C64) -> f64 {
    z.re.abs() + z.im.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn from_roots(roots: &[C64]) -> Vec<f64> {
        let mut p = Poly::new(&[1.0]);
        for r in roots {
            let f = if r.im != 0.0 {
                Poly::new(&[r.norm_sqr(), -2.0 * r.re, 1.0])
            } else {
                Poly::new(&[-r.re, 1.0])
            };
            p = p.mul(&f);
        }
        (0..p.len()).map(|i| 3.0 * p.coef(i)).collect()
    }

    #[test]
    fn aberth_and_qr_find_the_same_roots() {
        let exact = [
            C64::new(-23.3, 68.1),
            C64::new(-51.2, 46.0),
            C64::new(-3.2, 8.5),
            C64::new(-2.8, 7.7),
        ];
        let d = from_roots(&exact);
        let start = Roots {
            n: 4,
            z: [
                C64::new(-20.0, 60.0),
                C64::new(-40.0, 50.0),
                C64::new(-3.0, 9.0),
                C64::new(-2.0, 6.0),
                C64::new(0.0, 0.0),
                C64::new(0.0, 0.0),
                C64::new(0.0, 0.0),
                C64::new(0.0, 0.0),
            ],
            pair: [true, true, true, true, false, false, false, false],
        };
        for r in [roots(&d, Some(&start)).unwrap(), roots(&d, None).unwrap()] {
            assert_eq!(r.n, 4);
            for e in exact {
                let near = r.z[..4]
                    .iter()
                    .map(|z| (z - e).norm())
                    .fold(f64::MAX, f64::min);
                assert!(near < 1e-12 * e.norm(), "{e}: {:?}", &r.z[..4]);
            }
        }
        // Two real roots: Aberth on pairs cannot hold them and hands over to QR.
        let mixed = [
            C64::new(-23.3, 68.1),
            C64::new(-4.0, 0.0),
            C64::new(-6.0, 0.0),
        ];
        let d = from_roots(&mixed);
        let mut start2 = start;
        start2.n = 2;
        let r = roots(&d, Some(&start2)).unwrap();
        assert_eq!(r.n, 3);
        assert_eq!(r.pair[..3].iter().filter(|p| **p).count(), 1);
    }

    #[test]
    fn adjugate_times_matrix_is_the_determinant() {
        let e = |c: &[f64]| Poly::new(c);
        let mut m = [[Poly::zero(); MAX_N]; MAX_N];
        let vals = [
            [e(&[4.0, 1.0, 2.0]), e(&[-1.0, -0.5]), e(&[0.5]), e(&[0.0])],
            [
                e(&[-1.0, -0.5]),
                e(&[5.0, 2.0, 1.0]),
                e(&[-2.0, -1.0]),
                e(&[0.3]),
            ],
            [e(&[0.5]), e(&[-2.0, -1.0]), e(&[6.0, 1.5, 3.0]), e(&[-1.0])],
            [e(&[0.0]), e(&[0.3]), e(&[-1.0]), e(&[7.0, 0.0, 1.0])],
        ];
        for r in 0..4 {
            for s in 0..4 {
                m[r][s] = vals[r][s];
            }
        }
        let adj = adjugate(&m, 4);
        let det = minor_det(&m, &[0, 1, 2, 3], &[0, 1, 2, 3]);
        for r in 0..4 {
            for s in 0..4 {
                let mut acc = Poly::zero();
                for k in 0..4 {
                    acc = acc.add_scaled(&m[r][k].mul(&adj[k][s]), 1.0);
                }
                for i in 0..CAP {
                    let want = if r == s { det.coef(i) } else { 0.0 };
                    assert!((acc.coef(i) - want).abs() < 1e-12 * (1.0 + det.coef(i).abs()));
                }
            }
        }
    }
}
