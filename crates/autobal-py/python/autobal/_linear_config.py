"""``autobal.run`` and ``autobal.analyse`` on a ``[linear_rotor]`` config file or a dict of its
tables (issue 19, "your own rotor"; a dict's matrix files are read relative to the working
folder, ``os.getcwd()``, as ``autobal.export_model`` reads them): ``stability``, ``simulate``,
``map``, ``sweep`` and ``basins`` as the CLI computes them, through ``_autobal.linear_rotor_run`` (the commands crate's functions, with the GIL
released and Ctrl-C stopping the work)."""

from __future__ import annotations

import json
import os
import re
from pathlib import Path
from typing import Any, Dict, Mapping, Optional, Tuple

import numpy as np

from . import _autobal

_TABLE = re.compile(r"^\s*\[\[?\s*linear_rotor\s*[.\]]", re.MULTILINE)


def is_linear(config: Any) -> bool:
    """Whether ``config`` is the path of a TOML file with a ``[linear_rotor]`` table, or a dict
    of tables with a ``linear_rotor`` table (its matrix files named relative to the working
    folder)."""
    if isinstance(config, Mapping):
        return "linear_rotor" in config
    if not isinstance(config, (str, os.PathLike)):
        return False
    p = Path(config)
    try:
        if not p.is_file() or p.stat().st_size > 1 << 20:
            return False
        return bool(_TABLE.search(p.read_text(encoding="utf-8", errors="replace")))
    except OSError:
        return False


def run(command: str, config: Any, set: Optional[Mapping[str, Any]] = None, **options: Any) -> Dict[str, Any]:
    """The dict ``autobal COMMAND --config CONFIG --format json`` prints (``map``: the axes'
    values, ``margin`` (1/s, NaN without a balanced state) and ``stable`` as arrays
    ``len(y) × len(x)``, ``verdict`` as lists, the bisected ``boundary`` points with
    ``boundary=True``: ``x``, ``y``, ``from``, ``to``, ``along``, the axis bisected, and ``rtol``,
    the relative tolerance in that axis to which the point is located)."""
    return run_with_extra(command, config, set, **options)[0]


def run_with_extra(command: str, config: Any, set: Optional[Mapping[str, Any]] = None, **options: Any) -> Tuple[Dict[str, Any], Dict[str, Any]]:
    """:func:`run`'s dict, and what the result object draws and tabulates beside it:
    ``figures`` (``[{"id", "figure"}]``: ``stability``'s margin, ``sweep``'s and ``basins'``
    figures, computed in the same run) and ``csv`` (``basins``: the CLI's CSV)."""
    sets = list((set or {}).items())
    if isinstance(config, Mapping):
        # a dict of tables: its matrix files relative to the working folder
        text, extra = _autobal.linear_rotor_run(command, None, sets, json.dumps(options), dict(config))
    else:
        text, extra = _autobal.linear_rotor_run(command, os.fspath(config), sets, json.dumps(options))
    out = json.loads(text)
    if command == "map":
        out["margin"] = np.array([[np.nan if v is None else v for v in row] for row in out["margin"]], dtype=float)
        out["stable"] = np.array([[v == "stable" for v in row] for row in out["verdict"]], dtype=bool)
        out["x"], out["y"] = np.asarray(out["x"], dtype=float), np.asarray(out["y"], dtype=float)
    if command == "simulate" and out.get("stopped"):
        from .errors import SimulationError

        e = SimulationError(out["stopped"])
        e.result = out  # type: ignore[attr-defined]
        raise e
    return out, json.loads(extra)
