"""An independent derivation of the spatial rigid rotor with ball balancers (papers 000/003,
Rodrigues et al. 2008's two planes), tilt free, in axes turning with the rotor.

Written from the physics (Lagrange's equations, SymPy), not from autobal's source; autobal's
docs were read for config keys and units only.

The rotor turns at a prescribed constant speed w. Axes x'y'z turn with it about the fixed
bearing axis z. The rotor's orientation is Q(t) = R_z(w t) Q', Q' = R_x(delta) R_y(theta): the
tilts delta, theta are rotations about the turning axes x', y'. The reference point is the
shaft point at the axial position z_ref (the common centre of mass C at balance); its lateral
position in turning axes is (xi, eta). A body point b (body axes = turning axes at zero tilt,
x' along the rotor frame's angle 0) is at r' = (xi, eta, 0) + Q' (b - z_ref e_z) in turning
axes, with inertial velocity v' = dr'/dt + w e_z x r' (turning components).

    T = sum_points 1/2 m |v'|^2 + 1/2 M_r |v'_G|^2 + 1/2 W^T diag(A_r, A_r, C_r) W,
        W = Q'^T (w e_z + w_t),  skew(w_t) = (dQ'/dt) Q'^T   (body angular velocity)
    V = sum_supports 1/2 (k_x X^2 + k_y Y^2) - sum_masses m g . (R_z(w t) r')
        X + i Y = (d_x + i d_y) e^{i w t},  d = lateral turning-axes position of the shaft
        point at the support's z
    R = sum_supports 1/2 (c_x Xd^2 + c_y Yd^2) + sum_balls 1/2 h_A R^2 psi_j'^2

Points: the unbalance m0 at (R0 cos a0, R0 sin a0, z_A) (plane of the first balancer), an
optional couple mass, balls at (R cos psi_j, R sin psi_j, z_plane). The spin about the body axis
is prescribed through this chart; at zero tilt (every balanced state below) another chart
(tilts about fixed axes, then spin) differs from this one by total time derivatives to second
order, so the linearisation does not depend on it (and it agrees with autobal's closed-form route,
paper 000's eq (6) with the exact inertia tensor, to ~1e-15 of max|lambda|:
check_spatial_one_plane.py).

With isotropic supports and no gravity the equations are autonomous; with k_x != k_y or
c_x != c_y at a support they are periodic in t with period pi/w; with gravity, 2 pi/w.
"""

from __future__ import annotations

import functools

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from scipy.optimize import fsolve


def _rx(a):
    return sp.Matrix([[1, 0, 0], [0, sp.cos(a), -sp.sin(a)], [0, sp.sin(a), sp.cos(a)]])


def _ry(a):
    return sp.Matrix([[sp.cos(a), 0, sp.sin(a)], [0, 1, 0], [-sp.sin(a), 0, sp.cos(a)]])


