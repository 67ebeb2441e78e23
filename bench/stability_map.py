#!/usr/bin/env python3
"""Stability-map benchmark: autobal against NumPy on the same problem, in one run.

The problem: the 12-state linearised model of paper 000, eq (6) (docs/model.md section 1), balls
free, over a 400 x 400 grid of z_A in [-2, 2] and Omega in [0.05, 4.5] (the layout of paper 003,
Fig. 5a), with C_Sigma = 0.75, rho_s = 0.4, l_L = 0.8, dA = 0.1, m = 0.05, D_A = 0.5,
h_x = 0.05, h_s = 0.1.

NumPy side: the matrices are assembled here, independently of autobal, straight from the
equations; the timed part is numpy.linalg.eigvals on the stacked 12x12 state matrices (the
fastest vectorised way a Python user has), single-threaded. autobal side: the example
`bench_map` (its timed part is the per-point work only, also single-threaded). Then the
verdicts are compared on every point away from the boundary (|max Re lambda| > 1e-6), and the
margins everywhere.

Usage: python3 bench/stability_map.py [N]      (N x N grid, default 400)
"""
import json
import os
import subprocess
import sys
import time

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
import numpy as np  # noqa: E402

N = int(sys.argv[1]) if len(sys.argv) > 1 else 400
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


def main():
    zs = np.linspace(-2.0, 2.0, N)
    ws = np.linspace(0.05, 4.5, N)
    Wg, Zg = np.meshgrid(ws, zs, indexing="ij")  # row j = speed, column i = z_A
    t0 = time.perf_counter()
    A = assemble(Zg.ravel(), Wg.ravel())
    t_assemble = time.perf_counter() - t0
    t0 = time.perf_counter()
    ev = np.linalg.eigvals(A)
    t_eig = time.perf_counter() - t0
    alpha_np = ev.real.max(axis=1)

    out = os.path.join(ROOT, "target", "bench_map.bin")
    cmd = ["cargo", "run", "--quiet", "--release", "--example", "bench_map", "-p", "autobal", "--", str(N), str(N), out]
    res = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True)
    timing = json.loads(res.stdout.strip().splitlines()[-1])
    raw = open(out, "rb").read()
    k = N * N
    alpha_rs = np.frombuffer(raw[: 8 * k], dtype="<f8")
    verdict_rs = np.frombuffer(raw[8 * k:], dtype=np.uint8).astype(bool)

    tol = 1e-11  # autobal::stability::STABILITY_TOLERANCE; balls free: stable iff max Re < -tol
    away = np.abs(alpha_np) > 1e-6
    stable_np = alpha_np < -tol
    mismatch_verdict = int(np.sum((verdict_rs != stable_np) & away))
    mismatch_margin_verdict = int(np.sum(((alpha_rs < -tol) != stable_np) & away))
    max_margin_diff = float(np.max(np.abs(alpha_rs - alpha_np)))
    np_us = 1e6 * t_eig / k
    report = {
        "grid": f"{N} x {N}",
        "points": k,
        "numpy_eigvals_us_per_point": np_us,
        "numpy_assembly_us_per_point": 1e6 * t_assemble / k,
        "autobal_verdict_us_per_point": timing["verdict_us_per_point"],
        "autobal_margin_us_per_point": timing["margin_us_per_point"],
        "ratio_verdict": np_us / timing["verdict_us_per_point"],
        "ratio_margin": np_us / timing["margin_us_per_point"],
        "points_away_from_boundary": int(away.sum()),
        "verdict_mismatches_away_from_boundary": mismatch_verdict,
        "margin_verdict_mismatches_away_from_boundary": mismatch_margin_verdict,
        "max_abs_margin_difference": max_margin_diff,
        "stable_fraction": float(stable_np.mean()),
    }
    print(json.dumps(report, indent=2))
    if mismatch_verdict or mismatch_margin_verdict or max_margin_diff > 1e-6:
        sys.exit("autobal and NumPy disagree")


if __name__ == "__main__":
    main()
