"""Result objects: one command's result with its figures, its table and its rich display.

:func:`analyse` runs a command as :func:`autobal.run` does and wraps what ``run`` returns
(``.result``, equal to ``autobal COMMAND --format json``) in a :class:`Result`:

- ``.plot(name=None)``: a ``plotly.graph_objects.Figure`` built from the figure description the
  CLI draws as SVG and the report draws with Plotly (the same Plotly JSON, computed in Rust by
  ``autobal_commands::figures_api``); ``.figures()`` lists them by id;
- ``.to_pandas()``: the result's table (critical speeds, ranges, the margin over speed, the
  Campbell lines, the map's cells, a run's samples, a sweep's runs, the basins' runs);
- ``_repr_html_``: a summary table and the main figure, for Jupyter.

:func:`report` writes the HTML report (``autobal report``) and returns a :class:`Report`, whose
``.plot(id)`` gives each figure of the page from the page's own data.
"""

from __future__ import annotations

import html
import json
import os
import re
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

from . import _autobal

#: Every command of the ``autobal`` command line (from the CLI's own argument parser).
COMMANDS: List[str] = list(_autobal.COMMANDS)
#: The commands whose results have figures (``.plot()``).
COMMANDS_WITH_FIGURES: List[str] = list(_autobal.COMMANDS_WITH_FIGURES)

# the options that change each command's figures, as the CLI's flags (figures_api::Options)
_FIGURE_OPTIONS: Dict[str, Tuple[str, ...]] = {
    "stability": ("omega_max", "samples", "balls", "route"),
    "campbell": ("omega_max", "points", "balls", "harmonics", "route"),
    "map": ("x", "y", "omega", "balls", "quantity", "boundary", "route"),
    "simulate": ("dt",),
    "sweep": ("x", "y", "axis", "shard"),
    "basins": ("n",),
}


def _figure_options(command: str, options: Mapping[str, Any]) -> str:
    out: Dict[str, Any] = {}
    for k in _FIGURE_OPTIONS.get(command, ()):
        v = options.get(k)
        if v is None:
            continue
        if k in ("omega_max", "omega"):
            v = v if isinstance(v, str) else repr(float(v))
        if k in ("x", "y") and not isinstance(v, str):
            raise TypeError(f"{k}: the {command}'s figure takes the axis as text, 'KEY=LO:HI:N' (as the CLI's --{k})")
        if k == "axis":
            v = [str(a) for a in v]
        if k == "shard":
            v = str(v)
        out[k] = v
    return json.dumps(out)


def _go() -> Any:
    try:
        import plotly.graph_objects as go
    except ImportError:
        raise ImportError("plotting needs plotly: pip install 'autobal[plot]' (or pip install plotly)") from None
    return go


def _scalars(d: Mapping[str, Any], prefix: str = "", depth: int = 0) -> List[Tuple[str, Any]]:
    """The numbers, strings and booleans of ``d`` as ``(key.path, value)``, nested tables
    flattened two levels deep."""
    rows: List[Tuple[str, Any]] = []
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, Mapping) and depth < 1:
            rows.extend(_scalars(v, key + ".", depth + 1))
        elif isinstance(v, (int, float, str, bool)) or v is None:
            rows.append((key, v))
    return rows


_PLOTLYJS_SENT = False


