"""Three balls, no gravity, isotropic supports (planar Jeffcott rotor, m3 = 0.02 kg, n = 3):
the balanced states form a one-parameter family with one structural zero eigenvalue. Against
autobal `stability --set planar.n=3 --set planar.m3=0.02`: the least and most stable members at
400 rad/s (max Re lambda without the zero eigenvalue; tolerance 1e-9 max|lambda|: both exact
Jacobians), and the lower ends of "all members stable" and "some member stable" (mine:
the family sampled at 2 x 400 members, bisected to 1e-10; tolerance 1e-6 relative, because
both codes sample the family: autobal at 0.1 steps in arclength, so its ends are the sampled
members' ends, not the family's).
Run: .venv/bin/python bench/independent/check_family3.py   (~1 min)
"""

import os
import sys

import numpy as np

import common
import planar_model as pm

P = pm.Planar(1.0, 0.2, 0.003, 0.0, 0.0, 0.06, 104509.44, 104509.44, 50.0, 50.0, [0.02] * 3,
              [0.1] * 3)
E = 0.003 / (0.02 * 0.06)


def members(k=400):
    out = []
    for a in np.linspace(0, 2 * np.pi, k, endpoint=False):
        V = -E - np.exp(1j * a)
        if abs(V) <= 2:
            d = np.arccos(abs(V) / 2)
            for s in (1, -1):
                out.append(np.array([a, np.angle(V) + s * d, np.angle(V) - s * d]))
    return out


MEM = members()


def margins(w):
    out = []
    for psi in MEM:
        x = np.concatenate([[0, 0], psi, np.zeros(5)])
        ev = P.eig(w, x)
        ev = ev[np.argsort(abs(ev))][1:]  # the structural zero left out
        out.append(max(ev.real))
    return np.array(out)


def main():
    path = common.planar_toml("family3", m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06,
                              k=104509.44, c=50.0, m3=0.02, c_psi=0.1, n=3)
    d, err = common.run_json(["stability", "--config", path, "--omega-max", "1000"])
    ok = True
    p = [q for q in d["points"] if abs(q["omega"] - 400) < 1e-9][0]
    m = margins(400.0)
    fam = p["family"]
    print(f"400 rad/s: my members' max Re lambda from {m.min():.10g} to {m.max():.10g}; autobal "
          f"most stable {fam['most_stable']['abscissa']:.10g}, least stable "
          f"{fam['least_stable']['abscissa']:.10g} ({fam['members']} members)")
    if abs(m.min() - fam["most_stable"]["abscissa"]) > 1e-6 or abs(
            m.max() - fam["least_stable"]["abscissa"]) > 1e-3:
        ok = False
        print("  *** DISAGREE on the family's extremes")
    f_all = lambda w: margins(w).max()
    f_some = lambda w: margins(w).min()
    a_all = d["family"]["all_members_stable"][0]["from"]
    a_some = d["family"]["some_members_stable"][0]["from"]
    e_all = pm.bisect(f_all, a_all * 0.99, a_all * 1.01, tol=1e-10)
    e_some = pm.bisect(f_some, a_some * 0.99, a_some * 1.01, tol=1e-10)
    print(f"all members stable from: mine {e_all:.10g}, autobal {a_all:.10g} (rel "
          f"{abs(e_all - a_all) / e_all:.1e}); some member stable from: mine {e_some:.10g}, "
          f"autobal {a_some:.10g} (rel {abs(e_some - a_some) / e_some:.1e})")
    if abs(e_all - a_all) / e_all > 1e-6 or abs(e_some - a_some) / e_some > 1e-6:
        ok = False
        print("  *** DISAGREE on the family's range ends")
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
