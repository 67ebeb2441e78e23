"""Bad input to a Python-built linear rotor (issue 19, review of the Python front end): refused
when the rotor is built, with the CLI's one-line error naming the field as the config names it
(``linear_rotor.balancer[0].node``, ``linear_rotor.unbalance[0].me``), never later when the rotor
is used, and never written by ``export`` as a config the CLI cannot read.

``autobal.from_ross`` is duck-typed (it calls ``rotor.M()``, ``K(w)``, ``C(w)``, ``G()``), so its
dict handling is tested here on a stand-in without ROSS; the reviewer's case on a real ROSS rotor
skips without ROSS (fails with AUTOBAL_REQUIRE_ROSS set), as test_linear_rotor_ross.py does. The
CLI comparison needs the `autobal` binary: $AUTOBAL_BIN, else target/debug/autobal.
"""

from __future__ import annotations

import math
import os
import subprocess
from pathlib import Path
from typing import Any, Dict

import numpy as np
import pytest

import autobal
from _cli import binary

try:
    import tomllib
except ImportError:  # Python < 3.11
    tomllib = None  # type: ignore[assignment]

# two nodes with x, y, alpha, beta: a rigid-ish shaft on springs, enough for every check here
N = 8


def matrices() -> Dict[str, np.ndarray]:
    m = np.diag([2.0, 2.0, 0.01, 0.01, 2.0, 2.0, 0.01, 0.01])
    k = np.zeros((N, N))
    for i in range(N):
        k[i, i] = 1e6 if i % 4 < 2 else 1e3
    # a coupling spring between the nodes' x and y
    for a, b in ((0, 4), (1, 5)):
        k[a, a] += 1e5
        k[b, b] += 1e5
        k[a, b] = k[b, a] = -1e5
    c = 1e-4 * k
    g = np.zeros((N, N))
    for base in (2, 6):
        g[base, base + 1], g[base + 1, base] = 0.02, -0.02
    return {"M": m, "C": c, "G": g, "K": k}


def rotor() -> autobal.LinearRotor:
    a = matrices()
    return autobal.LinearRotor(a["M"], a["C"], a["G"], a["K"], per_node=4)


class FakeRoss:
    """What ``from_ross`` reads of a ``ross.Rotor`` (ROSS 1's 4 DOFs per node), with the
    matrices above: enough to test the balancer and unbalance dicts without ROSS."""

    number_dof = 4
    nodes = [0, 1]

    def M(self) -> np.ndarray:
        return matrices()["M"]

    def K(self, speed: float) -> np.ndarray:
        return matrices()["K"]

    def C(self, speed: float) -> np.ndarray:
        return matrices()["C"]

    def G(self) -> np.ndarray:
        return matrices()["G"]


GOOD_BALANCER = dict(node=1, radius=0.08, balls=2, ball_mass=0.05, drag=0.05)
GOOD_UNBALANCE = dict(node=0, me=1e-4)


def message(e: pytest.ExceptionInfo) -> str:
    s = str(e.value)
    assert "\n" not in s, s  # one line
    return s


@pytest.mark.parametrize(
    "balancer, unbalance, expected",
    [
        (dict(GOOD_BALANCER, node=42), GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]\.node: 42 is not a node \(the nodes are 0 to 1\)$"),
        (dict(GOOD_BALANCER, ball_mass=-0.05), GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]\.ball_mass: must be positive, got -0\.05$"),
        (dict(GOOD_BALANCER, balls=0), GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]\.balls: must be at least 1$"),
        (GOOD_BALANCER, dict(GOOD_UNBALANCE, me=float("nan")), r"^linear_rotor\.unbalance\[0\]\.me: must be a finite number, got NaN$"),
        (GOOD_BALANCER, dict(GOOD_UNBALANCE, node=2), r"^linear_rotor\.unbalance\[0\]\.node: 2 is not a node \(the nodes are 0 to 1\)$"),
    ],
)
def test_from_ross_refuses_a_bad_entry_when_built(balancer, unbalance, expected):
    """The reviewer's cases (a node that does not exist, a negative ball mass, a NaN unbalance):
    refused by ``from_ross`` itself, named as the config names the entry."""
    with pytest.raises(autobal.InvalidParameter, match=expected) as e:
        autobal.from_ross(FakeRoss(), balancers=[balancer], unbalance=[unbalance])
    message(e)
    assert isinstance(e.value, ValueError)
    # the good ones are taken
    lr = autobal.from_ross(FakeRoss(), balancers=[GOOD_BALANCER], unbalance=[GOOD_UNBALANCE])
    assert len(lr.natural_frequencies(with_balls=True)) == N


