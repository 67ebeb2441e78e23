"""An independent derivation of the planar rotor with a ball balancer, in axes turning with it.

Written from the physics (Lagrange's equations), not from autobal's source. The rotor turns at
a prescribed constant speed w about the fixed bearing axis. Coordinates, all in axes turning
with the rotor (x' along the disk's eccentricity CG):

    z = u + i v          the shaft point C
    psi_j                ball j's angle on its race, measured from CG

Points (complex, turning axes):  disk centre of mass  G = z + s1,
housing centre E = z + s2 e^{i gamma},  ball j  P_j = E + r e^{i psi_j}.
A point p(t) of the turning axes has the inertial velocity (turning components) p' + i w p, and
fixed-axes position p e^{i w t}.

    T = 1/2 m1 |G' + i w G|^2 + 1/2 m2 |E' + i w E|^2 + sum_j 1/2 m_j |P_j' + i w P_j|^2
    V = 1/2 (k_x X^2 + k_y Y^2) - sum_masses m (g_x Re(p e^{iwt}) + g_y Im(p e^{iwt})),
        X + iY = z e^{iwt}
    R = 1/2 (c_x Xd^2 + c_y Yd^2) + sum_j 1/2 d_j psi_j'^2,   Xd + i Yd = (z' + i w z) e^{iwt}

(the disk's own moment of inertia and the housing's turn at the constant speed: constants in T).
With k_x = k_y, c_x = c_y and g = 0 the equations are autonomous (equilibria); otherwise they are
periodic in t with period pi/w (anisotropy) or 2 pi/w (gravity).

For the spatial rotor of papers 000/003 with its tilt locked (`[spatial] lock_tilt = true`) the
same equations hold with m1 = m0 (unbalance mass) at s1 = R0, m2 = M_r (the rotor, centred),
s2 = 0, k = c_L + c_R, c = h_L + h_R, balls of mass m on race R with d_j = h_A R^2.
"""

from __future__ import annotations

import functools

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve


@functools.lru_cache(maxsize=None)
def build(n: int):
    """Lagrange's equations of the n-ball planar rotor, as M(q, t) q'' = F(q, q', t) plus their
    exact partial derivatives (SymPy), lambdified. Returns a dict of callables taking
    (t, q, qd, params) or (t, q, qd, qdd, params)."""
    t = sp.Symbol("t", real=True)
    u, v = sp.symbols("u v", real=True)
    ud, vd = sp.symbols("ud vd", real=True)
    psi = sp.symbols(f"psi1:{n + 1}", real=True)
    psid = sp.symbols(f"psid1:{n + 1}", real=True)
    q = [u, v, *psi]
    qd = [ud, vd, *psid]
    qdd = sp.symbols(f"a1:{n + 3}", real=True)
    m1, m2, s1, s2, gam, r, kx, ky, cx, cy, w, gx, gy = sp.symbols(
        "m1 m2 s1 s2 gamma r kx ky cx cy w gx gy", real=True
    )
    mb = sp.symbols(f"mb1:{n + 1}", real=True)
    db = sp.symbols(f"db1:{n + 1}", real=True)
    params = [m1, m2, s1, s2, gam, r, kx, ky, cx, cy, w, gx, gy, *mb, *db]

    I = sp.I
    z = u + I * v
    zd = ud + I * vd
    E = z + s2 * sp.exp(I * gam)
    G = z + s1
    rot = sp.exp(I * w * t)

    def ke(m, p, pd):
        vel = pd + I * w * p
        return sp.Rational(1, 2) * m * sp.expand(vel * sp.conjugate(vel))

    def pot_g(m, p):
        pf = sp.expand(p * rot)
        return -m * (gx * sp.re(pf) + gy * sp.im(pf))

    T = ke(m1, G, zd) + ke(m2, E, zd)
    V = pot_g(m1, G) + pot_g(m2, E)
    for j in range(n):
        P = E + r * sp.exp(I * psi[j])
        Pd = zd + I * r * psid[j] * sp.exp(I * psi[j])
        T += ke(mb[j], P, Pd)
        V += pot_g(mb[j], P)
    Xf = sp.re(sp.expand(z * rot))
    Yf = sp.im(sp.expand(z * rot))
    vf = sp.expand((zd + I * w * z) * rot)
    Xd, Yd = sp.re(vf), sp.im(vf)
    V += sp.Rational(1, 2) * (kx * Xf**2 + ky * Yf**2)
    R = sp.Rational(1, 2) * (cx * Xd**2 + cy * Yd**2) + sum(
        sp.Rational(1, 2) * db[j] * psid[j] ** 2 for j in range(n)
    )
    R = sp.expand(sp.expand_complex(R))
    L = sp.expand(sp.expand_complex(T - V))
    N = n + 2
    # d/dt dL/dqd - dL/dq + dR/dqd = 0  ->  M qdd = F
    Mmat = sp.zeros(N, N)
    F = sp.zeros(N, 1)
    for a in range(N):
        p_a = sp.diff(L, qd[a])
        for b in range(N):
            Mmat[a, b] = sp.diff(p_a, qd[b])
        dpdt = sum(sp.diff(p_a, q[b]) * qd[b] for b in range(N)) + sp.diff(p_a, t)
        F[a] = (-(dpdt - sp.diff(L, q[a]) + sp.diff(R, qd[a])))
    resid = Mmat * sp.Matrix(qdd) - F  # = 0 on the motion
    Jq = resid.jacobian(q)
    Jqd = resid.jacobian(qd)
    args = (t, q, qd, params)
    return {
        "n": n,
        "M": sp.lambdify(args, Mmat, "numpy"),
        "F": sp.lambdify(args, F, "numpy"),
        "Jq": sp.lambdify((t, q, qd, qdd, params), Jq, "numpy"),
        "Jqd": sp.lambdify((t, q, qd, qdd, params), Jqd, "numpy"),
        "symbols": (t, q, qd, qdd, params, Mmat, F),
    }


