"""autobal: rotors with passive automatic balancing devices (ball balancers).

Two models, each built from keyword arguments, a dict of config tables or a TOML file (the
same tables and keys as the ``autobal`` command line, ``examples/*.toml``):

- :class:`SpatialModel`, the rigid rotor of papers 000/003: inertia, critical speeds,
  autobalancing ranges, exact stability against 003's necessary ranges, Campbell data;
- :class:`PlanarProblem`, the rotor of paper 004 with an eccentric ball balancer, in time:
  simulations (columns as NumPy arrays, :meth:`Simulation.to_pandas`), batches and sweeps
  (:func:`simulate_batch`, :func:`sweep`, on a Dask cluster with ``client=``), which also run
  the spatial rotor of a :class:`SpatialModel` with ``[drive]``.

:func:`run` is every command of the CLI but ``report`` as one call, returning the dict that
``autobal COMMAND --format json`` prints (for ``merge`` and ``export-model``, their JSON);
:func:`analyse` returns the same as a :class:`Result` with ``.plot()`` (Plotly figures, the
report's), ``.to_pandas()`` and a rich display in Jupyter; :func:`report` writes the HTML report
of ``autobal report``, :func:`merge` joins the shards of ``autobal sweep --shard K/N`` as
``autobal merge`` does, and :func:`export_model` writes a linear rotor's config and matrices as
``autobal export-model`` does. The wheel also installs the ``autobal`` command itself. Errors are
:mod:`autobal.errors` exceptions naming the field. Long calls release the GIL and stop on Ctrl-C.

>>> import autobal
>>> m = autobal.SpatialModel(delta_a=0.1)          # paper 000's base case, 003's anisotropy
>>> m.critical_speeds().round(2).tolist()
[0.84, 0.85, 2.52, 3.8]
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _autobal
from .errors import AutobalError, Interrupted, InvalidParameter, NoConvergence, SimulationError, TooLarge
from ._sweep import _axes, columns, simulate_batch, sweep, grid
from ._results import COMMANDS, COMMANDS_WITH_FIGURES, Report, Result, _report_path, report
from ._ross import from_ross
from . import _linear_config
from ._autobal import LinearRotor
from ._linear_rotor import LinearConfigResult, LinearSimulation

__version__: str = _autobal.__version__
#: Columns of a planar run's summary in :func:`simulate_batch` and :func:`sweep`, in order
#: (``outcome``: 0 not settled, 1 not balanced, 2 partially balanced, 3 balanced).
SUMMARY_COLUMNS: List[str] = list(_autobal.SUMMARY_COLUMNS)
#: Columns of a spatial run's summary (:class:`SpatialModel`): ``SUMMARY_COLUMNS``, then
#: ``residual_couple`` (NaN without a couple), ``static_sag`` (NaN where the run has no sag).
SPATIAL_SUMMARY_COLUMNS: List[str] = list(_autobal.SPATIAL_SUMMARY_COLUMNS)

__all__ = [
    "SpatialModel",
    "PlanarProblem",
    "Simulation",
    "run",
    "analyse",
    "report",
    "merge",
    "export_model",
    "Result",
    "Report",
    "COMMANDS",
    "COMMANDS_WITH_FIGURES",
    "simulate_batch",
    "sweep",
    "grid",
    "columns",
    "SUMMARY_COLUMNS",
    "SPATIAL_SUMMARY_COLUMNS",
    "AutobalError",
    "InvalidParameter",
    "TooLarge",
    "NoConvergence",
    "SimulationError",
    "Interrupted",
    "from_ross",
    "LinearRotor",
    "LinearSimulation",
]

ConfigLike = Union[None, str, "os.PathLike[str]", Mapping[str, Any]]

_SCHEMA: Dict[str, List[str]] = {t: list(k) for t, k in _autobal.SCHEMA}
_SPATIAL_FLAT = ("dimensionless", "analysis")
_SI_TABLES = ("rotor", "supports", "unbalance", "balancer")
_PLANAR_FLAT = ("planar", "drive", "integration")


def _invalid(field: str, reason: str) -> InvalidParameter:
    """An :class:`InvalidParameter` about ``field`` (``.field``, ``.reason``), as the Rust side
    raises them: the message is ``"field: reason"``."""
    e = InvalidParameter(f"{field}: {reason}")
    e.field, e.reason = field, reason
    return e


def _sets(keys: Mapping[str, Any], set: Optional[Mapping[str, Any]], flat_tables: Sequence[str]) -> List[Tuple[str, Any]]:
    """``table.key`` assignments from keyword arguments (``key=`` of a table in
    ``flat_tables``, or ``table={...}``) and the ``set`` mapping (``{"table.key": value}``)."""
    out: List[Tuple[str, Any]] = []
    for k, v in keys.items():
        if k in _SCHEMA and isinstance(v, Mapping):
            out.extend((f"{k}.{kk}", vv) for kk, vv in v.items())
            continue
        tables = [t for t in flat_tables if k in _SCHEMA[t]]
        if len(tables) != 1:
            known = ", ".join(sorted({kk for t in flat_tables for kk in _SCHEMA[t]}))
            raise _invalid(k, f"unknown keyword (keys: {known}; or a table as a dict, e.g. rotor={{...}}, or set={{'table.key': value}})")
        out.append((f"{tables[0]}.{k}", v))
    out.extend((set or {}).items())
    return out


def _read(config: ConfigLike, default: str, default_name: str) -> Tuple[Optional[str], Optional[dict], str]:
    if config is None:
        return default, None, default_name
    if isinstance(config, Mapping):
        return None, dict(config), "dict"
    p = _config_file(config)
    return p.read_text(encoding="utf-8"), None, str(p)


def _config_file(config: Union[str, "os.PathLike[str]"]) -> Path:
    """The config file ``config``, checked: it exists and holds at most 1 MiB."""
    p = Path(config)
    try:
        size = p.stat().st_size
    except OSError as e:
        # the OSError subclass Python users expect (FileNotFoundError for a missing file,
        # PermissionError, ...), naming the path
        raise type(e)(e.errno, f"config {p}: cannot read: {e.strerror}", str(p)) from None
    if size > 1 << 20:
        raise TooLarge(f"config {p}: {size} bytes exceeds the limit of 1048576 (a config is a few dozen lines)")
    return p


class _Config:
    """A validated config of one model: the default config, changed by keyword arguments and
    ``set``, or a dict or TOML file (see the subclasses)."""

    _DEFAULT: str = ""
    _DEFAULT_NAME: str = ""
    _FLAT: Sequence[str] = ()

    def __init__(self, config: ConfigLike = None, *, set: Optional[Mapping[str, Any]] = None, **keys: Any) -> None:
        if config is None and any(t in keys for t in _SI_TABLES):
            config = {}
        text, table, source = _read(config, self._DEFAULT, self._DEFAULT_NAME)
        self._cfg = self._make(text, table, source, _sets(keys, set, self._FLAT))

    @staticmethod
    def _make(text: Optional[str], dict: Optional[Mapping[str, Any]], source: str, sets: Sequence[Tuple[str, Any]]) -> Any:
        raise NotImplementedError

    @classmethod
    def from_toml(cls, path: Union[str, "os.PathLike[str]"], **keys: Any) -> Any:
        """The model of a TOML config file (``examples/*.toml``), changed by ``keys``."""
        return cls(path, **keys)

    @property
    def toml(self) -> str:
        """The config's tables as TOML (after keyword arguments and ``set``)."""
        return self._cfg.toml


class SpatialModel(_Config):
    """The rigid rotor on two supports with an unbalance mass and an n-ball balancer (papers
    000/003), validated.

    ``config``: a TOML file, a dict of tables (``{"dimensionless": {...}, "analysis": {...}}``
    or the SI tables ``rotor``, ``supports``, ``unbalance``, ``balancer``), or ``None`` for
    paper 000's base case (``examples/default.toml``). Keyword arguments set keys of
    ``[dimensionless]`` and ``[analysis]`` by name (``l_left=1.2``, ``anisotropy="paper"``) or
    whole tables (``rotor={"mass": 20, ...}``); ``set`` takes ``{"table.key": value}``, like the
    CLI's ``--set``. Without ``config``, SI tables start from an empty config.

    >>> SpatialModel(l_left=1.2).critical()["rotor_type"]
    'long'
    """

    _DEFAULT = _autobal.DEFAULT_SPATIAL
    _DEFAULT_NAME = "embedded default (examples/default.toml)"
    _FLAT = _SPATIAL_FLAT
    _make = staticmethod(_autobal.spatial_config)

    @classmethod
    def paper_000(cls, l_left: float = 0.8) -> "SpatialModel":
        """Paper 000's base case at layout ``l̄_L`` (``examples/default.toml``)."""
        return cls(l_left=l_left)

    @classmethod
    def paper_003(cls, l_left: float = 0.8) -> "SpatialModel":
        """Paper 003's worked examples at ``l̄_L`` = 0.5, 0.8, 1.2: ``ΔĀ = ΔĀ0 = 0.1`` given
        directly, no damping."""
        return cls({"dimensionless": {"c_sigma": 0.75, "rho_s": 0.4, "l_left": l_left, "z_a": 0.8, "delta_a": 0.1}})

    def _report(self, command: str, **options: Any) -> Dict[str, Any]:
        return json.loads(_autobal.spatial_report(command, self._cfg, **options))

    def inertia(self) -> Dict[str, Any]:
        """Composite inertia and anisotropy (``autobal inertia --format json``)."""
        return self._report("inertia")

    def critical(self) -> Dict[str, Any]:
        """Critical speeds, sensitivity, autobalancing ranges (``autobal critical``)."""
        return self._report("critical")

    def critical_speeds(self) -> np.ndarray:
        """The critical speeds Ω (dimensionless, ascending; exact roots of 000's eq (16))."""
        return np.array([k["omega"] for k in self.critical()["critical_speeds"]], dtype=float)

    def ranges(self) -> Dict[str, Any]:
        """Antiresonance and autobalancing ranges of 003 (``autobal ranges``)."""
        return self._report("ranges")

    def stability(self, omega_max: Optional[Union[float, str]] = None, samples: Optional[int] = None, balls: str = "free") -> Dict[str, Any]:
        """Exact stability ranges of the balanced state against 003's necessary ranges over
        ``0 < Ω ≤ omega_max`` (``autobal stability``); ``balls``: ``"free"`` or ``"locked"``.
        ``omega_max``: a number is the dimensionless Ω; a dimensional config also takes a speed
        with its unit, ``"1500 rpm"``, ``"157 rad/s"``, ``"25 Hz"``. With
        ``analysis.operating_speed`` the result's ``operating_speed`` says whether the balanced
        state is stable there, with the margin; ``*_rpm`` keys give the ranges in rpm. On a
        config the 12-state model does not represent (two planes, couple unbalance, supports
        that differ by direction, gravity) the general route's result, as the CLI gives it
        (``"route": "general"``). ``samples``: default 2000, on the general route 200 (50 for a
        periodic orbit)."""
        return self._report("stability", omega_max=omega_max, samples=samples, balls=balls)

    def campbell(self, omega_max: Optional[Union[float, str]] = None, points: Optional[int] = None, balls: str = "free") -> Dict[str, Any]:
        """Campbell data: ``omega`` (speeds), and per tracked line (rows) and speed (columns)
        ``re``, ``im`` (rotating axes), ``fixed_frequency``, ``log_decrement`` (NaN where
        undefined) as arrays, ``whirl`` and ``group`` as lists of lists; ``raw`` is the JSON of
        ``autobal campbell``. For a dimensional config also ``omega_rpm``, ``omega_rad_s`` and
        per mode ``fixed_frequency_hz``, ``fixed_frequency_rpm``, ``fixed_frequency_rad_s``,
        ``im_hz``, ``im_rad_s``, ``re_per_s`` (Ω-units times ω0). ``omega_max`` as for
        :meth:`stability`. ``points``: default 300. On a config the 12-state model does not
        represent, the general route's JSON as the CLI prints it (``"route": "general"``, 60
        points by default for a periodic orbit), returned as it is: ``state`` per speed (the
        state followed, ``stability``'s words; ``state_followed`` where the balls' capacity
        falls short and it is the partially balanced one), and a Floquet exponent whose
        multiplier is below the monodromy's round-off has ``re`` and ``log_decrement`` None and
        ``decay_at_least`` (the mode decays at least that fast; ``undetermined`` says why)."""
        raw = self._report("campbell", omega_max=omega_max, points=points, balls=balls)
        if raw.get("route") == "general":
            return raw
        lines = [line["modes"] for line in raw["lines"]]

        def arr(key: str) -> np.ndarray:
            return np.array([[np.nan if m.get(key) is None else m[key] for m in ms] for ms in lines], dtype=float)

        out = {
            "omega": np.array(raw["omega"], dtype=float),
            "re": arr("re"),
            "im": arr("im"),
            "fixed_frequency": arr("fixed_frequency"),
            "log_decrement": arr("log_decrement"),
            "whirl": [[m["whirl"] for m in ms] for ms in lines],
            "group": [[m["group"] for m in ms] for ms in lines],
            "raw": raw,
        }
        # a dimensional config: the same in SI
        for key in ("omega_rpm", "omega_rad_s"):
            if key in raw:
                out[key] = np.array(raw[key], dtype=float)
        si = ("fixed_frequency_hz", "fixed_frequency_rpm", "fixed_frequency_rad_s", "im_hz", "im_rad_s", "re_per_s")
        if lines and lines[0] and "fixed_frequency_hz" in lines[0][0]:
            for key in si:
                out[key] = arr(key)
        return out

    def simulate(self, dt: Optional[float] = None) -> "Simulation":
        """Run this rotor in time: the nonlinear spatial model (docs/notes/spatial.md) with the
        config's ``[drive]`` and ``[integration]`` (and ``[initial]``, ``[spatial]``,
        ``[couple]``, ``[balancer2]`` where given), as ``autobal simulate`` does; ``dt``
        overrides the output interval. Columns ``t, omega, x, y, tilt_x, tilt_y``,
        ``amplitude_left``, ``amplitude_right`` (supports), ``amplitude_plane1`` … (balancer
        planes), ``psi`` (samples × balls); the summary as ``autobal simulate --format json``
        prints it (``summary["mean_displacement"]`` and ``summary["static_sag"]`` are ``None``
        when the run turned less than a revolution: there is no revolution to average over). A
        run that stops before its end raises :class:`SimulationError`.

        >>> s = SpatialModel(drive={"kind": "speed", "omega0": 1.6, "t_end": 200}).simulate(dt=1.0)
        >>> s.summary["model"], s["psi"].shape, s.summary["units"]
        ('spatial', (201, 2), 'dimensionless (M_s = ω0 = ρ_s = 1)')
        """
        columns, summary = _autobal.spatial_simulate(self._cfg, dt)
        return _finished(Simulation(columns, json.loads(summary)))

    def basins(self, n: Optional[int] = None) -> Dict[str, Any]:
        """Where runs from an ``n × n`` grid of the first two balls' initial angles end (``n``
        ``None``: the CLI's default, ``--n 24``; the config's drive and integration; in parallel
        in Rust, Ctrl-C stops it), as ``autobal basins`` computes them: ``runs``, ``completed``, ``balanced`` (how many runs ended
        balanced), ``fraction_balanced``, ``wall_time_s`` (its JSON) and per run the arrays
        ``psi_1``, ``psi_2`` (initial angles), ``balanced_runs`` (bool: this run ended balanced;
        the CSV's ``balanced`` column), ``residual_unbalance``, ``final_amplitude`` (its CSV)."""
        arrays, summary = _autobal.spatial_basins(self._cfg, n)
        out: Dict[str, Any] = json.loads(summary)
        out.update(arrays)
        return out

    def stability_map(
        self,
        x: Union[str, Tuple[str, Sequence[float]]],
        y: Union[str, Tuple[str, Sequence[float]]],
        *,
        omega: Optional[float] = None,
        balls: str = "free",
        quantity: str = "margin",
        threads: Optional[int] = None,
    ) -> Dict[str, Any]:
        """The stability margin over two parameters, as ``autobal map`` computes it: ``x`` and
        ``y`` as ``"path=lo:hi:n"`` (or a list ``"path=v1,v2"``) or ``(path, values)``, with
        path ``omega`` for the speed or a parameter path (``dimensionless.z_a``); ``omega``: the
        speed when neither axis is it. Returns ``x``, ``y`` (the values) and ``margin`` (max Re λ
        of the balanced state; NaN with ``quantity="verdict"``), ``stable``, ``necessary``
        (inside 003's necessary ranges) as arrays ``len(y) × len(x)``, computed in parallel in
        Rust with the GIL released (Ctrl-C stops it).

        >>> m = SpatialModel().stability_map("dimensionless.z_a=-2:2:5", "omega=0.1:4.5:4")
        >>> m["margin"].shape, bool(m["stable"].any())
        ((4, 5), True)
        """
        (xp, xv), (yp, yv) = _axes([x, y])
        # the arrays, and the axes' paths
        out: Dict[str, Any] = _autobal.stability_map(self._cfg, (xp, xv), (yp, yv), omega, balls, quantity, threads)
        out["x_path"], out["y_path"] = xp, yp
        return out


class Simulation:
    """A run of a :class:`PlanarProblem` or of a :class:`SpatialModel` in time: ``columns``
    (1-D arrays: ``t``, ``omega``, ``x``, ``y``, ``amplitude`` for the planar rotor; ``t``,
    ``omega``, ``x``, ``y``, ``tilt_x``, ``tilt_y`` and the whirl radii for the spatial one;
    ``psi`` as samples × balls) and ``summary`` (the dict ``autobal simulate --format json``
    prints; ``summary["model"]`` says which)."""

    def __init__(self, columns: Dict[str, np.ndarray], summary: Dict[str, Any]) -> None:
        self.columns = columns
        self.summary = summary

    def __getitem__(self, name: str) -> np.ndarray:
        return self.columns[name]

    def __repr__(self) -> str:
        s = self.summary
        if s.get("units", "SI") == "SI":
            peak = f"{1e3 * s['peak_amplitude']:.4g} mm at ω = {s['omega_at_peak']:.4g} rad/s"
        else:
            peak = f"{s['peak_amplitude']:.4g} ρ_s at Ω = {s['omega_at_peak']:.4g}"
        return f"Simulation({s['model']}, {len(self.columns['t'])} samples, peak {peak}, balanced={s['balanced']})"

    def to_pandas(self) -> "Any":
        """The samples as a pandas DataFrame with the columns of the CLI's CSV (``psi`` split
        into ``psi_1 … psi_n``; needs pandas)."""
        import pandas as pd

        data = {k: v for k, v in self.columns.items() if k != "psi"}
        psi = self.columns["psi"]
        for j in range(psi.shape[1]):
            data[f"psi_{j + 1}"] = psi[:, j]
        return pd.DataFrame(data)


class PlanarProblem(_Config):
    """The planar rotor of paper 004 with its drive and integration settings, validated.

    ``config``: a TOML file, a dict of the tables ``planar``, ``drive``, ``integration``, or
    ``None`` for paper 004's passage (``examples/planar.toml``). Keyword arguments set keys of
    these tables by name (``m3=0.01``, ``b=5.0``, ``t_end=20``); ``set`` takes
    ``{"table.key": value}``.

    >>> PlanarProblem(m3=0.01).get("planar.m3")
    0.01
    """

    _DEFAULT = _autobal.DEFAULT_PLANAR
    _DEFAULT_NAME = "embedded default (examples/planar.toml)"
    _FLAT = _PLANAR_FLAT
    _make = staticmethod(_autobal.planar_config)

    @classmethod
    def paper_004(cls, m3: float = 0.03) -> "PlanarProblem":
        """Paper 004's passage with ball mass ``m3`` (kg): 0.03 balances, 0.01 does not."""
        return cls(m3=m3)

    @staticmethod
    def paths() -> List[Tuple[str, str]]:
        """Every parameter path a sweep can vary, with what it is."""
        return list(_autobal.planar_paths())

    def get(self, path: str) -> float:
        """The number at a parameter path (``planar.m3``, ``drive.b``, ``drive.psi0[1]``)."""
        return self._cfg.get(path)

    def simulate(self, dt: Optional[float] = None) -> Simulation:
        """Run it, sampling every ``dt`` seconds (default: the config's ``integration.dt``).
        A run that stops before its end raises :class:`SimulationError` (``.result`` holds
        the :class:`Simulation` up to then)."""
        columns, summary = _autobal.simulate(self._cfg, dt)
        return _finished(Simulation(columns, json.loads(summary)))


def _finished(sim: Simulation) -> Simulation:
    """``sim``, or :class:`SimulationError` (``.result``: the samples up to then) when the run
    stopped before its end."""
    if sim.summary.get("stopped"):
        e = SimulationError(f"{sim.summary['stopped']}: the samples up to then are in .result")
        e.result = sim
        raise e
    return sim


def run(command: str, config: ConfigLike = None, set: Optional[Mapping[str, Any]] = None, **options: Any) -> Dict[str, Any]:
    """Run a CLI command and return the dict ``autobal COMMAND --format json`` prints for the
    same config and ``--set`` overrides.

    Commands and their options (as the CLI's, with ``_`` for ``-``):

    - ``inertia``, ``ranges``, ``critical`` (``omega_max``, ``route``) on any config (a planar
      one takes the general route, as on the CLI);
    - ``stability`` (``omega_max``, ``samples``, ``balls``, ``route``), ``campbell``
      (``omega_max``, ``points``, ``balls``, ``route``); ``route``: ``"auto"`` (default) or
      ``"general"``, the CLI's ``--route``; the defaults are the CLI's;
    - ``simulate`` (``dt``): the summary (no files are written), of the planar rotor
      (``[planar]``), of the spatial rotor in time (the analytic config plus ``[drive]``) or of
      a linear rotor (``[linear_rotor]``);
    - ``basins`` (``n``): the JSON of ``autobal basins`` (no CSV is written; the runs' arrays:
      :meth:`SpatialModel.basins`);
    - ``sweep`` (``x``, ``y``, ``axis`` (a list), ``shard`` (``"K/N"``), ``threads``): the JSON
      of the sweep (no files are written), of either rotor;
    - ``map`` (``x``, ``y``, ``omega``, ``balls``, ``quantity``, ``route``, ``threads``) on any
      config (a planar one takes the general route, as on the CLI): the CLI writes CSV and
      figures; this returns the cells of its CSV as arrays ``len(y) × len(x)``: ``x``, ``y``,
      ``margin``, ``stable`` and ``necessary`` (closed form) or ``verdict``,
      ``family_dimension`` and ``state`` (general route, with ``route: "general"``);
    - ``merge`` (``shards``, ``out``, ``parquet``; no config): writes the merged sweep as
      :func:`merge` does and returns its JSON (the ``STEM.json`` written, the unsharded sweep's);
    - ``export-model`` (``out``, ``stem``): writes the files as :func:`export_model` does and
      returns ``{"files": [...]}``, the paths written.

    >>> run("critical", set={"dimensionless.delta_a": 0.1})["critical_speeds"][3]["omega"] > 3.79
    True
    """
    if command in _FILE_COMMANDS:
        # the commands that write files: their Result's JSON (the CLI's Output::json)
        return _FILE_COMMANDS[command](config, set, options).result
    if _linear_config.is_linear(config):
        # a [linear_rotor] config file: stability, simulate, map, sweep, basins (_linear_config)
        return _linear_config.run(command, config, set, **options)
    if command in _REPORT_OPTIONS:
        _no_more(command, {k: v for k, v in options.items() if k not in _REPORT_OPTIONS[command]})
        # the config as the CLI reads it (any rotor: a planar config takes the general route),
        # the command's own defaults and checks (autobal_commands' Args)
        text, table, source = _read(config, _autobal.DEFAULT_SPATIAL, SpatialModel._DEFAULT_NAME)
        return json.loads(_autobal.command_json(command, text, table, source, list((set or {}).items()), **options))
    if command == "simulate":
        dt = options.pop("dt", None)
        _no_more(command, options)
        # the CLI's command (its Args and run): the planar, spatial or linear rotor by the config
        text, table, source = _read(config, _autobal.DEFAULT_PLANAR, PlanarProblem._DEFAULT_NAME)
        _, summary = _autobal.simulate_command(text, table, source, list((set or {}).items()), dt, False)
        out = json.loads(summary)
        if out.get("stopped"):
            e = SimulationError(out["stopped"])
            e.result = out
            raise e
        return out
    if command == "sweep":
        p: Any
        try:
            p = PlanarProblem(config, set=set)
        except InvalidParameter as e:
            if not (e.field == "planar" and "missing" in str(e)):
                raise
            # the analytic commands' config: the spatial rotor in time
            p = SpatialModel(config, set=set)
        specs = [("x", options.pop("x", None))]
        if "y" in options:
            specs.append(("y", options.pop("y")))
        specs += [("axis", a) for a in options.pop("axis", [])]
        if specs[0][1] is None:
            raise _invalid("x", "required (the first axis, e.g. x='drive.b=0.5:12.5:5')")
        axes = [_autobal.parse_axis(spec) for _, spec in specs if spec is not None]
        shard = options.pop("shard", None)
        kn = None
        if shard is not None:
            try:
                k, n = (int(s) for s in str(shard).split("/"))
            except ValueError:
                raise _invalid("shard", f"{shard}: expected K/N with 1 ≤ K ≤ N, e.g. shard='3/8'") from None
            kn = (k, n)
        threads = options.pop("threads", None)
        _no_more(command, options)
        return json.loads(_autobal.sweep_report(p._cfg, axes, kn, threads))
    if command == "basins":
        n = options.pop("n", None)
        _no_more(command, options)
        return json.loads(_autobal.spatial_basins(SpatialModel(config, set=set)._cfg, n)[1])
    if command == "map":
        return _map(config, set, options)
    if command == "report":
        raise _invalid("command", "report writes a folder of pages: autobal.report(config, out=...) (or autobal.analyse(\"report\", ...))")
    raise _invalid(
        "command",
        f"\"{command}\" is not a command of autobal.run (inertia, critical, ranges, stability, campbell, simulate, sweep, merge, basins, map, export-model)",
    )


def _map(config: ConfigLike, set: Optional[Mapping[str, Any]], options: Dict[str, Any], boundary: bool = False) -> Dict[str, Any]:
    """``run("map", ...)`` on any config but a linear rotor's: the cells as arrays.
    ``boundary`` (:func:`analyse`'s, traced for its figure only) is checked as the CLI's
    ``--boundary`` before any cell is computed (a map at a speed in SI over axes that move
    omega0 cannot be traced: refused here, not after every cell while drawing)."""
    command = "map"
    if "x" not in options or "y" not in options:
        raise _invalid("x", "required, with y (e.g. x='dimensionless.z_a=-2:2:41', y='omega=0.05:4.5:41')")
    (xp, xv), (yp, yv) = _axes([options.pop("x"), options.pop("y")])
    kw = {k: options.pop(k) for k in ("omega", "balls", "quantity", "route", "threads") if k in options}
    _no_more(command, options)
    # the config as the CLI reads it (any rotor: a planar or two-plane config takes the
    # general route, as on the CLI), the command's own defaults and checks (map::Args)
    text, table, source = _read(config, _autobal.DEFAULT_SPATIAL, SpatialModel._DEFAULT_NAME)
    out = _autobal.map_cells(text, table, source, list((set or {}).items()), (xp, xv), (yp, yv), boundary=bool(boundary), **kw)
    for name in ("verdict", "state"):
        if name in out:
            out[name] = np.array(out[name], dtype=object)
    out["x_path"], out["y_path"] = xp, yp
    return out


# the options of the analytic commands (the others take theirs from ``options`` one by one)
_REPORT_OPTIONS: Dict[str, Tuple[str, ...]] = {
    "inertia": (),
    "critical": ("omega_max", "route"),
    "ranges": (),
    "stability": ("omega_max", "samples", "balls", "route"),
    "campbell": ("omega_max", "points", "balls", "route"),
}


def _no_more(command: str, options: Mapping[str, Any]) -> None:
    if options:
        raise _invalid(next(iter(options)), f"not an option of {command} (see help(autobal.run))")


def analyse(command: str, config: ConfigLike = None, set: Optional[Mapping[str, Any]] = None, **options: Any) -> Result:
    """Run a CLI command as :func:`run` does and return its :class:`Result`: ``.result`` is what
    :func:`run` returns (``autobal COMMAND --format json``), ``.plot(name=None)`` its figures as
    Plotly figures (those the CLI writes and the report draws, from the same description;
    ``stability``, ``campbell``, ``map`` with text axes, ``simulate``, ``sweep``, ``basins``),
    ``.to_pandas()`` its
    table, and Jupyter shows a summary table and the main figure. Options as for :func:`run`;
    ``campbell`` also takes ``harmonics`` (its figures' excitation lines), ``map``
    ``boundary=True`` (the traced boundary on its figure, as the CLI's ``--boundary``). ``analyse("report",
    config, out=..., quick=..., papers=...)`` is :func:`report`; ``analyse("merge", shards=...,
    out=...)`` is :func:`merge`, ``analyse("export-model", config, out=..., stem=...)``
    :func:`export_model`.

    The figures are computed on the first ``.plot()`` (for ``simulate``, ``sweep`` and
    ``basins`` the runs are repeated: they are not kept in Rust between the calls).

    >>> r = analyse("critical", set={"dimensionless.delta_a": 0.1})
    >>> r.result == run("critical", set={"dimensionless.delta_a": 0.1}), len(r.to_pandas())
    (True, 4)
    """
    arrays: Optional[Dict[str, Any]] = None
    if command in _FILE_COMMANDS:
        return _FILE_COMMANDS[command](config, set, options)
    if command != "report" and _linear_config.is_linear(config):
        lin, extra = _linear_config.run_with_extra(command, config, set, **options)
        return LinearConfigResult(command, lin, config, set, options, extra)
    if command == "report":
        # a dict of tables is refused there (TypeError), as by report itself
        return report(_report_path(config), options.pop("out", "autobal-report"), set=set, **options)
    if command == "simulate":
        _no_more(command, {k: v for k, v in options.items() if k != "dt"})
        text, table, source = _read(config, _autobal.DEFAULT_PLANAR, PlanarProblem._DEFAULT_NAME)
        columns, summary = _autobal.simulate_command(text, table, source, list((set or {}).items()), options.get("dt"))
        sim = _finished(Simulation(columns, json.loads(summary)))
        result, arrays = sim.summary, sim.columns
    elif command == "basins":
        _no_more(command, {k: v for k, v in options.items() if k != "n"})
        arrays, summary = _autobal.spatial_basins(SpatialModel(config, set=set)._cfg, options.get("n"))
        result = json.loads(summary)
    elif command == "map":
        # `boundary` draws the traced boundary on the figure; the cells are the same, and a
        # boundary that cannot be traced is refused before any of them is computed
        result = _map(config, set, {k: v for k, v in options.items() if k != "boundary"}, boundary=options.get("boundary", False))
    else:
        result = run(command, config, set, **options)
    planar_default = command in ("simulate", "sweep")
    text, table, source = _read(
        config,
        _autobal.DEFAULT_PLANAR if planar_default else _autobal.DEFAULT_SPATIAL,
        "embedded default (examples/planar.toml)" if planar_default else SpatialModel._DEFAULT_NAME,
    )
    return Result(command, result, (text, table, source, list((set or {}).items())), options, arrays)


def merge(shards: Sequence[Union[str, "os.PathLike[str]"]], out: Union[str, "os.PathLike[str]"], parquet: bool = False) -> Result:
    """Join the outputs of ``autobal sweep --shard K/N`` (each shard's ``STEM.csv`` and
    ``STEM.json``) into the unsharded sweep's ``STEM.csv`` and ``STEM.json`` at the stem ``out``
    (a folder ``DIR/``: ``DIR/sweep.*``), as ``autobal merge SHARDS --out OUT`` does (the
    same code): ``shards`` are the shards' CSV files, each with its ``STEM.json`` beside it, in
    any order; ``parquet=True`` also writes ``STEM.parquet`` (the CLI's ``--parquet``).
    Every shard is checked first (the same sweep, each shard once and complete, every row its
    JSON's run), and nothing is written unless all hold: otherwise :class:`AutobalError` naming
    the shard and line (:class:`InvalidParameter` for no shards or no ``out``). Ctrl-C stops it
    before anything is renamed into place.

    Returns a :class:`Result`: ``.result`` the merged JSON (the ``STEM.json`` written, the
    unsharded sweep's), ``.files`` the paths written, ``.to_pandas()`` one row per run as for
    ``sweep``."""
    shards = [shards] if isinstance(shards, (str, os.PathLike)) else list(shards)
    text, files = _autobal.merge([os.fspath(s) for s in shards], os.fspath(out), bool(parquet))
    return Result("merge", json.loads(text), (None, None, "", []), {"shards": list(shards), "out": out, "parquet": parquet}, files=[Path(f) for f in files])


def export_model(
    config: ConfigLike = None,
    out: Union[None, str, "os.PathLike[str]"] = None,
    stem: Optional[str] = None,
    *,
    set: Optional[Mapping[str, Any]] = None,
) -> Result:
    """Write a linear rotor as a config plus Matrix Market files, ``STEM.toml`` and
    ``STEM_M.mtx``, ``STEM_C.mtx``, ``STEM_G.mtx``, ``STEM_K.mtx``, into the folder ``out``
    (created if missing), as ``autobal export-model --config CONFIG --out OUT --stem STEM`` does
    (the same code, the same bytes): the rotor of a ``[linear_rotor]`` config (a TOML file, or a
    dict of its tables, whose matrix files are then read from the working folder), reduced
    where it sets ``linear_rotor.modes``; without a config, paper 004's rotor with its race
    centred as a Jeffcott rotor. ``out`` and ``stem`` ``None``: the CLI's defaults (``model``,
    ``rotor``); ``set``: ``{"table.key": value}``, the CLI's ``--set`` (needs a config). Every
    file is checked before any is written.

    Returns a :class:`Result`: ``.result`` ``{"files": [...]}`` (the paths written, the config
    first), ``.files`` the same as paths; :meth:`LinearRotor.from_config` reads them back."""
    path: Optional[str] = None
    table: Optional[dict] = None
    if isinstance(config, Mapping):
        table = dict(config)
    elif config is not None:
        _config_file(config)
        path = os.fspath(config)
    elif set:
        raise _invalid("set", "needs a config (without one, export_model writes paper 004's rotor as it is)")
    text = _autobal.export_model(path, table, list((set or {}).items()), None if out is None else os.fspath(out), stem)
    result = json.loads(text)
    return Result("export-model", result, (None, None, "", []), {"out": out, "stem": stem}, files=[Path(f) for f in result["files"]])


def _merge_command(config: ConfigLike, set: Optional[Mapping[str, Any]], options: Dict[str, Any]) -> Result:
    if config is not None or set:
        raise _invalid("config" if config is not None else "set", "merge takes no config: its shards carry their sweep's")
    o = dict(options)
    if "shards" not in o:
        raise _invalid("shards", "required: the shards' CSV files (each with its STEM.json beside it)")
    if "out" not in o:
        raise _invalid("out", "required: the merged sweep's stem")
    shards, out, parquet = o.pop("shards"), o.pop("out"), bool(o.pop("parquet", False))
    _no_more("merge", o)
    return merge(shards, out, parquet)


def _export_model_command(config: ConfigLike, set: Optional[Mapping[str, Any]], options: Dict[str, Any]) -> Result:
    o = dict(options)
    out, stem = o.pop("out", None), o.pop("stem", None)
    _no_more("export-model", o)
    return export_model(config, out, stem, set=set)


# the commands that write files, as run and analyse take them (config, set, options)
_FILE_COMMANDS = {"merge": _merge_command, "export-model": _export_model_command}
