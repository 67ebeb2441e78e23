"""Where `stability` switches from the partially balanced state to the balanced one: is the
stable range's end there a stability boundary?

The isotropic two-node x,y rotor of check_linear_simulate (balancer at node 0, unbalance at node
1; the balls' capacity 0.003 kg m). Between about 570 and 697 rad/s no balanced state exists (the
force the balls must give at node 0 exceeds their capacity) and `stability` analyses the
partially balanced state (balls bunched); above, the balanced state again. We follow, by
Newton continuation in speed with eigenvalues of the exact Jacobian (as check_linear_shaft):
  - the partially balanced state autobal reports at the last grid speed before its range end
    (same residual to 1e-9), past the end;
  - the balanced state from the closed-form start, down to where its balls merge (it ends at
    the capacity).
Then we bisect where each loses stability and compare with autobal's range end and its
`to_is_boundary`. Tolerances as check_linear_shaft (1e-8 of max|lambda| on eigenvalues).
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import linear_model as lm  # noqa: E402
from check_linear_shaft import TMP, stability  # noqa: E402
from check_linear_simulate import setup  # noqa: E402


def main():
    M, C, K, G, planes, unb, nodes = setup()
    mod = lm.LinearModel(M, C, K, G, nodes, planes, unb)
    path = lm.write_config(TMP, "partial", M, C, K, G, planes, unb, tilts=False)
    d = stability(path, 1500.0)
    U = sum(u["me"] * np.exp(1j * u["phase"]) for u in unb)
    res = lambda s: abs(U + sum(m * planes[0]["R"] * np.exp(1j * p)
                                for m, p in zip(planes[0]["m"], s[mod.N:mod.N + mod.nb]))) / abs(U)
    r0 = d["stable_ranges"][0]
    end = r0["to"]
    last = max((p for p in d["points"] if p["omega"] < end), key=lambda p: p["omega"])
    nxt = min((p for p in d["points"] if p["omega"] > end), key=lambda p: p["omega"])
    print(f"autobal: stable {r0['from']:.9g} to {end:.9g} (to_is_boundary {r0['to_is_boundary']}); "
          f"grid {last['omega']} {last['state']} abscissa {last['abscissa']:.6g}, "
          f"{nxt['omega']} {nxt['state']} abscissa {nxt['abscissa']:.6g}")
    # the partially balanced state at the last grid speed: bunched starts, keep autobal's
    w = last["omega"]
    s_pb = None
    for a in np.linspace(0, 2 * np.pi, 24, endpoint=False):
        s0 = mod.balanced_guess(w)
        s0[mod.N:mod.N + mod.nb] = a
        s = mod.equilibrium(w, s0)
        if abs(res(s) - last["residual"]) < 1e-9 and np.abs(mod.rot_rhs(0.0, s, w)).max() < 1e-8:
            s_pb = s
            break
    a = mod.eig(w, s_pb).real.max()
    print(f"  ours at {w}: the same state (residual {res(s_pb):.9g}), max Re {a:.9g}")
    ws = np.arange(w, w + 100.0, 1.0)
    s = s_pb
    lost = None
    prev = (w, a, s)
    for x in ws[1:]:
        s = mod.equilibrium(x, s)
        a = mod.eig(x, s).real.max()
        if a > 0 and lost is None:
            w0, a0, s0 = prev
            lost = lm.bisect(lambda v: mod.eig(v, mod.equilibrium(v, s0)).real.max(), w0, x, a0)
        prev = (x, a, s)
        if lost is None and int(x) % 5 == 0:
            print(f"    {x}: psi {s[mod.N:mod.N + mod.nb] % (2 * np.pi)}, max Re {a:.6g}")
    print(f"  the partially balanced state, followed: stable past {end:.9g}, loses stability at "
          f"{lost:.9g} rad/s (max Re at {end * (1 + 1e-6):.9g}: "
          f"{mod.eig(end * (1 + 1e-6), mod.equilibrium(end * (1 + 1e-6), s_pb)).real.max():.6g})")
    # the balanced state from above, down to its end
    s = mod.equilibrium(nxt["omega"])
    for x in np.linspace(nxt["omega"], end * (1 + 1e-7), 40):
        s = mod.equilibrium(x, s)
    sep = abs((s[mod.N] - s[mod.N + 1] + np.pi) % (2 * np.pi) - np.pi)
    print(f"  the balanced state at {end * (1 + 1e-7):.9g}: balls {sep:.3g} rad apart (merging: it "
          f"begins at the capacity), max Re {mod.eig(end * (1 + 1e-7), s).real.max():.6g}")
    # a run at a speed between the range's end and the loss of stability
    import csv
    from check_linear_shaft import run
    wr = 0.5 * (end + lost)
    out, err, rc = run(["simulate", "--config", path, "--set", 'drive.kind="speed"', "--set",
                        f"drive.omega0={wr}", "--set", "drive.t_end=20", "--out", "partial_run"])
    rows = list(csv.DictReader(open(os.path.join(TMP, "partial_run.csv"))))
    s_w = mod.equilibrium(wr, s_pb)
    for x in np.linspace(end, wr, 20):
        s_pb = mod.equilibrium(x, s_pb)
    psi_end = np.array([float(rows[-1][f"psi_{j}"]) for j in range(mod.nb)])
    dpsi = np.abs((psi_end - s_pb[mod.N:mod.N + mod.nb] + np.pi) % (2 * np.pi) - np.pi).max()
    rate = max(abs(float(rows[-1][f"psi_{j}"]) - float(rows[-101][f"psi_{j}"])) for j in range(mod.nb))
    pt = min(d["points"], key=lambda p: abs(p["omega"] - wr))
    print(f"  simulate at {wr:.6g} rad/s for 20 s: ends {dpsi:.2e} rad from the partially balanced "
          f"state (balls at rest: |dpsi| over the last 100 samples {rate:.1e} rad), race whirl "
          f"{float(rows[-1]['r_0']):.4g} m; stability's nearest grid speed {pt['omega']}: "
          f"{pt['verdict']} ({pt['state']})")
    ok = not r0["to_is_boundary"] or abs(lost - end) < 1e-7 * end
    print("AGREE" if ok else "*** DISAGREE: the range's end is where the analysed state switches "
          "(the balanced state begins, unstable), not where the partially balanced state loses "
          "stability; to_is_boundary is true")
    return ok


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
