#!/usr/bin/env python3
"""Stability-map benchmark: autobal against NumPy on the same problem and the same outputs, in
paired, interleaved runs.

The problem: the 12-state linearised model of paper 000, eq (6) (docs/notes/model.md section 1), balls
free, over an N x N grid of z_A in [-2, 2] and Omega in [0.05, 4.5] (the layout of paper 003,
Fig. 5a), with C_Sigma = 0.75, rho_s = 0.4, l_L = 0.8, dA = 0.1, m = 0.05, D_A = 0.5,
h_x = 0.05, h_s = 0.1.

Outputs compared, each timed from the parameters (NumPy's assembly of the matrices included,
vectorised over the whole grid, single-threaded BLAS):
  margin  = max Re lambda at every point.
            NumPy: numpy.linalg.eigvals on the stacked 12x12 state matrices (LAPACK dgeev);
            autobal: its map (continuation of the rightmost root of the characteristic
            polynomial in Omega, certified by a Routh count, QR where it cannot certify).
  verdict = stable or not at every point.
            NumPy, two ways: from eigvals (as above), and the Routh-Hurwitz test vectorised over
            the stack (Hessenberg reduction with pivoting, characteristic polynomial, Routh
            array: the same per-point algorithm autobal used before); the faster counts.
            autobal: its map (Routh-Hurwitz on the exact polynomial coefficients, every change
            of verdict confirmed by the direct test).
  boundary = the stability boundary of the plane, traced as curves by autobal (Hopf and fold
            conditions, pseudo-arclength continuation, every point located to ~1e-10),
            compared with what an N x N grid costs (autobal's maps, autobal's QR per point,
            NumPy's eigvals).
  For reference, autobal's per-point paths (QR per point; direct Routh-Hurwitz per point).

Each repetition runs NumPy's margin, autobal (one process: all its variants), NumPy's
verdict, in that order; ratios are formed within a repetition and reported as median and
min-max over repetitions. Outputs are checked: margins to autobal's certified bound
1e-10 (1 + |lambda|) + 1e-12 (lambda the rightmost eigenvalue), verdicts equal everywhere away
from the boundary (|max Re lambda| > 1e-6).

Each repetition also runs the command a user runs, `autobal map --quantity margin` and
`--quantity verdict` on the same grid (one thread; CSV, SVG and PNG written), as whole
processes: wall and CPU time (getrusage of the child), against NumPy's CPU time.

Load average before and after, CPU beside wall, LOADED rule: bench/measure.py.

Usage: python3 bench/stability_map.py [N] [REPEATS] [--allow-loaded] [--json FILE]   (default 400 5)
"""
import csv
import json
import os
import statistics
import subprocess
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import measure  # noqa: E402

OPTS = measure.strip_args(sys.argv)  # --allow-loaded, --json FILE; the positional arguments remain
N = int(sys.argv[1]) if len(sys.argv) > 1 else 400
REPEATS = int(sys.argv[2]) if len(sys.argv) > 2 else 5
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

C_SIGMA, RHO, L_LEFT, DA, MBAR, D_A, HX, HS = 0.75, 0.4, 0.8, 0.1, 0.05, 0.5, 0.05, 0.1


