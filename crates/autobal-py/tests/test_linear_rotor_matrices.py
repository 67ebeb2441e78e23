"""Every matrix of a ``[linear_rotor]`` config from Python (issue 19): ``LinearRotor``'s
``rotor_fixed_mass`` (``M_rot``, the inertia fixed to the rotor) and ``spin_chart`` (``Σ``,
the tilt chart fixed to it) besides ``m, c, g, k`` and ``spin_stiffness``. Set, each reads
back as given; refused (non-symmetric, ``M + T(φ) M_rot T(φ)ᵀ`` not positive definite, wrong
size) with an error naming the key, the rotor left as it was; and a rotor built in Python
equals the same rotor read from a config naming Matrix Market files written by SciPy: its
balanced state's stability (eigenvalues and margins at each speed) equal number for number,
its export equal character for character. The matrices' entries are dyadic fractions (exact
in any decimal text SciPy writes), so equality is exact, with no tolerance.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import autobal

N = 8  # two nodes, x, y, alpha, beta each


def matrices() -> dict[str, np.ndarray]:
    """A two-node rotor, isotropic (every (x, y), (α, β) block commutes with J), symmetric
    positive definite M, K; skew G."""
    m = np.diag([2.0, 2.0, 0.25, 0.25, 1.5, 1.5, 0.125, 0.125])
    k = np.diag([3e4, 3e4, 500.0, 500.0, 3e4, 3e4, 500.0, 500.0])
    for a, b in [(0, 4), (1, 5)]:
        k[a, b] = k[b, a] = -1e4
    c = np.diag([10.0, 10.0, 0.5, 0.5, 10.0, 10.0, 0.5, 0.5])
    g = np.zeros((N, N))
    g[2, 3], g[3, 2] = 0.0625, -0.0625
    g[6, 7], g[7, 6] = 0.03125, -0.03125
    # inertia fixed to the rotor, anisotropic (x heavier than y in the rotor's axes): positive
    # semi-definite, so M + T(φ) M_rot T(φ)ᵀ is positive definite at every φ
    m_rot = np.zeros((N, N))
    m_rot[0, 0], m_rot[2, 2] = 0.5, 0.0625
    # the native chart R_x(δ) R_y(θ) at node 0: Σ[α][β] = Σ[β][α] = ½
    chart = np.zeros((N, N))
    chart[2, 3] = chart[3, 2] = 0.5
    return {"M": m, "C": c, "G": g, "K": k, "M_rot": m_rot, "chart": chart}


def python_rotor(with_fixed: bool = True) -> autobal.LinearRotor:
    a = matrices()
    lr = autobal.LinearRotor(a["M"], a["C"], a["G"], a["K"], per_node=4)
    if with_fixed:
        lr.rotor_fixed_mass = a["M_rot"]
        lr.spin_chart = a["chart"]
    lr.polar_inertia = 0.0625
    lr.add_unbalance(0, 1e-4)
    lr.add_balancer(0, 0.05, 2, 0.01, 0.01)
    return lr


def test_set_reads_back_and_refusals_name_the_key():
    a = matrices()
    lr = python_rotor(with_fixed=False)
    assert lr.rotor_fixed_mass == [] and lr.spin_chart == []
    lr.rotor_fixed_mass = a["M_rot"]
    lr.spin_chart = a["chart"]
    assert np.array_equal(np.array(lr.rotor_fixed_mass), a["M_rot"])
    assert np.array_equal(np.array(lr.spin_chart), a["chart"])
    # non-symmetric: refused, naming the key and the entry, the value kept
    bad = a["M_rot"].copy()
    bad[1, 0] = 0.25
    with pytest.raises(autobal.AutobalError, match=r"linear_rotor\.rotor_fixed_mass\[1,0\].*symmetric"):
        lr.rotor_fixed_mass = bad
    assert np.array_equal(np.array(lr.rotor_fixed_mass), a["M_rot"])
    bad = a["chart"].copy()
    bad[4, 2] = 0.5
    with pytest.raises(autobal.AutobalError, match=r"linear_rotor\.spin_chart\[4,2\].*symmetric"):
        lr.spin_chart = bad
    assert np.array_equal(np.array(lr.spin_chart), a["chart"])
    # M + M_rot singular at φ = 0 (x of node 0 has no mass): the library's positive-definite check
    neg = np.zeros((N, N))
    neg[0, 0] = -2.0
    with pytest.raises(autobal.AutobalError, match=r"linear_rotor\.rotor_fixed_mass.*not positive definite"):
        lr.rotor_fixed_mass = neg
    # wrong size, not finite
    with pytest.raises(autobal.AutobalError, match=r"linear_rotor\.rotor_fixed_mass: is 4 × 4, m is 8 × 8"):
        lr.rotor_fixed_mass = np.eye(4)
    with pytest.raises(autobal.AutobalError, match=r"linear_rotor\.spin_chart: is 2 × 3, must be square"):
        lr.spin_chart = np.zeros((2, 3))
    nan = a["chart"].copy()
    nan[5, 5] = np.nan
    with pytest.raises(autobal.AutobalError, match=r"linear_rotor\.spin_chart\[5,5\]"):
        lr.spin_chart = nan
    assert np.array_equal(np.array(lr.rotor_fixed_mass), a["M_rot"])
    assert np.array_equal(np.array(lr.spin_chart), a["chart"])


def test_a_rotor_from_python_equals_the_config_of_its_files(tmp_path: Path):
    mmwrite = pytest.importorskip("scipy.io").mmwrite
    for name, a in matrices().items():
        mmwrite(str(tmp_path / f"{name}.mtx"), a)
    (tmp_path / "r.toml").write_text(
        "[linear_rotor]\n"
        'layout = "x,y,alpha,beta"\n'
        'm = "M.mtx"\nc = "C.mtx"\ng = "G.mtx"\nk = "K.mtx"\n'
        'rotor_fixed_mass = "M_rot.mtx"\nspin_chart = "chart.mtx"\n'
        "polar_inertia = 0.0625\n"
        "[[linear_rotor.unbalance]]\nnode = 0\nme = 1e-4\n"
        "[[linear_rotor.balancer]]\nnode = 0\nradius = 0.05\nballs = 2\nball_mass = 0.01\ndrag = 0.01\n"
    )
    from_file = autobal.LinearRotor.from_config(tmp_path / "r.toml")
    built = python_rotor()
    assert from_file.rotor_fixed_mass == built.rotor_fixed_mass
    assert from_file.spin_chart == built.spin_chart
    # the whole rotor: its export (every matrix's every digit, the tables)
    assert from_file.export("e") == built.export("e")
    # the balanced state's stability over speed (through the critical speeds, ≈ 71 and 141
    # rad/s): eigenvalues and margins equal number for number
    got = json.loads(built.stability(300.0, samples=6))
    want = json.loads(from_file.stability(300.0, samples=6))
    assert got == want
    # M_rot counts: without it the stability differs (the test can fail)
    without = json.loads(python_rotor(with_fixed=False).stability(300.0, samples=6))
    assert without["points"] != got["points"]
