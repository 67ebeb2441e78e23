#!/usr/bin/env python3
"""The spatial 1000-revolution run-up (bench/spatial.py's `runup` case) against a compiled peer:
numbalsoda's DOP853 with a numba-compiled right-hand side, at equal accuracy, the compile time
reported apart; beside it the `autobal simulate` command (whole process, CSV + 4 SVG).

The equations are bench/spatial.py's `make_rhs` (Kane's form of docs/notes/spatial.md, checked there
against the tests' independent SymPy derivation to 7e-16) written out in scalar loops for numba
(no allocation but the mass matrix's elimination): the same coordinates (q = ξ, η, δ, θ, φ,
ψ_1..N in axes turning with the rotor; state (q, q̇)), the same per-component absolute
tolerances (numbalsoda takes one scalar atol: the state is integrated scaled by them, z = y / w,
the same error test), `t_eval` at autobal's samples. `--check` compares this right-hand side
with `make_rhs` at random states.

Accuracy as bench/spatial.py measures it: the whirl radius at the balancer plane against autobal
at rtol 1e-12, largest error over the samples with Ω ≤ 2 (past Ω ≈ 2.2 no two integrations
agree), relative to the peak there; autobal at rtol 1e-8, atol 1e-10; the peer at the loosest
of 1e-6 … 1e-11 (atol = rtol / 100, as autobal's ratio) that reaches autobal's error.

Needs the bench environment (.venv-bench, bench/requirements-bench.txt).

    .venv-bench/bin/python bench/peers_spatial.py [--repeats 3] [--json FILE] [--allow-loaded]
    .venv-bench/bin/python bench/peers_spatial.py --check
"""
import argparse
import json
import os
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import measure  # noqa: E402
import spatial as S  # noqa: E402

LADDER = [1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 1e-10, 1e-11]