def assemble(z, w):
    """State matrices A (k, 12, 12) for arrays z, w of length k, from eq (6)."""
    k = z.size
    p2 = (L_LEFT**2 + (1 - L_LEFT) ** 2) / (2 * RHO**2)
    c = (2 * L_LEFT - 1) / (2 * RHO)
    ha, hya = HX * p2, HX * c
    E = np.eye(2)
    Ec = np.array([[0.0, -1.0], [1.0, 0.0]])
    EA = np.array([[-1.0, 0.0], [0.0, 1.0]])
    dA = np.diag([1 - D_A, 1 + D_A])
    W = w[:, None, None]
    Z = z[:, None, None]
    one = np.ones((k, 1, 1))
    M = np.zeros((k, 6, 6))
    G = np.zeros((k, 6, 6))
    K = np.zeros((k, 6, 6))

    def put(X, i, j, B):
        X[:, 2 * i:2 * i + 2, 2 * j:2 * j + 2] = B

    Kwc = -W * hya * E + c * Ec * one
    put(M, 0, 0, E * one)
    put(M, 1, 1, (E + DA * EA) * one)
    put(M, 0, 2, E * one)
    put(M, 1, 2, Z * Ec)
    put(M, 2, 0, 0.5 * MBAR * dA * one)
    put(M, 2, 1, -0.5 * MBAR * Z * (dA @ Ec))
    put(M, 2, 2, E * one)
    put(G, 0, 0, HX * E + 2 * W * Ec)
    put(G, 0, 1, hya * Ec * one)
    put(G, 1, 0, -hya * Ec * one)
    put(G, 1, 1, ha * E + W * (2 - C_SIGMA) * Ec)
    put(G, 0, 2, 2 * W * Ec)
    put(G, 1, 2, Z * (Ec @ (2 * Ec)) * W)
    put(G, 2, 0, 0.5 * MBAR * (dA @ (2 * Ec)) * W)
    put(G, 2, 1, -0.5 * MBAR * Z * (dA @ Ec @ (2 * Ec)) * W)
    put(G, 2, 2, HS * E * one)
    put(K, 0, 0, (1 - W**2) * E + W * HX * Ec)
    put(K, 0, 1, Kwc)
    put(K, 1, 0, -Kwc)
    put(K, 1, 1, (p2 - W**2 * (1 - C_SIGMA)) * E + DA * W**2 * EA + W * ha * Ec)
    put(K, 0, 2, -(W**2) * E)
    put(K, 1, 2, -Z * (W**2) * Ec)
    put(K, 2, 0, -0.5 * MBAR * (W**2) * dA)
    put(K, 2, 1, 0.5 * MBAR * Z * (W**2) * (dA @ Ec))
    X = np.linalg.solve(M, np.concatenate([K, G], axis=2))
    A = np.zeros((k, 12, 12))
    A[:, :6, 6:] = np.eye(6)
    A[:, 6:, :] = -X
    return A


def routh_hurwitz_vectorised(A):
    """Stable (all Re lambda < 0) for each matrix of the stack: Hessenberg reduction by
    elimination with partial pivoting, the characteristic polynomial by the recurrence on the
    leading minors, and the Routh array, each step vectorised over the stack."""
    A = A.copy()
    k, n, _ = A.shape
    idx = np.arange(k)
    for m in range(1, n - 1):
        piv = m + np.argmax(np.abs(A[:, m:, m - 1]), axis=1)
        row = A[idx, m, :].copy()
        A[idx, m, :] = A[idx, piv, :]
        A[idx, piv, :] = row
        col = A[idx, :, m].copy()
        A[idx, :, m] = A[idx, :, piv]
        A[idx, :, piv] = col
        x = A[:, m, m - 1]
        safe = x != 0.0
        y = np.where(safe[:, None], A[:, m + 1:, m - 1] / np.where(safe, x, 1.0)[:, None], 0.0)
        A[:, m + 1:, :] -= y[:, :, None] * A[:, m, None, :]
        A[:, :, m] += np.einsum("kij,kj->ki", A[:, :, m + 1:], y)
    # p[j] = characteristic polynomial of the leading j x j block, ascending powers
    p = [np.zeros((k, n + 1)) for _ in range(n + 1)]
    p[0][:, 0] = 1.0
    for j in range(1, n + 1):
        hjj = A[:, j - 1, j - 1][:, None]
        pj = np.zeros((k, n + 1))
        pj[:, 1:] = p[j - 1][:, :-1]
        pj -= hjj * p[j - 1]
        beta = np.ones(k)
        for i in range(j - 1, 0, -1):
            beta = beta * A[:, i, i - 1]
            pj -= (A[:, i - 1, j - 1] * beta)[:, None] * p[i - 1]
        p[j] = pj
    c = p[n][:, ::-1]  # descending: c[:, 0] = 1
    stable = np.all(c > 0.0, axis=1)
    r0 = c[:, 0::2].copy()
    r1 = np.zeros_like(r0)
    r1[:, : c[:, 1::2].shape[1]] = c[:, 1::2]
    for _ in range(1, n):
        stable &= r1[:, 0] > 0.0
        q = r0[:, 0] / np.where(r1[:, 0] != 0.0, r1[:, 0], 1.0)
        nxt = np.zeros_like(r0)
        nxt[:, :-1] = r0[:, 1:] - q[:, None] * r1[:, 1:]
        r0, r1 = r1, nxt
    stable &= r1[:, 0] > 0.0
    return stable


