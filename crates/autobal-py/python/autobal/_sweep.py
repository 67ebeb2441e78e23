"""Batches and sweeps of simulations, of the planar rotor (:class:`PlanarProblem`), of the
spatial rotor (:class:`SpatialModel` of a config with ``[drive]``) or of a linear rotor (the
path of a ``[linear_rotor]`` config file): in-process (Rust threads) or on a Dask cluster,
streamed to disk chunk by chunk so that an interrupted sweep keeps what finished and resumes.

A config travels to the Dask workers as its TOML text (a dict of tables too), and a linear
rotor config with the bytes of the matrix files it names (read once, here): the workers need no
shared file system."""

from __future__ import annotations

import hashlib
import json
import os
import tempfile
import uuid
from pathlib import Path
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _autobal
from .errors import InvalidParameter

if TYPE_CHECKING:  # pragma: no cover
    from . import PlanarProblem, SpatialModel

Problem = Union["PlanarProblem", "SpatialModel", str, "os.PathLike[str]", Mapping[str, Any]]


class _LinearProblem:
    """A ``[linear_rotor]`` config file with its matrix files read once (``_autobal.LinearSpec``)."""

    def __init__(self, spec: Any) -> None:
        self._cfg = spec

    @property
    def toml(self) -> str:
        return str(self._cfg.toml)


# a problem with a linear rotor config's path read (:func:`_problem`)
_Resolved = Union["PlanarProblem", "SpatialModel", _LinearProblem]


def _problem(problem: Union[Problem, _LinearProblem]) -> _Resolved:
    """``problem``, the path of a ``[linear_rotor]`` config file as its :class:`_LinearProblem`,
    or a dict of tables as its model: a ``[linear_rotor]`` config's (its matrix files read
    relative to the working folder, as :func:`autobal.run` reads a dict's), else the planar
    rotor's (``planar``, ``drive``, ``integration``) or, without ``planar``, the spatial
    rotor's, as ``autobal.run("sweep", tables)`` takes it."""
    if isinstance(problem, Mapping):
        from . import PlanarProblem, SpatialModel, _linear_config

        if _linear_config.is_linear(problem):
            return _LinearProblem(_autobal.LinearSpec.from_dict(dict(problem), []))
        if "planar" in problem:
            return PlanarProblem(problem)
        return SpatialModel(problem)
    if isinstance(problem, (str, os.PathLike)):
        from . import _linear_config

        if not _linear_config.is_linear(problem):
            raise InvalidParameter(f"problem: {os.fspath(problem)} is not a [linear_rotor] config file (a planar or spatial config: PlanarProblem(path), SpatialModel(path))")
        return _LinearProblem(_autobal.LinearSpec(os.fspath(problem), []))
    return problem

Axes = Union[Mapping[str, Sequence[float]], Sequence[Union[str, Tuple[str, Sequence[float]]]]]


def _axes(axes: Axes) -> List[Tuple[str, List[float]]]:
    """``{path: values}``, ``[(path, values)]`` or ``["path=lo:hi:n", ...]`` as ``[(path, values)]``."""
    items = axes.items() if isinstance(axes, Mapping) else axes
    out: List[Tuple[str, List[float]]] = []
    for a in items:
        if isinstance(a, str):
            out.append(_autobal.parse_axis(a))
        else:
            path, values = a
            out.append((str(path), [float(v) for v in np.atleast_1d(np.asarray(values, dtype=float))]))
    return out


def grid(axes: Axes) -> np.ndarray:
    """The points of a grid, one row per point (points × axes), the first axis varying
    fastest, as ``autobal sweep`` numbers them.

    >>> grid({"drive.b": [1.0, 2.0], "planar.c_psi": [0.1, 0.2]}).tolist()
    [[1.0, 0.1], [2.0, 0.1], [1.0, 0.2], [2.0, 0.2]]
    """
    return _autobal.grid_points(_axes(axes))


