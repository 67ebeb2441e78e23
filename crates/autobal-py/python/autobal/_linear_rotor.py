"""The run in time of a :class:`autobal.LinearRotor` (issue 19, docs/guide/your-own-rotor.md):
``LinearRotor.simulate()`` returns a :class:`LinearSimulation`, a :class:`autobal.Result` of
``simulate`` whose samples are the CLI's CSV (``autobal simulate --config FILE``), column for
column and bit for bit, and whose figures are the SVGs the CLI writes beside it.
"""

from __future__ import annotations

import io
import json
import os
from typing import Any, Dict, List, Mapping, Optional, Tuple

import numpy as np

from . import _autobal
from ._results import Result, _figure_options
from .errors import SimulationError


class LinearSimulation(Result):
    """A linear rotor's run in time (:meth:`autobal.LinearRotor.simulate`).

    ``columns`` (also ``arrays``): 1-D arrays named as the CLI's CSV columns, in its order:
    ``t`` (s), ``omega`` (rad/s), per balancer plane ``i`` its race centre ``x_i``, ``y_i`` (m,
    fixed axes) and radius ``r_i``, ``r_max`` (the largest translation radius of any node), the
    balls' angles ``psi_j`` (rad, relative to the rotor); ``summary`` (also ``result``): the
    dict ``autobal simulate --format json`` prints. ``.plot(name)``: the figures
    ``simulation_amplitude_omega`` (the main one), ``simulation_amplitude_t``,
    ``simulation_psi_t``, ``simulation_omega_t``; ``.to_pandas()``: the samples.
    """

    def __init__(self, columns: Dict[str, np.ndarray], summary: Dict[str, Any], figures: List[Dict[str, Any]]) -> None:
        super().__init__("simulate", summary, (None, None, "", []), {}, columns)
        self.columns = columns
        self.summary = summary
        self._figures = {f["id"]: f["figure"] for f in figures}

    def figures(self) -> Dict[str, Dict[str, Any]]:
        """The figures by id, as Plotly JSON (the CLI's SVGs' descriptions)."""
        assert self._figures is not None
        return self._figures

    def to_pandas(self) -> Any:
        """The samples as a pandas DataFrame with the CLI's CSV columns (needs pandas)."""
        import pandas as pd

        return pd.DataFrame(self.columns)

    def __repr__(self) -> str:
        s = self.summary
        return (
            f"LinearSimulation({len(self.columns['t'])} samples to t = {s['t_end_reached']:.4g} s, "
            f"peak radius {1e3 * s['peak_radius']:.4g} mm at ω = {s['peak_omega']:.4g} rad/s)"
        )


class LinearConfigResult(Result):
    """The result of a command on a ``[linear_rotor]`` config file (:func:`autobal.analyse`):
    ``.result`` what :func:`autobal.run` returns (the CLI's JSON; ``map``'s cells as arrays).

    Figures (``.plot(name)``, ``.figures()``): ``stability``: ``stability_margin`` (what
    ``autobal stability --svg`` draws); ``map``: ``stability_map`` (what ``autobal map --out``
    draws, computed on the first call by the CLI's ``map`` on the same file, ``x`` and ``y``
    as ``KEY=LO:HI:N``); ``sweep``: ``sweep_peak`` and ``sweep_final`` (the first balancer
    plane's peak and final whirl radius against the first axis, one curve per value of the
    others); ``basins``: ``basins`` (each run's end over the first two balls' initial angles,
    as the report draws the spatial rotor's basins). Tables (``.to_pandas()``): ``map``: one
    row per cell as the CLI's CSV columns (``margin``, ``verdict``, ``family_dimension``, ``state``);
    ``sweep``: one row per run; ``basins``: the CLI's CSV; ``stability``: the margin per speed.
    """

    def __init__(self, command: str, result: Dict[str, Any], path: Any, sets: Any, options: Dict[str, Any], extra: Dict[str, Any]) -> None:
        name = "dict" if isinstance(path, Mapping) else str(path)
        super().__init__(command, result, (None, None, name, list((sets or {}).items())), options, result if command == "map" else None)
        # a file, or a dict of tables (its matrix files relative to the working folder)
        self._path: Optional[str] = None if isinstance(path, Mapping) else os.fspath(path)
        self._dict: Optional[Dict[str, Any]] = dict(path) if isinstance(path, Mapping) else None
        self._sets = list((sets or {}).items())
        figs = extra.get("figures")
        if figs is not None:
            self._figures = {f["id"]: f["figure"] for f in figs}
        self._csv = extra.get("csv")

    def figures(self) -> Dict[str, Dict[str, Any]]:
        """The figures by id, as Plotly JSON (module docs of the class)."""
        if self._figures is None:
            if self.command == "map":
                raw = _autobal.linear_rotor_map_figures(self._path, self._sets, _figure_options("map", self._options), self._dict)
                self._figures = {f["id"]: f["figure"] for f in json.loads(raw)}
            else:
                self._figures = {}
        return self._figures

    def plot(self, name: Optional[str] = None) -> Any:
        if not self.figures():
            raise ValueError(f"{self.command} on a linear rotor config draws no figure (figures: stability, map, sweep, basins, simulate); its table: .to_pandas()")
        return super().plot(name)

    def to_pandas(self) -> Any:
        import pandas as pd

        r, c = self.result, self.command
        if c == "map":
            xs, ys = np.meshgrid(r["x"], r["y"])
            return pd.DataFrame(
                {
                    r["x_path"]: xs.ravel(),
                    r["y_path"]: ys.ravel(),
                    "margin": r["margin"].ravel(),
                    "verdict": np.asarray(r["verdict"], dtype=object).ravel(),
                    "family_dimension": np.asarray(r["family_dimension"], dtype=object).ravel(),
                    "state": np.asarray(r["state"], dtype=object).ravel(),
                }
            )
        if c == "basins":
            return pd.read_csv(io.StringIO(self._csv or ""))
        return super().to_pandas()

    def _summary_rows(self) -> List[Tuple[str, Any]]:
        if self.command == "sweep":
            r = self.result
            return [("model", "linear"), ("paths", ", ".join(r.get("paths", []))), ("runs", len(r.get("runs", []))), ("complete", r.get("complete"))]
        return super()._summary_rows()


def _simulation(columns: Dict[str, np.ndarray], summary: str, figures: str) -> LinearSimulation:
    """The result object of a run (called by the extension module), or :class:`SimulationError`
    (``.result``: the run up to then) when it stopped before its end."""
    sim = LinearSimulation(columns, json.loads(summary), json.loads(figures))
    if sim.summary.get("stopped"):
        e = SimulationError(f"{sim.summary['stopped']}: the samples up to then are in .result")
        e.result = sim
        raise e
    return sim


__all__ = ["LinearSimulation", "LinearConfigResult"]