@functools.lru_cache(maxsize=None)
def build(balls_per_plane: tuple, n_points: int, lock_tilt: bool = False):
    """Lagrange's equations M(q, t) q'' = F(q, q', t), exact partials, lambdified.

    balls_per_plane: e.g. (2,) or (2, 2). n_points: point masses fixed to the rotor (unbalance,
    couple). Parameters (a flat list, see Spatial.p): w, gx, gy, M_r, A_r, C_r, zG,
    supports (zL, kxL, kyL, cxL, cyL, zR, kxR, kyR, cxR, cyR), per point (m, rho, ang, z),
    per plane (z, R), per ball (m, h). All z relative to the reference point."""
    t = sp.Symbol("t", real=True)
    nb = sum(balls_per_plane)
    xi, eta, dl, th = sp.symbols("xi eta delta theta", real=True)
    xid, etad, dld, thd = sp.symbols("xid etad deltad thetad", real=True)
    psi = list(sp.symbols(f"psi1:{nb + 1}", real=True))
    psid = list(sp.symbols(f"psid1:{nb + 1}", real=True))
    if lock_tilt:
        q = [xi, eta, *psi]
        qd = [xid, etad, *psid]
    else:
        q = [xi, eta, dl, th, *psi]
        qd = [xid, etad, dld, thd, *psid]
    N = len(q)
    qdd = sp.symbols(f"a1:{N + 1}", real=True)
    w, gx, gy, Mr, Ar, Cr, zG = sp.symbols("w gx gy Mr Ar Cr zG", real=True)
    sup = sp.symbols("zL kxL kyL cxL cyL zR kxR kyR cxR cyR", real=True)
    pts = [sp.symbols(f"pm{i} prho{i} pang{i} pz{i}", real=True) for i in range(n_points)]
    planes = [sp.symbols(f"plz{i} plR{i}", real=True) for i in range(len(balls_per_plane))]
    bm = list(sp.symbols(f"bm1:{nb + 1}", real=True))
    bh = list(sp.symbols(f"bh1:{nb + 1}", real=True))
    params = [w, gx, gy, Mr, Ar, Cr, zG, *sup, *[s for p in pts for s in p],
              *[s for p in planes for s in p], *bm, *bh]

    if lock_tilt:
        Qp = sp.eye(3)
    else:
        Qp = _rx(dl) * _ry(th)
    p0 = sp.Matrix([xi, eta, 0])
    ez = sp.Matrix([0, 0, 1])

    def ddt(expr):
        return sum(sp.diff(expr, q[a]) * qd[a] for a in range(N))

    def pos(b):
        return p0 + Qp * b

    def vel(r):
        rd = r.applyfunc(ddt)
        return rd + (w * ez).cross(r)

    c, s = sp.cos(w * t), sp.sin(w * t)
    Rz = sp.Matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
    g = sp.Matrix([gx, gy, 0])

    T = 0
    V = 0
    # rotor
    rG = pos(sp.Matrix([0, 0, zG]))
    vG = vel(rG)
    T += sp.Rational(1, 2) * Mr * (vG.T * vG)[0]
    V += -Mr * (g.T * (Rz * rG))[0]
    Qd = Qp.applyfunc(ddt)
    S = Qd * Qp.T
    wt = sp.Matrix([S[2, 1], S[0, 2], S[1, 0]])
    W = Qp.T * (w * ez + wt)
    T += sp.Rational(1, 2) * (Ar * W[0] ** 2 + Ar * W[1] ** 2 + Cr * W[2] ** 2)
    # point masses fixed to the rotor
    for (m, rho, ang, zz) in pts:
        r = pos(sp.Matrix([rho * sp.cos(ang), rho * sp.sin(ang), zz]))
        v = vel(r)
        T += sp.Rational(1, 2) * m * (v.T * v)[0]
        V += -m * (g.T * (Rz * r))[0]
    # balls
    R = 0
    j = 0
    for ip, nbp in enumerate(balls_per_plane):
        zp, Rp = planes[ip]
        for _ in range(nbp):
            r = pos(sp.Matrix([Rp * sp.cos(psi[j]), Rp * sp.sin(psi[j]), zp]))
            v = vel(r)
            T += sp.Rational(1, 2) * bm[j] * (v.T * v)[0]
            V += -bm[j] * (g.T * (Rz * r))[0]
            R += sp.Rational(1, 2) * bh[j] * Rp**2 * psid[j] ** 2
            j += 1
    # supports
    for (zs, kx, ky, cx, cy) in (sup[:5], sup[5:]):
        d = pos(sp.Matrix([0, 0, zs]))
        dd = vel(d)  # inertial velocity, turning components
        X = c * d[0] - s * d[1]
        Y = s * d[0] + c * d[1]
        Xd = c * dd[0] - s * dd[1]
        Yd = s * dd[0] + c * dd[1]
        V += sp.Rational(1, 2) * (kx * X**2 + ky * Y**2)
        R += sp.Rational(1, 2) * (cx * Xd**2 + cy * Yd**2)
    L = T - V
    Mmat = sp.zeros(N, N)
    F = sp.zeros(N, 1)
    for a in range(N):
        p_a = sp.diff(L, qd[a])
        for b in range(N):
            Mmat[a, b] = sp.diff(p_a, qd[b])
        dpdt = sum(sp.diff(p_a, q[b]) * qd[b] for b in range(N)) + sp.diff(p_a, t)
        F[a] = -(dpdt - sp.diff(L, q[a]) + sp.diff(R, qd[a]))
    resid = Mmat * sp.Matrix(qdd) - F
    Jq = resid.jacobian(q)
    Jqd = resid.jacobian(qd)
    args = (t, q, qd, params)
    return {
        "N": N,
        "M": sp.lambdify(args, Mmat, "numpy", cse=True),
        "F": sp.lambdify(args, F, "numpy", cse=True),
        "Jq": sp.lambdify((t, q, qd, qdd, params), Jq, "numpy", cse=True),
        "Jqd": sp.lambdify((t, q, qd, qdd, params), Jqd, "numpy", cse=True),
        "sym": (t, q, qd, params, Mmat, F, L, R),
    }


