#!/usr/bin/env python3
"""Spatial-rotor benchmark: autobal against SciPy's solve_ivp (DOP853, Radau, LSODA).

The problem: the nonlinear spatial rotor of papers 000/003 (docs/notes/spatial.md) with paper 000's
base case (examples/spatial.toml: C̄Σ = 0.75, ρ̄s = 0.4, l̄_L = 0.8, z̄_A = 0.8, m̄0 = 0.025,
two balls m̄ = 0.05, R̄ = R̄0 = 2, h̄x = 0.05, h̄s = 0.1), in the papers' units (M_s = ω0 = ρ_s = 1):

  balance  constant speed Ω = 1.6 (exactly stable), balls started 57° off balance, τ ∈ [0, 1000],
           samples every Δτ = 1;
  runup    1000 revolutions at constant acceleration from rest to Ω = 4 through the critical
           speeds (0.843, 2.965) into 003's upper range, samples every Δτ = 1.

SciPy side: the same equations in the same coordinates (q = ξ, η, δ, θ, φ, ψ_1..N in axes
turning with the rotor, state (q, q̇) with the prescribed spin's φ̇ in it), written here with
NumPy from the d'Alembert form of docs/notes/spatial.md: the generalised inertia forces for all
unit accelerations at once (one array expression per body, balls vectorised), then
`np.linalg.solve` on the mass matrix; the same per-component absolute tolerances as autobal
(atol on displacements, atol/R on angles, times ω0 on rates) and `t_eval` at the sample
times. `--check` compares this right-hand side with the independent SymPy derivation of the
tests (crates/autobal/tests/spatial_lagrange.py) and the trajectory with autobal's.

autobal side: `autobal simulate` (release build) on the same config; its wall time as it
reports it (`wall_time_s`: the integration with the CSV written row by row), and the whole
process's wall time beside it.

Equal accuracy: every run is measured against a reference (autobal at rtol 1e-12) on the
sampled whirl radius at the balancer plane (max error over all samples / peak). autobal runs at
rtol 1e-8; each SciPy method gets the loosest rtol of 1e-6 … 1e-11 whose error is no larger
than autobal's (its cheapest run at least as accurate). Then paired, interleaved runs (autobal,
SciPy, autobal, SciPy …): per pair the ratio of wall times; median and min-max.

Usage:
  python3 bench/spatial.py                     # both cases, DOP853 + Radau + LSODA (minutes)
  python3 bench/spatial.py --case runup --pairs 5 --methods DOP853
  python3 bench/spatial.py --check             # equations vs SymPy, short trajectory vs autobal
"""
import argparse
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from scipy.integrate import solve_ivp

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import measure  # noqa: E402
CONFIG = os.path.join(ROOT, "examples", "spatial.toml")
EXE = None

CASES = {
    # name: (--set overrides of examples/spatial.toml, description, speeds compared)
    "balance": (["drive.t_end=1000"], "constant speed Ω = 1.6, τ ∈ [0, 1000], balls 57° off balance", np.inf),
    "runup": (
        ['drive.kind="acceleration"', "drive.omega0=0", f"drive.b={16.0 / (4000.0 * np.pi)!r}", f"drive.t_end={4000.0 * np.pi / 4.0!r}"],
        "1000 revolutions from rest to Ω = 4 at constant acceleration (b = 1.27e-3, τ ∈ [0, 3141.6])",
        # past Ω ≈ 2.2 the balls leave balance and slip round the race near the split angular
        # critical speeds: there two autobal references (rtol 1e-11 and 1e-12) already differ
        # by O(1), so accuracy is measured on Ω ≤ 2 (the first critical speed and the
        # balancing range); the whole run is timed
        2.0,
    ),
}