def numpy_margin(zs, ws):
    Wg, Zg = np.meshgrid(ws, zs, indexing="ij")  # row j = speed, column i = z_A
    t0, c0 = time.perf_counter(), time.process_time()
    A = assemble(Zg.ravel(), Wg.ravel())
    ev = np.linalg.eigvals(A)
    alpha = ev.real.max(axis=1)
    CPU["numpy_margin"].append(time.process_time() - c0)
    wall = time.perf_counter() - t0
    # untimed: |λ| of the rightmost eigenvalue, for autobal's certified bound (below)
    modulus = np.abs(ev[np.arange(len(ev)), ev.real.argmax(axis=1)])
    return wall, alpha, modulus


def numpy_verdict(zs, ws):
    Wg, Zg = np.meshgrid(ws, zs, indexing="ij")
    t0, c0 = time.perf_counter(), time.process_time()
    A = assemble(Zg.ravel(), Wg.ravel())
    stable = routh_hurwitz_vectorised(A)
    CPU["numpy_verdict"].append(time.process_time() - c0)
    return time.perf_counter() - t0, stable


CONFIG = os.path.join(os.path.dirname(os.path.abspath(__file__)), "stability_map.toml")
CPU = {"numpy_margin": [], "numpy_verdict": [], "autobal_example": [], "command_margin": [], "command_verdict": []}
WALL = {"command_margin": [], "command_verdict": []}


def spread(xs):
    return {"median": statistics.median(xs), "min": min(xs), "max": max(xs)}