def _kind(problem: Any) -> str:
    """``"spatial"`` for a :class:`SpatialModel`, ``"planar"`` for a :class:`PlanarProblem`,
    ``"linear"`` for a linear rotor config."""
    cfg = getattr(problem, "_cfg", None)
    if isinstance(cfg, _autobal.LinearSpec):
        return "linear"
    if isinstance(cfg, _autobal.SpatialConfig):
        return "spatial"
    if isinstance(cfg, _autobal.PlanarConfig):
        return "planar"
    raise InvalidParameter(f"problem: expected an autobal.PlanarProblem, an autobal.SpatialModel or the path of a [linear_rotor] config, got {type(problem).__name__}")


def columns(problem: Problem) -> List[str]:
    """The summary columns of ``problem``'s runs: ``SUMMARY_COLUMNS`` (planar, ending in
    ``outcome`` (0 not settled, 1 not balanced, 2 partially balanced, 3 balanced) and
    ``residual_unbalance``) or ``SPATIAL_SUMMARY_COLUMNS`` (spatial: the planar ones, then
    ``residual_couple`` (NaN without a couple unbalance), ``static_sag`` (NaN where the run
    has no sag)) or
    ``LINEAR_SUMMARY_COLUMNS`` (a linear rotor: the first balancer plane's ``peak_amplitude``
    with ``omega_at_peak``, ``t_at_peak``, ``peak_any_node`` with ``omega_at_peak_any_node``,
    ``final_amplitude`` (m), ``completed``, ``t_reached``, ``steps``: the CLI's sweep
    columns)."""
    return _columns(_kind(_problem(problem)))


def _columns(kind: str) -> List[str]:
    """:func:`columns` of a problem of ``kind`` (:func:`_kind`)."""
    if kind == "linear":
        return list(_autobal.LINEAR_SUMMARY_COLUMNS)
    return list(_autobal.SPATIAL_SUMMARY_COLUMNS if kind == "spatial" else _autobal.SUMMARY_COLUMNS)


def simulate_batch(problem: Problem, paths: Sequence[str], params: Any, threads: Optional[int] = None) -> np.ndarray:
    """Run one simulation per row of ``params`` (points × ``len(paths)``), each the problem
    with ``paths`` set to the row's values, in parallel in Rust (``threads``, default all
    cores) with the GIL released. Returns points × :func:`columns` (``SUMMARY_COLUMNS`` for a
    :class:`PlanarProblem`, ``SPATIAL_SUMMARY_COLUMNS`` for a :class:`SpatialModel`); the same
    bits whatever the number of threads or chunks.

    For a :class:`SpatialModel` (a config with ``[drive]``; without one, the default run-up)
    the paths are the config's keys (``balancer.ball_mass``, ``drive.omega0``,
    ``dimensionless.z_a``, ``drive.psi0[2]`` for one element of an array), and a row is
    exactly ``autobal simulate`` of the config with those keys set. For a linear rotor (the
    path of a ``[linear_rotor]`` config) the paths are its parameter paths
    (``linear_rotor.ball_mass``, ``linear_rotor.balancer[0].drag``, ``drive.b``, ...), and a
    row is ``autobal sweep``'s run of that point."""
    resolved = _problem(problem)
    p = np.require(np.asarray(params, dtype=float), requirements=["C", "A"])
    if p.ndim == 1 and len(paths) == 1:
        p = p.reshape(-1, 1)
    if p.ndim != 2:
        raise InvalidParameter(f"params: expected a 2-D array (points × {len(paths)} paths), got shape {p.shape}")
    return _autobal.simulate_batch(resolved._cfg, list(paths), p, threads)


def _run_chunk(kind: str, problem_toml: Any, paths: List[str], params: np.ndarray, threads: Optional[int]) -> np.ndarray:
    """One chunk on a worker: the problem (``kind``: planar, spatial or linear) from its TOML
    (a linear rotor's: ``(toml, {file name: bytes})``), then a batch."""
    cfg: Union[_autobal.LinearSpec, _autobal.PlanarConfig, _autobal.SpatialConfig]
    if kind == "linear":
        text, files = problem_toml
        cfg = _autobal.LinearSpec.from_parts(text, files)
    else:
        make = _autobal.spatial_config if kind == "spatial" else _autobal.planar_config
        cfg = make(problem_toml, None, "sweep", [])
    # arrays unpickled on a worker may be unaligned views of the message buffer
    return _autobal.simulate_batch(cfg, paths, np.require(params, dtype=float, requirements=["C", "A"]), threads)


