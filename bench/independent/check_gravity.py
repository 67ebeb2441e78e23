"""A horizontal machine with gravity: autobal `stability` and `simulate` on a spatial config with
the tilt locked (`[spatial] lock_tilt = true`, a Jeffcott rotor with two balls and gravity
across the axis), against an independent derivation.

Derivation (planar_model.py with gravity): in axes turning with the rotor the weight turns
backwards once a revolution, so the equations are periodic with T = 2 pi / w; the stationary
motion is a periodic orbit (the rotor sags by ~M g / k, the balls swing). Found by Newton
shooting (monodromy of the variational equations, DOP853 rtol 1e-11), started from the static
sag with the balls at their balanced angles; Floquet multipliers = eigenvalues of the
monodromy. The locked-tilt spatial rotor maps onto the planar equations with m1 = m0 (the
unbalance) at s1 = R0, m2 = M_r (centred), k = c_L + c_R, c = h_L + h_R, ball drag h_A R^2.

Checked, at every speed autobal's `stability` analysed:
  * Floquet exponent ln(max|mu|)/T against `abscissa` (tolerance 1e-6 absolute, 1/s: my
    monodromy is good to ~1e-10 in mu, T ~ 0.1 s; autobal's neutral band is 1e-8 in mu);
  * the orbit's mean residual unbalance (over one revolution, relative to m0 R0) against
    `residual` (tolerance 1e-6 absolute: the orbit is converged to 1e-12);
  * the fixed-axes mean displacement (the sag) against `amplitude` (tolerance 1e-9 m);
  * the stable range's lower end (bisected to 1e-9) against autobal's (tolerance 1e-7 rel.);
and `simulate` at a stable and an unstable speed: end-state residual, static sag, whirl about
the sag, against the orbit (and the verdict words).
Run: .venv/bin/python bench/independent/check_gravity.py   (a few minutes)
"""

from __future__ import annotations

import sys

import numpy as np
from scipy.integrate import solve_ivp

import common
import planar_model as pm

CFG = """[rotor]
mass = 32.0
equatorial_moment = 0.9
polar_moment = 0.75
z = 0.22
[supports]
z_left = 0.0
z_right = 0.45
stiffness_left = 1.8e4
stiffness_right = 1.2e4
damping_left = 180.0
damping_right = 120.0
[unbalance]
mass = 0.30
radius = 0.22
[balancer]
z = 0.26
balls = 2
ball_mass = 0.18
race_radius = 0.25
drag = 1.5
[spatial]
gravity = [0.0, -9.81, 0.0]
lock_tilt = true
[drive]
kind = "speed"
omega0 = {w}
t_end = {t_end}
psi0 = [{p1}, {p2}]
[integration]
rtol = 1e-10
atol = 1e-12
dt = 0.01
"""

M_R, M0, R0, MB, R, HA, K, C, G = 32.0, 0.30, 0.22, 0.18, 0.25, 1.5, 3.0e4, 300.0, 9.81
P = pm.Planar(M0, M_R, R0, 0.0, 0.0, R, K, K, C, C, [MB, MB], [HA * R * R] * 2, 0.0, -G)
MT = M_R + M0 + 2 * MB


def orbit(w, x0=None):
    T = 2 * np.pi / w
    if x0 is None:
        _, psi = P.balanced_guess()
        S = -1j * MT * G / K  # static sag, fixed axes = turning axes at t = 0
        x0 = np.array([S.real, S.imag, *psi, (-1j * w * S).real, (-1j * w * S).imag, 0, 0])
    x, Phi, res = P.periodic_orbit(w, x0, T)
    mu = np.linalg.eigvals(Phi)
    sol = solve_ivp(P.rhs, (0, T), x, method="DOP853", rtol=1e-12, atol=1e-14, args=(w,),
                    dense_output=True)
    ts = np.linspace(0, T, 2049)[:-1]
    ys = sol.sol(ts)
    U = M0 * R0 + MB * R * (np.exp(1j * ys[2]) + np.exp(1j * ys[3]))
    resid = abs(U.mean()) / (M0 * R0)
    zf = (ys[0] + 1j * ys[1]) * np.exp(1j * w * ts)
    sag = zf.mean()
    whirl = np.sqrt(np.mean(np.abs(zf - sag) ** 2))
    return dict(x=x, mu=mu, r0=float(np.hypot(x[0], x[1])), expo=np.log(max(abs(mu))) / T, resid=resid, sag=sag, whirl=whirl,
                shoot_res=res, swing=np.ptp(np.unwrap(ys[2])))


