"""Three balls (a family of balanced states) and gravity: the washer of
examples/washing_machine.toml, horizontal (gravity [0, -9.81, 0]) with the tilt locked (so that
the independent planar derivation applies exactly: m1 = 0.3 kg at 0.22 m, m2 = 32 kg, three
0.12 kg balls on R = 0.25 m with drag h_A R^2, k = 3e4 N/m, c = 300 N s/m).

Without gravity the balanced states of three balls form a one-parameter family (a zero
eigenvalue). Gravity turns against the rotor and breaks the family: the balls drift along it
unless they sit where the drift vanishes. Newton shooting (planar_model.py, full steps, from
seven members of the family) finds, at 1400 rpm and at 178.9 rad/s, the same stable orbit
(two balls together) and, from the mirror member, an unstable one.

Compared with `autobal stability --format json` on the same config: whether it finds a state
at those speeds, its verdict, Floquet exponent (`abscissa`) and residual, and the member it
names (`member_psi`). Tolerances: my orbits converge to 1e-13 and the monodromy is integrated
to rtol 1e-11, so exponents are good to ~1e-8 1/s and residuals to ~1e-9; a difference beyond
1e-6 1/s or 1e-7 in the residual is a disagreement.
Run: .venv/bin/python bench/independent/check_family_gravity.py   (about 3 minutes)
"""

from __future__ import annotations

import os
import sys

import numpy as np
from scipy.integrate import solve_ivp

import common
import planar_model as pm

P = pm.Planar(0.3, 32.0, 0.22, 0.0, 0.0, 0.25, 3e4, 3e4, 300.0, 300.0, [0.12] * 3,
              [1.5 * 0.0625] * 3, 0.0, -9.81)
MT = 32.0 + 0.3 + 0.36


def orbit(w, psi):
    T = 2 * np.pi / w
    S = -1j * MT * 9.81 / 3e4
    x = np.array([S.real, S.imag, *psi, (-1j * w * S).real, (-1j * w * S).imag, 0, 0, 0])
    x, Phi, res = P.periodic_orbit(w, x, T, maxit=25)
    mu = np.linalg.eigvals(Phi)
    sol = solve_ivp(P.rhs, (0, T), x, method="DOP853", rtol=1e-12, atol=1e-14, args=(w,),
                    dense_output=True)
    ys = sol.sol(np.linspace(0, T, 1025)[:-1])
    U = 0.066 + 0.03 * np.exp(1j * ys[2:5]).sum(0)
    return dict(res=res, expo=np.log(max(abs(mu))) / T, resid=abs(U.mean()) / 0.066,
                psi=np.mod(x[2:5], 2 * np.pi), maxmu=max(abs(mu)))


def members(k=7):
    out = []
    for a in np.linspace(np.pi - 1.1, np.pi + 1.1, k):
        V = -2.2 - np.exp(1j * a)
        if abs(V) <= 2:
            d = np.arccos(abs(V) / 2)
            out.append([a, np.angle(V) + d, np.angle(V) - d])
    return out


def main():
    src = os.path.join(common.ROOT, "examples", "washing_machine.toml")
    cfg = open(src).read() + "\n[spatial]\ngravity = [0.0, -9.81, 0.0]\nlock_tilt = true\n"
    path = os.path.join(common.TMP, "washer_gravity_locked.toml")
    with open(path, "w") as f:
        f.write(cfg)
    d, err = common.run_json(["stability", "--config", path])
    pts = {round(p["omega"], 6): p for p in d["points"]}
    ok = True
    # the grid speed nearest 1400 rpm, and the first speed where autobal finds a state
    w_op = min(pts, key=lambda w: abs(w - 146.6077))
    w_first = min(w for w, p in pts.items() if p["verdict"] is not None and w > 100)
    for w in (w_op, w_first):
        p = pts[w]
        found = {}
        for psi in members() + [[4.2816, 2.6712, 2.6712]]:
            o = orbit(w, psi)
            if o["res"] < 1e-9:
                key = tuple(np.round(np.sort(o["psi"]), 5))
                found[key] = o
        print(f"omega = {w} rad/s: autobal verdict {p['verdict']}, state {p['state']}, "
              f"abscissa {p['abscissa']}, residual {p['residual']}, member_psi "
              f"{np.round(np.mod(p['member_psi'], 2 * np.pi), 4).tolist()}, failure "
              f"{(p['failure'] or '')[:160]}")
        for key, o in found.items():
            st = "stable" if o["maxmu"] < 1 - 1e-8 else "unstable"
            print(f"   my orbit: balls at {np.round(o['psi'], 5).tolist()} rad, max|mu| "
                  f"{o['maxmu']:.10f} ({st}), exponent {o['expo']:.6e} 1/s, residual "
                  f"{o['resid']:.4e}")
        stable = [o for o in found.values() if o["maxmu"] < 1 - 1e-8]
        if p["verdict"] is None and stable:
            ok = False
            print("   *** DISAGREE: autobal finds no stationary state; a stable balanced orbit "
                  "exists")
        elif p["verdict"] is not None:
            if not any(abs(o["expo"] - p["abscissa"]) < 1e-6 and abs(o["resid"] - p["residual"])
                       < 1e-7 for o in found.values()):
                ok = False
                print("   *** DISAGREE: autobal's exponent/residual match none of my orbits")
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
