"""(a) An isotropic linear rotor from matrix files: the balanced state and its eigenvalues in
axes turning with the rotor, against `autobal stability --format json`.

The rotor: a 3-element Euler-Bernoulli steel shaft built here (linear_model.shaft: 4 nodes,
16 DOFs x, y, alpha, beta), two disks, isotropic damped bearings at the ends, damping 3 M added,
written as .npy files (layout "x,y,alpha,beta"). Cases:
  A: unbalance and a two-ball balancer at node 1, no offsets;
  B: balancer at node 1 with axial offset 0.02 m (the race plane's tilt terms act), unbalance
     at node 2 with offset -0.01 m and phase 0.7 (a balanced state with the shaft bent);
  C: as A with unequal drag per the docs' one `drag` key (not possible: one drag per plane) ->
     instead a lighter ball mass and a 10x smaller drag.
Per speed of autobal's grid: max Re lambda of the exact Jacobian (complex step, round-off
exact) vs `abscissa` (tolerance 1e-8 of max|lambda|: the eigenvalues of a 36x36 Jacobian
whose entries are computed to ~1e-15 relative carry ~1e-12 relative error, and a speed's grid
value is printed to 17 digits), the verdict words, `state` and `residual`; the ranges' bisected
ends vs ours (tolerance 1e-7 relative: autobal bisects to 1e-9 per the docs, we to 1e-11, and
the margin's slope at a crossing can be small).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import linear_model as lm  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
AUTOBAL = os.environ.get("AUTOBAL", os.path.join(ROOT, "target", "release", "autobal"))
TMP = tempfile.mkdtemp(prefix="autobal_lin_")


def run(args):
    p = subprocess.run([AUTOBAL, *args], capture_output=True, text=True, cwd=TMP)
    return p.stdout, p.stderr, p.returncode


def stability(path, omega_max, extra=()):
    out, err, rc = run(["stability", "--config", path, "--format", "json",
                        "--omega-max", f"{omega_max} rad/s", *extra])
    if rc != 0:
        raise RuntimeError(f"rc {rc}: {err[-1500:]}")
    return json.loads(out)


def shaft_model():
    M, C, K, G = lm.shaft(3, 0.6, 0.025, 2.1e11, 7850.0,
                          disks=[(1, 4.0, 0.01, 0.02), (2, 2.0, 0.005, 0.01)],
                          bearings=[(0, 2e6, 2e6, 300.0, 300.0), (3, 2e6, 2e6, 300.0, 300.0)])
    return M, C + 3.0 * M, K, G


CASES = {
    "A": dict(planes=[dict(node=1, R=0.06, m=[0.02, 0.02], d=[0.1, 0.1], z=0.0)],
              unb=[dict(node=1, me=2e-4, phase=0.0, z=0.0)]),
    "B": dict(planes=[dict(node=1, R=0.06, m=[0.02, 0.02], d=[0.1, 0.1], z=0.02)],
              unb=[dict(node=2, me=2e-4, phase=0.7, z=-0.01)]),
    "C": dict(planes=[dict(node=1, R=0.05, m=[0.012, 0.012], d=[0.01, 0.01], z=0.0)],
              unb=[dict(node=1, me=1e-4, phase=-1.0, z=0.0)]),
    # (c) two balancer planes, each with the unbalance at its node (phases apart): the balanced
    # state has the shaft at rest; and a variant with the race planes offset
    "D": dict(planes=[dict(node=1, R=0.06, m=[0.02, 0.02], d=[0.1, 0.1], z=0.0),
                      dict(node=2, R=0.05, m=[0.015, 0.015], d=[0.05, 0.05], z=0.0)],
              unb=[dict(node=1, me=2e-4, phase=0.0, z=0.0), dict(node=2, me=1e-4, phase=2.0, z=0.0)]),
    "E": dict(planes=[dict(node=1, R=0.06, m=[0.02, 0.02], d=[0.1, 0.1], z=0.01),
                      dict(node=2, R=0.05, m=[0.015, 0.015], d=[0.05, 0.05], z=-0.015)],
              unb=[dict(node=1, me=2e-4, phase=0.0, z=0.0), dict(node=2, me=1e-4, phase=2.0, z=0.0)]),
}


def residual(mod, s):
    U = sum(u["me"] * np.exp(1j * u["phase"]) for u in mod.unb)
    k = mod.N
    tot = U
    for pl in mod.planes:
        for mj in pl["m"]:
            tot += mj * pl["R"] * np.exp(1j * s[k])
            k += 1
    return abs(tot) / abs(U)


def check_case(name, spec, omega_max=2500.0):
    M, C, K, G = shaft_model()
    path = lm.write_config(TMP, name, M, C, K, G, spec["planes"], spec["unb"])
    mod = lm.LinearModel(M, C, K, G, lm.nodes_from_layout(4), spec["planes"], spec["unb"])
    assert mod.autonomous()
    d = stability(path, omega_max)
    worst = 0.0
    bad = []
    s_prev = None
    margins = {}
    states = {}
    for pt in d["points"]:
        w = pt["omega"]
        if s_prev is None:
            # homotopy in the offsets from the exactly balanced start with offsets 0
            for lam in np.linspace(0.0, 1.0, 11):
                pl = [dict(p_, z=lam * p_.get("z", 0.0)) for p_ in spec["planes"]]
                un = [dict(u, z=lam * u.get("z", 0.0)) for u in spec["unb"]]
                mh = lm.LinearModel(M, C, K, G, lm.nodes_from_layout(4), pl, un)
                s_prev = mh.equilibrium(w, s_prev)
        s = mod.equilibrium(w, s_prev)
        F = np.abs(mod.rot_rhs(0.0, s, w)).max()
        ev = mod.eig(w, s)
        a = ev.real.max()
        scale = np.abs(ev).max()
        margins[w] = a
        states[w] = s
        s_prev = s
        if pt["abscissa"] is None:
            bad.append(f"w={w}: autobal no abscissa ({pt.get('failure')}), ours {a:.6g}")
            continue
        err = abs(pt["abscissa"] - a) / scale
        worst = max(worst, err)
        if err > 1e-8:
            bad.append(f"w={w:.6g}: abscissa {pt['abscissa']:.10g} ours {a:.10g} (rel {err:.2e})")
        verdict = "stable" if a < -1e-9 * scale else ("unstable" if a > 1e-9 * scale else "neutral")
        if pt["verdict"] != verdict and pt["verdict"] != "neutral" and verdict != "neutral":
            bad.append(f"w={w:.6g}: verdict {pt['verdict']} ours {verdict} (a={a:.3e})")
        res = residual(mod, s)
        if pt.get("state") != "balanced" or abs(pt.get("residual", 0) - res) > 1e-6:
            bad.append(f"w={w:.6g}: state {pt.get('state')} residual {pt.get('residual')} ours {res:.3e}"
                       f" (F={F:.1e})")
    # ranges: our sign changes on the grid, bisected
    ws = [pt["omega"] for pt in d["points"]]
    ends = []
    for w0, w1 in zip(ws[:-1], ws[1:]):
        if (margins[w0] < 0) != (margins[w1] < 0):
            def f(w):
                s = mod.equilibrium(w, states[w0])
                return mod.eig(w, s).real.max()
            ends.append(lm.bisect(f, w0, w1, margins[w0], tol=1e-11))
    theirs = []
    for r in d["stable_ranges"]:
        lo, hi = (r["from"], r["to"]) if isinstance(r, dict) else r
        for v, isb in ((lo, r.get("from_is_boundary", True) if isinstance(r, dict) else True),
                       (hi, r.get("to_is_boundary", True) if isinstance(r, dict) else True)):
            if v is not None and isb:
                theirs.append(v)
    ends_err = None
    if len(theirs) == len(ends):
        ends_err = max((abs(a - b) / b for a, b in zip(sorted(theirs), ends)), default=0.0)
        if ends_err > 1e-7:
            bad.append(f"range ends {sorted(theirs)} ours {ends}")
    else:
        bad.append(f"range ends {sorted(theirs)} (ranges {d['stable_ranges']}) ours {ends}")
    # natural frequencies at rest with the balls as rings (mass n m at the race centre,
    # I_d = n m R^2 / 2): against `natural_frequencies` (tolerance 1e-9 relative: a generalised
    # symmetric eigenproblem of 16 DOFs, condition well below 1e6)
    import scipy.linalg as sla
    Mr = M.copy()
    nodes = lm.nodes_from_layout(4)
    for pl in spec["planes"]:
        nd = nodes[pl["node"]]
        mb = sum(pl["m"])
        Mr[nd.ix, nd.ix] += mb
        Mr[nd.iy, nd.iy] += mb
        Mr[nd.ia, nd.ia] += mb * pl["R"] ** 2 / 2
        Mr[nd.ib, nd.ib] += mb * pl["R"] ** 2 / 2
        z = pl.get("z", 0.0)  # the ring at axial offset z: its centre at x + z beta, y - z alpha
        Mr[nd.ix, nd.ib] += mb * z
        Mr[nd.ib, nd.ix] += mb * z
        Mr[nd.ib, nd.ib] += mb * z * z
        Mr[nd.iy, nd.ia] -= mb * z
        Mr[nd.ia, nd.iy] -= mb * z
        Mr[nd.ia, nd.ia] += mb * z * z
    fn = np.sqrt(sla.eigh(K, Mr, eigvals_only=True))
    theirs_fn = np.array(d.get("natural_frequencies", []))
    fn_err = np.max(np.abs(fn[:len(theirs_fn)] - theirs_fn) / theirs_fn) if len(theirs_fn) else np.nan
    if not fn_err < 1e-9:
        bad.append(f"natural frequencies {theirs_fn} ours {fn[:len(theirs_fn)]}")
    print(f"case {name}: natural frequencies (balls as rings, {len(theirs_fn)}) rel. diff {fn_err:.1e}")
    print(f"case {name}: {len(d['points'])} speeds, worst |abscissa diff|/max|lambda| {worst:.2e}; "
          f"ends ours {['%.9g' % e for e in ends]} vs {['%.9g' % e for e in sorted(theirs)]}"
          f" (rel {ends_err if ends_err is None else '%.1e' % ends_err}) "
          + ("OK" if not bad else "*** DISAGREE"))
    for b in bad[:12]:
        print("   ", b)
    return not bad, d


if __name__ == "__main__":
    ok = True
    for name in sys.argv[1:] or CASES:
        good, _ = check_case(name, CASES[name])
        ok &= good
    print("ALL AGREE" if ok else "DISAGREEMENTS")
    sys.exit(0 if ok else 1)