# ---------------------------------------------------------------- the rotor from autobal's JSON
class Rotor:
    """The parameters autobal used (its JSON summary's `rotor`), positions relative to O."""

    def __init__(self, r):
        planes = r["planes"]
        unb = r["unbalances"]
        mr = r["rotor"]["mass"]
        m_tot = mr + sum(u["mass"] for u in unb) + sum(p["n"] * p["ball_mass"] for p in planes)
        z_ref = (mr * r["rotor"]["z"] + sum(u["mass"] * u["z"] for u in unb) + sum(p["n"] * p["ball_mass"] * p["z"] for p in planes)) / m_tot
        self.gravity = np.array(r["gravity"], dtype=float)
        self.spin_drag = r["spin_drag"]
        # carrier: rigid rotor + unbalance masses; mass, first moment S and tensor J_b about O (body axes)
        zg = r["rotor"]["z"] - z_ref
        kap, bet = r["rotor"]["axis_tilt"], r["rotor"]["axis_tilt_angle"]
        a, c = r["rotor"]["equatorial_moment"], r["rotor"]["polar_moment"]
        e = np.array([np.sin(kap) * np.cos(bet), np.sin(kap) * np.sin(bet), np.cos(kap)])
        rho_g = np.array([0.0, 0.0, zg])
        self.mc = mr
        self.S = mr * rho_g
        self.Jb = a * np.eye(3) + (c - a) * np.outer(e, e) + mr * (zg * zg * np.eye(3) - np.outer(rho_g, rho_g))
        for u in unb:
            rho = np.array([u["radius"] * np.cos(u["angle"]), u["radius"] * np.sin(u["angle"]), u["z"] - z_ref])
            self.mc += u["mass"]
            self.S = self.S + u["mass"] * rho
            self.Jb = self.Jb + u["mass"] * (rho @ rho * np.eye(3) - np.outer(rho, rho))
        self.bm = np.array([p["ball_mass"] for p in planes for _ in range(p["n"])])
        self.bR = np.array([p["race_radius"] for p in planes for _ in range(p["n"])])
        self.bz = np.array([p["z"] - z_ref for p in planes for _ in range(p["n"])])
        self.bh = np.array([p["drag"] for p in planes for _ in range(p["n"])])
        self.sz = np.array([s["z"] - z_ref for s in r["supports"]])
        self.k = np.array([s["stiffness"] for s in r["supports"]])
        self.c = np.array([s["damping"] for s in r["supports"]])
        self.n = len(self.bm)
        self.nq = 5 + self.n
        self.wn = np.sqrt(self.k[:, 0].sum() / m_tot)
        radii = [p["race_radius"] for p in planes] + [u["radius"] for u in unb]
        self.length = max(radii) if max(radii, default=0.0) > 0 else np.sqrt(a / m_tot)
        self.z_plane = (planes[0]["z"] if planes else unb[0]["z"]) - z_ref
        # [rotor coordinate rows | ball rows] x [unit accelerations | no acceleration]
        self.unit = np.hstack([np.eye(self.nq), np.zeros((self.nq, 1))])
        self.lock_tilt = r["lock_tilt"]
        self.z_ref = z_ref
        self.raw = r


