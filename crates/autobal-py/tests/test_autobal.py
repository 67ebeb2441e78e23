"""Tests of the Python package on the built wheel (scripts/test.sh builds it into .venv).

The CLI comparisons need the `autobal` binary: $AUTOBAL_BIN, else target/debug/autobal.
Optional tools (pandas, pyarrow, polars, dask) are required when AUTOBAL_REQUIRE_PYTHON is
set (scripts/test.sh and CI set it), else their tests are skipped.
"""

from __future__ import annotations

import json
import os
import subprocess
import threading
import time
import _thread
from pathlib import Path

import numpy as np
import pytest

import autobal
from autobal.errors import AutobalError, InvalidParameter

ROOT = Path(__file__).resolve().parents[3]
REQUIRE = bool(os.environ.get("AUTOBAL_REQUIRE_PYTHON"))


def need(module: str):
    try:
        return __import__(module)
    except ImportError:
        if REQUIRE:
            raise
        pytest.skip(f"needs {module} (pip install -r requirements-test.txt)")


def cli(*args: str) -> dict:
    exe = os.environ.get("AUTOBAL_BIN", str(ROOT / "target" / "debug" / "autobal"))
    if not Path(exe).exists():
        if REQUIRE:
            raise FileNotFoundError(f"{exe}: build the CLI first (cargo build -p autobal-cli)")
        pytest.skip("needs the autobal binary")
    out = subprocess.run([exe, *args, "--format", "json"], capture_output=True, text=True, check=True, cwd=os.environ.get("TMPDIR", "/tmp"))
    return json.loads(out.stdout)


def without(d, key):
    """`d` without `key` at any depth (wall times differ between runs)."""
    if isinstance(d, dict):
        return {k: without(v, key) for k, v in d.items() if k != key}
    if isinstance(d, list):
        return [without(v, key) for v in d]
    return d


SETS = {"dimensionless.l_left": 1.2, "analysis.anisotropy": "paper"}


@pytest.mark.parametrize("command", ["inertia", "critical", "ranges"])
def test_run_equals_the_cli_json(command):
    assert autobal.run(command) == cli(command)
    args = [a for k, v in SETS.items() for a in ("--set", f"{k}={v}")]
    assert autobal.run(command, set=SETS) == cli(command, *args)
    dim = str(ROOT / "examples" / "dimensional.toml")
    got = autobal.run(command, config=dim)
    assert got == cli(command, "--config", dim)


def test_run_linear_commands_equal_the_cli_json():
    assert autobal.run("stability", omega_max=4.0, samples=200) == cli("stability", "--omega-max", "4", "--samples", "200")
    assert autobal.run("stability", balls="locked", samples=100) == cli("stability", "--balls", "locked", "--samples", "100")
    got = autobal.run("campbell", points=20, omega_max=3.0)
    assert got == cli("campbell", "--points", "20", "--omega-max", "3")


def test_run_simulate_and_sweep_equal_the_cli_json(tmp_path):
    sets = {"drive.t_end": 1.0, "drive.omega0": 250.0, "drive.b": 100.0}
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={v}")]
    got = autobal.run("simulate", set=sets)
    want = cli("simulate", "--out", str(tmp_path / "s.csv"), *args)
    assert without(got, "wall_time_s") == without(want, "wall_time_s")
    got = autobal.run("sweep", set=sets, x="planar.c_psi=0.05:0.15:3", y="drive.b=80,120", shard="2/3")
    want = cli("sweep", "--out", str(tmp_path / "sw"), "--x", "planar.c_psi=0.05:0.15:3", "--y", "drive.b=80,120", "--shard", "2/3", *args)
    assert without(got, "wall_time_s") == without(want, "wall_time_s")


