"""A linear rotor's run in time from Python (``LinearRotor.simulate``) against the CLI's
``simulate`` (its CSV, Parquet file and JSON, bit for bit), its figures, and the report about a
``[linear_rotor]`` config from Python against the CLI's, file by file (issue 19).

The CLI comparisons need the `autobal` binary cargo built: $AUTOBAL_BIN, else target/debug/autobal.
"""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

import autobal
from _cli import binary, cli

ROOT = Path(__file__).resolve().parents[3]
SHAFT = str(ROOT / "examples" / "linear_rotor_shaft.toml")
SHORT = {"drive.t_end": 0.2}


def without_walls(d):
    if isinstance(d, dict):
        return {k: without_walls(v) for k, v in d.items() if not k.startswith("wall")}
    return d


def test_simulate_equals_the_clis_csv_parquet_and_json(tmp_path):
    # the same run (the shaft example, reduced, a run-up of 0.2 s): every sample of every
    # column equal bit for bit (the CSV holds the shortest string that reads back to the same
    # double), the summary equal but for the wall time
    want = json.loads(cli("simulate", "--config", SHAFT, "--set", "drive.t_end=0.2", "--parquet", "--format", "json", "--out", str(tmp_path / "s")).stdout)
    sim = autobal.LinearRotor.from_config(SHAFT, set=SHORT).simulate()
    assert isinstance(sim, autobal.LinearSimulation) and isinstance(sim, autobal.Result)
    assert without_walls(sim.summary) == without_walls(want)
    lines = (tmp_path / "s.csv").read_text().splitlines()
    header = lines[0].split(",")
    assert list(sim.columns) == header == ["t", "omega", "x_0", "y_0", "r_0", "r_max", "psi_0", "psi_1"]
    rows = np.array([[float(v) for v in line.split(",")] for line in lines[1:]])
    got = np.column_stack([sim.columns[c] for c in header])
    assert got.shape == rows.shape == (101, 8)
    assert np.array_equal(got, rows)
    # the Parquet file: the same columns and doubles
    pd = pytest.importorskip("pandas")
    pytest.importorskip("pyarrow")
    df = pd.read_parquet(tmp_path / "s.parquet")
    assert list(df.columns) == header and np.array_equal(df.to_numpy(), rows)
    assert list(sim.to_pandas().columns) == header and np.array_equal(sim.to_pandas().to_numpy(), rows)


def test_simulate_from_matrices_equals_the_config(tmp_path):
    # a rotor built from NumPy matrices (as from_ross builds one) runs as the config it was
    # exported from (export-model writes every digit; a rotor without a config gets the CLI's
    # defaults: no [drive], [integration]'s defaults)
    import tomllib

    text, files = autobal.LinearRotor.from_config(SHAFT).export("e")
    for name, body in files:
        (tmp_path / name).write_text(body)
    (tmp_path / "e.toml").write_text(text)
    mmread = pytest.importorskip("scipy.io").mmread

    def dense(x: str) -> np.ndarray:
        a = mmread(str(tmp_path / f"e_{x}.mtx"))
        return np.ascontiguousarray(np.asarray(a.todense() if hasattr(a, "todense") else a, dtype=float))

    lr = autobal.LinearRotor(*(dense(x) for x in "MCGK"), per_node=4)
    t = tomllib.loads(text)["linear_rotor"]
    for b in t.get("bearings", []):
        k = np.array([b[x] for x in ("kxx", "kxy", "kyx", "kyy")]).T.copy()
        c = np.array([b[x] for x in ("cxx", "cxy", "cyx", "cyy")]).T.copy()
        lr.add_speed_bearing(b["node"], b["speeds"], k, c)
    for u in t["unbalance"]:
        lr.add_unbalance(u["node"], u["me"], u["phase"], u["offset"])
    for b in t["balancer"]:
        lr.add_balancer(b["node"], b["radius"], b["balls"], b["ball_mass"], b["drag"], b["offset"])
    a = lr.simulate(omega_max=300.0, dt=0.5, modes=2)
    b = autobal.LinearRotor.from_config(tmp_path / "e.toml").simulate(omega_max=300.0, dt=0.5, modes=2)
    assert list(a.columns) == list(b.columns)
    for col in a.columns:
        assert np.array_equal(a.columns[col], b.columns[col]), col
    assert without_walls(a.summary) == without_walls(b.summary)
    # without [drive]: from rest to omega_max in 1000 revolutions, t_end = 4π·1000/omega_max
    t_end = 4 * np.pi * 1000 / 300.0
    assert a.summary["t_end_reached"] == pytest.approx(t_end, rel=1e-12)
    # the speed rises linearly, Ω = 300 t / t_end; the last sample within dt = 0.5 s of the end
    assert np.allclose(a.columns["omega"], 300.0 * a.columns["t"] / t_end, rtol=1e-12, atol=0)
    assert a.columns["t"][-1] > t_end - 0.5 - 1e-9
    assert a.summary["reduction"]["mode_pairs"] == 2


