"""`autobal map` on the spatial rotor (one plane, tilt free, isotropic supports, SI config):
speed x balancer.ball_mass, 10 x 6 cells, on both routes, against my eigenvalues
(spatial_model.py).

max_real_part is per unit tau (docs/reference/outputs.md): my max Re lambda (1/s) divided by
omega0 = sqrt((k_L + k_R) / M_s), M_s with the cell's ball mass. Tolerance 1e-9 of max|lambda|
/ omega0 (as check_spatial_one_plane.py); the verdict column against my sign (outside the
neutral band 1e-9 max|lambda|).
Run: .venv/bin/python bench/independent/check_spatial_map.py   (~1 min)
"""

from __future__ import annotations

import csv
import os
import sys

import numpy as np

import check_spatial_one_plane as one
import common
import spatial_model as sm


def main():
    ok = True
    rotor, sup, pts, planes = one.si_rotor()
    path = one.write("map_si", sm.toml(rotor, sup, pts, planes, omega=1000.0, t_end=0.1))
    for route in ("auto", "general"):
        stem = os.path.join(common.TMP, f"map_{route}")
        common.run(["map", "--config", path, "--x", "speed=150:1500:10",
                    "--y", "balancer.ball_mass=0.006:0.05:6", "-o", stem, "--route", route])
        worst, nv, n = 0.0, 0, 0
        with open(stem + ".csv") as f:
            for row in csv.DictReader(f):
                w, mb = float(row["speed"]), float(row["balancer.ball_mass"])
                pl = [dict(planes[0], masses=[mb, mb])]
                S = sm.Spatial(rotor, sup, pts, pl)
                x, res = S.equilibrium(w)
                lam = S.eig(w, x)
                Ms = S.mass
                w0 = np.sqrt((sup[0]["kx"] + sup[1]["kx"]) / Ms)
                e = np.max(lam.real) / w0
                sc = np.max(np.abs(lam)) / w0
                diff = abs(e - float(row["max_real_part"])) / sc
                worst = max(worst, diff)
                n += 1
                if diff > 1e-9:
                    ok = False
                    print(f"  DISAGREE speed={w} ball_mass={mb}: mine {e:.12g} autobal "
                          f"{row['max_real_part']}")
                v = row.get("verdict") or ("stable" if row.get("stable") == "1" else "unstable")
                want = "stable" if e < -1e-9 * sc else ("unstable" if e > 1e-9 * sc else v)
                if v != want:
                    nv += 1
                    ok = False
                    print(f"  VERDICT speed={w} ball_mass={mb}: mine {want}, autobal {v}")
        print(f"map speed x balancer.ball_mass, route {route}: {n} cells, worst diff {worst:.1e} "
              f"of max|lambda|, {nv} verdicts differ{' OK' if ok else ' *** DISAGREE'}")
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
