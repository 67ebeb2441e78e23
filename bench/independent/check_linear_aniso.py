"""(b) Bearings that differ by direction: the balanced state is a periodic orbit (period pi/W)
in axes turning with the rotor; its Floquet multipliers against `autobal stability`.

The rotor: a 2-element shaft (3 nodes, 12 DOFs), a 4 kg disk, unbalance and two-ball balancer
at node 1 (mid-span, no offsets), so that the balls cancel the unbalance exactly and the
structure stays at rest: the orbit is the constant state (checked: the field vanishes along it
at 7 instants of the period). Cases:
  F: the anisotropy in the K, C files (kxx 2e6, kyy 1.5e6, cxx 300, cyy 500 at both ends);
  T: isotropic files plus a [[linear_rotor.bearings]] table over speed at node 2 with
     kxx != kyy and cross-coupling kxy = -kyx (ROSS's convention assumed: f_x = -kxx x - kxy y),
     constant over its speeds, and the same added to our K, C;
  P: the two-node x,y-only model with a balancer at node 0 and the unbalance at node 1 (a bent
     state: the orbit is found by Newton shooting).
At a subset of autobal's speeds: our largest Floquet exponent log|mu|/T (monodromy by DOP853,
rtol 1e-11) vs `abscissa`: tolerance 1e-7 of max(1, |exponent|) 1/s (the monodromy's
integration error at rtol 1e-11 over one period, amplified by the multipliers' conditioning).
Range ends: our exponent's sign at each reported end x (1 -+ 2e-6) (autobal's ends are bisected
to 1e-9; 2e-6 leaves room for a slope as small as |dexp/dW| ~ 1e-3).
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import linear_model as lm  # noqa: E402
from check_linear_shaft import TMP, stability  # noqa: E402


def model(case):
    if case == "P":
        # two nodes, x and y only: masses 3 and 1.5 kg joined by 4e5 N/m, grounded by
        # direction-dependent springs at node 0 and a spring at node 1
        m0, m1 = 3.0, 1.5
        M = np.diag([m0, m0, m1, m1])
        kc = 4e5
        K = np.array([[kc + 1e6, 0, -kc, 0], [0, kc + 1.3e6, 0, -kc], [-kc, 0, kc + 2e5, 0],
                      [0, -kc, 0, kc + 2e5]])
        C = np.diag([80.0, 120.0, 20.0, 20.0]) + 0.5 * K / 1e4
        G = np.zeros((4, 4))
        planes = [dict(node=0, R=0.05, m=[0.03, 0.03], d=[0.05, 0.05], z=0.0)]
        unb = [dict(node=1, me=1e-3, phase=0.4, z=0.0)]
        return M, C, K, G, planes, unb, lm.nodes_from_layout(2, tilts=False), False, ()
    planes = [dict(node=1, R=0.06, m=[0.02, 0.02], d=[0.1, 0.1], z=0.0)]
    unb = [dict(node=1, me=2e-4, phase=0.0, z=0.0)]
    if case == "F":
        M, C, K, G = lm.shaft(2, 0.5, 0.025, 2.1e11, 7850.0, disks=[(1, 4.0, 0.01, 0.02)],
                              bearings=[(0, 2e6, 1.5e6, 300.0, 500.0), (2, 2e6, 1.5e6, 300.0, 500.0)])
        return M, C + 3.0 * M, K, G, planes, unb, lm.nodes_from_layout(3), True, ()
    M, C, K, G = lm.shaft(2, 0.5, 0.025, 2.1e11, 7850.0, disks=[(1, 4.0, 0.01, 0.02)],
                          bearings=[(0, 2e6, 2e6, 300.0, 300.0)])
    C = C + 3.0 * M
    kxx, kyy, kxy, kyx, cxx, cyy = 2e6, 1.4e6, 3e5, -3e5, 300.0, 450.0
    table = dict(node=2, speeds=[0.0, 1e4], kxx=[kxx] * 2, kyy=[kyy] * 2, kxy=[kxy] * 2,
                 kyx=[kyx] * 2, cxx=[cxx] * 2, cyy=[cyy] * 2)
    Kt, Ct = K.copy(), C.copy()
    i = 8
    Kt[i, i] += kxx
    Kt[i, i + 1] += kxy
    Kt[i + 1, i] += kyx
    Kt[i + 1, i + 1] += kyy
    Ct[i, i] += cxx
    Ct[i + 1, i + 1] += cyy
    return (M, C, K, G, planes, unb, lm.nodes_from_layout(3), True, (table,), Kt, Ct)


def check(case, omega_max, n_pts):
    spec = model(case)
    M, C, K, G, planes, unb, nodes, tilts, tables = spec[:9]
    Km, Cm = (spec[9], spec[10]) if len(spec) > 9 else (K, C)
    path = lm.write_config(TMP, "aniso_" + case, M, C, K, G, planes, unb, tilts=tilts,
                           bearings=tables)
    mod = lm.LinearModel(M, Cm, Km, G, nodes, planes, unb)
    d = stability(path, omega_max)
    bad = []
    if d.get("stationary_state") != "periodic_orbit":
        bad.append(f"stationary_state {d.get('stationary_state')} (expected periodic_orbit)")
    pts = [p for p in d["points"] if p["abscissa"] is not None]
    idx = np.unique(np.linspace(0, len(pts) - 1, n_pts).round().astype(int))
    worst = 0.0
    x_prev = None
    for k in idx:
        pt = pts[k]
        w = pt["omega"]
        x0 = mod.orbit_start(w)
        x_prev = x0
        x, mu, ex = mod.periodic_orbit(w, x0)
        T = mod.period(w)
        F = max(np.abs(mod.rot_rhs(t, x, w)).max() for t in np.linspace(0, T, 7))
        if case != "P" and F > 1e-9:
            bad.append(f"w={w}: the constant state is not an orbit (|F| {F:.1e})")
        e = ex.max()
        err = abs(e - pt["abscissa"]) / max(1.0, abs(e))
        worst = max(worst, err)
        if err > 1e-7:
            bad.append(f"w={w:.8g}: abscissa {pt['abscissa']:.10g} ours {e:.10g}")
        v = "stable" if e < 0 else "unstable"
        print(f"   w={w:.6g}: exponent {e:.10g} autobal {pt['abscissa']:.10g} {pt['verdict']}"
              f" {pt.get('state')} residual {pt.get('residual'):.4g}", flush=True)
        if pt["verdict"] != v:
            bad.append(f"w={w:.8g}: verdict {pt['verdict']} ours {v} ({e:.3e})")
    for r in d["stable_ranges"]:
        for key in ("from", "to"):
            if r.get(key) is None or not r.get(key + "_is_boundary", True):
                continue
            w = r[key]
            signs = []
            for f in (1 - 2e-6, 1 + 2e-6):
                x0 = mod.orbit_start(w * f)
                _, _, ex = mod.periodic_orbit(w * f, x0)
                signs.append(ex.max())
            want = (signs[0] > 0, signs[1] < 0) if key == "from" else (signs[0] < 0, signs[1] > 0)
            if not all(want):
                bad.append(f"range {key} {w:.9g}: our exponents at -+2e-6: {signs}")
    print(f"case {case}: {len(idx)} of {len(d['points'])} speeds, worst exponent diff {worst:.2e};"
          f" ranges {[(r['from'], r['to']) for r in d['stable_ranges']]} "
          + ("OK" if not bad else "*** DISAGREE"))
    for b in bad[:12]:
        print("   ", b)
    return not bad


if __name__ == "__main__":
    todo = {"F": (2500.0, 8), "T": (2500.0, 8), "P": (1500.0, 10)}
    ok = True
    for c in sys.argv[1:] or todo:
        ok &= check(c, *todo[c])
    print("ALL AGREE" if ok else "DISAGREEMENTS")
    sys.exit(0 if ok else 1)
