// HiFi criteria of one Ks x Cs cell per invocation: the frequency route of
// `cell.rs`, operation for operation, in f32. The constants HALF_STRIDE, OFF_* and
// NODES_PER_PANEL are prepended from Rust (`device.rs`), so the buffer layout has one
// definition.
//
// Bindings:
//   params: grid size, number of halves, combined and split node counts
//   halves: HALF_STRIDE floats per half (see `cell::pack_half`)
//   nodes:  vec4(w rad/s, weight, cross.re, cross.im), the combined nodes first
//   axes:   the Ks values (N/m) then the Cs values (N s/m)
//   out:    3 floats per cell, row-major (Cs rows): var / Gv of BAcc, DTL, SWS

struct Params {
    n_ks: u32,
    n_cs: u32,
    n_halves: u32,
    n_combined: u32,
    n_split: u32,
    pad0: u32,
    pad1: u32,
    pad2: u32,
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<storage, read> halves: array<f32>;
@group(0) @binding(2) var<storage, read> nodes: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read> axes: array<f32>;
@group(0) @binding(4) var<storage, read_write> out: array<f32>;

fn cmul(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    return vec2<f32>(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x);
}

fn cdiv(a: vec2<f32>, b: vec2<f32>) -> vec2<f32> {
    let d = b.x * b.x + b.y * b.y;
    return vec2<f32>((a.x * b.x + a.y * b.y) / d, (a.y * b.x - a.x * b.y) / d);
}

fn norm2(a: vec2<f32>) -> f32 {
    return a.x * a.x + a.y * a.y;
}

// Symmetric 2 x 2 solve by elimination with partial pivoting.
fn solve2(s00: vec2<f32>, s01: vec2<f32>, s11: vec2<f32>, r0: vec2<f32>, r1: vec2<f32>) -> array<vec2<f32>, 2> {
    if norm2(s00) >= norm2(s01) {
        let l = cdiv(s01, s00);
        let x1 = cdiv(r1 - cmul(l, r0), s11 - cmul(l, s01));
        return array<vec2<f32>, 2>(cdiv(r0 - cmul(s01, x1), s00), x1);
    }
    let l = cdiv(s00, s01);
    let x1 = cdiv(r0 - cmul(l, r1), s01 - cmul(l, s11));
    return array<vec2<f32>, 2>(cdiv(r1 - cmul(s11, x1), s01), x1);
}

// Transfers [front BAcc, DTL, SWS, rear BAcc, DTL, SWS] of half `base` at `w` rad/s,
// with the cell's stiffness `k` and damping `c` on the nine slots.
fn transfers(base: u32, k: array<f32, 9>, c: array<f32, 9>, w: f32) -> array<vec2<f32>, 6> {
    var kk = k;
    var cc = c;
    let w2 = w * w;
    var z: array<vec2<f32>, 9>;
    for (var s = 0u; s < 9u; s++) {
        z[s] = vec2<f32>(kk[s] - w2 * halves[base + OFF_M + s], w * cc[s]);
    }
    let one = vec2<f32>(1.0, 0.0);
    let d2 = cdiv(one, z[7]);
    let d3 = cdiv(one, z[8]);
    let z02 = z[3];
    let z03 = z[4];
    let z12 = z[5];
    let z13 = z[6];
    let s00 = z[0] - cmul(cmul(z02, d2), z02) - cmul(cmul(z03, d3), z03);
    let s01 = z[1] - cmul(cmul(z02, d2), z12) - cmul(cmul(z03, d3), z13);
    let s11 = z[2] - cmul(cmul(z12, d2), z12) - cmul(cmul(z13, d3), z13);
    var t: array<vec2<f32>, 6>;
    for (var g = 0u; g < 2u; g++) {
        var f: array<vec2<f32>, 4>;
        for (var i = 0u; i < 4u; i++) {
            f[i] = vec2<f32>(halves[base + OFF_KR + 4u * g + i], w * halves[base + OFF_CR + 4u * g + i]);
        }
        let r0 = f[0] - cmul(cmul(z02, d2), f[2]) - cmul(cmul(z03, d3), f[3]);
        let r1 = f[1] - cmul(cmul(z12, d2), f[2]) - cmul(cmul(z13, d3), f[3]);
        let pb = solve2(s00, s01, s11, r0, r1);
        let p2 = cmul(d2, f[2] - cmul(z02, pb[0]) - cmul(z12, pb[1]));
        let p3 = cmul(d3, f[3] - cmul(z03, pb[0]) - cmul(z13, pb[1]));
        var p = array<vec2<f32>, 4>(pb[0], pb[1], p2, p3);
        for (var o = 0u; o < 3u; o++) {
            var acc = vec2<f32>(halves[base + OFF_YR + 3u * g + o], 0.0);
            for (var i = 0u; i < 4u; i++) {
                let at = 4u * o + i;
                let coef = vec2<f32>(
                    halves[base + OFF_OUT_Q + at] - w2 * halves[base + OFF_OUT_A + at],
                    w * halves[base + OFF_OUT_V + at],
                );
                acc = acc + cmul(coef, p[i]);
            }
            t[3u * g + o] = acc;
        }
    }
    return t;
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    let j = id.y;
    if i >= params.n_ks || j >= params.n_cs {
        return;
    }
    let ks = axes[i];
    let cs = axes[params.n_ks + j];
    var total = vec3<f32>(0.0, 0.0, 0.0);
    for (var h = 0u; h < params.n_halves; h++) {
        let base = h * HALF_STRIDE;
        var k: array<f32, 9>;
        var c: array<f32, 9>;
        for (var s = 0u; s < 9u; s++) {
            k[s] = halves[base + OFF_K0 + s] + ks * halves[base + OFF_DK + s];
            c[s] = halves[base + OFF_C0 + s] + cs * halves[base + OFF_DC + s];
        }
        var acc = vec3<f32>(0.0, 0.0, 0.0);
        // Combined nodes: weight |T_f + cross T_r|^2, summed per panel.
        for (var p = 0u; p < params.n_combined; p += NODES_PER_PANEL) {
            var part = vec3<f32>(0.0, 0.0, 0.0);
            for (var q = p; q < p + NODES_PER_PANEL; q++) {
                let node = nodes[q];
                var t = transfers(base, k, c, node.x);
                let cross = node.zw;
                for (var o = 0u; o < 3u; o++) {
                    part[o] = part[o] + node.y * norm2(t[o] + cmul(cross, t[3u + o]));
                }
            }
            acc = acc + part;
        }
        // Split nodes: weight (|T_f|^2 + |T_r|^2) + Re(cross T_f conj(T_r)).
        let n_all = params.n_combined + params.n_split;
        for (var p = params.n_combined; p < n_all; p += NODES_PER_PANEL) {
            var part = vec3<f32>(0.0, 0.0, 0.0);
            for (var q = p; q < p + NODES_PER_PANEL; q++) {
                let node = nodes[q];
                var t = transfers(base, k, c, node.x);
                let cross = node.zw;
                for (var o = 0u; o < 3u; o++) {
                    let tf = t[o];
                    let tr = t[3u + o];
                    let ff = vec2<f32>(tf.x * tr.x + tf.y * tr.y, tf.y * tr.x - tf.x * tr.y);
                    part[o] = part[o] + (node.y * (norm2(tf) + norm2(tr)) + cmul(cross, ff).x);
                }
            }
            acc = acc + part;
        }
        total = total + halves[base + OFF_WEIGHT] * acc;
    }
    let cell = 3u * (j * params.n_ks + i);
    out[cell] = total.x;
    out[cell + 1u] = total.y;
    out[cell + 2u] = total.z;
}