def test_simulate_plots_and_errors():
    pytest.importorskip("plotly")
    sim = autobal.LinearRotor.from_config(SHAFT, set=SHORT).simulate()
    assert set(sim.figures()) == {"simulation_amplitude_omega", "simulation_amplitude_t", "simulation_psi_t", "simulation_omega_t"}
    fig = sim.plot()
    assert "against speed" in fig.layout.title.text and len(fig.data) == 2
    assert "<table>" in sim._repr_html_()
    with pytest.raises(autobal.AutobalError, match="not a linear rotor config"):
        autobal.LinearRotor.from_config(ROOT / "examples" / "spatial.toml")
    with pytest.raises(autobal.AutobalError, match="drive.t_end"):
        autobal.LinearRotor.from_config(SHAFT, set={"drive.t_end": -1.0}).simulate()
    with pytest.raises(autobal.AutobalError, match=r"^set rotor\.mass: "):
        autobal.LinearRotor.from_config(SHAFT, set={"rotor.mass": 1.0})
    # a run cut short by its budget: SimulationError with the samples up to then
    with pytest.raises(autobal.SimulationError) as e:
        autobal.LinearRotor.from_config(SHAFT, set={"integration.max_steps": 20}).simulate()
    assert isinstance(e.value.result, autobal.LinearSimulation) and e.value.result.summary["stopped"]


def test_the_report_from_python_equals_the_clis(tmp_path):
    # a [linear_rotor] config: the same files from `autobal report` and `autobal.report`, but
    # for the page's wall time
    cli("report", "--config", SHAFT, "--set", "drive.t_end=0.5", "--quick", "--out", str(tmp_path / "cli"))
    rep = autobal.report(SHAFT, out=tmp_path / "py", set={"drive.t_end": 0.5}, quick=True)
    names = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "py").iterdir())
    assert "linear_rotor_modes_0.svg" in names and "linear_rotor_runup_amplitude_omega.png" in names
    timed = re.compile(r"(computed in |right-hand sides, |\()[0-9.]+ s")
    for name in names:
        a, b = (tmp_path / "cli" / name).read_bytes(), (tmp_path / "py" / name).read_bytes()
        if name == "index.html":
            a, b = (timed.sub("", x.decode()) for x in (a, b))
        assert a == b, name
    assert "linear_rotor_campbell_diagram" in rep.figures()


def test_a_report_whose_run_up_failed_is_returned_with_a_warning(tmp_path):
    # review 23: the CLI writes the report and exits 2 with "the report in ... is written, but
    # ... the run-up failed at t = ..."; Python returns the Report and warns with that line (it
    # raised, losing the Report object); a step budget of 100 steps fails the shaft's run-up
    import warnings
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        rep = autobal.report(SHAFT, out=tmp_path / "py", set={"integration.max_steps": 100}, quick=True)
    lines = [str(w.message) for w in caught if issubclass(w.category, UserWarning)]
    assert any("is written, but" in m and "the run-up failed at t = " in m for m in lines), lines
    assert (tmp_path / "py" / "index.html").exists() and "linear_rotor_campbell_diagram" in rep.figures()
    assert "The run-up failed at t = " in (tmp_path / "py" / "index.html").read_text()


