#!/usr/bin/env python3
"""Issue 19 item 6: a flexible shaft of 40 elements with one ball balancer, reduced, against a
SciPy user's code on the same reduced equations.

The rotor: a steel shaft of 40 Euler-Bernoulli elements (1.2 m, 25 mm; 164 DOFs), a disk with
the unbalance and a two-ball balancer at node 13, isotropic bearings at both ends; reduced by
autobal to 4 interior mode pairs plus the balancer node (`linear_rotor.modes = 4`). The reduced
matrices are those `autobal export-model` writes for it (Matrix Market, every digit), read here
with `scipy.io.mmread`, so both sides integrate the same equations.

1. Run-up: from rest at constant acceleration to `omega_max` (1.5 x the 4th natural
   frequency with the balls as rings) in 1000 revolutions, 2000 samples.
   autobal: `LinearRotor.from_config(cfg).simulate()` in this process (CPU time), and the
            command `autobal simulate --config cfg` as a process (CSV, 4 SVG figures, wall and
            CPU of the child).
   SciPy:   `solve_ivp(method="DOP853")` on the fixed-axes equations of the reduced rotor with
            its balls (crates/autobal/src/linear_rotor/field.rs, ported line by line to NumPy:
            the residual `R(x) - A(psi) a` and the mass matrix `A(psi)`, `a = A^-1 R`), with the
            same tolerances (rtol, and the same per-component atol: displacements, angles /
            race radius, rates x the top speed) and the same sample times.
   Accuracy: both runs against autobal's at rtol 1e-12 (the reference), as the largest
   difference of the balancer plane's whirl radius `r_0` over the samples, relative to its
   peak. "Equal accuracy" means those two numbers are of the same order; they are printed.
2. Stability over speed: the balanced state's eigenvalues at 200 speeds up to `omega_max`.
   autobal: `LinearRotor.stability(omega_max, 200, modes=4)` (Newton for the state, exact
            Jacobian by automatic differentiation, eigenvalues) and `autobal stability` as a
            process.
   SciPy:   per speed, the balanced state in closed form (the unbalance and the balls on one
            node: the structure rests on the axis, the balls at `pi +- arccos(me / (2 m R))`
            from the unbalance), the Jacobian of the same ported equations in axes turning with
            the rotor by central differences, `numpy.linalg.eigvals`; and `eigvals` alone on
            those matrices (the floor of any Python code). The verdicts are compared speed by
            speed with autobal's (they must agree but at the ends of ranges).

Load average before and after, CPU beside wall, the LOADED rule: bench/measure.py. The issue's
goal: each autobal figure under 1 s (2 cores).

The autobal extension must be a release build (bench/measure.py's check_extension: a dev-profile
one is refused unless --allow-dev-extension; a release wheel: docs/notes/benchmarks.md).

Usage: python3 bench/linear_rotor.py [--allow-loaded] [--allow-dev-extension] [--json FILE]
       (the autobal binary: $AUTOBAL_BIN, else target/release/autobal, else target/debug/autobal)
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("MKL_NUM_THREADS", "1")
import numpy as np  # noqa: E402
import tomllib  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import measure  # noqa: E402

import autobal  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
NODE = 13
CONFIG = f"""# bench/linear_rotor.py: a 40-element shaft with one balancer, reduced
[linear_rotor]
modes = 4
[[linear_rotor.elements]]
length = 0.03
diameter = 0.025
e = 2.1e11
rho = 7850.0
count = 40
[[linear_rotor.disks]]
node = {NODE}
mass = 4.0
id = 0.01
ip = 0.02
[[linear_rotor.bearings]]
node = 0
k = 2e6
c = 300.0
[[linear_rotor.bearings]]
node = 40
k = 2e6
c = 300.0
[[linear_rotor.unbalance]]
node = {NODE}
me = 2e-4
[[linear_rotor.balancer]]
node = {NODE}
radius = 0.06
balls = 2
ball_mass = 0.02
drag = 0.1
[integration]
rtol = 1e-7
atol = 1e-9
"""


def binary() -> str:
    for p in (os.environ.get("AUTOBAL_BIN"), ROOT / "target" / "release" / "autobal", ROOT / "target" / "debug" / "autobal"):
        if p and Path(p).exists():
            return str(p)
    raise SystemExit("no autobal binary: cargo build --release -p autobal-cli (or set AUTOBAL_BIN)")


class Reduced:
    """The reduced rotor's equations with its balls (field.rs, ported to NumPy)."""

    def __init__(self, d: Path, stem: str):
        from scipy.io import mmread

        cfg = tomllib.loads((d / f"{stem}.toml").read_text())["linear_rotor"]
        def dense(x: str) -> np.ndarray:
            a = mmread(str(d / f"{stem}_{x}.mtx"))
            return np.asarray(a.todense() if hasattr(a, "todense") else a, dtype=float)

        self.M, self.C, self.G, self.K = (dense(x) for x in "MCGK")
        # K_st: the term Omega' K_st q of a speed that changes (LinearRotor::spin_stiffness;
        # empty = G / 2, from the kinetic energy's 1/2 phi' q'^T G' q)
        self.Kst = dense("KST") if "kst" in cfg else 0.5 * self.G
        assert "spin_chart" not in cfg and "rotor_fixed_mass" not in cfg, "terms this port leaves out"
        self.n = self.M.shape[0]
        (b,) = cfg["balancer"]
        (u,) = cfg["unbalance"]
        assert b["offset"] == 0.0 and u["offset"] == 0.0 and b["node"] == u["node"]
        node = b["node"]
        self.ix, self.iy, self.ia, self.ib = 4 * node, 4 * node + 1, 4 * node + 2, 4 * node + 3
        self.nb, self.r, self.m, self.drag = b["balls"], b["radius"], b["ball_mass"], b["drag"]
        self.me, self.phase = u["me"], u["phase"]
        self.nc = self.n + self.nb

    def accelerations(self, x, w, wdot, nu, chi, D):
        """`A(psi)^-1 R(x)` (field.rs `residual` with a = 0 and `mass_matrix`; z = 0; the term
        `wdot K_st p` is written for fixed axes, nu = 0, where run-ups are integrated)."""
        n, nc, nb = self.n, self.nc, self.nb
        p, pd = x[:n], x[nc:nc + n]
        # v = pd + nu J p, a_s = 2 nu J pd - nu^2 p (J (a, b) = (-b, a))
        v = pd.copy()
        a = -(nu * nu) * p
        v[0::2] -= nu * p[1::2]
        v[1::2] += nu * p[0::2]
        a[0::2] += -2.0 * nu * pd[1::2]
        a[1::2] += 2.0 * nu * pd[0::2]
        f = np.zeros(n)
        force = self.me * complex(w * w, -wdot) * np.exp(1j * (self.phase + chi))
        f[self.ix] += force.real
        f[self.iy] += force.imag
        out = np.empty(nc)
        out[:n] = f - self.M @ a - D @ v - self.Kc @ p - wdot * (self.Kst @ p)
        A = np.zeros((nc, nc))
        A[:n, :n] = self.M
        m, r = self.m, self.r
        mr2 = m * r * r
        ix, iy, ia, ib = self.ix, self.iy, self.ia, self.ib
        ta, tb = p[ia], p[ib]
        oa, ob = v[ia], v[ib]
        da, db = a[ia], a[ib]
        for g in range(nb):
            psi, psid = x[n + g], x[nc + n + g]
            s, c = np.sin(psi + chi), np.cos(psi + chi)
            rate = psid + w
            w2 = rate * rate
            pdd = wdot
            ax = a[ix] + (s * pdd + c * w2) * (-r)
            ay = a[iy] + (c * pdd - s * w2) * r
            out[ix] -= ax * m
            out[iy] -= ay * m
            out[n + g] = -psid * self.drag - (c * ay - s * ax) * (m * r)
            sigma = oa * s - ob * c
            o_e = oa * c + ob * s
            sigma_dot = (da * s - db * c) + rate * o_e
            out[ia] -= (sigma_dot * s + rate * sigma * c) * mr2 + tb * (0.5 * mr2 * pdd) + rate * ob * mr2
            out[ib] -= (sigma_dot * (-c) + rate * sigma * s) * mr2 - ta * (0.5 * mr2 * pdd) - rate * oa * mr2
            out[n + g] += -(da * tb - db * ta) * (0.5 * mr2) + sigma * o_e * mr2
            j = n + g
            for i, e in ((ix, -m * r * s), (iy, m * r * c)):
                A[i, i] += m
                A[i, j] += e
                A[j, i] += e
            A[j, j] += mr2
            A[ia, ia] += mr2 * s * s
            A[ia, ib] -= mr2 * s * c
            A[ib, ia] -= mr2 * s * c
            A[ib, ib] += mr2 * c * c
            A[ia, j] += 0.5 * mr2 * tb
            A[j, ia] += 0.5 * mr2 * tb
            A[ib, j] -= 0.5 * mr2 * ta
            A[j, ib] -= 0.5 * mr2 * ta
        return np.linalg.solve(A, out)

    def rhs_runup(self, b):
        """Fixed axes, Omega = b t, phi = b t^2 / 2 (constant bearings: C, K do not move)."""
        self.Kc = self.K
        nc = self.nc

        def f(t, x):
            w = b * t
            acc = self.accelerations(x, w, b, 0.0, 0.5 * b * t * t, self.C + w * self.G)
            return np.concatenate((x[nc:], acc))

        return f

    def jacobian_rotating(self, w):
        """The balanced state at speed w in axes turning with the rotor and the Jacobian there
        (central differences, step 1e-7 of each component's scale)."""
        self.Kc = self.K
        nc, n = self.nc, self.n
        x0 = np.zeros(2 * nc)
        half = np.arccos(self.me / (self.nb * self.m * self.r))
        x0[n:n + 2] = [self.phase + np.pi + half, self.phase + np.pi - half]
        D = self.C + w * self.G

        def f(x):
            return np.concatenate((x[nc:], self.accelerations(x, w, 0.0, w, 0.0, D)))

        assert np.max(np.abs(f(x0))) < 1e-6 * w * w, "not the balanced state"
        h = np.concatenate((np.full(n, 1e-9), np.full(self.nb, 1e-7), np.full(n, 1e-9 * max(w, 1.0)), np.full(self.nb, 1e-7 * max(w, 1.0))))
        J = np.empty((2 * nc, 2 * nc))
        for k in range(2 * nc):
            e = np.zeros(2 * nc)
            e[k] = h[k]
            J[:, k] = (f(x0 + e) - f(x0 - e)) / (2 * h[k])
        return J


