"""(e) `autobal simulate` on a linear rotor at constant speed: the run against our own
integration of the fixed-axes equations (linear_model.fixed_acc) from the CSV's first row, and
the end state against the balanced state and its verdict.

The rotor: the two-node x,y model of check_linear_aniso case P made isotropic (supports 1e6
N/m, damping 80), balancer at node 0, unbalance at node 1. `stability` finds it stable at
1000 rad/s (largest Re lambda about -1.5 1/s) and unstable at 760 rad/s (+13 1/s: the balanced
state exists there). Runs: `drive.kind = "speed"`, 12 s, integration rtol 1e-10, atol 1e-12.

Checks: (1) the race centre x_0, y_0 (fixed axes) and the ball angles psi_j at t = 0.25, 0.5,
1 s against DOP853 at rtol 1e-12 from the same start: tolerance 1e-6 of the peak radius and
1e-6 rad (two integrators at rtol 1e-10 over ~160 revolutions of a damped system);
(2) at 1000 rad/s the end: psi_j mod 2 pi against the balanced equilibrium's (tolerance 1e-6 rad:
exp(-1.5 x 12) ~ 1.5e-8 of the initial distance is left), `final_radius` below 1e-6 of the peak,
and the residual static unbalance we compute from the end angles; (3) at 760 rad/s the end is not
the balanced state (angles away from it or the race still whirling), as an unstable verdict says.
"""

from __future__ import annotations

import csv
import os
import sys

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, os.path.dirname(__file__))
import linear_model as lm  # noqa: E402
from check_linear_aniso import model  # noqa: E402
from check_linear_shaft import TMP, run, stability  # noqa: E402


def setup():
    M, C, K, G, planes, unb, nodes, tilts, tables = model("P")
    K = K.copy()
    C = C.copy()
    K[1, 1] = K[0, 0]
    C[1, 1] = C[0, 0]
    return M, C, K, G, planes, unb, nodes


def simulate(path, w, t_end, stem):
    import json
    out, err, rc = run(["simulate", "--config", path, "--set", 'drive.kind="speed"',
                        "--set", f"drive.omega0={w}", "--set", f"drive.t_end={t_end}",
                        "--set", "integration.rtol=1e-10", "--set", "integration.atol=1e-12",
                        "--out", stem, "--format", "json"])
    if rc != 0:
        raise RuntimeError(err[-1500:])
    rows = list(csv.DictReader(open(os.path.join(TMP, stem + ".csv"))))
    cols = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    return json.loads(out), cols


def ours(mod, w, psi0, t_eval):
    N, nb = mod.N, mod.nb

    def rhs(t, y):
        q, psi, qd, psid = y[:N], y[N:N + nb], y[N + nb:2 * N + nb], y[2 * N + nb:]
        qdd, psidd = mod.fixed_acc(t, q[:, None], qd[:, None], psi[:, None], psid[:, None], w)
        return np.concatenate([qd, psid, qdd[:, 0], psidd[:, 0]])

    y0 = np.concatenate([np.zeros(N), psi0, np.zeros(N + nb)])
    return solve_ivp(rhs, (0, t_eval[-1]), y0, method="DOP853", rtol=1e-12, atol=1e-15,
                     t_eval=t_eval)


def main():
    M, C, K, G, planes, unb, nodes = setup()
    mod = lm.LinearModel(M, C, K, G, nodes, planes, unb)
    path = lm.write_config(TMP, "sim", M, C, K, G, planes, unb, tilts=False)
    d = stability(path, 1500.0)
    bad = []
    for w, t_end in ((1000.0, 12.0), (760.0, 12.0)):
        pt = min(d["points"], key=lambda p: abs(p["omega"] - w))
        summ, cols = simulate(path, w, t_end, f"sim_{int(w)}")
        t = cols["t"]
        psi0 = np.array([cols[f"psi_{j}"][0] for j in range(mod.nb)])
        if cols["x_0"][0] != 0 or cols["y_0"][0] != 0:
            bad.append(f"w={w}: the run does not start at rest ({cols['x_0'][0]}, {cols['y_0'][0]})")
        te = [0.25, 0.5, 1.0]
        idx = [int(np.argmin(abs(t - x))) for x in te]
        sol = ours(mod, w, psi0, t[idx])
        peak = summ["peak_radius"]
        dx = max(np.hypot(sol.y[0, k] - cols["x_0"][i], sol.y[1, k] - cols["y_0"][i])
                 for k, i in enumerate(idx)) / peak
        dpsi = max(abs(sol.y[mod.N + j, k] - cols[f"psi_{j}"][i])
                   for k, i in enumerate(idx) for j in range(mod.nb))
        if dx > 1e-6 or dpsi > 1e-6:
            bad.append(f"w={w}: trajectory differs: race centre {dx:.2e} of the peak, psi {dpsi:.2e} rad")
        # the end
        s_eq = mod.equilibrium(w)
        ev = mod.eig(w, s_eq).real.max()
        psi_end = np.array([cols[f"psi_{j}"][-1] for j in range(mod.nb)])
        dang = np.abs((psi_end - s_eq[mod.N:mod.N + mod.nb] + np.pi) % (2 * np.pi) - np.pi)
        dang_sw = np.abs((psi_end[::-1] - s_eq[mod.N:mod.N + mod.nb] + np.pi) % (2 * np.pi) - np.pi)
        dang = min(dang.max(), dang_sw.max())
        U = sum(u["me"] * np.exp(1j * u["phase"]) for u in unb)
        res = abs(U + sum(m * planes[0]["R"] * np.exp(1j * p) for m, p in zip(planes[0]["m"], psi_end))) / abs(U)
        rate = [(cols[f"psi_{j}"][-1] - cols[f"psi_{j}"][-11]) / (t[-1] - t[-11]) for j in range(mod.nb)]
        print(f"w={w}: stability says {pt['verdict']} ({pt['abscissa']:.4g}, {pt['state']}), ours max Re "
              f"{ev:.4g}; trajectory to t=1: race centre {dx:.1e} of the peak, psi {dpsi:.1e} rad; "
              f"end: final_radius {summ['final_radius']:.3e} m (peak {peak:.3e}), angles "
              f"{dang:.2e} rad from the balanced state, residual static unbalance {res:.4g} "
              f"(balanced state's {pt['residual']:.4g}), ball rates {np.round(rate, 4)} rad/s",
              flush=True)
        if pt["verdict"] == "stable":
            if dang > 1e-6 or summ["final_radius"] > 1e-6 * peak:
                bad.append(f"w={w}: stable verdict but the run does not end balanced")
        else:
            if dang < 1e-3 and summ["final_radius"] < 1e-6 * peak:
                bad.append(f"w={w}: unstable verdict but the run ends on the balanced state")
    print("ALL AGREE" if not bad else "DISAGREEMENTS")
    for b in bad:
        print("   ", b)
    return not bad


if __name__ == "__main__":
    sys.exit(0 if main() else 1)
