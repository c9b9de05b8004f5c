//! The kernel's arithmetic for one cell, on the CPU, in any float type: in `f64` it is
//! the GPU route's reference, in `f32` it emulates `kernel.wgsl` operation for operation
//! (same buffers, same order), so the route's error and its f32 error are both measured
//! here without a GPU.
//!
//! At each node (angular frequency `w`) and for each half and wheel group `g` (front,
//! rear), with `Z = K - w^2 M + i w C` on the nine slots of [`super::halves::SLOTS`]:
//!
//! ```text
//! d_u = 1 / Z_uu                                   (u = 2, 3: the wheels)
//! S_ab = Z_ab - sum_u Z_au d_u Z_ub                (a, b = 0, 1: the body)
//! r_a  = F_a - sum_u Z_au d_u F_u,   F = Kr_g + i w Cr_g
//! S p_b = r                                        (2 x 2, partial pivoting)
//! p_u  = d_u (F_u - sum_a Z_ua p_a)
//! T_o  = sum_i (Yq_oi - w^2 Ya_oi + i w Yv_oi) p_i + Yr_go
//! ```
//!
//! and the node adds `weight |T_f + cross T_r|^2` (combined) or
//! `weight (|T_f|^2 + |T_r|^2) + Re(cross T_f conj(T_r))` (split), times the half's
//! weight. Sums run per panel, then over panels (pairwise at two levels: the f32 error of
//! a sum of `n` positive terms drops from `n eps` to about `(8 + n / 8) eps`).
//!
//! The product uses the packing ([`pack_half`], [`pack_node`]); the arithmetic is test
//! code (`#[cfg(test)]`), the yardstick of `kernel.wgsl`.

use super::halves::Half;
#[cfg(test)]
use super::halves::N_COORD;
use super::quadrature::Node;
#[cfg(test)]
use super::quadrature::NODES_PER_PANEL;
use crate::model::N_OUT;
#[cfg(test)]
use num_complex::Complex;
#[cfg(test)]
use num_traits::Float;

/// Floats per half in the packed buffer (see [`pack_half`]).
pub const HALF_STRIDE: usize = 104;
/// Offsets in a packed half.
pub(crate) mod offset {
    pub const WEIGHT: usize = 0;
    pub const M: usize = 1;
    pub const K0: usize = 10;
    pub const DK: usize = 19;
    pub const C0: usize = 28;
    pub const DC: usize = 37;
    pub const KR: usize = 46;
    pub const CR: usize = 54;
    pub const YR: usize = 62;
    pub const OUT_Q: usize = 68;
    pub const OUT_V: usize = 80;
    pub const OUT_A: usize = 92;
}

/// A half as `HALF_STRIDE` numbers: weight, `m`, `k0`, `dk`, `c0`, `dc` (9 slots each),
/// `kr`, `cr` (group-major, 4 each), `yr` (group-major, 3 each), `out_q`, `out_v`, `out_a`
/// (output-major, 4 each).
pub fn pack_half(h: &Half) -> [f64; HALF_STRIDE] {
    let mut out = [0.0; HALF_STRIDE];
    out[offset::WEIGHT] = h.weight;
    for (at, s) in [
        (offset::M, &h.m),
        (offset::K0, &h.k0),
        (offset::DK, &h.dk),
        (offset::C0, &h.c0),
        (offset::DC, &h.dc),
    ] {
        out[at..at + 9].copy_from_slice(s);
    }
    for g in 0..2 {
        out[offset::KR + 4 * g..offset::KR + 4 * g + 4].copy_from_slice(&h.kr[g]);
        out[offset::CR + 4 * g..offset::CR + 4 * g + 4].copy_from_slice(&h.cr[g]);
        out[offset::YR + 3 * g..offset::YR + 3 * g + 3].copy_from_slice(&h.yr[g]);
    }
    for o in 0..N_OUT {
        out[offset::OUT_Q + 4 * o..offset::OUT_Q + 4 * o + 4].copy_from_slice(&h.out_q[o]);
        out[offset::OUT_V + 4 * o..offset::OUT_V + 4 * o + 4].copy_from_slice(&h.out_v[o]);
        out[offset::OUT_A + 4 * o..offset::OUT_A + 4 * o + 4].copy_from_slice(&h.out_a[o]);
    }
    out
}

/// A node as the kernel reads it: `[w, weight, cross.re, cross.im]`.
pub fn pack_node(n: &Node) -> [f64; 4] {
    [n.omega, n.weight, n.cross.re, n.cross.im]
}

#[cfg(test)]
type C<F> = Complex<F>;

#[cfg(test)]
fn c<F: Float>(re: F, im: F) -> C<F> {
    Complex::new(re, im)
}

#[cfg(test)]
fn cmul<F: Float>(a: C<F>, b: C<F>) -> C<F> {
    c(a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re)
}

#[cfg(test)]
fn cdiv<F: Float>(a: C<F>, b: C<F>) -> C<F> {
    let d = b.re * b.re + b.im * b.im;
    c(
        (a.re * b.re + a.im * b.im) / d,
        (a.im * b.re - a.re * b.im) / d,
    )
}

#[cfg(test)]
fn norm2<F: Float>(a: C<F>) -> F {
    a.re * a.re + a.im * a.im
}

/// One half's matrices at a design: `K` and `C` on the nine slots.
#[cfg(test)]
struct Design<F> {
    k: [F; 9],
    c: [F; 9],
}

