"""Type stubs of the extension module (the Rust side of autobal); use the `autobal` package."""

from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union, final

import numpy as np
import numpy.typing as npt

__all__ = [
    "__version__",
    "SUMMARY_COLUMNS",
    "SPATIAL_SUMMARY_COLUMNS",
    "SCHEMA",
    "DEFAULT_SPATIAL",
    "DEFAULT_PLANAR",
    "SpatialConfig",
    "PlanarConfig",
    "spatial_config",
    "planar_config",
    "spatial_report",
    "stability_map",
    "simulate",
    "simulate_batch",
    "spatial_simulate",
    "spatial_basins",
    "sweep_report",
    "check_batch",
    "grid_points",
    "parse_axis",
    "shard",
    "planar_paths",
    "cli_main",
    "figures",
    "report",
    "COMMANDS_WITH_FIGURES",
    "COMMANDS",
]
__version__: str
SUMMARY_COLUMNS: List[str]
SPATIAL_SUMMARY_COLUMNS: List[str]
SCHEMA: List[Tuple[str, List[str]]]
DEFAULT_SPATIAL: str
DEFAULT_PLANAR: str

@final
class SpatialConfig:
    @property
    def toml(self) -> str: ...

@final
class PlanarConfig:
    @property
    def toml(self) -> str: ...
    def get(self, path: str) -> float: ...
    def to_json(self) -> str: ...

def spatial_config(text: Optional[str], dict: Optional[Mapping[str, Any]], source: str, sets: Sequence[Tuple[str, Any]]) -> SpatialConfig: ...
def planar_config(text: Optional[str], dict: Optional[Mapping[str, Any]], source: str, sets: Sequence[Tuple[str, Any]]) -> PlanarConfig: ...
def spatial_report(command: str, cfg: SpatialConfig, omega_max: Optional[Union[float, str]] = None, samples: int = 2000, points: int = 300, balls: str = "free") -> str: ...
def stability_map(cfg: SpatialConfig, x: Tuple[str, Sequence[float]], y: Tuple[str, Sequence[float]], omega: Optional[float] = None, balls: str = "free", quantity: str = "margin", threads: Optional[int] = None) -> Dict[str, npt.NDArray[Any]]: ...
def simulate(cfg: PlanarConfig, dt: Optional[float] = None) -> Tuple[Dict[str, npt.NDArray[np.float64]], str]: ...
def spatial_simulate(cfg: SpatialConfig, dt: Optional[float] = None) -> Tuple[Dict[str, npt.NDArray[np.float64]], str]: ...
# arrays: psi_1, psi_2, balanced_runs (bool per run), residual_unbalance, final_amplitude; the JSON's
# `balanced` is the count of balanced runs
def spatial_basins(cfg: SpatialConfig, n: int = 16) -> Tuple[Dict[str, npt.NDArray[Any]], str]: ...
def simulate_batch(cfg: Union[PlanarConfig, SpatialConfig], paths: Sequence[str], params: npt.NDArray[np.float64], threads: Optional[int] = None) -> npt.NDArray[np.float64]: ...
def check_batch(cfg: Union[PlanarConfig, SpatialConfig], paths: Sequence[str], params: npt.NDArray[np.float64]) -> None: ...
def sweep_report(cfg: Union[PlanarConfig, SpatialConfig], axes: Sequence[Tuple[str, Sequence[float]]], shard: Optional[Tuple[int, int]] = None, threads: Optional[int] = None) -> str: ...
def grid_points(axes: Sequence[Tuple[str, Sequence[float]]], lo: Optional[int] = None, hi: Optional[int] = None) -> npt.NDArray[np.float64]: ...
def parse_axis(spec: str) -> Tuple[str, List[float]]: ...
def shard(total: int, k: int, n: int) -> Tuple[int, int]: ...
def planar_paths() -> List[Tuple[str, str]]: ...
def cli_main(argv: Sequence[str]) -> int: ...
COMMANDS: List[str]
COMMANDS_WITH_FIGURES: List[str]
# JSON [{"id", "title", "figure"}], `figure` Plotly's {data, layout}; `options` JSON of the CLI's flags
def figures(command: str, text: Optional[str], dict: Optional[Mapping[str, Any]], source: str, sets: Sequence[Tuple[str, Any]], options: str = "{}") -> str: ...
def report(config: Optional[str], sets: Sequence[str], out: str, quick: bool = False, papers: bool = False) -> str: ...
