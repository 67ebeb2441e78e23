"""The wheel as a whole front end (issue 20 §3, §6): the `autobal` command it installs, every
command's JSON equal to the CLI's, the figures of the result objects equal to the report's, the
report from Python equal to the CLI's, and the stubs equal to the module.

The CLI comparisons need the `autobal` binary cargo built: $AUTOBAL_BIN, else target/debug/autobal.
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import autobal
from _cli import binary

ROOT = Path(__file__).resolve().parents[3]
REQUIRE = bool(os.environ.get("AUTOBAL_REQUIRE_PYTHON"))


def need(module: str):
    try:
        return __import__(module)
    except ImportError:
        if REQUIRE:
            raise
        pytest.skip(f"needs {module} (pip install -r requirements-test.txt)")


def script() -> str:
    """The console script the wheel installed beside this Python."""
    exe = Path(sys.executable).parent / "autobal"
    assert exe.exists(), f"{exe}: the wheel installs the autobal command ([project.scripts])"
    return str(exe)


def run(exe: str, *args: str, cwd=None) -> subprocess.CompletedProcess:
    return subprocess.run([exe, *args], capture_output=True, text=True, cwd=cwd or os.environ.get("TMPDIR", "/tmp"))


@pytest.mark.parametrize(
    "args",
    [
        ("critical",),
        ("critical", "--format", "json", "--set", "dimensionless.l_left=1.2"),
        ("--version",),
        ("stability", "--omega-max", "nope"),
        ("frobnicate",),
    ],
)
def test_the_installed_command_is_the_clis(args):
    # the same stdout, stderr and exit code as the binary cargo built (errors and usage included)
    a, b = run(script(), *args), run(binary(), *args)
    assert (a.returncode, a.stdout, a.stderr) == (b.returncode, b.stdout, b.stderr)


def cli_json(*args: str) -> dict:
    out = run(binary(), *args, "--format", "json")
    assert out.returncode == 0, out.stderr
    return json.loads(out.stdout)


def without_walls(d):
    """`d` without the wall times (they differ between runs) at any depth."""
    if isinstance(d, dict):
        return {k: without_walls(v) for k, v in d.items() if not k.startswith("wall")}
    if isinstance(d, list):
        return [without_walls(v) for v in d]
    return d


def setargs(sets: dict) -> list:
    return [a for k, v in sets.items() for a in ("--set", f"{k}={v}")]


EX = ROOT / "examples"
SPATIAL = str(EX / "spatial.toml")
SHORT_PLANAR = {"drive.t_end": 1.0, "drive.omega0": 250.0, "drive.b": 100.0}
GRID = {"x": "planar.c_psi=0.05:0.15:3", "y": "drive.b=80,120"}


def case_linear(command):
    def check(tmp_path):
        dim = str(EX / "dimensional.toml")
        assert autobal.run(command) == cli_json(command)
        assert autobal.run(command, config=dim) == cli_json(command, "--config", dim)
        assert autobal.analyse(command, config=dim).result == cli_json(command, "--config", dim)

    return check


def test_the_general_route_from_python_equals_the_clis():
    # a config the 12-state model does not represent (two planes, couple unbalance, supports
    # that differ by direction, gravity): stability, campbell and critical take the general
    # route from Python as the CLI does (the same commands-crate functions)
    two = str(EX / "spatial_two_plane.toml")
    got = autobal.run("stability", config=two, omega_max=1.5, samples=10)
    assert got["route"] == "general"
    assert without_walls(got) == without_walls(cli_json("stability", "--config", two, "--omega-max", "1.5", "--samples", "10"))
    got = autobal.run("campbell", config=two, omega_max=1.5, points=3)
    assert got["route"] == "general"
    assert without_walls(got) == without_walls(cli_json("campbell", "--config", two, "--omega-max", "1.5", "--points", "3"))
    dim = str(EX / "dimensional.toml")
    sets = {"rotor.axis_tilt": 0.01}
    got = autobal.run("critical", config=dim, set=sets)
    assert got["route"] == "general"
    assert without_walls(got) == without_walls(cli_json("critical", "--config", dim, *setargs(sets)))


def test_options_are_checked_once_and_named_as_keywords():
    # one check of `samples` for both routes (the commands crate's Args), the CLI's message with
    # the flag shown as Python's keyword
    for config in (None, str(EX / "spatial_two_plane.toml")):
        with pytest.raises(autobal.errors.InvalidParameter) as e:
            autobal.run("stability", config=config, samples=3)
        assert e.value.field == "samples" and str(e.value) == "samples: must lie between 10 and 1000000, got 3"
    with pytest.raises(autobal.errors.InvalidParameter) as e:
        autobal.run("stability", route="sideways")
    assert e.value.field == "route"


def test_general_route_results_tabulate():
    pd = need("pandas")
    two = str(EX / "spatial_two_plane.toml")
    r = autobal.analyse("stability", config=two, omega_max=1.5, samples=10)
    assert r.result["route"] == "general"
    df = r.to_pandas()
    assert list(df.columns) == ["omega", "max_real_part", "verdict", "state", "residual"] and len(df) == 10
    # the table and the ranges are the same result: every speed the table calls stable lies in
    # a stable range, and every speed in the table has its margin or says why not
    stable = df[df.verdict == "stable"]
    assert all(any(s["from"] <= w <= s["to"] for s in r.result["stable_ranges"]) for w in stable.omega)
    assert len(stable) == 0 or (stable.max_real_part < 0).all()
    c = autobal.analyse("campbell", config=two, omega_max=1.5, points=3)
    dfc = c.to_pandas()
    assert len(dfc) == sum(p is not None for line in c.result["lines"] for p in line["points"]) > 0
    assert set(dfc.omega) <= set(c.result["omega"])
    crit = autobal.analyse("critical", config=str(EX / "dimensional.toml"), set={"rotor.axis_tilt": 0.01})
    assert crit.result["route"] == "general"
    assert list(crit.to_pandas().omega) == [s["omega"] for s in crit.result["locked_critical_speeds"]["speeds"]]
    rg = autobal.analyse("ranges", config=str(EX / "planar.toml")).to_pandas()
    assert list(rg.kind.unique()) == ["exact_stable_ranges"]
    assert len(rg) == len(autobal.run("ranges", config=str(EX / "planar.toml"))["exact"]["stable_ranges"]) > 0


def case_stability(tmp_path):
    assert autobal.run("stability", omega_max=4.0, samples=200) == cli_json("stability", "--omega-max", "4", "--samples", "200")
    dim = str(EX / "washing_machine.toml")
    assert autobal.analyse("stability", config=dim).result == cli_json("stability", "--config", dim)


def case_campbell(tmp_path):
    assert autobal.analyse("campbell", points=20, omega_max=3.0).result == cli_json("campbell", "--points", "20", "--omega-max", "3")


def case_map(tmp_path):
    # the CLI writes the map as CSV (no JSON): the same cells, bit for bit
    x, y = "dimensionless.z_a=-2:2:9", "omega=0.05:4.5:7"
    out = run(binary(), "map", "--x", x, "--y", y, "--out", str(tmp_path / "m"))
    assert out.returncode == 0, out.stderr
    df = autobal.analyse("map", x=x, y=y).to_pandas()
    rows = [line.split(",") for line in (tmp_path / "m.csv").read_text().splitlines()]
    assert rows[0] == list(df.columns)
    assert [[float(v) for v in r] for r in rows[1:]] == df.astype(float).values.tolist()
    # a dimensional config's margin is per τ: the CSV names it so (session 22), and so does the
    # table Python gives (it read max_real_part)
    dim = str(EX / "dimensional.toml")
    x, y = "omega=0.2:3:5", "balancer.ball_mass=0.01:0.05:3"
    out = run(binary(), "map", "--config", dim, "--x", x, "--y", y, "--out", str(tmp_path / "d"))
    assert out.returncode == 0, out.stderr
    df = autobal.analyse("map", config=dim, x=x, y=y).to_pandas()
    rows = [line.split(",") for line in (tmp_path / "d.csv").read_text().splitlines()]
    assert rows[0] == list(df.columns) and "max_real_part_per_tau" in rows[0]
    assert [[float(v) for v in r] for r in rows[1:]] == df.astype(float).values.tolist()


def case_simulate(tmp_path):
    got = autobal.analyse("simulate", set=SHORT_PLANAR)
    want = cli_json("simulate", "--out", str(tmp_path / "s.csv"), *setargs(SHORT_PLANAR))
    assert without_walls(got.result) == without_walls(want) == without_walls(autobal.run("simulate", set=SHORT_PLANAR))
    csv = (tmp_path / "s.csv").read_text().splitlines()
    df = got.to_pandas()
    assert csv[0].split(",") == list(df.columns) and len(csv) - 1 == len(df)


def case_sweep(tmp_path):
    got = autobal.run("sweep", set=SHORT_PLANAR, **GRID)
    want = cli_json("sweep", "--out", str(tmp_path / "sw"), "--x", GRID["x"], "--y", GRID["y"], *setargs(SHORT_PLANAR))
    assert without_walls(got) == without_walls(want)
    assert len(autobal.analyse("sweep", set=SHORT_PLANAR, **GRID).to_pandas()) == 6


def case_merge(tmp_path):
    # merge joins the shards of a sweep: its JSON is the unsharded sweep's, which run gives
    for k in (1, 2):
        r = run(binary(), "sweep", "--out", str(tmp_path / f"p{k}"), "--shard", f"{k}/2", "--x", GRID["x"], "--y", GRID["y"], *setargs(SHORT_PLANAR))
        assert r.returncode == 0, r.stderr
    shards = [str(tmp_path / "p2.csv"), str(tmp_path / "p1.csv")]
    r = run(binary(), "merge", *shards, "--out", str(tmp_path / "merged"))
    assert r.returncode == 0, r.stderr
    merged = json.loads((tmp_path / "merged.json").read_text())
    # bit for bit: merge reads the shards' JSON back with serde_json's correctly rounded parser
    # (feature float_roundtrip; the default one once missed by 1 ulp: 0.0019022483945061678 in
    # the shard, 0.001902248394506168 in merged.json)
    assert without_walls(merged) == without_walls(autobal.run("sweep", set=SHORT_PLANAR, **GRID))
    # Python's merge of the same shards: the CLI's JSON, wall times included (they are the
    # shards'), and the same files byte for byte; run and analyse give the same
    got = autobal.merge(shards, out=tmp_path / "py")
    assert got.result == merged == autobal.run("merge", shards=shards, out=str(tmp_path / "run"))
    assert got.files == [tmp_path / "py.csv", tmp_path / "py.json"]
    for ext in ("csv", "json"):
        assert (tmp_path / f"py.{ext}").read_bytes() == (tmp_path / f"merged.{ext}").read_bytes(), ext
    assert autobal.analyse("merge", shards=shards, out=str(tmp_path / "an")).result == merged
    df = got.to_pandas()
    assert list(df.point) == list(range(6)) and len((tmp_path / "py.csv").read_text().splitlines()) == 7
    pq = autobal.merge(shards, out=tmp_path / "pq", parquet=True)
    assert pq.files == [tmp_path / "pq.csv", tmp_path / "pq.json", tmp_path / "pq.parquet"] and pq.files[-1].stat().st_size > 0
    # the CLI's checks and messages: a shard given twice (nothing written), no shards
    with pytest.raises(autobal.AutobalError, match=r"^shard 2 of 2 is given twice"):
        autobal.merge([shards[0], shards[0]], out=tmp_path / "twice")
    assert not (tmp_path / "twice.csv").exists()
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.merge([], out=tmp_path / "none")
    assert e.value.field == "shards"
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.run("merge", config=SPATIAL, shards=shards, out=str(tmp_path / "x"))
    assert e.value.field == "config"


def case_basins(tmp_path):
    sets = {"drive.t_end": 50.0}
    got = autobal.analyse("basins", config=SPATIAL, set=sets, n=3)
    want = cli_json("basins", "--config", SPATIAL, "--n", "3", "--out", str(tmp_path / "b.csv"), *setargs(sets))
    assert without_walls(got.result) == {k: v for k, v in without_walls(want).items() if k not in ("csv", "svg")}
    csv = (tmp_path / "b.csv").read_text().splitlines()
    assert csv[0].split(",") == list(got.to_pandas().columns) and len(csv) == 10


def case_report(tmp_path):
    # the report from Python equals the CLI's, file by file (but for the wall times on the page)
    cfg = str(EX / "washing_machine.toml")
    r = run(binary(), "report", "--config", cfg, "--quick", "--out", str(tmp_path / "cli"))
    assert r.returncode == 0, r.stderr
    rep = autobal.report(cfg, out=tmp_path / "py", quick=True)
    assert rep.path == tmp_path / "py" / "index.html"
    names = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "py").iterdir()) and len(names) > 20
    # the wall times: the page's "computed in N s", the run-up's "N right-hand sides, N s", the
    # basins' "(N s here)"
    timed = re.compile(r"(computed in |right-hand sides, |\()[0-9.]+ s")
    for name in names:
        a, b = (tmp_path / "cli" / name).read_bytes(), (tmp_path / "py" / name).read_bytes()
        if name == "index.html":
            a, b = (timed.sub("", x.decode()) for x in (a, b))
        assert a == b, name


def case_export_model(tmp_path):
    # export-model prints the files it wrote: the wheel's `autobal` writes the binary's, byte
    # for byte, and so do autobal.export_model and run("export-model"), whose {"files"} are the
    # paths the CLI printed; Python reads them back (scipy.io.mmread) into a LinearRotor whose
    # undamped natural frequencies are NumPy's sqrt(eig(M⁻¹ K)) of the same matrices
    printed = {}
    for exe, d in ((binary(), "cli"), (script(), "py")):
        r = run(exe, "export-model", "--out", str(tmp_path / d))
        assert r.returncode == 0, r.stderr
        printed[d] = r.stdout
    names = sorted(p.name for p in (tmp_path / "cli").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "py").iterdir()) and len(names) == 5
    got = autobal.export_model(out=tmp_path / "fn")
    ran = autobal.run("export-model", out=str(tmp_path / "py"))
    assert printed["py"] == "wrote " + ", ".join(ran["files"]) + "\n"
    assert got.files == [tmp_path / "fn" / f for f in ("rotor.toml", "rotor_M.mtx", "rotor_C.mtx", "rotor_G.mtx", "rotor_K.mtx")]
    assert got.result == {"files": [str(p) for p in got.files]}
    for name in names:
        for d in ("py", "fn"):
            assert (tmp_path / "cli" / name).read_bytes() == (tmp_path / d / name).read_bytes(), (d, name)
    # a config with --set and --stem: the same files as the CLI's
    cfg = tmp_path / "fn" / "rotor.toml"
    r = run(binary(), "export-model", "--config", str(cfg), "--set", "linear_rotor.polar_inertia=0.5", "--out", str(tmp_path / "c2"), "--stem", "s")
    assert r.returncode == 0, r.stderr
    again = autobal.analyse("export-model", config=cfg, set={"linear_rotor.polar_inertia": 0.5}, out=tmp_path / "p2", stem="s")
    assert [p.name for p in again.files] == ["s.toml", "s_M.mtx", "s_C.mtx", "s_G.mtx", "s_K.mtx"]
    for p in again.files:
        assert p.read_bytes() == (tmp_path / "c2" / p.name).read_bytes(), p.name
    with pytest.raises(autobal.AutobalError, match=r'^stem "a/b": a file name stem without a folder'):
        autobal.export_model(out=tmp_path / "never", stem="a/b")
    assert not (tmp_path / "never").exists()
    # errors as for the other commands: a missing config file, --set without a config
    with pytest.raises(FileNotFoundError, match="nope.toml"):
        autobal.export_model(config=tmp_path / "nope.toml", out=tmp_path / "never")
    with pytest.raises(autobal.InvalidParameter) as e:
        autobal.run("export-model", set={"linear_rotor.polar_inertia": 0.5}, out=str(tmp_path / "never"))
    assert e.value.field == "set" and not (tmp_path / "never").exists()
    with pytest.raises(TypeError, match="no table"):
        got.to_pandas()
    mmread = pytest.importorskip("scipy.io").mmread

    def dense(x: str) -> np.ndarray:
        a = mmread(str(tmp_path / "py" / f"rotor_{x}.mtx"))
        return np.asarray(a.todense() if hasattr(a, "todense") else a, dtype=float)

    m, c, g, k = (dense(x) for x in "MCGK")
    # paper 004's rotor as a Jeffcott rotor: one node with x and y only
    f = np.sort(autobal.LinearRotor(m, c, g, k, per_node=2).natural_frequencies())
    want = np.sort(np.sqrt(np.linalg.eigvals(np.linalg.solve(m, k)).real))
    assert np.allclose(f, want, rtol=1e-12, atol=0), (f, want)
    # the stiffness turned indefinite: ω² = −k/m exactly, refused by natural_frequencies (it
    # read 0 rad/s), given with its sign by natural_frequencies_squared, in the CLI's words
    neg = autobal.LinearRotor(m, c, g, -k, per_node=2)
    sq = np.sort(neg.natural_frequencies_squared())
    want_sq = np.sort(-np.linalg.eigvals(np.linalg.solve(m, k)).real)
    assert np.allclose(sq, want_sq, rtol=1e-12, atol=0) and (sq < 0).all(), (sq, want_sq)
    with pytest.raises(ValueError, match="statically unstable at rest: 2 mode") as e:
        neg.natural_frequencies()
    assert e.value.field == "k"


def case_ranges(tmp_path):
    case_linear("ranges")(tmp_path)
    # a planar config: the exact ranges of the general route, 003's not defined, as the CLI
    planar = str(EX / "planar.toml")
    got = autobal.run("ranges", config=planar)
    assert got["autobalancing_ranges"] is None and got["exact"]["route"] == "general"
    assert without_walls(got) == without_walls(cli_json("ranges", "--config", planar))


CASES = {
    "inertia": case_linear("inertia"),
    "critical": case_linear("critical"),
    "ranges": case_ranges,
    "stability": case_stability,
    "campbell": case_campbell,
    "map": case_map,
    "simulate": case_simulate,
    "sweep": case_sweep,
    "merge": case_merge,
    "basins": case_basins,
    "report": case_report,
    "export-model": case_export_model,
}


@pytest.mark.parametrize("command", autobal.COMMANDS)
def test_every_command_from_python_equals_the_cli(command, tmp_path):
    """Every command of the CLI (the list from its argument parser, not kept here): Python's
    result equals the CLI's output. A new command fails here until its case is written."""
    need("pandas")
    assert command in CASES, f"{command}: a new command of the CLI; add its comparison to CASES"
    CASES[command](tmp_path)