def test_spatial_simulate_and_basins_equal_the_cli_json(tmp_path):
    spatial = str(ROOT / "examples" / "spatial.toml")
    sets = {"drive.t_end": 300.0}
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={v}")]
    got = autobal.run("simulate", config=spatial, set=sets)
    want = cli("simulate", "--config", spatial, "--out", str(tmp_path / "s.csv"), *args)
    assert got["model"] == "spatial" and without(got, "wall_time_s") == without(want, "wall_time_s")
    # the columns are the CLI's CSV, sample by sample and bit for bit
    sim = autobal.SpatialModel(spatial, set=sets).simulate()
    assert without(sim.summary, "wall_time_s") == without(want, "wall_time_s")
    csv = np.genfromtxt(tmp_path / "s.csv", delimiter=",", names=True)
    for name in csv.dtype.names:
        col = sim[name] if not name.startswith("psi_") else sim["psi"][:, int(name[4:]) - 1]
        assert np.array_equal(col, csv[name]), name
    # a dimensional two-plane rotor: SI units, both planes' columns
    two = str(ROOT / "examples" / "spatial_two_plane.toml")
    s2 = autobal.SpatialModel(two, set={"drive.t_end": 0.05}).simulate()
    assert s2.summary["units"] == "SI" and "amplitude_plane2" in s2.columns and s2["psi"].shape[1] == 4
    # basins: the CLI's JSON (but the CSV's and SVG's names) and the CLI's CSV as arrays
    bsets = {"drive.t_end": 50.0}
    bargs = [a for k, v in bsets.items() for a in ("--set", f"{k}={v}")]
    got = autobal.run("basins", config=spatial, set=bsets, n=3)
    want = cli("basins", "--config", spatial, "--n", "3", "--out", str(tmp_path / "b.csv"), *bargs)
    assert without(got, "wall_time_s") == without(without(without(want, "wall_time_s"), "csv"), "svg")
    b = autobal.SpatialModel(spatial, set=bsets).basins(n=3)
    rows = np.genfromtxt(tmp_path / "b.csv", delimiter=",", names=True)
    for name in rows.dtype.names:
        # the CSV's per-run `balanced` column is `balanced_runs`: `balanced` is the JSON's count
        key = "balanced_runs" if name == "balanced" else name
        assert np.array_equal(np.asarray(b[key], dtype=float), rows[name]), name
    # the dict carries the JSON as the CLI prints it (balanced = how many runs ended balanced)
    arrays = ("psi_1", "psi_2", "balanced_runs", "residual_unbalance", "final_amplitude")
    assert without({k: v for k, v in b.items() if k not in arrays}, "wall_time_s") == without(without(without(want, "wall_time_s"), "csv"), "svg")
    assert b["balanced"] == int(np.count_nonzero(b["balanced_runs"])) and b["balanced_runs"].dtype == bool
    # no [drive]: the default run-up through the critical speeds, as the CLI runs it
    run_up = autobal.run("simulate", config=str(ROOT / "examples" / "dimensional.toml"))
    assert run_up["drive_is_default"] and run_up["drive"]["kind"] == "acceleration"
    # one default grid: without n, Python runs the CLI's `--n` default (basins::Args::default())
    short = {"drive.t_end": 0.5}
    dflt = cli("basins", "--config", spatial, "--out", str(tmp_path / "d.csv"), "--set", "drive.t_end=0.5")["runs"]
    assert autobal.run("basins", config=spatial, set=short)["runs"] == dflt == 24 * 24
    assert autobal.SpatialModel(spatial, set=short).basins()["runs"] == dflt
    # errors name the field: too small a grid
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.run("basins", config=spatial, n=1)
    assert e.value.field == "n"


def test_models_from_keywords_dicts_and_files(tmp_path):
    a = autobal.SpatialModel(l_left=1.2, anisotropy="paper")
    b = autobal.SpatialModel(set={"dimensionless.l_left": 1.2, "analysis.anisotropy": "paper"})
    assert a.critical() == b.critical()
    f = tmp_path / "m.toml"
    f.write_text(a.toml)
    c = autobal.SpatialModel.from_toml(f)
    assert np.array_equal(c.critical_speeds(), a.critical_speeds())
    d = autobal.SpatialModel(dict(dimensionless=dict(c_sigma=0.75, rho_s=0.4, l_left=0.8, z_a=0.8, delta_a=0.1)))
    # 003's worked example at l_L = 0.8 (Ω_K1-4 = 0.837, 0.849, 2.52, 3.80 as printed)
    assert np.allclose(d.critical_speeds(), [0.837, 0.849, 2.52, 3.80], atol=0.005)
    assert np.array_equal(autobal.SpatialModel.paper_003(0.8).critical_speeds(), d.critical_speeds())
    si = autobal.SpatialModel(rotor=dict(mass=20.0, equatorial_moment=0.6, polar_moment=0.15, z=0.25), supports=dict(z_left=0.0, z_right=0.5, stiffness_left=2e6, stiffness_right=3e6))
    assert si.critical()["model"]["scale"]["omega0"] > 0
    p = autobal.PlanarProblem(m3=0.01, b=5.0, t_end=20.0)
    assert (p.get("planar.m3"), p.get("drive.b"), p.get("drive.t_end")) == (0.01, 5.0, 20.0)
    assert autobal.PlanarProblem.paper_004(0.01).get("planar.m3") == 0.01
    assert any(path == "drive.psi0[j]" for path, _ in autobal.PlanarProblem.paths())