def main() -> None:
    s = measure.Session("linear_rotor", allow_loaded=OPTS.allow_loaded)
    build, ok = measure.check_extension("linear_rotor", OPTS.allow_dev_extension)
    if not ok:
        raise SystemExit("linear_rotor.py: the autobal extension is not a release build (--allow-dev-extension to time it anyway)")
    from scipy.integrate import solve_ivp

    exe = binary()
    report: dict = {"extension": build, "rotor": "40 Euler-Bernoulli elements (164 DOFs), one 2-ball balancer, reduced to 4 mode pairs"}
    with tempfile.TemporaryDirectory() as td:
        d = Path(td)
        cfg = d / "shaft.toml"
        cfg.write_text(CONFIG)
        subprocess.run([exe, "export-model", "--config", str(cfg), "--out", str(d), "--stem", "red"], check=True, capture_output=True)
        red = Reduced(d, "red")
        lr = autobal.LinearRotor.from_config(cfg)
        report["dofs"] = {"full": lr.dofs, "reduced": red.n, "balls": red.nb}

        # -- 1. the run-up --------------------------------------------------------------
        (w1, c1), sim = measure.cpu_of(lambda: lr.simulate())
        (w1, c1), sim = measure.cpu_of(lambda: lr.simulate())  # the second: warm
        wall_cli, cpu_cli = measure.run_cmd([exe, "simulate", "--config", str(cfg), "--out", str(d / "run.csv")])
        ref = autobal.LinearRotor.from_config(cfg, set={"integration.rtol": 1e-12, "integration.atol": 1e-15}).simulate()
        t = sim.columns["t"]
        w_top = sim.columns["omega"][-1]
        b = w_top / t[-1]
        atol = np.concatenate((np.full(red.n, 1e-9), np.full(red.nb, 1e-9 / red.r)))
        atol = np.concatenate((atol, atol * max(w_top, 1.0)))
        x0 = np.zeros(2 * red.nc)
        x0[red.n:red.n + red.nb] = 2 * np.pi * np.arange(red.nb) / red.nb
        (w2, c2), sp = measure.cpu_of(lambda: solve_ivp(red.rhs_runup(b), (0.0, t[-1]), x0, method="DOP853", rtol=1e-7, atol=atol, t_eval=t))
        assert sp.success, sp.message
        r_sp = np.hypot(sp.y[red.ix], sp.y[red.iy])
        peak = np.max(ref.columns["r_0"])
        err_ab = float(np.max(np.abs(sim.columns["r_0"] - ref.columns["r_0"])) / peak)
        err_sp = float(np.max(np.abs(r_sp - ref.columns["r_0"])) / peak)
        report["runup"] = {
            "revolutions": 1000,
            "omega_max": float(w_top),
            "samples": len(t),
            "autobal_python": {"wall_s": w1, "cpu_s": c1, "error_vs_reference": err_ab, "steps": sim.summary["steps"]},
            "autobal_cli": {"wall_s": wall_cli, "cpu_s": cpu_cli},
            "scipy_dop853": {"wall_s": w2, "cpu_s": c2, "error_vs_reference": err_sp, "rhs_evaluations": int(sp.nfev)},
            "cpu_ratio_scipy_over_autobal": c2 / c1 if c1 > 0 else None,
        }
        print(f"run-up: autobal {c1:.3f} s CPU ({w1:.3f} s wall, error {err_ab:.1e}), CLI {cpu_cli:.3f} s CPU; "
              f"SciPy DOP853 {c2:.2f} s CPU ({sp.nfev} right-hand sides, error {err_sp:.1e})", file=sys.stderr)

        # -- 2. stability over speed ----------------------------------------------------
        samples = 200
        (w3, c3), st = measure.cpu_of(lambda: json.loads(lr.stability(w_top, samples, modes=4)))
        (w3, c3), st = measure.cpu_of(lambda: json.loads(lr.stability(w_top, samples, modes=4)))
        wall_cli_s, cpu_cli_s = measure.run_cmd([exe, "stability", "--config", str(cfg), "--omega-max", f"{float(w_top)!r} rad/s", "--samples", str(samples), "--format", "json"])
        speeds = [p["omega"] for p in st["points"]]
        verdict_ab = [p.get("verdict") for p in st["points"]]
        t0c, t0w = time.process_time(), time.perf_counter()
        jacs = [red.jacobian_rotating(w) for w in speeds]
        abscissa = [float(np.max(np.linalg.eigvals(J).real)) for J in jacs]
        c4, w4 = time.process_time() - t0c, time.perf_counter() - t0w
        (w5, c5), _ = measure.cpu_of(lambda: [np.linalg.eigvals(J) for J in jacs])
        # the verdicts: autobal's margin is 1e-11 of the speed scale; central differences carry
        # ~1e-6 relative error, so speeds where either margin is within 1e-4 of the largest
        # |Re| are not compared
        scale = max(abs(a) for a in abscissa)
        disagree = [w for w, a, v in zip(speeds, abscissa, verdict_ab) if abs(a) > 1e-4 * scale and v in ("stable", "unstable") and (a < 0) != (v == "stable")]
        report["stability"] = {
            "speeds": samples,
            "stable_ranges": [(r["from"], r["to"]) for r in st["stable_ranges"]],
            "autobal_python": {"wall_s": w3, "cpu_s": c3},
            "autobal_cli": {"wall_s": wall_cli_s, "cpu_s": cpu_cli_s},
            "scipy_jacobian_and_eigvals": {"wall_s": w4, "cpu_s": c4},
            "numpy_eigvals_only": {"wall_s": w5, "cpu_s": c5},
            "verdicts_disagreeing": disagree,
        }
        print(f"stability: autobal {c3:.3f} s CPU (CLI {cpu_cli_s:.3f} s), SciPy Jacobian + eigvals {c4:.2f} s CPU, eigvals alone {c5:.3f} s CPU; "
              f"verdicts disagreeing at {len(disagree)} of {samples} speeds", file=sys.stderr)
    ok = s.finish(report)
    print(json.dumps(report, indent=2))
    measure.write_table(OPTS.json, report, ok)


OPTS = measure.strip_args(sys.argv)

if __name__ == "__main__":
    main()
