#!/usr/bin/env python3
"""Stationary state and its stability per speed: autobal's general route against what a SciPy
user would write (issue 18, item 7).

Problems:
  planar   paper 004's rotor with the race centred (examples/planar.toml, s2 = 0): the
           Jeffcott rotor with two balls. Autobal: `autobal stability --route general` on a
           grid of N speeds up to 3 omega_n (Newton with the AD Jacobian from the closed form,
           eigenvalues, range ends bisected to 1e-9). SciPy: the same equations derived by SymPy
           (Lagrange, crates/autobal/tests/planar_linearisation.py, lambdified to NumPy), per
           speed scipy.optimize.root (hybr, its own finite-difference Jacobian) from the same
           closed-form balanced state, a central-difference Jacobian at the root and
           numpy.linalg.eigvals. Checked: the abscissa max Re(lambda) at every grid speed agrees
           (to 1e-6 of max|lambda|, the difference quotients' accuracy) and the stable range's
           lower end lies in the grid cell where SciPy's verdict changes.
  floquet  a periodic stationary state (Floquet multipliers). Autobal:
           examples/spatial_two_plane.toml (16 states: two ball planes, supports stiffer in y,
           gravity), N speeds up to 5 omega_0, and the same rotor made autonomous (no gravity,
           equal supports) for the equilibrium-to-Floquet ratio. SciPy: the planar rotor above
           with its support stiffer by 30 % along one fixed direction (8 states; in rotating
           axes periodic with the revolution), per speed shooting by scipy.optimize.root (hybr)
           on x0 - x(T; x0) with solve_ivp (DOP853, rtol 1e-10), then the monodromy matrix by
           solve_ivp of the 8 + 64 variational equations with the exact (SymPy) Jacobian, and
           numpy.linalg.eigvals. NOT the same problem as autobal's (autobal's planar model has
           no direction-dependent supports, and a NumPy version of the 16-state spatial rotor is
           not written): the two are printed for scale, without a ratio. Also the SciPy user
           without SymPy: the monodromy by central differences of 2n solve_ivp flows. Where
           autobal's planar model takes per-direction supports (planar.k_y), autobal runs
           SciPy's own problem (k along x, 1.3 k along y) and the CPU ratios are printed.

Autobal is timed as whole processes (wall and CPU of the child); its per-speed cost is the CPU
time over the grid's speeds (the location of the range ends to 1e-9 included: a few trial
speeds per end), less the process start (measured apart: `autobal stability` on 10 speeds of
the planar rotor). The two-plane grid of 50 speeds starts at 50 rad/s, where no orbit is found
at the first two speeds (a revolution is long there and the failed search dear): it is also
timed on 10 speeds (250-2500 rad/s, every orbit found);
the planar rotor is timed on 50 N_PLANAR speeds (N_PLANAR cost a few ms), checked on N_PLANAR.

Load average before and after, CPU beside wall, LOADED rule: bench/measure.py.

Usage: python3 bench/stationary.py [N_PLANAR] [N_FLOQUET] [--allow-loaded] [--json FILE]
(default 400 50; the SciPy Floquet side runs 5 speeds)
"""
import json
import math
import os
import subprocess
import sys
import time
import tomllib

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")
import numpy as np  # noqa: E402
import sympy as sp  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402
from scipy.optimize import root  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import measure  # noqa: E402

OPTS = measure.strip_args(sys.argv)
N_PLANAR = int(sys.argv[1]) if len(sys.argv) > 1 else 400
N_FLOQUET = int(sys.argv[2]) if len(sys.argv) > 2 else 50
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = os.environ.get("AUTOBAL", os.path.join(ROOT, "target", "release", "autobal"))
TWO_PLANE = os.path.join(ROOT, "examples", "spatial_two_plane.toml")
AUTONOMOUS = ["--set", "spatial.gravity=[0.0,0.0,0.0]", "--set", "supports.stiffness_left_y=2.0e6", "--set", "supports.stiffness_right_y=3.0e6"]


def planar_params():
    """examples/planar.toml's rotor, race centred: the parameters only (no equations)."""
    with open(os.path.join(ROOT, "examples", "planar.toml"), "rb") as f:
        p = tomllib.load(f)["planar"]
    p["s2"] = 0.0
    return p