def test_a_missing_config_file_is_file_not_found(tmp_path):
    missing = tmp_path / "no_such.toml"
    for make in (autobal.SpatialModel, autobal.PlanarProblem):
        with pytest.raises(FileNotFoundError) as e:
            make(missing)
        assert e.value.filename == str(missing) and str(missing) in str(e.value)
    with pytest.raises(OSError):
        autobal.run("critical", config=str(missing))


def test_errors_name_the_field():
    with pytest.raises(InvalidParameter) as e:
        autobal.SpatialModel(rho_s=-1.0)
    assert e.value.field == "dimensionless.rho_s" and str(e.value).startswith("dimensionless.rho_s: must lie in")
    assert isinstance(e.value, ValueError) and isinstance(e.value, AutobalError)
    with pytest.raises(InvalidParameter) as e:
        autobal.PlanarProblem(set={"planar.m3": -1})
    assert e.value.field == "planar.m3"
    with pytest.raises(InvalidParameter, match="^l_lef: unknown keyword") as e:
        autobal.SpatialModel(l_lef=1.0)
    assert e.value.field == "l_lef" and "l_left" in str(e.value)
    with pytest.raises(InvalidParameter, match="^m33: unknown keyword") as e:
        autobal.PlanarProblem(m33=1.0)
    assert e.value.field == "m33" and e.value.reason.startswith("unknown keyword") and "m3," in str(e.value)
    with pytest.raises(InvalidParameter) as e:
        autobal.run("critical", nonsense=1)
    assert e.value.field == "nonsense"
    with pytest.raises(InvalidParameter) as e:
        autobal.SpatialModel(set={"dimensionless.l_lef": 1.0})
    assert e.value.field == "dimensionless.l_lef"
    with pytest.raises(InvalidParameter) as e:
        autobal.simulate_batch(autobal.PlanarProblem(), ["drive.torque"], [[1.0]])
    assert e.value.field == "drive.torque" and "kind acceleration" in str(e.value)
    with pytest.raises(InvalidParameter) as e:
        autobal.run("stability", omega_max=-1.0)
    assert e.value.field == "omega_max"
    # the report is a folder of pages: the error names the function that writes it
    with pytest.raises(InvalidParameter, match=r"autobal\.report\(config, out=\.\.\.\)") as e:
        autobal.run("report")
    assert e.value.field == "command"


def test_simulation_columns():
    s = autobal.PlanarProblem(t_end=1.0, omega0=250.0, b=100.0).simulate(dt=0.01)
    t = s["t"]
    assert t.shape == (101,) and t[-1] == pytest.approx(1.0)
    assert s["psi"].shape == (101, 2)
    assert np.allclose(s["amplitude"], np.hypot(s["x"], s["y"]), rtol=1e-9, atol=1e-15)
    assert s.summary["peak_amplitude"] >= s["amplitude"].max()
    pd = need("pandas")
    df = s.to_pandas()
    assert list(df.columns) == ["t", "omega", "x", "y", "amplitude", "psi_1", "psi_2"]
    assert isinstance(df, pd.DataFrame)


def short():
    return autobal.PlanarProblem(t_end=0.5, omega0=250.0, b=100.0)


def test_batch_equals_single_runs_and_threads_do_not_matter():
    p = short()
    params = autobal.grid({"planar.c_psi": [0.05, 0.1, 0.2], "drive.b": [80.0, 120.0]})
    one = autobal.simulate_batch(p, ["planar.c_psi", "drive.b"], params, threads=1)
    many = autobal.simulate_batch(p, ["planar.c_psi", "drive.b"], params, threads=4)
    assert one.tobytes() == many.tobytes()
    assert one.shape == (6, len(autobal.SUMMARY_COLUMNS))
    # row 4 is the problem at c_psi = 0.1, b = 120, run on its own
    s = autobal.PlanarProblem(t_end=0.5, omega0=250.0, b=120.0, c_psi=0.1, dt=0.5).simulate().summary
    row = dict(zip(autobal.SUMMARY_COLUMNS, one[4]))
    assert row["peak_amplitude"] == s["peak_amplitude"] and row["steps"] == s["steps"]


