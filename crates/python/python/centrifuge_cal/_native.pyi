"""Type stubs of the native module (Rust, PyO3); the public API is in __init__.py."""

from typing import Any

import numpy as np
import numpy.typing as npt

VERSION: str

class CentrifugeCalError(Exception):
    @property
    def message(self) -> str: ...
    file: str | None
    line: int | None
    field: str | None
    hint: str | None

class InputError(CentrifugeCalError, ValueError): ...
class RecordingError(CentrifugeCalError): ...
class ConfigError(CentrifugeCalError): ...
class ComputationError(CentrifugeCalError): ...
class CentrifugeCalWarning(UserWarning): ...

class NativeRecording:
    def arrays(self) -> dict[str, Any]: ...
    def analyze(
        self,
        rate_rad_s: float,
        order: int,
        drift: bool,
        revolutions: int | None,
        probe_along: bool,
    ) -> dict[str, Any]: ...

def defaults() -> dict[str, Any]: ...
def fit_harmonics(
    time_s: npt.NDArray[np.float64],
    gap: npt.NDArray[np.float64],
    angle_rad: npt.NDArray[np.float64] | None,
    rate_rad_s: float,
    start_angle_rad: float,
    order: int,
    drift: bool,
    revolutions: int | None,
    max_gap_intervals: float,
    probe_along: bool,
    gap_unit: str,
    on_outlier: str,
) -> dict[str, Any]: ...
def read_recording(
    path: str,
    format_ron: str | None = None,
    format_dict: dict[str, Any] | None = None,
    group: str | None = None,
    waveform_time: bool = False,
) -> NativeRecording: ...
def run_study_file(path: str) -> dict[str, Any]: ...
def run_study_dict(
    config: dict[str, Any], source: str, tables: dict[str, Any]
) -> dict[str, Any]: ...
def plan(ron_path: str | None = None, dict: dict[str, Any] | None = None) -> dict[str, Any]: ...
def fit_radius_error(
    rate_rad_s: npt.NDArray[np.float64],
    radius_error_m: npt.NDArray[np.float64],
    sigma_m: npt.NDArray[np.float64] | None,
    three_term: bool,
) -> dict[str, Any]: ...
def delta_k2(
    k1_rad_s_g: float, c_r_m_s2: float, c_r_sigma_m_s2: float, radius_m: float, g_m_s2: float
) -> tuple[float, float]: ...
def cli_main(argv: list[str]) -> int: ...
def certificate(results: str, out: str | None = None) -> str: ...
def unit_history(
    unit: str,
    records: str | None = None,
    at: str | None = None,
    term: str | None = None,
    tolerance: float | None = None,
    reliability: float = 0.95,
) -> dict[str, Any]: ...
def centrifuge_health(
    name: str,
    records: str | None = None,
    target_u95: float | None = None,
    share: float | None = None,
    next: str | None = None,
) -> dict[str, Any]: ...
