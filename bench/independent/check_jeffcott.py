"""Planar Jeffcott rotor with a ball balancer (race centred, isotropic supports): autobal
`stability` against an independent derivation (planar_model.py: SymPy Lagrange equations,
exact Jacobian, numpy eigvals, ranges bisected to 1e-11).

Checks, per configuration (paper 004's numbers with s2 = 0 and four ball drags, then random
ones, some with balls of unequal mass and drag):
  * the balanced state's ball angles (closed form / Newton) against autobal's `member_psi`;
  * max Re(lambda) at every speed autobal sampled against its `abscissa`
    (tolerance 1e-9 * max|lambda|: autobal's own neutral tolerance, far above the
    eigenvalue round-off eps * ||A|| ~ 1e-11 * max|lambda| of either code);
  * the stable ranges' ends against autobal's `stable_ranges` (tolerance 1e-8 relative:
    autobal claims 1e-9, mine are bisected to 1e-11; the margin's slope turns the
    eigenvalue round-off into < 1e-10 on the speed).
Run: .venv/bin/python bench/independent/check_jeffcott.py   (about a minute)
"""

from __future__ import annotations

import sys

import numpy as np

import common
import planar_model as pm

RNG = np.random.default_rng(20261129)


def my_margin(P, w):
    x, res = P.equilibrium(w)
    ev = P.eig(w, x)
    return ev, x, res


def my_ranges(P, ws):
    """Stable ranges over the grid ws, ends bisected."""
    f = lambda w: max(my_margin(P, w)[0].real)
    vals = [f(w) for w in ws]
    ends = []
    for i in range(1, len(ws)):
        if np.sign(vals[i]) != np.sign(vals[i - 1]):
            ends.append((pm.bisect(f, ws[i - 1], ws[i], vals[i - 1], tol=1e-11),
                         "enter" if vals[i] < 0 else "leave"))
    return vals, ends


def check(name, cfg, omega_max, P):
    path = common.planar_toml(name, **cfg)
    d, err = common.run_json(["stability", "--config", path, "--omega-max", str(omega_max)])
    ok = True
    g = P.balanced_guess()[1]
    mp = np.array(d["member_psi"])
    dpsi = np.angle(np.exp(1j * (mp - g)))
    worst_ev = 0.0
    for pt in d["points"]:
        if not pt["analysed"]:
            continue
        ev, x, res = my_margin(P, pt["omega"])
        scale = max(abs(ev))
        diff = abs(max(ev.real) - pt["abscissa"]) / scale
        worst_ev = max(worst_ev, diff)
        if diff > 1e-9:
            ok = False
            print(f"  DISAGREE at omega={pt['omega']}: mine {max(ev.real):.12g} autobal "
                  f"{pt['abscissa']:.12g} (rel {diff:.2e})")
    ws = np.array([pt["omega"] for pt in d["points"]])
    vals, ends = my_ranges(P, ws)
    # autobal's ranges -> ends
    ab_ends = []
    for rg in d["stable_ranges"]:
        if rg.get("from_is_boundary"):
            ab_ends.append((rg["from"], "enter"))
        if rg.get("to_is_boundary"):
            ab_ends.append((rg["to"], "leave"))
    worst_end = 0.0
    if len(ab_ends) != len(ends):
        ok = False
        print(f"  DISAGREE: range ends mine {ends} autobal {ab_ends}")
    else:
        for (a, ka), (b, kb) in zip(sorted(ends), sorted(ab_ends)):
            rel = abs(a - b) / abs(a)
            worst_end = max(worst_end, rel)
            if rel > 1e-8 or ka != kb:
                ok = False
                print(f"  DISAGREE: end mine {a!r} ({ka}) autobal {b!r} ({kb}) rel {rel:.2e}")
    print(f"{name}: psi diff {np.max(np.abs(dpsi)):.1e} rad; max Re lambda worst rel diff "
          f"{worst_ev:.1e} over {len(ws)} speeds; ends mine "
          f"{[f'{e:.10g} {k}' for e, k in sorted(ends)]}, worst rel diff {worst_end:.1e}; "
          f"autobal ranges {[(r['from'], r['to']) for r in d['stable_ranges']]}"
          f"{' OK' if ok else ' *** DISAGREE'}")
    neutral = [pt["omega"] for pt in d["points"] if pt["verdict"] == "neutral"]
    if neutral:
        nv = [max(my_margin(P, w)[0].real) for w in neutral]
        print(f"  autobal 'neutral' at {neutral}: my max Re lambda there {nv}")
    if err.strip():
        print("  stderr:", err.strip().replace("\n", " | "))
    return ok


def main():
    all_ok = True
    base = dict(m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06, k=104509.44, c=50.0,
                m3=0.03)
    # ball-drag dependence of the lowest stable speed (paper 004's drags)
    for cpsi in [0.004, 0.01, 0.1, 0.4]:
        cfg = dict(base, c_psi=cpsi)
        P = pm.Planar(1.0, 0.2, 0.003, 0.0, 0.0, 0.06, 104509.44, 104509.44, 50.0, 50.0,
                      [0.03, 0.03], [cpsi, cpsi])
        all_ok &= check(f"jeffcott_cpsi{cpsi}", cfg, 1500.0, P)
    # random configurations
    for i in range(6):
        m1 = RNG.uniform(0.5, 20)
        m2 = RNG.uniform(0.0, 5)
        s1 = RNG.uniform(1e-4, 5e-3)
        r = RNG.uniform(0.02, 0.2)
        cap = RNG.uniform(1.1, 3.0)  # capacity / unbalance
        k = RNG.uniform(1e4, 1e6)
        c = RNG.uniform(1.0, 200.0)
        if i % 2 == 0:
            mb = [cap * m1 * s1 / (2 * r)] * 2
            db = [RNG.uniform(1e-4, 0.5) * mb[0] * r * r * 100] * 2
            cfg = dict(m1=m1, m2=m2, s1=s1, s2=0.0, gamma=0.0, r=r, k=k, c=c, m3=mb[0],
                       c_psi=db[0])
        else:
            f = RNG.uniform(0.6, 0.9)
            tot = cap * m1 * s1 / r
            mb = [f * tot / (1 + f) * 1.0, tot / (1 + f)]
            db = list(RNG.uniform(1e-4, 0.5, 2) * np.array(mb) * r * r * 100)
            cfg = dict(m1=m1, m2=m2, s1=s1, s2=0.0, gamma=0.0, r=r, k=k, c=c, ball_masses=mb,
                       ball_drags=db)
        P = pm.Planar(m1, m2, s1, 0.0, 0.0, r, k, k, c, c, mb, db)
        wn = np.sqrt(k / (m1 + m2 + sum(mb)))
        all_ok &= check(f"random{i}", cfg, float(4 * wn), P)
    print("ALL AGREE" if all_ok else "SOME DISAGREE")
    return 0 if all_ok else 1


if __name__ == "__main__":
    sys.exit(main())
