"""(d') Gravity on a shaft with tilts: the 3-element shaft of check_linear_shaft (case A,
balancer and unbalance at node 1, no offsets, and case B, race offset 0.02 m, unbalance at
node 2) with `gravity = [0, -9.81]`. Our model twice: with the balls' weight potential kept to
second order in the tilt, like their kinetic energy, and to first order only (the weight on the
race centre and its torque on the ball, as docs/guide/your-own-rotor.md describes the model's
gravity). Floquet exponents (T = 2 pi/W, DOP853 rtol 1e-11, shooting from the gravity-free
equilibrium followed in g) against `abscissa` at 4 speeds; tolerance 1e-7 of max(1, |exp|).
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import linear_model as lm  # noqa: E402
from check_linear_shaft import CASES, TMP, shaft_model, stability  # noqa: E402

GRAV = (0.0, -9.81)


def check(case, speeds):
    M, C, K, G = shaft_model()
    spec = CASES[case]
    path = lm.write_config(TMP, "gtilt_" + case, M, C, K, G, spec["planes"], spec["unb"],
                           gravity=GRAV)
    d = stability(path, 2500.0)
    nodes = lm.nodes_from_layout(4)
    ok = True
    for w0 in speeds:
        pt = min((p for p in d["points"] if p["abscissa"] is not None),
                 key=lambda p: abs(p["omega"] - w0))
        w = pt["omega"]
        out = []
        for grav2 in (True, False):
            x = None
            for lam in np.linspace(0.0, 1.0, 11) if spec["planes"][0].get("z") else (0.0,):
                pl = [dict(p_, z=lam * p_.get("z", 0.0)) for p_ in spec["planes"]]
                un = [dict(u, z=lam * u.get("z", 0.0)) for u in spec["unb"]]
                x = lm.LinearModel(M, C, K, G, nodes, pl, un).equilibrium(w, x)
            for lam in (0.5, 1.0):
                mod = lm.LinearModel(M, C, K, G, nodes, spec["planes"], spec["unb"],
                                     (lam * GRAV[0], lam * GRAV[1]), grav2=grav2)
                x, mu, ex = mod.periodic_orbit(w, x)
            out.append(ex.max())
        e2, e1 = out
        err = min(abs(e - pt["abscissa"]) for e in out) / max(1.0, abs(e1))
        which = "first order" if abs(e1 - pt["abscissa"]) <= abs(e2 - pt["abscissa"]) else "second order"
        good = err < 1e-7
        ok &= good
        print(f"case {case} w={w:.6g}: autobal {pt['abscissa']:.12g} ({pt['verdict']}, {pt['state']}); ours "
              f"weight to 2nd order {e2:.12g}, to 1st order {e1:.12g}: nearest {which}, "
              f"diff {err:.1e} " + ("OK" if good else "*** DISAGREE"), flush=True)
    return ok


if __name__ == "__main__":
    ok = check("A", (600.0, 1200.0)) & check("B", (600.0, 2000.0))
    print("ALL AGREE" if ok else "DISAGREEMENTS")
    sys.exit(0 if ok else 1)