def test_run_and_analyse_on_a_linear_rotor_config(tmp_path):
    """``autobal.run`` on a ``[linear_rotor]`` file (issue 19 item 4): ``map``, ``sweep`` and
    ``basins`` as the CLI computes them (the map's cells equal the CLI's CSV, a sweep's JSON
    the CLI's but for wall times), ``stability`` and ``simulate`` as the CLI's JSON; a path that
    does not exist is an ``InvalidParameter`` naming it."""
    m = autobal.run("map", SHAFT, x="speed=100:1500:4", y="linear_rotor.drag=0.02,0.1")
    assert m["margin"].shape == m["stable"].shape == (2, 4) and m["x_path"] == "speed"
    cli("map", "--config", SHAFT, "--x", "speed=100:1500:4", "--y", "linear_rotor.drag=0.02:0.1:2", "--out", str(tmp_path / "m"))
    rows = [line.split(",") for line in (tmp_path / "m.csv").read_text().splitlines()[1:]]
    for k, r in enumerate(rows):
        j, i = divmod(k, 4)
        assert (r[2] == "" and np.isnan(m["margin"][j, i])) or float(r[2]) == m["margin"][j, i]
        assert r[3] == (m["verdict"][j][i] or "")
    # below the first critical speed the balls' balanced state is unstable
    assert m["verdict"][0][0] == "unstable"
    with pytest.raises(autobal.InvalidParameter, match="linear_rotor.nope"):
        autobal.run("map", SHAFT, x="speed=100:1500:4", y="linear_rotor.nope=1,2")
    s = autobal.run("sweep", SHAFT, set=SHORT, x="linear_rotor.ball_mass=0.02,0.03")
    want = json.loads(cli("sweep", "--config", SHAFT, "--set", "drive.t_end=0.2", "--x", "linear_rotor.ball_mass=0.02,0.03", "--format", "json", "--out", str(tmp_path / "s")).stdout)
    assert s["problem"]["model"] == "linear" and len(s["runs"]) == 2
    assert [without_walls(r) for r in s["runs"]] == [without_walls(r) for r in want["runs"]]
    assert s["definition_checksum"] == want["definition_checksum"]
    b = autobal.run("basins", SHAFT, set={"drive.t_end": 0.05}, n=2)
    assert b["model"] == "linear" and b["runs"] == 4 and b["completed"] == 4
    st = autobal.run("stability", SHAFT, omega_max="1500 rad/s", samples=20)
    assert st["model"] == "linear"
    assert autobal.analyse("map", SHAFT, x="speed=100:1500:4", y="linear_rotor.drag=0.02,0.1").result["margin"].shape == (2, 4)


def test_the_maps_boundary_is_bisected_along_both_axes_as_by_the_cli(tmp_path):
    """``boundary=True`` on a linear rotor config with the speed on ``y`` (hunt 28: only the rows
    were bisected, so every column's change from unstable to stable along the speed gave no
    point): one point per column, ``along`` ``"y"``, the CLI's ``_boundary.csv`` row for row (the
    same code: equal to 1e-12 relative, far inside the 1e-9 bisection); transposed, the same
    points along ``"x"``."""
    x, y = "linear_rotor.support_stiffness_scale=0.5,1.25,2", "speed=100:3000:6"
    m = autobal.run("map", SHAFT, x=x, y=y, boundary=True)
    pts = m["boundary"]
    assert [(p["x"], p["along"], p["from"], p["to"]) for p in pts] == [(s, "y", "unstable", "stable") for s in (0.5, 1.25, 2.0)]
    # each a change of verdict, bisected to the library's BOUNDARY_RTOL (not a fold's 1e-4)
    assert [p["rtol"] for p in pts] == [1e-9] * 3
    cli("map", "--config", SHAFT, "--x", x.replace("0.5,1.25,2", "0.5:2:3"), "--y", y, "--boundary", "--out", str(tmp_path / "m"))
    lines = (tmp_path / "m_boundary.csv").read_text().splitlines()
    assert lines[0] == "linear_rotor.support_stiffness_scale,speed,from,to,along"
    rows = [line.split(",") for line in lines[1:]]
    assert len(rows) == len(pts)
    for r, p in zip(rows, pts):
        assert float(r[0]) == p["x"] and abs(float(r[1]) - p["y"]) <= 1e-12 * p["y"] and r[2:] == [p["from"], p["to"], p["along"]]
    t = autobal.run("map", SHAFT, x=y, y=x, boundary=True)["boundary"]
    assert [(q["y"], q["along"]) for q in t] == [(p["x"], "x") for p in pts]
    assert all(abs(q["x"] - p["y"]) <= 1e-12 * p["y"] for q, p in zip(t, pts))