def spatial_two_plane():
    """examples/spatial_two_plane.toml (SI; static and couple unbalance, two ball sets, gravity,
    anisotropic supports) cut to half a second."""
    return autobal.SpatialModel(str(ROOT / "examples" / "spatial_two_plane.toml"), set={"drive.t_end": 0.5})


SPATIAL_AXES = {"balancer.ball_mass": [0.015, 0.025], "supports.stiffness_left_y": [2e6, 2.6e6], "balancer2.drag": [0.5, 1.0]}


def test_spatial_sweep_equals_the_cli_and_single_runs(tmp_path):
    """A sweep of the spatial rotor: the CLI's rows bit for bit (all but wall_s), its JSON
    through run("sweep"), the same bits on 1 or 2 threads, in chunks and on a worker, and a
    row is the config with those keys set, simulated on its own."""
    m = spatial_two_plane()
    paths = list(SPATIAL_AXES)
    names = ["point", *paths, *autobal.SPATIAL_SUMMARY_COLUMNS]
    assert autobal.columns(m) == autobal.SPATIAL_SUMMARY_COLUMNS
    assert autobal.SPATIAL_SUMMARY_COLUMNS[: len(autobal.SUMMARY_COLUMNS)] == autobal.SUMMARY_COLUMNS
    table = autobal.sweep(m, SPATIAL_AXES)
    cols = {k: np.asarray(v) for k, v in dict(table).items()} if isinstance(table, dict) else {c: table[c].to_numpy() for c in table.columns}
    assert list(cols) == names and len(cols["point"]) == 8
    # the CLI on the same config and grid
    two = str(ROOT / "examples" / "spatial_two_plane.toml")
    grid = ["--x", "balancer.ball_mass=0.015,0.025", "--y", "supports.stiffness_left_y=2e6,2.6e6", "--axis", "balancer2.drag=0.5,1"]
    want = cli("sweep", "--config", two, "--set", "drive.t_end=0.5", "--out", str(tmp_path / "cli"), *grid)
    csv = np.genfromtxt(tmp_path / "cli.csv", delimiter=",", names=True, deletechars="")
    assert list(csv.dtype.names) == [*names, "wall_s"]
    for name in names:
        assert np.array_equal(cols[name].astype(float), csv[name], equal_nan=True), name
    got = autobal.run("sweep", config=two, set={"drive.t_end": 0.5}, x=grid[1], y=grid[3], axis=[grid[5]])
    assert got["problem"]["model"] == "spatial" and without(got, "wall_time_s") == without(want, "wall_time_s")
    # threads, chunks and the Dask worker's route give the same bits
    params = autobal.grid(SPATIAL_AXES)
    one = autobal.simulate_batch(m, paths, params, threads=1)
    two_threads = autobal.simulate_batch(m, paths, params, threads=2)
    assert one.shape == (8, len(autobal.SPATIAL_SUMMARY_COLUMNS)) and one.tobytes() == two_threads.tobytes()
    from autobal._sweep import _run_chunk

    assert _run_chunk("spatial", m.toml, paths, params[3:], 1).tobytes() == one[3:].tobytes()
    chunked = autobal.sweep(m, SPATIAL_AXES, out=tmp_path / "sp.csv", chunk_size=3)
    assert np.array_equal(np.column_stack([np.asarray(chunked[c], dtype=float) for c in names]), np.column_stack([cols[c].astype(float) for c in names]), equal_nan=True)
    # row 5: ball mass 0.025, stiffness 2e6, drag 1.0, simulated on its own
    assert params[5].tolist() == [0.025, 2e6, 1.0]
    single = autobal.SpatialModel(two, set={"drive.t_end": 0.5, "balancer.ball_mass": 0.025, "supports.stiffness_left_y": 2e6, "balancer2.drag": 1.0}).simulate()
    row = dict(zip(autobal.SPATIAL_SUMMARY_COLUMNS, one[5]))
    for key in ["peak_amplitude", "t_at_peak", "final_amplitude", "residual_unbalance", "residual_couple", "static_sag", "steps", "rhs_evaluations"]:
        # (a null in the summary, e.g. the static sag of a run not settled: NaN in the row)
        want = single.summary[key]
        assert row[key] == want or (want is None and np.isnan(row[key])), key
    assert row["t_reached"] == single.summary["t_end"] == 0.5 and row["completed"] == 1.0
    outcomes = ["not_settled", "not_balanced", "partially_balanced", "balanced"]
    assert outcomes[int(row["outcome"])] == single.summary["outcome"]
    # the points differ: the axes reached the rotor
    assert len(set(one[:, 0].tolist())) == 8
    # paths are the config's keys; others are refused, naming the path
    with pytest.raises(InvalidParameter) as e:
        autobal.simulate_batch(m, ["planar.c_psi"], [[0.1]])
    assert e.value.field == "planar.c_psi"
    with pytest.raises(InvalidParameter) as e:
        autobal.simulate_batch(m, ["balancer.ball_mass"], [[0.02], [-0.02]])
    assert e.value.field == "balancer.ball_mass" and "at the point balancer.ball_mass = -0.02" in str(e.value)


