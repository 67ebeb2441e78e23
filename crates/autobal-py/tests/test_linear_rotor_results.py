"""A linear rotor config (``[linear_rotor]``) from Python (issue 19 item 4, issue 20 item 3):
the result objects of ``map``, ``sweep``, ``basins`` and ``stability`` with their figures and
tables, the paths of one balancer plane or unbalance of several, and the sweep on a Dask
cluster (the config shipped as its text and its matrix files' bytes).

The CLI comparisons need the `autobal` binary cargo built: $AUTOBAL_BIN, else target/debug/autobal.
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

import autobal
from _cli import binary, cli

ROOT = Path(__file__).resolve().parents[3]
SHAFT = str(ROOT / "examples" / "linear_rotor_shaft.toml")
SHORT = {"drive.t_end": 0.2}


def traces(fig):
    return [t for t in fig.to_dict()["data"]]


def test_paths_of_one_plane_or_unbalance():
    """``linear_rotor.balancer[j].KEY`` in a sweep is, on a one-plane config, the sweep of
    ``linear_rotor.ball_mass`` run for run (two routes to the same tables); as ``set`` it is
    the config edited; an index past the last plane is an ``InvalidParameter`` naming the path
    and the count."""
    a = autobal.run("sweep", SHAFT, set=SHORT, x="linear_rotor.balancer[0].ball_mass=0.02,0.03")
    b = autobal.run("sweep", SHAFT, set=SHORT, x="linear_rotor.ball_mass=0.02,0.03")
    assert [r["summary"] for r in a["runs"]] == [r["summary"] for r in b["runs"]]
    assert a["runs"][0]["summary"] != a["runs"][1]["summary"], "the ball mass changes the run"
    st = autobal.run("stability", SHAFT, set={"linear_rotor.balancer[0].ball_mass": 0.035}, omega_max="2500 rad/s", samples=20)
    base = autobal.run("stability", SHAFT, omega_max="2500 rad/s", samples=20)
    assert st["points"] != base["points"]
    with pytest.raises(autobal.InvalidParameter, match=r"linear_rotor\.balancer\[1\]\.drag: the config has 1 \[\[linear_rotor\.balancer\]\] \(j from 0 to 0\)"):
        autobal.run("sweep", SHAFT, set=SHORT, x="linear_rotor.balancer[1].drag=0.1,0.2")
    with pytest.raises(autobal.InvalidParameter, match=r"linear_rotor\.unbalance\[0\]\.mass: unknown key"):
        autobal.run("map", SHAFT, x="speed=100:1500:3", y="linear_rotor.unbalance[0].mass=1:2:2")


def test_map_plot_table_and_rich_display():
    """``analyse("map")`` on a linear config: ``.plot()`` is the CLI's ``stability_map`` (the
    heatmap's cells are the margins ``run`` returns, computed by the CLI's ``map`` a second
    time, and the verdicts agree), ``.to_pandas()`` one row per cell as the CLI's CSV,
    ``_repr_html_`` a table and the figure."""
    pytest.importorskip("plotly")
    pd = pytest.importorskip("pandas")
    r = autobal.analyse("map", SHAFT, x="speed=100:1500:4", y="linear_rotor.drag=0.02:0.1:2")
    fig = r.plot()
    assert set(r.figures()) == {"stability_map"}
    heat = [t for t in traces(fig) if t["type"] == "heatmap"]
    assert len(heat) == 1
    z = np.array(heat[0]["z"], dtype=float)
    assert z.shape == r.result["margin"].shape == (2, 4)
    finite = np.isfinite(r.result["margin"])
    assert finite.any()
    # the same margins by the figure's run and by run()'s (each a full computation): the
    # heatmap draws them on the diverging scale, sign(m) sqrt(|m| / largest |m| of that sign),
    # written to 4 decimals (hence the tolerance 1e-4)
    m = r.result["margin"][finite]
    scale = np.where(m > 0, m.max(), -m.min())
    np.testing.assert_allclose(z[finite], np.sign(m) * np.sqrt(np.abs(m) / scale), rtol=0, atol=1e-4)
    df = r.to_pandas()
    assert isinstance(df, pd.DataFrame) and len(df) == 8
    assert list(df.columns) == ["speed", "linear_rotor.drag", "margin", "verdict", "family_dimension", "state"]
    assert df["verdict"].iloc[0] == "unstable"  # below the first critical speed
    # the CLI's CSV, row for row
    out = Path(os.environ.get("TMPDIR", "/tmp")) / f"autobal-linmap-{os.getpid()}"
    cli("map", "--config", SHAFT, "--x", "speed=100:1500:4", "--y", "linear_rotor.drag=0.02:0.1:2", "--out", str(out))
    rows = [line.split(",") for line in out.with_suffix(".csv").read_text().splitlines()[1:]]
    assert [(float(a), float(b)) for a, b, *_ in rows] == list(zip(df["speed"], df["linear_rotor.drag"]))
    assert [x[3] or None for x in rows] == list(df["verdict"])
    html = r._repr_html_()
    assert "autobal map" in html and "plotly" in html.lower()


def test_sweep_plot_and_table():
    """``analyse("sweep")``: the figures ``sweep_peak`` and ``sweep_final`` hold each run's
    peak and final whirl radius (mm) at its value of the first axis, one curve per value of
    the second, the same numbers as the JSON's run summaries; ``.to_pandas()`` one row per run."""
    pytest.importorskip("plotly")
    pytest.importorskip("pandas")
    s = autobal.analyse("sweep", SHAFT, set=SHORT, x="linear_rotor.ball_mass=0.02,0.03", y="linear_rotor.drag=0.1,0.2")
    assert set(s.figures()) == {"sweep_peak", "sweep_final"}
    peak = traces(s.plot("sweep_peak"))
    assert len(peak) == 2, "one curve per drag"
    runs = s.result["runs"]
    for k, drag in enumerate([0.1, 0.2]):
        mine = [r for r in runs if r["values"][1] == drag]
        assert list(peak[k]["x"]) == [r["values"][0] for r in mine]
        # the figure writes 6 significant digits
        np.testing.assert_allclose(peak[k]["y"], [1e3 * r["summary"]["peak"]["value"] for r in mine], rtol=1e-5, atol=0)
        assert "linear_rotor.drag = " + ("0.1" if k == 0 else "0.2") == peak[k]["name"]
    final = traces(s.plot("sweep_final"))
    np.testing.assert_allclose(final[0]["y"], [1e3 * r["summary"]["final_radius"] for r in runs if r["values"][1] == 0.1], rtol=1e-5, atol=0)
    assert len(s.to_pandas()) == 4
    assert "plotly" in s._repr_html_().lower()


