"""``autobal.from_ross``: a ROSS rotor (``ross.Rotor``) as an autobal :class:`LinearRotor`, with
ball balancers and unbalances added (issue 19, docs/guide/your-own-rotor.md).

ROSS is not a dependency of autobal: the function takes the rotor object and calls ROSS's own
matrix methods, ``rotor.M()``, ``rotor.K(speed)``, ``rotor.C(speed)``, ``rotor.G()``. ROSS 2
numbers 6 DOFs per shaft node (``x, y, z, alpha, beta, theta``), ROSS 1 four (``x, y, alpha,
beta``); the lateral ones, ``x, y, alpha, beta``, are kept (the axial and torsional DOFs of
ROSS's shaft elements are not coupled to them). After the shaft's nodes ROSS numbers the nodes
of its point masses beyond the shaft (the support, "link", nodes of ``n_link`` bearings: a
pedestal, a washer's tub, a drive's suspended base) with half a node's DOFs each (``x, y, z`` in
ROSS 2, ``x, y`` in ROSS 1; ``Rotor.__init__``'s ``dof_global_index``); they become autobal nodes
with ``x, y`` only, under the same node numbers. Bearings whose coefficients ROSS tabulates over frequency
become speed-dependent bearings: ``K(speed) - K(speeds[0])`` and the same for ``C`` at each
speed of the table (the union of the bearings' ``frequency`` arrays, or ``speeds=``), on the
bearing's node, and for an ``n_link`` bearing on both its nodes (``[[B, -B], [-B, B]]``), interpolated
linearly between them (ROSS interpolates its tables itself).
The rotor's polar moment of inertia about its axis (the spin's inertia under a torque drive,
``LinearRotor.polar_inertia``) is the disks' ``DiskElement.Ip`` plus the shaft elements'
``ρ ∫ J dz``, ``J = π (d_o⁴ − d_i⁴)/32`` along each (tapered) element, by :func:`polar_inertia_of`;
the gyroscopic matrix is ROSS's ``rotor.G()``, which holds the same moments. The
angular-acceleration stiffness of run-ups, ``LinearRotor.spin_stiffness`` (``K_st`` in
``M q'' + (C + Ω G) q' + (K + Ω̇ K_st) q = f``), is ROSS's ``rotor.Ksdt()`` as ROSS's time
response uses it (``K + Ksdt * dΩ/dt``), so that a run-up under a prescribed speed solves ROSS's
equations. Note that ROSS's ``Ksdt`` is not the ``K_st`` of a kinetic energy with ROSS's ``G``:
its disks give ``Ksdt − Ksdtᵀ = −G`` (a Lagrangian ``½ φ̇ q̇ᵀ G' q`` gives ``K_st − K_stᵀ = G``),
and its shaft elements leave out the shear terms of their ``G``; a torque-driven run-up of such
a rotor then does not conserve energy exactly (docs/reference/config.md, ``kst``).
Refused with a ``ValueError`` naming the cause: DOFs that are neither the shaft nodes' nor
the point-mass nodes' numbered after them (ROSS counts every ``PointMass`` as a new node, one
placed on a shaft node leaves empty rows), and a speed-dependent bearing whose change with
speed is not on the x, y blocks of its bearings (tilt terms, or an element other than a bearing).
"""

from __future__ import annotations

from typing import Any, Iterable, List, Mapping, Optional, Sequence, Set

import numpy as np

from . import _autobal
from .errors import InvalidParameter


def _lateral(per_node: int) -> Sequence[int]:
    if per_node == 6:
        return (0, 1, 3, 4)
    if per_node == 4:
        return (0, 1, 2, 3)
    raise ValueError(f"rotor.number_dof = {per_node}: expected 4 (x, y, alpha, beta) or 6 (x, y, z, alpha, beta, theta)")


def _gauss3(f: Any, length: float) -> float:
    # 3-point Gauss-Legendre on [0, length]: exact for polynomials up to degree 5, so for the
    # quartic d(z)⁴ of a linearly tapered diameter
    r = (3.0 / 5.0) ** 0.5
    return 0.5 * length * sum(w * f(0.5 * length * (1.0 + x)) for x, w in ((-r, 5.0 / 9.0), (0.0, 8.0 / 9.0), (r, 5.0 / 9.0)))