class Spatial:
    """One configuration in SI (or any consistent units), config z coordinates.

    rotor: dict(mass, A, C, z); supports: [dict(z, kx, ky, cx, cy)] * 2;
    points: [dict(m, rho, ang, z)] (unbalance first, then the couple);
    planes: [dict(z, R, masses=[...], drags=[...])] (drag h_A per ball, N s/m)."""

    def __init__(self, rotor, supports, points, planes, gravity=(0.0, 0.0), lock_tilt=False):
        self.rotor, self.supports, self.points, self.planes = rotor, supports, points, planes
        self.g = list(gravity)
        self.lock = lock_tilt
        self.bpp = tuple(len(p["masses"]) for p in planes)
        self.nb = sum(self.bpp)
        self.sys = build(self.bpp, len(points), lock_tilt)
        self.N = self.sys["N"]
        self.nq0 = 2 if lock_tilt else 4  # rotor coordinates before the ball angles
        mtot = rotor["mass"] + sum(p["m"] for p in points) + sum(sum(p["masses"]) for p in planes)
        self.mass = mtot
        self.zref = (rotor["mass"] * rotor["z"] + sum(p["m"] * p["z"] for p in points)
                     + sum(sum(p["masses"]) * p["z"] for p in planes)) / mtot
        zr = self.zref
        self._base = [rotor["mass"], rotor["A"], rotor["C"], rotor["z"] - zr]
        for s in supports:
            self._base += [s["z"] - zr, s["kx"], s["ky"], s["cx"], s["cy"]]
        for p in points:
            self._base += [p["m"], p["rho"], p["ang"], p["z"] - zr]
        for p in planes:
            self._base += [p["z"] - zr, p["R"]]
        self._base += [m for p in planes for m in p["masses"]]
        self._base += [h for p in planes for h in p["drags"]]

    def p(self, w):
        return [w, *self.g, *self._base]

    @property
    def autonomous(self):
        return self.g == [0.0, 0.0] and all(s["kx"] == s["ky"] and s["cx"] == s["cy"]
                                             for s in self.supports)

    def period(self, w):
        if self.g != [0.0, 0.0]:
            return 2 * np.pi / abs(w)
        if not self.autonomous:
            return np.pi / abs(w)
        return 0.0

    def rhs(self, t, x, w):
        N = self.N
        q, qd = x[:N], x[N:]
        p = self.p(w)
        M = np.asarray(self.sys["M"](t, q, qd, p), float)
        F = np.asarray(self.sys["F"](t, q, qd, p), float).ravel()
        return np.concatenate([qd, np.linalg.solve(M, F)])

    def jac(self, t, x, w):
        N = self.N
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

    # ---- the balanced state ------------------------------------------------------------
    def plane_demands(self):
        """Complex first moments U_p (sum m R e^{i psi}) each ball plane must supply so that the
        static and the couple unbalance vanish (closed form: one plane cancels the static
        unbalance; two planes solve the force and moment balances)."""
        u = [p["m"] * p["rho"] * np.exp(1j * p["ang"]) for p in self.points]
        zs = [p["z"] for p in self.points]
        if len(self.planes) == 1:
            return [-sum(u)]
        zA, zB = self.planes[0]["z"], self.planes[1]["z"]
        S = sum(u)
        Mz = sum(ui * zi for ui, zi in zip(u, zs))
        # UA + UB = -S ; zA UA + zB UB = -Mz
        UA = (-Mz + zB * S) / (zA - zB)
        UB = -S - UA
        return [UA, UB]

    def balanced_angles(self):
        """Ball angles of the balanced state (two balls per plane), or None if a plane's
        capacity is short (|U_p| > sum m R or < |m1 - m2| R)."""
        out = []
        for pl, U in zip(self.planes, self.plane_demands()):
            if len(pl["masses"]) != 2:
                return None
            a, b = pl["masses"][0] * pl["R"], pl["masses"][1] * pl["R"]
            L = abs(U)
            if L > a + b or L < abs(a - b):
                return None
            al = np.arccos(np.clip((a * a + L * L - b * b) / (2 * a * L), -1, 1))
            pa = np.angle(U) + al
            pb = np.angle(U - a * np.exp(1j * pa))
            out += [pa, pb]
        return np.array(out)

    def state(self, psi):
        x = np.zeros(2 * self.N)
        x[self.nq0:self.nq0 + self.nb] = psi
        return x

    def equilibrium(self, w, psi0=None, q0=None):
        """Newton (fsolve) on the equations with q' = q'' = 0 from the closed form (or from the
        ball angles psi0, or from the whole position q0)."""
        N = self.N
        if q0 is not None:
            x0 = np.array(q0[:N], float)
            # MINPACK's finite-difference step is relative: an entry of 1e-18 gets a useless
            # step, so clear entries that are zero to rounding
            x0[np.abs(x0) < 1e-12] = 0.0
        else:
            if psi0 is None:
                psi0 = self.balanced_angles()
            x0 = self.state(psi0)[:N]

        def res(y):
            return self.rhs(0.0, np.concatenate([y, np.zeros(N)]), w)[N:]

        y = fsolve(res, x0, xtol=1e-14)
        return np.concatenate([y, np.zeros(N)]), float(np.max(np.abs(res(y))))

    def eig(self, w, x=None):
        if x is None:
            x, _ = self.equilibrium(w)
        return np.linalg.eigvals(self.jac(0.0, x, w))

    # ---- periodic cases --------------------------------------------------------------
    def _var(self, t, Y, w):
        d = 2 * self.N
        x = Y[:d]
        Phi = Y[d:].reshape(d, d)
        return np.concatenate([self.rhs(t, x, w), (self.jac(t, x, w) @ Phi).ravel()])

    def monodromy(self, w, x0, T=None, rtol=1e-11, atol=1e-13):
        d = 2 * self.N
        if T is None:
            T = self.period(w)
        Y0 = np.concatenate([x0, np.eye(d).ravel()])
        sol = solve_ivp(self._var, (0.0, T), Y0, method="DOP853", rtol=rtol, atol=atol,
                        args=(w,))
        Y = sol.y[:, -1]
        return Y[:d], Y[d:].reshape(d, d)

    def periodic_orbit(self, w, x0, T=None, tol=1e-12, maxit=20):
        d = 2 * self.N
        x = np.array(x0, float)
        for _ in range(maxit):
            xT, Phi = self.monodromy(w, x, T)
            dx = np.linalg.lstsq(Phi - np.eye(d), -(xT - x), rcond=None)[0]
            x = x + dx
            if np.max(np.abs(dx)) < tol * max(1.0, np.max(np.abs(x))):
                break
        xT, Phi = self.monodromy(w, x, T)
        return x, Phi, float(np.max(np.abs(xT - x)))

    def residual_unbalance(self, psi):
        """|static| and |couple| (about the reference point) unbalance left, complex sums."""
        u = sum(p["m"] * p["rho"] * np.exp(1j * p["ang"]) for p in self.points)
        mz = sum(p["m"] * p["rho"] * np.exp(1j * p["ang"]) * (p["z"] - self.zref)
                 for p in self.points)
        j = 0
        for pl in self.planes:
            for m in pl["masses"]:
                e = m * pl["R"] * np.exp(1j * psi[j])
                u += e
                mz += e * (pl["z"] - self.zref)
                j += 1
        return u, mz