def test_basins_plot_and_table_equal_the_clis_csv(tmp_path):
    """``analyse("basins")``: ``.to_pandas()`` is the CLI's CSV (the same runs, bit for bit);
    ``.plot()`` a cell per run at its initial angles, balanced or not as the CSV says (the
    verdict scale's Plotly values: -0.5 stable/balanced, +0.5 not)."""
    pytest.importorskip("plotly")
    pd = pytest.importorskip("pandas")
    sets = {"drive.t_end": 0.05}
    b = autobal.analyse("basins", SHAFT, set=sets, n=2)
    df = b.to_pandas()
    cli("basins", "--config", SHAFT, "--set", "drive.t_end=0.05", "--n", "2", "--out", str(tmp_path / "b.csv"))
    want = pd.read_csv(tmp_path / "b.csv")
    assert list(df.columns) == list(want.columns)
    assert df.to_numpy().tobytes() == want.to_numpy().tobytes()
    heat = [t for t in traces(b.plot()) if t["type"] == "heatmap"][0]
    z = np.array(heat["z"], dtype=float)
    assert z.shape == (2, 2)
    for _, row in df.iterrows():
        i, j = int(round(row["psi_1"] / np.pi)), int(round(row["psi_2"] / np.pi))
        assert z[j, i] == (-0.5 if row["balanced"] else 0.5)


def test_stability_plot_is_the_margin():
    """``analyse("stability")`` on a linear config draws ``stability_margin`` (``autobal
    stability --svg``'s figure), from the same run."""
    pytest.importorskip("plotly")
    r = autobal.analyse("stability", SHAFT, omega_max="2500 rad/s", samples=20)
    assert set(r.figures()) == {"stability_margin"}
    assert traces(r.plot())


def short_matrix_config(tmp_path: Path) -> Path:
    """The shaft example exported as Matrix Market files, with a short run-up: a config whose
    matrices live in files beside it."""
    autobal.export_model(SHAFT, out=tmp_path / "model", stem="shaft")
    cfg = tmp_path / "model" / "shaft.toml"
    cfg.write_text(cfg.read_text() + '\n[drive]\nkind = "acceleration"\nomega0 = 300.0\nb = 1000.0\nt_end = 0.1\n\n[integration]\ndt = 0.002\n')
    return cfg