def polar_inertia_of(rotor: Any) -> float:
    """The polar moment of inertia (kg m²) of a ROSS rotor about its axis: ``Σ DiskElement.Ip``
    plus, for each shaft element, ``ρ ∫₀ᴸ π (d_o(z)⁴ − d_i(z)⁴)/32 dz`` with the diameters
    linear from the left end (``odl``, ``idl``) to the right (``odr``, ``idr``), integrated
    exactly (3-point Gauss). Elements without these attributes (point masses, bearings) add
    nothing."""
    total = 0.0
    for d in getattr(rotor, "disk_elements", []):
        total += float(getattr(d, "Ip", 0.0))
    for e in getattr(rotor, "shaft_elements", []):
        try:
            length, rho = float(e.L), float(e.material.rho)
            odl, idl = float(e.odl), float(e.idl)
            odr, idr = float(getattr(e, "odr", odl)), float(getattr(e, "idr", idl))
        except AttributeError:
            continue

        def j(z: float) -> float:
            s = z / length
            do, di = odl + (odr - odl) * s, idl + (idr - idl) * s
            return np.pi * (do**4 - di**4) / 32.0

        total += rho * _gauss3(j, length)
    return total


def from_ross(
    rotor: Any,
    balancers: Iterable[Mapping[str, float]] = (),
    unbalance: Iterable[Mapping[str, float]] = (),
    speeds: Optional[Sequence[float]] = None,
    polar_inertia: Optional[float] = None,
) -> "_autobal.LinearRotor":
    """The ROSS rotor ``rotor`` as a :class:`autobal.LinearRotor` (DOFs ``x, y, alpha, beta``
    per shaft node and ``x, y`` per point-mass node beyond the shaft, the support nodes of
    ``n_link`` bearings, in ROSS's order and node numbers).

    ``balancers``: dicts with ``node``, ``radius`` (m), ``balls``, ``ball_mass`` (kg), and
    optionally ``drag`` (N m s per ball) and ``offset`` (m), and real balls by the config's keys
    (``contact``, ``ball_diameter``, ``restitution``, ``contact_stiffness``,
    ``rolling_resistance``, ``slip_rate``: ``LinearRotor.add_balancer``). ``unbalance``: dicts with ``node``,
    ``me`` (kg m; or ``magnitude`` as ROSS calls it), optionally ``phase`` (rad) and ``offset``.
    ``speeds``: where the bearings' speed dependence is sampled (rad/s); default the union of
    the bearings' ``frequency`` tables. ``polar_inertia``: the rotor's polar moment (kg m²)
    for torque drives instead of :func:`polar_inertia_of`'s (disks' ``Ip`` and the shaft's).

    The dicts are read as the CLI reads a config's ``[[linear_rotor.balancer]]`` and
    ``[[linear_rotor.unbalance]]`` tables, and the rotor is checked as it reads them
    (``LinearRotor::validate``): an unknown or missing key, a node that does not exist, a
    ball mass that is not positive, a number that is not finite raise
    :class:`autobal.InvalidParameter` (a ``ValueError``) naming the entry as the config does,
    ``linear_rotor.balancer[0].ball_mass: must be positive, got -0.05``.

    >>> import ross, autobal                                     # doctest: +SKIP
    >>> r = autobal.from_ross(ross.rotor_example(), balancers=[dict(node=2, radius=0.1, balls=2, ball_mass=0.05, drag=0.01)],
    ...                       unbalance=[dict(node=2, me=1e-4)])  # doctest: +SKIP
    >>> r.stability(omega_max=1000.0)                             # doctest: +SKIP
    """
    per = int(getattr(rotor, "number_dof", 4))
    lat = _lateral(per)
    m_full = np.asarray(rotor.M(), dtype=float)
    n_nodes = len(getattr(rotor, "nodes", ())) or m_full.shape[0] // per
    # the point masses' nodes beyond the shaft: ROSS numbers them on from the shaft's last node
    # and gives each half a node's DOFs, node n at per * n_nodes + (per / 2) * (n - n_nodes)
    half = per // 2
    links = sorted({int(p.n) for p in getattr(rotor, "point_mass_elements", []) if int(p.n) >= n_nodes})
    if m_full.shape[0] != per * n_nodes + half * len(links) or links != list(range(n_nodes, n_nodes + len(links))):
        raise ValueError(
            f"from_ross: the rotor has {m_full.shape[0]} DOFs, its {n_nodes} shaft nodes {per} each and the point-mass nodes "
            f"{links} beyond them {half} each make {per * n_nodes + half * len(links)}; autobal takes shaft nodes and point-mass "
            f"nodes numbered on from the shaft's last ({n_nodes}, {n_nodes + 1}, …), one point mass each"
        )
    idx = [k * per + j for k in range(n_nodes) for j in lat] + [per * n_nodes + half * i + j for i in range(len(links)) for j in (0, 1)]
    # each node's first DOF (its x) among the kept ones
    start = [4 * k for k in range(n_nodes)] + [4 * n_nodes + 2 * i for i in range(len(links))]
    layout = [4] * n_nodes + [2] * len(links)
    sel = np.ix_(idx, idx)
    if speeds is None:
        tabulated: Set[float] = set()
        for b in getattr(rotor, "bearing_elements", []):
            f = getattr(b, "frequency", None)
            if f is not None and np.size(f) > 1:
                tabulated.update(float(v) for v in np.atleast_1d(f))
        speeds = sorted(tabulated) or [0.0]
    speeds = [float(w) for w in speeds]
    k0 = np.asarray(rotor.K(speeds[0]), dtype=float)[sel]
    c0 = np.asarray(rotor.C(speeds[0]), dtype=float)[sel]
    g = np.asarray(rotor.G(), dtype=float)[sel]
    out = _autobal.LinearRotor(
        np.ascontiguousarray(m_full[sel]), np.ascontiguousarray(c0), np.ascontiguousarray(g), np.ascontiguousarray(k0), per_node=layout if links else 4
    )
    out.polar_inertia = float(polar_inertia_of(rotor) if polar_inertia is None else polar_inertia)
    ksdt = getattr(rotor, "Ksdt", None)
    if callable(ksdt):
        # ROSS's angular-acceleration stiffness, as its time response applies it: K + Ksdt dΩ/dt
        out.spin_stiffness = np.ascontiguousarray(np.asarray(ksdt(), dtype=float)[sel])
    if len(speeds) > 1:
        ks = [np.asarray(rotor.K(w), dtype=float)[sel] - k0 for w in speeds]
        cs = [np.asarray(rotor.C(w), dtype=float)[sel] - c0 for w in speeds]
        # each bearing's change with speed, from its own K(w), C(w): the x, y block of its node
        # (ROSS's link bearings have [[B, -B], [-B, B]] on the two nodes' x, y, z), summed over
        # bearings between the same nodes
        tables: dict = {}
        for b in getattr(rotor, "bearing_elements", []):
            link = getattr(b, "n_link", None)
            key = (int(b.n), None if link is None else int(link))
            kb = [np.asarray(b.K(w), dtype=float)[:2, :2] - np.asarray(b.K(speeds[0]), dtype=float)[:2, :2] for w in speeds]
            cb = [np.asarray(b.C(w), dtype=float)[:2, :2] - np.asarray(b.C(speeds[0]), dtype=float)[:2, :2] for w in speeds]
            if key in tables:
                kb = [a + b2 for a, b2 in zip(tables[key][0], kb)]
                cb = [a + b2 for a, b2 in zip(tables[key][1], cb)]
            tables[key] = (kb, cb)
        rebuilt_k = [np.zeros_like(k0) for _ in speeds]
        rebuilt_c = [np.zeros_like(c0) for _ in speeds]
        for (node, link), (kb, cb) in sorted(tables.items(), key=lambda t: (t[0][0], -1 if t[0][1] is None else t[0][1])):
            if not any(np.any(a != 0.0) for a in kb + cb):
                continue
            out.add_speed_bearing(node, speeds, np.array([a.ravel() for a in kb]), np.array([a.ravel() for a in cb]), link=link)
            i, j = start[node], None if link is None else start[link]
            for table, rebuilt in ((kb, rebuilt_k), (cb, rebuilt_c)):
                for a, r in zip(table, rebuilt):
                    r[i : i + 2, i : i + 2] += a
                    if j is not None:
                        r[j : j + 2, j : j + 2] += a
                        r[i : i + 2, j : j + 2] -= a
                        r[j : j + 2, i : i + 2] -= a
        # what changes with speed must be those blocks: a change elsewhere (tilt terms, an element
        # that is not a bearing) would be dropped here, so it is refused
        for name, table, rebuilt in (("stiffness", ks, rebuilt_k), ("damping", cs, rebuilt_c)):
            for w, a, r in zip(speeds, table, rebuilt):
                scale = max(float(np.max(np.abs(a))), 1e-300)
                if np.max(np.abs(a - r)) > 1e-12 * scale:
                    raise ValueError(
                        f"from_ross: the rotor's {name} changes with speed (at {w} rad/s) outside the x, y blocks of its bearings "
                        "(tilt terms, or an element that is not a bearing); autobal's speed-dependent bearings act on the x, y of "
                        "a node, or of two nodes (n_link)"
                    )
    for i, b in enumerate(_entries("balancers", "balancer", balancers)):
        field = f"linear_rotor.balancer[{i}]"
        _known(field, b, _BALANCER_KEYS)
        out.add_balancer(
            _whole(field, b, "node"),
            _number(field, b, "radius"),
            _whole(field, b, "balls"),
            _number(field, b, "ball_mass"),
            _number(field, b, "drag", 0.0),
            _number(field, b, "offset", 0.0),
            **_ball_physics(field, b),
        )
    for i, u in enumerate(_entries("unbalance", "unbalance", unbalance)):
        field = f"linear_rotor.unbalance[{i}]"
        _known(field, u, _UNBALANCE_KEYS)
        if "me" in u and "magnitude" in u:
            raise _invalid(f"{field}.magnitude", "give me or magnitude (ROSS's name for it), not both")
        me = _number(field, u, "me") if "me" in u or "magnitude" not in u else _number(field, u, "magnitude")
        out.add_unbalance(_whole(field, u, "node"), me, _number(field, u, "phase", 0.0), _number(field, u, "offset", 0.0))
    return out