def model(n):
    """Lagrange's equations of the planar rotor in axes turning at W (as in
    crates/autobal/tests/planar_linearisation.py), with the support stiffness k along the fixed
    x axis and k (1 + a) along fixed y: M(z) q'' = h(t, z), lambdified; and dh/dz, dM/dz."""
    m1, m2, m3, s1, r, k, a, c, cpsi, W, t = sp.symbols("m1 m2 m3 s1 r k a c c_psi W t", real=True)
    xi, eta, xid, etad = sp.symbols("xi eta xid etad", real=True)
    psi = sp.symbols(f"psi1:{n + 1}", real=True)
    psid = sp.symbols(f"psid1:{n + 1}", real=True)
    q = [xi, eta, *psi]
    qd = [xid, etad, *psid]
    u = sp.Matrix([xi, eta])
    ud = sp.Matrix([xid, etad])

    def vel(pos):
        dpos = sp.Matrix([sum(sp.diff(pos[i], qq) * vv for qq, vv in zip(q, qd)) for i in range(2)])
        return dpos + W * sp.Matrix([-pos[1], pos[0]])

    bodies = [(m1, u + sp.Matrix([s1, 0])), (m2, u)]
    bodies += [(m3, u + r * sp.Matrix([sp.cos(p), sp.sin(p)])) for p in psi]
    T = sum(m * (vel(pos).T * vel(pos))[0] for m, pos in bodies) / 2
    X = xi * sp.cos(W * t) - eta * sp.sin(W * t)
    Y = xi * sp.sin(W * t) + eta * sp.cos(W * t)
    V = (k * X**2 + k * (1 + a) * Y**2) / 2
    vc = ud + W * sp.Matrix([-eta, xi])
    Q = [-c * vc[0], -c * vc[1]] + [-cpsi * pd for pd in psid]
    N = len(q)
    Tqd = [sp.diff(T, v) for v in qd]
    M = sp.Matrix(N, N, lambda i, j: sp.diff(Tqd[i], qd[j]))
    h = sp.Matrix([Q[i] - sp.diff(V, q[i]) + sp.diff(T, q[i]) - sum(sp.diff(Tqd[i], q[j]) * qd[j] for j in range(N)) for i in range(N)])
    z = q + qd
    params = [m1, m2, m3, s1, r, k, a, c, cpsi, W]
    fM = sp.lambdify([params, t, z], M, "numpy")
    fh = sp.lambdify([params, t, z], h, "numpy")
    fdM = sp.lambdify([params, t, z], sp.Matrix.hstack(*[M.diff(v) for v in z]), "numpy")
    fdh = sp.lambdify([params, t, z], h.jacobian(z), "numpy")
    return fM, fh, fdM, fdh


class Planar:
    """The SciPy user's right-hand side z' = (q', M⁻¹ h) and exact Jacobian at speed W."""

    def __init__(self, fns, p, W, a):
        self.fM, self.fh, self.fdM, self.fdh = fns
        self.n = p["n"]
        self.N = 2 + self.n
        self.par = [p["m1"], p["m2"], p["m3"], p["s1"], p["r"], p["k"], a, p["c"], p["c_psi"], W]

    def rhs(self, t, z):
        N = self.N
        M = np.array(self.fM(self.par, t, z), dtype=float)
        h = np.array(self.fh(self.par, t, z), dtype=float).reshape(N)
        return np.concatenate([z[N:], np.linalg.solve(M, h)])

    def jac(self, t, z):
        N = self.N
        M = np.array(self.fM(self.par, t, z), dtype=float)
        h = np.array(self.fh(self.par, t, z), dtype=float).reshape(N)
        qdd = np.linalg.solve(M, h)
        dM = np.array(self.fdM(self.par, t, z), dtype=float).reshape(N, 2 * N, N)  # dM/dz_j in blocks
        dh = np.array(self.fdh(self.par, t, z), dtype=float)
        rhs = dh - np.einsum("ijk,k->ij", dM.reshape(N, 2 * N, N), qdd)
        A = np.zeros((2 * N, 2 * N))
        A[:N, N:] = np.eye(N)
        A[N:, :] = np.linalg.solve(M, rhs)
        return A


def balanced_guess(p):
    """u = 0, the two balls at pi -+ acos(m1 s1 / (2 m3 r)), at rest relative to the rotor."""
    b = math.acos(p["m1"] * p["s1"] / (2 * p["m3"] * p["r"]))
    return np.array([0.0, 0.0, math.pi - b, math.pi + b, 0.0, 0.0, 0.0, 0.0])


def central_jacobian(f, x):
    """(f(x + h e_j) - f(x - h e_j)) / 2h, h = 1e-6 max(|x_j|, 1e-3)."""
    n = x.size
    J = np.empty((n, n))
    for j in range(n):
        h = 1e-6 * max(abs(x[j]), 1e-3)
        e = np.zeros(n)
        e[j] = h
        J[:, j] = (f(x + e) - f(x - e)) / (2 * h)
    return J