def cross(a, b):
    """a × b over the last axis, broadcast over the others (np.cross is several times slower
    on small arrays: it moves axes around on every call)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def rot_t(de, th):
    """R_t = R_x(δ) R_y(θ)."""
    cd, sd, ct, st = np.cos(de), np.sin(de), np.cos(th), np.sin(th)
    return np.array([[ct, 0.0, st], [sd * st, cd, -sd * ct], [-cd * st, sd, cd * ct]])


def make_rhs(rot, drive):
    """dy/dt of the state (q, q̇) for a drive ("speed", ω0), ("acceleration", ω0, b) or
    ("torque", ω0, M): Kane's form of docs/notes/spatial.md, vectorised over balls and over the
    unit accelerations that give the mass matrix's columns."""
    n, nq, unit = rot.n, rot.nq, rot.unit
    bm, bR, bz, bh = rot.bm, rot.bR, rot.bz, rot.bh
    kind = drive[0]
    free = [i for i in range(nq) if not (i == 4 and kind != "torque") and not (i in (2, 3) and rot.lock_tilt)]
    ex, ey, ez = np.eye(3)

    def rhs(t, y):
        q, qd = y[:nq], y[nq:]
        xi, eta, de, th, phi = q[:5]
        xid, etad, ded, thd = qd[:4]
        if kind == "torque":
            phid, phidd = qd[4], 0.0
        else:
            b = drive[2] if kind == "acceleration" else 0.0
            phid, phidd = drive[1] + b * t, b
        psi, psid = q[5:], qd[5:]
        cd, sd = np.cos(de), np.sin(de)
        Rt = rot_t(de, th)
        # partial velocities of O and partial angular velocities (rows: ξ η δ θ φ)
        V = np.array([ex, ey, np.zeros(3), np.zeros(3), [-eta, xi, 0.0]])
        G = np.array([np.zeros(3), np.zeros(3), ex, [0.0, cd, sd], ez])
        w = np.array([ded, thd * cd, phid + thd * sd])
        aO0 = np.array([-2 * phid * etad - phid**2 * xi, 2 * phid * xid - phid**2 * eta, 0.0])
        al0 = np.array([-phid * thd * cd, -thd * ded * sd + phid * ded, thd * ded * cd])
        # accelerations for each unit q̈ (columns 0..nq-1) and for q̈ = 0 (column nq)
        aO = unit[:5].T @ V
        al = unit[:5].T @ G
        aO[-1] += aO0
        al[-1] += al0
        s = Rt @ rot.S
        J = Rt @ rot.Jb @ Rt.T
        Fc = rot.mc * aO + cross(al, s)
        Fc[-1] += cross(w, cross(w, s))
        Tc = cross(s, aO) + al @ J.T
        Tc[-1] += cross(w, J @ w)
        # balls: r_j, t_j = ∂r_j/∂ψ_j, n_j = ∂²r_j/∂ψ_j² (F components)
        cp, sp = np.cos(psi), np.sin(psi)
        rb = np.stack([bR * cp, bR * sp, bz], axis=1) @ Rt.T
        tb = np.stack([-bR * sp, bR * cp, np.zeros(n)], axis=1) @ Rt.T
        nb = np.stack([-bR * cp, -bR * sp, np.zeros(n)], axis=1) @ Rt.T
        ab = aO[:, None, :] + cross(al[:, None, :], rb[None]) + unit[5:].T[:, :, None] * tb[None]
        ab[-1] += cross(w, cross(w, rb)) + 2 * psid[:, None] * cross(w, tb) + (psid**2)[:, None] * nb
        Fb = bm[None, :, None] * ab
        F = Fc + Fb.sum(axis=1)
        T = Tc + cross(rb[None], Fb).sum(axis=1)
        gen = np.empty((nq, nq + 1))
        gen[:5] = V @ F.T + G @ T.T
        gen[5:] = np.einsum("jk,cjk->jc", tb, Fb)
        # applied forces: supports (fixed-axes spring and damper on the shaft point), gravity,
        # ball drag, drive torque and spin drag
        cf, sf = np.cos(phi), np.sin(phi)
        Rz = np.array([[cf, -sf, 0.0], [sf, cf, 0.0], [0.0, 0.0, 1.0]])
        vO = np.array([xid - phid * eta, etad + phid * xi, 0.0])
        u = np.array([xi, eta, 0.0])
        rs = np.outer(rot.sz, Rt[:, 2])
        X = (u + rs) @ Rz.T
        Xd = (vO + cross(w, rs)) @ Rz.T
        fs = -(rot.k * X[:, :2] + rot.c * Xd[:, :2])
        fs = np.hstack([fs, np.zeros((len(rot.sz), 1))]) @ Rz  # to F components
        g = Rz.T @ rot.gravity
        Fe = fs.sum(axis=0) + (rot.mc + bm.sum()) * g
        Te = cross(rs, fs).sum(axis=0) + cross(s, rot.mc * g) + cross(rb, bm[:, None] * g).sum(axis=0)
        Q = np.empty(nq)
        Q[:5] = V @ Fe + G @ Te
        Q[5:] = tb @ g * bm - bh * bR**2 * psid
        if kind == "torque":
            Q[4] += drive[2] - rot.spin_drag * phid
        rhs_ = Q - gen[:, nq]
        M = gen[:, :nq]
        acc = np.zeros(nq)
        acc[4] = phidd
        rhs_ -= M[:, 4] * acc[4] if kind != "torque" else 0.0
        acc[free] = np.linalg.solve(M[np.ix_(free, free)], rhs_[free])
        dy = np.empty(2 * nq)
        dy[:nq] = qd
        dy[4] = phid
        dy[nq:] = acc
        return dy

    return rhs


def plane_radius(rot, y):
    """Whirl radius of the shaft point in the (first) balancer plane, for states in columns."""
    de, th = y[2], y[3]
    z = rot.z_plane
    return np.hypot(y[0] + z * np.sin(th), y[1] - z * np.sin(de) * np.cos(th))