def _invalid(field: str, reason: str) -> InvalidParameter:
    """The library's error on ``field`` (``FIELD: REASON``, ``.field``, ``.reason``)."""
    e = InvalidParameter(f"{field}: {reason}")
    e.field, e.reason = field, reason
    return e


# the keys of from_ross's dicts: the config's [[linear_rotor.balancer]] and
# [[linear_rotor.unbalance]] keys that a LinearRotor holds (ROSS's "magnitude" for me)
_BALL_PHYSICS_KEYS = ("ball_diameter", "restitution", "contact_stiffness", "rolling_resistance", "slip_rate")
_BALANCER_KEYS = ("node", "radius", "balls", "ball_mass", "drag", "offset", "contact") + _BALL_PHYSICS_KEYS


def _ball_physics(field: str, entry: Mapping[str, Any]) -> dict:
    """The real-ball keys of a balancer dict (``contact``, ``ball_diameter``, ...) as
    ``LinearRotor.add_balancer``'s keywords: those given, checked as the config reader checks
    their type (``contact`` true or false, the others numbers); their ranges are the library's
    check."""
    out: dict = {}
    if "contact" in entry:
        c = entry["contact"]
        if not isinstance(c, (bool, np.bool_)):
            raise _invalid(f"{field}.contact", "expected true or false")
        out["contact"] = bool(c)
    for k in _BALL_PHYSICS_KEYS:
        if k in entry:
            out[k] = _number(field, entry, k)
    return out
