"""Type stubs of the compiled module ``rockslide._rockslide`` (re-exported by ``rockslide``)."""

from os import PathLike
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, "PathLike[str]"]
_Array = npt.NDArray[np.float64]
_ArrayLike = npt.ArrayLike

__version__: str
ENGINES: List[str]
"""The engine ids a case or ``run(engines=...)`` can name."""

class InputError(ValueError):
    """A case, record or argument that cannot be used. The message lists every problem,
    one ``file:line:col: field: reason`` line each; the attributes locate the first."""

    file: str
    line: Optional[int]
    column: Optional[int]
    field: str
    reason: str
    errors: List[Dict[str, Any]]
    """Every problem: ``file``, ``line``, ``column``, ``field``, ``reason`` (and
    ``within_file``, ``within_line``, ``within_column`` for a problem inside a file a field
    names, such as a record)."""

class Case:
    """A validated case."""

    @staticmethod
    def load(path: _Path) -> Case:
        """Read and validate a case file."""
    @staticmethod
    def from_toml(text: str, path: Optional[_Path] = None) -> Case:
        """Parse and validate TOML text; ``path`` names it in errors and anchors relative
        record paths."""
    @staticmethod
    def from_dict(tables: Mapping[str, Any], path: Optional[_Path] = None) -> Case:
        """Write a dict (the TOML file's tables as nested dicts and lists) as the case's
        TOML and validate it."""
    @property
    def name(self) -> str:
        """The case's name, the name of its report folder."""
    @property
    def title(self) -> str: ...
    @property
    def path(self) -> Path:
        """The case file, as given."""
    @property
    def text(self) -> str:
        """The case's TOML text."""
    @property
    def duration(self) -> float:
        """Simulated duration, s."""
    def run(self, engines: Optional[Sequence[str]] = None) -> Result:
        """Run the case; see :func:`run`."""

class Result:
    """Everything known about a case after running it."""

    @property
    def case(self) -> str: ...
    @property
    def participants(self) -> List[str]:
        """Each run as ``engine/variant`` (external programs by their label), then
        ``reference`` when the case has one."""
    def trace(self, participant: str) -> Dict[str, _Array]:
        """``{"time": array, quantity: array, ...}`` (SI; quantity keys as in
        :func:`quantities`; contacts as ``<contact>.<field>``)."""
    def traces(self) -> Dict[str, Dict[str, _Array]]:
        """Every participant's trace."""
    @property
    def responses(self) -> Dict[str, Dict[str, float]]:
        """``{participant: {quantity: value}}``, SI; the reference's event times exact."""
    @property
    def statuses(self) -> List[Tuple[str, str]]:
        """``(participant, "completed" | "diverged" | "not converged")`` per run."""
    @property
    def not_applicable(self) -> List[Tuple[str, str]]:
        """``(engine, why)`` for engines that do not apply."""
    @property
    def checks(self) -> List[Dict[str, Any]]:
        """The tolerance checks as ``result.json`` lists them."""
    @property
    def azimuths(self) -> Optional[Dict[str, Any]]:
        """A case with ``x_azimuths_deg``: each participant's figures at every azimuth, their
        maxima over the set and the governing azimuth (``result.json``'s ``azimuths``);
        ``None`` otherwise. The traces and responses are the governing azimuth's."""
    @property
    def passed(self) -> bool:
        """Whether the case passes the gate."""
    @property
    def failures(self) -> List[str]:
        """The gate's failure lines, as ``rockslide check`` prints them."""
    def to_json(self) -> str:
        """The typed record the command line writes as ``result.json``, same serialisation."""
    def record_dict(self) -> Dict[str, Any]:
        """The typed record as Python values."""
    def write_report(self, folder: _Path) -> Path:
        """Write the report, traces and ``result.json`` into ``<folder>/<case>/``; returns
        that folder."""
    def to_pandas(self, participant: str) -> Any:
        """A participant's trace as a ``pandas.DataFrame`` indexed by time (needs pandas)."""

def load_case(path: _Path) -> Case: ...
def case_from_toml(text: str, path: Optional[_Path] = None) -> Case: ...
def case_from_dict(tables: Mapping[str, Any], path: Optional[_Path] = None) -> Case: ...
def run(case: Case, engines: Optional[Sequence[str]] = None) -> Result:
    """Run a case: every engine it names (all that apply when it names none), or only
    ``engines``; the engines run in parallel with the GIL released."""

def quantities() -> Dict[str, Dict[str, str]]:
    """The quantity catalogue: ``{key: {"label", "unit", "doc"}}``."""

def read_record(
    path: _Path, unit: Optional[str] = None, column: Optional[int] = None
) -> Tuple[float, _Array]:
    """A PEER AT2 or CSV record as ``(dt, samples)``, samples in m/s²; ``unit`` (``"g"``,
    ``"m/s2"``, ``"cm/s2"``) is required for a CSV."""

def reference(case: Case, times: Optional[_Array] = None) -> Dict[str, Any]:
    """The case's exact reference at ``times`` (default: every ``[run] dt``): arrays by
    quantity, and ``"exact"``: the quantities known exactly (event times)."""

def epo_record(
    dt: float,
    acceleration: _Array,
    mass: float,
    stiffness: float,
    mu: float,
    gravity: float = 9.80665,
    duration: Optional[float] = None,
    times: Optional[_Array] = None,
) -> Dict[str, Any]:
    """The undamped elastic-perfectly-plastic oscillator under a ground-acceleration record."""

def rigid_block(
    dt: float, acceleration: _Array, ky: float, one_way: bool = False, tail: float = 0.0
) -> Dict[str, Any]:
    """Newmark's rigid block under a record (both ways, or one way as SLAMMER's):
    ``time``, ``velocity``, ``displacement``, ``slides``, ``peak``."""

def housner(
    half_width: float,
    half_height: float,
    amplitude: float,
    omega: float,
    duration: float,
    cycles: float = 0.5,
    gravity: float = 9.80665,
    initial_tilt: float = 0.0,
    samples: int = 2000,
    times: Optional[_Array] = None,
) -> Dict[str, Any]:
    """Housner's rocking block under a ground-acceleration sine pulse."""

def plan_block(
    dt: float,
    acceleration_x: _Array,
    acceleration_y: _Array,
    mu: float,
    gravity: float = 9.80665,
    duration: Optional[float] = None,
    step: float = 1e-4,
    times: Optional[_Array] = None,
) -> Dict[str, Any]:
    """The rigid block on an isotropic friction cone under two horizontal components."""

def plan_oscillator(
    dt: float,
    acceleration_x: _Array,
    acceleration_y: _Array,
    mass: float,
    stiffness: float,
    mu: float,
    gravity: float = 9.80665,
    duration: Optional[float] = None,
    step: float = 1e-4,
    times: Optional[_Array] = None,
) -> Dict[str, Any]:
    """The elastic-perfectly-plastic oscillator on an isotropic friction cone under two
    horizontal components."""

def run_study(
    grid: _Path, out: _Path, shard: Optional[Tuple[int, int]] = None
) -> Dict[str, Any]:
    """Run a study grid in parallel (resumable) and, unsharded, gather ``study.json`` and
    its summary: counts and ``"study"``."""