def _write_atomic(path: Path, write) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=path.name, suffix=".tmp")
    os.close(fd)
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


class _Parts:
    """Finished chunks on disk: ``DIR/manifest.json`` (what the sweep is) and one
    ``chunk-NNNNNN.npy`` per chunk (written whole or not at all)."""

    def __init__(self, directory: Path, manifest: Dict[str, Any], resume: bool) -> None:
        self.dir = directory
        self.dir.mkdir(parents=True, exist_ok=True)
        manifest = json.loads(json.dumps(manifest))  # as it reads back (tuples become lists)
        mpath = self.dir / "manifest.json"
        if mpath.exists():
            old = json.loads(mpath.read_text())
            if not resume:
                for f in self.dir.glob("chunk-*.npy"):
                    f.unlink()
            elif old != manifest:
                raise InvalidParameter(
                    f"out: {self.dir} holds parts of a different sweep (problem, axes or chunk size differ); "
                    "give another out, or resume=False to start over"
                )
        _write_atomic(mpath, lambda t: Path(t).write_text(json.dumps(manifest, indent=1)))

    def path(self, i: int) -> Path:
        return self.dir / f"chunk-{i:06d}.npy"

    def done(self, i: int) -> bool:
        return self.path(i).exists()

    def save(self, i: int, a: np.ndarray) -> None:
        def w(t: str) -> None:
            with open(t, "wb") as f:
                np.save(f, a)

        _write_atomic(self.path(i), w)

    def load(self, i: int) -> np.ndarray:
        return np.load(self.path(i))


def _table(points: np.ndarray, paths: List[str], results: np.ndarray, names: List[str]) -> Dict[str, np.ndarray]:
    cols: Dict[str, np.ndarray] = {"point": np.arange(len(points), dtype=np.int64)}
    for j, p in enumerate(paths):
        cols[p] = points[:, j]
    for j, c in enumerate(names):
        cols[c] = results[:, j]
    return cols


def _write_table(cols: Dict[str, np.ndarray], out: Path) -> None:
    if out.suffix == ".parquet":
        import pandas as pd

        _write_atomic(out, lambda t: pd.DataFrame(cols).to_parquet(t, index=False))
        return
    names = list(cols)
    data = np.column_stack([cols[n].astype(float) for n in names]) if len(cols[names[0]]) else np.zeros((0, len(names)))

    def w(t: str) -> None:
        with open(t, "w") as f:
            f.write(",".join(names) + "\n")
            # %.17g: every double round-trips exactly; integers print as integers
            np.savetxt(f, data, fmt="%.17g", delimiter=",")

    _write_atomic(out, w)


