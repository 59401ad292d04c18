"""Type stubs of the compiled core ``tribo._tribo`` (crates/tribo-py). Use the documented
API of the package ``tribo``; these names may change."""

from pathlib import Path
from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

class InputError(ValueError):
    """Bad input: a field breaking a rule."""

    field: str
    value: str
    rule: str

class ConvergenceError(RuntimeError):
    """A solver stopped before reaching its tolerance."""

    solver: str
    iterations: int
    residual: float
    tolerance: float

class SolverError(RuntimeError):
    """A failure of the computation other than non-convergence."""

class HertzContact:
    """The exact Hertz solution of an elliptical (or circular) contact."""

    @property
    def semi_major(self) -> float: ...
    @property
    def semi_minor(self) -> float: ...
    @property
    def radius(self) -> float: ...
    @property
    def max_pressure(self) -> float: ...
    @property
    def mean_pressure(self) -> float: ...
    @property
    def approach(self) -> float: ...
    @property
    def normal_load(self) -> float: ...
    @property
    def contact_area(self) -> float: ...
    @property
    def angle(self) -> float: ...
    @property
    def composite_modulus(self) -> float: ...
    def pressure(
        self, x: npt.NDArray[np.float64], y: npt.NDArray[np.float64]
    ) -> npt.NDArray[np.float64]: ...

