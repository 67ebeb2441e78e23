#!/usr/bin/env python3
"""Paper 004's passage against compiled peers: numbalsoda (DOP853, LSODA; right-hand side a
numba @cfunc), diffrax (JAX, x64: Tsit5, Dopri8, Kvaerno5), diffsol (Rust, through pydiffsol:
Tsit45, BDF, ESDIRK34; the right-hand side in DiffSL, compiled by LLVM) and SUNDIALS CVODE
(scikit-sundae: Adams and BDF; a numba-compiled right-hand side called through Python), at
equal accuracy, with the
compile/JIT time reported apart; beside them the `autobal simulate` command (whole process:
CSV + 4 SVG) and the library in-process (examples/passage.rs).

The problem is bench/passage.py's: m1 = 1, m2 = 0.2, m3 = 0.03 kg, two balls, b = 2.5 1/s² from
rest to 600 rad/s (240 s), the radius of C sampled every 0.05 s (4 801 samples), in rotor axes
with the balls eliminated in closed form (the same equations, the same axes, the same state
as autobal's and bench/passage.py's `rotor_axes`, which `--check` compares with). Absolute
tolerances per component as autobal's (atol on displacements, atol/r on angles, times sqrt(k/m0)
on rates): numbalsoda takes one scalar atol, so every peer integrates the state scaled by those
weights (z = y / w, atol_z = atol), which is the same error test.

Accuracy: each peer's tolerance is the loosest of the ladder 1e-6 … 1e-12 (atol = rtol / 10)
whose error before the peak (max |radius - reference| / peak, reference: autobal at rtol 1e-12)
is no larger than autobal's at its defaults (rtol 1e-8). A peer that never reaches it is timed
at its tightest rung and marked "not reached" (its ratio is then a lower bound).

Timing: each peer's run at the chosen tolerance `--repeats` times after the compile/JIT run, wall
and CPU time (this process), median and min-max; autobal's command and example likewise as
child processes (CPU from getrusage). Load average printed before and after (bench/measure.py);
a LOADED run writes no --json table unless --allow-loaded.

Needs the bench environment (not CI's): python3 -m venv .venv-bench &&
.venv-bench/bin/pip install -r bench/requirements-bench.txt (numbalsoda builds from source with
CMake and gfortran: apt-get install -y gfortran cmake).

The slowest passage of paper 004 (Fig. 4c): `--b 0.04` (from rest to 600 rad/s: 15 000 s; the
samples every `--dt`, default 5 s there, 3 001 samples, as bench/passage.py --balls times it).
autobal's command runs with `--set drive.b=… drive.t_end=… integration.dt=…` (the same samples;
`dt` is also its implicit steps' resolution, 4 dt).

Usage:
  .venv-bench/bin/python bench/peers_passage.py [--repeats 3] [--peers numbalsoda,diffrax] [--json FILE]
  .venv-bench/bin/python bench/peers_passage.py --b 0.04 --methods DOP853,LSODA,Tsit5 --repeats 3
  .venv-bench/bin/python bench/peers_passage.py --check    # right-hand sides vs bench/passage.py
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import measure  # noqa: E402
import passage as P  # noqa: E402  (the problem's constants, the reference rhs, autobal runners)

ROOT = os.path.dirname(HERE)
B, OMEGA0, T_END, DT = 2.5, 0.0, 240.0, 0.05
LADDER = [1e-6, 3e-7, 1e-7, 3e-8, 1e-8, 3e-9, 1e-9, 3e-10, 1e-10, 1e-11, 1e-12]
# constants of the closed form, as bench/passage.py defines them
M0, M1, M3, R, K, C, C_PSI, S1 = P.M0, P.M1, P.M3, P.R, P.K, P.C, P.C_PSI, P.S1
ME, EX, EY, M3R = P.ME, P.EX, P.EY, P.M3R


def weights(atol_unit=1.0):
    """Per-component scale w: autobal's atol vector for atol = 1 (the state is integrated as y / w)."""
    return P.atol_vector(atol_unit) / atol_unit