class Result:
    """The result of one command (:func:`analyse`).

    ``command``: its name; ``result``: what :func:`autobal.run` returns for it (for every command
    but ``map``, the dict ``autobal COMMAND --format json`` prints; for ``merge`` and
    ``export-model``, which print a line, their JSON: the merged ``STEM.json``,
    ``{"files": [...]}``); ``arrays``: per-sample or per-run arrays where the command has them
    (``simulate``'s columns, ``basins``' runs); ``files``: the paths a command that writes files
    wrote (``merge``, ``export-model``; else empty). ``result[key]`` reads the result.
    """

    def __init__(
        self,
        command: str,
        result: Dict[str, Any],
        config: Tuple[Optional[str], Optional[dict], str, List[Tuple[str, Any]]],
        options: Mapping[str, Any],
        arrays: Optional[Dict[str, Any]] = None,
        files: Sequence[Path] = (),
    ) -> None:
        self.command = command
        self.result = result
        self.arrays = arrays
        self.files: List[Path] = list(files)
        self._config = config
        self._options = dict(options)
        self._figures: Optional[Dict[str, Dict[str, Any]]] = None

    def __getitem__(self, key: str) -> Any:
        return self.result[key]

    def __repr__(self) -> str:
        return f"<autobal.Result {self.command}: {len(self.result)} keys{', figures: ' + ', '.join(self.figures()) if self._figures else ''}>"

    # -- figures -----------------------------------------------------------------------------
    def figures(self) -> Dict[str, Dict[str, Any]]:
        """The figures of this result by id, each the Plotly JSON ``{"data", "layout"}`` of the
        CLI's and the report's figure description (computed on the first call, then kept; an
        empty dict for a command without figures)."""
        if self._figures is None:
            if self.command not in COMMANDS_WITH_FIGURES:
                self._figures = {}
            else:
                text, table, source, sets = self._config
                raw = _autobal.figures(self.command, text, table, source, sets, _figure_options(self.command, self._options))
                self._figures = {f["id"]: f["figure"] for f in json.loads(raw)}
        return self._figures

    def plot(self, name: Optional[str] = None) -> Any:
        """The figure ``name`` (default: the main one, the first of :meth:`figures`) as a
        ``plotly.graph_objects.Figure`` (needs plotly: ``pip install 'autobal[plot]'``)."""
        figs = self.figures()
        if not figs:
            raise ValueError(f"{self.command} draws no figure (figures: {', '.join(COMMANDS_WITH_FIGURES)}); its table: .to_pandas()")
        if name is None:
            name = next(iter(figs))
        if name not in figs:
            raise KeyError(f"{name}: not a figure of {self.command} (figures: {', '.join(figs)})")
        return _go().Figure(figs[name])

    # -- tables ------------------------------------------------------------------------------
    def to_pandas(self) -> Any:
        """The result's table as a pandas DataFrame (needs pandas):

        - ``critical``: one row per critical speed (on the general route, per locked critical
          speed); ``ranges``: one row per range (``kind`` ``autobalancing_ranges``,
          ``instability_ranges`` (003's, where defined) or ``exact_stable_ranges``, ``from``,
          ``to``); ``stability``: the largest real part of the eigenvalues (on the general
          route, of the Floquet exponents of a periodic orbit) per speed (``omega``,
          ``max_real_part``; the general route adds ``verdict``, ``state`` and ``residual``, the residual unbalance the
          balls leave as a fraction of what the JSON's ``residual_scale`` names (the unbalance, a
          linear rotor's static one; the balls' capacity where the unbalance is below 1e-6 of
          it; a planar rotor's race-centre offset without the balls); ``state`` is ``balanced`` for a residual at most 1e-6, or on a periodic orbit at
          most 0.1 where a balanced state exists, ``partially_balanced`` where none exists);
        - ``campbell``: one row per speed and tracked line (``omega``, ``line`` and the mode's
          fields; on the general route, the speeds where the line has a point); ``map``: one
          row per cell, as the CLI's CSV;
        - ``simulate``: the samples (the CLI's CSV columns); ``sweep`` and ``merge``: one row
          per run; ``basins``: one row per run (the CLI's CSV).

        ``inertia`` and ``export-model`` have no table (their results are a few numbers, or
        the files written: ``.result``, ``.files``)."""
        import pandas as pd

        r, c = self.result, self.command
        general = isinstance(r, Mapping) and r.get("route") == "general"
        if c == "critical":
            if general:
                speeds = (r.get("locked_critical_speeds") or {}).get("speeds") or []
                return pd.DataFrame(speeds) if speeds else pd.DataFrame(columns=["omega", "multiplicity", "motion", "whirl"])
            return pd.DataFrame(r["critical_speeds"])
        if c == "ranges":
            rows = [
                {"kind": kind, "from": lo, "to": hi}
                for kind in ("autobalancing_ranges", "instability_ranges")
                for lo, hi in (r.get(kind) or [])
            ]
            # the exact ranges: pairs on the closed-form route, {"from", "to", ...} on the general
            for e in (r.get("exact") or {}).get("stable_ranges") or []:
                lo, hi = (e["from"], e["to"]) if isinstance(e, Mapping) else (e[0], e[1])
                rows.append({"kind": "exact_stable_ranges", "from": lo, "to": hi})
            return pd.DataFrame(rows, columns=["kind", "from", "to"])
        if c == "stability":
            if general:
                return pd.DataFrame(
                    [
                        {"omega": p["omega"], "max_real_part": p.get("abscissa"), "verdict": p.get("verdict"), "state": p.get("state"), "residual": p.get("residual")}
                        for p in r["points"]
                    ],
                    columns=["omega", "max_real_part", "verdict", "state", "residual"],
                )
            return pd.DataFrame(r["max_real_part"], columns=["omega", "max_real_part"])
        if c == "campbell":
            if general:
                return pd.DataFrame([{"line": i, **p} for i, line in enumerate(r["lines"]) for p in line["points"] if p is not None])
            rows = [
                {"omega": w, "line": i, **m}
                for i, line in enumerate(r["lines"])
                for w, m in zip(r["omega"], line["modes"])
            ]
            return pd.DataFrame(rows)
        if c == "map":
            import numpy as np

            xs, ys = np.meshgrid(r["x"], r["y"])
            # the CLI CSV's name: ``max_real_part_per_tau`` on a dimensional spatial config
            cols = {r["x_path"]: xs.ravel(), r["y_path"]: ys.ravel(), r.get("margin_column", "max_real_part"): r["margin"].ravel()}
            if "necessary" in r:
                cols.update(stable=r["stable"].ravel(), necessary=r["necessary"].ravel())
            else:
                # the general route's CSV columns
                cols.update(verdict=r["verdict"].ravel(), family_dimension=r["family_dimension"].ravel(), state=r["state"].ravel())
            return pd.DataFrame(cols)
        if c == "simulate" and self.arrays is not None:
            data = {k: v for k, v in self.arrays.items() if k != "psi"}
            # the ball angles of a planar or spatial run are one array (a linear rotor's are
            # columns psi_0 ... already)
            psi = self.arrays.get("psi")
            if psi is not None:
                for j in range(psi.shape[1]):
                    data[f"psi_{j + 1}"] = psi[:, j]
            return pd.DataFrame(data)
        if c in ("sweep", "merge"):
            return pd.json_normalize(r["runs"])
        if c == "basins" and self.arrays is not None:
            return pd.DataFrame({k: self.arrays[k] for k in ("psi_1", "psi_2", "balanced_runs", "residual_unbalance", "final_amplitude")}).rename(
                columns={"balanced_runs": "balanced"}
            )
        if c == "export-model":
            raise TypeError(f"{c} has no table: it writes files ({', '.join(str(p) for p in self.files)}; .files)")
        raise TypeError(f"{c} has no table: its result is a few numbers (.result)")

    # -- Jupyter -----------------------------------------------------------------------------
    def _summary_rows(self) -> List[Tuple[str, Any]]:
        if self.command == "map":
            import numpy as np

            r = self.result
            return [
                ("x", f"{r['x_path']}: {len(r['x'])} values"),
                ("y", f"{r['y_path']}: {len(r['y'])} values"),
                ("stable cells", f"{int(np.sum(r['stable']))} of {r['stable'].size}"),
            ]
        written = [("files", ", ".join(str(p) for p in self.files))] if self.files else []
        return written + _scalars(self.result)

    def _repr_html_(self) -> str:
        global _PLOTLYJS_SENT
        rows = "".join(f"<tr><th style='text-align:left'>{html.escape(k)}</th><td style='text-align:left'>{html.escape(str(v))}</td></tr>" for k, v in self._summary_rows()[:40])
        out = f"<div><b>autobal {html.escape(self.command)}</b><table>{rows}</table>"
        if self.command in COMMANDS_WITH_FIGURES or self._figures:
            try:
                fig = self.plot()
            except ImportError as e:
                out += f"<p>{html.escape(str(e))}</p>"
            else:
                # plotly.js once per session, in the page itself (readable offline)
                out += fig.to_html(full_html=False, include_plotlyjs=not _PLOTLYJS_SENT)
                _PLOTLYJS_SENT = True
        return out + "</div>"