def scipy_equilibrium(fns, p, speeds):
    alphas = []
    for W in speeds:
        m = Planar(fns, p, W, 0.0)
        f = lambda z: m.rhs(0.0, z)  # noqa: E731
        sol = root(f, balanced_guess(p), method="hybr", options={"xtol": 1e-13})
        lam = np.linalg.eigvals(central_jacobian(f, sol.x))
        alphas.append((float(lam.real.max()), float(np.abs(lam).max())))
    return alphas


def scipy_floquet(fns, p, W, a=0.3, rtol=1e-10):
    m = Planar(fns, p, W, a)
    T = 2 * math.pi / W
    n = 8
    atol = 1e-12

    def flow(x0):
        s = solve_ivp(m.rhs, (0.0, T), x0, method="DOP853", rtol=rtol, atol=atol)
        return s.y[:, -1]

    sol = root(lambda x0: x0 - flow(x0), balanced_guess(p), method="hybr", options={"xtol": 1e-11})

    def var(t, y):
        z = y[:n]
        phi = y[n:].reshape(n, n)
        return np.concatenate([m.rhs(t, z), (m.jac(t, z) @ phi).ravel()])

    y0 = np.concatenate([sol.x, np.eye(n).ravel()])
    s = solve_ivp(var, (0.0, T), y0, method="DOP853", rtol=rtol, atol=atol)
    mu = np.linalg.eigvals(s.y[n:, -1].reshape(n, n))
    return float(np.log(np.abs(mu).max()) / T), sol.success


def scipy_floquet_fd(fns, p, W, a=0.3, rtol=1e-10):
    """What a SciPy user without a symbolic Jacobian writes: the orbit by scipy.optimize.root
    (hybr, its own finite-difference Jacobian) on x0 - x(T; x0) with solve_ivp (DOP853), then the
    monodromy matrix column by column by central differences of the flow,
    (x(T; x0 + h e_j) - x(T; x0 - h e_j)) / 2h (2n more solve_ivp calls), and numpy.linalg.eigvals.
    Its multipliers are good to ~sqrt(rtol) at best (the difference quotient of an integrated flow)."""
    m = Planar(fns, p, W, a)
    T = 2 * math.pi / W
    n = 8
    atol = 1e-12

    def flow(x0):
        s = solve_ivp(m.rhs, (0.0, T), x0, method="DOP853", rtol=rtol, atol=atol)
        return s.y[:, -1]

    sol = root(lambda x0: x0 - flow(x0), balanced_guess(p), method="hybr", options={"xtol": 1e-11})
    phi = np.empty((n, n))
    for j in range(n):
        h = 1e-6 * max(abs(sol.x[j]), 1e-3)
        e = np.zeros(n)
        e[j] = h
        phi[:, j] = (flow(sol.x + e) - flow(sol.x - e)) / (2 * h)
    mu = np.linalg.eigvals(phi)
    return float(np.log(np.abs(mu).max()) / T), sol.success


# the planar config keys of direction-dependent supports (issue 18 item 3: k_x and k_y, given
# together and instead of k); where the autobal in use does not take them, the same problem
# cannot be run by autobal and the SciPy Floquet figures are printed for scale only
PLANAR_KY = "planar.k_y"


def autobal_planar_anisotropic(p, a, speeds):
    """autobal stability on SciPy's anisotropic planar problem (k along x, k (1 + a) along y), or
    None where this autobal has no per-direction planar supports."""
    import re
    import tempfile
    with open(os.path.join(ROOT, "examples", "planar.toml")) as f:
        text = re.sub(r"(?m)^k\s*=.*$", f"k_x = {p['k']!r}\nk_y = {p['k'] * (1 + a)!r}", f.read(), count=1)
    cfg = tempfile.NamedTemporaryFile("w", suffix=".toml", delete=False)
    cfg.write(text)
    cfg.close()
    args = ["--config", cfg.name, "--set", "planar.s2=0", "--route", "general", "--omega-max", str(max(speeds)), "--samples", str(len(speeds))]
    try:
        subprocess.run([EXE, "stability", "--format", "json", *args], check=True, capture_output=True, text=True)
    except subprocess.CalledProcessError:
        return None
    return args