def set_problem(b, dt):
    """The passage at acceleration `b` from rest to 600 rad/s, samples every `dt` (module
    constants, read by the peers' right-hand sides when they are compiled)."""
    global B, T_END, DT
    B, T_END, DT = b, 600.0 / b, dt


def command_sets():
    """`--set` arguments that make `autobal simulate`'s default config this problem."""
    out = []
    for kv in (f"drive.b={B!r}", f"drive.omega0={OMEGA0!r}", f"drive.t_end={T_END!r}", f"integration.dt={DT!r}"):
        out += ["--set", kv]
    return out


def t_eval():
    t = np.arange(0.0, T_END + 0.5 * DT, DT)
    return t[t <= T_END * (1 + 1e-12)]


def errors(amp, amp_ref, pre, peak):
    n = min(len(amp), len(amp_ref))
    amp, ref, pre = amp[:n], amp_ref[:n], pre[:n]
    return {"before_peak": float(np.max(np.abs(amp[pre] - ref[pre])) / peak), "peak": float(abs(amp.max() - peak) / peak)}


def silence_fd1():
    """Context: numbalsoda's DOP853 prints a stiffness notice from Fortran/C on fd 1."""
    class S:
        def __enter__(self):
            sys.stdout.flush()
            self.saved, self.null = os.dup(1), os.open(os.devnull, os.O_WRONLY)
            os.dup2(self.null, 1)

        def __exit__(self, *a):
            os.dup2(self.saved, 1)
            os.close(self.null)
            os.close(self.saved)
    return S()


# ---------------------------------------------------------------------------------------------
# numbalsoda: the closed form of bench/passage.py's rotor_axes, scalar, compiled by numba

def numba_rhs(W):
    """The closed form as a numba-compiled `f(t, z, out)` on the scaled state z = y / W."""
    import numba as nb

    @nb.njit(cache=False)
    def f(t, y, out):
        ww = OMEGA0 + B * t
        wd = B
        ux, uy, p1, p2, vx, vy, d1, d2 = (y[0] * W[0], y[1] * W[1], y[2] * W[2], y[3] * W[3], y[4] * W[4], y[5] * W[5], y[6] * W[6], y[7] * W[7])
        c1, s1, c2, s2 = math.cos(p1), math.sin(p1), math.cos(p2), math.sin(p2)
        px, py = ux + EX, uy + EY
        Sx = M0 * ux + M1 * S1 + ME * EX + M3R * (c1 + c2)
        Sy = M0 * uy + ME * EY + M3R * (s1 + s2)
        Bx = M0 * vx - M3R * (s1 * d1 + s2 * d2)
        By = M0 * vy + M3R * (c1 * d1 + c2 * d2)
        Kx = -M3R * (c1 * d1 * d1 + c2 * d2 * d2) - wd * Sy - 2 * ww * By - ww * ww * Sx
        Ky = -M3R * (s1 * d1 * d1 + s2 * d2 * d2) + wd * Sx + 2 * ww * Bx - ww * ww * Sy
        Fx = -K * ux - C * (vx - ww * uy)
        Fy = -K * uy - C * (vy + ww * ux)
        g1 = -C_PSI * d1 / M3R - wd * (c1 * px + s1 * py + R) - 2 * ww * (c1 * vx + s1 * vy) + ww * ww * (-s1 * px + c1 * py)
        g2 = -C_PSI * d2 / M3R - wd * (c2 * px + s2 * py + R) - 2 * ww * (c2 * vx + s2 * vy) + ww * ww * (-s2 * px + c2 * py)
        a11 = M0 - M3 * (s1 * s1 + s2 * s2)
        a22 = M0 - M3 * (c1 * c1 + c2 * c2)
        a12 = M3 * (s1 * c1 + s2 * c2)
        rx = Fx - Kx + M3 * (s1 * g1 + s2 * g2)
        ry = Fy - Ky - M3 * (c1 * g1 + c2 * g2)
        det = a11 * a22 - a12 * a12
        ax = (a22 * rx - a12 * ry) / det
        ay = (a11 * ry - a12 * rx) / det
        out[0] = vx / W[0]
        out[1] = vy / W[1]
        out[2] = d1 / W[2]
        out[3] = d2 / W[3]
        out[4] = ax / W[4]
        out[5] = ay / W[5]
        out[6] = (g1 + s1 * ax - c1 * ay) / R / W[6]
        out[7] = (g2 + s2 * ax - c2 * ay) / R / W[7]

    return f


