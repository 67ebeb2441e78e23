"""An independent derivation of a linear rotor-bearing model with ball balancers.

Written from the physics (Lagrange's equations for the balls, SymPy), not from autobal's source;
only the docs' statement of the model is used (docs/guide/your-own-rotor.md, "The model", "The
balls"): the structure in fixed axes

    M q'' + (C + W G) q' + K q = f        (W the prescribed constant speed)

with DOFs per node x, y (and alpha, beta: the tilt's rotation vector components about x, y),
an unbalance at a node (m e, phase, axial offset z: the force acts at the point
x + z beta, y - z alpha), and balls of mass m_j on a race of radius R whose centre is the node's
point at the plane's axial offset z and whose plane tilts with the node. A ball's position in
fixed axes is

    r_j = (x, y, 0) + Rot(alpha, beta) (R cos th_j, R sin th_j, z),   th_j = W t + psi_j,

Rot = exp([w]x) with the rotation vector w = (alpha, beta, 0) (the symmetric chart: the only one
that treats x and y alike), its kinetic energy 1/2 m_j |r_j'|^2 kept exact in th_j and to second
order in the structure's coordinates (q and q' of order one), drag -d_j psi_j' on psi_j, and
gravity g = (g_x, g_y) as the potential -m_j g . r_j (same truncation) plus the structure's
weight M r_g (r_g: g_x on every x DOF, g_y on every y DOF).

Axes turning with the rotor: q = T(W t) p, T the quarter-turn generator J's exponential acting
on every (x, y) and (alpha, beta) pair. The turning-axes field is obtained from the fixed-axes one
exactly (q'' = T (p'' + 2 W J p' + W^2 J^2 p)), so that nothing of autobal's turning-axes matrices
is assumed. Isotropic structure, no gravity: autonomous, the balanced state an equilibrium;
otherwise periodic (pi/W for direction-dependent bearings, 2 pi/W with gravity).

Derivatives: complex-step (exact to round-off for this analytic field; the linear solve for the
accelerations is done in complex arithmetic), hence the Jacobian, Newton, the variational
equations and the monodromy matrix (solve_ivp DOP853, rtol 1e-11).
"""

from __future__ import annotations

import functools

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

H_CS = 1e-30  # complex step


@functools.lru_cache(maxsize=None)
def ball_equations(grav2=True):
    """Euler-Lagrange terms of one ball on a node with (x, y, a, b) and the ball angle th.

    Returns lambdified A(q, th; m, R, z) (5x5, coefficient of (x'', y'', a'', b'', th'')) and
    rest(q, qd, th, thd; m, R, z, gx, gy) (the remaining terms of d/dt dL/dqd - dL/dq)."""
    t = sp.symbols("t")
    m, R, z, gx, gy, eps = sp.symbols("m R z g_x g_y epsilon")
    names = ["x", "y", "a", "b", "th"]
    f = {n: sp.Function(n)(t) for n in names}
    x, y, a, b, th = (f[n] for n in names)
    W = sp.Matrix([[0, 0, b], [0, 0, -a], [-b, a, 0]]) * eps  # [w]x, w = (a, b, 0)
    Rot = sp.eye(3) + W + W * W / 2  # exp to second order
    p = sp.Matrix([R * sp.cos(th), R * sp.sin(th), z])
    r = sp.Matrix([eps * x, eps * y, 0]) + Rot * p
    v = r.diff(t)
    T = sp.expand(m * (v.T * v)[0] / 2)
    V = sp.expand(-m * (gx * r[0] + gy * r[1]))
    # grav2: the weight's potential to second order in the tilt as the kinetic energy; without
    # it, to first order (the weight on the race centre and its torque on the ball)
    Vs = sp.series(V, eps, 0, 3 if grav2 else 2).removeO()
    L = (sp.series(T, eps, 0, 3).removeO() - Vs).subs(eps, 1)
    L = sp.expand(L)
    # symbols for the derivatives
    q = sp.symbols("x y a b th")
    qd = sp.symbols("xd yd ad bd thd")
    qdd = sp.symbols("xdd ydd add bdd thdd")
    subs = {}
    for n, s0, s1, s2 in zip(names, q, qd, qdd):
        subs[f[n].diff(t, 2)] = s2
    for n, s0, s1, s2 in zip(names, q, qd, qdd):
        subs[f[n].diff(t)] = s1
    for n, s0, s1, s2 in zip(names, q, qd, qdd):
        subs[f[n]] = s0
    eqs = []
    for n in names:
        e = L.diff(f[n].diff(t)).diff(t) - L.diff(f[n])
        eqs.append(sp.expand(e.subs(subs)))
    A = sp.Matrix([[e.coeff(s2) for s2 in qdd] for e in eqs])
    rest = sp.Matrix([sp.expand(e - sum(e.coeff(s2) * s2 for s2 in qdd)) for e in eqs])
    args_A = (*q, m, R, z)
    args_r = (*q, *qd, m, R, z, gx, gy)
    fA = [[sp.lambdify(args_A, A[i, j], "numpy") for j in range(5)] for i in range(5)]
    fr = [sp.lambdify(args_r, rest[i], "numpy") for i in range(5)]
    return fA, fr, L, A, rest


