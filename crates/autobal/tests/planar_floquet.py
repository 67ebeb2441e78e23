"""Independent Floquet analysis of the planar rotor's balanced state on supports that differ by
direction (tests/planar_anisotropic.rs).

Lagrange's equations derived by SymPy from the energies in axes turning with the rotor at the
constant speed W (race centred, s2 = 0: disk m1 at C + s1, housing m2 at C, ball j of mass m_j
at C + r e^{i psi_j}), with the supports in FIXED axes: potential (k_x X^2 + k_y Y^2)/2 and
damping force -(c_x X', c_y Y') on C, (X, Y) = R(W t) (xi, eta); drag c_psi_j on ball j's motion
relative to the disk. The library instead uses d'Alembert's principle with the balls eliminated,
the support force written as -k u - c v - (dk conj(u) + dc conj(v)) e^{-2 i theta} in rotor
axes, dual-number Jacobians, its own DOP853 and shooting.

Reads JSON on stdin: {"cases": [{"p": {...}, "omega": W, "x": state, "period": T}],
"lowest": [{"p": {...}, "lo": W0, "hi": W1}]}. For each case: the multipliers of the monodromy
matrix over T (scipy solve_ivp, DOP853, rtol 1e-11, of Phi' = A(t) Phi with A(t) the SymPy
Jacobian at the constant state x, which is an equilibrium for every t: checked, max |f(t, x)| at
8 times is returned) and the largest |f|. For each "lowest": the speed in [lo, hi] where the
balanced state's largest multiplier modulus crosses 1, by bisection to 1e-7 relative, with the
balanced state computed here from the two-ball closed form and polished by scipy.optimize.root
on f(0, x) = 0, and the period pi/W.
"""
import json
import math
import sys

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import root


def model(n):
    m1, m2, s1, r, kx, ky, cx, cy, W, t = sp.symbols("m1 m2 s1 r k_x k_y c_x c_y W t", real=True)
    ms = sp.symbols(f"m1:{n + 1}_ball", positive=True)
    cps = sp.symbols(f"cpsi1:{n + 1}", real=True)
    xi, eta, xid, etad = sp.symbols("xi eta xid etad", real=True)
    psi = sp.symbols(f"psi1:{n + 1}", real=True)
    psid = sp.symbols(f"psid1:{n + 1}", real=True)
    q = [xi, eta, *psi]
    qd = [xid, etad, *psid]
    u = sp.Matrix([xi, eta])

    def vel(pos):
        dpos = sp.Matrix([sum(sp.diff(pos[i], qq) * vv for qq, vv in zip(q, qd)) for i in range(2)])
        return dpos + W * sp.Matrix([-pos[1], pos[0]])

    bodies = [(m1, u + sp.Matrix([s1, 0])), (m2, u)]
    bodies += [(m, u + r * sp.Matrix([sp.cos(p), sp.sin(p)])) for m, p in zip(ms, psi)]
    T = sum(m * (vel(pos).T * vel(pos))[0] for m, pos in bodies) / 2
    th = W * t
    R = sp.Matrix([[sp.cos(th), -sp.sin(th)], [sp.sin(th), sp.cos(th)]])
    XY = R * u
    V = (kx * XY[0] ** 2 + ky * XY[1] ** 2) / 2
    vfix = R * vel(u)  # absolute velocity of C in fixed axes
    F = sp.Matrix([-cx * vfix[0], -cy * vfix[1]])
    Qc = R.T * F  # generalised forces on (xi, eta)
    Q = [Qc[0], Qc[1]] + [-c * pd for c, pd in zip(cps, psid)]
    N = len(q)
    Tqd = [sp.diff(T, v) for v in qd]
    M = sp.Matrix(N, N, lambda i, j: sp.diff(Tqd[i], qd[j]))
    h = sp.Matrix([Q[i] - sp.diff(V, q[i]) + sp.diff(T, q[i]) - sum(sp.diff(Tqd[i], q[j]) * qd[j] for j in range(N)) for i in range(N)])
    z = q + qd
    params = [m1, m2, s1, r, kx, ky, cx, cy, W, *ms, *cps]
    fM = sp.lambdify([params, t, z], M, "numpy")
    fh = sp.lambdify([params, t, z], h, "numpy")
    fdM = sp.lambdify([params, t, z], sp.Matrix.hstack(*[M.diff(v) for v in z]), "numpy")
    fdh = sp.lambdify([params, t, z], h.jacobian(z), "numpy")
    return fM, fh, fdM, fdh