/// The variances `[BAcc, DTL, SWS]` divided by the road velocity PSD `Gv` (times `Gv`,
/// m^2/s^2 per Hz, they are m^2/s^4, N^2, m^2) of the cell with front spring `ks` (N/m)
/// and damper `cs` (N s/m), from packed halves, packed combined nodes and packed split
/// nodes. Every float operation is done in `F`. The kernel's arithmetic on the CPU, for
/// the tests that check the kernel's f32 against the route (`GpuMapper::map_cpu`).
#[cfg(test)]
pub fn cell_variances<F: Float>(
    halves: &[[F; HALF_STRIDE]],
    combined: &[[F; 4]],
    split: &[[F; 4]],
    ks: F,
    cs: F,
) -> [F; N_OUT] {
    let mut total = [F::zero(); N_OUT];
    for h in halves {
        let d = Design {
            k: std::array::from_fn(|s| h[offset::K0 + s] + ks * h[offset::DK + s]),
            c: std::array::from_fn(|s| h[offset::C0 + s] + cs * h[offset::DC + s]),
        };
        let mut acc = [F::zero(); N_OUT];
        for (nodes, is_combined) in [(combined, true), (split, false)] {
            for panel in nodes.chunks(NODES_PER_PANEL) {
                let mut part = [F::zero(); N_OUT];
                for node in panel {
                    let [tf, tr] = transfers(h, &d, node[0]);
                    let cross = c(node[2], node[3]);
                    for o in 0..N_OUT {
                        let v = if is_combined {
                            node[1] * norm2(tf[o] + cmul(cross, tr[o]))
                        } else {
                            node[1] * (norm2(tf[o]) + norm2(tr[o]))
                                + cmul(cross, cmul(tf[o], tr[o].conj())).re
                        };
                        part[o] = part[o] + v;
                    }
                }
                for o in 0..N_OUT {
                    acc[o] = acc[o] + part[o];
                }
            }
        }
        for o in 0..N_OUT {
            total[o] = total[o] + h[offset::WEIGHT] * acc[o];
        }
    }
    total
}

/// Displacement transfers of the front and rear wheel groups to `[BAcc, DTL, SWS]` at
/// angular frequency `w` (see the module doc).
#[cfg(test)]
fn transfers<F: Float>(h: &[F; HALF_STRIDE], d: &Design<F>, w: F) -> [[C<F>; N_OUT]; 2] {
    let w2 = w * w;
    let z: [C<F>; 9] = std::array::from_fn(|s| c(d.k[s] - w2 * h[offset::M + s], w * d.c[s]));
    // Slots: 0 (0,0), 1 (0,1), 2 (1,1), 3 (0,2), 4 (0,3), 5 (1,2), 6 (1,3), 7 (2,2), 8 (3,3).
    let one = c(F::one(), F::zero());
    let d2 = cdiv(one, z[7]);
    let d3 = cdiv(one, z[8]);
    let (z02, z03, z12, z13) = (z[3], z[4], z[5], z[6]);
    let s00 = z[0] - cmul(cmul(z02, d2), z02) - cmul(cmul(z03, d3), z03);
    let s01 = z[1] - cmul(cmul(z02, d2), z12) - cmul(cmul(z03, d3), z13);
    let s11 = z[2] - cmul(cmul(z12, d2), z12) - cmul(cmul(z13, d3), z13);
    std::array::from_fn(|g| {
        let f: [C<F>; N_COORD] =
            std::array::from_fn(|i| c(h[offset::KR + 4 * g + i], w * h[offset::CR + 4 * g + i]));
        let r0 = f[0] - cmul(cmul(z02, d2), f[2]) - cmul(cmul(z03, d3), f[3]);
        let r1 = f[1] - cmul(cmul(z12, d2), f[2]) - cmul(cmul(z13, d3), f[3]);
        let (p0, p1) = solve2(s00, s01, s11, r0, r1);
        let p2 = cmul(d2, f[2] - cmul(z02, p0) - cmul(z12, p1));
        let p3 = cmul(d3, f[3] - cmul(z03, p0) - cmul(z13, p1));
        let p = [p0, p1, p2, p3];
        std::array::from_fn(|o| {
            let mut t = c(h[offset::YR + 3 * g + o], F::zero());
            for i in 0..N_COORD {
                let coef = c(
                    h[offset::OUT_Q + 4 * o + i] - w2 * h[offset::OUT_A + 4 * o + i],
                    w * h[offset::OUT_V + 4 * o + i],
                );
                t = t + cmul(coef, p[i]);
            }
            t
        })
    })
}

/// Solves the symmetric `[[s00, s01], [s01, s11]] [x0, x1] = [r0, r1]` by elimination
/// with partial pivoting (no determinant: its square would overflow f32 at the tail).
#[cfg(test)]
fn solve2<F: Float>(s00: C<F>, s01: C<F>, s11: C<F>, r0: C<F>, r1: C<F>) -> (C<F>, C<F>) {
    if norm2(s00) >= norm2(s01) {
        let l = cdiv(s01, s00);
        let x1 = cdiv(r1 - cmul(l, r0), s11 - cmul(l, s01));
        (cdiv(r0 - cmul(s01, x1), s00), x1)
    } else {
        // Pivot on row 1, whose first entry is s01.
        let l = cdiv(s00, s01);
        let x1 = cdiv(r0 - cmul(l, r1), s01 - cmul(l, s11));
        (cdiv(r1 - cmul(s11, x1), s01), x1)
    }
}
