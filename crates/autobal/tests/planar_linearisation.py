"""Independent linearisation of the planar rotor at constant speed (tests/analysis.rs).

Lagrange's equations from the kinetic and potential energies in axes turning with the rotor at
the constant speed W (paper 004's rotor: disk m1 at C + s1, housing m2 at the race centre
E = C + s2 e^{i gamma}, n balls m3 at E + r e^{i psi_j}; shaft stiffness k; damping c on the
absolute velocity of C; drag c_psi on each ball's motion relative to the disk), derived by SymPy,
where the library uses d'Alembert's principle with the ball accelerations eliminated and
dual-number derivatives. Reads a JSON list of cases {"p": {...}, "omega": W, "x": reduced
state (xi, eta, psi_1..n, rates)} on stdin, writes for each the eigenvalues of the Jacobian of
x' = f(x) at x (numpy.linalg.eigvals: LAPACK dgeev, balanced) and max |f(x)| scaled, so the
caller can check that x is stationary in these equations too.
"""
import json
import sys

import numpy as np
import sympy as sp


def model(n):
    m1, m2, m3, s1, s2, g, r, k, c, cpsi, W = sp.symbols("m1 m2 m3 s1 s2 gamma r k c c_psi W", real=True)
    xi, eta = sp.symbols("xi eta", real=True)
    xid, etad = sp.symbols("xid etad", real=True)
    psi = sp.symbols(f"psi1:{n + 1}", real=True)
    psid = sp.symbols(f"psid1:{n + 1}", real=True)
    q = [xi, eta, *psi]
    qd = [xid, etad, *psid]
    u = sp.Matrix([xi, eta])
    ud = sp.Matrix([xid, etad])

    def vel(pos):
        # absolute velocity in rotor axes: d(pos)/dt (through the coordinates) + W x pos
        dpos = sp.Matrix([sum(sp.diff(pos[i], qq) * vv for qq, vv in zip(q, qd)) for i in range(2)])
        return dpos + W * sp.Matrix([-pos[1], pos[0]])

    e = sp.Matrix([s2 * sp.cos(g), s2 * sp.sin(g)])
    bodies = [(m1, u + sp.Matrix([s1, 0])), (m2, u + e)]
    bodies += [(m3, u + e + r * sp.Matrix([sp.cos(p), sp.sin(p)])) for p in psi]
    T = sum(m * (vel(pos).T * vel(pos))[0] for m, pos in bodies) / 2
    V = k * (xi**2 + eta**2) / 2
    vc = ud + W * sp.Matrix([-eta, xi])
    Q = [-c * vc[0], -c * vc[1]] + [-cpsi * pd for pd in psid]
    N = len(q)
    Tqd = [sp.diff(T, v) for v in qd]
    M = sp.Matrix(N, N, lambda i, j: sp.diff(Tqd[i], qd[j]))
    h = sp.Matrix([Q[i] - sp.diff(V, q[i]) + sp.diff(T, q[i]) - sum(sp.diff(Tqd[i], q[j]) * qd[j] for j in range(N)) for i in range(N)])
    z = q + qd
    params = [m1, m2, m3, s1, s2, g, r, k, c, cpsi, W]
    fM = sp.lambdify([params, z], M, "numpy")
    fh = sp.lambdify([params, z], h, "numpy")
    fdM = [sp.lambdify([params, z], M.diff(v), "numpy") for v in z]
    fdh = sp.lambdify([params, z], h.jacobian(z), "numpy")
    return fM, fh, fdM, fdh


def main():
    cases = json.load(sys.stdin)
    models = {}
    out = []
    for case in cases:
        p = case["p"]
        n = p["n"]
        if n not in models:
            models[n] = model(n)
        fM, fh, fdM, fdh = models[n]
        params = [p["m1"], p["m2"], p["m3"], p["s1"], p["s2"], p["gamma"], p["r"], p["k"], p["c"], p["c_psi"], case["omega"]]
        z = case["x"]
        N = 2 + n
        M = np.array(fM(params, z), dtype=float)
        h = np.array(fh(params, z), dtype=float).reshape(N)
        qdd = np.linalg.solve(M, h)
        # d qdd / dz = M^-1 (dh/dz - (dM/dz) qdd)
        dh = np.array(fdh(params, z), dtype=float)
        dq = np.empty((N, 2 * N))
        for j in range(2 * N):
            dq[:, j] = np.linalg.solve(M, dh[:, j] - np.array(fdM[j](params, z), dtype=float) @ qdd)
        A = np.zeros((2 * N, 2 * N))
        A[:N, N:] = np.eye(N)
        A[N:, :] = dq
        f = np.concatenate([np.array(z[N:]), qdd])
        lam = np.linalg.eigvals(A)
        out.append({"eigenvalues": [[float(l.real), float(l.imag)] for l in lam], "rhs": [float(v) for v in f]})
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main()