def traces(fig) -> list:
    """A plotly Figure's traces as JSON (what the page's Plotly draws)."""
    return json.loads(fig.to_json())["data"]


# figures the report draws that no command draws (the rotor's response, the design maps with the
# speed in rpm, the basins): they come out of the Report's .plot() only
REPORT_ONLY = re.compile(r"^(rotor_response|design_.*|basins)$")


def test_every_figure_of_the_report_comes_out_of_plot(tmp_path):
    need("plotly")
    cfg = str(EX / "washing_machine.toml")
    rep = autobal.report(cfg, out=tmp_path / "r")
    page = rep.figures()
    assert len(page) >= 10 and "stability_margin" in page
    # every figure of the page, as a plotly Figure with the page's own traces
    for fid, fig in page.items():
        assert traces(rep.plot(fid)) == fig["data"], fid
    # the figures the commands draw (the same descriptions, the report's options) are the
    # report's, trace by trace
    from_commands = {}
    for r in (autobal.analyse("stability", cfg), autobal.analyse("campbell", cfg, points=240), autobal.analyse("simulate", cfg)):
        from_commands.update({fid: r.plot(fid) for fid in r.figures()})
    # the run-up's figures: `simulate`'s (the report adds the rpm axis on top, drawn by an
    # invisible trace on the axis x2, to its speed axis: left out of the comparison)
    rename = {f"simulation_{s}": f"spatial_run_{s}" for s in ("amplitude_omega", "amplitude_t", "psi_t")}
    for fid, fig in from_commands.items():
        fid = rename.get(fid, fid)
        if fid in page:
            got = [t for t in traces(fig) if t.get("xaxis") != "x2"]
            want = [t for t in page[fid]["data"] if t.get("xaxis") != "x2"]
            assert got == want and got, fid
    covered = {rename.get(f, f) for f in from_commands}
    missing = [f for f in page if f not in covered and not REPORT_ONLY.match(f)]
    assert not missing, f"figures of the report that no command's .plot() gives: {missing}"


