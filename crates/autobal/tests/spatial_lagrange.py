#!/usr/bin/env python3
"""Independent symbolic derivation of the spatial rotor's equations of motion (SymPy).

The Rust model (crates/autobal/src/spatial/dynamics/equations.rs) is written with
d'Alembert's principle in the rotating frame: partial velocities, Newton-Euler inertia forces of
the carrier, ball accelerations assembled by hand. This script derives the same equations by the
textbook route instead: positions of every mass point in *fixed* axes, the rigid rotor's angular
velocity from Q^T dQ/dt, the Lagrangian L = T - V and Rayleigh's dissipation function, then
Lagrange's equations by symbolic differentiation:

    M(q) q'' = Q_drive - dR/dq' + dL/dq - (d/dq (dL/dq')) q'        M = d^2 T / dq'^2

Coordinates q = (xi, eta, delta, theta, phi, psi_1..N): body orientation Q = Rz(phi) Rx(delta)
Ry(theta), body point rho at Rz(phi) (xi, eta, 0) + Q rho in fixed axes.

Reads cases as JSON from stdin (one structure: the same numbers of unbalances, balls and
supports in every case), writes the accelerations q'' as JSON to stdout. A case gives either a
torque (free spin) or a prescribed spin acceleration; `lock_tilt` holds delta = theta = 0.
"""
import json
import sys

import numpy as np
import sympy as sp


def rot_x(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])


def rot_y(a):
    return sp.Matrix([[sp.cos(a), 0, sp.sin(a)], [0, 1, 0], [-sp.sin(a), 0, sp.cos(a)]])


def rot_z(a):
    return sp.Matrix([[sp.cos(a), -sp.sin(a), 0], [sp.sin(a), sp.cos(a), 0], [0, 0, 1]])


def derive(n_unb, n_balls, n_sup):
    """Symbolic M(q) and the rest of Lagrange's equations for one structure; returns a
    numeric function of (q, qd, parameters)."""
    nq = 5 + n_balls
    q = sp.symbols(f"q0:{nq}")
    qd = sp.symbols(f"qd0:{nq}")
    xi, eta, de, th, phi = q[:5]
    # parameters
    Mr, A, C, zg, kap, bet = sp.symbols("Mr A C zg kap bet")
    unb = [sp.symbols(f"um{i} ur{i} ua{i} uz{i}") for i in range(n_unb)]
    balls = [sp.symbols(f"bm{i} bR{i} bz{i} bh{i}") for i in range(n_balls)]
    sups = [sp.symbols(f"sz{i} kx{i} ky{i} cx{i} cy{i}") for i in range(n_sup)]
    gx, gy, gz, cphi = sp.symbols("gx gy gz cphi")
    g = sp.Matrix([gx, gy, gz])
    Rz = rot_z(phi)
    Q = Rz * rot_x(de) * rot_y(th)
    u = sp.Matrix([xi, eta, 0])

    def pos(rho):
        return Rz * u + Q * rho

    def vel(x):
        return x.jacobian(q) * sp.Matrix(qd)

    # rigid rotor: centre of mass G on the axis at zg, tensor A I + (C - A) e e^T about G
    xg = pos(sp.Matrix([0, 0, zg]))
    vg = vel(xg)
    qdot = sum((Q.diff(qi) * qdi for qi, qdi in zip(q, qd)), sp.zeros(3, 3))
    wskew = Q.T * qdot  # body angular velocity as a skew matrix
    wb = sp.Matrix([wskew[2, 1], wskew[0, 2], wskew[1, 0]])
    e = sp.Matrix([sp.sin(kap) * sp.cos(bet), sp.sin(kap) * sp.sin(bet), sp.cos(kap)])
    JG = A * sp.eye(3) + (C - A) * e * e.T
    T = sp.Rational(1, 2) * Mr * (vg.T * vg)[0] + sp.Rational(1, 2) * (wb.T * JG * wb)[0]
    V = -Mr * (g.T * xg)[0]
    for m, r, a, z in unb:
        x = pos(sp.Matrix([r * sp.cos(a), r * sp.sin(a), z]))
        v = vel(x)
        T += sp.Rational(1, 2) * m * (v.T * v)[0]
        V -= m * (g.T * x)[0]
    Rd = sp.Rational(1, 2) * cphi * qd[4] ** 2
    for i, (m, R, z, h) in enumerate(balls):
        psi = q[5 + i]
        x = pos(sp.Matrix([R * sp.cos(psi), R * sp.sin(psi), z]))
        v = vel(x)
        T += sp.Rational(1, 2) * m * (v.T * v)[0]
        V -= m * (g.T * x)[0]
        Rd += sp.Rational(1, 2) * h * R**2 * qd[5 + i] ** 2
    for z, kx, ky, cx, cy in sups:
        x = pos(sp.Matrix([0, 0, z]))
        v = vel(x)
        V += sp.Rational(1, 2) * (kx * x[0] ** 2 + ky * x[1] ** 2)
        Rd += sp.Rational(1, 2) * (cx * v[0] ** 2 + cy * v[1] ** 2)
    L = T - V
    p = sp.Matrix([L.diff(v) for v in qd])
    M = p.jacobian(qd)
    rest = p.jacobian(q) * sp.Matrix(qd) - sp.Matrix([L.diff(v) for v in q]) + sp.Matrix([Rd.diff(v) for v in qd])
    params = [Mr, A, C, zg, kap, bet, gx, gy, gz, cphi]
    for group in (unb, balls, sups):
        for s in group:
            params.extend(s)
    f = sp.lambdify([q, qd, params], [M, rest], modules="numpy", cse=True)
    return f


def main():
    cases = json.load(sys.stdin)
    c0 = cases[0]
    n_unb, n_balls, n_sup = len(c0["unbalances"]), len(c0["balls"]), len(c0["supports"])
    f = derive(n_unb, n_balls, n_sup)
    out = []
    for c in cases:
        assert (len(c["unbalances"]), len(c["balls"]), len(c["supports"])) == (n_unb, n_balls, n_sup)
        r = c["rotor"]
        params = [r["mass"], r["a"], r["c"], r["zeta"], r["kappa"], r["beta"], *c["gravity"], c["spin_drag"]]
        for u in c["unbalances"]:
            params += [u["mass"], u["radius"], u["angle"], u["zeta"]]
        for b in c["balls"]:
            params += [b["mass"], b["radius"], b["zeta"], b["drag"]]
        for s in c["supports"]:
            params += [s["zeta"], s["kx"], s["ky"], s["cx"], s["cy"]]
        M, rest = f(c["q"], c["qd"], params)
        M = np.array(M, dtype=float)
        rhs = -np.array(rest, dtype=float).ravel()
        nq = M.shape[0]
        known = {}
        if c["lock_tilt"]:
            known[2] = 0.0
            known[3] = 0.0
        if c["prescribed"]:
            known[4] = c["phi_dd"]
        else:
            rhs[4] += c["torque"]
        free = [i for i in range(nq) if i not in known]
        for i, v in known.items():
            rhs -= M[:, i] * v
        acc = np.zeros(nq)
        acc[free] = np.linalg.solve(M[np.ix_(free, free)], rhs[free])
        for i, v in known.items():
            acc[i] = v
        out.append(acc.tolist())
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