def test_linear_spec_travels_as_text_and_bytes(tmp_path):
    """What a Dask worker gets, the config's text and its files' bytes, rebuilds the same
    problem without the files on disk: the same batch, bit for bit."""
    cfg = short_matrix_config(tmp_path)
    spec = autobal._autobal.LinearSpec(str(cfg), [])
    files = spec.files()
    assert sorted(files) == ["shaft_C.mtx", "shaft_G.mtx", "shaft_K.mtx", "shaft_M.mtx"]
    text = spec.toml
    paths = ["linear_rotor.ball_mass"]
    here = autobal.simulate_batch(str(cfg), paths, [[0.02], [0.03]])
    for f in files:
        (cfg.parent / f).unlink()
    again = autobal._autobal.LinearSpec.from_parts(text, files)
    there = autobal._autobal.simulate_batch(again, paths, np.array([[0.02], [0.03]]), None)
    assert here.tobytes() == there.tobytes()
    assert here.shape == (2, len(autobal.columns(str(SHAFT))))
    with pytest.raises(autobal.AutobalError, match="shaft_M.mtx"):
        autobal._autobal.LinearSpec.from_parts(text, {})


def test_dask_sweep_of_a_linear_config_equals_the_serial_one_and_the_clis(tmp_path):
    """``autobal.sweep(path, axes, client=)`` on a config naming matrix files: on a local
    cluster of processes the same table as without a client, bit for bit; each run's peak and
    final radius those of ``autobal sweep`` (the CLI's JSON) at the same point."""
    pytest.importorskip("pandas")
    pytest.importorskip("dask")
    distributed = pytest.importorskip("distributed")
    cfg = short_matrix_config(tmp_path)
    axes = {"linear_rotor.ball_mass": [0.02, 0.03], "linear_rotor.balancer[0].drag": [0.1, 0.2]}
    serial = autobal.sweep(str(cfg), axes)
    assert list(serial.columns) == ["point", *axes, *autobal._autobal.LINEAR_SUMMARY_COLUMNS]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        got = autobal.sweep(str(cfg), axes, client=client, chunk_size=1, out=tmp_path / "d.csv")
    assert got.to_numpy().tobytes() == serial.to_numpy().tobytes()
    assert len(list((tmp_path / "d.parts").glob("chunk-*.npy"))) == 4
    want = json.loads(
        cli("sweep", "--config", str(cfg), "--x", "linear_rotor.ball_mass=0.02,0.03", "--y", "linear_rotor.balancer[0].drag=0.1,0.2", "--format", "json", "--out", str(tmp_path / "c")).stdout
    )
    for row, run in zip(got.itertuples(index=False), want["runs"]):
        assert [row[1], row[2]] == run["values"]
        assert row.peak_amplitude == run["summary"]["peak"]["value"]
        assert row.final_amplitude == run["summary"]["final_radius"]
    with pytest.raises(autobal.InvalidParameter, match="not a \\[linear_rotor\\] config"):
        autobal.sweep(str(ROOT / "examples" / "planar.toml"), axes)


def test_a_dict_config_reads_its_matrix_files_from_the_working_folder(tmp_path, monkeypatch):
    """``run``/``analyse`` on a dict of a ``[linear_rotor]`` config's tables: its matrix files
    are read relative to the working folder (as ``export_model`` reads a dict's). From the
    folder of the files, the same results as the file (stability, a sweep's runs, the map's
    cells and figure); from another folder an error naming the key and the file."""
    tomllib = pytest.importorskip("tomllib")
    cfg = short_matrix_config(tmp_path)
    tables = tomllib.loads(cfg.read_text())
    monkeypatch.chdir(cfg.parent)
    for command, opts in (("stability", {"omega_max": "2500 rad/s", "samples": 20}), ("sweep", {"x": "linear_rotor.balancer[0].ball_mass=0.02,0.03"})):
        a = autobal.run(command, tables, **opts)
        b = autobal.run(command, str(cfg), **opts)
        if command == "sweep":
            assert [r["summary"] for r in a["runs"]] == [r["summary"] for r in b["runs"]]
            assert a["definition_checksum"] == b["definition_checksum"]
        else:
            assert a == b
    m = autobal.analyse("map", tables, x="speed=300:1500:3", y="linear_rotor.ball_mass=0.02:0.03:2")
    mf = autobal.analyse("map", str(cfg), x="speed=300:1500:3", y="linear_rotor.ball_mass=0.02:0.03:2")
    np.testing.assert_array_equal(m.result["margin"], mf.result["margin"])
    if pytest.importorskip("plotly"):
        assert m.figures() == mf.figures()
    monkeypatch.chdir(tmp_path)
    # a file's matrix files are read beside it from any working folder: the map's cells and
    # figure (the commands' map on the file's tables with the file's folder) as from its own
    mr = autobal.analyse("map", os.path.relpath(cfg), x="speed=300:1500:3", y="linear_rotor.ball_mass=0.02:0.03:2")
    np.testing.assert_array_equal(mr.result["margin"], mf.result["margin"])
    assert mr.figures() == mf.figures()
    monkeypatch.chdir(tmp_path)
    with pytest.raises(autobal.AutobalError, match=r"linear_rotor\.m: .*shaft_M\.mtx"):
        autobal.run("stability", tables, omega_max="2500 rad/s", samples=20)
