//! Eigenvalues of a small real matrix: reduction to upper Hessenberg form by
//! stabilised elementary similarity transforms, then the Francis double-shift QR
//! iteration (EISPACK `elmhes` + `hqr`, as in Press et al., Numerical Recipes, 11.5-11.6).
//!
//! Written here rather than taken from nalgebra because nalgebra's Schur-based
//! `complex_eigenvalues` took about 44 us on the 8 x 8 half-car matrix, more than the
//! whole HiFi evaluation budget; this takes a few microseconds.

use num_complex::Complex64 as C64;

/// Eigenvalues of the row-major `n x n` matrix `a` (destroyed), or `None` if the
/// QR iteration does not converge.
pub(crate) fn eigenvalues(a: &mut [f64], n: usize) -> Option<Vec<C64>> {
    balance(a, n);
    elmhes(a, n);
    let (mut wr, mut wi) = (vec![0.0; n], vec![0.0; n]);
    hqr(a, n, &mut wr, &mut wi).then(|| (0..n).map(|i| C64::new(wr[i], wi[i])).collect())
}

/// Eigenvalues of the row-major upper Hessenberg `n x n` matrix `a` (destroyed), real
/// parts into `wr[..n]` and imaginary parts into `wi[..n]`, without allocating; a complex
/// pair is returned as two consecutive entries with `wi` of opposite signs, exactly
/// conjugate. Returns false if the QR iteration does not converge.
pub(crate) fn hessenberg_eigenvalues(
    a: &mut [f64],
    n: usize,
    wr: &mut [f64],
    wi: &mut [f64],
) -> bool {
    balance(a, n);
    hqr(a, n, wr, wi)
}

/// Diagonal similarity scaling by powers of 2 so that rows and columns have comparable
/// norms (EISPACK `balanc`): the state matrices mix entries of order 1 and 1e4.
fn balance(a: &mut [f64], n: usize) {
    const RADIX: f64 = 2.0;
    let sqrdx = RADIX * RADIX;
    let mut done = false;
    while !done {
        done = true;
        for i in 0..n {
            let (mut r, mut c) = (0.0, 0.0);
            for j in 0..n {
                if j != i {
                    c += a[j * n + i].abs();
                    r += a[i * n + j].abs();
                }
            }
            if c != 0.0 && r != 0.0 {
                let mut g = r / RADIX;
                let mut f = 1.0;
                let s = c + r;
                while c < g {
                    f *= RADIX;
                    c *= sqrdx;
                }
                g = r * RADIX;
                while c > g {
                    f /= RADIX;
                    c /= sqrdx;
                }
                if (c + r) / f < 0.95 * s {
                    done = false;
                    let g = 1.0 / f;
                    for j in 0..n {
                        a[i * n + j] *= g;
                    }
                    for j in 0..n {
                        a[j * n + i] *= f;
                    }
                }
            }
        }
    }
}

fn elmhes(a: &mut [f64], n: usize) {
    let at = |i: usize, j: usize| i * n + j;
    for m in 1..n.saturating_sub(1) {
        let mut x: f64 = 0.0;
        let mut i = m;
        for j in m..n {
            if a[at(j, m - 1)].abs() > x.abs() {
                x = a[at(j, m - 1)];
                i = j;
            }
        }
        if i != m {
            for j in (m - 1)..n {
                a.swap(at(i, j), at(m, j));
            }
            for j in 0..n {
                a.swap(at(j, i), at(j, m));
            }
        }
        if x != 0.0 {
            for i in (m + 1)..n {
                let mut y = a[at(i, m - 1)];
                if y != 0.0 {
                    y /= x;
                    a[at(i, m - 1)] = y;
                    for j in m..n {
                        a[at(i, j)] -= y * a[at(m, j)];
                    }
                    for j in 0..n {
                        a[at(j, m)] += y * a[at(j, i)];
                    }
                }
            }
        }
    }
    // Clear the multipliers stored below the subdiagonal.
    for i in 2..n {
        for j in 0..i - 1 {
            a[at(i, j)] = 0.0;
        }
    }
}

