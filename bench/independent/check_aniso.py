"""Planar Jeffcott rotor with balls on supports that differ by direction (k_x != k_y,
c_x != c_y): autobal `stability` against an independent derivation.

Derivation (planar_model.py): in axes turning with the rotor the support forces depend on
the angle w t, so the equations are periodic with period pi/w. The balanced state (C on the
axis, balls cancelling the unbalance) feels no support force, so it is the same point at every
instant: an equilibrium of a periodic system. Its stability is given by the Floquet
multipliers over pi/w (monodromy of the variational equations, solve_ivp DOP853 rtol 1e-11,
atol 1e-13, with the exact SymPy Jacobian). Checked:
  * the residual of the equations at the balanced state at several instants (< 1e-10);
  * the Floquet exponent ln(max|mu|)/T at every speed autobal sampled against its `abscissa`
    (tolerance 1e-7 relative to the largest |lambda| scale, i.e. |mu| to ~1e-8: the monodromy
    integrated to rtol 1e-11 gives |mu| to ~1e-10, and autobal's neutral band is 1e-8);
  * the stable ranges' ends (bisected to 1e-10) against autobal's (tolerance 1e-8 relative).
Also a limit case: k_x = k_y treated as periodic (T = pi/w), multipliers = exp(lambda T).
Run: .venv/bin/python bench/independent/check_aniso.py   (a few minutes)
"""

from __future__ import annotations

import sys

import numpy as np

import common
import planar_model as pm

RNG = np.random.default_rng(18)


def expo(P, w):
    x, res = P.equilibrium(w)
    T = np.pi / w
    xT, Phi = P.monodromy(w, x, T)
    mu = np.linalg.eigvals(Phi)
    return np.log(max(abs(mu))) / T, x, mu


def check(name, cfg, P, omega_max):
    path = common.planar_toml(name, **cfg)
    d, err = common.run_json(["stability", "--config", path, "--omega-max", str(omega_max)])
    ok = True
    worst = 0.0
    ws, vals = [], []
    for pt in d["points"]:
        if not pt["analysed"]:
            continue
        w = pt["omega"]
        e, x, mu = expo(P, w)
        for tt in (0.1, 0.37, 0.8):
            r = np.max(np.abs(P.rhs(tt * np.pi / w, x, w)))
            if r > 1e-8:
                print(f"  balanced state not at rest at omega={w}: residual {r}")
        diff = abs(e - pt["abscissa"]) / max(1.0, abs(e))
        worst = max(worst, diff)
        if diff > 1e-7:
            ok = False
            print(f"  DISAGREE at omega={w}: my exponent {e:.12g} autobal {pt['abscissa']:.12g}")
        ws.append(w)
        vals.append(e)
    ends = []
    f = lambda w: expo(P, w)[0]
    for i in range(1, len(ws)):
        if np.sign(vals[i]) != np.sign(vals[i - 1]):
            ends.append((pm.bisect(f, ws[i - 1], ws[i], vals[i - 1], tol=1e-10),
                         "enter" if vals[i] < 0 else "leave"))
    ab = []
    for rg in d["stable_ranges"]:
        if rg.get("from_is_boundary"):
            ab.append((rg["from"], "enter"))
        if rg.get("to_is_boundary"):
            ab.append((rg["to"], "leave"))
    we = 0.0
    if len(ab) != len(ends):
        ok = False
        print(f"  DISAGREE: ends mine {ends} autobal {ab}")
    else:
        for (a, ka), (b, kb) in zip(sorted(ends), sorted(ab)):
            rel = abs(a - b) / a
            we = max(we, rel)
            if rel > 1e-8 or ka != kb:
                ok = False
                print(f"  DISAGREE: end mine {a!r} {ka} autobal {b!r} {kb} rel {rel:.1e}")
    print(f"{name}: stationary_state={d['stationary_state']}; exponent worst rel diff {worst:.1e}"
          f" over {len(ws)} speeds; my ends {[f'{e:.10g} {k}' for e, k in ends]}, worst rel diff "
          f"{we:.1e}; autobal {[(r['from'], r['to']) for r in d['stable_ranges']]}"
          f"{' OK' if ok else ' *** DISAGREE'}")
    return ok


def main():
    ok = True
    # limit case: isotropic, treated as periodic by me: multipliers = exp(lambda T)
    P = pm.Planar(1.0, 0.2, 0.003, 0.0, 0.0, 0.06, 104509.44, 104509.44, 50.0, 50.0,
                  [0.03, 0.03], [0.1, 0.1])
    for w in (250.0, 400.0):
        x, _ = P.equilibrium(w)
        lam = P.eig(w, x)
        T = np.pi / w
        _, Phi = P.monodromy(w, x, T)
        mu = np.sort_complex(np.linalg.eigvals(Phi))
        ex = np.sort_complex(np.exp(lam * T))
        print(f"limit k_x = k_y, omega={w}: max |mu - exp(lambda T)| = {np.max(np.abs(mu - ex)):.1e}")
    base = dict(m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06, m3=0.03, c_psi=0.1)
    cases = [("aniso_paper", dict(base, kx=9.0e4, ky=1.2e5, cx=40.0, cy=60.0), 1000.0)]
    for i in range(4):
        m1 = RNG.uniform(0.5, 10)
        s1 = RNG.uniform(5e-4, 5e-3)
        r = RNG.uniform(0.03, 0.15)
        cap = RNG.uniform(1.1, 2.5)
        m3 = cap * m1 * s1 / (2 * r)
        kx = RNG.uniform(2e4, 5e5)
        ky = kx * RNG.uniform(0.5, 2.0)
        cx = RNG.uniform(5, 100)
        cy = cx * RNG.uniform(0.3, 3.0)
        cpsi = RNG.uniform(0.02, 2.0) * m3 * r * r * 100
        cfg = dict(m1=m1, m2=RNG.uniform(0, 2), s1=s1, s2=0.0, gamma=0.0, r=r, m3=m3,
                   c_psi=cpsi, kx=kx, ky=ky, cx=cx, cy=cy)
        wmax = 3.5 * np.sqrt(max(kx, ky) / (m1 + cfg["m2"] + 2 * m3))
        cases.append((f"aniso_random{i}", cfg, float(wmax)))
    for name, cfg, wmax in cases:
        P = pm.Planar(cfg["m1"], cfg["m2"], cfg["s1"], 0.0, 0.0, cfg["r"], cfg["kx"], cfg["ky"],
                      cfg["cx"], cfg["cy"], [cfg["m3"]] * 2, [cfg["c_psi"]] * 2)
        ok &= check(name, cfg, P, wmax)
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
