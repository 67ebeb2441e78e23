"""The spatial rigid rotor, one balancer plane, tilt free, isotropic supports, no gravity
(papers 000/003): autobal `stability` against an independent derivation (spatial_model.py).

The balanced state (C on the axis, no tilt, the two balls at the closed-form angles that cancel
the static unbalance) is an equilibrium in turning axes; Newton (fsolve, xtol 1e-14) on the full
nonlinear equations from the closed form; eigenvalues of the exact SymPy Jacobian (numpy eigvals).
Checked, at every speed autobal analysed:
  * max Re lambda against `abscissa` (tolerance 1e-9 of max|lambda| at that speed: eigvals of
    a 12x12 matrix are good to ~1e-14 of its norm, and 1e-9 max|lambda| is autobal's own neutral
    band, so a larger difference could flip a verdict);
  * the ball angles against `member_psi` (1e-9 rad);
  * every stable-range end (my bisection to 1e-11 between autobal's samples AND on my own grid
    of 400 speeds, so that a range autobal's grid misses shows) against `stable_ranges`
    (tolerance 1e-8 relative: autobal locates ends to 1e-9).
Configs: paper 000's base case (examples/spatial.toml, dimensionless, on both routes), an SI
rotor (examples/spatial_two_plane.toml's rotor with one plane, isotropic), 3 random SI rotors.
Run: .venv/bin/python bench/independent/check_spatial_one_plane.py   (~2 min)
"""

from __future__ import annotations

import os
import sys

import numpy as np

import common
import spatial_model as sm

RNG = np.random.default_rng(1618)


def base_case():
    """examples/spatial.toml in SI-like units M_s = 1, omega0 = 1, rho_s = 1 (the conversion
    of docs/notes/spatial.md 'Units')."""
    cs, rho_s, lL, za, m0, r0, mm, r, n, hx, hs = 0.75, 0.4, 0.8, 0.8, 0.025, 2.0, 0.05, 2.0, 2, 0.05, 0.1
    Mr = 1 - m0 - mm
    zG = -(m0 + mm) * za / Mr
    Ar = 1 - Mr * zG**2 - (m0 + mm) * za**2 - 0.5 * m0 * r0**2 - 0.5 * mm * r**2
    Cr = cs - m0 * r0**2 - mm * r**2
    sup = [dict(z=-lL / rho_s, kx=0.5, ky=0.5, cx=hx / 2, cy=hx / 2),
           dict(z=(1 - lL) / rho_s, kx=0.5, ky=0.5, cx=hx / 2, cy=hx / 2)]
    hA = hs * mm / n
    return sm.Spatial(dict(mass=Mr, A=Ar, C=Cr, z=zG), sup, [dict(m=m0, rho=r0, ang=0.0, z=za)],
                      [dict(z=za, R=r, masses=[mm / n] * n, drags=[hA] * n)])


def si_rotor():
    rotor = dict(mass=20.0, A=0.6, C=0.15, z=0.25)
    sup = [dict(z=0.0, kx=2e6, ky=2e6, cx=300.0, cy=300.0),
           dict(z=0.5, kx=3e6, ky=3e6, cx=300.0, cy=300.0)]
    pts = [dict(m=0.01, rho=0.1, ang=0.0, z=0.45)]
    planes = [dict(z=0.45, R=0.12, masses=[0.02, 0.02], drags=[0.5, 0.5])]
    return rotor, sup, pts, planes


def random_rotor():
    M = RNG.uniform(2, 50)
    span = RNG.uniform(0.2, 1.0)
    zg = span * RNG.uniform(0.2, 0.8)
    rg = span * RNG.uniform(0.2, 0.6)  # radius of gyration
    A = M * rg**2
    C = A * RNG.uniform(0.3, 1.6)
    kL, kR = (float(v) for v in RNG.uniform(1e4, 1e6, 2) * M / 10)
    cL, cR = RNG.uniform(0.02, 0.1) * np.sqrt(kL * M), RNG.uniform(0.02, 0.1) * np.sqrt(kR * M)
    zA = span * RNG.uniform(-0.3, 1.3)
    R = RNG.uniform(0.05, 0.3)
    m0, r0 = M * RNG.uniform(1e-4, 5e-3), RNG.uniform(0.05, 0.3)
    mb = RNG.uniform(0.6, 1.5) * m0 * r0 / R  # capacity 1.2-3
    h = RNG.uniform(0.05, 5.0) * mb * np.sqrt((kL + kR) / M)
    rotor = dict(mass=M, A=A, C=C, z=zg)
    sup = [dict(z=0.0, kx=kL, ky=kL, cx=cL, cy=cL), dict(z=span, kx=kR, ky=kR, cx=cR, cy=cR)]
    pts = [dict(m=m0, rho=r0, ang=RNG.uniform(-3, 3), z=zA)]
    planes = [dict(z=zA, R=R, masses=[mb, mb], drags=[h, h])]
    return rotor, sup, pts, planes


def write(name, text):
    path = os.path.join(common.TMP, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def main():
    ok = True
    S = base_case()
    ex = os.path.join(common.ROOT, "examples", "spatial.toml")
    for route in ("auto", "general"):
        d, err = common.run_json(["stability", "--config", ex, "--route", route])
        wmax = d["omega_max"]
        o, _ = sm.compare_stability(f"base case 000 (examples/spatial.toml), route {route}", S, d,
                                    grid=np.linspace(0.02, wmax, 400))
        ok &= o
    cases = [("si_one_plane", si_rotor(), 1500.0)]
    for i in range(3):
        rotor, sup, pts, planes = random_rotor()
        w0 = np.sqrt((sup[0]["kx"] + sup[1]["kx"]) / rotor["mass"])
        cases.append((f"random{i}", (rotor, sup, pts, planes), float(4 * w0)))
    for name, (rotor, sup, pts, planes), wmax in cases:
        S = sm.Spatial(rotor, sup, pts, planes)
        path = write(name, sm.toml(rotor, sup, pts, planes, omega=wmax / 2, t_end=1.0))
        for route in ("auto", "general"):
            d, err = common.run_json(["stability", "--config", path, "--omega-max",
                                      f"{wmax!r} rad/s", "--route", route])
            o, _ = sm.compare_stability(f"{name} route {route}", S, d,
                                        grid=np.linspace(wmax / 400, wmax, 400))
            ok &= o
            if err.strip():
                print("   stderr:", err.strip().replace("\n", " | ")[:400])
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