#[allow(clippy::many_single_char_names)]
fn hqr(a: &mut [f64], n: usize, wr: &mut [f64], wi: &mut [f64]) -> bool {
    let at = |i: usize, j: usize| i * n + j;
    let mut anorm: f64 = 0.0;
    for i in 0..n {
        for j in i.saturating_sub(1)..n {
            anorm += a[at(i, j)].abs();
        }
    }
    let mut nn = n as isize - 1;
    let mut t: f64 = 0.0;
    while nn >= 0 {
        let mut its = 0;
        loop {
            // Look for a single small subdiagonal element.
            let mut l = nn;
            while l >= 1 {
                let (lu, lm) = (l as usize, (l - 1) as usize);
                let s = a[at(lm, lm)].abs() + a[at(lu, lu)].abs();
                let s = if s == 0.0 { anorm } else { s };
                if a[at(lu, lm)].abs() + s == s {
                    a[at(lu, lm)] = 0.0;
                    break;
                }
                l -= 1;
            }
            let nu = nn as usize;
            let x = a[at(nu, nu)];
            if l == nn {
                wr[nu] = x + t;
                wi[nu] = 0.0;
                nn -= 1;
                break;
            }
            let y = a[at(nu - 1, nu - 1)];
            let w = a[at(nu, nu - 1)] * a[at(nu - 1, nu)];
            if l == nn - 1 {
                let p = 0.5 * (y - x);
                let q = p * p + w;
                let z = q.abs().sqrt();
                let x = x + t;
                if q >= 0.0 {
                    let z = p + z.copysign(p);
                    wr[nu - 1] = x + z;
                    wr[nu] = if z != 0.0 { x - w / z } else { x + z };
                    wi[nu - 1] = 0.0;
                    wi[nu] = 0.0;
                } else {
                    wr[nu - 1] = x + p;
                    wr[nu] = x + p;
                    wi[nu - 1] = -z;
                    wi[nu] = z;
                }
                nn -= 2;
                break;
            }
            if its == 60 {
                return false;
            }
            let (mut x, mut y, mut w) = (x, y, w);
            if its == 10 || its == 20 {
                // Exceptional shift.
                t += x;
                for i in 0..=nu {
                    a[at(i, i)] -= x;
                }
                let s = a[at(nu, nu - 1)].abs() + a[at(nu - 1, nu - 2)].abs();
                x = 0.75 * s;
                y = x;
                w = -0.4375 * s * s;
            }
            its += 1;
            // Form the shift and look for two consecutive small subdiagonal elements.
            let lu = l as usize;
            let mut m = nu - 2;
            let (mut p, mut q, mut r);
            loop {
                let z = a[at(m, m)];
                let rr = x - z;
                let ss = y - z;
                p = (rr * ss - w) / a[at(m + 1, m)] + a[at(m, m + 1)];
                q = a[at(m + 1, m + 1)] - z - rr - ss;
                r = a[at(m + 2, m + 1)];
                let s = p.abs() + q.abs() + r.abs();
                p /= s;
                q /= s;
                r /= s;
                if m == lu {
                    break;
                }
                let u = a[at(m, m - 1)].abs() * (q.abs() + r.abs());
                let v = p.abs() * (a[at(m - 1, m - 1)].abs() + z.abs() + a[at(m + 1, m + 1)].abs());
                if u + v == v {
                    break;
                }
                m -= 1;
            }
            for i in (m + 2)..=nu {
                a[at(i, i - 2)] = 0.0;
                if i != m + 2 {
                    a[at(i, i - 3)] = 0.0;
                }
            }
            // Double QR step on rows l..nn and columns m..nn.
            let mut k = m;
            while k < nu {
                if k != m {
                    p = a[at(k, k - 1)];
                    q = a[at(k + 1, k - 1)];
                    r = if k + 1 != nu {
                        a[at(k + 2, k - 1)]
                    } else {
                        0.0
                    };
                    x = p.abs() + q.abs() + r.abs();
                    if x != 0.0 {
                        p /= x;
                        q /= x;
                        r /= x;
                    }
                }
                let s = (p * p + q * q + r * r).sqrt().copysign(p);
                if s != 0.0 {
                    if k == m {
                        if l as usize != m {
                            a[at(k, k - 1)] = -a[at(k, k - 1)];
                        }
                    } else {
                        a[at(k, k - 1)] = -s * x;
                    }
                    p += s;
                    x = p / s;
                    y = q / s;
                    let z = r / s;
                    q /= p;
                    r /= p;
                    for j in k..=nu {
                        let mut pp = a[at(k, j)] + q * a[at(k + 1, j)];
                        if k + 1 != nu {
                            pp += r * a[at(k + 2, j)];
                            a[at(k + 2, j)] -= pp * z;
                        }
                        a[at(k + 1, j)] -= pp * y;
                        a[at(k, j)] -= pp * x;
                    }
                    let mmin = if nu < k + 3 { nu } else { k + 3 };
                    for i in lu..=mmin {
                        let mut pp = x * a[at(i, k)] + y * a[at(i, k + 1)];
                        if k + 1 != nu {
                            pp += z * a[at(i, k + 2)];
                            a[at(i, k + 2)] -= pp * r;
                        }
                        a[at(i, k + 1)] -= pp * q;
                        a[at(i, k)] -= pp;
                    }
                }
                k += 1;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_nalgebra_on_random_matrices() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for n in [1usize, 2, 3, 5, 8, 14] {
            for _ in 0..20 {
                let v: Vec<f64> = (0..n * n).map(|_| rng.random_range(-3.0..3.0)).collect();
                let m = nalgebra::DMatrix::from_row_slice(n, n, &v);
                let mut reference: Vec<C64> = m.complex_eigenvalues().iter().copied().collect();
                let mut mine = eigenvalues(&mut v.clone(), n).unwrap();
                let key = |c: &C64| {
                    (c.re * 1e6).round() as i64 * 1_000_000_000 + (c.im * 1e3).round() as i64
                };
                reference.sort_by_key(key);
                mine.sort_by_key(key);
                for (a, b) in reference.iter().zip(&mine) {
                    assert!(
                        (a - b).norm() < 1e-8 * (1.0 + a.norm()),
                        "n={n}: {a} vs {b}"
                    );
                }
            }
        }
    }
}
