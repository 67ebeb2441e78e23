"""Shared comparison of `autobal campbell --format json` with an independent spectrum.

The spectrum at a speed comes from the derivations here (planar_model.py, spatial_model.py,
linear_model.py): the eigenvalues and right eigenvectors of the exact Jacobian at the balanced
state (numpy eig), or the Floquet multipliers and their eigenvectors of the monodromy over the
equations' period T. From an eigenvector, the rotor's circular components are computed here:
a real motion Re(X e^{lambda t}) of the coordinate pairs (a, b) with the complex coordinate
c = a + i b moves, in the turning axes, as (X_a + i X_b)/2 e^{lambda t} + (X_a - i X_b)^*/2 ...,
i.e. components at +nu and -nu; in fixed axes (c e^{i Omega t}) at Omega + nu ("forward" part,
weight |X_a + i X_b|^2) and Omega - nu (weight |X_a - i X_b|^2). The forward share is the
first weight over their sum, summed over the pairs given (the translation (xi, eta) and, for
the spatial rotor, the axis tip theta - i delta at the radius of gyration).

Tolerances (justified where they are used):
  * eigenvalues: 1e-9 of max|lambda| at that speed (numpy eig and autobal's solver are both
    backward stable, ~1e-14 ||A||; 1e-9 is autobal's own neutral band). Where two eigenvalues of
    mine are within 1e-4 max|lambda| of each other (a near-collision: the eigenvalue is then as
    sensitive as sqrt(eps) times the gap's inverse) the bound is 1e-7.
  * shares: 1e-6 absolute (an eigenvector's direction is good to eps / gap; the shares of
    near-double eigenvalues are not defined and are skipped: gap below 1e-4 max|lambda|).
  * Floquet exponents: Re to 1e-7 / T (the monodromy by DOP853 at rtol 1e-11 is good to
    ~1e-9 relative), Im modulo the ambiguity 2 pi / T to 1e-7 / T.
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import linear_sum_assignment

# autobal's rule for the log decrement (spatial::stability::log_decrement): -2 pi sigma/|f|
# where |f| > sqrt(eps) times the largest |lambda| at that speed, else null (|f| not resolved:
# the error of a double eigenvalue). Checked within 1 % of the threshold either side.
RESOLUTION = float(np.sqrt(np.finfo(float).eps))


def circ_weights(vec, pairs):
    """(forward, backward) weights of an eigenvector over the coordinate pairs [(ia, ib, s)]:
    c = s (x_a + i x_b), s a real scale (or (ia, ib, s, sign) with c = s (x_a + i sign x_b))."""
    fw = bw = 0.0
    for p in pairs:
        ia, ib, s = p[:3]
        sg = p[3] if len(p) > 3 else 1.0
        a, b = vec[ia], sg * vec[ib]
        fw += s * s * abs(a + 1j * b) ** 2
        bw += s * s * abs(a - 1j * b) ** 2
    return fw, bw


class Spec:
    """A spectrum at one speed: eigenvalues lam, forward shares, gaps (distance to the nearest
    other eigenvalue), group energies (translation, tilt, balls) per eigenvalue."""

    def __init__(self, w, lam, vecs, pairs, groups=None):
        self.w = w
        self.lam = np.asarray(lam)
        n = len(lam)
        self.scale = float(np.max(np.abs(lam)))
        self.share = np.zeros(n)
        self.rotor = np.zeros(n)
        self.gap = np.full(n, np.inf)
        self.group = [None] * n
        for k in range(n):
            v = vecs[:, k] / np.linalg.norm(vecs[:, k])
            fw, bw = circ_weights(v, pairs)
            self.rotor[k] = fw + bw
            self.share[k] = fw / (fw + bw) if fw + bw > 0 else 0.5
            d = np.abs(self.lam - self.lam[k])
            d[k] = np.inf
            self.gap[k] = d.min()
            if groups is not None:
                en = {g: sum(s * s * abs(v[i]) ** 2 for i, s in idx) for g, idx in groups.items()}
                self.group[k] = en


def match(theirs, mine, period=None):
    """Optimal assignment of autobal's values to mine; with a period P the imaginary parts are
    compared modulo P. Returns (rows, cols, distances)."""
    th = np.asarray(theirs)
    D = th[:, None] - np.asarray(mine)[None, :]
    if period:
        im = D.imag - period * np.round(D.imag / period)
        D = D.real + 1j * im
    C = np.abs(D)
    r, c = linear_sum_assignment(C)
    return r, c, C[r, c]


def compare_lines(d, specs, *, tol=1e-9, tol_near=1e-7, period_of=None, check_shares=True,
                  check_groups=None, label="", logdec="fixed", tol_share=1e-6):
    """d: campbell JSON; specs: {speed index: Spec}. Compares every line point with the
    spectrum: value, fixed_frequency, forward_share, whirl, log_decrement. Returns
    (problems, summary)."""
    bad = []
    worst = worst_near = worst_share = worst_ld = 0.0
    n_pts = n_share = 0
    lines = d["lines"]
    for j, sp in specs.items():
        w = d["omega"][j]
        pts = [(li, l["points"][j]) for li, l in enumerate(lines) if l["points"][j] is not None]
        if len(pts) != len(sp.lam):
            bad.append(f"{label} w={w:.6g}: {len(pts)} line points, {len(sp.lam)} eigenvalues")
        th = [p["re"] + 1j * p["im"] for _, p in pts]
        P = period_of(w) if period_of else None
        r, c, dist = match(th, sp.lam, P)
        for a, b, dd in zip(r, c, dist):
            li, p = pts[a]
            rel = dd / sp.scale if not P else dd
            near = sp.gap[b] < 1e-4 * sp.scale
            if near:
                worst_near = max(worst_near, rel)
            else:
                worst = max(worst, rel)
            t = (tol_near if near else tol)
            if rel > t:
                bad.append(f"{label} w={w:.8g} line {li}: ({p['re']:.12g}, {p['im']:.12g}) nearest "
                           f"mine {sp.lam[b]:.12g} (diff {rel:.2e}{' near-double' if near else ''})")
            n_pts += 1
            # shares, fixed frequency, whirl, log decrement: from my eigenvector, where defined
            if not check_shares or near or sp.rotor[b] < 1e-12:
                continue
            s = sp.share[b]
            if P is None and abs(sp.lam[b].imag) < 1e-12 * sp.scale:
                s = 0.5  # a real eigenvalue: the two components coincide (both at Omega)
            n_share += 1
            ds = abs(p["forward_share"] - s)
            worst_share = max(worst_share, ds)
            if tol_share is None:
                s = p["forward_share"]  # shares not defined by the docs: autobal's own, for f
            elif ds > tol_share:
                bad.append(f"{label} w={w:.8g} line {li} ({p['re']:.6g}, {p['im']:.6g}): "
                           f"forward_share {p['forward_share']:.9f}, mine {s:.9f}")
            if abs(s - 0.5) > 1e-6:
                f = w + p["im"] if s > 0.5 else w - p["im"]
                if abs(p["fixed_frequency"] - f) > 1e-9 * max(1.0, abs(f), sp.scale):
                    bad.append(f"{label} w={w:.8g} line {li}: fixed_frequency "
                               f"{p['fixed_frequency']:.12g}, dominant component {f:.12g}")
                wh = "forward" if f > 0 else "backward"
                if p.get("whirl") not in (wh,) and abs(f) > 1e-9 * sp.scale:
                    bad.append(f"{label} w={w:.8g} line {li}: whirl {p.get('whirl')}, "
                               f"dominant component at {f:.6g} ({wh})")
                ld = p.get("log_decrement")
                den = abs(f) if logdec == "fixed" else abs(p["im"])
                # (equilibria: a Floquet spectrum's scale holds exponents of multipliers below
                # round-off, which autobal's leaves out)
                if P is None and (ld is None) != (den <= RESOLUTION * sp.scale) \
                        and abs(den / (RESOLUTION * sp.scale) - 1) > 0.01:
                    bad.append(f"{label} w={w:.8g} line {li}: log_decrement {ld}, |f| {den:.3g}, "
                               f"resolution {RESOLUTION * sp.scale:.3g}")
                if ld is not None and den > 1e-9 * sp.scale:
                    mine_ld = -2 * np.pi * p["re"] / den
                    e = abs(ld - mine_ld) / max(1.0, abs(mine_ld))
                    worst_ld = max(worst_ld, e)
                    if e > 1e-9:
                        bad.append(f"{label} w={w:.8g} line {li}: log_decrement {ld:.9g}, "
                                   f"-2 pi sigma/|f| {mine_ld:.9g}")
            if check_groups and sp.group[b] is not None:
                g = check_groups(sp.group[b])
                if g is not None and p.get("group") != g:
                    bad.append(f"{label} w={w:.8g} line {li} ({p['re']:.6g}, {p['im']:.6g}): "
                               f"group {p.get('group')}, energies {fmt_en(sp.group[b])}")
    return bad, dict(points=n_pts, worst=worst, worst_near=worst_near, worst_share=worst_share,
                     shares=n_share, worst_logdec=worst_ld)


def fmt_en(en):
    return "{" + ", ".join(f"{k}: {v:.3g}" for k, v in en.items()) + "}"


def group_by_energy(en, margin=10.0):
    """The dominant group where it dominates by a factor `margin` (else None: undecided)."""
    items = sorted(en.items(), key=lambda kv: -kv[1])
    if len(items) < 2 or items[0][1] > margin * items[1][1]:
        return items[0][0]
    return None


def compare_modes(d, specs, label="", tol_share=1e-6):
    """fixed_axes_modes: per point the followed component's signed frequency f in
    {Omega + nu, Omega - nu} of its line's value, `share` of that component, log_decrement =
    -2 pi re/|f|, whirl = sign f; at each speed every complex pair of mine carried by exactly
    one mode; 'delta > 0 on every curve' iff my max Re lambda < 0."""
    bad = []
    n = 0
    by_speed = {}
    for m in d.get("fixed_axes_modes", []):
        li = m["line"]
        for p in m["points"]:
            w = p["omega"]
            j = int(np.argmin(np.abs(np.asarray(d["omega"]) - w)))
            if abs(d["omega"][j] - w) > 1e-12 * max(1, w):
                continue  # a speed off the table's grid (not expected)
            by_speed.setdefault(j, []).append((m["mode"], li, p))
            lp = d["lines"][li]["points"][j]
            if lp is None:
                bad.append(f"{label} w={w:.6g} mode {m['mode']}: line {li} has no point")
                continue
            n += 1
            f = p["fixed_frequency"]
            cands = [w + lp["im"], w - lp["im"]]
            if min(abs(f - x) for x in cands) > 1e-9 * max(1.0, abs(f)):
                bad.append(f"{label} w={w:.6g} mode {m['mode']}: fixed_frequency {f:.10g} not "
                           f"Omega +- nu {cands}")
            if abs(p["frequency"] - abs(f)) > 1e-12 * max(1, abs(f)):
                bad.append(f"{label} w={w:.6g} mode {m['mode']}: frequency {p['frequency']} != |f|")
            wh = "forward" if f > 0 else "backward"
            if p["whirl"] != wh and abs(f) > 0:
                bad.append(f"{label} w={w:.6g} mode {m['mode']}: whirl {p['whirl']} but f {f:.6g}")
            if p["re"] is None:
                # a Floquet exponent below round-off: a bound only (`decay_at_least`), no
                # log decrement (check_campbell_planar.py checks the bounds)
                if p.get("log_decrement") is not None or not p.get("decay_at_least"):
                    bad.append(f"{label} w={w:.6g} mode {m['mode']}: re null without a bound, or "
                               f"with a log decrement {p.get('log_decrement')}")
                continue
            ld = -2 * np.pi * p["re"] / abs(f) if f != 0 else None
            if p["log_decrement"] is None:
                # |f| not resolved (RESOLUTION): near zero, where my scale says so
                if ld is not None and j in specs and abs(f) > 1.01 * RESOLUTION * specs[j].scale:
                    bad.append(f"{label} w={w:.6g} mode {m['mode']}: log_decrement null at "
                               f"|f| {abs(f):.3g}")
            elif ld is not None and abs(p["log_decrement"] - ld) > 1e-9 * max(1, abs(ld)):
                bad.append(f"{label} w={w:.6g} mode {m['mode']}: log_decrement "
                           f"{p['log_decrement']:.9g}, -2 pi re/|f| {ld:.9g}")
            if j in specs:
                sp = specs[j]
                k = int(np.argmin(np.abs(sp.lam - (lp["re"] + 1j * lp["im"]))))
                if sp.gap[k] > 1e-4 * sp.scale and sp.rotor[k] > 1e-12 and abs(lp["im"]) > 1e-9 * sp.scale:
                    s_f = sp.share[k]
                    s = s_f if abs(f - (w + lp["im"])) < abs(f - (w - lp["im"])) else 1 - s_f
                    if tol_share is not None and abs(p["share"] - s) > tol_share:
                        bad.append(f"{label} w={w:.6g} mode {m['mode']}: share {p['share']:.9f}, "
                                   f"mine {s:.9f}")
    for j, sp in specs.items():
        ms = by_speed.get(j, [])
        # coverage of my complex pairs
        for k in np.where(sp.lam.imag > 1e-9 * sp.scale)[0]:
            lk = sp.lam[k]
            hits = [mm for mm in ms if abs(mm[2]["re"] - lk.real) + abs(abs(mm[2]["nu"]) - lk.imag)
                    < 1e-8 * sp.scale]
            if len(hits) != 1:
                bad.append(f"{label} w={d['omega'][j]:.6g}: my pair {lk:.8g} carried by "
                           f"{len(hits)} modes")
        if ms and all(mm[2]["log_decrement"] is not None for mm in ms):
            stable = sp.lam.real.max() < 0
            alldpos = all(mm[2]["log_decrement"] > 0 for mm in ms)
            if stable != alldpos:
                bad.append(f"{label} w={d['omega'][j]:.6g}: max Re lambda {sp.lam.real.max():.4g} "
                           f"but min log_decrement {min(mm[2]['log_decrement'] for mm in ms):.4g}")
    return bad, n


def critical_events(spec_fn, w0, w1, n=2000, tol=1e-12):
    """My 1x critical speeds in [w0, w1]: where the number of real eigenvalues changes (a pair
    meeting the real axis: both fixed-axes components at Omega) and where the number of
    eigenvalues with |Im| > 2 Omega changes (a backward component Omega - nu at -Omega).
    Found on a grid of n speeds, each change bisected (on the count itself) to tol relative.
    Each real-axis event is also flagged `exempt` by the docs' rule (docs/notes/stability.md:
    a mode on the real axis from the first speed has no crossing where it leaves it, nor one
    that lands and stays to the last speed): the two eigenvalues that meet there are followed
    on the grid (nearest value) back to the first speed (a departure) or on to the last (a
    landing), and the event is exempt where they are real all the way."""
    ws = np.linspace(w0, w1, n)
    lams = [np.asarray(spec_fn(w)) for w in ws]

    def isreal(lam):
        return np.abs(lam.imag) <= 1e-13 * np.max(np.abs(lam))

    def counts_of(lam):
        return (int(np.sum(isreal(lam))), int(np.sum(np.abs(lam.imag) > 2 * w_cur[0])))

    w_cur = [0.0]

    def counts(w):
        w_cur[0] = w
        return counts_of(np.asarray(spec_fn(w)))

    cs = []
    for w, lam in zip(ws, lams):
        w_cur[0] = w
        cs.append(counts_of(lam))

    def follow(i, vals, step):
        """Follow the values from grid index i in direction step; True if they stay real."""
        cur = np.array(vals)
        k = i
        while 0 <= k + step < n:
            k += step
            lam = lams[k]
            nxt = []
            for v in cur:
                m = int(np.argmin(np.abs(lam - v)))
                if not isreal(lam)[m]:
                    return False
                nxt.append(lam[m])
            cur = np.array(nxt)
        return True

    def follow_fine(wa, wb, vals, steps=4000):
        cur = np.array(vals)
        for w in np.linspace(wa, wb, steps)[1:]:
            lam = np.asarray(spec_fn(w))
            r = isreal(lam)
            nxt = []
            for v in cur:
                m = int(np.argmin(np.abs(lam - v)))
                if not r[m]:
                    return False
                nxt.append(lam[m])
            cur = np.array(nxt)
        return True

    ev = []
    for kind in range(2):
        for i in range(n - 1):
            if cs[i][kind] == cs[i + 1][kind]:
                continue
            lo, c_lo, cb = ws[i], cs[i][kind], cs[i + 1][kind]
            while c_lo != cb:  # several changes in one step: one after another
                a, b = lo, ws[i + 1]
                while b - a > tol * b:
                    m = 0.5 * (a + b)
                    if counts(m)[kind] == c_lo:
                        a = m
                    else:
                        b = m
                c_new = counts(b)[kind]
                exempt = False
                if kind == 0:
                    # the pair that meets: the two real eigenvalues nearest each other just on
                    # the real side of the event, followed (nearest value, 4000 steps) to the
                    # grid's end on that side
                    up = c_new > c_lo
                    we = b if up else a
                    lam = np.asarray(spec_fn(we))
                    re = np.sort(lam[isreal(lam)].real)
                    if len(re) >= 2:
                        g = np.argmin(np.diff(re))
                        exempt = follow_fine(we, w1 if up else w0, re[g:g + 2] + 0j)
                ev.append((0.5 * (a + b), "real-axis" if kind == 0 else "backward 2 Omega",
                           c_lo, c_new, exempt))
                lo, c_lo = b, c_new
    return sorted(ev)


def compare_criticals(d, mine, tol=1e-8, label="", notes=None, spec_fn=None):
    """spec_fn (optional): my eigenvalues at a speed, to test an event of autobal's that my grid
    missed: the count of real eigenvalues (or of |Im| > 2 Omega) changes across it."""
    notes = [] if notes is None else notes
    th = [(c["omega"], c["mode"], c["whirl"], c["harmonic"], c.get("share")) for c in
          d.get("critical_speeds", []) if c["harmonic"] == 1]
    bad = []
    used = set()
    worst = 0.0
    for i, (w, kind, a, b, exempt) in enumerate(mine):
        k = min(range(len(th)), key=lambda i: abs(th[i][0] - w), default=None)
        if k is None or abs(th[k][0] - w) > tol * w:
            if exempt:
                notes.append(f"{label} my real-axis event at {w:.10g} ({a}->{b} real eigenvalues)"
                             f" not listed: the docs' rule (on the axis from the first speed / "
                             f"to the last)")
                continue
            bad.append(f"{label} my 1x event at {w:.10g} ({kind}, count {a}->{b}) not in autobal's "
                       f"list")
        else:
            used.add(k)
            worst = max(worst, abs(th[k][0] - w) / w)
            want = "forward" if kind == "real-axis" else "backward"
            if th[k][2] != want:
                bad.append(f"{label} critical {th[k][0]:.10g}: whirl {th[k][2]}, expected {want}")
    for i, t in enumerate(th):
        if i not in used and spec_fn is not None:
            def cnt(w):
                lam = np.asarray(spec_fn(w))
                sc = np.max(np.abs(lam))
                return (int(np.sum(np.abs(lam.imag) <= 1e-13 * sc)),
                        int(np.sum(np.abs(lam.imag) > 2 * w)))
            lo, hi = cnt(t[0] * (1 - 1e-8)), cnt(t[0] * (1 + 1e-8))
            if lo != hi:
                notes.append(f"{label} autobal critical {t[0]:.10g} (mode {t[1]}, {t[2]}) missed by "
                             f"my grid, confirmed by my spectrum (counts {lo} -> {hi} across "
                             f"+-1e-8)")
                used.add(i)
    for i, t in enumerate(th):
        if i not in used:
            bad.append(f"{label} autobal critical {t[0]:.10g} (mode {t[1]}, {t[2]}) has no event of "
                       f"mine")
    return bad, worst, len(th)


def track_check(d, vec_fn, label="", mac_margin=0.2):
    """Continuity: for each line and each pair of neighbouring speeds, the eigenvector of my
    spectrum nearest the line's value at the first speed must have its largest overlap (MAC,
    |v1^H v2|^2 / (|v1|^2 |v2|^2)) with the eigenvector nearest the line's value at the next
    speed, unless another eigenvector's MAC is within mac_margin (then undecided).
    vec_fn(w) -> (lam, V). Returns problems and the number of steps checked."""
    bad = []
    lines = d["lines"]
    ws = d["omega"]
    cache = {}

    def get(j):
        if j not in cache:
            cache[j] = vec_fn(ws[j])
        return cache[j]

    n = 0
    for j in range(len(ws) - 1):
        pairs = [(li, l["points"][j], l["points"][j + 1]) for li, l in enumerate(lines)
                 if l["points"][j] is not None and l["points"][j + 1] is not None]
        if not pairs:
            continue
        lam0, V0 = get(j)
        lam1, V1 = get(j + 1)
        V0n = V0 / np.linalg.norm(V0, axis=0)
        V1n = V1 / np.linalg.norm(V1, axis=0)
        MAC = np.abs(V0n.conj().T @ V1n) ** 2
        for li, p0, p1 in pairs:
            a = int(np.argmin(np.abs(lam0 - (p0["re"] + 1j * p0["im"]))))
            b = int(np.argmin(np.abs(lam1 - (p1["re"] + 1j * p1["im"]))))
            row = MAC[a].copy()
            best = int(np.argmax(row))
            if (abs(p0["im"]) == 0.0) != (abs(p1["im"]) == 0.0):
                continue  # the line meets or leaves the real axis: a branch point, no swap
            n += 1
            if best != b:
                # a swap matters where the two candidates are comparably near the line's last
                # value (a near-crossing); near a branch point on the real axis the eigenvectors
                # are nearly parallel and the MAC says nothing about a far eigenvalue
                d_b, d_best = abs(lam1[b] - lam0[a]), abs(lam1[best] - lam0[a])
                if row[best] - row[b] > mac_margin and d_best < 3 * d_b + 1e-12 * abs(lam1).max():
                    bad.append(f"{label} line {li} {ws[j]:.8g}->{ws[j + 1]:.8g}: "
                               f"{lam0[a]:.6g} -> {lam1[b]:.6g} (MAC {row[b]:.3f}), but the "
                               f"eigenvector continues to {lam1[best]:.6g} (MAC {row[best]:.3f})")
    return bad, n
