"""Supports that differ by direction (k_x != k_y, c_x != c_y at each bearing), tilt free, no
gravity: autobal `stability` on the spatial rotor against an independent derivation
(spatial_model.py).

In turning axes the support forces depend on w t: the equations are periodic with T = pi/w.
The balanced state (C on the axis, no tilt, balls cancelling the unbalance) feels no support
force, so it is at rest in turning axes at every instant: an equilibrium of a periodic system,
whose stability is given by the Floquet multipliers over T (monodromy of the variational
equations with the exact SymPy Jacobian, solve_ivp DOP853 rtol 1e-11, atol 1e-13). Checked:
  * the residual of the equations at the balanced state at t = 0.1, 0.37, 0.8 T (< 1e-9 of the
    largest force term's scale: it must be an equilibrium at every instant);
  * limit case k_x = k_y treated as periodic: multipliers = exp(lambda T) (1e-9);
  * ln(max|mu|)/T against `abscissa` at every 4th speed autobal analysed (tolerance 1e-7/T: the
    monodromy at rtol 1e-11 gives |mu| to ~1e-10, so ln|mu| to 1e-10, and autobal's neutral band
    on |mu| is 1e-8);
  * the stable-range ends (bisected to 1e-10 between autobal's samples) against
    `stable_ranges` (1e-8 relative).
Configs: examples/spatial_two_plane.toml's rotor with one plane and its supports (k_y 30 % and
20 % stiffer, damping 300/450 N s/m) without gravity; the same with both planes and the couple;
one random one-plane rotor.
Run: .venv/bin/python bench/independent/check_spatial_aniso.py   (~10-15 min)
"""

from __future__ import annotations

import os
import sys

import numpy as np

import common
import spatial_model as sm

RNG = np.random.default_rng(3)


def write(name, text):
    path = os.path.join(common.TMP, name + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def thin(d, every):
    pts = [p for p in d["points"] if p["analysed"] and p.get("abscissa") is not None]
    return dict(d, points=pts[::every] + ([pts[-1]] if (len(pts) - 1) % every else []))


def check(name, S, rotor, sup, pts, planes, wmax, every=4):
    path = write(name, sm.toml(rotor, sup, pts, planes, omega=wmax / 2, t_end=0.1))
    d, err = common.run_json(["stability", "--config", path, "--omega-max", f"{wmax!r} rad/s"])
    w = wmax / 2
    x, res = S.equilibrium(w)
    worst_r = max(np.max(np.abs(S.rhs(f * np.pi / w, x, w)[S.N:])) for f in (0.1, 0.37, 0.8))
    print(f"{name}: balanced state at rest at every instant: max |q''| {worst_r:.1e} "
          f"(at w = {w:.6g})")
    ok = worst_r < 1e-9
    # exponents at every `every`-th point; ends bisected between ALL autobal's samples where
    # autobal's sign changes (and mine), to keep the cost down
    # my exponents also at autobal's samples on both sides of each of its range ends, so that a
    # narrow range is not lost to the thinning
    ws = [p["omega"] for p in d["points"] if p["analysed"] and p.get("abscissa") is not None]
    br = set()
    for rg in d["stable_ranges"]:
        for e in (rg["from"], rg["to"]):
            lo = [w for w in ws if w < e]
            hi = [w for w in ws if w > e]
            if lo and hi:
                br |= {max(lo), min(hi)}
    o, info = sm.compare_stability(name, S, thin(d, every), tol_expo=1e-7, tol_end=1e-8,
                                   grid=sorted(br))
    ok &= o
    if err.strip():
        print("   stderr:", err.strip().replace("\n", " | ")[:400])
    return ok


def main():
    ok = True
    # limit case: isotropic treated as periodic
    rotor = dict(mass=20.0, A=0.6, C=0.15, z=0.25)
    iso = [dict(z=0.0, kx=2e6, ky=2e6, cx=300.0, cy=300.0),
           dict(z=0.5, kx=3e6, ky=3e6, cx=300.0, cy=300.0)]
    pts1 = [dict(m=0.01, rho=0.1, ang=0.0, z=0.45)]
    pl1 = [dict(z=0.45, R=0.12, masses=[0.02] * 2, drags=[0.5] * 2)]
    S = sm.Spatial(rotor, iso, pts1, pl1)
    for w in (400.0, 1200.0):
        x, _ = S.equilibrium(w)
        lam = S.eig(w, x)
        T = np.pi / w
        _, Phi = S.monodromy(w, x, T)
        mu = np.linalg.eigvals(Phi)
        ex = np.exp(lam * T)
        dm = max(np.min(np.abs(ex - m)) for m in mu)
        print(f"limit k_x = k_y at w = {w}: max_mu min|mu - exp(lambda T)| = {dm:.1e}")
        ok &= dm < 1e-9
    aniso = [dict(z=0.0, kx=2e6, ky=2.6e6, cx=300.0, cy=450.0),
             dict(z=0.5, kx=3e6, ky=3.6e6, cx=300.0, cy=450.0)]
    S = sm.Spatial(rotor, aniso, pts1, pl1)
    ok &= check("aniso_one_plane", S, rotor, aniso, pts1, pl1, 1500.0)
    pts2 = pts1 + [dict(m=0.01, rho=0.1, ang=2.5, z=0.05)]
    pl2 = pl1 + [dict(z=0.05, R=0.12, masses=[0.02] * 2, drags=[0.5] * 2)]
    S = sm.Spatial(rotor, aniso, pts2, pl2)
    ok &= check("aniso_two_plane", S, rotor, aniso, pts2, pl2, 1500.0, every=8)
    # one random one-plane rotor
    M = RNG.uniform(3, 30)
    span = RNG.uniform(0.3, 0.8)
    A = M * (span * RNG.uniform(0.25, 0.5)) ** 2
    r = dict(mass=M, A=A, C=A * RNG.uniform(0.4, 1.4), z=span * RNG.uniform(0.3, 0.7))
    kL, kR = (float(v) for v in RNG.uniform(5e4, 5e5, 2) * M)
    sup = [dict(z=0.0, kx=kL, ky=kL * RNG.uniform(0.6, 1.6), cx=0.05 * np.sqrt(kL * M),
                cy=0.08 * np.sqrt(kL * M)),
           dict(z=span, kx=kR, ky=kR * RNG.uniform(0.6, 1.6), cx=0.06 * np.sqrt(kR * M),
                cy=0.03 * np.sqrt(kR * M))]
    zA = span * RNG.uniform(0.6, 1.2)
    R = RNG.uniform(0.05, 0.2)
    m0, r0 = M * 1e-3, RNG.uniform(0.05, 0.2)
    mb = m0 * r0 / R * RNG.uniform(0.7, 1.3)
    pts = [dict(m=m0, rho=r0, ang=RNG.uniform(-3, 3), z=zA)]
    planes = [dict(z=zA, R=R, masses=[mb] * 2, drags=[mb * np.sqrt(kL / M)] * 2)]
    S = sm.Spatial(r, sup, pts, planes)
    ok &= check("aniso_random", S, r, sup, pts, planes,
                float(3.5 * np.sqrt((kL + kR) / M)), every=6)
    print("ALL AGREE" if ok else "SOME DISAGREE")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
