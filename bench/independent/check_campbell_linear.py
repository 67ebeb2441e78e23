"""`autobal campbell` on the linear rotor route against linear_model.py (the balls' Lagrangian by
SymPy, complex-step Jacobian in turning axes, numpy eig). Comparison rules and tolerances:
check_campbell_common.py; the eigenvalue bound is 1e-8 of max|lambda| here (as
check_linear_shaft.py: the complex-step Jacobian is exact to rounding, but the 3-element
shaft's spectrum spans 1e-9..1e5, so eig's absolute error ~1e-16 ||A|| ~ 1e-9 max|lambda|).

Cases:
  L1  check_linear_shaft.py's case A: a 3-element shaft (.npy matrices, C + 3 M damping, two
      disks, isotropic bearings), balancer and unbalance at node 1;
  L2  examples/linear_rotor_shaft.toml with `modes = 0` and the elements' rotary inertia and
      gyroscopic matrices off (the bearing at node 6 tabulated over speed), our shaft as in
      check_linear_examples.py.
Shares: every node's x + i y and alpha + i beta, each weighted by sqrt of the pair's mean
diagonal mass (docs/reference/outputs.md: w_p^2 = M_p / M_s; the common 1/M_s cancels in the
ratio; the balls' mass is not in M), checked to 1e-6 as the other routes' shares. Until share18
autobal's eigenvectors on this route were mixed by its solver's pivot floor (0.29 apart on L2
where two modes are 2 Omega = 25 rad/s apart), so they were only printed; the formula here was
right (autobal's own Jacobian gives the same shares through numpy's eig).
Run: .venv/bin/python bench/independent/check_campbell_linear.py [L1 L2]   (~3 min)
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import check_campbell_common as cc  # noqa: E402
import common  # noqa: E402
import linear_model as lm  # noqa: E402
from check_linear_shaft import CASES, shaft_model  # noqa: E402
from check_linear_shaft import TMP as LTMP  # noqa: E402


def pairs_of(M, nodes, mod=None):
    M = M.copy()
    if mod is not None and BALLS_IN_WEIGHT:
        for nd, m, R, z, dd in mod.balls:
            M[nd.ix, nd.ix] += m
            M[nd.iy, nd.iy] += m
    out = []
    for nd in nodes:
        for a, b in ((nd.ix, nd.iy), (nd.ia, nd.ib)):
            if a is not None:
                out.append((a, b, float(np.sqrt(0.5 * (M[a, a] + M[b, b])))))
    return out


BALLS_IN_WEIGHT = os.environ.get("BALLS_IN_WEIGHT", "0") == "1"


def groups_of(mod, M, nodes):
    tr = [(nd.ix, float(np.sqrt(M[nd.ix, nd.ix]))) for nd in nodes] + \
         [(nd.iy, float(np.sqrt(M[nd.iy, nd.iy]))) for nd in nodes]
    ti = [(nd.ia, float(np.sqrt(M[nd.ia, nd.ia]))) for nd in nodes if nd.ia is not None] + \
         [(nd.ib, float(np.sqrt(M[nd.ib, nd.ib]))) for nd in nodes if nd.ib is not None]
    balls = [(mod.N + k, float(np.sqrt(b[1])) * b[2]) for k, b in enumerate(mod.balls)]
    return {"translation": tr, "tilt": ti, "balls": balls}


def linear_group(en):
    # autobal's groups on the linear route are not defined in the docs; only the balls' label
    # is checked (translation and tilt weights there are autobal's own choice)
    g = cc.group_by_energy(en)
    if g is None:
        return None
    return "balls" if g == "balls" else None


def run_case(name, path, model_at, nodes, M0, extra=(), fine=600):
    d, _ = common.run_json(["campbell", "--config", path, *extra])
    specs, xs = {}, {}
    sp = None
    for j, w in enumerate(d["omega"]):
        if not d["analysed"][j] or d["failures"][j] is not None:
            continue
        mod = model_at(w)
        s = mod.equilibrium(w, sp)
        sp = s
        lam, V = np.linalg.eig(mod.jac(0.0, s, w))
        specs[j] = cc.Spec(w, lam, V, pairs_of(M0, nodes, mod), groups_of(mod, M0, nodes))
        xs[j] = s
    # shares checked to 1e-6 (check_campbell_common's rule: an eigenvector's direction is
    # good to eps / gap, near-double values skipped); until share18 they differed by up to
    # 1.3e-4 (L1) and 0.29 (L2) through autobal's unbalanced inverse iteration, not the formula
    bad, st = cc.compare_lines(d, specs, tol=1e-8, tol_near=1e-7, check_groups=linear_group,
                               label=name)
    bad2, nm = cc.compare_modes(d, specs, label=name)
    js = sorted(specs)

    def near(w):
        j = min(js, key=lambda i: abs(d["omega"][i] - w))
        mod = model_at(w)
        return mod, mod.equilibrium(w, xs[j])

    def spec_fn(w):
        mod, s = near(w)
        return np.linalg.eigvals(mod.jac(0.0, s, w))

    mine = cc.critical_events(spec_fn, d["omega"][js[0]], d["omega"][js[-1]], n=800)
    notes = []
    bad3, worst_c, nth = cc.compare_criticals(d, mine, label=name, notes=notes,
                                               spec_fn=spec_fn)
    allbad = bad + bad2 + bad3
    print(f"{name}: {len(specs)} speeds {d['omega'][js[0]]:.6g}-{d['omega'][js[-1]]:.6g}, "
          f"{st['points']} line points: eigenvalues worst {st['worst']:.1e} of max|lambda| "
          f"(near-double {st['worst_near']:.1e}); shares ({st['shares']}) worst "
          f"{st['worst_share']:.1e}; log dec worst {st['worst_logdec']:.1e}; {nm} mode points; "
          f"critical speeds autobal {nth}, mine {len(mine)}, worst {worst_c:.1e} rel. "
          + ("OK" if not allbad else "*** DISAGREE"))
    for b in notes:
        print("    note:", b)
    for b in allbad[:25]:
        print("   ", b)
    if len(allbad) > 25:
        print(f"    ... {len(allbad) - 25} more")
    ok = not allbad
    if fine:
        d2, _ = common.run_json(["campbell", "--config", path, "--points", str(fine), *extra])

        def vec_fn(w):
            mod, s = near(w)
            return np.linalg.eig(mod.jac(0.0, s, w))

        bad4, n = cc.track_check(d2, vec_fn, label=name + " tracking")
        print(f"{name} tracking ({fine} speeds): {n} line steps checked by eigenvector overlap "
              + ("OK" if not bad4 else f"*** {len(bad4)} steps jump"))
        for b in bad4[:10]:
            print("   ", b)
        ok &= not bad4
    return ok


def case_L1():
    M, C, K, G = shaft_model()
    spec = CASES["A"]
    path = lm.write_config(LTMP, "campA", M, C, K, G, spec["planes"], spec["unb"])
    nodes = lm.nodes_from_layout(4)
    mod = lm.LinearModel(M, C, K, G, nodes, spec["planes"], spec["unb"])
    return run_case("L1 3-element shaft (case A)", path, lambda w: mod, nodes, M,
                    ("--omega-max", "2500 rad/s"))


def case_L2():
    from check_linear_examples import EX, config_copy, matrices
    ex = EX["shaft"]
    path = config_copy("camp_shaft", ex)
    nodes = lm.nodes_from_layout(ex["n_el"] + 1)
    M0 = matrices(ex, 0.0)[0]
    return run_case("L2 examples/linear_rotor_shaft.toml (modes 0)", path,
                    lambda w: lm.LinearModel(*matrices(ex, w), nodes, ex["planes"], ex["unb"]),
                    nodes, M0, ("--omega-max", f"{ex['omega_max']} rad/s"))


if __name__ == "__main__":
    ok = True
    for c in sys.argv[1:] or ["L1", "L2"]:
        ok &= {"L1": case_L1, "L2": case_L2}[c]()
    print("ALL AGREE" if ok else "DISAGREEMENTS")
    sys.exit(0 if ok else 1)