@pytest.mark.parametrize(
    "balancer, unbalance, expected",
    [
        (
            dict(GOOD_BALANCER, ball_mas=0.05),
            GOOD_UNBALANCE,
            r"^linear_rotor\.balancer\[0\]\.ball_mas: unknown key \(known keys: node, radius, balls, ball_mass, drag, offset, contact, ball_diameter, restitution, contact_stiffness, rolling_resistance, slip_rate\)$",
        ),
        (
            GOOD_BALANCER,
            dict(GOOD_UNBALANCE, phse=1.0),
            r"^linear_rotor\.unbalance\[0\]\.phse: unknown key \(known keys: node, me, magnitude, phase, offset\)$",
        ),
        ({k: v for k, v in GOOD_BALANCER.items() if k != "ball_mass"}, GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]\.ball_mass: missing \(required\)$"),
        ({k: v for k, v in GOOD_BALANCER.items() if k != "balls"}, GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]\.balls: missing \(required\)$"),
        (GOOD_BALANCER, dict(node=0), r"^linear_rotor\.unbalance\[0\]\.me: missing \(required\)$"),
        (GOOD_BALANCER, dict(node=0, me=1e-4, magnitude=1e-4), r"^linear_rotor\.unbalance\[0\]\.magnitude: give me or magnitude"),
        (dict(GOOD_BALANCER, node=-1), GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]\.node: expected a whole number ≥ 0, got -1$"),
        (dict(GOOD_BALANCER, balls=2.5), GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]\.balls: expected a whole number ≥ 0, got 2\.5$"),
        (dict(GOOD_BALANCER, radius="0.08"), GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]\.radius: expected a number, got '0\.08'$"),
        ("not a dict", GOOD_UNBALANCE, r"^linear_rotor\.balancer\[0\]: expected a dict"),
    ],
)
def test_from_ross_names_a_misspelt_or_missing_key(balancer, unbalance, expected):
    """A misspelt key is refused as the CLI refuses one in a config (naming the entry, the key and
    the known keys), a missing required one as ``missing (required)``: an ``InvalidParameter``
    (a ``ValueError``), not a bare ``KeyError``."""
    with pytest.raises(autobal.InvalidParameter, match=expected) as e:
        autobal.from_ross(FakeRoss(), balancers=[balancer], unbalance=[unbalance])
    message(e)


def test_from_ross_names_the_entry_by_its_index():
    """The second balancer plane is ``balancer[1]``; ROSS's ``magnitude`` stands for ``me``; a
    single dict instead of a list is refused, naming the argument."""
    lr = autobal.from_ross(FakeRoss(), balancers=[GOOD_BALANCER], unbalance=[dict(node=0, magnitude=1e-4, phase=0.5)])
    assert "me = 0.0001" in lr.export("x")[0]
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.balancer\[1\]\.radius: must be positive, got 0$"):
        autobal.from_ross(FakeRoss(), balancers=[GOOD_BALANCER, dict(GOOD_BALANCER, radius=0.0)])
    with pytest.raises(autobal.InvalidParameter, match=r"^balancers: expected a list of dicts, got dict$"):
        autobal.from_ross(FakeRoss(), balancers=GOOD_BALANCER)  # type: ignore[arg-type]


def test_linear_rotor_from_matrices_is_checked_when_built():
    """``LinearRotor(m, c, g, k)`` makes the library's check at once: a non-finite entry, an
    M that is not symmetric, a G that is not skew are refused naming the entry."""
    a = matrices()
    nan = a["K"].copy()
    nan[3, 3] = np.nan
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.k\[3,3\]: must be a finite number, got NaN$"):
        autobal.LinearRotor(a["M"], a["C"], a["G"], nan, per_node=4)
    m = a["M"].copy()
    m[1, 0] = 0.5
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.m\[1,0\]: must equal m\[0,1\] \(M symmetric\)$"):
        autobal.LinearRotor(m, a["C"], a["G"], a["K"], per_node=4)
    g = a["G"].copy()
    g[3, 2] = 0.02
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.g\[3,2\]: must equal −g\[2,3\] \(G skew\)$"):
        autobal.LinearRotor(a["M"], a["C"], g, a["K"], per_node=4)


