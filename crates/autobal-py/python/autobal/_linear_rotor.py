"""The run in time of a :class:`autobal.LinearRotor` (issue 19, docs/guide/your-own-rotor.md):
``LinearRotor.simulate()`` returns a :class:`LinearSimulation`, a :class:`autobal.Result` of
``simulate`` whose samples are the CLI's CSV (``autobal simulate --config FILE``), column for
column and bit for bit, and whose figures are the SVGs the CLI writes beside it.
"""

from __future__ import annotations

import json
from typing import Any, Dict, List

import numpy as np

from ._results import Result
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


def _simulation(columns: Dict[str, np.ndarray], summary: str, figures: str) -> LinearSimulation:
    """The result object of a run (called by the extension module), or :class:`SimulationError`
    (``.result``: the run up to then) when it stopped before its end."""
    sim = LinearSimulation(columns, json.loads(summary), json.loads(figures))
    if sim.summary.get("stopped"):
        e = SimulationError(f"{sim.summary['stopped']}: the samples up to then are in .result")
        e.result = sim
        raise e
    return sim


__all__ = ["LinearSimulation"]