# ---------------------------------------------------------------- runs
def autobal_exe():
    exe = EXE or os.path.join(ROOT, "target", "release", "autobal")
    if EXE is None:
        subprocess.run(["cargo", "build", "--release", "--quiet", "-p", "autobal-cli"], cwd=ROOT, check=True)
    return exe


def run_autobal(sets, rtol, atol):
    with tempfile.TemporaryDirectory() as d:
        out = os.path.join(d, "sim.csv")
        cmd = [autobal_exe(), "simulate", "--config", CONFIG, "--format", "json", "--out", out,
               "--set", f"integration.rtol={rtol!r}", "--set", f"integration.atol={atol!r}"]
        for s in sets:
            cmd += ["--set", s]
        t0 = time.perf_counter()
        res = subprocess.run(cmd, check=True, capture_output=True, text=True)
        process = time.perf_counter() - t0
        summary = json.loads(res.stdout)
        data = np.loadtxt(out, delimiter=",", skiprows=1)
    summary["process_wall_s"] = process
    return summary, data


def drive_of(summary):
    d = summary["drive"]
    kind = d.get("kind")
    if kind == "speed":
        return ("speed", d["omega0"])
    if kind == "acceleration":
        return ("acceleration", d["omega0"], d["b"])
    if kind == "torque" and d.get("t_off") is None:
        return ("torque", d["omega0"], d["torque"])
    sys.exit(f"bench/spatial.py: drive {d} not written here")


def initial_state(rot, summary):
    ini = summary["initial"]
    drive = drive_of(summary)
    y0 = np.zeros(2 * rot.nq)
    # at τ = 0 the turning frame is the fixed one: F components equal fixed ones
    y0[0:2] = ini["position"]
    y0[2:4] = ini["tilt"]
    y0[5:rot.nq] = ini["psi"]
    phid = drive[1]
    y0[rot.nq:rot.nq + 2] = np.array(ini["velocity"]) - phid * np.array([-ini["position"][1], ini["position"][0]])
    if any(ini["tilt"]) or any(ini["tilt_rate"]):
        sys.exit("bench/spatial.py: initial tilts are not written here")
    y0[rot.nq + 4] = phid
    y0[rot.nq + 5:] = ini["psi_rate"]
    return y0


def tolerances(rot, rtol, atol):
    nq = rot.nq
    base = np.array([atol, atol] + [atol / max(rot.length, atol)] * (nq - 2))
    return np.concatenate([base, base * rot.wn])


def run_scipy(rot, summary, method, rtol, atol):
    t_end = summary["t_end"]
    dt = summary["integration"]["dt"]
    t_eval = np.arange(0.0, t_end + 0.5 * dt, dt)
    t_eval = t_eval[t_eval <= t_end * (1 + 1e-12)]
    rhs = make_rhs(rot, drive_of(summary))
    y0 = initial_state(rot, summary)
    t0 = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, rtol=rtol, atol=tolerances(rot, rtol, atol), t_eval=t_eval)
    wall = time.perf_counter() - t0
    if not sol.success:
        raise RuntimeError(f"SciPy {method} failed: {sol.message}")
    return wall, sol


def err(amp, ref, mask=None):
    """Largest error over the compared samples, relative to the reference's peak there."""
    n = min(len(amp), len(ref))
    m = np.ones(n, dtype=bool) if mask is None else mask[:n]
    return float(np.max(np.abs(amp[:n][m] - ref[:n][m])) / np.max(np.abs(ref[:n][m])))