def toml(rotor, supports, points, planes, *, omega=1.0, t_end=1.0, psi0=None, gravity=None,
         lock_tilt=False, extra="", rtol=1e-10, atol=1e-12, dt=0.01):
    """An SI spatial config for autobal from the same description as Spatial."""
    f = lambda x: repr(float(x))
    sl, sr = supports
    L = ["[rotor]", f"mass = {f(rotor['mass'])}", f"equatorial_moment = {f(rotor['A'])}",
         f"polar_moment = {f(rotor['C'])}", f"z = {f(rotor['z'])}",
         "[supports]", f"z_left = {f(sl['z'])}", f"z_right = {f(sr['z'])}",
         f"stiffness_left = {f(sl['kx'])}", f"stiffness_right = {f(sr['kx'])}",
         f"stiffness_left_y = {f(sl['ky'])}", f"stiffness_right_y = {f(sr['ky'])}",
         f"damping_left = {f(sl['cx'])}", f"damping_right = {f(sr['cx'])}",
         f"damping_left_y = {f(sl['cy'])}", f"damping_right_y = {f(sr['cy'])}",
         "[unbalance]", f"mass = {f(points[0]['m'])}", f"radius = {f(points[0]['rho'])}",
         f"angle = {f(points[0]['ang'])}"]
    assert abs(points[0]["z"] - planes[0]["z"]) < 1e-15, "the unbalance sits in plane 1"
    if len(points) > 1:
        p = points[1]
        L += ["[couple]", f"mass = {f(p['m'])}", f"radius = {f(p['rho'])}",
              f"angle = {f(p['ang'])}", f"z = {f(p['z'])}"]
    for i, pl in enumerate(planes):
        assert len(set(pl["masses"])) == 1 and len(set(pl["drags"])) == 1
        L += ["[balancer]" if i == 0 else "[balancer2]", f"z = {f(pl['z'])}",
              f"balls = {len(pl['masses'])}", f"ball_mass = {f(pl['masses'][0])}",
              f"race_radius = {f(pl['R'])}", f"drag = {f(pl['drags'][0])}"]
    g = gravity or (0.0, 0.0)
    L += ["[spatial]", f"gravity = [{f(g[0])}, {f(g[1])}, 0.0]",
          f"lock_tilt = {'true' if lock_tilt else 'false'}",
          "[drive]", 'kind = "speed"', f"omega0 = {f(omega)}", f"t_end = {f(t_end)}"]
    if psi0 is not None:
        L += ["psi0 = [" + ", ".join(f(x) for x in psi0) + "]"]
    L += ["[integration]", f"rtol = {rtol}", f"atol = {atol}", f"dt = {dt}", extra]
    return "\n".join(L) + "\n"