def test_a_repeated_axis_value_is_refused_as_the_cli_refuses_it():
    # the dict form reached the grid without the text form's check: one point ran three times
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.sweep(short(), {"drive.b": [1.0, 1.0, 1.0]})
    assert e.value.field == "drive.b"
    assert "the value 1 is given more than once" in str(e.value)
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.sweep(short(), {"drive.b": [80.0], "planar.c_psi": [0.1, 0.2, 0.1]})
    assert e.value.field == "planar.c_psi"


def test_sweep_streams_and_resumes(tmp_path):
    pd = need("pandas")
    p = short()
    axes = {"planar.c_psi": [0.05, 0.1, 0.15, 0.2], "drive.b": [80.0, 120.0]}
    ref = autobal.sweep(p, axes)
    out = tmp_path / "sw.csv"
    got = autobal.sweep(p, axes, out=out, chunk_size=3)
    assert got.equals(ref)
    back = pd.read_csv(out)
    assert back.drop(columns="point").to_numpy().tobytes() == ref.drop(columns="point").to_numpy().tobytes()
    # an interrupted sweep keeps its finished chunks; the same call runs only the missing one
    parts = sorted((tmp_path / "sw.parts").glob("chunk-*.npy"))
    assert len(parts) == 3
    kept = parts[0].stat().st_mtime_ns
    parts[2].unlink()
    out.unlink()
    again = autobal.sweep(p, axes, out=out, chunk_size=3)
    assert again.equals(ref) and parts[0].stat().st_mtime_ns == kept and parts[2].exists()
    with pytest.raises(InvalidParameter, match="different sweep"):
        autobal.sweep(p, {"planar.c_psi": [0.3]}, out=out, chunk_size=3)


def test_parquet_is_read_by_pandas_and_polars(tmp_path):
    pd = need("pandas")
    need("pyarrow")
    ref = autobal.sweep(short(), {"planar.c_psi": [0.05, 0.1], "drive.b": [80.0, 120.0]}, out=tmp_path / "sw.parquet")
    assert pd.read_parquet(tmp_path / "sw.parquet").equals(ref)
    pl = need("polars")
    df = pl.read_parquet(tmp_path / "sw.parquet")
    assert df.columns == list(ref.columns)
    assert np.array_equal(df["peak_amplitude"].to_numpy(), ref["peak_amplitude"].to_numpy())


def test_long_calls_release_the_gil_and_stop_on_ctrl_c():
    # 4096 passages of 30 s: seconds of work on any machine, so Ctrl-C at 0.3 s lands mid-batch
    p = autobal.PlanarProblem(t_end=30.0, omega0=250.0, b=10.0)
    params = np.linspace(0.05, 0.2, 4096).reshape(-1, 1)
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.01)

    t = threading.Thread(target=tick)
    t.start()
    ctrl_c = threading.Timer(0.3, _thread.interrupt_main)
    ctrl_c.start()
    t0 = time.perf_counter()
    try:
        with pytest.raises(KeyboardInterrupt):
            autobal.simulate_batch(p, ["planar.c_psi"], params)
    finally:
        ctrl_c.cancel()  # a batch that ended first must not interrupt the test session later
        done.set()
        t.join()
    stopped = time.perf_counter() - t0
    assert stopped < 5.0, f"took {stopped:.1f} s to stop"
    assert len([x for x in ticks if x < t0 + 0.3]) >= 5, "another Python thread ran while the batch ran"


def test_stubs_are_shipped():
    pkg = Path(autobal.__file__).parent
    assert (pkg / "py.typed").exists() and (pkg / "_autobal.pyi").exists()


def test_docstring_examples_run():
    import doctest

    import autobal._sweep

    for mod in (autobal, autobal._sweep):
        r = doctest.testmod(mod, optionflags=doctest.NORMALIZE_WHITESPACE)
        assert r.failed == 0 and r.attempted > 0, mod.__name__


