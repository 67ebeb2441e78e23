"""``autobal.sweep`` of a dict of config tables, in-process and on a Dask cluster of processes
(issues 19/20: the Dask sweep took a config file, not a dict). The dict travels to the workers
as TOML text; a ``[linear_rotor]`` dict naming matrix files is read here, relative to the
working folder (as ``autobal.run`` reads a dict's), and its files travel as bytes: the workers,
started in another folder, never open them. Every table is compared bit for bit with the sweep
of the same config given as a file (the runs are deterministic: any difference is a different
problem reaching the workers)."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

import autobal

ROOT = Path(__file__).resolve().parents[3]
tomllib = pytest.importorskip("tomllib")


def _cluster():
    pytest.importorskip("pandas")
    pytest.importorskip("dask")
    distributed = pytest.importorskip("distributed")
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None)
    return cluster, distributed.Client(cluster)


def _bytes(table) -> bytes:
    return table.to_numpy().tobytes()


@pytest.mark.parametrize(
    "example, short, axes",
    [
        # paper 004's passage cut short
        ("planar.toml", {"drive": {"t_end": 1.0, "omega0": 250.0, "b": 100.0}}, {"planar.c_psi": [0.05, 0.1, 0.15], "drive.b": [80.0, 120.0]}),
        # the spatial rotor of papers 000/003 (no [planar]: the spatial model)
        ("spatial.toml", {"drive": {"t_end": 5.0}}, {"drive.omega0": [1.5, 1.6], "dimensionless.m": [0.04, 0.05]}),
    ],
)
def test_dask_sweep_of_a_dict_equals_the_models_and_the_serial_sweep(tmp_path, example, short, axes):
    tables = tomllib.loads((ROOT / "examples" / example).read_text())
    for t, keys in short.items():
        tables.setdefault(t, {}).update(keys)
    # the same tables as the model they make: the reference
    model = autobal.PlanarProblem(tables) if "planar" in tables else autobal.SpatialModel(tables)
    want = autobal.sweep(model, axes)
    serial = autobal.sweep(tables, axes)
    assert list(serial.columns) == ["point", *axes, *autobal.columns(model)]
    assert _bytes(serial) == _bytes(want)
    cluster, client = _cluster()
    with cluster, client:
        got = autobal.sweep(tables, axes, client=client, chunk_size=1, out=tmp_path / "d.csv")
    assert _bytes(got) == _bytes(want)
    assert len(list((tmp_path / "d.parts").glob("chunk-*.npy"))) == len(got)


def short_matrix_config(tmp_path: Path) -> Path:
    """The shaft example exported as Matrix Market files beside its config, with a short
    run-up (as test_linear_rotor_results.py builds it)."""
    autobal.export_model(str(ROOT / "examples" / "linear_rotor_shaft.toml"), out=tmp_path / "model", stem="shaft")
    cfg = tmp_path / "model" / "shaft.toml"
    cfg.write_text(cfg.read_text() + '\n[drive]\nkind = "acceleration"\nomega0 = 300.0\nb = 1000.0\nt_end = 0.1\n\n[integration]\ndt = 0.002\n')
    return cfg


def test_dask_sweep_of_a_linear_dict_ships_its_matrix_files(tmp_path, monkeypatch):
    cfg = short_matrix_config(tmp_path)
    tables = tomllib.loads(cfg.read_text())
    axes = {"linear_rotor.ball_mass": [0.02, 0.03], "linear_rotor.balancer[0].drag": [0.1, 0.2]}
    want = autobal.sweep(str(cfg), axes)
    assert list(want.columns) == ["point", *axes, *autobal._autobal.LINEAR_SUMMARY_COLUMNS]
    # the workers start in this folder, which holds no matrix file
    monkeypatch.chdir(tmp_path)
    cluster, client = _cluster()
    with cluster, client:
        here = os.getcwd()
        assert set(client.run(os.getcwd).values()) == {here}
        with pytest.raises(autobal.AutobalError, match="shaft_M.mtx"):
            autobal.sweep(tables, axes, client=client)
        # from the files' folder the dict is the file's config: its files read here, sent as bytes
        monkeypatch.chdir(cfg.parent)
        serial = autobal.sweep(tables, axes)
        got = autobal.sweep(tables, axes, client=client, chunk_size=1, out=tmp_path / "d.csv")
    assert _bytes(serial) == _bytes(want)
    assert _bytes(got) == _bytes(want)
    assert len(list((tmp_path / "d.parts").glob("chunk-*.npy"))) == 4
    # the points differ: the axes reach the workers' runs
    assert not np.array_equal(got["peak_amplitude"].to_numpy()[:1], got["peak_amplitude"].to_numpy()[1:2])
