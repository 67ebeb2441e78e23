"""`autobal simulate` on the spatial rotor (tilt free, no gravity, isotropic supports) at a speed
where the balanced state is stable and one where it is unstable, against my own integration of
my equations (spatial_model.py; solve_ivp DOP853 rtol 1e-10, atol 1e-13), from the same start
(C on the axis at rest) and the same rtol:
C on the axis at rest, no tilt, the balls 0.3 rad off their balanced angles.

Compared at the end: the verdict (`balanced`, `outcome`) against my exponent's sign and my end
state; `residual_unbalance` (and `residual_couple` for two planes) against my residual static
(couple) unbalance over the unbalance's; `final_amplitude` (the whirl radius at the balancer plane,
docs/reference/outputs.md) against that plane's shaft point's distance from the axis at the end. Where the balanced state is stable both runs must end balanced (residual below
1e-6 of the unbalance, say, after ~20 e-foldings) and agree on the decay; where it is unstable
the end state is a property of the attractor, compared to ~1e-3 relative (two integrations of
the same equations by different codes diverge on a chaotic transient; a periodic end state must
agree).
Run: .venv/bin/python bench/independent/check_spatial_simulate.py   (~5 min)
"""

from __future__ import annotations

import sys

import numpy as np
from scipy.integrate import solve_ivp

import check_spatial_one_plane as one
import check_spatial_two_plane as two
import common
import spatial_model as sm


def my_run(S, w, psi0, t_end):
    x0 = S.state(psi0)
    sol = solve_ivp(S.rhs, (0.0, t_end), x0, method="DOP853", rtol=1e-10, atol=1e-13,
                    args=(w,), dense_output=True)
    T = 2 * np.pi / w
    ts = np.linspace(t_end - T, t_end, 257)
    ys = sol.sol(ts)
    st, cp = [], []
    u0 = abs(sum(p["m"] * p["rho"] * np.exp(1j * p["ang"]) for p in S.points))
    c0 = abs(sum(p["m"] * p["rho"] * np.exp(1j * p["ang"]) * (p["z"] - S.zref)
                 for p in S.points))
    for k in range(len(ts)):
        u, mz = S.residual_unbalance(ys[S.nq0:S.nq0 + S.nb, k])
        st.append(u)
        cp.append(mz)
    # the shaft point in the first balancer plane (where autobal's final_amplitude is taken)
    a = S.planes[0]["z"] - S.zref
    if S.lock:
        dz = ys[0] + 1j * ys[1]
    else:
        dz = ys[0] + a * np.sin(ys[3]) + 1j * (ys[1] - a * np.cos(ys[3]) * np.sin(ys[2]))
    r = np.abs(dz)
    zf = dz * np.exp(1j * w * ts)  # fixed axes
    mean_f = zf[:-1].mean()
    # autobal's definitions (docs/notes/spatial.md): RMS of |r - mean| over the last revolution
    whirl_about_mean = float(np.sqrt(np.mean(np.abs(zf[:-1] - mean_f) ** 2)))
    # ball_drift: change of a ball's mean angle between the last two revolutions
    prev = sol.sol(ts - T)[S.nq0:S.nq0 + S.nb]
    drift = float(np.max(np.abs(ys[S.nq0:S.nq0 + S.nb, :-1].mean(1) - prev[:, :-1].mean(1))))
    rates = ys[S.N + S.nq0:S.N + S.nq0 + S.nb]
    return dict(resid=abs(np.mean(st)) / u0, couple=abs(np.mean(cp)) / max(c0, 1e-300),
                couple_abs=abs(np.mean(cp)), r_end=float(r[-1]), r_max=float(r.max()),
                psi=ys[S.nq0:S.nq0 + S.nb, -1], drift=float(np.max(np.abs(rates[:, -1]))),
                whirl=whirl_about_mean, mean=mean_f, bdrift=drift)


def run_case(name, rotor, sup, pts, planes, w, t_end):
    S = sm.Spatial(rotor, sup, pts, planes)
    psi_b = S.balanced_angles()
    e, x, _ = sm.exponent(S, w)
    psi0 = psi_b + 0.3
    path = one.write(name, sm.toml(rotor, sup, pts, planes, omega=w, t_end=t_end, psi0=psi0,
                                   dt=1e-3))
    s, err = common.run_json(["simulate", "--config", path, "--out", common.TMP + "/" + name])
    s = s.get("summary", s)
    m = my_run(S, w, psi0, t_end)
    keys = ["outcome", "balanced", "residual_unbalance", "residual_couple", "final_amplitude",
            "ball_drift", "static_sag", "mean_displacement"]
    print(f"{name} at {w} rad/s (my exponent {e:.5g} 1/s, {'stable' if e < 0 else 'unstable'}), "
          f"t_end {t_end} s:")
    print(f"  mine:    residual static {m['resid']:.6g}, couple {m['couple']:.6g} of the "
          f"unbalance's ({m['couple_abs']:.3e} kg m^2), balancer plane's distance from the axis at the "
          f"end {m['r_end']:.6g} m (max over the last rev {m['r_max']:.6g}, RMS about its mean "
          f"{m['whirl']:.6g} (autobal's final_amplitude), |mean| {abs(m['mean']):.6g} (its "
          f"static_sag)), ball drift between the last two revolutions {m['bdrift']:.4g} rad, ball rates at end {m['drift']:.3e} rad/s, angles "
          f"{np.round(np.mod(m['psi'], 2 * np.pi), 6)}")
    print("  autobal: " + ", ".join(f"{k}={s.get(k)}" for k in keys))
    if err.strip():
        print("   stderr:", err.strip().replace("\n", " | ")[:500])
    ok = True
    if e < 0:
        if not (s.get("balanced") and m["resid"] < 1e-6):
            ok = False
            print("  *** DISAGREE: stable balanced state, both should end balanced")
    else:
        if s.get("balanced") or s.get("outcome") == "balanced":
            ok = False
            print("  *** DISAGREE: unstable balanced state reported balanced")
        rel = abs(s.get("residual_unbalance", np.nan) - m["resid"]) / max(m["resid"], 1e-12)
        if not rel < 1e-3:
            print(f"  note: residual differs by {rel:.2e} relative (a chaotic/long transient? see "
                  f"docstring)")
    return ok


def main():
    ok = True
    rotor, sup, pts, planes = one.si_rotor()
    ok &= run_case("sim_one_plane_stable", rotor, sup, pts, planes, 1200.0, 3.0)
    ok &= run_case("sim_one_plane_unstable", rotor, sup, pts, planes, 800.0, 3.0)
    rotor, sup, pts, planes = two.example_rotor()
    ok &= run_case("sim_two_plane_stable", rotor, sup, pts, planes, 1400.0, 3.0)
    ok &= run_case("sim_two_plane_unstable", rotor, sup, pts, planes, 900.0, 3.0)
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