class Case:
    @staticmethod
    def from_toml_text(text: str, source: str = ..., base_dir: Optional[str] = ...) -> "Case": ...
    @staticmethod
    def from_dict(
        data: Dict[str, Any], source: str = ..., base_dir: Optional[str] = ...
    ) -> "Case": ...
    @staticmethod
    def example(name: str) -> "Case": ...
    @property
    def kind(self) -> str: ...
    @property
    def title(self) -> str: ...
    @property
    def toml(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def base_dir(self) -> Optional[Path]: ...

class NormalSolver:
    def __init__(
        self,
        shape: Tuple[int, int],
        size: Tuple[float, float],
        composite_modulus: float,
        tolerance: float = ...,
        max_iterations: int = ...,
        method: str = ...,
        periodic: bool = ...,
        kernel: str = ...,
    ) -> None: ...
    def solve(
        self,
        gap: npt.NDArray[np.float64],
        load: Optional[float] = ...,
        approach: Optional[float] = ...,
        initial_pressure: Optional[npt.NDArray[np.float64]] = ...,
    ) -> Dict[str, Any]: ...

class Results:
    def summary_json(self) -> str: ...
    def write(self, directory: str) -> List[str]: ...
    def fields(self) -> Optional[Dict[str, Any]]: ...
    def field(self) -> Optional[Dict[str, Any]]: ...

def hertz(
    radii1: Sequence[float],
    radii2: Sequence[float],
    angle_between: float,
    composite_modulus: float,
    load: Optional[float] = ...,
    approach: Optional[float] = ...,
) -> HertzContact: ...
def composite_modulus(e1: float, nu1: float, e2: float, nu2: float) -> float: ...
def normal_contact(
    gap: npt.NDArray[np.float64],
    size: Tuple[float, float],
    composite_modulus: float,
    load: Optional[float] = ...,
    approach: Optional[float] = ...,
    tolerance: float = ...,
    max_iterations: int = ...,
    method: str = ...,
    initial_pressure: Optional[npt.NDArray[np.float64]] = ...,
    periodic: bool = ...,
    kernel: str = ...,
) -> Dict[str, Any]: ...
def tangential_contact(
    pressure: npt.NDArray[np.float64],
    size: Tuple[float, float],
    friction: float,
    materials: Tuple[float, float, float, float],
    tangential_load: Optional[float] = ...,
    sliding: bool = ...,
    angle: float = ...,
    tolerance: float = ...,
    max_iterations: int = ...,
    free: bool = ...,
    periodic: bool = ...,
    kernel: str = ...,
) -> Dict[str, Any]: ...
def coupled_contact(
    gap: npt.NDArray[np.float64],
    size: Tuple[float, float],
    materials: Tuple[float, float, float, float],
    friction: float,
    load: Optional[float] = ...,
    approach: Optional[float] = ...,
    tangential_load: Optional[float] = ...,
    sliding: bool = ...,
    angle: float = ...,
    free: bool = ...,
    tolerance: float = ...,
    max_passes: int = ...,
) -> Dict[str, Any]: ...
def stress_field(
    pressure: npt.NDArray[np.float64],
    size: Tuple[float, float],
    material: Tuple[float, float],
    z: Sequence[float],
    x: Optional[Sequence[float]] = ...,
    y: Optional[Sequence[float]] = ...,
    traction_x: Optional[npt.NDArray[np.float64]] = ...,
    traction_y: Optional[npt.NDArray[np.float64]] = ...,
    method: str = ...,
    edge_refinement: int = ...,
) -> Dict[str, Any]: ...
def damage(
    components: Sequence[npt.NDArray[np.float64]],
    x: Sequence[float],
    y: Sequence[float],
    z: Sequence[float],
    material: Tuple[float, float],
    name: str,
    limit: float,
) -> Tuple[npt.NDArray[np.float64], str, str]: ...
def energy_damage(
    components: Sequence[npt.NDArray[np.float64]],
    x: Sequence[float],
    y: Sequence[float],
    z: Sequence[float],
    material: Tuple[float, float],
    u0: float,
    coefficients: Tuple[float, float, float, float, float],
    temperature: Sequence[float],
) -> Tuple[npt.NDArray[np.float64], str]: ...
def fatigue_fit(
    load: Sequence[float],
    cycles: Sequence[float],
    runout: Sequence[bool],
    kind_name: str = ...,
    measure_name: Optional[str] = ...,
    confidence: float = ...,
    source: str = ...,
) -> str: ...
def fatigue_diagram(data: Any, base_dir: Optional[str] = ...) -> str: ...
def run(case: Case) -> Results: ...
def example_names() -> List[str]: ...

class Study:
    @staticmethod
    def from_toml_text(text: str, source: str = ..., directory: Optional[str] = ...) -> "Study": ...
    @staticmethod
    def from_dict(
        data: Dict[str, Any], source: str = ..., directory: Optional[str] = ...
    ) -> "Study": ...
    @staticmethod
    def example(name: str) -> "Study": ...
    @property
    def name(self) -> str: ...
    @property
    def seed(self) -> int: ...
    @property
    def text(self) -> str: ...
    @property
    def kind(self) -> str: ...
    @property
    def outputs(self) -> str: ...
    @property
    def base_dir(self) -> Path: ...
    @property
    def base_toml(self) -> str: ...
    @property
    def parameters(self) -> List[Tuple[str, str, str]]: ...
    @property
    def collect(self) -> List[Tuple[str, str, str]]: ...
    def __len__(self) -> int: ...
    def points(self) -> List[Tuple[str, List[Any]]]: ...
    def case_toml(self, i: int) -> str: ...
    def plan(self, directory: str) -> "StudyDir": ...

class StudyDir:
    @staticmethod
    def open(directory: str) -> "StudyDir": ...
    @property
    def directory(self) -> Path: ...
    @property
    def study(self) -> Study: ...
    def run(
        self,
        points: Optional[Sequence[int]] = ...,
        jobs: Optional[int] = ...,
        progress: Optional[Callable[[int, int], Any]] = ...,
    ) -> Dict[str, Any]: ...
    def states(self) -> List[Tuple[str, str]]: ...
    def gather(self, write: bool = ...) -> Dict[str, Any]: ...
    def slurm(
        self,
        tribo: str,
        chunk: Optional[int] = ...,
        partition: Optional[str] = ...,
        time: str = ...,
        cpus_per_task: int = ...,
        max_running: Optional[int] = ...,
    ) -> Tuple[Path, Path]: ...

def slurm_ranges(ids: Sequence[int]) -> str: ...
def slurm_job_id(answer: str) -> Optional[int]: ...
def study_examples() -> List[Tuple[str, str]]: ...

# Rough surfaces (python/tribo/surface.py; crates/tribo-py/src/surface.rs)
def surface_generate(
    shape: Tuple[int, int],
    size: Tuple[float, float],
    rolloff: float,
    powerlaw_start: float,
    cutoff: float,
    hurst: float,
    anisotropy: Tuple[float, float],
    rms_height: Optional[float],
    rms_slope: Optional[float],
    method: str,
    seed: int,
) -> npt.NDArray[np.float64]: ...
def spectrum_moments(
    rolloff: float,
    powerlaw_start: float,
    cutoff: float,
    hurst: float,
    anisotropy: Tuple[float, float],
    shape: Optional[Tuple[int, int]] = ...,
    size: Optional[Tuple[float, float]] = ...,
) -> Dict[str, Dict[str, Optional[float]]]: ...
def surface_statistics(
    heights: npt.NDArray[np.float64], spacing: Tuple[float, float]
) -> Dict[str, Optional[float]]: ...
def surface_psd(
    heights: npt.NDArray[np.float64], spacing: Tuple[float, float]
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.uint64]]: ...
def surface_fit_power_law(
    q: Sequence[float], psd: Sequence[float], modes: Sequence[int], q_min: float, q_max: float
) -> Dict[str, Any]: ...
def surface_autocorrelation(
    heights: npt.NDArray[np.float64], spacing: Tuple[float, float]
) -> npt.NDArray[np.float64]: ...
def surface_detrend(
    heights: npt.NDArray[np.float64], spacing: Tuple[float, float], degree: int
) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], List[float]]: ...
def surface_resample(
    heights: npt.NDArray[np.float64],
    spacing: Tuple[float, float],
    shape: Tuple[int, int],
    new_spacing: Tuple[float, float],
    periodic: bool,
) -> npt.NDArray[np.float64]: ...
def surface_read(
    path: str,
    spacing: Optional[Tuple[float, float]] = ...,
    height_unit: float = ...,
    keep_invalid: bool = ...,
) -> Tuple[npt.NDArray[np.float64], Tuple[float, float], int]: ...