def numba_rhs(rot, drive):
    """An njit f(t, y, dy) equal to spatial.make_rhs(rot, drive) for an acceleration or speed drive."""
    import numba as nb

    kind = drive[0]
    if kind == "torque":
        sys.exit("peers_spatial.py: torque drives are not written here")
    w0 = float(drive[1])
    b = float(drive[2]) if kind == "acceleration" else 0.0
    n, nq = rot.n, rot.nq
    mc, Sv, Jb = float(rot.mc), rot.S.astype(float).copy(), rot.Jb.astype(float).copy()
    bm, bR, bz, bh = (np.ascontiguousarray(x, dtype=float) for x in (rot.bm, rot.bR, rot.bz, rot.bh))
    sz, K, Cd = np.ascontiguousarray(rot.sz, dtype=float), np.ascontiguousarray(rot.k, dtype=float), np.ascontiguousarray(rot.c, dtype=float)
    grav = rot.gravity.astype(float).copy()
    ns = len(sz)
    free = np.array([i for i in range(nq) if i != 4 and not (i in (2, 3) and rot.lock_tilt)], dtype=np.int64)
    nf = len(free)
    mtot = mc + float(bm.sum())

    @nb.njit(cache=False, fastmath=False)
    def cross(a0, a1, a2, b0, b1, b2):
        return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0

    @nb.njit(cache=False, fastmath=False)
    def f(t, y, dy):
        xi, eta, de, th, phi = y[0], y[1], y[2], y[3], y[4]
        xid, etad, ded, thd = y[nq], y[nq + 1], y[nq + 2], y[nq + 3]
        phid = w0 + b * t
        phidd = b
        cd, sd, ct, st = np.cos(de), np.sin(de), np.cos(th), np.sin(th)
        Rt = np.empty((3, 3))
        Rt[0, 0], Rt[0, 1], Rt[0, 2] = ct, 0.0, st
        Rt[1, 0], Rt[1, 1], Rt[1, 2] = sd * st, cd, -sd * ct
        Rt[2, 0], Rt[2, 1], Rt[2, 2] = -cd * st, sd, cd * ct
        V = np.zeros((5, 3))
        V[0, 0] = 1.0
        V[1, 1] = 1.0
        V[4, 0], V[4, 1] = -eta, xi
        G = np.zeros((5, 3))
        G[2, 0] = 1.0
        G[3, 1], G[3, 2] = cd, sd
        G[4, 2] = 1.0
        w = np.array([ded, thd * cd, phid + thd * sd])
        # accelerations of O and angular accelerations per unit q̈ (rows 0..nq-1) and at q̈ = 0 (row nq)
        aO = np.zeros((nq + 1, 3))
        al = np.zeros((nq + 1, 3))
        for c in range(5):
            for k in range(3):
                aO[c, k] = V[c, k]
                al[c, k] = G[c, k]
        aO[nq, 0] += -2 * phid * etad - phid ** 2 * xi
        aO[nq, 1] += 2 * phid * xid - phid ** 2 * eta
        al[nq, 0] += -phid * thd * cd
        al[nq, 1] += -thd * ded * sd + phid * ded
        al[nq, 2] += thd * ded * cd
        s = Rt @ Sv
        J = Rt @ Jb @ Rt.T
        Jw = J @ w
        F = np.zeros((nq + 1, 3))
        T = np.zeros((nq + 1, 3))
        for c in range(nq + 1):
            x0, x1, x2 = cross(al[c, 0], al[c, 1], al[c, 2], s[0], s[1], s[2])
            F[c, 0] = mc * aO[c, 0] + x0
            F[c, 1] = mc * aO[c, 1] + x1
            F[c, 2] = mc * aO[c, 2] + x2
            y0, y1, y2 = cross(s[0], s[1], s[2], aO[c, 0], aO[c, 1], aO[c, 2])
            T[c, 0] = y0 + (al[c, 0] * J[0, 0] + al[c, 1] * J[0, 1] + al[c, 2] * J[0, 2])
            T[c, 1] = y1 + (al[c, 0] * J[1, 0] + al[c, 1] * J[1, 1] + al[c, 2] * J[1, 2])
            T[c, 2] = y2 + (al[c, 0] * J[2, 0] + al[c, 1] * J[2, 1] + al[c, 2] * J[2, 2])
        ws0, ws1, ws2 = cross(w[0], w[1], w[2], s[0], s[1], s[2])
        a0, a1, a2 = cross(w[0], w[1], w[2], ws0, ws1, ws2)
        F[nq, 0] += a0
        F[nq, 1] += a1
        F[nq, 2] += a2
        a0, a1, a2 = cross(w[0], w[1], w[2], Jw[0], Jw[1], Jw[2])
        T[nq, 0] += a0
        T[nq, 1] += a1
        T[nq, 2] += a2
        gen = np.zeros((nq, nq + 1))
        # balls
        rb = np.empty((n, 3))
        tb = np.empty((n, 3))
        for j in range(n):
            cp, sp = np.cos(y[5 + j]), np.sin(y[5 + j])
            pr = (bR[j] * cp, bR[j] * sp, bz[j])
            pt = (-bR[j] * sp, bR[j] * cp, 0.0)
            pn = (-bR[j] * cp, -bR[j] * sp, 0.0)
            nbv = np.empty(3)
            for k in range(3):
                rb[j, k] = Rt[k, 0] * pr[0] + Rt[k, 1] * pr[1] + Rt[k, 2] * pr[2]
                tb[j, k] = Rt[k, 0] * pt[0] + Rt[k, 1] * pt[1] + Rt[k, 2] * pt[2]
                nbv[k] = Rt[k, 0] * pn[0] + Rt[k, 1] * pn[1] + Rt[k, 2] * pn[2]
            psid = y[nq + 5 + j]
            for c in range(nq + 1):
                x0, x1, x2 = cross(al[c, 0], al[c, 1], al[c, 2], rb[j, 0], rb[j, 1], rb[j, 2])
                ab0, ab1, ab2 = aO[c, 0] + x0, aO[c, 1] + x1, aO[c, 2] + x2
                if c == 5 + j:
                    ab0 += tb[j, 0]
                    ab1 += tb[j, 1]
                    ab2 += tb[j, 2]
                if c == nq:
                    wr0, wr1, wr2 = cross(w[0], w[1], w[2], rb[j, 0], rb[j, 1], rb[j, 2])
                    c0, c1, c2 = cross(w[0], w[1], w[2], wr0, wr1, wr2)
                    d0, d1, d2 = cross(w[0], w[1], w[2], tb[j, 0], tb[j, 1], tb[j, 2])
                    ab0 += c0 + 2 * psid * d0 + psid ** 2 * nbv[0]
                    ab1 += c1 + 2 * psid * d1 + psid ** 2 * nbv[1]
                    ab2 += c2 + 2 * psid * d2 + psid ** 2 * nbv[2]
                fb0, fb1, fb2 = bm[j] * ab0, bm[j] * ab1, bm[j] * ab2
                F[c, 0] += fb0
                F[c, 1] += fb1
                F[c, 2] += fb2
                m0, m1, m2 = cross(rb[j, 0], rb[j, 1], rb[j, 2], fb0, fb1, fb2)
                T[c, 0] += m0
                T[c, 1] += m1
                T[c, 2] += m2
                gen[5 + j, c] = tb[j, 0] * fb0 + tb[j, 1] * fb1 + tb[j, 2] * fb2
        for i in range(5):
            for c in range(nq + 1):
                gen[i, c] = (V[i, 0] * F[c, 0] + V[i, 1] * F[c, 1] + V[i, 2] * F[c, 2]) + (G[i, 0] * T[c, 0] + G[i, 1] * T[c, 1] + G[i, 2] * T[c, 2])
        # applied forces: supports, gravity, ball drag
        cf, sf = np.cos(phi), np.sin(phi)
        vO0, vO1 = xid - phid * eta, etad + phid * xi
        Fe = np.zeros(3)
        Te = np.zeros(3)
        g0, g1, g2 = cf * grav[0] + sf * grav[1], -sf * grav[0] + cf * grav[1], grav[2]
        for i in range(ns):
            rs0, rs1, rs2 = sz[i] * Rt[0, 2], sz[i] * Rt[1, 2], sz[i] * Rt[2, 2]
            u0, u1 = xi + rs0, eta + rs1
            X0, X1 = cf * u0 - sf * u1, sf * u0 + cf * u1
            wr0, wr1, wr2 = cross(w[0], w[1], w[2], rs0, rs1, rs2)
            v0, v1 = vO0 + wr0, vO1 + wr1
            Xd0, Xd1 = cf * v0 - sf * v1, sf * v0 + cf * v1
            f0 = -(K[i, 0] * X0 + Cd[i, 0] * Xd0)
            f1 = -(K[i, 1] * X1 + Cd[i, 1] * Xd1)
            # back to F components: [f0, f1, 0] @ Rz
            h0, h1 = cf * f0 + sf * f1, -sf * f0 + cf * f1
            Fe[0] += h0
            Fe[1] += h1
            m0, m1, m2 = cross(rs0, rs1, rs2, h0, h1, 0.0)
            Te[0] += m0
            Te[1] += m1
            Te[2] += m2
        Fe[0] += mtot * g0
        Fe[1] += mtot * g1
        Fe[2] += mtot * g2
        m0, m1, m2 = cross(s[0], s[1], s[2], mc * g0, mc * g1, mc * g2)
        Te[0] += m0
        Te[1] += m1
        Te[2] += m2
        for j in range(n):
            m0, m1, m2 = cross(rb[j, 0], rb[j, 1], rb[j, 2], bm[j] * g0, bm[j] * g1, bm[j] * g2)
            Te[0] += m0
            Te[1] += m1
            Te[2] += m2
        r = np.empty(nq)
        for i in range(5):
            r[i] = (V[i, 0] * Fe[0] + V[i, 1] * Fe[1] + V[i, 2] * Fe[2]) + (G[i, 0] * Te[0] + G[i, 1] * Te[1] + G[i, 2] * Te[2]) - gen[i, nq]
        for j in range(n):
            r[5 + j] = (tb[j, 0] * g0 + tb[j, 1] * g1 + tb[j, 2] * g2) * bm[j] - bh[j] * bR[j] ** 2 * y[nq + 5 + j] - gen[5 + j, nq]
        for i in range(nq):
            r[i] -= gen[i, 4] * phidd
        # the free accelerations: Gaussian elimination with partial pivoting on M[free, free]
        A = np.empty((nf, nf + 1))
        for a in range(nf):
            for c in range(nf):
                A[a, c] = gen[free[a], free[c]]
            A[a, nf] = r[free[a]]
        for c in range(nf):
            p = c
            for a in range(c + 1, nf):
                if abs(A[a, c]) > abs(A[p, c]):
                    p = a
            if p != c:
                for k in range(c, nf + 1):
                    A[c, k], A[p, k] = A[p, k], A[c, k]
            for a in range(c + 1, nf):
                m = A[a, c] / A[c, c]
                for k in range(c, nf + 1):
                    A[a, k] -= m * A[c, k]
        acc = np.zeros(nq)
        acc[4] = phidd
        for c in range(nf - 1, -1, -1):
            v = A[c, nf]
            for k in range(c + 1, nf):
                v -= A[c, k] * acc[free[k]]
            acc[free[c]] = v / A[c, c]
        for i in range(nq):
            dy[i] = y[nq + i]
            dy[nq + i] = acc[i]
        dy[4] = phid

    return f


