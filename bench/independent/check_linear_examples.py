"""The shipped examples/linear_rotor_shaft.toml and linear_rotor_windows.toml through our own
shaft: the same physical rotor assembled here (linear_model.shaft: Euler-Bernoulli elements
with consistent mass, rigid disks with their gyroscopic matrix, bearings; the shaft example's
bearing at node 6 tabulated over speed, interpolated linearly and held outside as the docs
say) against `autobal stability` on the example with `modes = 0` (the full model), and with the
elements' rotary inertia and gyroscopic matrices switched off in a copy of the config
(`rotary_inertia = false`, `gyroscopic = false`), which our shaft leaves out (the disks keep
theirs). Every grid speed: max Re lambda vs `abscissa` (1e-8 of max|lambda|; our element
matrices are textbook ones written here, so a difference in the assembly would show as O(1));
range ends by bisection (1e-7 rel.). A second line compares the structure's matrices from
`export-model` with ours (relative Frobenius difference).
"""

from __future__ import annotations

import os
import re
import sys

import numpy as np
import scipy.io

sys.path.insert(0, os.path.dirname(__file__))
import linear_model as lm  # noqa: E402
from check_linear_shaft import ROOT, TMP, run, stability  # noqa: E402

EX = {
    "shaft": dict(file="examples/linear_rotor_shaft.toml", n_el=6, L=0.6, rho=7850.0,
                  disks=[(3, 4.0, 0.01, 0.02)], bear=[(0, 2e6, 300.0)], table=(6, [0.0, 1000.0],
                  [2e6, 3e6], [300.0, 300.0]), planes=[dict(node=3, R=0.06, m=[0.02, 0.02],
                  d=[0.1, 0.1], z=0.0)], unb=[dict(node=3, me=2e-4, phase=0.0, z=0.0)],
                  omega_max=2500.0),
    "windows": dict(file="examples/linear_rotor_windows.toml", n_el=8, L=1.0, rho=7800.0,
                    disks=[(2, 4.0, 0.02, 0.04), (6, 4.0, 0.02, 0.04)],
                    bear=[(0, 5e6, 2000.0), (8, 5e6, 2000.0)], table=None,
                    planes=[dict(node=2, R=0.08, m=[0.03, 0.03], d=[0.05, 0.05], z=0.0)],
                    unb=[dict(node=2, me=2e-4, phase=0.0, z=0.0)], omega_max=2000.0),
}


def config_copy(name, ex):
    src = open(os.path.join(ROOT, ex["file"])).read()
    src = re.sub(r"^rotary_inertia = true", "rotary_inertia = false", src, flags=re.M)
    src = re.sub(r"^gyroscopic = true", "gyroscopic = false", src, flags=re.M)
    src = re.sub(r"^modes = \d+", "modes = 0", src, flags=re.M)
    assert "rotary_inertia = false" in src and "gyroscopic = false" in src and "modes = 0" in src
    path = os.path.join(TMP, name + ".toml")
    open(path, "w").write(src)
    return path


def matrices(ex, w, table=True):
    M, C, K, G = lm.shaft(ex["n_el"], ex["L"], 0.025, 2.1e11, ex["rho"], disks=ex["disks"],
                          bearings=[(n, k, k, c, c) for n, k, c in ex["bear"]])
    if ex["table"] is not None and table:
        n, sp, kk, cc = ex["table"]
        k = np.interp(w, sp, kk)
        c = np.interp(w, sp, cc)
        K[4 * n, 4 * n] += k
        K[4 * n + 1, 4 * n + 1] += k
        C[4 * n, 4 * n] += c
        C[4 * n + 1, 4 * n + 1] += c
    return M, C, K, G


def check(name):
    ex = EX[name]
    path = config_copy(name, ex)
    d = stability(path, ex["omega_max"])
    nodes = lm.nodes_from_layout(ex["n_el"] + 1)
    bad = []
    worst = 0.0
    marg = {}
    prev = None
    for pt in d["points"]:
        w = pt["omega"]
        mod = lm.LinearModel(*matrices(ex, w), nodes, ex["planes"], ex["unb"])
        s = mod.equilibrium(w, prev)
        prev = s
        ev = mod.eig(w, s)
        a = ev.real.max()
        marg[w] = (a, s)
        err = abs(a - pt["abscissa"]) / np.abs(ev).max()
        worst = max(worst, err)
        if err > 1e-8:
            bad.append(f"w={w:.6g}: abscissa {pt['abscissa']:.10g} ours {a:.10g} ({err:.1e})")
    ws = sorted(marg)
    ends = []
    for w0, w1 in zip(ws[:-1], ws[1:]):
        if (marg[w0][0] < 0) != (marg[w1][0] < 0):
            def f(w):
                mod = lm.LinearModel(*matrices(ex, w), nodes, ex["planes"], ex["unb"])
                return mod.eig(w, mod.equilibrium(w, marg[w0][1])).real.max()
            ends.append(lm.bisect(f, w0, w1, marg[w0][0], tol=1e-11))
    theirs = sorted(v for r in d["stable_ranges"] for k_, v in (("from", r["from"]), ("to", r["to"]))
                    if v is not None and r[k_ + "_is_boundary"])
    e_err = (max(abs(a - b) / b for a, b in zip(ends, theirs)) if len(ends) == len(theirs) else None)
    if e_err is None or e_err > 1e-7:
        bad.append(f"ends ours {ends} autobal {theirs}")
    # export-model's matrices vs ours (at speed 0 for the table)
    out, err, rc = run(["export-model", "--config", path, "--out", name + "_exp", "--stem", "r"])
    diffs = {}
    if rc == 0:
        M, C, K, G = matrices(ex, 0.0, table=False)
        for key, A in (("M", M), ("K", K), ("G", G)):
            B = scipy.io.mmread(os.path.join(TMP, name + "_exp", f"r_{key}.mtx"))
            B = B.toarray() if hasattr(B, "toarray") else np.asarray(B)
            diffs[key] = np.linalg.norm(A - B) / np.linalg.norm(A) if np.linalg.norm(A) else np.linalg.norm(B)
    print(f"{ex['file']} (modes 0, element rotary inertia and gyroscopic off): {len(d['points'])} "
          f"speeds, worst |abscissa diff|/max|lambda| {worst:.1e}; ends ours "
          f"{['%.9g' % e for e in ends]} vs {['%.9g' % e for e in theirs]} (rel {e_err if e_err is None else '%.1e' % e_err}); "
          f"export-model vs ours (rel. Frobenius, K without the table's bearing at 0 rad/s) "
          f"{ {k: '%.1e' % v for k, v in diffs.items()} } " + ("OK" if not bad else "*** DISAGREE"))
    for b in bad[:10]:
        print("   ", b)
    return not bad


if __name__ == "__main__":
    ok = True
    for n in sys.argv[1:] or EX:
        ok &= check(n)
    print("ALL AGREE" if ok else "DISAGREEMENTS")
    sys.exit(0 if ok else 1)
