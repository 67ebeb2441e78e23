"""`autobal campbell` on the planar rotor (paper 004's disk, housing and balls) against the
independent derivation planar_model.py (SymPy Lagrange equations in turning axes, exact
Jacobian, numpy eig; monodromy by DOP853 rtol 1e-11).

Cases:
  P  examples/planar.toml as shipped (eccentric race, isotropic: the semi-balanced equilibrium);
  J  the Jeffcott limit: the same rotor with s2 = 0 (race centred);
  A  supports that differ by direction (k_x = 9e4, k_y = 1.2e5, c_x = 40, c_y = 60, race
     centred): the balanced state is at rest in turning axes, the equations periodic with
     T = pi/Omega; autobal gives Floquet exponents.
Checked (check_campbell_common.py for the tolerances):
  * every line point (re, im) against my eigenvalues at that speed (all 8, as a multiset);
    for A, my Floquet exponents ln(mu)/T, Im modulo 2 pi/T, and which branch autobal picks;
  * forward_share, fixed_frequency, whirl, log_decrement of every line point from my
    eigenvectors; group (translation/balls) by energy per unit mass where one dominates 10x;
  * fixed_axes_modes: f in {Omega +- nu}, share, log_decrement, whirl, one mode per complex
    pair, "delta > 0 on every curve iff stable";
  * the 1x critical speeds against my own events (real-axis count, |Im| = 2 Omega), bisected;
  * tracking: each line's step follows the eigenvector of largest overlap (MAC), on a fine grid.
Run: .venv/bin/python bench/independent/check_campbell_planar.py [P J A H selftest]   (~1 min)
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
import check_campbell_common as cc  # noqa: E402
import common  # noqa: E402
import planar_model as pm  # noqa: E402

BASE = dict(m1=1.0, m2=0.2, s1=0.003, s2=0.0005, gamma=0.0, r=0.06, m3=0.03, c_psi=0.1)
K, C = 104509.44, 50.0


def model(s2, kx=K, ky=K, cx=C, cy=C):
    return pm.Planar(BASE["m1"], BASE["m2"], BASE["s1"], s2, BASE["gamma"], BASE["r"], kx, ky,
                     cx, cy, [BASE["m3"]] * 2, [BASE["c_psi"]] * 2)


def planar_groups(P):
    mt = P.m1 + 0.2 + sum(P.mb)
    return {"translation": [(0, 1.0), (1, 1.0)],
            "balls": [(2 + j, np.sqrt(P.mb[j] / mt) * P.r) for j in range(P.n)]}


PAIRS = [(0, 1, 1.0)]


def equilibrium_specs(P, d):
    """My spectrum at every analysed speed (continuation of the state along the grid)."""
    specs, xs = {}, {}
    x_prev = None
    for j, w in enumerate(d["omega"]):
        if not d["analysed"][j] or d["failures"][j] is not None:
            continue
        if x_prev is None:
            x, res = P.equilibrium(w)
        else:
            x, res = P.equilibrium(w, psi0=x_prev[2:4], z0=x_prev[0] + 1j * x_prev[1])
        assert res < 1e-8, (w, res)
        lam, V = np.linalg.eig(P.jac(0.0, x, w))
        specs[j] = cc.Spec(w, lam, V, PAIRS, planar_groups(P))
        xs[j] = x
        x_prev = x
    return specs, xs


def run_equilibrium_case(name, P, cfg_path, extra=()):
    ok = True
    d, _ = common.run_json(["campbell", "--config", cfg_path, *extra])
    specs, xs = equilibrium_specs(P, d)
    bad, s = cc.compare_lines(d, specs, check_groups=cc.group_by_energy, label=name)
    bad2, nm = cc.compare_modes(d, specs, label=name)
    js = sorted(specs)
    w0, w1 = d["omega"][js[0]], d["omega"][js[-1]]
    xcache = {j: xs[j] for j in js}

    def spec_fn(w):
        j = min(js, key=lambda i: abs(d["omega"][i] - w))
        x = xcache[j]
        x, _ = P.equilibrium(w, psi0=x[2:4], z0=x[0] + 1j * x[1])
        return np.linalg.eigvals(P.jac(0.0, x, w))

    mine = cc.critical_events(spec_fn, w0, w1, n=1500)
    notes = []
    bad3, worst_c, nth = cc.compare_criticals(d, mine, label=name, notes=notes,
                                               spec_fn=spec_fn)
    print(f"{name}: {len(specs)} speeds {w0:.6g}-{w1:.6g}, {s['points']} line points: eigenvalues "
          f"worst {s['worst']:.1e} of max|lambda| (near-double {s['worst_near']:.1e}); shares "
          f"({s['shares']}) worst {s['worst_share']:.1e}; log dec worst {s['worst_logdec']:.1e}; "
          f"{nm} mode points; critical speeds: autobal {nth}, mine {len(mine)} "
          f"({', '.join('%.9g %s' % (e[0], e[1]) for e in mine)}), worst {worst_c:.1e} rel. "
          + ("OK" if not (bad or bad2 or bad3) else "*** DISAGREE"))
    for b in notes:
        print("    note:", b)
    for b in (bad + bad2 + bad3)[:25]:
        print("   ", b)
    if len(bad + bad2 + bad3) > 25:
        print(f"    ... {len(bad + bad2 + bad3) - 25} more")
    ok &= not (bad or bad2 or bad3)
    # tracking on a fine grid (1000 speeds)
    d2, _ = common.run_json(["campbell", "--config", cfg_path, "--points", "1000", *extra])
    xprev = {}

    def vec_fn(w):
        j = min(js, key=lambda i: abs(d["omega"][i] - w))
        x = xcache[j]
        x, _ = P.equilibrium(w, psi0=x[2:4], z0=x[0] + 1j * x[1])
        return np.linalg.eig(P.jac(0.0, x, w))

    d2["lines"] = d2["lines"]
    bad4, n = cc.track_check(d2, vec_fn, label=name + " tracking")
    print(f"{name} tracking (1000 speeds): {n} line steps checked by eigenvector overlap "
          + ("OK" if not bad4 else f"*** {len(bad4)} steps jump"))
    for b in bad4[:10]:
        print("   ", b)
    ok &= not bad4
    return ok, d


def case_P():
    return run_equilibrium_case("P (examples/planar.toml)", model(BASE["s2"]),
                                os.path.join(common.ROOT, "examples", "planar.toml"))


def case_J():
    path = common.planar_toml("jeffcott", m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06,
                              k=K, c=C, m3=0.03, c_psi=0.1)
    return run_equilibrium_case("J (Jeffcott, s2 = 0)", model(0.0), path)


def case_A(points=40):
    """k_x != k_y: Floquet exponents."""
    P = model(0.0, kx=9.0e4, ky=1.2e5, cx=40.0, cy=60.0)
    path = common.planar_toml("aniso", m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06,
                              kx=9.0e4, ky=1.2e5, cx=40.0, cy=60.0, m3=0.03, c_psi=0.1)
    d, _ = common.run_json(["campbell", "--config", path, "--points", str(points)])
    print(f"A: stationary_state {d.get('stationary_state')!r}; what: {d.get('what')!r}")
    for k in ("branch", "period", "exponents"):
        if k in d:
            print(f"A: {k}: {d[k]!r}")
    bad = []
    worst_re = worst_im = 0.0
    branch_q = branch_alt = 0
    nchk = 0
    specs = {}
    undetermined = []
    nbound = [0]
    for j, w in enumerate(d["omega"]):
        if not d["analysed"][j] or d["failures"][j] is not None:
            continue
        T = np.pi / w
        x, _ = P.equilibrium(w)  # the balanced state is at rest in turning axes (no support force)
        xT, Phi = P.monodromy(w, x, T)
        assert np.max(np.abs(xT - x)) < 1e-9 * max(1, np.max(np.abs(x))), "not a periodic orbit"
        mu, V = np.linalg.eig(Phi)
        rho = np.log(mu.astype(complex)) / T
        allpts = [(li, l["points"][j]) for li, l in enumerate(d["lines"]) if l["points"][j]]
        # autobal's bounds (|mu| below its round-off bound: `re` null, `decay_at_least`): each
        # must hold for one of my exponents of multipliers that small, checked apart
        bounds = [p for _, p in allpts if p["re"] is None]
        pts = [(li, p) for li, p in allpts if p["re"] is not None]
        mine_small = sorted(rho[np.abs(mu) < 1e-6 * np.linalg.norm(Phi, 2)].real)
        for bp in bounds:
            nbound[0] += 1
            # one of my exponents of small multipliers must decay at least that fast (1e-7/T: the
            # exponents' tolerance above; which one is the round-off's guess, so only one)
            if not mine_small or mine_small[0] > -bp["decay_at_least"] + 1e-7 / T:
                bad.append(f"A w={w:.6g}: autobal bounds an exponent by sigma <= {-bp['decay_at_least']:.6g}, "
                           f"my smallest multipliers' exponents {mine_small}")
        th = np.array([p["re"] + 1j * p["im"] for _, p in pts])
        r, c, dist = cc.match(th, rho, 2 * np.pi / T)
        J0 = P.jac(0.0, x, w)
        for a, b, dd in zip(r, c, dist):
            p = pts[a][1]
            nchk += 1
            er = abs(p["re"] - rho[b].real) * T
            dim = p["im"] - rho[b].imag
            k = np.round(dim / (2 * np.pi / T))
            ei = abs(dim - k * 2 * np.pi / T) * T
            # a multiplier below 1e-10 of ||Phi|| is round-off of the monodromy (mine and
            # autobal's alike): its exponent is not determined; counted apart
            if abs(mu[b]) < 1e-10 * np.linalg.norm(Phi, 2):
                undetermined.append((w, p["re"], p["im"], rho[b]))
                continue
            # tolerance 1e-7 / T plus an absolute error of 1e-10 ||Phi|| in a multiplier (a
            # monodromy integrated to rtol ~1e-10, as autobal's may be; mine, at rtol 1e-11,
            # moves by < 1e-12 relative at rtol 1e-13) over |mu|
            tl = 1e-7 + 1e-10 * np.linalg.norm(Phi, 2) / abs(mu[b])
            worst_re, worst_im = max(worst_re, er), max(worst_im, ei)
            if er > tl or ei > tl:
                bad.append(f"A w={w:.6g} line {pts[a][0]}: ({p['re']:.10g}, {p['im']:.10g}) "
                           f"mine {rho[b]:.10g} (Re diff*T {er:.1e}, Im diff*T mod 2pi {ei:.1e})")
            # the branch: Im nearest Im of the Rayleigh quotient v^H J(0) v / v^H v (unscaled)
            v = V[:, b]
            q = (v.conj() @ J0 @ v) / (v.conj() @ v)
            cand = rho[b].imag + (2 * np.pi / T) * np.arange(-3, 4)
            best = cand[np.argmin(np.abs(cand - q.imag))]
            if abs(best - p["im"]) < 1e-6 * (2 * np.pi / T):
                branch_q += 1
            else:
                branch_alt += 1
        specs[j] = (w, rho, V)
    print(f"A: {nchk} exponents at {len(specs)} speeds: Re worst {worst_re:.1e}/T, Im (mod 2 pi/T = "
          f"2 Omega) worst {worst_im:.1e}/T; branch = my unscaled Rayleigh quotient's at "
          f"{branch_q}, another at {branch_alt} "
          + ("OK" if not bad else "*** DISAGREE"))
    for b in bad[:15]:
        print("   ", b)
    print(f"A: {nbound[0]} exponents given as bounds (decay_at_least), each checked against my smallest multipliers")
    if undetermined:
        print(f"A: {len(undetermined)} exponents have |mu| < 1e-10 ||Phi|| (round-off: not "
              f"determined by a monodromy), at {sorted(set(round(u[0], 4) for u in undetermined))} "
              f"rad/s; autobal prints them as values, e.g. w={undetermined[0][0]:.6g}: "
              f"({undetermined[0][1]:.6g}, {undetermined[0][2]:.6g}), mine {undetermined[0][3]:.6g}")
    # isotropic limit: the exponents continue the equilibrium eigenvalues
    Pi = model(0.0, kx=1.05e5, ky=1.05e5 * (1 + 1e-7), cx=50.0, cy=50.0)
    pathi = common.planar_toml("aniso_lim", m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06,
                               kx=1.05e5, ky=1.05e5 * (1 + 1e-7), cx=50.0, cy=50.0, m3=0.03,
                               c_psi=0.1)
    di, _ = common.run_json(["campbell", "--config", pathi, "--points", "12"])
    P0 = model(0.0, kx=1.05e5, ky=1.05e5, cx=50.0, cy=50.0)
    worst_lim = 0.0
    lim_und = []
    lim_bad = []
    for j, w in enumerate(di["omega"]):
        if not di["analysed"][j] or di["failures"][j] is not None:
            continue
        lam = P0.eig(w)
        T = np.pi / w
        allpts = [l["points"][j] for l in di["lines"] if l["points"][j]]
        # a bound (`re` null) must hold for an eigenvalue whose multiplier is that small
        for bp in (p for p in allpts if p["re"] is None):
            small_re = lam.real[np.exp(lam.real * T) < 1e-6]
            if not len(small_re) or small_re.min() > -bp["decay_at_least"] * (1 - 1e-6):
                lim_bad.append((w, bp["decay_at_least"], sorted(small_re)))
        pts = [p for p in allpts if p["re"] is not None]
        th = np.array([p["re"] + 1j * p["im"] for p in pts])
        r, c, dist = cc.match(th, lam)  # no modulo: the branch must be the eigenvalue itself
        small = np.exp(lam.real * T) < 1e-10  # multipliers at round-off: not determined
        for a, b, dd in zip(r, c, dist):
            if small[b]:
                lim_und.append((w, th[a], lam[b]))
            else:
                worst_lim = max(worst_lim, dd / np.abs(lam).max())
    lim_ok = worst_lim < 1e-5  # the anisotropy 1e-7 moves eigenvalues by ~1e-7 relative
    # the exponents whose multipliers are below round-off: here the answer is known (the
    # isotropic eigenvalue); autobal's values are reported as a disagreement where they miss it
    # by more than the same 1e-5 of max|lambda|
    wrong = [u for u in lim_und if abs(u[1] - u[2]) > 1e-5 * 1e3]
    lim_ok &= not wrong and not lim_bad
    for b in lim_bad:
        print(f"A limit: at {b[0]:.6g} rad/s autobal bounds an exponent by sigma <= {-b[1]:.6g}, "
              f"the isotropic eigenvalues with multipliers below 1e-6 have Re {b[2]} *** DISAGREE")
    if lim_und:
        e = max(lim_und, key=lambda u: abs(u[1] - u[2]))
        print(f"A limit: {len(lim_und)} exponents with exp(Re lambda T) < 1e-10 left out (speeds "
              f"{sorted(set(round(u[0], 4) for u in lim_und))}); worst: at {e[0]:.6g} rad/s autobal "
              f"prints {e[1]:.6g}, the eigenvalue is {e[2]:.6g}; {len(wrong)} off by more than "
              f"1e-5 max|lambda|" + (" *** DISAGREE" if wrong else ""))
    print(f"A limit k_y = k_x (1 + 1e-7): exponents (no modulo) vs the isotropic eigenvalues worst "
          f"{worst_lim:.1e} of max|lambda| " + ("OK" if lim_ok else "*** DISAGREE"))
    # fixed-axes modes: only the internal relations (f in Omega +- nu, log dec, whirl)
    bad2, nm = cc.compare_modes(d, {}, label="A")
    print(f"A fixed_axes_modes: {nm} points " + ("OK" if not bad2 else "*** DISAGREE"))
    for b in bad2[:10]:
        print("   ", b)
    return not bad and lim_ok and not bad2, d


def case_H():
    """--harmonics 1,2 on examples/planar.toml and the Jeffcott limit: the 2x critical speeds.
    A pair nu = |Im lambda| has a forward component at Omega + nu (share s of the Im > 0
    eigenvector) and a backward one at Omega - nu; the forward one meets 2 Omega at nu = Omega,
    the backward one -2 Omega at nu = 3 Omega. Ours: changes of the count of |Im| > Omega and
    |Im| > 3 Omega, bisected, with the component's share at the event (listed by autobal where
    at least 1e-9, its docs)."""
    ok = True
    for name, s2, path in (("H planar.toml", BASE["s2"], os.path.join(common.ROOT, "examples",
                                                                        "planar.toml")),
                           ("H Jeffcott", 0.0, common.planar_toml(
                               "jeffcott_h", m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06,
                               k=K, c=C, m3=0.03, c_psi=0.1))):
        P = model(s2)
        d, _ = common.run_json(["campbell", "--config", path, "--harmonics", "1,2"])
        th = [c for c in d["critical_speeds"] if c["harmonic"] == 2]
        specs, xs = equilibrium_specs(P, d)
        js = sorted(specs)

        def eig_at(w):
            j = min(js, key=lambda i: abs(d["omega"][i] - w))
            x, _ = P.equilibrium(w, psi0=xs[j][2:4], z0=xs[j][0] + 1j * xs[j][1])
            return np.linalg.eig(P.jac(0.0, x, w))

        mine = []
        ws = np.linspace(d["omega"][js[0]], d["omega"][js[-1]], 1500)
        for mult, comp in ((1.0, "forward"), (3.0, "backward")):
            cnt = lambda w: int(np.sum(np.abs(eig_at(w)[0].imag) > mult * w))
            cs = [cnt(w) for w in ws]
            for i in range(len(ws) - 1):
                if cs[i] != cs[i + 1]:
                    a, b = ws[i], ws[i + 1]
                    while b - a > 1e-13 * b:
                        m = 0.5 * (a + b)
                        if cnt(m) == cs[i]:
                            a = m
                        else:
                            b = m
                    we = 0.5 * (a + b)
                    lam, V = eig_at(we)
                    k = int(np.argmin(np.abs(np.abs(lam.imag) - mult * we) + 1e9 * (lam.imag < 0)))
                    fw, bw = cc.circ_weights(V[:, k] / np.linalg.norm(V[:, k]), PAIRS)
                    sh = fw / (fw + bw) if comp == "forward" else bw / (fw + bw)
                    mine.append((we, comp, sh))
        bad = []
        used = set()
        for we, comp, sh in mine:
            k = min(range(len(th)), key=lambda i: abs(th[i]["omega"] - we), default=None)
            hit = k is not None and abs(th[k]["omega"] - we) < 1e-8 * we
            if hit:
                used.add(k)
                if th[k]["whirl"] != comp or abs(th[k]["share"] - sh) > 1e-6:
                    bad.append(f"{name} 2x at {we:.10g}: autobal {th[k]['whirl']} share "
                               f"{th[k]['share']:.3g}, mine {comp} share {sh:.3g}")
            elif sh >= 1e-9:
                bad.append(f"{name} my 2x event at {we:.10g} ({comp}, share {sh:.3g}) not listed")
        for i, c in enumerate(th):
            if i not in used:
                bad.append(f"{name} autobal 2x critical {c['omega']:.10g} ({c['whirl']}) not mine")
        print(f"{name} --harmonics 1,2: 2x critical speeds autobal {len(th)}, mine "
              f"{[('%.9g' % m[0], m[1], '%.2g' % m[2]) for m in mine]} "
              + ("OK" if not bad else "*** DISAGREE"))
        for b in bad:
            print("   ", b)
        ok &= not bad
    return ok, None


def selftest():
    """The comparisons can fail: examples/planar.toml's JSON altered four ways, each must be
    caught (a value moved by 1e-7 max|lambda|; a whirl word flipped; two lines swapped from mid
    grid on (a tracking jump); a critical speed dropped)."""
    import copy
    P = model(BASE["s2"])
    path = os.path.join(common.ROOT, "examples", "planar.toml")
    d, _ = common.run_json(["campbell", "--config", path, "--points", "120"])
    specs, xs = equilibrium_specs(P, d)
    j = sorted(specs)[len(specs) // 2]
    ok = True
    d1 = copy.deepcopy(d)
    d1["lines"][2]["points"][j]["re"] += 1e-7 * specs[j].scale
    ok &= bool(cc.compare_lines(d1, specs, label="t")[0])
    d2 = copy.deepcopy(d)
    p = d2["lines"][2]["points"][j]
    p["whirl"] = "backward" if p["whirl"] == "forward" else "forward"
    ok &= bool(cc.compare_lines(d2, specs, label="t")[0])
    d3 = copy.deepcopy(d)
    a, b = 2, 3  # translation lines: swap from the middle on
    for k in range(j, len(d3["omega"])):
        d3["lines"][a]["points"][k], d3["lines"][b]["points"][k] = (
            d3["lines"][b]["points"][k], d3["lines"][a]["points"][k])

    def vec_fn(w):
        x, _ = P.equilibrium(w, psi0=xs[j][2:4], z0=xs[j][0] + 1j * xs[j][1])
        return np.linalg.eig(P.jac(0.0, x, w))

    bad3, _ = cc.track_check(dict(d3, omega=d3["omega"][j - 1:j + 1],
                                  lines=[dict(points=l["points"][j - 1:j + 1]) for l in d3["lines"]]),
                             vec_fn)
    ok &= bool(bad3)
    d4 = copy.deepcopy(d)
    d4["critical_speeds"] = d4["critical_speeds"][1:]
    mine = [(c["omega"], "real-axis", 0, 2, False) for c in d["critical_speeds"]]
    ok &= bool(cc.compare_criticals(d4, mine)[0])
    print("selftest: the four altered outputs are " + ("all caught" if ok else "*** NOT all caught"))
    return ok, d


if __name__ == "__main__":
    which = sys.argv[1:] or ["P", "J", "A", "H", "selftest"]
    ok = True
    for c in which:
        good, _ = {"P": case_P, "J": case_J, "A": case_A, "H": case_H, "selftest": selftest}[c]()
        ok &= good
    print("ALL AGREE" if ok else "DISAGREEMENTS")
    sys.exit(0 if ok else 1)