def test_results_plot_and_tabulate():
    pd = need("pandas")
    need("plotly")
    r = autobal.analyse("stability", samples=100)
    assert r.result == autobal.run("stability", samples=100)
    fig = r.plot()
    assert fig.layout.title.text and len(fig.data) >= 1
    df = r.to_pandas()
    assert isinstance(df, pd.DataFrame) and list(df.columns) == ["omega", "max_real_part"]
    html_ = r._repr_html_()
    assert "<table>" in html_ and "plotly" in html_.lower()
    c = autobal.analyse("campbell", points=20)
    assert set(c.figures()) == {"campbell_modes", "campbell_fixed", "campbell_rotating"}
    assert len(c.to_pandas()) == 20 * len(c.result["lines"])
    m = autobal.analyse("map", x="dimensionless.z_a=-2:2:5", y="omega=0.1:4.5:4")
    assert m.plot().data[0].type == "heatmap" and len(m.to_pandas()) == 20
    crit = autobal.analyse("critical")
    assert len(crit.to_pandas()) == 4 and "<table>" in crit._repr_html_()
    with pytest.raises(ValueError, match="draws no figure"):
        crit.plot()
    with pytest.raises(TypeError, match="no table"):
        autobal.analyse("inertia").to_pandas()
    with pytest.raises(KeyError, match="not a figure"):
        r.plot("nope")
    with pytest.raises(autobal.AutobalError, match="samples"):
        autobal.analyse("stability", samples=3).plot()
    with pytest.raises(TypeError, match="TOML file"):
        autobal.report({"dimensionless": {}}, out="never-written")
    with pytest.raises(TypeError, match="TOML file"):
        autobal.analyse("report", {"dimensionless": {}}, out="never-written")