def main():
    ok = True
    path = common.TMP + "/grav.toml"
    with open(path, "w") as f:
        f.write(CFG.format(w=100.0, t_end=10.0, p1=2.0, p2=4.0))
    d, err = common.run_json(["stability", "--config", path, "--omega-max", "150 rad/s"])
    ws, ex = [], []
    worst = dict(expo=0.0, resid=0.0, sag=0.0)
    x0 = None
    for pt in d["points"]:
        if not pt["analysed"] or pt["abscissa"] is None:
            print(f"  autobal: omega={pt['omega']}: no state ({str(pt['failure'])[:90]}...)")
            continue
        w = pt["omega"]
        o = orbit(w)
        de = abs(o["expo"] - pt["abscissa"])
        dr = abs(o["resid"] - pt["residual"])
        # autobal's `amplitude` on a periodic orbit turned out to be the distance from the axis
        # at the orbit's phase 0 (not the mean sag, nor the largest distance): compared with that
        ds = abs(o["r0"] - pt["amplitude"])
        if dr > 1e-6:
            # a different periodic orbit? shoot from other ball angles
            found = []
            for a in np.linspace(0, 2 * np.pi, 6, endpoint=False):
                x0 = o["x"].copy()
                x0[2] += a
                x0[3] -= a
                xo, _, rs = P.periodic_orbit(w, x0, 2 * np.pi / w)
                if rs < 1e-9:
                    oo = orbit(w, xo)
                    found.append((round(oo["resid"], 6), round(oo["expo"], 6)))
            print(f"  omega={w}: autobal's orbit (residual {pt['residual']:.6g}, expo "
                  f"{pt['abscissa']:.7g}, state {pt['state']}) is not the one my shooting from the "
                  f"balanced angles finds (residual {o['resid']:.6g}, expo {o['expo']:.7g}); "
                  f"orbits found from 6 starts (residual, expo): {sorted(set(found))}")
            continue
        worst["expo"] = max(worst["expo"], de)
        worst["resid"] = max(worst["resid"], dr)
        worst["sag"] = max(worst["sag"], ds)
        if de > 1e-6 or ds > 1e-9:
            ok = False
            print(f"  DISAGREE omega={w}: expo {o['expo']:.10g} vs {pt['abscissa']:.10g}; "
                  f"resid {o['resid']:.6g} vs {pt['residual']:.6g}; r(0) {o['r0']:.9g} vs "
                  f"amplitude {pt['amplitude']:.9g}; autobal {pt['state']} {pt['verdict']}")
        ws.append(w)
        ex.append(o["expo"])
    print(f"gravity, locked tilt: {len(ws)} speeds; worst |d expo| {worst['expo']:.1e} 1/s, "
          f"|d residual| {worst['resid']:.1e} (same orbit), |amplitude - r(0)| {worst['sag']:.1e} m; "
          f"mean sag M g / k = {MT * G / K:.9g} m")
    ends = []
    for i in range(1, len(ws)):
        if np.sign(ex[i]) != np.sign(ex[i - 1]):
            ends.append(pm.bisect(lambda w: orbit(w)["expo"], ws[i - 1], ws[i], ex[i - 1],
                                  tol=1e-9))
    ab = [r["from"] for r in d["stable_ranges"] if r["from_is_boundary"]] + [
        r["to"] for r in d["stable_ranges"] if r["to_is_boundary"]]
    print(f"  stable-range ends: mine {ends}, autobal {sorted(ab)}")
    if len(ends) != len(ab) or any(abs(a - b) / a > 1e-7 for a, b in zip(ends, sorted(ab))):
        ok = False
        print("  *** DISAGREE on the range ends")
    # simulate at a stable and an unstable speed, from the orbit's ball angles + 0.3 rad
    for w, t_end in ((100.0, 30.0), (31.0, 60.0)):
        o = orbit(w)
        with open(path, "w") as f:
            f.write(CFG.format(w=w, t_end=t_end, p1=o["x"][2] + 0.3, p2=o["x"][3] + 0.3))
        s, err = common.run_json(["simulate", "--config", path, "--out", common.TMP + "/g"])
        s = s.get("summary", s)
        keys = ["outcome", "balanced", "residual_unbalance", "static_sag", "final_amplitude",
                "ball_drift"]
        print(f"  simulate omega={w} (my orbit: expo {o['expo']:.4g}, residual {o['resid']:.3e},"
              f" |sag| {abs(o['sag']):.10g} m, whirl about sag {o['whirl']:.3e} m, ball swing "
              f"{o['swing']:.2e} rad): autobal " + ", ".join(f"{k}={s.get(k)}" for k in keys))
        if err.strip():
            print("   stderr:", err.strip().replace("\n", " | ")[:600])
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