def interrupt_after_first_part(parts_dir: Path):
    """A thread that presses Ctrl-C (KeyboardInterrupt in the main thread) as soon as the first
    finished chunk lies in `parts_dir`, so the interruption lands mid-sweep whatever the load."""
    stop = threading.Event()

    def watch():
        while not stop.is_set():
            if any(parts_dir.glob("chunk-*.npy")):
                _thread.interrupt_main()
                return
            time.sleep(0.002)

    t = threading.Thread(target=watch, daemon=True)
    t.start()
    return stop


def interrupted_then_resumed(tmp_path, name, **kw):
    """Run a sweep, press Ctrl-C after its first chunk, check what was kept, resume; returns the
    resumed table and the number of chunks kept at the interruption."""
    p = autobal.PlanarProblem(t_end=2.0, omega0=250.0, b=100.0, dt=2.0)
    axes = {"planar.c_psi": np.linspace(0.05, 0.2, 24), "drive.b": [80.0, 120.0]}
    out = tmp_path / f"{name}.csv"
    parts = tmp_path / f"{name}.parts"
    stop = interrupt_after_first_part(parts)
    with pytest.raises(KeyboardInterrupt):
        autobal.sweep(p, axes, out=out, chunk_size=1, **kw)
    stop.set()
    kept = sorted(parts.glob("chunk-*.npy"))
    assert 0 < len(kept) < 48, f"{len(kept)} of 48 chunks kept"
    assert not out.exists(), "the table is written only when every chunk is done"
    stamps = {f.name: f.stat().st_mtime_ns for f in kept}
    again = autobal.sweep(p, axes, out=out, chunk_size=1, **kw)
    # the chunks kept were not run again
    assert all((parts / n).stat().st_mtime_ns == s for n, s in stamps.items())
    assert len(list(parts.glob("chunk-*.npy"))) == 48
    return p, axes, again, len(kept)


def test_an_interrupted_sweep_keeps_what_finished_and_resumes(tmp_path):
    need("pandas")
    p, axes, again, _ = interrupted_then_resumed(tmp_path, "serial", threads=1)
    assert again.to_numpy().tobytes() == autobal.sweep(p, axes).to_numpy().tobytes()


def test_dask_local_cluster_equals_the_serial_sweep_and_resumes(tmp_path):
    need("dask")
    distributed = need("distributed")
    axes = {"planar.c_psi": [0.05, 0.1, 0.15, 0.2, 0.25], "drive.b": [80.0, 100.0, 120.0]}
    serial = autobal.sweep(short(), axes)
    with distributed.LocalCluster(n_workers=3, threads_per_worker=1, processes=True, dashboard_address=None) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 3
        got = autobal.sweep(short(), axes, client=client, chunk_size=2, out=tmp_path / "d.csv")
        # interrupted on the cluster, resumed on it: the chunks kept are not run again
        p, big_axes, again, kept = interrupted_then_resumed(tmp_path, "dask", client=client)
    assert got.to_numpy().tobytes() == serial.to_numpy().tobytes()
    assert len(list((tmp_path / "d.parts").glob("chunk-*.npy"))) == 8
    assert again.to_numpy().tobytes() == autobal.sweep(p, big_axes).to_numpy().tobytes()


def test_cli_parquet_equals_its_csv_and_merged_shards_equal_the_sweep(tmp_path):
    """`--parquet` of simulate, sweep and merge, read back by pandas (pyarrow) and polars: the
    same numbers as the CSV beside it, bit for bit; merged shards equal the unsharded sweep."""
    pd = need("pandas")
    need("pyarrow")
    pl = need("polars")

    def same(parquet, csv):
        a = pd.read_parquet(parquet, engine="pyarrow")
        b = pd.read_csv(csv, float_precision="round_trip")
        assert list(a.columns) == list(b.columns)
        assert a.to_numpy(dtype=float).tobytes() == b.to_numpy(dtype=float).tobytes()
        assert pl.read_parquet(parquet).columns == list(b.columns)
        return a

    sets = ["--set", "drive.t_end=1", "--set", "drive.omega0=250", "--set", "drive.b=100"]
    cli("simulate", "--out", str(tmp_path / "s.csv"), "--parquet", "--dt", "0.001", *sets)
    s = same(tmp_path / "s.parquet", tmp_path / "s.csv")
    assert len(s) == 1001 and list(s.columns)[-2:] == ["psi_1", "psi_2"]
    grid = ["--x", "planar.c_psi=0.05:0.15:3", "--y", "drive.b=80,120", "--axis", "drive.psi0[1]=1,2"]
    cli("sweep", "--out", str(tmp_path / "all"), "--parquet", *grid, *sets)
    whole = same(tmp_path / "all.parquet", tmp_path / "all.csv")
    assert str(whole["point"].dtype) == "int64" and "drive.psi0[1]" in whole.columns
    for k in (1, 2, 3):
        cli("sweep", "--out", str(tmp_path / f"part{k}"), "--shard", f"{k}/3", *grid, *sets)
    exe = os.environ.get("AUTOBAL_BIN", str(ROOT / "target" / "debug" / "autobal"))
    subprocess.run([exe, "merge", *(str(tmp_path / f"part{k}.csv") for k in (3, 1, 2)), "--out", str(tmp_path / "merged"), "--parquet"], check=True, capture_output=True)
    merged = same(tmp_path / "merged.parquet", tmp_path / "merged.csv")
    assert merged.drop(columns="wall_s").equals(whole.drop(columns="wall_s"))