def unscaled(f, w):
    """`f(t, z, out)` on the scaled state z = y / w as a right-hand side of y (for `--check`)."""
    def rhs_py(t, y):
        out = np.zeros(8)
        f(t, y / w, out)
        return out * w

    return rhs_py


def numbalsoda_peer():
    import numba as nb
    from numba import cfunc
    from numbalsoda import dop853, lsoda, lsoda_sig

    w = weights()
    W = tuple(float(x) for x in w)
    f = numba_rhs(W)

    @cfunc(lsoda_sig)
    def rhs(t, u, du, p):
        y = nb.carray(u, (8,))
        out = nb.carray(du, (8,))
        f(t, y, out)

    ptr = rhs.address
    z0 = P.initial_state() / w
    te = t_eval()

    def run(method, rtol):
        solver = dop853 if method == "DOP853" else lsoda
        with silence_fd1():
            # mxstep bounds the steps of the whole run (default 10 000: DOP853 needs ~40 000 here)
            usol, ok = solver(ptr, z0, te, rtol=rtol, atol=rtol / 10, mxstep=100_000_000)
        if not ok:
            return None
        y = usol * w
        return np.hypot(y[:, 0], y[:, 1])

    return {"DOP853": lambda rtol: run("DOP853", rtol), "LSODA": lambda rtol: run("LSODA", rtol)}, unscaled(f, w)


# ---------------------------------------------------------------------------------------------
# diffrax: the same closed form in jax.numpy, x64, tolerances traced (one compilation per method)

def diffrax_peer():
    import jax

    jax.config.update("jax_enable_x64", True)
    jax.config.update("jax_platforms", "cpu")
    import diffrax
    import jax.numpy as jnp

    w = jnp.asarray(weights())

    def f(t, z, args):
        y = z * w
        ww = OMEGA0 + B * t
        wd = B
        ux, uy, p1, p2, vx, vy, d1, d2 = (y[i] for i in range(8))
        c1, s1, c2, s2 = jnp.cos(p1), jnp.sin(p1), jnp.cos(p2), jnp.sin(p2)
        px, py = ux + EX, uy + EY
        Sx = M0 * ux + M1 * S1 + ME * EX + M3R * (c1 + c2)
        Sy = M0 * uy + ME * EY + M3R * (s1 + s2)
        Bx = M0 * vx - M3R * (s1 * d1 + s2 * d2)
        By = M0 * vy + M3R * (c1 * d1 + c2 * d2)
        Kx = -M3R * (c1 * d1 * d1 + c2 * d2 * d2) - wd * Sy - 2 * ww * By - ww * ww * Sx
        Ky = -M3R * (s1 * d1 * d1 + s2 * d2 * d2) + wd * Sx + 2 * ww * Bx - ww * ww * Sy
        Fx = -K * ux - C * (vx - ww * uy)
        Fy = -K * uy - C * (vy + ww * ux)
        g1 = -C_PSI * d1 / M3R - wd * (c1 * px + s1 * py + R) - 2 * ww * (c1 * vx + s1 * vy) + ww * ww * (-s1 * px + c1 * py)
        g2 = -C_PSI * d2 / M3R - wd * (c2 * px + s2 * py + R) - 2 * ww * (c2 * vx + s2 * vy) + ww * ww * (-s2 * px + c2 * py)
        a11 = M0 - M3 * (s1 * s1 + s2 * s2)
        a22 = M0 - M3 * (c1 * c1 + c2 * c2)
        a12 = M3 * (s1 * c1 + s2 * c2)
        rx = Fx - Kx + M3 * (s1 * g1 + s2 * g2)
        ry = Fy - Ky - M3 * (c1 * g1 + c2 * g2)
        det = a11 * a22 - a12 * a12
        ax = (a22 * rx - a12 * ry) / det
        ay = (a11 * ry - a12 * rx) / det
        dy = jnp.stack([vx, vy, d1, d2, ax, ay, (g1 + s1 * ax - c1 * ay) / R, (g2 + s2 * ax - c2 * ay) / R])
        return dy / w

    te = jnp.asarray(t_eval())
    z0 = jnp.asarray(P.initial_state()) / w
    term = diffrax.ODETerm(f)
    solvers = {"Tsit5": diffrax.Tsit5(), "Dopri8": diffrax.Dopri8(), "Kvaerno5": diffrax.Kvaerno5()}
    # 4 million steps for 240 s at b = 2.5; the slow passage needs proportionally more
    max_steps = int(4_000_000 * max(1.0, T_END / 240.0))
    compiled = {}

    def make(name):
        solver = solvers[name]

        @jax.jit
        def solve(rtol, atol):
            sol = diffrax.diffeqsolve(term, solver, t0=0.0, t1=T_END, dt0=1e-4, y0=z0, saveat=diffrax.SaveAt(ts=te),
                                      stepsize_controller=diffrax.PIDController(rtol=rtol, atol=atol), max_steps=max_steps,
                                      throw=False)
            return sol.ys, sol.result, sol.stats["num_steps"]

        return solve

    def run(name, rtol):
        if name not in compiled:
            compiled[name] = make(name)
        ys, res, steps = compiled[name](jnp.float64(rtol), jnp.float64(rtol / 10))
        ys = np.asarray(jax.block_until_ready(ys))
        if not bool(res == diffrax.RESULTS.successful):
            return None
        y = ys * np.asarray(w)
        return np.hypot(y[:, 0], y[:, 1])

    def rhs_py(t, y):
        return np.asarray(f(t, jnp.asarray(y) / w, None)) * np.asarray(w)

    return {n: (lambda rtol, n=n: run(n, rtol)) for n in solvers}, rhs_py