_UNBALANCE_KEYS = ("node", "me", "magnitude", "phase", "offset")


def _entries(argument: str, kind: str, items: Any) -> List[Mapping[str, Any]]:
    """``balancers=`` or ``unbalance=`` as a list of dicts, or :class:`InvalidParameter`
    naming the argument or the entry (``linear_rotor.balancer[1]``) that is not one."""
    if isinstance(items, (Mapping, str, bytes)) or not isinstance(items, Iterable):
        raise _invalid(argument, f"expected a list of dicts, got {type(items).__name__}")
    out = list(items)
    for i, e in enumerate(out):
        if not isinstance(e, Mapping):
            raise _invalid(f"linear_rotor.{kind}[{i}]", f"expected a dict (a [[linear_rotor.{kind}]] table), got {type(e).__name__}")
    return out


def _known(field: str, entry: Mapping[str, Any], keys: Sequence[str]) -> None:
    """The config reader's check of a table's keys: the first unknown one is refused, naming
    the known ones."""
    for k in entry:
        if k not in keys:
            raise _invalid(f"{field}.{k}", f"unknown key (known keys: {', '.join(keys)})")


def _number(field: str, entry: Mapping[str, Any], key: str, default: Optional[float] = None) -> float:
    """``entry[key]`` as a float (``default`` where absent; required where ``default`` is
    None), or the config reader's error naming ``FIELD.KEY``. Its range (finite, positive, …)
    is the library's check, made by ``LinearRotor.add_*``."""
    if key not in entry:
        if default is None:
            raise _invalid(f"{field}.{key}", "missing (required)")
        return default
    v = entry[key]
    if isinstance(v, bool) or not isinstance(v, (int, float, np.integer, np.floating)):
        raise _invalid(f"{field}.{key}", f"expected a number, got {v!r}")
    return float(v)


def _whole(field: str, entry: Mapping[str, Any], key: str) -> int:
    """``entry[key]`` as a whole number ≥ 0 (required), or the config reader's error."""
    if key not in entry:
        raise _invalid(f"{field}.{key}", "missing (required)")
    v = entry[key]
    if isinstance(v, bool) or not isinstance(v, (int, np.integer)) or v < 0:
        raise _invalid(f"{field}.{key}", f"expected a whole number ≥ 0, got {v!r}")
    return int(v)