# ---------------------------------------------------------------- checks
def check_equations(rot, seed=3):
    """Our NumPy right-hand side against the tests' independent SymPy derivation (positions in
    fixed axes, Lagrange's equations by symbolic differentiation) at random states far from
    balance, under the three kinds of drive; returns the largest relative difference of q̈."""
    path = os.path.join(ROOT, "crates", "autobal", "tests", "spatial_lagrange.py")
    spec = importlib.util.spec_from_file_location("spatial_lagrange", path)
    lag = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(lag)
    raw = rot.raw
    f = lag.derive(len(raw["unbalances"]), rot.n, len(rot.sz))
    r = raw["rotor"]
    params = [r["mass"], r["equatorial_moment"], r["polar_moment"], r["z"] - rot.z_ref, r["axis_tilt"], r["axis_tilt_angle"], *rot.gravity, rot.spin_drag]
    for u in raw["unbalances"]:
        params += [u["mass"], u["radius"], u["angle"], u["z"] - rot.z_ref]
    for j in range(rot.n):
        params += [rot.bm[j], rot.bR[j], rot.bz[j], rot.bh[j]]
    for i in range(len(rot.sz)):
        params += [rot.sz[i], rot.k[i, 0], rot.k[i, 1], rot.c[i, 0], rot.c[i, 1]]
    rng = np.random.default_rng(seed)
    worst = 0.0
    for drive in [("acceleration", 1.3, 0.4), ("torque", 0.7, 0.05), ("speed", 1.6)]:
        for _ in range(5):
            y = np.concatenate([rng.uniform(-0.3, 0.3, 5), rng.uniform(0, 2 * np.pi, rot.n), rng.uniform(-0.5, 0.5, rot.nq)])
            t = rng.uniform(0, 3)
            ours = make_rhs(rot, drive)(t, y)[rot.nq:]
            q, qd = y[:rot.nq], y[rot.nq:].copy()
            if drive[0] != "torque":
                qd[4] = drive[1] + (drive[2] if drive[0] == "acceleration" else 0.0) * t
            M, rest = f(list(q), list(qd), params)
            M = np.array(M, dtype=float)
            rhs = -np.array(rest, dtype=float).ravel()
            theirs = np.zeros(rot.nq)
            if drive[0] == "torque":
                rhs[4] += drive[2]
                theirs = np.linalg.solve(M, rhs)
            else:
                theirs[4] = drive[2] if drive[0] == "acceleration" else 0.0
                rhs -= M[:, 4] * theirs[4]
                free = [i for i in range(rot.nq) if i != 4]
                theirs[free] = np.linalg.solve(M[np.ix_(free, free)], rhs[free])
            scale = max(1.0, float(np.max(np.abs(theirs))))
            worst = max(worst, float(np.max(np.abs(ours - theirs))) / scale)
    return worst


# ---------------------------------------------------------------- the benchmark
def calibrate(rot, summary, method, target, ref_amp, mask, atol_per_rtol, loosest):
    """The loosest rtol (`loosest` … 1e-11) at which SciPy's error is no larger than `target`."""
    tried = []
    for rtol in [r for r in [1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11] if r <= loosest]:
        wall, sol = run_scipy(rot, summary, method, rtol, rtol * atol_per_rtol)
        e = err(plane_radius(rot, sol.y), ref_amp, mask)
        tried.append({"rtol": rtol, "error": e, "wall_s": wall, "rhs_evaluations": int(sol.nfev)})
        print(f"  {method} rtol {rtol:g}: error {e:.2e} (autobal {target:.2e}), {wall:.2f} s, {sol.nfev} rhs", file=sys.stderr)
        if e <= target:
            return rtol, tried
    return None, tried