# ---------------------------------------------------------------------------------------------
# diffsol (Rust, pydiffsol): the same closed form in DiffSL, compiled by LLVM at construction

def diffsl_code():
    """The passage's closed form (numbalsoda_peer's `f`, line for line) in DiffSL: the state is
    z = y / w (diffsol takes one scalar atol), constants written out at full precision."""
    w = weights()
    z0 = P.initial_state() / w
    k = {"M0": M0, "M1": M1, "M3": M3, "R": R, "K": K, "C": C, "CPSI": C_PSI, "S1": S1, "ME": ME,
         "EX": EX, "EY": EY, "M3R": M3R, "OMEGA0": OMEGA0, "B": B}
    k.update({f"W{i}": float(w[i]) for i in range(8)})
    consts = "\n".join(f"{n} {{ {v!r} }}" for n, v in k.items())
    init = ", ".join(f"z{i} = {float(z0[i])!r}" for i in range(8))
    return f"""
in = [ ]
{consts}
u_i {{ {init}, }}
ww {{ OMEGA0 + B * t }}
ux {{ z0 * W0 }}
uy {{ z1 * W1 }}
p1 {{ z2 * W2 }}
p2 {{ z3 * W3 }}
vx {{ z4 * W4 }}
vy {{ z5 * W5 }}
d1 {{ z6 * W6 }}
d2 {{ z7 * W7 }}
c1 {{ cos(p1) }}
s1 {{ sin(p1) }}
c2 {{ cos(p2) }}
s2 {{ sin(p2) }}
px {{ ux + EX }}
py {{ uy + EY }}
sx {{ M0 * ux + M1 * S1 + ME * EX + M3R * (c1 + c2) }}
sy {{ M0 * uy + ME * EY + M3R * (s1 + s2) }}
bx {{ M0 * vx - M3R * (s1 * d1 + s2 * d2) }}
by {{ M0 * vy + M3R * (c1 * d1 + c2 * d2) }}
kx {{ -M3R * (c1 * d1 * d1 + c2 * d2 * d2) - B * sy - 2 * ww * by - ww * ww * sx }}
ky {{ -M3R * (s1 * d1 * d1 + s2 * d2 * d2) + B * sx + 2 * ww * bx - ww * ww * sy }}
fx {{ -K * ux - C * (vx - ww * uy) }}
fy {{ -K * uy - C * (vy + ww * ux) }}
g1 {{ -CPSI * d1 / M3R - B * (c1 * px + s1 * py + R) - 2 * ww * (c1 * vx + s1 * vy) + ww * ww * (-s1 * px + c1 * py) }}
g2 {{ -CPSI * d2 / M3R - B * (c2 * px + s2 * py + R) - 2 * ww * (c2 * vx + s2 * vy) + ww * ww * (-s2 * px + c2 * py) }}
a11 {{ M0 - M3 * (s1 * s1 + s2 * s2) }}
a22 {{ M0 - M3 * (c1 * c1 + c2 * c2) }}
a12 {{ M3 * (s1 * c1 + s2 * c2) }}
rx {{ fx - kx + M3 * (s1 * g1 + s2 * g2) }}
ry {{ fy - ky - M3 * (c1 * g1 + c2 * g2) }}
det {{ a11 * a22 - a12 * a12 }}
ax {{ (a22 * rx - a12 * ry) / det }}
ay {{ (a11 * ry - a12 * rx) / det }}
F_i {{
  vx / W0,
  vy / W1,
  d1 / W2,
  d2 / W3,
  ax / W4,
  ay / W5,
  (g1 + s1 * ax - c1 * ay) / R / W6,
  (g2 + s2 * ax - c2 * ay) / R / W7,
}}
out_i {{ ux, uy, }}
"""