def sweep(
    problem: Problem,
    axes: Axes,
    *,
    out: Union[None, str, "os.PathLike[str]"] = None,
    client: Any = None,
    chunk_size: Optional[int] = None,
    resume: bool = True,
    threads: Optional[int] = None,
) -> Any:
    """Run the problem at every point of the grid ``axes`` (``{path: values}``, or
    ``["drive.b=0.5:12.5:5", ...]``; the first axis varies fastest) and return the table:
    ``point``, the paths, the summary's :func:`columns` — a pandas DataFrame when pandas is
    installed, else a dict of arrays.

    ``problem``: a :class:`PlanarProblem` (paths such as ``planar.c_psi``, ``drive.b``) or a
    :class:`SpatialModel` of a config with ``[drive]`` (paths: the config's keys, such as
    ``balancer.ball_mass``, ``drive.omega0``, ``dimensionless.z_a``; see :func:`simulate_batch`),
    or the path of a ``[linear_rotor]`` config file (paths: ``linear_rotor.ball_mass``,
    ``linear_rotor.balancer[0].drag``, ``drive.b``, ...; its matrix files read here once and
    sent to the workers with the config's text), or a dict of any of these configs' tables (a
    ``[linear_rotor]`` one's matrix files read relative to the working folder; the tables
    sent to the workers as TOML text).

    - ``client``: a ``dask.distributed.Client``; the grid is cut into chunks of ``chunk_size``
      points, each submitted as one :func:`simulate_batch` call (``threads`` per task, default
      1: Dask runs the tasks in parallel). Without a client, the chunks run here on all cores.
    - ``out``: ``NAME.csv`` or ``NAME.parquet`` for the table. Chunks are written to
      ``NAME.parts/`` as they arrive; an interrupted sweep (Ctrl-C, a lost worker) keeps them,
      and the same call resumes, running only the missing chunks (``resume=False`` starts
      over). The table is written when every chunk is done.

    The results are the same bits whatever the client, workers, chunks or threads.
    """
    resolved = _problem(problem)
    kind = _kind(resolved)
    names = _columns(kind)
    ax = _axes(axes)
    paths = [p for p, _ in ax]
    points = _autobal.grid_points(ax)
    n = len(points)
    if chunk_size is None:
        workers = len(client.scheduler_info().get("workers", {})) if client is not None else 1
        chunk_size = max(1, min(4096, -(-n // max(1, 8 * workers)))) if client is not None else max(1, min(n, 4096))
    if chunk_size < 1:
        raise InvalidParameter(f"chunk_size: must be at least 1, got {chunk_size}")
    chunks = [(i, i * chunk_size, min(n, (i + 1) * chunk_size)) for i in range(-(-n // chunk_size))]
    toml = resolved.toml
    parts: Optional[_Parts] = None
    table_path: Optional[Path] = None
    if out is not None:
        table_path = Path(out)
        if table_path.suffix not in (".csv", ".parquet"):
            raise InvalidParameter(f"out: {table_path} must end in .csv or .parquet")
        manifest = {"problem": toml, "axes": ax, "chunk_size": chunk_size, "columns": names}
        if kind == "linear":
            # the matrix files are part of the problem
            manifest["files"] = {k: hashlib.sha256(v).hexdigest() for k, v in sorted(resolved._cfg.files().items())}
        parts = _Parts(table_path.with_suffix(".parts"), manifest, resume)
    results: Dict[int, np.ndarray] = {}
    todo = []
    for i, lo, hi in chunks:
        if parts is not None and parts.done(i):
            results[i] = parts.load(i)
        else:
            todo.append((i, lo, hi))
    # every point is checked before anything runs (errors name the path and the point)
    _autobal.check_batch(resolved._cfg, paths, points)
    if client is None:
        for i, lo, hi in todo:
            r = _autobal.simulate_batch(resolved._cfg, paths, points[lo:hi], threads)
            results[i] = r
            if parts is not None:
                parts.save(i, r)
    else:
        from dask.distributed import as_completed

        # keys unique to this call: a resumed sweep must not reuse the key of a future that the
        # interrupted call cancelled (the scheduler may still be forgetting it, and would
        # cancel the new one too; `id(points)` had been reused by the next call)
        run = uuid.uuid4().hex
        payload: Any = (toml, dict(resolved._cfg.files())) if kind == "linear" else toml
        futures = {
            client.submit(_run_chunk, kind, payload, paths, points[lo:hi], threads or 1, pure=False, key=f"autobal-sweep-{run}-{i}"): i
            for i, lo, hi in todo
        }
        try:
            for fut in as_completed(list(futures)):
                i = futures[fut]
                r = fut.result()
                results[i] = r
                if parts is not None:
                    parts.save(i, r)
        except BaseException:
            client.cancel(list(futures))
            raise
    res = np.concatenate([results[i] for i, _, _ in chunks]) if chunks else np.zeros((0, len(names)))
    cols = _table(points, paths, res, names)
    if table_path is not None:
        _write_table(cols, table_path)
    try:
        import pandas as pd
    except ImportError:
        return cols
    return pd.DataFrame(cols)