def setup(sets):
    """autobal's reference run (rtol 1e-12): its summary (the rotor's parameters) and samples."""
    return S.run_autobal(sets, 1e-12, 1e-14)


def peer(rot, summary, atol_ratio):
    """numbalsoda DOP853 on z = y / w; returns (run(rtol) -> plane radius samples or None, rhs_py)."""
    import numba as nb
    from numba import cfunc
    from numbalsoda import dop853, lsoda_sig

    drive = S.drive_of(summary)
    w = S.tolerances(rot, 1e-8, 1e-8 * atol_ratio) / (1e-8 * atol_ratio)
    W = np.ascontiguousarray(w)
    dim = 2 * rot.nq
    f = numba_rhs(rot, drive)

    @cfunc(lsoda_sig)
    def rhs(t, u, du, p):
        z = nb.carray(u, (dim,))
        out = nb.carray(du, (dim,))
        y = np.empty(dim)
        for i in range(dim):
            y[i] = z[i] * W[i]
        f(t, y, out)
        for i in range(dim):
            out[i] /= W[i]

    t_end = summary["t_end"]
    dt = summary["integration"]["dt"]
    te = np.arange(0.0, t_end + 0.5 * dt, dt)
    te = te[te <= t_end * (1 + 1e-12)]
    z0 = S.initial_state(rot, summary) / w

    def run(rtol):
        usol, ok = dop853(rhs.address, z0, te, rtol=rtol, atol=rtol * atol_ratio, mxstep=100_000_000)
        if not ok:
            return None
        return S.plane_radius(rot, (usol * w).T)

    def rhs_py(t, y):
        out = np.empty(dim)
        f(t, np.ascontiguousarray(y, dtype=float), out)
        return out

    return run, rhs_py