def test_stability_map_equals_the_cli_map(tmp_path):
    """`SpatialModel.stability_map` and `autobal map` on the same config: the same cells, bit
    for bit (margin, verdict, necessary ranges), in the CSV's order (rows at y, x fastest)."""
    exe = os.environ.get("AUTOBAL_BIN", str(ROOT / "target" / "debug" / "autobal"))
    dim = str(ROOT / "examples" / "default.toml")
    for x, y, extra in (("dimensionless.z_a=-2:2:9", "omega=0.05:4.5:7", {}), ("dimensionless.l_left=0.5:1.2:4", "dimensionless.z_a=-1:1:3", {"omega": 2.0})):
        args = [exe, "map", "--config", dim, "--x", x, "--y", y, "--out", str(tmp_path / "m")]
        if extra:
            args += ["--omega", str(extra["omega"])]
        subprocess.run(args, check=True, capture_output=True)
        got = autobal.SpatialModel.from_toml(dim).stability_map(x, y, **extra)
        rows = [line.split(",") for line in (tmp_path / "m.csv").read_text().splitlines()[1:]]
        assert got["margin"].shape == (len(got["y"]), len(got["x"])) and len(rows) == got["margin"].size
        assert [float(r[0]) for r in rows[: len(got["x"])]] == got["x"].tolist()
        assert [float(r[2]) for r in rows] == got["margin"].ravel().tolist()
        assert [r[3] == "1" for r in rows] == got["stable"].ravel().tolist()
        assert [r[4] == "1" for r in rows] == got["necessary"].ravel().tolist()
        if not extra:
            assert got["stable"].any() and not got["stable"].all()
        via_run = autobal.run("map", config=dim, x=x, y=y, **extra)
        assert via_run["margin"].tobytes() == got["margin"].tobytes() and (via_run["stable"] == got["stable"]).all()
    with pytest.raises(InvalidParameter) as e:
        autobal.SpatialModel().stability_map("dimensionless.z_a=-2:2:3", "dimensionless.l_left=0.5:1:3")
    assert e.value.field == "omega"
    # the per-tau margins' omega0 on an SI config (audit 25's F6): sqrt((c_L + c_R) / M_s),
    # M_s = rotor + unbalance + balls from the file's own entries; None on a dimensionless one
    si = str(ROOT / "examples" / "dimensional.toml")
    m = autobal.run("map", config=si, x="balancer.z=0.3:0.45:2", y="omega=0.5:3:2")
    cfg = tomllib_load(si)
    m_s = cfg["rotor"]["mass"] + cfg["unbalance"]["mass"] + cfg["balancer"]["balls"] * cfg["balancer"]["ball_mass"]
    want = ((cfg["supports"]["stiffness_left"] + cfg["supports"]["stiffness_right"]) / m_s) ** 0.5
    assert m["omega0_rad_s"] == pytest.approx(want, rel=1e-12) and m["omega0_range_rad_s"] == [m["omega0_rad_s"]] * 2
    assert autobal.run("map", config=dim, x="dimensionless.z_a=-2:2:3", y="omega=0.5:3:2")["omega0_rad_s"] is None