def diffsol_peer():
    """pydiffsol (diffsol, Rust; the right-hand side JIT-compiled by LLVM from DiffSL): its
    explicit Tsit45 and its implicit BDF and ESDIRK34 (dense LU, Jacobian by the JIT's
    automatic differentiation); outputs at the samples by its dense output (`solve_dense`)."""
    import pydiffsol as ds

    code = diffsl_code()
    te = t_eval()
    methods = {"Tsit45": ds.tsit45, "BDF": ds.bdf, "ESDIRK34": ds.esdirk34}
    odes = {name: ds.Ode(code, ode_solver=m) for name, m in methods.items()}
    for name in ("BDF", "ESDIRK34"):
        # at its defaults (Jacobian refreshed every 20 steps, the right-hand side's every 50)
        # BDF stops at the resonance (t ~ 100-120 s: "Exceeded maximum number of nonlinear
        # solver failures"); refreshed at every step it runs (measured 2026-11-28). ESDIRK34
        # fails either way (reported as failed rungs).
        o = odes[name].options
        o.update_jacobian_after_steps, o.update_rhs_jacobian_after_steps, o.max_nonlinear_solver_iterations = 1, 1, 20
    none = np.array([], dtype=float)

    def run(name, rtol):
        ode = odes[name]
        ode.rtol, ode.atol = rtol, rtol / 10
        try:
            sol = ode.solve_dense(none, te)
        except Exception:  # a step-size failure is raised: the rung failed
            return None
        ys = np.asarray(sol.ys)
        if ys.shape[1] != len(te):
            return None
        return np.hypot(ys[0], ys[1])

    probe = ds.Ode(code, ode_solver=ds.tsit45)

    def rhs_py(t, y):
        return np.asarray(probe.rhs(none, float(t), y / weights())) * weights()

    return {n: (lambda rtol, n=n: run(n, rtol)) for n in methods}, rhs_py


# ---------------------------------------------------------------------------------------------
# SUNDIALS CVODE (scikit-sundae): Adams (non-stiff) and BDF, the right-hand side numba-compiled
# and called from CVODE through Python (the package takes a Python callable)

def sundials_peer():
    from sksundae.cvode import CVODE

    w = weights()
    rhs_nb = numba_rhs(tuple(float(x) for x in w))
    z0 = P.initial_state() / w
    te = t_eval()

    def rhsfn(t, y, yp):
        rhs_nb(t, y, yp)

    def run(method, rtol):
        solver = CVODE(rhsfn, method=method, rtol=rtol, atol=rtol / 10, max_num_steps=100_000_000)
        sol = solver.solve(te, z0)
        if not sol.success or sol.y.shape[0] != len(te):
            return None
        y = sol.y * w
        return np.hypot(y[:, 0], y[:, 1])

    return {"CVODE-Adams": lambda rtol: run("Adams", rtol), "CVODE-BDF": lambda rtol: run("BDF", rtol)}, unscaled(rhs_nb, w)