class Node:
    def __init__(self, ix, iy, ia=None, ib=None):
        self.ix, self.iy, self.ia, self.ib = ix, iy, ia, ib

    @property
    def tilts(self):
        return self.ia is not None


def nodes_from_layout(n_nodes, tilts=True):
    """ROSS's order: x, y (, alpha, beta) node after node."""
    k = 4 if tilts else 2
    return [Node(k * i, k * i + 1, *( (k * i + 2, k * i + 3) if tilts else ())) for i in range(n_nodes)]


class LinearModel:
    """M, C, K, G: N x N in fixed axes (K, C may differ by direction). planes: list of dicts
    node, R, m (list per ball), d (list of drags per ball), z (offset). unbalances: list of dicts
    node, me, phase, z. gravity: (g_x, g_y) or None."""

    def __init__(self, M, C, K, G, nodes, planes, unbalances, gravity=None, grav2=True):
        self.grav2 = grav2
        self.M, self.C, self.K, self.G = (np.asarray(A, float) for A in (M, C, K, G))
        self.N = self.M.shape[0]
        self.nodes = nodes
        self.planes = planes
        self.unb = unbalances
        self.g = np.zeros(2) if gravity is None else np.asarray(gravity, float)
        self.balls = []  # (node, m, R, z, d)
        for pl in planes:
            for mj, dj in zip(pl["m"], pl["d"]):
                self.balls.append((nodes[pl["node"]], mj, pl["R"], pl.get("z", 0.0), dj))
        self.nb = len(self.balls)
        self.n = 2 * (self.N + self.nb)
        Jm = np.zeros((self.N, self.N))
        for nd in nodes:
            for i, j in ((nd.ix, nd.iy), (nd.ia, nd.ib)):
                if i is not None:
                    Jm[j, i] = 1.0
                    Jm[i, j] = -1.0
        self.J = Jm
        rg = np.zeros(self.N)
        for nd in nodes:
            rg[nd.ix], rg[nd.iy] = self.g
        self.weight = self.M @ rg

    def isotropic(self):
        return all(np.allclose(A @ self.J, self.J @ A, rtol=0, atol=1e-12 * (1 + abs(A).max()))
                   for A in (self.M, self.C, self.K, self.G))

    def T(self, phi):
        c, s = np.cos(phi), np.sin(phi)
        return np.eye(self.N) * c + self.J * s if True else None  # exp(phi J): J^2 = -I on pairs

    def period(self, w):
        if np.any(self.g != 0):
            return 2 * np.pi / w
        return np.pi / w

    def autonomous(self):
        return self.isotropic() and not np.any(self.g != 0)

    # ---- fixed axes ----
    def fixed_acc(self, t, q, qd, psi, psid, w):
        """Accelerations (q'', psi''): q etc. of shape (N, B) / (nb, B), possibly complex."""
        fA, fr, *_ = ball_equations(self.grav2)
        B = q.shape[1]
        N, nb = self.N, self.nb
        dt = np.result_type(q, qd, psi, psid)
        Mt = np.zeros((B, N + nb, N + nb), dtype=dt)
        Mt[:, :N, :N] = self.M
        rhs = np.zeros((B, N + nb), dtype=dt)
        f = np.zeros((N, B), dtype=dt) + self.weight[:, None]
        for u in self.unb:
            nd = self.nodes[u["node"]]
            ph = w * t + u.get("phase", 0.0)
            Fx, Fy = u["me"] * w * w * np.cos(ph), u["me"] * w * w * np.sin(ph)
            f[nd.ix] += Fx
            f[nd.iy] += Fy
            zz = u.get("z", 0.0)
            if zz != 0.0:
                f[nd.ia] += -zz * Fy
                f[nd.ib] += zz * Fx
        rhs[:, :N] = (f - (self.C + w * self.G) @ qd - self.K @ q).T
        for j, (nd, mj, R, zz, dj) in enumerate(self.balls):
            idx = [nd.ix, nd.iy] + ([nd.ia, nd.ib] if nd.tilts else [])
            zero = np.zeros(B, dtype=dt)
            qa = [q[nd.ix], q[nd.iy]] + ([q[nd.ia], q[nd.ib]] if nd.tilts else [zero, zero])
            qda = [qd[nd.ix], qd[nd.iy]] + ([qd[nd.ia], qd[nd.ib]] if nd.tilts else [zero, zero])
            th = w * t + psi[j]
            thd = w + psid[j]
            gl = [0, 1] + ([2, 3] if nd.tilts else [])
            gidx = idx + [N + j]
            loc = gl + [4]
            for r_, gi in zip(loc, gidx):
                for c_, gj in zip(loc, gidx):
                    Mt[:, gi, gj] += np.broadcast_to(fA[r_][c_](*qa, th, mj, R, zz), (B,))
                rhs[:, gi] -= np.broadcast_to(
                    fr[r_](*qa, th, *qda, thd, mj, R, zz, self.g[0], self.g[1]), (B,))
            rhs[:, N + j] -= dj * psid[j]
        acc = np.linalg.solve(Mt, rhs[..., None])[..., 0].T
        return acc[:N], acc[N:]

    # ---- turning axes ----
    def rot_rhs(self, t, s, w):
        """s: (n,) or (n, B): (p, psi, pd, psid) in turning axes."""
        one = s.ndim == 1
        if one:
            s = s[:, None]
        N, nb = self.N, self.nb
        p, psi, pd, psid = s[:N], s[N:N + nb], s[N + nb:2 * N + nb], s[2 * N + nb:]
        T = self.T(w * t)
        q = T @ p
        qd = T @ (pd + w * self.J @ p)
        qdd, psidd = self.fixed_acc(t, q, qd, psi, psid, w)
        pdd = T.T @ qdd - 2 * w * self.J @ pd - w * w * self.J @ (self.J @ p)
        out = np.concatenate([pd, psid, pdd, psidd])
        return out[:, 0] if one else out

    def jac(self, t, s, w):
        n = self.n
        S = s[:, None] + 1j * H_CS * np.eye(n)
        return (self.rot_rhs(t, S, w).imag / H_CS)

    # ---- balanced state ----
    def balanced_guess(self, w):
        """Balls placed so that the plane's balls cancel the static unbalance (one plane, two
        equal balls), the structure at rest."""
        psi = np.zeros(self.nb)
        U = sum(u["me"] * np.exp(1j * u.get("phase", 0.0)) for u in self.unb)
        k = 0
        own = [sum(u["me"] * np.exp(1j * u.get("phase", 0.0)) for u in self.unb
                   if u["node"] == pl["node"]) for pl in self.planes]
        for pl, o in zip(self.planes, own):
            cap = sum(pl["m"]) * pl["R"]
            # one plane: the whole static unbalance; several: the unbalance at its own node
            share = -U if len(self.planes) == 1 else (-o if o != 0 else -U / len(self.planes))
            c = np.clip(abs(share) / cap, 0, 1)
            a = np.arccos(c)
            ang = np.angle(share)
            psi[k], psi[k + 1] = ang + a, ang - a
            k += len(pl["m"])
        return np.concatenate([np.zeros(self.N), psi, np.zeros(self.N + self.nb)])

    def isotropised(self):
        """The model with every matrix averaged over the turn, (A + J^T A J)/2."""
        av = lambda A: 0.5 * (A + self.J.T @ A @ self.J)
        return LinearModel(av(self.M), av(self.C), av(self.K), av(self.G), self.nodes,
                           self.planes, self.unb, None, self.grav2)

    def orbit_start(self, w, s0=None):
        """Start for shooting: the isotropised model's equilibrium (exact where the balanced
        state leaves the anisotropic parts at rest)."""
        return self.isotropised().equilibrium(w, s0)

    def equilibrium(self, w, s0=None, tol=1e-13, maxit=50):
        """Newton on (p, psi) with p' = psi' = 0 (autonomous case)."""
        s = self.balanced_guess(w) if s0 is None else np.array(s0, float)
        m = self.N + self.nb
        for _ in range(maxit):
            F = self.rot_rhs(0.0, s, w)[m:]
            Jf = self.jac(0.0, s, w)[m:, :m]
            dx = np.linalg.solve(Jf, -F)
            s[:m] += dx
            if np.max(np.abs(dx)) < tol * (1 + np.max(np.abs(s[:m]))):
                break
        return s

    def eig(self, w, s):
        return np.linalg.eigvals(self.jac(0.0, s, w))

    def _var(self, t, Y, w):
        n = self.n
        x = Y[:n]
        Phi = Y[n:].reshape(n, n)
        S = x[:, None] + 1j * H_CS * np.concatenate([np.zeros((n, 1)), Phi], axis=1)
        out = self.rot_rhs(t, S, w)
        return np.concatenate([out[:, 0].real, (out[:, 1:].imag / H_CS).ravel()])

    def monodromy(self, w, x0, T=None, rtol=1e-11, atol=1e-13):
        T = self.period(w) if T is None else T
        n = self.n
        Y0 = np.concatenate([x0, np.eye(n).ravel()])
        sol = solve_ivp(self._var, (0, T), Y0, method="DOP853", rtol=rtol, atol=atol, args=(w,))
        return sol.y[:n, -1], sol.y[n:, -1].reshape(n, n)

    def periodic_orbit(self, w, x0, T=None, tol=1e-11, maxit=15):
        T = self.period(w) if T is None else T
        x = np.array(x0, float)
        for it in range(maxit):
            xT, Phi = self.monodromy(w, x, T)
            r = xT - x
            dx = np.linalg.solve(Phi - np.eye(self.n), -r)
            x += dx
            if np.max(np.abs(dx)) < tol * (1 + np.max(np.abs(x))):
                break
        if np.max(np.abs(dx)) > 1e-8 * (1 + np.max(np.abs(x))):
            xT, Phi = self.monodromy(w, x, T)  # else Phi at x - dx: differs by O(dx)
        self.last_shoot = (it + 1, float(np.max(np.abs(dx))))
        mu = np.linalg.eigvals(Phi)
        return x, mu, np.log(np.abs(mu)) / T