def test_add_refuses_and_leaves_the_rotor_as_it_was():
    """``add_balancer``, ``add_unbalance``, ``add_speed_bearing`` check the entry when it is
    added; a refused one is not kept (the rotor's export is the same as before)."""
    lr = rotor()
    lr.add_balancer(1, 0.08, 2, 0.05, 0.05)
    before = lr.export("x")
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.balancer\[1\]\.drag: must not be negative, got -0\.1$"):
        lr.add_balancer(0, 0.08, 2, 0.05, -0.1)
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.balancer\[1\]\.node: expected a whole number ≥ 0, got -3$"):
        lr.add_balancer(-3, 0.08, 2, 0.05)
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.unbalance\[0\]\.phase: must be a finite number, got inf$"):
        lr.add_unbalance(0, 1e-4, math.inf)
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.bearings\[0\]\.speeds: must increase strictly$"):
        lr.add_speed_bearing(0, [10.0, 5.0], np.zeros((2, 4)), np.zeros((2, 4)))
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.bearings\[0\]\.link: 0 is not a node other than the bearing's 0"):
        lr.add_speed_bearing(0, [10.0], np.zeros((1, 4)), np.zeros((1, 4)), link=0)
    assert lr.export("x") == before


def test_export_writes_a_config_the_cli_reads_with_finite_numbers(tmp_path: Path):
    """What ``export`` writes is valid TOML with finite numbers only (no ``NaN``): the rotor can
    hold no other, and the CLI reads it back."""
    lr = autobal.from_ross(FakeRoss(), balancers=[GOOD_BALANCER], unbalance=[dict(node=0, me=1e-4, phase=0.3)])
    text, files = lr.export("r")
    if tomllib is not None:
        doc: Any = tomllib.loads(text)

        def numbers(v: Any):
            if isinstance(v, dict):
                for x in v.values():
                    yield from numbers(x)
            elif isinstance(v, list):
                for x in v:
                    yield from numbers(x)
            elif isinstance(v, float):
                yield v

        assert all(math.isfinite(x) for x in numbers(doc))
        assert doc["linear_rotor"]["balancer"][0]["ball_mass"] == 0.05
    for name, body in files:
        assert "nan" not in body.lower() and "inf " not in body.lower(), name
    (tmp_path / "r.toml").write_text(text)
    for name, body in files:
        (tmp_path / name).write_text(body)
    out = subprocess.run([binary(), "stability", "--config", str(tmp_path / "r.toml"), "--omega-max", "300rad/s", "--samples", "10"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr


@pytest.mark.parametrize(
    "table, python",
    [
        ("[[linear_rotor.balancer]]\nnode = 42\nradius = 0.08\nballs = 2\nball_mass = 0.05\n", lambda lr: lr.add_balancer(42, 0.08, 2, 0.05)),
        ("[[linear_rotor.balancer]]\nnode = 1\nradius = 0.08\nballs = 2\nball_mass = -0.05\n", lambda lr: lr.add_balancer(1, 0.08, 2, -0.05)),
        ("[[linear_rotor.unbalance]]\nnode = 0\nme = 1e-4\noffset = inf\n", lambda lr: lr.add_unbalance(0, 1e-4, 0.0, math.inf)),
        (
            "[[linear_rotor.balancer]]\nnode = 1\nradius = 0.08\nballs = 2\nball_mas = 0.05\n",
            lambda lr: autobal.from_ross(FakeRoss(), balancers=[dict(node=1, radius=0.08, balls=2, ball_mas=0.05)]),
        ),
        (
            "[[linear_rotor.balancer]]\nnode = 1\nradius = 0.08\nballs = 2\n",
            lambda lr: autobal.from_ross(FakeRoss(), balancers=[dict(node=1, radius=0.08, balls=2)]),
        ),
        # real balls (the config's keys of [[linear_rotor.balancer]])
        (
            "[[linear_rotor.balancer]]\nnode = 1\nradius = 0.08\nballs = 2\nball_mass = 0.05\ncontact = true\nrestitution = 2\n",
            lambda lr: lr.add_balancer(1, 0.08, 2, 0.05, contact=True, restitution=2.0),
        ),
        (
            "[[linear_rotor.balancer]]\nnode = 1\nradius = 0.08\nballs = 2\nball_mass = 0.05\ncontact = true\nball_diameter = 0.2\n",
            lambda lr: lr.add_balancer(1, 0.08, 2, 0.05, contact=True, ball_diameter=0.2),
        ),
        (
            "[[linear_rotor.balancer]]\nnode = 1\nradius = 0.08\nballs = 2\nball_mass = 0.05\nrolling_resistance = 5\n",
            lambda lr: autobal.from_ross(FakeRoss(), balancers=[dict(node=1, radius=0.08, balls=2, ball_mass=0.05, rolling_resistance=5)]),
        ),
        (
            "[[linear_rotor.balancer]]\nnode = 1\nradius = 0.08\nballs = 2\nball_mass = 0.05\ncontact = \"yes\"\n",
            lambda lr: autobal.from_ross(FakeRoss(), balancers=[dict(node=1, radius=0.08, balls=2, ball_mass=0.05, contact="yes")]),
        ),
    ],
)
def test_python_error_reads_as_the_clis(tmp_path: Path, table, python):
    """The same bad entry in a config the CLI reads and in Python: the same field and reason
    (compared up to the list of known keys, which the CLI and Python order differently)."""
    text, files = rotor().export("r")
    (tmp_path / "r.toml").write_text(text + "\n" + table)
    for name, body in files:
        (tmp_path / name).write_text(body)
    out = subprocess.run([binary(), "stability", "--config", str(tmp_path / "r.toml"), "--omega-max", "300rad/s"], capture_output=True, text=True)
    assert out.returncode != 0
    with pytest.raises(autobal.InvalidParameter) as e:
        python(rotor())
    ours = message(e).split(" (known keys:")[0]
    assert ours in out.stderr, (ours, out.stderr)


def ross():
    try:
        import ross as rs  # noqa: F401

        return rs
    except Exception as e:  # ImportError, or ROSS's own import failure under plotly 7
        if os.environ.get("AUTOBAL_REQUIRE_ROSS"):
            raise
        pytest.skip(f"needs ROSS (pip install ross-rotordynamics 'plotly<6'; not in requirements-test.txt): {e.__class__.__name__}")


def test_from_ross_on_a_ross_rotor_refuses_the_reviewers_cases():
    """The review's reproduction on ROSS's example rotor (7 nodes): a node that does not exist,
    a negative ball mass, a NaN unbalance and a misspelt key are refused by ``from_ross``."""
    rs = ross()
    r = rs.rotor_example()
    n = len(r.nodes)
    good_b, good_u = dict(node=2, radius=0.08, balls=2, ball_mass=0.05, drag=0.05), dict(node=3, me=1e-4)
    cases = [
        (dict(good_b, node=42), good_u, rf"^linear_rotor\.balancer\[0\]\.node: 42 is not a node \(the nodes are 0 to {n - 1}\)$"),
        (dict(good_b, ball_mass=-0.05), good_u, r"^linear_rotor\.balancer\[0\]\.ball_mass: must be positive, got -0\.05$"),
        (good_b, dict(good_u, me=float("nan")), r"^linear_rotor\.unbalance\[0\]\.me: must be a finite number, got NaN$"),
        (dict(good_b, ball_mas=0.05), good_u, r"^linear_rotor\.balancer\[0\]\.ball_mas: unknown key \(known keys: "),
    ]
    for b, u, expected in cases:
        with pytest.raises(autobal.InvalidParameter, match=expected):
            autobal.from_ross(r, balancers=[b], unbalance=[u])
    lr = autobal.from_ross(r, balancers=[good_b], unbalance=[good_u])
    text, _ = lr.export("r")
    if tomllib is not None:
        assert tomllib.loads(text)["linear_rotor"]["unbalance"][0]["me"] == 1e-4


def test_real_balls_from_python_are_the_configs(tmp_path: Path):
    """Real balls given to ``add_balancer`` / ``from_ross`` are the config's: ``export`` writes
    them as ``[[linear_rotor.balancer]]`` keys, and the CLI reading that config refuses the
    stationary analysis as it refuses a config written by hand (a friction dead zone or resting
    contact has no linearisation); the Python rotor's own stability refuses it the same way. A
    contact-law key without ``contact=True`` would be ignored, so it is refused by name."""
    lr = autobal.from_ross(
        FakeRoss(), balancers=[dict(GOOD_BALANCER, contact=True, ball_diameter=0.02, rolling_resistance=2e-3)], unbalance=[GOOD_UNBALANCE]
    )
    text, files = lr.export("r")
    if tomllib is not None:
        b = tomllib.loads(text)["linear_rotor"]["balancer"][0]
        assert (b["contact"], b["ball_diameter"], b["rolling_resistance"], b["restitution"]) == (True, 0.02, 2e-3, 0.5)
    else:
        assert "contact = true" in text and "ball_diameter = 0.02" in text
    cfg = tmp_path / "r.toml"
    cfg.write_text(text)
    for name, body in files:
        (cfg.parent / name).write_text(body)
    out = subprocess.run([binary(), "stability", "--config", str(cfg), "--omega-max", "300rad/s", "--samples", "10"], capture_output=True, text=True)
    assert out.returncode != 0 and "linearisation" in out.stderr, out.stderr
    with pytest.raises(Exception, match="linearisation"):
        lr.stability(300.0, samples=10)
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.balancer\[1\]\.ball_diameter: has no effect without contact=True$"):
        lr.add_balancer(0, 0.08, 2, 0.05, ball_diameter=0.02)
    with pytest.raises(autobal.InvalidParameter, match=r"^linear_rotor\.balancer\[1\]\.slip_rate: has no effect without a rolling_resistance$"):
        lr.add_balancer(0, 0.08, 2, 0.05, slip_rate=1e-3)