def test_a_fixed_speed_beside_a_speed_axis_is_refused_as_by_the_cli(tmp_path):
    """``omega`` beside a speed axis: ``autobal.run("map")`` on a linear rotor config ignored it
    (hunt 28; the CLI refuses it since hunt 27). Refused in the library's one place
    (``rotor_map::check_fixed_speed``), so Python on a linear rotor config, Python on any other
    config and the CLI say the same words, Python's field its keyword ``omega``."""
    words = "3000 rpm: the map's y axis {} is the speed already; drop the fixed speed, or map over two other parameters at that speed"
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.run("map", SHAFT, x="linear_rotor.drag=0.02,0.1", y="speed=100:1500:3", omega="3000 rpm")
    assert str(e.value) == "omega: " + words.format("speed")
    out = subprocess.run(
        [binary(), "map", "--config", SHAFT, "--x", "linear_rotor.drag=0.02:0.1:2", "--y", "speed=100:1500:3", "--omega", "3000 rpm", "--out", str(tmp_path / "m")],
        capture_output=True,
        text=True,
    )
    assert out.returncode != 0 and out.stderr.strip() == "error: --omega: " + words.format("speed"), out.stderr
    assert not (tmp_path / "m.csv").exists()
    planar = str(ROOT / "examples" / "planar.toml")
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.run("map", planar, x="planar.c_psi=0.05:0.2:2", y="omega=300:400:2", omega="3000 rpm")
    assert str(e.value) == "omega: " + words.format("omega")


def _cli_stability(*sets: str, omega_max: str = "1500 rad/s", samples: str = "20"):
    """`autobal stability --format json` on the shaft example with `--set`s, and its exit."""
    import subprocess

    args = [binary(), "stability", "--config", SHAFT, "--omega-max", omega_max, "--samples", samples, "--format", "json"]
    for s in sets:
        args += ["--set", s]
    return subprocess.run(args, capture_output=True, text=True)


