"""autobal `map` (and `map --boundary`) on the planar Jeffcott rotor against the independent
derivation (planar_model.py).

1. Isotropic supports, speed x ball drag (omega x planar.c_psi): every cell's
   `max_real_part` against my max Re(lambda) (tolerance 1e-9 * max|lambda|, autobal's neutral
   band), every cell's verdict, and every traced boundary point (the lowest stable speed per
   drag) against my bisection to 1e-11 (tolerance 1e-8 relative: autobal says 1e-9).
2. Supports that differ by direction, speed x k_y (omega x planar.k_y): Floquet exponents
   ln(max|mu|)/T, T = pi/w, against `max_real_part` (tolerance 1e-6 1/s) and the verdicts.
Run: .venv/bin/python bench/independent/check_map.py   (a few minutes)
"""

from __future__ import annotations

import csv
import sys

import numpy as np

import common
import planar_model as pm


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def iso():
    ok = True
    cfg = dict(m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06, k=104509.44, c=50.0,
               m3=0.03, c_psi=0.1)
    path = common.planar_toml("map_iso", **cfg)
    stem = common.TMP + "/map_iso"
    out, err, rc = common.run(["map", "--config", path, "--x", "omega=250:500:41", "--y",
                               "planar.c_psi=0.004:0.4:31", "--boundary", "--out", stem])
    rows = read(stem + ".csv")
    models = {}
    worst, bad_verdict = 0.0, 0
    for row in rows:
        w, cp = float(row["omega"]), float(row["planar.c_psi"])
        if cp not in models:
            models[cp] = pm.Planar(1.0, 0.2, 0.003, 0.0, 0.0, 0.06, 104509.44, 104509.44, 50.0,
                                   50.0, [0.03, 0.03], [cp, cp])
        ev = models[cp].eig(w)
        d = abs(max(ev.real) - float(row["max_real_part"])) / max(abs(ev))
        worst = max(worst, d)
        mine = "stable" if max(ev.real) < -1e-9 * max(abs(ev)) else (
            "unstable" if max(ev.real) > 1e-9 * max(abs(ev)) else "neutral")
        if mine != row["verdict"]:
            bad_verdict += 1
            print(f"  verdict differs at omega={w}, c_psi={cp}: mine {mine} ({max(ev.real):.3g})"
                  f" autobal {row['verdict']}")
        if d > 1e-9:
            ok = False
            print(f"  DISAGREE omega={w} c_psi={cp}: {max(ev.real)!r} vs {row['max_real_part']}")
    wb = 0.0
    for b in read(stem + "_boundary.csv"):
        w, cp = float(b["omega"]), float(b["planar.c_psi"])
        P = models[cp]
        f = lambda x: max(P.eig(x).real)
        lo, hi = w * (1 - 1e-4), w * (1 + 1e-4)
        mine = pm.bisect(f, lo, hi, tol=1e-12)
        rel = abs(mine - w) / w
        wb = max(wb, rel)
        if rel > 1e-8:
            ok = False
            print(f"  DISAGREE boundary at c_psi={cp}: mine {mine!r} autobal {w!r}")
    print(f"map iso (omega x c_psi, {len(rows)} cells): worst |d max Re lambda|/max|lambda| "
          f"{worst:.1e}, verdicts differing {bad_verdict}; boundary ({len(read(stem + '_boundary.csv'))}"
          f" points) worst rel diff {wb:.1e}{' OK' if ok else ' *** DISAGREE'}")
    return ok


def aniso():
    ok = True
    cfg = dict(m1=1.0, m2=0.2, s1=0.003, s2=0.0, gamma=0.0, r=0.06, kx=9.0e4, ky=1.2e5,
               cx=40.0, cy=60.0, m3=0.03, c_psi=0.1)
    path = common.planar_toml("map_aniso", **cfg)
    stem = common.TMP + "/map_aniso"
    out, err, rc = common.run(["map", "--config", path, "--x", "omega=200:450:11", "--y",
                               "planar.k_y=6e4:1.8e5:7", "--out", stem])
    rows = read(stem + ".csv")
    worst, nv = 0.0, 0
    for row in rows:
        w, ky = float(row["omega"]), float(row["planar.k_y"])
        P = pm.Planar(1.0, 0.2, 0.003, 0.0, 0.0, 0.06, 9.0e4, ky, 40.0, 60.0, [0.03, 0.03],
                      [0.1, 0.1])
        x, _ = P.equilibrium(w)
        T = np.pi / w
        _, Phi = P.monodromy(w, x, T)
        mu = max(abs(np.linalg.eigvals(Phi)))
        e = np.log(mu) / T
        d = abs(e - float(row["max_real_part"]))
        worst = max(worst, d)
        mine = "stable" if mu < 1 - 1e-8 else ("unstable" if mu > 1 + 1e-8 else "neutral")
        if mine != row["verdict"]:
            nv += 1
            print(f"  verdict differs at omega={w} k_y={ky}: mine {mine} autobal {row['verdict']}")
        if d > 1e-6:
            ok = False
            print(f"  DISAGREE omega={w} k_y={ky}: my exponent {e!r} vs {row['max_real_part']}")
    print(f"map aniso (omega x k_y, {len(rows)} cells, Floquet): worst |d exponent| {worst:.1e} 1/s,"
          f" verdicts differing {nv}{' OK' if ok else ' *** DISAGREE'}")
    if err.strip():
        print("  stderr:", err.strip().replace("\n", " | ")[:400])
    return ok


if __name__ == "__main__":
    ok = iso()
    ok &= aniso()
    print("ALL AGREE" if ok else "SOME DISAGREE")
    sys.exit(0 if ok else 1)
