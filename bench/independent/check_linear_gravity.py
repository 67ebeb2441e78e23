"""(d) Gravity on a linear rotor (`[linear_rotor] gravity = [g_x, g_y]`): the balanced state is a
periodic orbit of one revolution in turning axes (the weight turns there); its Floquet exponents
against `autobal stability`.

The rotor: two nodes with x, y only (3 kg and 1.5 kg joined by 4e5 N/m; isotropic supports
1.15e6 and 2e5 N/m, damping), a two-ball balancer at node 0 and the unbalance at node 0 (case
S) or node 1 (case B), gravity (0, -9.81) (the structure's weight M r_g and the balls' weight
as potentials, linear_model). The orbit by Newton shooting from the gravity-free equilibrium,
followed in g (0, 1/4, ..., 1 of it) at each speed; exponents log|mu|/T, T = 2 pi/W
(DOP853, rtol 1e-11). Tolerance 1e-7 of max(1, |exponent|) 1/s (as check_linear_aniso).
Also the orbit's residual static unbalance (balls plus unbalance over the unbalance, the
resultant averaged over the period at 64 instants, then its modulus; the mean modulus is printed
too) against `residual`: tolerance 1e-6 absolute (it is a
ratio; autobal's averaging rule is not stated in the docs, so a larger difference is reported
as a note, not as a disagreement).
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import linear_model as lm  # noqa: E402
from check_linear_shaft import TMP, stability  # noqa: E402

GRAV = (0.0, -9.81)


def model(case, g=GRAV):
    m0, m1 = 3.0, 1.5
    M = np.diag([m0, m0, m1, m1])
    kc = 4e5
    K = np.array([[kc + 1.15e6, 0, -kc, 0], [0, kc + 1.15e6, 0, -kc], [-kc, 0, kc + 2e5, 0],
                  [0, -kc, 0, kc + 2e5]])
    C = np.diag([100.0, 100.0, 20.0, 20.0]) + 0.5 * K / 1e4
    G = np.zeros((4, 4))
    planes = [dict(node=0, R=0.05, m=[0.03, 0.03], d=[0.05, 0.05], z=0.0)]
    unb = [dict(node=0 if case == "S" else 1, me=1e-3, phase=0.4, z=0.0)]
    return M, C, K, G, planes, unb


def mean_residual(mod, x, w, T):
    U = sum(u["me"] * np.exp(1j * u["phase"]) for u in mod.unb)
    sol = lm.solve_ivp(mod.rot_rhs, (0, T), x, method="DOP853", rtol=1e-11, atol=1e-13,
                       args=(w,), t_eval=np.linspace(0, T, 65)[:-1])
    r = []
    for psi in sol.y[mod.N:mod.N + mod.nb].T:
        tot = U + sum(pl_m * mod.planes[0]["R"] * np.exp(1j * p)
                      for pl_m, p in zip(mod.planes[0]["m"], psi))
        r.append(tot / abs(U))
    return float(np.mean(np.abs(r))), float(abs(np.mean(r)))


def check(case, omega_max=1500.0, n_pts=10):
    M, C, K, G, planes, unb = model(case)
    path = lm.write_config(TMP, "grav_" + case, M, C, K, G, planes, unb, tilts=False,
                           gravity=GRAV)
    d = stability(path, omega_max)
    bad, notes = [], []
    if d.get("stationary_state") != "periodic_orbit":
        bad.append(f"stationary_state {d.get('stationary_state')} (expected periodic_orbit)")
    pts = [p for p in d["points"] if p["abscissa"] is not None]
    idx = np.unique(np.linspace(0, len(pts) - 1, n_pts).round().astype(int))
    worst = 0.0
    nodes = lm.nodes_from_layout(2, tilts=False)
    for k in idx:
        pt = pts[k]
        w = pt["omega"]
        m0 = lm.LinearModel(M, C, K, G, nodes, planes, unb)
        starts = [None]
        if pt.get("state") == "partially_balanced":
            # autobal's partially balanced state: balls bunched; try bunched starts all round
            # and keep the orbit with autobal's residual (the same state), if any
            starts = []
            for a in np.linspace(0, 2 * np.pi, 12, endpoint=False):
                s0 = m0.balanced_guess(w)
                s0[m0.N:m0.N + m0.nb] = a
                starts.append(s0)
        cands = []
        for s0 in starts:
            x = m0.equilibrium(w, s0)
            for lam in (0.25, 0.5, 0.75, 1.0):
                mod = lm.LinearModel(M, C, K, G, nodes, planes, unb, (lam * GRAV[0], lam * GRAV[1]))
                x, mu, ex = mod.periodic_orbit(w, x)
            res_abs, res = mean_residual(mod, x, w, mod.period(w))
            cands.append((abs(res - pt.get("residual", np.nan)), ex, res_abs, res, x))
            if cands[-1][0] < 1e-6:
                break
        _, ex, res_abs, res, x = min(cands, key=lambda c: c[0])
        e = ex.max()
        err = abs(e - pt["abscissa"]) / max(1.0, abs(e))
        worst = max(worst, err)
        print(f"   w={w:.6g}: exponent {e:.10g} autobal {pt['abscissa']:.10g} {pt['verdict']}"
              f" {pt.get('state')}; residual ours |mean| {res:.6g} mean|.| {res_abs:.6g} autobal {pt.get('residual'):.6g}",
              flush=True)
        if err > 1e-7:
            bad.append(f"w={w:.8g}: abscissa {pt['abscissa']:.10g} ours {e:.10g}")
        if pt["verdict"] != ("stable" if e < 0 else "unstable"):
            bad.append(f"w={w:.8g}: verdict {pt['verdict']} ours exponent {e:.3e}")
        if abs(res - pt.get("residual", np.nan)) > 1e-6:
            notes.append(f"w={w:.8g}: residual {pt.get('residual')} ours {res:.6g}")
    print(f"case {case}: {len(idx)} of {len(d['points'])} speeds, worst exponent diff {worst:.2e};"
          f" ranges {[(r['from'], r['to']) for r in d['stable_ranges']]} "
          + ("OK" if not bad else "*** DISAGREE"))
    for b in bad[:12]:
        print("   ", b)
    for b in notes[:6]:
        print("    note:", b)
    return not bad


if __name__ == "__main__":
    ok = True
    for c in sys.argv[1:] or ("S", "B"):
        ok &= check(c)
    print("ALL AGREE" if ok else "DISAGREEMENTS")
    sys.exit(0 if ok else 1)
