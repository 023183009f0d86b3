"""The Dr.Jit peer of the crate's batch kernels (issue 53): the same formulas written by hand in
Dr.Jit (Mitsuba 3's JIT array library), LLVM backend, one thread, f32, 2^20 elements, timed
over repeated runs. Prints ns per element (median, min, max over the runs) as a markdown table.

    python3 -m venv V && V/bin/pip install mitsuba numpy
    V/bin/python benches/peer/drjit_peer.py [--runs 15] [--n 1048576]

Inputs (seeded, numpy): unit half vectors with slopes ~ N(0, 0.2^2) per axis (the crate's
bench draws its realistic cases' half vectors from a comparable spread), footprints whose
slope derivatives have lengths log-uniform in [0.005, 0.5] and uniform directions. Materials as
`benches/batch.rs`: isotropic alpha = 0.1 for the unfiltered rows, axis-aligned (0.1, 0.3) for
the filtered rows, pixel filter sigma = 0.5. The peer has no clamp rules (the crate's filtered
rows run `ClampRules::default()`), and evaluates every element without checks for non-finite
input (the crate's kernels return 0 there).

Timing: each run traces the expression, launches the kernel and waits for it (dr.eval +
dr.sync_thread); the first run (JIT compilation, cached after) is not counted. With
JitFlag.KernelHistory the kernels' own execution time is reported beside the wall time.
"""

import argparse
import math
import statistics
import time

import numpy as np
import mitsuba as mi

mi.set_variant("llvm_ad_rgb")
import drjit as dr  # noqa: E402  (after the variant: Mitsuba picks the backend)
from drjit.llvm import Float  # noqa: E402

INV_PI = 1.0 / math.pi


def inputs(n, seed=0x5EED):
    rng = np.random.default_rng(seed)
    s = rng.normal(0.0, 0.2, size=(n, 2))
    inv = 1.0 / np.sqrt(1.0 + (s * s).sum(axis=1))
    h = np.stack([-s[:, 0] * inv, -s[:, 1] * inv, inv], axis=1)
    lu = np.exp(rng.uniform(math.log(0.005), math.log(0.5), size=n))
    lv = lu * np.exp(rng.uniform(math.log(0.1), 0.0, size=n))
    pu, pv = rng.uniform(0, 2 * math.pi, size=n), rng.uniform(0, 2 * math.pi, size=n)
    du = np.stack([lu * np.cos(pu), lu * np.sin(pu)], axis=1)
    dv = np.stack([lv * np.cos(pv), lv * np.sin(pv)], axis=1)
    cols = [h[:, 0], h[:, 1], h[:, 2], du[:, 0], du[:, 1], dv[:, 0], dv[:, 1]]
    out = [Float(c.astype(np.float32)) for c in cols]
    dr.eval(*out)
    return out


def ggx_d_iso(hx, hy, hz, fp, alpha=0.1):
    # D = 1 / (pi a^2 z^4 (1 + (x^2 + y^2) / (a^2 z^2))^2) = a^2 / (pi (x^2 + y^2 + a^2 z^2)^2)
    a2 = alpha * alpha
    q = hx * hx + hy * hy + a2 * hz * hz
    return dr.select(hz > 0, a2 * INV_PI / (q * q), 0.0)


def beckmann_d_iso(hx, hy, hz, fp, alpha=0.1):
    # D = exp(-(x^2 + y^2) / (a^2 z^2)) / (pi a^2 z^4)
    a2 = alpha * alpha
    z2 = hz * hz
    iz2 = dr.rcp(z2)
    t = (hx * hx + hy * hy) * iz2 / a2
    return dr.select(hz > 0, dr.exp(-t) * INV_PI / a2 * iz2 * iz2, 0.0)


