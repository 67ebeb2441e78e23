"""Two balancer planes, tilt free, isotropic supports, no gravity (Rodrigues et al. 2008's
two-plane balancer; autobal's `[balancer2]` and `[couple]`): `stability` against an independent
derivation (spatial_model.py with two ball planes and two unbalance masses).

The balanced state: C on the axis, no tilt, each plane's two balls at the closed-form angles that
make the static AND the couple unbalance vanish (force and moment balance: each plane's demand
U_p, then the law of cosines). It exists iff |U_p| <= 2 m R in both planes. For a static
unbalance at the middle of two planes symmetric about it (here: the unbalance half in plane A
and the `[couple]` mass, same angle, half in plane B), |U_p| = m_u e / 2, so the threshold is
m_c = m_u e / (4 R): Rodrigues et al. 2008 eq (21), m_c = eps/4 in their units (ball mass over
rotor mass, eccentricity over race radius). Checked:
  * existence: at 0.97 and 0.999998 m_c autobal must report no balanced state (no `balanced`
    point), at 1.000002, 1.03 and 1.5 m_c a balanced state with my ball angles (1e-9 rad);
  * below m_c the partially balanced state (each plane's balls together, Newton from there):
    exponents, residual and amplitude against autobal's points; near the translational critical
    speed several such states coexist, so the comparison is made on autobal's own (Newton from
    its `member_psi`), and at each stable-range end my continuation says whether it is a
    stability change or a fold (the state followed ceases to exist);
  * `critical` (balls locked, undamped) against my stiffness determinant (6 printed digits);
  * max Re lambda at autobal's speeds vs `abscissa` (1e-9 of max|lambda|, as in the one-plane
    check) and the stable-range ends (1e-8 relative, my bisection to 1e-11 on autobal's samples
    and my own 300 speeds);
  * "born unstable below the conical critical speed": just above m_c, the balanced state is
    unstable at every speed below the conical critical speed (undamped, balls locked at balance:
    my 8x8 eigenproblem), and autobal says so;
  * examples/spatial_two_plane.toml's rotor made isotropic and without gravity (static plus
    couple unbalance), and 2 random two-plane rotors.
Run: .venv/bin/python bench/independent/check_spatial_two_plane.py   (~5 min)
"""

from __future__ import annotations

import os
import sys

import numpy as np

import common
import spatial_model as sm

RNG = np.random.default_rng(2008)