def test_linear_rotor_stability_takes_the_operating_speed_as_the_cli():
    """``LinearRotor.stability(operating_speed=...)`` (review 21: the object took none, the
    config route did): the verdict at the machine's speed, JSON ``operating``, equal bit for bit
    to ``autobal stability --set linear_rotor.operating_speed=...`` on the same rotor (the
    shaft example, reduced to its config's 4 mode pairs) in every form the key takes (rpm, a
    range, Hz, rad/s, a bare number in rad/s); the speed converted as the units say (rpm
    π/30, Hz 2π, to 1 ulp: one product of doubles); the CLI's refusals word for word."""
    import math

    lr = autobal.LinearRotor.from_config(SHAFT)
    plain = json.loads(lr.stability(1500.0, samples=20, modes=4))
    assert plain["operating"] is None
    verdicts = set()
    for form, toml, want_omega in [
        ("1400 rpm", '"1400 rpm"', [1400 * math.pi / 30] * 2),
        ("4000-5000 rpm", '"4000-5000 rpm"', [4000 * math.pi / 30, 5000 * math.pi / 30]),
        ("80 Hz", '"80 Hz"', [2 * math.pi * 80] * 2),
        ("700 rad/s", '"700 rad/s"', [700.0, 700.0]),
        (700.0, "700.0", [700.0, 700.0]),
        (700, "700", [700.0, 700.0]),
    ]:
        got = json.loads(lr.stability(1500.0, samples=20, modes=4, operating_speed=form))
        out = _cli_stability(f"linear_rotor.operating_speed={toml}")
        assert out.returncode == 0, out.stderr
        want = json.loads(out.stdout)
        assert got["operating"] == want["operating"], form
        # the scan is the CLI's too (its speeds, verdicts, ranges)
        assert got["points"] == want["points"] and [(s["from"], s["to"]) for s in got["stable_ranges"]] == [(s["from"], s["to"]) for s in want["stable_ranges"]]
        assert all(abs(a - b) <= 2.3e-16 * b for a, b in zip(got["operating"]["omega"], want_omega)), (form, got["operating"]["omega"])
        verdicts.add(got["operating"]["verdict"])
    # below the first critical speed the balls cannot balance; above it they do (both verdicts
    # checked: the comparison is not of two nulls)
    assert verdicts == {"stable", "unstable"}, verdicts
    for bad in ['"-100 rpm"', '"fast"', "0", "2e6", "true", '"900-800 rpm"']:
        out = _cli_stability(f"linear_rotor.operating_speed={bad}")
        assert out.returncode != 0
        want = out.stderr.strip().splitlines()[-1].removeprefix("error: ")
        value = {"true": True, "0": 0, "2e6": 2e6}.get(bad, bad.strip('"'))
        with pytest.raises(autobal.InvalidParameter) as e:
            lr.stability(1500.0, samples=20, modes=4, operating_speed=value)
        assert str(e.value) == want and e.value.field == "linear_rotor.operating_speed"


def test_linear_rotor_stability_stopped_keeps_what_it_analysed():
    """Ctrl-C during ``LinearRotor.stability`` (review 24: it raised ``KeyboardInterrupt`` and
    dropped the scan, where the CLI keeps the speeds analysed): ``KeyboardInterrupt`` still, its
    ``result`` the JSON kept, marked as the CLI's (``complete: false``, ``stopped`` naming the
    count), its points the first speeds of the grid; each of them equals a complete scan over
    those same speeds (a second run: the grid's first ``k`` speeds are
    ``stability(omega_max * k / n, samples=k)``'s to rounding, one division: 1e-15 relative)."""
    import _thread
    import threading

    lr = autobal.LinearRotor.from_config(SHAFT)
    n, omega_max = 1_000_000, 1500.0  # far more speeds than a second computes
    ctrl_c = threading.Timer(1.0, _thread.interrupt_main)
    ctrl_c.start()
    try:
        with pytest.raises(KeyboardInterrupt) as e:
            lr.stability(omega_max, samples=n, modes=4)
    finally:
        ctrl_c.cancel()
    kept = json.loads(e.value.result)
    k = len(kept["points"])
    assert kept["complete"] is False and 0 < k < n
    assert kept["stopped"].startswith(f"interrupted: {k} of {n} speeds analysed"), kept["stopped"]
    omegas = [p["omega"] for p in kept["points"]]
    assert all(abs(w - omega_max * i / n) <= 1e-15 * w for i, w in zip(range(1, k + 1), omegas))
    whole = json.loads(lr.stability(omega_max * k / n, samples=k, modes=4))
    assert "complete" not in whole and len(whole["points"]) == k
    for a, b in zip(kept["points"], whole["points"]):
        assert a["verdict"] == b["verdict"]
        # the abscissa at speeds 1e-15 apart: the eigenvalues move by that much relative, well
        # under 1e-9 of the largest rate (the solver's own round-off is ~1e-13 of it)
        if a["abscissa"] is not None:
            assert abs(a["abscissa"] - b["abscissa"]) <= 1e-9 * max(1.0, abs(b["abscissa"]))