def check(sets):
    summary, _ = S.run_autobal(sets[:3] + ["drive.t_end=60"], 1e-10, 1e-12)
    rot = S.Rotor(summary["rotor"])
    drive = S.drive_of(summary)
    ref = S.make_rhs(rot, drive)
    f = numba_rhs(rot, drive)
    rng = np.random.default_rng(5)
    worst = 0.0
    for _ in range(30):
        y = np.concatenate([rng.uniform(-0.3, 0.3, 5), rng.uniform(0, 2 * np.pi, rot.n), rng.uniform(-0.5, 0.5, rot.nq)])
        t = rng.uniform(0, 100)
        a = ref(t, y)
        out = np.empty(2 * rot.nq)
        f(t, y, out)
        worst = max(worst, float(np.max(np.abs(a - out)) / max(1.0, np.max(np.abs(a)))))
    print(json.dumps({"numba_vs_make_rhs_max_rel": worst}))
    if worst > 1e-12:
        sys.exit(f"right-hand sides disagree: {worst:.2e}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--rtol", type=float, default=1e-8)
    ap.add_argument("--atol", type=float, default=1e-10)
    ap.add_argument("--cap", type=float, default=60.0, help="stop the ladder after a run longer than this (s)")
    ap.add_argument("--exe", default=os.path.join(S.ROOT, "target", "release", "autobal"))
    ap.add_argument("--check", action="store_true")
    measure.add_args(ap)
    a = ap.parse_args()
    S.EXE = a.exe
    sets, what, compared = S.CASES["runup"]
    if a.check:
        check(sets)
        return
    sess = measure.Session("peers_spatial", allow_loaded=a.allow_loaded)
    ref, ref_data = S.run_autobal(sets, 1e-12, 1e-14)
    ref_amp = ref_data[:, 8]
    mask = ref_data[:, 1] <= compared
    rot = S.Rotor(ref["rotor"])
    ab, ab_data = S.run_autobal(sets, a.rtol, a.atol)
    target = S.err(ab_data[:, 8], ref_amp, mask)
    report = {"problem": what, "samples": int(len(ref_amp)), "target_error": target,
              "autobal": {"steps": ab["steps"], "rhs_evaluations": ab["rhs_evaluations"], "error": target}}
    cmd = [a.exe, "simulate", "--config", S.CONFIG, "--set", f"integration.rtol={a.rtol!r}", "--set", f"integration.atol={a.atol!r}"]
    for s in sets:
        cmd += ["--set", s]
    runs = []
    with tempfile.TemporaryDirectory() as d:
        for _ in range(a.repeats):
            runs.append(measure.run_cmd(cmd + ["--out", os.path.join(d, "sim.csv")], cwd=d))
    report["autobal"]["command_wall_s"] = measure.median_spread([r[0] for r in runs])
    report["autobal"]["command_cpu_s"] = measure.median_spread([r[1] for r in runs])
    print(f"autobal: error {target:.3g}, command {report['autobal']['command_cpu_s']['median'] * 1e3:.0f} ms CPU", file=sys.stderr)
    (setup_wall, _), (run, _) = measure.cpu_of(lambda: peer(rot, ref, a.atol / a.rtol))
    ladder, chosen, first = [], None, True
    for rtol in LADDER:
        (wall, cpu), amp = measure.cpu_of(lambda: run(rtol))
        e = None if amp is None else S.err(amp, ref_amp, mask)
        ladder.append({"rtol": rtol, "wall_s": wall, "cpu_s": cpu, "error": e, **({"includes_compile": True} if first else {})})
        first = False
        print(f"numbalsoda DOP853 rtol {rtol:g}: error {e}, {cpu:.2f} s CPU", file=sys.stderr)
        if e is not None and e <= target:
            chosen = rtol
            break
        if wall > a.cap:
            break
    reached = chosen is not None
    rtol = chosen if reached else ladder[-1]["rtol"]
    timed = [measure.cpu_of(lambda: run(rtol))[0] for _ in range(a.repeats)]
    cpu = measure.median_spread([x[1] for x in timed])
    wall = measure.median_spread([x[0] for x in timed])
    report["numbalsoda DOP853"] = {"rtol": rtol, "reached_target": reached, "ladder": ladder, "setup_s": setup_wall,
                                   "wall_s": wall, "cpu_s": cpu,
                                   "cpu_vs_command": cpu["median"] / report["autobal"]["command_cpu_s"]["median"],
                                   "wall_vs_command": wall["median"] / report["autobal"]["command_wall_s"]["median"]}
    print(f"numbalsoda DOP853: rtol {rtol:g}{'' if reached else ' (target not reached)'}, CPU {cpu['median'] * 1e3:.0f} ms = "
          f"{report['numbalsoda DOP853']['cpu_vs_command']:.2f}x the command's", file=sys.stderr)
    ok = sess.finish(report)
    print(json.dumps(report, indent=2))
    measure.write_table(a.json, report, ok)


if __name__ == "__main__":
    main()