def autobal(args):
    out = subprocess.run([EXE, "stability", "--format", "json", *args], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def evaluations(d, samples):
    """The grid's speeds: autobal's cost is quoted per grid speed, the location of the range
    ends (regula falsi on the abscissa, a handful of trial speeds per end) included."""
    return samples


def timed_autobal(args, samples, repeats=3):
    walls, cpus = [], []
    for _ in range(repeats):
        w, c = measure.run_cmd([EXE, "stability", "--format", "json", *args])
        walls.append(w)
        cpus.append(c)
    return min(walls), min(cpus)


def main():
    s = measure.Session("stationary", allow_loaded=OPTS.allow_loaded)
    report = {"n_planar": N_PLANAR, "n_floquet": N_FLOQUET}
    p = planar_params()
    planar_cfg = [
        "--config", os.path.join(ROOT, "examples", "planar.toml"), "--set", "planar.s2=0", "--route", "general",
    ]
    # process start and config: 10 speeds of the planar rotor
    _, start_cpu = timed_autobal([*planar_cfg, "--samples", "10"], 10)
    report["autobal_start_cpu_s"] = start_cpu

    # planar equilibrium
    d = autobal([*planar_cfg, "--samples", str(N_PLANAR)])
    ev = evaluations(d, N_PLANAR)
    # timed on 50x the grid (the same rotor and axis): 400 speeds cost a few ms, near the
    # resolution of getrusage
    nt = 50 * N_PLANAR
    dt_ = autobal([*planar_cfg, "--samples", str(nt)])
    evt = evaluations(dt_, nt)
    wall, cpu = timed_autobal([*planar_cfg, "--samples", str(nt)], nt)
    a_per = max(cpu - start_cpu, 0.0) / evt
    speeds = [pt["omega"] for pt in d["points"]]
    fns = model(p["n"])
    (sw, sc), alphas = measure.cpu_of(lambda: scipy_equilibrium(fns, p, speeds))
    s_per = sc / len(speeds)
    worst = max(abs(pt["abscissa"] - a) / rho for pt, (a, rho) in zip(d["points"], alphas) if pt["abscissa"] is not None)
    lo = d["stable_ranges"][0]["from"] if d["stable_ranges"] else None
    cell = None
    for i in range(len(speeds) - 1):
        if alphas[i][0] >= 0 > alphas[i + 1][0]:
            cell = (speeds[i], speeds[i + 1])
            break
    report["planar"] = {
        "speeds": N_PLANAR, "autobal_timed_speeds": nt, "autobal_evaluations": evt, "autobal_wall_s": wall, "autobal_cpu_s": cpu,
        "autobal_cpu_per_speed_ms": 1e3 * a_per, "scipy_cpu_s": sc, "scipy_wall_s": sw,
        "scipy_cpu_per_speed_ms": 1e3 * s_per, "ratio": s_per / a_per if a_per > 0 else None,
        "max_abscissa_difference_over_rho": worst, "autobal_lower_end": lo, "scipy_sign_change_cell": cell,
        "lower_end_in_cell": bool(lo and cell and cell[0] <= lo <= cell[1]),
    }
    print(f"planar equilibrium: autobal {1e3 * a_per:.4f} ms CPU per speed ({evt} evaluations, {cpu:.3f} s CPU, "
          f"start {start_cpu:.3f} s), SciPy {1e3 * s_per:.2f} ms CPU per speed: ratio {s_per / a_per:.0f}x; "
          f"abscissae agree to {worst:.1e} max|lambda|; lower end {lo} in SciPy's cell {cell}", file=sys.stderr)

    # Floquet: autobal two-plane, its autonomous twin, SciPy planar anisotropic
    two = ["--config", TWO_PLANE, "--route", "general", "--omega-max", "5", "--samples", str(N_FLOQUET)]
    d = autobal(two)
    ev = evaluations(d, N_FLOQUET)
    wall, cpu = timed_autobal(two, N_FLOQUET, repeats=2)
    f_per = max(cpu - start_cpu, 0.0) / ev
    ten = ["--config", TWO_PLANE, "--route", "general", "--omega-max", "5", "--samples", "10"]
    d10 = autobal(ten)
    wall10, cpu10 = timed_autobal(ten, 10)
    f10 = max(cpu10 - start_cpu, 0.0) / 10
    de = autobal([*two, *AUTONOMOUS])
    eve = evaluations(de, N_FLOQUET)
    walle, cpue = timed_autobal([*two, *AUTONOMOUS], N_FLOQUET)
    # the equilibrium is too cheap to time on 50 speeds against the process start: 2000
    big = ["--config", TWO_PLANE, "--route", "general", "--omega-max", "5", "--samples", "2000", *AUTONOMOUS]
    db = autobal(big)
    evb = evaluations(db, 2000)
    wallb, cpub = timed_autobal(big, 2000)
    e_per = max(cpub - start_cpu, 0.0) / evb
    wn = math.sqrt(p["k"] / (p["m1"] + p["m2"] + p["n"] * p["m3"]))
    fl_speeds = [1.5 * wn, 2.0 * wn, 2.5 * wn, 3.0 * wn, 3.5 * wn]
    (fw, fc), fl = measure.cpu_of(lambda: [scipy_floquet(fns, p, W) for W in fl_speeds])
    (fdw, fdc), fld = measure.cpu_of(lambda: [scipy_floquet_fd(fns, p, W) for W in fl_speeds])
    same = autobal_planar_anisotropic(p, 0.3, [wn * 3.5 * (i + 1) / 50 for i in range(50)])
    same_report = None
    if same is not None:
        # autobal on the same problem as SciPy: 50 speeds up to 3.5 omega_n (CPU per speed)
        sw_, sc_ = timed_autobal(same, 50, repeats=2)
        a_same = max(sc_ - start_cpu, 0.0) / 50
        same_report = {"cpu_s": sc_, "wall_s": sw_, "cpu_per_speed_ms": 1e3 * a_same,
                       "scipy_exact_jacobian_over_autobal": (fc / len(fl_speeds)) / a_same if a_same > 0 else None,
                       "scipy_fd_over_autobal": (fdc / len(fl_speeds)) / a_same if a_same > 0 else None}
    report["floquet"] = {
        "autobal_two_plane": {"speeds": N_FLOQUET, "evaluations": ev, "wall_s": wall, "cpu_s": cpu, "cpu_per_speed_ms": 1e3 * f_per,
                              "stable_ranges": d["stable_ranges"], "failures": sum(1 for pt in d["points"] if pt["failure"])},
        "autobal_two_plane_10": {"speeds": 10, "cpu_s": cpu10, "wall_s": wall10, "cpu_per_speed_ms": 1e3 * f10,
                                 "stable_ranges": d10["stable_ranges"], "failures": sum(1 for pt in d10["points"] if pt["failure"])},
        "autobal_autonomous_twin": {"speeds": 2000, "evaluations": evb, "cpu_s": cpub, "cpu_per_speed_ms": 1e3 * e_per,
                                    "n50_evaluations": eve, "n50_cpu_s": cpue},
        "floquet_over_equilibrium": f_per / e_per if e_per > 0 else None,
        "floquet_over_equilibrium_10": f10 / e_per if e_per > 0 else None,
        "scipy_planar_anisotropic": {"speeds": fl_speeds, "cpu_s": fc, "wall_s": fw, "cpu_per_speed_ms": 1e3 * fc / len(fl_speeds),
                                     "largest_exponents": [x[0] for x in fl], "converged": [x[1] for x in fl]},
        "scipy_planar_anisotropic_fd": {"cpu_s": fdc, "wall_s": fdw, "cpu_per_speed_ms": 1e3 * fdc / len(fl_speeds),
                                        "largest_exponents": [x[0] for x in fld], "converged": [x[1] for x in fld]},
        "autobal_planar_anisotropic": same_report,
    }
    print(f"Floquet: autobal two-plane {1e3 * f_per:.2f} ms CPU per speed ({ev} evaluations, {cpu:.2f} s CPU); its autonomous "
          f"twin {1e3 * e_per:.4f} ms per speed (2000-speed run): {f_per / e_per:.0f}x; on 10 speeds (all found) "
          f"{1e3 * f10:.2f} ms per speed: {f10 / e_per:.0f}x; SciPy planar anisotropic (8 states) "
          f"{1e3 * fc / len(fl_speeds):.0f} ms CPU per speed (exact SymPy Jacobian), "
          f"{1e3 * fdc / len(fl_speeds):.0f} ms (monodromy by differences of solve_ivp flows)", file=sys.stderr)
    if same_report:
        print(f"Floquet, same problem (planar, k_y = 1.3 k): autobal {same_report['cpu_per_speed_ms']:.2f} ms CPU per speed; "
              f"SciPy / autobal {same_report['scipy_exact_jacobian_over_autobal']:.0f}x (exact Jacobian), "
              f"{same_report['scipy_fd_over_autobal']:.0f}x (differences)", file=sys.stderr)
    else:
        print(f"Floquet, same problem: this autobal has no {PLANAR_KY} (per-direction planar supports): no ratio", file=sys.stderr)
    ok = s.finish(report)
    print(json.dumps(report, indent=2))
    measure.write_table(OPTS.json, report, ok)


if __name__ == "__main__":
    main()