MODELS = {}


class Rotor:
    def __init__(self, p, W):
        n = p["n"]
        if n not in MODELS:
            MODELS[n] = model(n)
        self.fM, self.fh, self.fdM, self.fdh = MODELS[n]
        self.N = 2 + n
        self.par = [p["m1"], p["m2"], p["s1"], p["r"], p["k_x"], p["k_y"], p["c_x"], p["c_y"], W, *p["masses"], *p["drags"]]

    def rhs(self, t, z):
        N = self.N
        M = np.array(self.fM(self.par, t, z), dtype=float)
        h = np.array(self.fh(self.par, t, z), dtype=float).reshape(N)
        return np.concatenate([z[N:], np.linalg.solve(M, h)])

    def jac(self, t, z):
        N = self.N
        M = np.array(self.fM(self.par, t, z), dtype=float)
        h = np.array(self.fh(self.par, t, z), dtype=float).reshape(N)
        qdd = np.linalg.solve(M, h)
        dM = np.array(self.fdM(self.par, t, z), dtype=float).reshape(N, 2 * N, N)
        dh = np.array(self.fdh(self.par, t, z), dtype=float)
        A = np.zeros((2 * N, 2 * N))
        A[:N, N:] = np.eye(N)
        A[N:, :] = np.linalg.solve(M, dh - np.einsum("ijk,k->ij", dM, qdd))
        return A


def monodromy(rot, x, T):
    n = 2 * rot.N
    z = np.array(x, dtype=float)

    def var(t, y):
        return (rot.jac(t, z) @ y.reshape(n, n)).ravel()

    s = solve_ivp(var, (0.0, T), np.eye(n).ravel(), method="DOP853", rtol=1e-11, atol=1e-13)
    assert s.success, s.message
    return s.y[:, -1].reshape(n, n)


def balanced(p, W):
    """u = 0, the two balls at their closed-form angles (sum of m_j r e^{i psi_j} = -m1 s1),
    polished by root on f(0, x) = 0."""
    a, b = p["masses"][0] * p["r"], p["masses"][1] * p["r"]
    d = p["m1"] * p["s1"]  # |D|, D = -m1 s1 along -x: beta = pi
    da = math.acos((d * d + a * a - b * b) / (2 * d * a))
    db = math.acos((d * d + b * b - a * a) / (2 * d * b))
    x0 = np.array([0.0, 0.0, math.pi + da, math.pi - db, 0.0, 0.0, 0.0, 0.0])
    rot = Rotor(p, W)
    sol = root(lambda x: rot.rhs(0.0, x), x0, method="hybr", options={"xtol": 1e-14})
    return rot, sol.x


def largest(p, W):
    rot, x = balanced(p, W)
    mu = np.linalg.eigvals(monodromy(rot, x, math.pi / W))
    return float(np.abs(mu).max())


def main():
    req = json.load(sys.stdin)
    out = {"cases": [], "lowest": []}
    for case in req.get("cases", []):
        rot = Rotor(case["p"], case["omega"])
        T = case["period"]
        f = max(float(np.abs(rot.rhs(t, np.array(case["x"]))).max()) for t in np.linspace(0.0, T, 8))
        mu = np.linalg.eigvals(monodromy(rot, case["x"], T))
        out["cases"].append({"multipliers": [[float(m.real), float(m.imag)] for m in mu], "rhs": f})
    for job in req.get("lowest", []):
        p, lo, hi = job["p"], job["lo"], job["hi"]
        flo, fhi = largest(p, lo) - 1.0, largest(p, hi) - 1.0
        assert flo > 0.0 > fhi, (flo, fhi)
        while hi - lo > 1e-7 * hi:
            mid = 0.5 * (lo + hi)
            if largest(p, mid) > 1.0:
                lo = mid
            else:
                hi = mid
        out["lowest"].append(0.5 * (lo + hi))
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
