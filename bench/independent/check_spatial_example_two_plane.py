"""examples/spatial_two_plane.toml as given (two planes, static + couple unbalance, supports
stiffer vertically, gravity, tilt free): autobal `stability` against an independent derivation
(spatial_model.py). The stationary motion is a periodic orbit (T = 2 pi/w: gravity; the
supports' anisotropy has period pi/w, within it); found by Newton shooting from the static sag
with the balls at their balanced angles; Floquet exponent ln(max|mu|)/T (DOP853 rtol 1e-11).
Checked at 3 of autobal's speeds (exponent: 1e-6 relative to max(1, |expo|), for the reason
given in check_spatial_gravity.py; residual 1e-6 absolute) and the stable range's lower end
(brentq, 1e-7 relative).
Run: .venv/bin/python bench/independent/check_spatial_example_two_plane.py   (~15-30 min)
"""

from __future__ import annotations

import os
import sys

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import common
import spatial_model as sm

G = 9.81
ROTOR = dict(mass=20.0, A=0.6, C=0.15, z=0.25)
SUP = [dict(z=0.0, kx=2.0e6, ky=2.6e6, cx=300.0, cy=300.0),
       dict(z=0.5, kx=3.0e6, ky=3.6e6, cx=300.0, cy=300.0)]
PTS = [dict(m=0.01, rho=0.1, ang=0.0, z=0.45), dict(m=0.01, rho=0.1, ang=2.5, z=0.05)]
PLANES = [dict(z=0.45, R=0.12, masses=[0.02] * 2, drags=[0.5] * 2),
          dict(z=0.05, R=0.12, masses=[0.02] * 2, drags=[0.5] * 2)]


def orbit(S, w):
    T = 2 * np.pi / w
    x0 = S.state(S.balanced_angles())
    # static sag of the two springs (tilt ignored in the guess)
    sag = -1j * S.mass * G / (SUP[0]["ky"] + SUP[1]["ky"])
    x0[0], x0[1] = sag.real, sag.imag
    v = -1j * w * sag
    x0[S.N], x0[S.N + 1] = v.real, v.imag
    x, Phi, res = S.periodic_orbit(w, x0, T, tol=1e-11)
    mu = np.linalg.eigvals(Phi)
    sol = solve_ivp(S.rhs, (0, T), x, method="DOP853", rtol=1e-12, atol=1e-14, args=(w,),
                    dense_output=True)
    ts = np.linspace(0, T, 257)[:-1]
    ys = sol.sol(ts)
    U = sum(S.residual_unbalance(ys[S.nq0:S.nq0 + S.nb, k])[0] for k in range(len(ts))) / len(ts)
    return dict(expo=float(np.log(np.max(np.abs(mu))) / T), res=res,
                resid=abs(U) / abs(sum(p["m"] * p["rho"] * np.exp(1j * p["ang"]) for p in PTS)))


def main():
    ok = True
    S = sm.Spatial(ROTOR, SUP, PTS, PLANES, gravity=(0.0, -G))
    ex = os.path.join(common.ROOT, "examples", "spatial_two_plane.toml")
    d, err = common.run_json(["stability", "--config", ex, "--omega-max", "1500 rad/s"])
    pts = [p for p in d["points"] if p["analysed"] and p.get("abscissa") is not None]
    print(f"autobal: {d['stationary_state']}, {len(pts)} points, stable ranges "
          f"{[(r['from'], r['to'], r['from_is_boundary']) for r in d['stable_ranges']]}, "
          f"residual_scale {d.get('residual_scale')}")
    sel = [min(pts, key=lambda p: abs(p["omega"] - w)) for w in (700.0, 1100.0, 1400.0)]
    for p in sel:
        o = orbit(S, p["omega"])
        de = abs(o["expo"] - p["abscissa"]) / max(1.0, abs(o["expo"]))
        good = de < 1e-6 and o["res"] < 1e-8
        ok &= good
        print(f"  omega={p['omega']:.6g}: expo mine {o['expo']:.10g} autobal {p['abscissa']:.10g} "
              f"(rel {de:.1e}); mean residual mine {o['resid']:.4g} autobal {p['residual']:.4g} "
              f"({d.get('residual_scale')}); shooting residual {o['res']:.1e}; autobal "
              f"{p['state']} {p['verdict']}{' OK' if good else ' *** DISAGREE'}")
    for r in d["stable_ranges"]:
        if r["from_is_boundary"]:
            lo = max(p["omega"] for p in pts if p["omega"] < r["from"])
            hi = min(p["omega"] for p in pts if p["omega"] > r["from"])
            e = brentq(lambda w: orbit(S, w)["expo"], lo, hi, xtol=1e-10, rtol=1e-10)
            rel = abs(e - r["from"]) / e
            ok &= rel < 1e-7
            print(f"  range start: mine {e!r}, autobal {r['from']!r}, rel {rel:.1e}"
                  f"{' OK' if rel < 1e-7 else ' *** DISAGREE'}")
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