def main():
    sess = measure.Session("stability_map", allow_loaded=OPTS.allow_loaded)
    cli = os.path.join(ROOT, "target", "release", "autobal")
    tmp = os.path.join(ROOT, "target", "bench_map_cmd")
    zs = np.linspace(-2.0, 2.0, N)
    ws = np.linspace(0.05, 4.5, N)
    k = N * N
    out = os.path.join(ROOT, "target", "bench_map.bin")
    subprocess.run(["cargo", "build", "--quiet", "--release", "--example", "bench_map", "-p", "autobal"], cwd=ROOT, check=True)
    exe = os.path.join(ROOT, "target", "release", "examples", "bench_map")
    runs = []
    for r in range(REPEATS):
        t_np_margin, alpha_np, modulus_np = numpy_margin(zs, ws)
        c0 = measure.children_cpu()
        res = subprocess.run([exe, str(N), str(N), out], cwd=ROOT, check=True, capture_output=True, text=True)
        CPU["autobal_example"].append(measure.children_cpu() - c0)
        if os.path.exists(cli):
            for q in ("margin", "verdict"):
                # the same rotor as NumPy's and the example's (bench/stability_map.toml)
                w, c = measure.run_cmd([cli, "map", "--config", CONFIG, "--threads", "1", "--quantity", q, "--x", f"dimensionless.z_a=-2:2:{N}",
                                        "--y", f"omega=0.05:4.5:{N}", "--out", f"{tmp}_{q}"])
                WALL[f"command_{q}"].append(w)
                CPU[f"command_{q}"].append(c)
        rs = json.loads(res.stdout.strip().splitlines()[-1])
        t_np_verdict, stable_np_rh = numpy_verdict(zs, ws)
        runs.append((t_np_margin, t_np_verdict, rs))
        print(f"repetition {r + 1}/{REPEATS}: numpy margin {t_np_margin:.2f} s, numpy RH verdict {t_np_verdict:.2f} s, "
              f"autobal margin {rs['margin_s']:.3f} s, verdict {rs['verdict_s']:.3f} s", file=sys.stderr)
    raw = open(out, "rb").read()
    alpha_rs = np.frombuffer(raw[: 8 * k], dtype="<f8")
    verdict_rs = np.frombuffer(raw[8 * k:], dtype=np.uint8).astype(bool)
    tol = 1e-11  # autobal::spatial::stability::STABILITY_TOLERANCE; balls free: stable iff max Re < -tol
    away = np.abs(alpha_np) > 1e-6
    stable_np = alpha_np < -tol
    checks = {
        "points_away_from_boundary": int(away.sum()),
        "verdict_mismatches_away_from_boundary": int(np.sum((verdict_rs != stable_np) & away)),
        "numpy_rh_verdict_mismatches_away_from_boundary": int(np.sum((stable_np_rh != stable_np) & away)),
        "margin_verdict_mismatches_away_from_boundary": int(np.sum(((alpha_rs < -tol) != stable_np) & away)),
        "max_abs_margin_difference": float(np.max(np.abs(alpha_rs - alpha_np))),
        # autobal certifies the abscissa to ACCEPT (1 + |λ|) + GAP = 1e-10 (1 + |λ|) + 1e-12
        # (linalg::charpoly::AbscissaTracker); NumPy's own error is ~1e-15 |λ|: the largest
        # difference over that bound must stay below 1
        "max_margin_difference_over_certified_bound": float(np.max(np.abs(alpha_rs - alpha_np) / (1e-10 * (1.0 + modulus_np) + 1e-12))),
        "stable_fraction": float(stable_np.mean()),
    }
    if os.path.exists(cli):
        # the command's own CSV: the same map (rows by speed, z_A fastest, as NumPy's layout)
        with open(f"{tmp}_margin.csv") as f:
            alpha_cmd = np.array([float(r["max_real_part"]) for r in csv.DictReader(f)])
        checks["command_max_margin_difference_over_certified_bound"] = float(
            np.max(np.abs(alpha_cmd - alpha_np) / (1e-10 * (1.0 + modulus_np) + 1e-12)))
    us = lambda s: 1e6 * s / k  # noqa: E731
    report = {
        "grid": f"{N} x {N}",
        "repeats": REPEATS,
        "us_per_point": {
            "numpy_eigvals_with_assembly": spread([us(t[0]) for t in runs]),
            "numpy_routh_hurwitz_vectorised_with_assembly": spread([us(t[1]) for t in runs]),
            "autobal_margin_map": spread([t[2]["margin_us_per_point"] for t in runs]),
            "autobal_verdict_map": spread([t[2]["verdict_us_per_point"] for t in runs]),
            "autobal_margin_qr_per_point": spread([t[2]["margin_qr_us_per_point"] for t in runs]),
            "autobal_verdict_direct_per_point": spread([t[2]["verdict_direct_us_per_point"] for t in runs]),
        },
        "boundary_ms": spread([1e3 * t[2]["boundary_s"] for t in runs]),
        "boundary_evaluations": runs[-1][2]["boundary_evaluations"],
        "boundary_points": runs[-1][2]["boundary_points"],
        "ratios_paired": {
            "margin: numpy eigvals / autobal map": spread([t[0] / t[2]["margin_s"] for t in runs]),
            "verdict: numpy eigvals / autobal map": spread([t[0] / t[2]["verdict_s"] for t in runs]),
            "verdict: numpy best (min of eigvals, vectorised RH) / autobal map": spread([min(t[0], t[1]) / t[2]["verdict_s"] for t in runs]),
            "margin: autobal QR per point / autobal map": spread([t[2]["margin_qr_s"] / t[2]["margin_s"] for t in runs]),
            "boundary: autobal margin map (N x N) / traced curves": spread([t[2]["margin_s"] / t[2]["boundary_s"] for t in runs]),
            "boundary: autobal verdict map (N x N) / traced curves": spread([t[2]["verdict_s"] / t[2]["boundary_s"] for t in runs]),
            "boundary: autobal QR per point (N x N) / traced curves": spread([t[2]["margin_qr_s"] / t[2]["boundary_s"] for t in runs]),
            "boundary: numpy eigvals (N x N) / traced curves": spread([t[0] / t[2]["boundary_s"] for t in runs]),
        },
        "autobal_map_points_by_continuation": runs[-1][2]["margin_continued"],
        "autobal_map_qr_fallbacks": runs[-1][2]["margin_direct"],
        "autobal_verdict_confirmations": runs[-1][2]["verdict_confirmations"],
        "checks": checks,
        "cpu_s": {k: spread(v) for k, v in CPU.items() if v},
        "commands_wall_s": {k: spread(v) for k, v in WALL.items() if v},
    }
    if CPU["command_margin"]:
        # whole commands (process CPU) against NumPy's CPU, pair by pair
        report["ratios_cpu_paired"] = {
            "margin: numpy eigvals CPU / autobal map --quantity margin process CPU": spread([a / b for a, b in zip(CPU["numpy_margin"], CPU["command_margin"])]),
            "verdict: numpy eigvals CPU / autobal map --quantity verdict process CPU": spread([a / b for a, b in zip(CPU["numpy_margin"], CPU["command_verdict"])]),
        }
    ok = sess.finish(report)
    print(json.dumps(report, indent=2))
    measure.write_table(OPTS.json, report, ok)
    if (checks["verdict_mismatches_away_from_boundary"] or checks["margin_verdict_mismatches_away_from_boundary"]
            or checks["numpy_rh_verdict_mismatches_away_from_boundary"] or checks["max_margin_difference_over_certified_bound"] > 1.0
            or checks.get("command_max_margin_difference_over_certified_bound", 0.0) > 1.0):
        sys.exit("autobal and NumPy disagree")


if __name__ == "__main__":
    main()
