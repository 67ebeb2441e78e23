"""A horizontal two-bearing machine, tilt FREE, gravity across the axis (one plane, two balls,
isotropic supports): autobal `stability` against an independent derivation (spatial_model.py
with gravity). Session 15's check_gravity.py did the same rotor with the tilt locked.

In turning axes the weight turns backwards once a revolution: the equations are periodic with
T = 2 pi/w and the stationary motion is a periodic orbit (the rotor sags and tilts, the balls
swing). Found by Newton shooting (monodromy of the variational equations, DOP853 rtol 1e-11),
started from the static sag with the balls at their balanced angles; Floquet multipliers =
eigenvalues of the monodromy. Checked at every 5th speed autobal analysed:
  * the Floquet exponent ln(max|mu|)/T against `abscissa` (tolerance 1e-5 relative to max(1,
    |expo|) 1/s: the orbit is not at the origin (sag ~ 1 cm, tilt ~ 1e-3 rad), so where my
    rigid-body chart and support geometry differ from autobal's at second order in the tilt the
    exponent may differ by ~tilt^2 relative; the integration error is ~1e-9);
  * the orbit's mean residual unbalance (over one revolution, of m0 R0) against `residual`
    (1e-6 absolute);
  * the balancer plane's distance from the axis at the orbit's phase 0 against `amplitude`
    (session 15's finding, with the tilt locked, was "C's distance at phase 0"; with the tilt
    free it is the balancer plane's, 3.5e-4 m from C's here), 1e-7 m;
  * the stable range's lower end (brentq to 1e-10 relative on my exponent) against autobal's
    (1e-7 relative).
Run: .venv/bin/python bench/independent/check_spatial_gravity.py   (~10 min)
"""

from __future__ import annotations

import os
import sys

import numpy as np
from scipy.integrate import solve_ivp

import common
import spatial_model as sm

G = 9.81
ROTOR = dict(mass=32.0, A=0.9, C=0.75, z=0.22)
SUP = [dict(z=0.0, kx=1.8e4, ky=1.8e4, cx=180.0, cy=180.0),
       dict(z=0.45, kx=1.2e4, ky=1.2e4, cx=120.0, cy=120.0)]
PTS = [dict(m=0.30, rho=0.22, ang=0.0, z=0.26)]
PLANES = [dict(z=0.26, R=0.25, masses=[0.18, 0.18], drags=[1.5, 1.5])]


def orbit(S, w, x0=None):
    T = 2 * np.pi / w
    if x0 is None:
        psi = S.balanced_angles()
        sag = -1j * S.mass * G / (SUP[0]["kx"] + SUP[1]["kx"])
        x0 = S.state(psi)
        x0[0], x0[1] = sag.real, sag.imag
        v = -1j * w * sag
        x0[S.N], x0[S.N + 1] = v.real, v.imag
    x, Phi, res = S.periodic_orbit(w, x0, T)
    mu = np.linalg.eigvals(Phi)
    sol = solve_ivp(S.rhs, (0, T), x, method="DOP853", rtol=1e-12, atol=1e-14, args=(w,),
                    dense_output=True)
    ts = np.linspace(0, T, 513)[:-1]
    ys = sol.sol(ts)
    U = sum(S.residual_unbalance(ys[S.nq0:S.nq0 + S.nb, k])[0] for k in range(len(ts))) / len(ts)
    u0 = PTS[0]["m"] * PTS[0]["rho"]
    a = PLANES[0]["z"] - S.zref  # the balancer plane's shaft point at phase 0
    rA = abs(x[0] + a * np.sin(x[3]) + 1j * (x[1] - a * np.cos(x[3]) * np.sin(x[2])))
    return dict(x=x, expo=float(np.log(np.max(np.abs(mu))) / T), resid=abs(U) / u0,
                r0=float(np.hypot(x[0], x[1])), rA=float(rA), tilt=float(np.hypot(x[2], x[3])),
                res=res)


def main():
    ok = True
    S = sm.Spatial(ROTOR, SUP, PTS, PLANES, gravity=(0.0, -G))
    path = os.path.join(common.TMP, "grav_tilt.toml")
    with open(path, "w") as f:
        f.write(sm.toml(ROTOR, SUP, PTS, PLANES, omega=100.0, t_end=1.0, gravity=(0.0, -G)))
    d, err = common.run_json(["stability", "--config", path, "--omega-max", "150 rad/s"])
    pts = [p for p in d["points"] if p["analysed"]]
    worst = dict(expo=0.0, resid=0.0, amp=0.0)
    n = 0
    for p in pts[::5] + [pts[-1]]:
        if p.get("abscissa") is None:
            print(f"  autobal: omega={p['omega']:.6g}: no state ({str(p.get('failure'))[:100]})")
            try:
                o = orbit(S, p["omega"])
                print(f"    mine there: shooting residual {o['res']:.1e}, expo {o['expo']:.6g}, "
                      f"residual {o['resid']:.3g}")
            except Exception as ex:  # noqa: BLE001
                print(f"    mine there: {ex}")
            continue
        w = p["omega"]
        o = orbit(S, w)
        de = abs(o["expo"] - p["abscissa"]) / max(1.0, abs(o["expo"]))
        dr = abs(o["resid"] - p["residual"])
        da = abs(o["rA"] - p["amplitude"])
        n += 1
        if dr > 1e-6:
            print(f"  omega={w:.6g}: another orbit? mine residual {o['resid']:.6g} expo "
                  f"{o['expo']:.7g} (shooting residual {o['res']:.1e}); autobal residual "
                  f"{p['residual']:.6g} expo {p['abscissa']:.7g} state {p['state']}")
            continue
        worst["expo"] = max(worst["expo"], de)
        worst["resid"] = max(worst["resid"], dr)
        worst["amp"] = max(worst["amp"], da)
        if de > 1e-5 or da > 1e-7:
            ok = False
            print(f"  DISAGREE omega={w:.6g}: expo mine {o['expo']:.10g} autobal "
                  f"{p['abscissa']:.10g}; r_A(0) {o['rA']:.9g} (C: {o['r0']:.9g}) vs amplitude {p['amplitude']:.9g}; "
                  f"tilt {o['tilt']:.2e} rad; autobal {p['state']} {p['verdict']}")
    ends = []
    ex = [(p["omega"], p["abscissa"]) for p in pts if p.get("abscissa") is not None]
    for (w1, e1), (w2, e2) in zip(ex, ex[1:]):
        if np.sign(e1) != np.sign(e2):
            from scipy.optimize import brentq
            ends.append(brentq(lambda w: orbit(S, w)["expo"], w1, w2, xtol=1e-12, rtol=1e-11))
    ab = sorted([r["from"] for r in d["stable_ranges"] if r["from_is_boundary"]]
                + [r["to"] for r in d["stable_ranges"] if r["to_is_boundary"]])
    print(f"  stable-range ends: mine {ends}, autobal {ab}")
    if len(ends) != len(ab) or any(abs(a - b) / a > 1e-7 for a, b in zip(ends, ab)):
        ok = False
        print("  *** DISAGREE on the range ends")
    print(f"gravity, tilt free: {n} speeds; worst rel d expo {worst['expo']:.1e}, |d residual| "
          f"{worst['resid']:.1e}, |amplitude - r_A(0)| {worst['amp']:.1e} m; autobal stable ranges "
          f"{[(r['from'], r['to'], r['from_is_boundary'], r['to_is_boundary']) for r in d['stable_ranges']]}"
          f"{' OK' if ok else ' *** DISAGREE'}")
    if err.strip():
        print("   stderr:", err.strip().replace("\n", " | ")[:400])
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