# ---- comparison with `autobal stability --format json` ------------------------------------
def exponent(S, w, x=None, psi0=None):
    """max Re lambda (autonomous) or ln(max|mu|)/T (periodic) of the balanced state at w (or of
    the equilibrium Newton finds from the ball angles psi0); returns (value, state x, Newton
    residual)."""
    if x is None:
        x, res = S.equilibrium(w, psi0)
    else:
        res = 0.0
    if S.autonomous:
        return float(np.max(S.eig(w, x).real)), x, res
    T = S.period(w)
    _, Phi = S.monodromy(w, x, T)
    mu = np.linalg.eigvals(Phi)
    return float(np.log(np.max(np.abs(mu))) / T), x, res


def bisect(f, a, b, fa=None, tol=1e-11):
    if fa is None:
        fa = f(a)
    while abs(b - a) > tol * abs(b):
        m = 0.5 * (a + b)
        fm = f(m)
        if np.sign(fm) == np.sign(fa):
            a, fa = m, fm
        else:
            b = m
    return 0.5 * (a + b)


def ang_diff(a, b):
    """Largest difference of two sets of ball angles, per plane unordered, mod 2 pi."""
    d = np.angle(np.exp(1j * (np.asarray(a) - np.asarray(b))))
    return float(np.max(np.abs(d)))