# ---------------------------------------------------------------------------------------------

PEERS = {"numbalsoda": numbalsoda_peer, "diffrax": diffrax_peer, "diffsol": diffsol_peer, "sundials": sundials_peer}


def check():
    """The peers' right-hand sides against bench/passage.py's rotor_axes at random states."""
    ref, _ = P.rotor_axes(OMEGA0, B)
    rng = np.random.default_rng(3)
    worst = {}
    for name, make in PEERS.items():
        try:
            _, rhs = make()
        except ImportError as e:
            worst[name] = f"not installed: {e}"
            continue
        err = 0.0
        for _ in range(20):
            y = rng.normal(size=8) * np.array([1e-3, 1e-3, 3, 3, 0.3, 0.3, 50, 50])
            t = rng.uniform(0, T_END)
            a, b = ref(t, y), rhs(t, y)
            err = max(err, float(np.max(np.abs(a - b)) / np.max(np.abs(a))))
        worst[name] = err
    print(json.dumps(worst, indent=2))
    bad = [k for k, v in worst.items() if not isinstance(v, str) and v > 1e-12]
    if bad:
        sys.exit(f"right-hand sides disagree: {bad}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peers", default="numbalsoda,diffrax,diffsol,sundials")
    ap.add_argument("--methods", default="", help="only these methods (comma-separated, e.g. DOP853,LSODA,Tsit5); default all")
    ap.add_argument("--b", type=float, default=2.5, help="acceleration (1/s^2), from rest to 600 rad/s (default 2.5; 0.04: the slowest passage)")
    ap.add_argument("--dt", type=float, default=None, help="sample interval (s); default 0.05 at b = 2.5, else (600/b)/3000")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--cap", type=float, default=30.0, help="stop a ladder after a run longer than this (s)")
    ap.add_argument("--exe", default=os.path.join(ROOT, "target", "release", "autobal"))
    ap.add_argument("--check", action="store_true")
    measure.add_args(ap)
    a = ap.parse_args()
    set_problem(a.b, a.dt if a.dt is not None else (0.05 if a.b == 2.5 else 600.0 / a.b / 3000.0))
    if a.check:
        check()
        return
    sess = measure.Session("peers_passage", allow_loaded=a.allow_loaded)
    te = t_eval()
    report = {"problem": f"paper 004 passage, b = {B} 1/s^2 from rest to 600 rad/s ({T_END:g} s), {len(te)} samples"}

    # reference and target (autobal at rtol 1e-12, and at its defaults)
    _, ref, amp_ref = P.run_autobal(OMEGA0, B, T_END, DT, 1e-12, 1e-14)
    peak = float(amp_ref.max())
    pre = te[:len(amp_ref)] <= ref["t_at_peak"]
    _, s_def, amp_def = P.run_autobal(OMEGA0, B, T_END, DT, 1e-8, 1e-9)
    target = errors(amp_def, amp_ref, pre, peak)["before_peak"]
    report["target_error_before_peak"] = target

    # autobal: the command (whole process) and the library (in-process wall of the example)
    cmd_runs, lib_runs = [], []
    with tempfile.TemporaryDirectory() as d:
        for _ in range(a.repeats):
            cmd_runs.append(measure.run_cmd([a.exe, "simulate", "--out", os.path.join(d, "sim.csv")] + command_sets(), cwd=d))
            c0 = measure.children_cpu()
            wall_in, s, _ = P.run_autobal(OMEGA0, B, T_END, DT, 1e-8, 1e-9, samples=False)
            lib_runs.append((wall_in[0], measure.children_cpu() - c0))
    report["autobal"] = {
        "rhs_evaluations": s_def["rhs_evaluations"], "steps": s_def["steps"], "error_before_peak": target,
        "command_wall_s": measure.median_spread([r[0] for r in cmd_runs]), "command_cpu_s": measure.median_spread([r[1] for r in cmd_runs]),
        "library_wall_s": measure.median_spread([r[0] for r in lib_runs]),
        "library_process_cpu_s": measure.median_spread([r[1] for r in lib_runs]),
    }
    cmd_wall = report["autobal"]["command_wall_s"]["median"]
    lib_wall = report["autobal"]["library_wall_s"]["median"]
    print(f"autobal: command {cmd_wall * 1e3:.1f} ms wall, library {lib_wall * 1e3:.1f} ms; target error {target:.2e}", file=sys.stderr)

    peers = {}
    for name in a.peers.split(","):
        try:
            t0 = time.perf_counter()
            methods, _ = PEERS[name]()
            setup = time.perf_counter() - t0
        except Exception as e:  # an install or build failure is a result: reported, not fatal
            peers[name] = {"error": f"{type(e).__name__}: {e}"}
            print(f"{name}: {e}", file=sys.stderr)
            continue
        for m, run in methods.items():
            if a.methods and m not in a.methods.split(","):
                continue
            key = f"{name} {m}"
            ladder, chosen, first = [], None, True
            for rtol in LADDER:
                (wall, cpu), amp = measure.cpu_of(lambda: run(rtol))
                entry = {"rtol": rtol, "wall_s": wall, "cpu_s": cpu}
                if first:
                    entry["includes_compile"] = True
                    first = False
                if amp is None:
                    entry["failed"] = True
                    ladder.append(entry)
                    if wall > a.cap:
                        break
                    continue
                entry["error_before_peak"] = errors(amp, amp_ref, pre, peak)["before_peak"]
                ladder.append(entry)
                if entry["error_before_peak"] <= target:
                    chosen = rtol
                    break
                if wall > a.cap:
                    break
            if not any("error_before_peak" in e for e in ladder):
                peers[key] = {"failed_at_every_rung": True, "ladder": ladder}
                print(f"{key}: failed at every rung of the ladder (no time: nothing to compare)", file=sys.stderr)
                continue
            reached = chosen is not None
            rtol = chosen if reached else max((e for e in ladder if "error_before_peak" in e), key=lambda e: -e["error_before_peak"], default={"rtol": LADDER[-1]})["rtol"]
            # compile/JIT: the first call at this tolerance minus a warm one
            runs = []
            for _ in range(a.repeats):
                (wall, cpu), amp = measure.cpu_of(lambda: run(rtol))
                runs.append((wall, cpu))
            wm = measure.median_spread([r[0] for r in runs])
            # JIT compilation (diffrax: at the first call, tolerances traced): the first call
            # minus a warm call at the same rung; numba compiles the @cfunc at setup
            (warm0, _), _ = measure.cpu_of(lambda: run(LADDER[0]))
            peers[key] = {"rtol": rtol, "reached_target": reached, "ladder": ladder,
                          "setup_s": setup, "compile_s": ladder[0]["wall_s"] - warm0,
                          "wall_s": wm, "cpu_s": measure.median_spread([r[1] for r in runs]),
                          "vs_command": wm["median"] / cmd_wall, "vs_library": wm["median"] / lib_wall}
            # CPU: the peer's process time against the command's and the example's process CPU
            cm = peers[key]["cpu_s"]["median"]
            peers[key]["cpu_vs_command"] = cm / report["autobal"]["command_cpu_s"]["median"]
            peers[key]["cpu_vs_library_process"] = cm / report["autobal"]["library_process_cpu_s"]["median"]
            bound = "" if reached else " (target not reached: lower bound)"
            print(f"{key}: rtol {rtol:g}, {wm['median'] * 1e3:.1f} ms wall = {wm['median'] / cmd_wall:.2f}x the command, "
                  f"{wm['median'] / lib_wall:.2f}x the library; CPU {cm * 1e3:.1f} ms = {peers[key]['cpu_vs_command']:.2f}x the "
                  f"command's, {peers[key]['cpu_vs_library_process']:.2f}x the example process's{bound}", file=sys.stderr)
    report["peers"] = peers
    ok = sess.finish(report)
    print(json.dumps(report, indent=2))
    measure.write_table(a.json, report, ok)


if __name__ == "__main__":
    main()
