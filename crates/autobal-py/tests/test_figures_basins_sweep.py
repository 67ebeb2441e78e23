"""`.plot()` of `basins` and `sweep` on a spatial config: the figures of
`autobal_commands::figures_api` (the report's basins figure, the sweep's peak and final whirl
radius), as Plotly figures, with a trace per value of the sweep's other axis."""

from __future__ import annotations

from pathlib import Path

import pytest

import autobal

go = pytest.importorskip("plotly.graph_objects")

SPATIAL = str(Path(__file__).resolve().parents[3] / "examples" / "spatial.toml")
SHORT = {"drive.t_end": 10.0}  # tiny runs: the figures' plumbing, not the physics


def test_basins_plot_is_the_grid_of_runs():
    r = autobal.analyse("basins", SPATIAL, set=SHORT, n=2)
    assert "basins" in autobal.COMMANDS_WITH_FIGURES
    fig = r.plot()
    assert isinstance(fig, go.Figure)
    assert list(r.figures()) == ["basins"]
    assert len(fig.data) == 1 and fig.data[0].type == "heatmap"
    # a cell per run: balanced -1, not +1, in the grid's 2 x 2 cells
    z = [v for row in fig.data[0].z for v in row]
    assert len(z) == 4
    assert sum(v == -1 for v in z) == r.result["balanced"]


def test_sweep_plot_has_a_curve_per_value_of_the_other_axis():
    r = autobal.analyse("sweep", SPATIAL, set=SHORT, x="drive.omega0=1.5,1.6", y="drive.t_end=5,10")
    assert set(r.figures()) == {"sweep_peak", "sweep_final"}
    fig = r.plot()
    assert isinstance(fig, go.Figure)
    assert len(fig.data) == 2, "a curve per value of drive.t_end"
    # each point a run: the first axis' value, the run's peak whirl radius (rho_s: factor 1)
    # (the Plotly JSON keeps 6 significant digits: a relative rounding error of at most 5e-6)
    runs = r.result["runs"]
    assert list(fig.data[0].x) == [run["values"][0] for run in runs[:2]]
    assert list(fig.data[0].y) == pytest.approx([run["summary"]["peak_amplitude"] for run in runs[:2]], rel=5e-6)
    final = r.plot("sweep_final")
    assert list(final.data[1].y) == pytest.approx([run["summary"]["final_amplitude"] for run in runs[2:]], rel=5e-6)