def test_the_stubs_are_the_module():
    """Every public name of the extension module is in its stub, and every name of the stub is
    in the module."""
    import ast

    stub = Path(autobal.__file__).with_name("_autobal.pyi")
    tree = ast.parse(stub.read_text())
    names = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            names.add(node.name)
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            names.add(node.target.id)
    public = {n for n in dir(autobal._autobal) if not n.startswith("_")} | {"__version__"}
    assert names == public, f"only in the module: {sorted(public - names)}; only in the stub: {sorted(names - public)}"
    # and each class's public members
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            members = {n.name for n in node.body if isinstance(n, ast.FunctionDef) and not n.name.startswith("_")}
            real = {n for n in dir(getattr(autobal._autobal, node.name)) if not n.startswith("_")}
            assert members == real, node.name


def test_report_and_figures_stop_on_ctrl_c(tmp_path):
    """Ctrl-C during `autobal.report` stops it in order, as it stops the CLI's: KeyboardInterrupt,
    the page written and marked incomplete, no later than the CLI stops (measured here the same
    way; the design maps finish their current map first: about 7 s); a map's figures stop within
    seconds; the next call runs normally (the stop flags are cleared)."""
    import _thread
    import signal
    import threading
    import time

    cfg = str(EX / "washing_machine.toml")
    p = subprocess.Popen([binary(), "report", "--config", cfg, "--out", str(tmp_path / "cli")], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(1.0)
    t0 = time.perf_counter()
    p.send_signal(signal.SIGINT)
    assert p.wait() == 2
    cli_stop = time.perf_counter() - t0
    for work, bound in (
        (lambda: autobal.report(cfg, out=tmp_path / "r"), cli_stop + 3.0),
        (lambda: autobal.analyse("map", x="dimensionless.z_a=-2:2:1500", y="omega=0.05:4.5:8000").figures(), 5.0),
    ):
        ctrl_c = threading.Timer(1.0, _thread.interrupt_main)
        ctrl_c.start()
        t0 = time.perf_counter()
        try:
            with pytest.raises(KeyboardInterrupt):
                work()
        finally:
            ctrl_c.cancel()
        stopped = time.perf_counter() - t0 - 1.0
        assert stopped < bound, f"took {stopped:.1f} s to stop (the CLI's report: {cli_stop:.1f} s)"
    for d in ("cli", "r"):
        assert 'id="interrupted"' in (tmp_path / d / "index.html").read_text()
    assert list(autobal.analyse("stability", samples=50).figures()) == ["stability_margin"]


def test_a_notebook_of_results_renders_in_a_browser(tmp_path):
    """A notebook whose cells end in results, with the outputs Jupyter makes of them (the rich
    display, `_repr_html_`, beside the text), rendered to HTML by nbconvert and opened in
    headless Chromium: every figure drawn by the embedded plotly.js (offline), with its traces,
    beside the summary tables. Chromium: $AUTOBAL_CHROMIUM, else /usr/bin/chromium (required
    when AUTOBAL_REQUIRE_BROWSER is set, as for the report's browser test)."""
    nbformat = need("nbformat")
    need("nbconvert")
    need("plotly")
    from nbconvert import HTMLExporter

    chromium = os.environ.get("AUTOBAL_CHROMIUM", "/usr/bin/chromium")
    if not Path(chromium).exists():
        if os.environ.get("AUTOBAL_REQUIRE_BROWSER"):
            raise FileNotFoundError(f"{chromium}: install Chromium (sudo apt-get install chromium)")
        pytest.skip("needs Chromium (sudo apt-get install chromium)")
    # a notebook is a session of its own: its first figure brings plotly.js
    import autobal._results

    autobal._results._PLOTLYJS_SENT = False
    sources = [
        'autobal.analyse("stability", samples=100)',
        'autobal.analyse("campbell", points=30)',
        'autobal.analyse("critical")',
    ]
    cells, figures = [nbformat.v4.new_code_cell("import autobal")], []
    for k, src in enumerate(sources):
        r = eval(src, {"autobal": autobal})
        out = nbformat.v4.new_output("execute_result", data={"text/html": r._repr_html_(), "text/plain": repr(r)}, execution_count=k + 2)
        cells.append(nbformat.v4.new_code_cell(src, outputs=[out], execution_count=k + 2))
        if r.command in autobal.COMMANDS_WITH_FIGURES:
            figures.append(r.plot())
    page, _ = HTMLExporter().from_notebook_node(nbformat.v4.new_notebook(cells=cells))
    path = tmp_path / "results.html"
    path.write_text(page, encoding="utf-8")
    dom = subprocess.run(
        [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--virtual-time-budget=15000", "--dump-dom", path.as_uri()],
        capture_output=True, text=True, timeout=120,
    ).stdout
    # plotly.js marks each figure it drew, and draws each scatter trace with a point as a group
    # of its own (a trace without one, e.g. a mode's component that never carries 10 % of its
    # motion, draws nothing)
    assert dom.count('class="plot-container plotly"') == len(figures), "a figure was not drawn"
    want = sum(1 for f in figures for t in f.data if t.type == "scatter" and any(x is not None and y is not None for x, y in zip(t.x or (), t.y or ())))
    assert want > 20
    assert len(re.findall(r'class="trace scatter trace[0-9a-f]+"', dom)) == want
    # the summary tables: the results' numbers, in the page as drawn
    for k in ("autobal critical", "rotor_type", "antiresonance_speed", "autobal stability", "balanced_state_exists", "autobal campbell"):
        assert k in dom, k


def test_the_stubs_pass_mypy_stubtest():
    """mypy's stubtest: every name, signature (parameter names, kinds, defaults), class and
    `__all__` of the stub against the compiled module."""
    need("mypy")
    out = subprocess.run([sys.executable, "-m", "mypy.stubtest", "autobal._autobal"], capture_output=True, text=True, cwd=os.environ.get("TMPDIR", "/tmp"), timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr


def test_the_package_passes_mypy(tmp_path):
    """mypy on the package's Python source (``crates/autobal-py/python/autobal``, typed against
    the stubs ``_autobal.pyi``), with the settings of ``crates/autobal-py/pyproject.toml``
    (the optional pandas, plotly and dask used untyped): no error."""
    need("mypy")
    pkg = Path(__file__).resolve().parents[1]
    cmd = [sys.executable, "-m", "mypy", "--config-file", str(pkg / "pyproject.toml"), "--cache-dir", str(tmp_path / "mypy-cache"), str(pkg / "python" / "autobal")]
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=pkg, timeout=300)
    assert out.returncode == 0, out.stdout + out.stderr


def test_plot_figures_have_no_empty_or_unnamed_trace():
    """Every trace of a ``.plot()`` figure has a name and a finite point (audit 21): the planar
    run-up's amplitude figure carried "semi-balanced (= s2)" with 601 y values all NaN (that
    state exists nowhere on the run's speeds), and every figure with an rpm axis (the washer's
    stability margin) a trace with no name and y = [NaN, NaN], there only to show the axis. A
    trace without points (the Campbell diagram's log-decrement key) has none to be finite. The
    rpm axis is still drawn (its trace is kept, finite and invisible)."""
    need("plotly")
    cases = [
        autobal.analyse("stability", config=str(EX / "washing_machine.toml")),
        autobal.analyse("simulate", config=str(EX / "planar.toml"), set={"drive.t_end": 5.0}),
    ]
    for r in cases:
        for name in r.figures():
            fig = r.plot(name).to_dict()
            for t in fig["data"]:
                if t.get("type") == "heatmap":
                    continue
                assert isinstance(t.get("name"), str) and t["name"], (r.command, name, t)
                y = np.asarray(t.get("y", ()), dtype=float)
                assert y.size == 0 or np.isfinite(y).any(), (r.command, name, t["name"])
    fig = cases[0].plot().to_dict()
    axis = [t for t in fig["data"] if t.get("xaxis") == "x2"]
    assert len(axis) == 1 and "xaxis2" in fig["layout"] and axis[0]["opacity"] == 0
    # the whole run-up (to 240 s) reaches the speeds where the semi-balanced state exists: its
    # curve is drawn there (only a curve of gaps is left out)
    full = autobal.analyse("simulate", config=str(EX / "planar.toml")).plot().to_dict()
    s2 = [t for t in full["data"] if t["name"] == "semi-balanced (= s2)"]
    assert len(s2) == 1 and np.isfinite(np.asarray(s2[0]["y"], dtype=float)).sum() > 100