def bisect(f, a, b, fa=None, tol=1e-10):
    fa = f(a) if fa is None else fa
    for _ in range(200):
        c = 0.5 * (a + b)
        fc = f(c)
        if (fc > 0) == (fa > 0):
            a, fa = c, fc
        else:
            b = c
        if b - a < tol * abs(b):
            break
    return 0.5 * (a + b)


# ---- a small shaft built here (Euler-Bernoulli, consistent mass, rigid disks) ----
def shaft(n_el, L, d, E, rho, disks=(), bearings=()):
    """Returns M, K, G (bearings' K, C separately: bearings list of (node, kxx, kyy, cxx, cyy)),
    DOFs x, y, alpha, beta per node; x' = beta, y' = -alpha (a point at axial offset z from the
    node is at x + z beta, y - z alpha)."""
    n = n_el + 1
    N = 4 * n
    A = np.pi * d * d / 4
    I = np.pi * d ** 4 / 64
    M = np.zeros((N, N))
    K = np.zeros((N, N))
    G = np.zeros((N, N))
    C = np.zeros((N, N))
    l = L / n_el
    ke = E * I / l ** 3 * np.array([[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l],
                                     [-12, -6 * l, 12, -6 * l], [6 * l, 2 * l * l, -6 * l, 4 * l * l]])
    me = rho * A * l / 420 * np.array([[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
                                        [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    for e in range(n_el):
        # x-plane: (x_i, beta_i, x_j, beta_j); y-plane: (y_i, -alpha_i, y_j, -alpha_j)
        ix = [4 * e, 4 * e + 3, 4 * e + 4, 4 * e + 7]
        iy = [4 * e + 1, 4 * e + 2, 4 * e + 5, 4 * e + 6]
        sy = np.array([1, -1, 1, -1])
        for a_ in range(4):
            for b_ in range(4):
                K[ix[a_], ix[b_]] += ke[a_, b_]
                M[ix[a_], ix[b_]] += me[a_, b_]
                K[iy[a_], iy[b_]] += sy[a_] * sy[b_] * ke[a_, b_]
                M[iy[a_], iy[b_]] += sy[a_] * sy[b_] * me[a_, b_]
    for (nd, m, Id, Ip) in disks:
        i = 4 * nd
        M[i, i] += m
        M[i + 1, i + 1] += m
        M[i + 2, i + 2] += Id
        M[i + 3, i + 3] += Id
        # the ring of balls' (and so a disk's) gyroscopic sign from the same Lagrangian:
        # KE term 1/2 Ip W (alpha' beta - beta' alpha) -> Ip W (beta', -alpha') in (alpha, beta)
        G[i + 2, i + 3] += Ip
        G[i + 3, i + 2] -= Ip
    for (nd, kxx, kyy, cxx, cyy) in bearings:
        i = 4 * nd
        K[i, i] += kxx
        K[i + 1, i + 1] += kyy
        C[i, i] += cxx
        C[i + 1, i + 1] += cyy
    return M, C, K, G


# ---- configs for the CLI ----
def write_config(folder, name, M, C, K, G, planes, unbalances, *, tilts=True, gravity=None,
                 bearings=(), extra=""):
    """Writes NAME_{M,C,K,G}.npy and NAME.toml (layout x,y[,alpha,beta]); planes as in
    LinearModel but with equal balls (m[0], d[0] used, n = len(m)); bearings: list of dicts
    written as [[linear_rotor.bearings]] tables verbatim."""
    import os
    for key, A in (("M", M), ("C", C), ("K", K), ("G", G)):
        np.save(os.path.join(folder, f"{name}_{key}.npy"), np.asarray(A, float))
    f = lambda v: repr(float(v))
    lines = ["[linear_rotor]", f'layout = "{"x,y,alpha,beta" if tilts else "x,y"}"',
             f'm = "{name}_M.npy"', f'k = "{name}_K.npy"', f'c = "{name}_C.npy"',
             f'g = "{name}_G.npy"']
    if gravity is not None:
        lines.append(f"gravity = [{f(gravity[0])}, {f(gravity[1])}]")
    for b in bearings:
        lines.append("[[linear_rotor.bearings]]")
        for k_, v in b.items():
            lines.append(f"{k_} = {v!r}" if not isinstance(v, list) else
                         f"{k_} = [{', '.join(f(x) for x in v)}]")
    for u in unbalances:
        lines += ["[[linear_rotor.unbalance]]", f"node = {u['node']}", f"me = {f(u['me'])}",
                  f"phase = {f(u.get('phase', 0.0))}", f"offset = {f(u.get('z', 0.0))}"]
    for pl in planes:
        lines += ["[[linear_rotor.balancer]]", f"node = {pl['node']}", f"radius = {f(pl['R'])}",
                  f"balls = {len(pl['m'])}", f"ball_mass = {f(pl['m'][0])}",
                  f"drag = {f(pl['d'][0])}", f"offset = {f(pl.get('z', 0.0))}"]
    lines.append(extra)
    path = os.path.join(folder, name + ".toml")
    with open(path, "w") as fh:
        fh.write("\n".join(lines) + "\n")
    return path