def compare_stability(name, S, d, *, tol_expo=1e-9, tol_end=1e-8, scale=None, grid=None,
                      verbose=True, psi0=None):
    """Compares autobal's stability JSON `d` with my exponents at every analysed point and the
    range ends. tol_expo: absolute, in units of `scale` (default: max|lambda| at that speed for
    the autonomous case, 1/T for the periodic one). grid: my own extra speeds (to catch ranges
    that fall between autobal's samples). Returns (ok, summary dict)."""
    ok = True
    if "points" not in d:  # the closed-form route's JSON: [omega, max Re lambda] pairs
        # (a dimensional config: max_real_part_si in rad/s and 1/s, ranges in Omega x omega0)
        si = d.get("omega_max_rad_s") is not None
        w0 = d["omega_max_rad_s"] / d["omega_max"] if si else 1.0
        # max_real_part_si is [rpm, 1/s] pairs (its rustdoc; docs/reference/outputs.md omits it)
        mrp = ([(r * np.pi / 30, v) for r, v in d["max_real_part_si"]] if si
               else d["max_real_part"])
        wmin, wtop = mrp[0][0], d["omega_max"] * w0
        sc = lambda v: None if v is None else v * w0
        d = dict(d, route="closed form", stationary_state="equilibrium",
                 points=[dict(omega=w, abscissa=v, analysed=True) for w, v in mrp],
                 stable_ranges=[dict(**{"from": sc(lo), "to": sc(hi)},
                                     from_is_boundary=lo is not None and sc(lo) > wmin,
                                     to_is_boundary=hi is not None and sc(hi) < wtop)
                                for lo, hi in d["stable_ranges"]])
    worst = 0.0
    ws, vals, scs = [], [], []
    n_other = 0
    worst_psi = 0.0
    msgs = []
    for pt in d["points"]:
        if not pt["analysed"] or pt.get("abscissa") is None:
            msgs.append(f"  autobal: omega={pt['omega']:.6g}: no value ({pt.get('state')}, "
                        f"{str(pt.get('failure'))[:100]})")
            continue
        w = pt["omega"]
        e, x, res = exponent(S, w, psi0=psi0)
        if pt.get("member_psi") is not None and psi0 is not None and ang_diff(
                sorted_planes(S, x), sorted_planes(S, np.concatenate(
                    [np.zeros(S.nq0), pt["member_psi"]]))) > 1e-6:
            # several stationary states coexist (partially balanced, near a resonance): check
            # autobal's own: Newton from its ball angles must stay there, then its eigenvalues
            e, x, res = exponent(S, w, psi0=np.asarray(pt["member_psi"]))
            n_other += 1
        if S.autonomous:
            sc = float(np.max(np.abs(S.eig(w, x)))) if scale is None else scale
        else:
            sc = 1.0 / S.period(w) if scale is None else scale
        diff = abs(e - pt["abscissa"]) / sc
        worst = max(worst, diff)
        if pt.get("member_psi") is not None:
            worst_psi = max(worst_psi, ang_diff(sorted_planes(S, x), sorted_planes(
                S, np.concatenate([np.zeros(S.nq0), pt["member_psi"]]))))
        if diff > tol_expo:
            ok = False
            msgs.append(f"  DISAGREE omega={w:.10g}: my exponent {e:.12g} autobal "
                        f"{pt['abscissa']:.12g} (diff {diff:.1e} of scale {sc:.3g}); autobal "
                        f"state {pt.get('state')} verdict {pt.get('verdict')}")
        want = "stable" if e < -tol_expo * sc else ("unstable" if e > tol_expo * sc else None)
        if want and pt.get("verdict") not in (want, None) and not str(pt.get("verdict")).startswith(want):
            ok = False
            msgs.append(f"  VERDICT omega={w:.10g}: mine {want} (expo {e:.3g}), autobal "
                        f"{pt.get('verdict')}")
        ws.append(w)
        vals.append(e)
        scs.append(sc)
    f = lambda w: exponent(S, w, psi0=psi0)[0]
    ends = []
    allw, allv, alls = list(ws), list(vals), list(scs)
    if grid is not None:
        for w in grid:
            e, x, _ = exponent(S, float(w), psi0=psi0)
            allw.append(float(w))
            allv.append(e)
            alls.append(float(np.max(np.abs(S.eig(w, x)))) if S.autonomous else 1 / S.period(w))
        o = np.argsort(allw)
        allw = [allw[i] for i in o]
        allv = [allv[i] for i in o]
        alls = [alls[i] for i in o]
    # sign with autobal's neutral band (1e-9 of the scale): ends only between definite signs
    last = None
    for i in range(len(allw)):
        sg = 1 if allv[i] > 1e-9 * alls[i] else (-1 if allv[i] < -1e-9 * alls[i] else 0)
        if sg == 0:
            continue
        if last is not None and sg != last[0]:
            ends.append((bisect(f, last[1], allw[i], last[2]), "enter" if sg < 0 else "leave"))
        last = (sg, allw[i], allv[i])
    ab = []
    for rg in d["stable_ranges"]:
        if rg.get("from_is_boundary"):
            ab.append((rg["from"], "enter"))
        if rg.get("to_is_boundary"):
            ab.append((rg["to"], "leave"))
    we = 0.0
    if len(ab) != len(ends):
        ok = False
        msgs.append(f"  DISAGREE on the number of range ends: mine {ends} autobal {ab}")
    else:
        for (a, ka), (b, kb) in zip(sorted(ends), sorted(ab)):
            rel = abs(a - b) / a
            we = max(we, rel)
            if rel > tol_end or ka != kb:
                ok = False
                msgs.append(f"  DISAGREE: end mine {a!r} {ka} autobal {b!r} {kb} rel {rel:.1e}")
    if verbose:
        for m in msgs:
            print(m)
        print(f"{name}: {d.get('stationary_state')} ({d.get('route')}); exponent worst diff "
              f"{worst:.1e} (of max|lambda| or 1/T) over {len(ws)} speeds; ball angles worst "
              f"{worst_psi:.1e} rad; my ends {[f'{e:.11g} {k}' for e, k in ends]}, worst rel "
              f"diff {we:.1e}; autobal {[(r['from'], r['to']) for r in d['stable_ranges']]}"
              f"{f'; {n_other} points on another branch than my Newton from psi0 (compared at autobal' + chr(39) + 's)' if n_other else ''}"
              f"{' OK' if ok else ' *** DISAGREE'}")
    return ok, dict(worst=worst, worst_end=we, ends=ends, ab=ab, worst_psi=worst_psi)


def sorted_planes(S, x):
    """Ball angles per plane, each plane's sorted mod 2 pi (ball order is arbitrary)."""
    psi = np.mod(np.asarray(x[S.nq0:S.nq0 + S.nb]), 2 * np.pi)
    out, j = [], 0
    for n in S.bpp:
        out += sorted(psi[j:j + n])
        j += n
    return np.array(out)