def filtered_matrix(fp, ax=0.1, ay=0.3, sigma=0.5):
    # A' = A + 2 Sigma, Sigma = sigma^2 (du du^T + dv dv^T) (KHPL16 eq. 13-15, TK19 sec. 2.2)
    ux, uy, vx, vy = fp
    k = 2.0 * sigma * sigma
    a11 = ax * ax + k * (ux * ux + vx * vx)
    a12 = k * (ux * uy + vx * vy)
    a22 = ay * ay + k * (uy * uy + vy * vy)
    return a11, a12, a22


def quad_form(hx, hy, hz, a11, a12, a22):
    # s^T A^-1 s with s = -h_xy / h_z, and det A
    det = a11 * a22 - a12 * a12
    idet = dr.rcp(det)
    iz = dr.rcp(hz)
    sx, sy = -hx * iz, -hy * iz
    q = (a22 * sx * sx - 2.0 * a12 * sx * sy + a11 * sy * sy) * idet
    return q, det, iz


def beckmann_d_filtered(hx, hy, hz, fp):
    a11, a12, a22 = filtered_matrix(fp)
    q, det, iz = quad_form(hx, hy, hz, a11, a12, a22)
    iz2 = iz * iz
    return dr.select(hz > 0, dr.exp(-q) * INV_PI * dr.rsqrt(det) * iz2 * iz2, 0.0)


def ggx_d_filtered_tk19(hx, hy, hz, fp):
    a11, a12, a22 = filtered_matrix(fp)
    q, det, iz = quad_form(hx, hy, hz, a11, a12, a22)
    iz2 = iz * iz
    t = 1.0 + q
    return dr.select(hz > 0, INV_PI * dr.rsqrt(det) * iz2 * iz2 / (t * t), 0.0)


KERNELS = [
    ("GGX `D`, isotropic", "batch_ggx_d_isotropic", ggx_d_iso),
    ("Beckmann `D`, isotropic", "batch_beckmann_d_isotropic", beckmann_d_iso),
    (
        "Beckmann `A + 2 Sigma` then `D` (peer without clamps)",
        "batch_beckmann_d_filtered",
        beckmann_d_filtered,
    ),
    (
        "TK19 GGX `A + 2 Sigma` then `D` (peer without clamps)",
        "batch_ggx_d_filtered_tk19",
        ggx_d_filtered_tk19,
    ),
]


def time_kernel(f, args, runs):
    hx, hy, hz, ux, uy, vx, vy = args
    fp = (ux, uy, vx, vy)
    n = dr.width(hx)
    out = f(hx, hy, hz, fp)
    dr.eval(out)
    dr.sync_thread()
    walls, kernels = [], []
    for _ in range(runs):
        dr.kernel_history()  # clear
        t0 = time.perf_counter()
        out = f(hx, hy, hz, fp)
        dr.eval(out)
        dr.sync_thread()
        walls.append((time.perf_counter() - t0) * 1e9 / n)
        hist = dr.kernel_history()
        ks = [h.get("execution_time", 0.0) for h in hist if h.get("type") != "other"]
        if ks:
            kernels.append(sum(ks) * 1e6 / n)
    return walls, kernels


def stats(xs):
    if not xs:
        return "-"
    return f"{statistics.median(xs):.2f} ({min(xs):.2f}-{max(xs):.2f})"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=15)
    ap.add_argument("--n", type=int, default=1 << 20)
    a = ap.parse_args()
    dr.set_thread_count(1)
    dr.set_flag(dr.JitFlag.KernelHistory, True)
    args = inputs(a.n)
    print(f"Dr.Jit {dr.__version__}, Mitsuba {mi.__version__}, LLVM backend, 1 thread, f32, "
          f"{a.n} elements, {a.runs} runs: ns per element, median (min-max)\n")
    print("| kernel | crate bench group | Dr.Jit wall | Dr.Jit kernel only |")
    print("|---|---|---:|---:|")
    for name, group, f in KERNELS:
        walls, kernels = time_kernel(f, args, a.runs)
        print(f"| {name} | `{group}/f32` | {stats(walls)} | {stats(kernels)} |")


if __name__ == "__main__":
    main()