def bench_case(name, a):
    sets, what, compared = CASES[name]
    if a.t_end is not None:
        sets = sets + [f"drive.t_end={a.t_end!r}"]
        what += f" (here τ ∈ [0, {a.t_end:g}])"
    print(f"case {name}: {what}", file=sys.stderr)
    ref, ref_data = run_autobal(sets, 1e-12, 1e-14)
    ref_amp = ref_data[:, 8]
    mask = ref_data[:, 1] <= compared
    rot = Rotor(ref["rotor"])
    ab, ab_data = run_autobal(sets, a.rtol, a.atol)
    e_ab = err(ab_data[:, 8], ref_amp, mask)
    out = {"case": name, "problem": what, "samples": int(len(ref_amp)), "samples_compared": int(mask.sum()),
           "autobal": {"rtol": a.rtol, "atol": a.atol, "error": e_ab, "steps": ab["steps"], "rhs_evaluations": ab["rhs_evaluations"],
                       "wall_s": ab["wall_time_s"], "balanced": ab["balanced"], "peak_amplitude": ab["peak_amplitude"], "omega_at_peak": ab["omega_at_peak"]},
           "methods": {}}
    for method in a.methods:
        rtol, tried = calibrate(rot, ref, method, e_ab, ref_amp, mask, a.atol / a.rtol, a.loosest)
        entry = {"calibration": tried}
        if rtol is None:
            entry["note"] = "no rtol down to 1e-11 reached autobal's error"
            out["methods"][method] = entry
            continue
        pairs = a.pairs if method == "DOP853" else a.pairs_implicit
        if name == "runup":
            pairs = min(pairs, a.pairs_runup)
        ratios, t_ab, t_sp, t_proc = [], [], [], []
        for _ in range(pairs):
            s_ab, _ = run_autobal(sets, a.rtol, a.atol)
            w_sp, sol = run_scipy(rot, ref, method, rtol, rtol * a.atol / a.rtol)
            t_ab.append(s_ab["wall_time_s"])
            t_proc.append(s_ab["process_wall_s"])
            t_sp.append(w_sp)
            ratios.append(w_sp / s_ab["wall_time_s"])
        entry.update({
            "rtol": rtol, "error": err(plane_radius(rot, sol.y), ref_amp, mask), "rhs_evaluations": int(sol.nfev),
            "pairs": pairs, "scipy_wall_s_median": float(np.median(t_sp)), "autobal_wall_s_median": float(np.median(t_ab)),
            "autobal_process_wall_s_median": float(np.median(t_proc)),
            "ratio_median": float(np.median(ratios)), "ratio_min": float(np.min(ratios)), "ratio_max": float(np.max(ratios)),
            "ratio_vs_process_median": float(np.median(t_sp) / np.median(t_proc)),
        })
        print(f"  {method}: ratio median {entry['ratio_median']:.0f} (min {entry['ratio_min']:.0f}, max {entry['ratio_max']:.0f})", file=sys.stderr)
        out["methods"][method] = entry
    return out


def check(a):
    """Equations against SymPy; a short run against autobal (exit 1 on disagreement)."""
    sets = CASES["runup"][0][:3] + ["drive.t_end=60"]
    s, data = run_autobal(sets, 1e-10, 1e-12)
    rot = Rotor(s["rotor"])
    worst = check_equations(rot)
    _, sol = run_scipy(rot, s, "DOP853", 1e-10, 1e-12)
    e = err(plane_radius(rot, sol.y), data[:, 8])
    print(json.dumps({"numpy_vs_sympy_max_rel": worst, "scipy_vs_autobal_trajectory_rel": e}, indent=2))
    if worst > 1e-9 or e > 1e-6:
        sys.exit(f"disagreement: equations {worst:.2e} (limit 1e-9), trajectory {e:.2e} (limit 1e-6)")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", choices=[*CASES, "all"], default="all")
    ap.add_argument("--methods", nargs="+", default=["DOP853", "Radau", "LSODA"])
    ap.add_argument("--pairs", type=int, default=5, help="paired runs for DOP853")
    ap.add_argument("--pairs-implicit", type=int, default=3, help="paired runs for Radau and LSODA")
    ap.add_argument("--pairs-runup", type=int, default=3, help="at most this many pairs on the run-up (SciPy takes minutes)")
    ap.add_argument("--loosest", type=float, default=1e-6, help="the loosest SciPy rtol tried")
    ap.add_argument("--runup-methods", nargs="+", help="methods on the run-up (default: --methods)")
    ap.add_argument("--rtol", type=float, default=1e-8, help="autobal's rtol")
    ap.add_argument("--atol", type=float, default=1e-10, help="autobal's atol (SciPy's scaled with its rtol)")
    ap.add_argument("--t-end", type=float, help="shorter runs (e.g. for Radau, which takes long): drive.t_end of the case")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--exe", help="the autobal binary (default: target/release/autobal, built first)")
    measure.add_args(ap)
    a = ap.parse_args()
    global EXE
    EXE = a.exe
    if a.check:
        check(a)
        return
    sess = measure.Session("spatial", allow_loaded=a.allow_loaded)
    names = list(CASES) if a.case == "all" else [a.case]
    results = []
    for n in names:
        methods = a.methods
        if n == "runup" and a.runup_methods:
            a.methods = a.runup_methods
        results.append(bench_case(n, a))
        a.methods = methods
        print(json.dumps(results[-1]), file=sys.stderr)
    report = {"cases": results}
    ok = sess.finish(report)
    print(json.dumps(report, indent=2))
    measure.write_table(a.json, report, ok)


if __name__ == "__main__":
    main()