def write(name, text):
    path = os.path.join(common.TMP, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def example_rotor():
    rotor = dict(mass=20.0, A=0.6, C=0.15, z=0.25)
    sup = [dict(z=0.0, kx=2e6, ky=2e6, cx=300.0, cy=300.0),
           dict(z=0.5, kx=3e6, ky=3e6, cx=300.0, cy=300.0)]
    pts = [dict(m=0.01, rho=0.1, ang=0.0, z=0.45), dict(m=0.01, rho=0.1, ang=2.5, z=0.05)]
    planes = [dict(z=0.45, R=0.12, masses=[0.02] * 2, drags=[0.5] * 2),
              dict(z=0.05, R=0.12, masses=[0.02] * 2, drags=[0.5] * 2)]
    return rotor, sup, pts, planes


def rodrigues(frac):
    """A symmetric rotor (G midway, equal supports, planes symmetric about G), the static
    unbalance m_u e at G split into two halves in the balancer planes; ball mass frac * m_c."""
    M, span, R = 10.0, 0.4, 0.08
    mu, e = 0.02, 0.1           # unbalance m_u e = 2e-3 kg m
    mc = mu * e / (4 * R)        # per ball
    mb = frac * mc
    rotor = dict(mass=M, A=0.16, C=0.08, z=0.2)  # long rotor: C < A
    sup = [dict(z=0.0, kx=5e5, ky=5e5, cx=100.0, cy=100.0),
           dict(z=span, kx=5e5, ky=5e5, cx=100.0, cy=100.0)]
    zA, zB = 0.32, 0.08
    pts = [dict(m=mu / 2, rho=e, ang=0.0, z=zA), dict(m=mu / 2, rho=e, ang=0.0, z=zB)]
    planes = [dict(z=zA, R=R, masses=[mb] * 2, drags=[0.3] * 2),
              dict(z=zB, R=R, masses=[mb] * 2, drags=[0.3] * 2)]
    return rotor, sup, pts, planes


def conical_critical(S, psi):
    """Undamped, balls locked at balance: the critical speeds (det of the 4x4 rotor stiffness
    in turning axes = 0, the free whirl at the spin frequency) by scanning the smallest singular
    value of the rotor block of my linearisation with damping removed. Returns the list."""
    S0 = sm.Spatial(S.rotor, [dict(s, cx=0.0, cy=0.0) for s in S.supports], S.points,
                    [dict(p, drags=[0.0] * len(p["drags"])) for p in S.planes])
    N = S0.N

    def kdet(w):
        x = S0.state(psi)
        # the stiffness in turning axes at rest, d(M q'' - F)/dq, rotor rows and columns only
        # (balls locked): singular where a synchronous whirl needs no force
        Jq = np.asarray(S0.sys["Jq"](0.0, x[:N], x[N:], np.zeros(N), S0.p(w)), float)
        return np.linalg.det(Jq[:4, :4])
    ws = np.linspace(1.0, 2000.0, 4000)
    v = np.array([kdet(w) for w in ws])
    out = []
    for i in range(1, len(ws)):
        if np.sign(v[i]) != np.sign(v[i - 1]):
            out.append(sm.bisect(kdet, ws[i - 1], ws[i], v[i - 1], tol=1e-12))
    return out


def trace(S, w0, x0, w1, step):
    """Natural continuation of an equilibrium from (w0, x0) towards w1; stops where Newton
    jumps (a fold: the branch ends). Returns (last speed, its exponent, x) and whether it
    jumped."""
    x, w, last = x0, w0, None
    while (w1 - w) * np.sign(w1 - w0) > -1e-12:
        xn, r = S.equilibrium(w, q0=x)  # warm start: the whole previous state
        if r > 1e-9 or sm.ang_diff(xn[S.nq0:S.nq0 + S.nb], x[S.nq0:S.nq0 + S.nb]) > 0.05:
            return last, True
        x = xn
        last = (w, float(np.max(S.eig(w, x).real)), x)
        w += step * np.sign(w1 - w0)
    return last, False


def fold_check(S, d):
    """At each stable-range end that autobal marks as a boundary: is it a stability change of
    one state (its exponent crosses 0 along a continued branch), the end of a branch (a fold),
    or a switch between two coexisting states that each keep their stability across it? Both
    autobal's states next to the end (outside and inside the range, Newton from its member_psi)
    are continued across it by 3 rad/s (steps 0.01 rad/s, warm-started Newton). Returns False
    where an end marked as a boundary is not a stability change of either."""
    good = True
    pts = [p for p in d["points"] if p["analysed"] and p.get("member_psi") is not None]
    for rg in d["stable_ranges"]:
        for key, side in (("from", -1), ("to", 1)):
            if not rg.get(f"{key}_is_boundary"):
                continue
            wend = rg[key]
            out = max((p for p in pts if p["omega"] < wend), key=lambda p: p["omega"]) if side < 0 \
                else min((p for p in pts if p["omega"] > wend), key=lambda p: p["omega"])
            ins = min((p for p in pts if rg["from"] < p["omega"] < rg["to"]),
                      key=lambda p: abs(p["omega"] - wend))
            res = []
            for p, target in ((out, wend - side * 3.0), (ins, wend + side * 3.0)):
                x0, _ = S.equilibrium(p["omega"], np.asarray(p["member_psi"]))
                last, jumped = trace(S, p["omega"], x0, target, 0.01)
                res.append((p, last, jumped))
            (po, lo, jo), (pi, li, ji) = res
            flips = [not j and np.sign(l[1]) != np.sign(p["abscissa"]) for p, l, j in res]
            if any(flips):
                print(f"  range end {key} {wend:.8g}: a stability change along a continued state "
                      f"(exponent {lo[1]:.3g} at {lo[0]:.6g} from autobal's state at "
                      f"{po['omega']:.6g}) OK")
                continue
            good = False
            what = []
            for nm, (p, l, j) in (("outside", res[0]), ("inside", res[1])):
                what.append(f"autobal's {nm} state ({p['omega']:.6g} rad/s, exponent "
                            f"{p['abscissa']:.4g}) " + (f"ends at {l[0]:.4f} (fold)" if j else
                                                        f"continues to {l[0]:.4f} with exponent "
                                                        f"{l[1]:.4g}"))
            print(f"  range end {key} {wend:.8g} rad/s: NOT a stability change: " + "; ".join(what)
                  + ": the end is where autobal's Newton switches between coexisting states, yet "
                  f"{key}_is_boundary = true *** DISAGREE")
    return good


def main():
    ok = True
    cases = []
    r = example_rotor()
    cases.append(("two_plane_example_iso", r, 1500.0))
    for i in range(2):
        M = RNG.uniform(3, 40)
        span = RNG.uniform(0.3, 1.0)
        rg = span * RNG.uniform(0.2, 0.5)
        A = M * rg**2
        rotor = dict(mass=M, A=A, C=A * RNG.uniform(0.3, 1.5), z=span * RNG.uniform(0.3, 0.7))
        kL, kR = (float(v) for v in RNG.uniform(2e4, 5e5, 2) * M)
        sup = [dict(z=0.0, kx=kL, ky=kL, cx=0.05 * np.sqrt(kL * M), cy=0.05 * np.sqrt(kL * M)),
               dict(z=span, kx=kR, ky=kR, cx=0.04 * np.sqrt(kR * M), cy=0.04 * np.sqrt(kR * M))]
        zA, zB = span * RNG.uniform(0.6, 1.1), span * RNG.uniform(-0.1, 0.4)
        R = RNG.uniform(0.05, 0.2)
        m0, r0 = M * RNG.uniform(2e-4, 2e-3), RNG.uniform(0.05, 0.2)
        pts = [dict(m=m0, rho=r0, ang=RNG.uniform(-3, 3), z=zA),
               dict(m=m0 * RNG.uniform(0.3, 1.5), rho=r0, ang=RNG.uniform(-3, 3),
                    z=span * RNG.uniform(0, 1))]
        Sx = sm.Spatial(rotor, sup, pts, [dict(z=zA, R=R, masses=[1, 1], drags=[1, 1]),
                                          dict(z=zB, R=R, masses=[1, 1], drags=[1, 1])])
        need = max(abs(U) for U in Sx.plane_demands()) / (2 * R)
        mb = need * RNG.uniform(1.2, 2.0)
        h = mb * np.sqrt((kL + kR) / M) * RNG.uniform(0.1, 3)
        planes = [dict(z=zA, R=R, masses=[mb] * 2, drags=[h] * 2),
                  dict(z=zB, R=R, masses=[mb] * 2, drags=[h] * 2)]
        cases.append((f"two_plane_random{i}", (rotor, sup, pts, planes),
                      float(3.5 * np.sqrt((kL + kR) / M))))
    for name, (rotor, sup, pts, planes), wmax in cases:
        S = sm.Spatial(rotor, sup, pts, planes)
        path = write(name, sm.toml(rotor, sup, pts, planes, omega=wmax / 2, t_end=0.1))
        d, err = common.run_json(["stability", "--config", path, "--omega-max", f"{wmax!r} rad/s"])
        o, _ = sm.compare_stability(name, S, d, grid=np.linspace(wmax / 300, wmax, 300))
        ok &= o
        if err.strip():
            print("   stderr:", err.strip().replace("\n", " | ")[:400])

    # the existence threshold m_c = eps / 4 and the state born unstable below the conical speed
    for frac in (0.97, 0.999998, 1.000002, 1.03, 1.5):
        rotor, sup, pts, planes = rodrigues(frac)
        S = sm.Spatial(rotor, sup, pts, planes)
        psi = S.balanced_angles()
        path = write(f"rodrigues_{frac}", sm.toml(rotor, sup, pts, planes, omega=500.0, t_end=0.1))
        d, err = common.run_json(["stability", "--config", path, "--omega-max", "1500 rad/s"])
        states = sorted({str(p.get("state")) for p in d["points"]})
        if psi is None:
            # no balanced state: the partially balanced one, each plane's two balls together
            # on the side opposite its demand (Newton from there; the rotor whirls with the
            # residual unbalance)
            bal = [p for p in d["points"] if p.get("state") == "balanced"]
            good = not bal
            print(f"rodrigues m = {frac} m_c: mine: no balanced state (|U_p| > 2 m R); autobal "
                  f"states {states}{' OK' if good else ' *** DISAGREE: a balanced point'}")
            g = np.concatenate([[np.angle(U)] * 2 for U in S.plane_demands()])
            o, info = sm.compare_stability(f"rodrigues m = {frac} m_c, partially balanced", S, d,
                                           grid=np.linspace(5.0, 1500.0, 300), psi0=g)
            ok &= good and o
            ok &= fold_check(S, d)
            x, _ = S.equilibrium(1000.0, g)
            u, mz = S.residual_unbalance(x[S.nq0:S.nq0 + S.nb])
            stat0 = sum(p["m"] * p["rho"] for p in S.points)
            pt = min(d["points"], key=lambda p: abs(p["omega"] - 1000.0))
            xa, _ = S.equilibrium(pt["omega"], g)
            ua, mza = S.residual_unbalance(xa[S.nq0:S.nq0 + S.nb])
            print(f"  at {pt['omega']:.6g} rad/s: my residual static unbalance |sum m r e^(i phi)|"
                  f" / m_u e = {abs(ua) / stat0:.6g}, couple (about C) {abs(mza):.3e} kg m^2, rotor "
                  f"offset |xi + i eta| {abs(xa[0] + 1j * xa[1]):.3e} m; autobal residual "
                  f"{pt.get('residual')!r} ({d.get('residual_scale')}), amplitude "
                  f"{pt.get('amplitude')!r}, state {pt.get('state')}, verdict {pt.get('verdict')}")
            continue
        cc = conical_critical(S, psi)
        # autobal `critical` (text) against mine: the tilt pair (sign changes of my det) and the
        # translation's double root sqrt(sum k / M_s) (a double root: no sign change)
        import re
        txt, _, _ = common.run(["critical", "--config", path])
        ab_cc = [float(v) for v in re.findall(r"^\s+\d+\.\s+([0-9.]+) rad/s", txt, re.M)]
        mine_cc = sorted(cc + [np.sqrt((sup[0]["kx"] + sup[1]["kx"]) / S.mass)])
        dcc = (max(abs(a - b) / b for a, b in zip(ab_cc, mine_cc))
               if len(ab_cc) == len(mine_cc) else np.inf)
        print(f"  `critical`: autobal {ab_cc} rad/s, mine {[f'{c:.6f}' for c in mine_cc]}: worst "
              f"rel diff {dcc:.1e} (printed to 6 digits: tolerance 5e-6)"
              f"{' OK' if dcc < 5e-6 else ' *** DISAGREE'}")
        ok &= dcc < 5e-6
        o, info = sm.compare_stability(f"rodrigues m = {frac} m_c", S, d,
                                       grid=np.linspace(5.0, 1500.0, 300))
        ok &= o
        # unstable below the conical critical speed (the higher of the two criticals)
        wk = max(cc) if cc else None
        below = [p for p in d["points"] if p["analysed"] and p.get("abscissa") is not None
                 and wk and p["omega"] < wk]
        mine_below = [sm.exponent(S, w)[0] for w in np.linspace(5.0, wk * 0.999, 60)] if wk else []
        allun_mine = all(e > 0 for e in mine_below)
        allun_ab = all(p["abscissa"] > 0 for p in below)
        print(f"  critical speeds (balls locked, undamped; mine): {[f'{c:.6g}' for c in cc]} "
              f"rad/s; unstable at every speed below the conical one: mine {allun_mine}, "
              f"autobal {allun_ab} ({len(below)} points); autobal states {states}")
        if allun_mine != allun_ab:
            ok = False
            print("  *** DISAGREE on 'born unstable below the conical critical speed'")
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
