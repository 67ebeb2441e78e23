"""`autobal campbell` on the spatial rotor with the tilt free against the independent derivation
spatial_model.py (SymPy Lagrange equations in turning axes, exact Jacobian, numpy eig;
monodromy by DOP853 rtol 1e-11). Comparison rules and tolerances: check_campbell_common.py.

Cases:
  S1  examples/spatial.toml (paper 000's base case, one plane, dimensionless), --route auto
      (the 12-state model) and --route general;
  S2  examples/spatial_two_plane.toml's rotor, two planes, static + couple unbalance, made
      isotropic and without gravity (an equilibrium), --route general (auto picks it);
  S3  the same with k_x != k_y at both supports (2e6/2.6e6, 3e6/3.6e6) and no gravity: the
      balanced state is at rest in turning axes, T = pi/Omega: Floquet exponents;
  S4  examples/spatial_two_plane.toml as shipped (gravity: a periodic orbit found by shooting)
      at 3 of autobal's speeds.
Shares: the translation xi + i eta and the axis tip theta - i delta at the radius of gyration
sqrt(A_r / M) (A_r the rotor body's equatorial moment, M the total mass: autobal's choice, read
from its rustdoc since the docs do not say which radius; with the whole rotor's moment about C
the shares differ by up to 1.4e-2).
Run: .venv/bin/python bench/independent/check_campbell_spatial.py [S1 S2 S3 S4]  (~5-15 min)
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import check_campbell_common as cc  # noqa: E402
import common  # noqa: E402
import spatial_model as sm  # noqa: E402
from check_spatial_one_plane import base_case  # noqa: E402
from check_spatial_two_plane import example_rotor  # noqa: E402


def rho2(S):
    # autobal's weight (its rustdoc, rotor_campbell.rs): the rotor body's equatorial moment over
    # the total mass; the docs say only "at the radius of gyration"
    return S.rotor["A"] / S.mass


def pairs_groups(S, tilt=True):
    r = np.sqrt(rho2(S))
    pairs = [(0, 1, 1.0)] + ([(3, 2, r, -1.0)] if tilt else [])
    balls = []
    k = S.nq0
    for pl in S.planes:
        for m in pl["masses"]:
            balls.append((k, np.sqrt(m / S.mass) * pl["R"]))
            k += 1
    groups = {"translation": [(0, 1.0), (1, 1.0)], "tilt": [(2, r), (3, r)], "balls": balls}
    return pairs, groups


def write(name, text):
    path = os.path.join(common.TMP, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def normalise(d):
    """The 12-state route's JSON (lines[].modes, every speed) in the general route's form."""
    if "analysed" in d:
        return d, "fixed"
    n = len(d["omega"])
    d = dict(d, analysed=[True] * n, failures=[None] * n)
    d["lines"] = [dict(points=[dict(p, omega=w) for p, w in zip(l["modes"], d["omega"])])
                  for l in d["lines"]]
    # its per-line log_decrement is the rotating-frame one, -2 pi sigma/|nu| (the docs)
    return d, "rotating"


def equilibrium_case(name, S, path, extra=(), shares=True, tilt_share=True, fine=1000):
    d, _ = common.run_json(["campbell", "--config", path, *extra])
    d, ldm = normalise(d)
    pairs, groups = pairs_groups(S, tilt_share)
    specs, xs = {}, {}
    xp = None
    for j, w in enumerate(d["omega"]):
        if not d["analysed"][j] or d["failures"][j] is not None:
            continue
        x, res = S.equilibrium(w) if xp is None else S.equilibrium(w, q0=xp)
        if res > 1e-8:
            x, res = S.equilibrium(w)
        lam, V = np.linalg.eig(S.jac(0.0, x, w))
        specs[j] = cc.Spec(w, lam, V, pairs, groups)
        xs[j] = x
        xp = x
    bad, s = cc.compare_lines(d, specs, check_shares=shares, check_groups=cc.group_by_energy,
                              label=name, logdec=ldm)
    bad2, nm = cc.compare_modes(d, specs if shares else {}, label=name)
    js = sorted(specs)

    def near_x(w):
        j = min(js, key=lambda i: abs(d["omega"][i] - w))
        x, _ = S.equilibrium(w, q0=xs[j])
        return x

    def spec_fn(w):
        return np.linalg.eigvals(S.jac(0.0, near_x(w), w))

    mine = cc.critical_events(spec_fn, d["omega"][js[0]], d["omega"][js[-1]], n=1200)
    notes = []
    bad3, worst_c, nth = cc.compare_criticals(d, mine, label=name, notes=notes,
                                               spec_fn=spec_fn)
    allbad = bad + bad2 + bad3
    print(f"{name}: {len(specs)} speeds {d['omega'][js[0]]:.6g}-{d['omega'][js[-1]]:.6g}, "
          f"{s['points']} line points: eigenvalues worst {s['worst']:.1e} of max|lambda| "
          f"(near-double {s['worst_near']:.1e}); shares ({s['shares']}) worst "
          f"{s['worst_share']:.1e}; log dec worst {s['worst_logdec']:.1e}; {nm} mode points; "
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
        d2, _ = normalise(d2)
        bad4, n = cc.track_check(d2, lambda w: np.linalg.eig(S.jac(0.0, near_x(w), w)),
                                 label=name + " tracking")
        print(f"{name} tracking ({fine} speeds): {n} line steps checked by eigenvector overlap "
              + ("OK" if not bad4 else f"*** {len(bad4)} steps jump"))
        for b in bad4[:10]:
            print("   ", b)
        ok &= not bad4
    return ok, d


def case_S1():
    S = base_case()
    ex = os.path.join(common.ROOT, "examples", "spatial.toml")
    ok = True
    for route in ("auto", "general"):
        # the 12-state route's share also counts the balls' unbalance (docs/notes/stability.md):
        # not compared there
        o, _ = equilibrium_case(f"S1 spatial.toml route {route}", S, ex, ("--route", route),
                                shares=(route == "general"))
        ok &= o
    return ok


def iso_two_plane():
    rotor, sup, pts, planes = example_rotor()
    return rotor, sup, pts, planes


def case_S2():
    rotor, sup, pts, planes = iso_two_plane()
    S = sm.Spatial(rotor, sup, pts, planes)
    path = write("two_plane_iso", sm.toml(rotor, sup, pts, planes, omega=700.0, t_end=0.1))
    o, _ = equilibrium_case("S2 two planes isotropic", S, path, ("--omega-max", "1500 rad/s"))
    return o


def floquet_compare(name, S, d, idx, orbit=None):
    bad = []
    und = []
    worst = 0.0
    n = 0
    for j in idx:
        w = d["omega"][j]
        T = S.period(w)
        if orbit is None:
            x, res = S.equilibrium(w)
            xT, Phi = S.monodromy(w, x, T)
            assert np.max(np.abs(xT - x)) < 1e-8 * max(1, np.max(np.abs(x)))
        else:
            x, Phi = orbit(S, w)
        mu, V = np.linalg.eig(Phi)
        rho = np.log(mu.astype(complex)) / T
        pts = [(li, l["points"][j]) for li, l in enumerate(d["lines"]) if l["points"][j]]
        if len(pts) != len(mu):
            bad.append(f"{name} w={w:.6g}: {len(pts)} line points, {len(mu)} multipliers")
        th = np.array([p["re"] + 1j * p["im"] for _, p in pts])
        r, c, dist = cc.match(th, rho, 2 * np.pi / T)
        nP = np.linalg.norm(Phi, 2)
        for a, b, dd in zip(r, c, dist):
            if abs(mu[b]) < 1e-10 * nP:
                und.append((w, th[a], rho[b]))
                continue
            n += 1
            e = dd * T
            tl = 1e-7 + 1e-10 * nP / abs(mu[b])
            worst = max(worst, e)
            if e > tl:
                bad.append(f"{name} w={w:.8g} line {pts[a][0]}: {th[a]:.10g}, mine {rho[b]:.10g} "
                           f"(mod 2 pi/T; diff*T {e:.1e})")
    print(f"{name}: {n} exponents at {len(idx)} speeds, worst |diff| T {worst:.1e} (Im modulo "
          f"2 pi/T) " + ("OK" if not bad else "*** DISAGREE"))
    if und:
        print(f"    {len(und)} exponents with |mu| < 1e-10 ||Phi|| (undetermined) left out, e.g. "
              f"w={und[0][0]:.6g}: autobal {und[0][1]:.6g}, mine {und[0][2]:.6g}")
    for b in bad[:15]:
        print("   ", b)
    return not bad


def case_S3(every=6):
    rotor, sup, pts, planes = iso_two_plane()
    sup = [dict(sup[0], ky=2.6e6), dict(sup[1], ky=3.6e6)]
    S = sm.Spatial(rotor, sup, pts, planes)
    path = write("two_plane_aniso", sm.toml(rotor, sup, pts, planes, omega=700.0, t_end=0.1))
    d, _ = common.run_json(["campbell", "--config", path, "--omega-max", "1500 rad/s"])
    print(f"S3: {d.get('stationary_state')}; branch: {str(d.get('branch'))[:60]}...")
    idx = [j for j, w in enumerate(d["omega"]) if d["analysed"][j] and d["failures"][j] is None]
    return floquet_compare("S3 two planes, k_x != k_y, no gravity", S, d, idx[::every])


def case_S4():
    import check_spatial_example_two_plane as ex2
    S = sm.Spatial(ex2.ROTOR, ex2.SUP, ex2.PTS, ex2.PLANES, gravity=(0.0, -ex2.G))
    ex = os.path.join(common.ROOT, "examples", "spatial_two_plane.toml")
    d, _ = common.run_json(["campbell", "--config", ex, "--omega-max", "1500 rad/s",
                            "--points", "20"])
    idx = [j for j, w in enumerate(d["omega"]) if d["analysed"][j] and d["failures"][j] is None]
    print(f"S4: {len(idx)} of {len(d['omega'])} speeds analysed; failures "
          f"{sorted(set(str(f)[:90] for f in d['failures'] if f))}")

    def orbit(S, w):
        T = 2 * np.pi / w
        x0 = S.state(S.balanced_angles())
        sag = -1j * S.mass * ex2.G / (ex2.SUP[0]["ky"] + ex2.SUP[1]["ky"])
        x0[0], x0[1] = sag.real, sag.imag
        x, Phi, res = S.periodic_orbit(w, x0, T, tol=1e-11)
        return x, Phi

    pick = [idx[len(idx) // 4], idx[len(idx) // 2], idx[-1]]
    return floquet_compare("S4 examples/spatial_two_plane.toml", S, d, pick, orbit)


if __name__ == "__main__":
    which = sys.argv[1:] or ["S1", "S2", "S3", "S4"]
    ok = True
    for c in which:
        ok &= {"S1": case_S1, "S2": case_S2, "S3": case_S3, "S4": case_S4}[c]()
    print("ALL AGREE" if ok else "DISAGREEMENTS")
    sys.exit(0 if ok else 1)