def test_a_design_map_at_an_si_speed_is_the_cli_map(tmp_path):
    """`autobal.run("map", omega="6000rpm")` over two axes that move omega0 (a ball mass, a
    stiffness): every cell at its own Omega, as the CLI maps it (the same CSV cells, bit for
    bit), and the key `fixed_speed` names the speed; over axes that do not move omega0 it is
    None (one Omega for the whole map)."""
    exe = os.environ.get("AUTOBAL_BIN", str(ROOT / "target" / "debug" / "autobal"))
    si = str(ROOT / "examples" / "dimensional.toml")
    x, y = "balancer.ball_mass=0.01:0.05:6", "supports.stiffness_left=1e6:4e6:5"
    subprocess.run([exe, "map", "--config", si, "--x", x, "--y", y, "--omega", "6000rpm", "--out", str(tmp_path / "d")], check=True, capture_output=True)
    rows = [line.split(",") for line in (tmp_path / "d.csv").read_text().splitlines()[1:]]
    got = autobal.run("map", config=si, x=x, y=y, omega="6000rpm")
    assert got["fixed_speed"] == "6000 rpm"
    assert [float(r[2]) for r in rows] == got["margin"].ravel().tolist()
    assert [r[3] == "1" for r in rows] == got["stable"].ravel().tolist()
    assert got["stable"].any() and not got["stable"].all()
    assert autobal.run("map", config=si, x="balancer.drag=0.5:3:2", y="balancer.z=0.3:0.45:2", omega="6000rpm")["fixed_speed"] is None


def test_a_design_maps_boundary_at_an_si_speed_is_refused_before_any_cell():
    """`analyse("map", omega="6000rpm", boundary=True)` over axes that move omega0 (each cell at
    its own Omega: no plane to trace): computed every cell, then failed on `.plot()` with the
    CLI's `--route general`, `--omega` (session 29). Now `analyse` itself raises
    `InvalidParameter` on `boundary`, the options named as Python calls them, as the CLI
    refuses `--boundary` (its words, its flag). Over axes that keep omega0 it is taken."""
    si = str(ROOT / "examples" / "dimensional.toml")
    x, y = "balancer.ball_mass=0.01:0.05:3", "supports.stiffness_left=1e6:4e6:2"
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.analyse("map", config=si, x=x, y=y, omega="6000rpm", boundary=True)
    assert e.value.field == "boundary"
    words = "at a fixed speed in SI over axes that move ω0 (each cell at its own Ω) the boundary is not traced; use route general (its boundary is bisected between cells), or give omega as Ω"
    assert str(e.value) == "boundary: " + words
    exe = os.environ.get("AUTOBAL_BIN", str(ROOT / "target" / "debug" / "autobal"))
    out = subprocess.run([exe, "map", "--config", si, "--x", x, "--y", y, "--omega", "6000rpm", "--boundary", "--out", "unused"], capture_output=True, text=True)
    assert out.returncode == 2 and out.stderr.strip() == "error: --boundary: " + words, out.stderr
    # without boundary, or over axes that keep omega0, the map is taken
    assert autobal.analyse("map", config=si, x=x, y=y, omega="6000rpm").result["fixed_speed"] == "6000 rpm"
    r = autobal.analyse("map", config=si, x="balancer.drag=0.5:3:2", y="balancer.z=0.3:0.45:2", omega="6000rpm", boundary=True)
    assert r.result["fixed_speed"] is None


def tomllib_load(path):
    """The numbers of a flat TOML file (`[section]`, `key = number  # comment`) as nested dicts:
    enough for the examples' entries, without tomllib (Python 3.11+)."""
    out, sec = {}, None
    for line in open(path, encoding="utf-8"):
        line = line.split("#", 1)[0].strip()
        if line.startswith("[") and line.endswith("]"):
            sec = out.setdefault(line[1:-1], {})
        elif "=" in line and sec is not None:
            k, v = (t.strip() for t in line.split("=", 1))
            try:
                sec[k] = float(v)
            except ValueError:
                pass
    return out


def test_the_readme_session_runs_as_printed(tmp_path, monkeypatch):
    """The README's Python session, line by line with its printed results (doctest), in a fresh
    folder that has the repository's examples/: what a new user types after installing."""
    import doctest

    need("pandas")
    need("pyarrow")
    text = (ROOT / "README.md").read_text()
    session = text.split("## Python", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    monkeypatch.chdir(tmp_path)
    test = doctest.DocTestParser().get_doctest(session, {}, "README.md", "README.md", 0)
    assert len(test.examples) >= 8
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    runner.run(test)
    assert runner.failures == 0
    assert (tmp_path / "sweep.parquet").exists()