class Report(Result):
    """The HTML report written by :func:`report`: ``path`` (its ``index.html``); ``.figures()``
    every figure of the page by its id, read from the page's own data (what the page draws);
    ``.plot(id)`` one of them as a plotly Figure."""

    def __init__(self, path: str) -> None:
        super().__init__("report", {"index": path}, (None, None, "", []), {})
        self.path = Path(path)

    def figures(self) -> Dict[str, Dict[str, Any]]:
        if self._figures is None:
            page = self.path.read_text(encoding="utf-8")
            found = re.findall(r'<script type="application/json" id="data-([^"]+)">(.*?)</script>', page, flags=re.S)
            self._figures = {fid: json.loads(data) for fid, data in found}
        return self._figures

    def __repr__(self) -> str:
        return f"<autobal.Report {self.path}: {len(self.figures())} figures>"

    def _summary_rows(self) -> List[Tuple[str, Any]]:
        return [("index", str(self.path)), ("figures", ", ".join(self.figures()))]


def report(
    config: Union[None, str, "os.PathLike[str]"] = None,
    out: Union[str, "os.PathLike[str]"] = "autobal-report",
    *,
    set: Optional[Mapping[str, Any]] = None,
    quick: bool = False,
    papers: bool = False,
) -> Report:
    """Write the HTML report to the folder ``out``, as ``autobal report --config CONFIG --out
    OUT`` does (the same code: the same files): about the config's rotor, or the papers'
    reproductions with ``papers=True`` or without a config. ``set``: ``{"table.key": value}``,
    the CLI's ``--set``; ``quick``: shorter runs in time. Ctrl-C stops it (the page is still
    written, marked incomplete, and :class:`KeyboardInterrupt` is raised). A report written
    with a run that failed (a run-up whose integrator stopped on its own: the CLI's exit 2) is
    returned with a :class:`UserWarning` carrying the CLI's line."""
    sets = [f"{k}={_toml_value(v)}" for k, v in (set or {}).items()]
    return Report(_autobal.report(_report_path(config), sets, os.fspath(out), quick, papers))


def _report_path(config: Any) -> Optional[str]:
    """The report's config file, as the CLI's ``--config`` (``None``: the papers' or the
    default); a dict of tables is refused (:class:`TypeError`)."""
    if isinstance(config, Mapping):
        raise TypeError("config: the report reads a TOML file, as the CLI's --config (a dict of tables: write it to a file first)")
    return None if config is None else os.fspath(config)


def _toml_value(v: Any) -> str:
    """``v`` as the CLI's ``--set KEY=VALUE`` reads it (TOML)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"set: {v!r} is not a number, string, bool or list")


__all__: Sequence[str] = ["Result", "Report", "report", "COMMANDS", "COMMANDS_WITH_FIGURES"]