class Planar:
    """Numbers of one configuration (SI or any consistent units)."""

    def __init__(self, m1, m2, s1, s2, gamma, r, kx, ky, cx, cy, ball_masses, ball_drags,
                 gx=0.0, gy=0.0):
        self.n = len(ball_masses)
        self.sys = build(self.n)
        self.base = [m1, m2, s1, s2, gamma, r, kx, ky, cx, cy]
        self.g = [gx, gy]
        self.mb = list(ball_masses)
        self.db = list(ball_drags)
        self.m1, self.s1, self.s2, self.gamma, self.r = m1, s1, s2, gamma, r
        self.kx, self.ky, self.cx, self.cy = kx, ky, cx, cy

    def p(self, w):
        return [*self.base, w, *self.g, *self.mb, *self.db]

    @property
    def autonomous(self):
        return self.kx == self.ky and self.cx == self.cy and self.g == [0.0, 0.0]

    def period(self, w):
        """The period of the equations in turning axes (0 when autonomous)."""
        if self.g != [0.0, 0.0]:
            return 2 * np.pi / abs(w)
        if self.kx != self.ky or self.cx != self.cy:
            return np.pi / abs(w)
        return 0.0

    def rhs(self, t, x, w):
        N = self.n + 2
        q, qd = x[:N], x[N:]
        p = self.p(w)
        M = np.asarray(self.sys["M"](t, q, qd, p), float)
        F = np.asarray(self.sys["F"](t, q, qd, p), float).ravel()
        return np.concatenate([qd, np.linalg.solve(M, F)])

    def jac(self, t, x, w):
        """Exact Jacobian of the first-order system (from SymPy's partial derivatives)."""
        N = self.n + 2
        q, qd = x[:N], x[N:]
        p = self.p(w)
        M = np.asarray(self.sys["M"](t, q, qd, p), float)
        F = np.asarray(self.sys["F"](t, q, qd, p), float).ravel()
        a = np.linalg.solve(M, F)
        Jq = np.asarray(self.sys["Jq"](t, q, qd, a, p), float)
        Jqd = np.asarray(self.sys["Jqd"](t, q, qd, a, p), float)
        A = np.zeros((2 * N, 2 * N))
        A[:N, N:] = np.eye(N)
        A[N:, :N] = -np.linalg.solve(M, Jq)
        A[N:, N:] = -np.linalg.solve(M, Jqd)
        return A

    # ---- balanced (or stationary) state -------------------------------------------------
    def balanced_guess(self, w=None):
        """Closed form: the race centre E on the axis, the balls' resultant cancelling the
        eccentricity about E. Two balls (or all equal): symmetric about -CG direction.
        Returns (z, psi) or None when the capacity is short."""
        n = self.n
        # total moment about E that the balls must cancel: m1 (s1 - E) + m2 (0)... with E at
        # the origin, C = -s2 e^{i gamma}: G = C + s1, disk moment m1 (s1 - s2 e^{ig}),
        # housing at the origin, carrier (C itself) massless.
        e = self.s2 * np.exp(1j * self.gamma)
        U = self.m1 * (self.s1 - e)  # balls must give -U about E; C at -e
        if w:  # force balance of the whole rotor with E on the axis (C at -e, spring at C)
            U = U + (self.kx + 1j * self.cx * w) * e / w**2
        cap = sum(self.mb) * self.r
        if n == 2:
            a, b = self.mb[0] * self.r, self.mb[1] * self.r
            L = abs(U)
            if L > a + b or L < abs(a - b):
                return None
            al = np.arccos((a * a + L * L - b * b) / (2 * a * L))
            pa = np.angle(-U) + al
            pb = np.angle(-U - a * np.exp(1j * pa)) if b > 0 else 0.0
            return -e, np.array([pa, pb])
        return -e, None

    def equilibrium(self, w, psi0=None, z0=None):
        N = self.n + 2
        guess = self.balanced_guess(w)
        zg, pg = guess if guess is not None else (0j, None)
        if psi0 is None:
            psi0 = pg
        if z0 is None:
            z0 = zg
        x0 = np.concatenate([[z0.real, z0.imag], psi0])

        def res(y):
            x = np.concatenate([y, np.zeros(N)])
            return self.rhs(0.0, x, w)[N:]

        y, info, ier, msg = fsolve(res, x0, full_output=True, xtol=1e-14)
        x = np.concatenate([y, np.zeros(N)])
        return x, np.max(np.abs(res(y)))

    def eig(self, w, x=None):
        if x is None:
            x, _ = self.equilibrium(w)
        return np.linalg.eigvals(self.jac(0.0, x, w))

    # ---- periodic orbit (shooting) and Floquet multipliers ------------------------------
    def _var(self, t, Y, w):
        d = 2 * (self.n + 2)
        x = Y[:d]
        Phi = Y[d:].reshape(d, d)
        return np.concatenate([self.rhs(t, x, w), (self.jac(t, x, w) @ Phi).ravel()])

    def monodromy(self, w, x0, T=None, rtol=1e-11, atol=1e-13):
        d = 2 * (self.n + 2)
        if T is None:
            T = self.period(w)
        Y0 = np.concatenate([x0, np.eye(d).ravel()])
        sol = solve_ivp(self._var, (0.0, T), Y0, method="DOP853", rtol=rtol, atol=atol, args=(w,))
        Y = sol.y[:, -1]
        return Y[:d], Y[d:].reshape(d, d)

    def periodic_orbit(self, w, x0, T=None, tol=1e-12, maxit=20):
        """Newton shooting on x(T) - x0 = 0. Returns (x0, monodromy, residual)."""
        d = 2 * (self.n + 2)
        x = np.array(x0, float)
        for _ in range(maxit):
            xT, Phi = self.monodromy(w, x, T)
            r = xT - x
            dx = np.linalg.lstsq(Phi - np.eye(d), -r, rcond=None)[0]
            x = x + dx
            if np.max(np.abs(dx)) < tol * max(1.0, np.max(np.abs(x))):
                break
        xT, Phi = self.monodromy(w, x, T)
        return x, Phi, np.max(np.abs(xT - x))


def bisect(f, a, b, fa=None, tol=1e-10):
    """Root of a sign change of f between a and b, to relative tol."""
    if fa is None:
        fa = f(a)
    while abs(b - a) > tol * abs(b):
        mdl = 0.5 * (a + b)
        fm = f(mdl)
        if np.sign(fm) == np.sign(fa):
            a, fa = mdl, fm
        else:
            b = mdl
    return 0.5 * (a + b)
