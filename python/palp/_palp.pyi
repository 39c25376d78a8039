# SPDX-License-Identifier: Apache-2.0
# Type stubs for palp._palp, the bound SDK (hand-written; python/tests/test_stubs.py checks that
# they name every public attribute of the module and of each class, and nothing else).
# Units: SI, in every name. Enums are their catalogue names (str).
import builtins
import os
import pathlib
from typing import Any, Callable, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

class channel:
    """Stream channel bits (Probe.configure_stream(channels=...))."""
    i_cmd: int
    i_meas: int
    encoder: int
    pressure: int
    status: int
    v_cmd: int
    all: int

sdk_version: str
GAP_SOURCES: tuple[str, ...]
sample_dtype: np.dtype
gap_dtype: np.dtype

_Path = Union[str, os.PathLike[str]]

# --- errors (palp/error.hpp) -------------------------------------------------------------------
class Error(Exception): ...
class ConfigError(Error, ValueError): ...
class ConnectionError(Error, builtins.ConnectionError): ...
class TimeoutError(Error, builtins.TimeoutError):
    waited_for: str
    timeout_s: float
class VersionError(Error): ...
class DeviceError(Error):
    request: str
    code: int
    field_index: int
    detail: int
class FaultError(Error):
    reason: int
class ProtocolError(Error): ...
class RecordingError(Error):
    file: str
    line: int
    problem: str
class DataError(Error): ...
class RobotRejectedError(Error):
    result: int
    register_address: int
class RobotFaultError(Error): ...
class FlashError(Error):
    erased: bool
class RobotLinkError(ConnectionError): ...

# --- the protocol's messages (catalogue fields; keyword arguments, catalogue defaults) ----------
class Params:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    current_clamp_A: float
    i2t_continuous_A: float
    i2t_limit_A2s: float
    i2t_tau_s: float
    travel_min_counts: int
    travel_max_counts: int
    heartbeat_timeout_ms: int
    control_rate_Hz: int
    supply_V: float
    contact_output: str
    contact_output_hold_ms: int
    def to_dict(self) -> dict[str, Any]: ...

class Calibration:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    layout_version: int
    kf_position_counts: list[int]
    kf_N_per_A: list[float]
    current_offset_A: float
    current_gain: float
    pressure_offset_Pa: list[float]
    pressure_gain: list[float]
    spring_k_N_per_m: float
    stroke_origin_counts: int
    stroke_origin_valid: int
    def to_dict(self) -> dict[str, Any]: ...

class HoldProgram:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    current_A: float
    duration_s: float
    def to_dict(self) -> dict[str, Any]: ...

class RampProgram:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    start_A: float
    stop_A: float
    step_A: float
    dwell_s: float
    repetitions: int
    unload: int
    displacement_limit_counts: int
    def to_dict(self) -> dict[str, Any]: ...

class SineProgram:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    offset_A: float
    amplitude_A: float
    frequency_Hz: float
    cycles: int
    def to_dict(self) -> dict[str, Any]: ...

class SweepProgram:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    offset_A: float
    amplitude_A: float
    start_Hz: float
    stop_Hz: float
    step_Hz: float
    settle_cycles: int
    settle_min_s: float
    measure_cycles: int
    def to_dict(self) -> dict[str, Any]: ...

class MultisineProgram:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    offset_A: float
    fundamental_Hz: float
    line_first: int
    line_last: int
    line_step: int
    line_amplitude_A: float
    phase_mode: str
    phase_seed: int
    periods: int
    def to_dict(self) -> dict[str, Any]: ...

class ContactWatchProgram:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    hold_current_A: float
    threshold_counts: int
    timeout_s: float
    def to_dict(self) -> dict[str, Any]: ...

class ProgramStatus:
    fields: tuple[str, ...]
    def __init__(self, **fields: Any) -> None: ...
    kind: str
    state: str
    end: str
    elapsed_us: int
    step: int
    repetition: int
    def to_dict(self) -> dict[str, Any]: ...

# --- the probe (palp/probe.hpp) ------------------------------------------------------------------
class DeviceInfo:
    serial: str
    board: str
    git_hash: str
    firmware_version: str
    protocol_major: int
    protocol_minor: int
    schema_hash: int
    capabilities: int
    max_current_A: float
    control_rate_Hz: float
    max_stream_rate_Hz: float
    heartbeat_timeout_s: float
    max_payload: int

class Handshake:
    missing_features: bool
    missing: list[str]
    message: str

class Status:
    t_device_s: float
    state: str
    fault: str
    program: str
    program_state: str
    i_cmd_A: float
    i_A: float
    z_m: float
    encoder_counts: int
    i2t_fraction: float
    streaming: bool
    status_bits: int

class Health:
    device_time_us: int
    device_frames_rx: int
    device_frames_tx: int
    device_rx_rejected: int
    isr_queue_overflows: int
    stream_backlog_max: int
    stream_samples_lost: int
    usb_in_not_drained: int
    tx_frames_dropped: int
    control_overruns: int
    device_stream_gaps: int
    device_valid: bool
    host_frames_rx: int
    host_rx_rejected: int
    host_samples_received: int
    host_samples_missing: int
    host_queue_dropped: int
    host_queue_max: int
    host_gaps: int
    reconnects: int
    requests_resent: int

class ProgramResult:
    kind: str
    end: str
    t_device_s: float
    repetitions_done: int

class FaultInfo:
    reason: str
    t_device_s: float
    detail: int
    text: str

class DeviceListing:
    serial: str
    firmware_version: str
    product: str
    vid: int
    pid: int
    uris: list[str]
    note: str

def list_devices() -> list[DeviceListing]: ...

class StreamInfo:
    rate_Hz: float
    period_s: float
    channels: int
    batch_samples: int
    wire_bytes_per_s: int

_Program = Union[HoldProgram, RampProgram, SineProgram, SweepProgram, MultisineProgram, ContactWatchProgram]

class Probe:
    def __init__(self, uri: str, timeout_s: float = 2.0, reconnect: bool = True) -> None: ...
    @property
    def info(self) -> DeviceInfo: ...
    @property
    def handshake(self) -> Handshake: ...
    @property
    def uri(self) -> str: ...
    @property
    def stream_info(self) -> StreamInfo: ...
    def status(self) -> Status: ...
    def health(self) -> Health: ...
    def params(self) -> Params: ...
    def set_params(self, params: Params) -> None: ...
    def calibration(self) -> Calibration: ...
    def set_calibration(self, calibration: Calibration) -> None: ...
    def commit_calibration(self) -> None: ...
    def load(self, program: _Program) -> None: ...
    def start(self) -> None: ...
    def stop(self) -> None: ...
    def wait(self, timeout_s: float) -> ProgramResult: ...
    def run(self, program: _Program, timeout_s: float) -> ProgramResult: ...
    def program_status(self) -> ProgramStatus: ...
    def fault(self) -> FaultInfo: ...
    def clear_fault(self) -> None: ...
    def zero_current_offset(self, seconds: float = 0.5) -> float: ...
    def zero_pressure(self, seconds: float = 0.5) -> list[float]: ...
    def home(self, hold_current_A: float = -0.3, seconds: float = 1.0) -> int: ...
    def make_safe(self) -> Status: ...
    def close(self) -> None: ...
    def configure_stream(self, rate_Hz: float = 1000.0, channels: int = ..., batch_samples: int = 0) -> StreamInfo: ...
    def start_stream(self) -> None: ...
    def stop_stream(self) -> None: ...
    def read(self, n: int, timeout_s: float = 10.0) -> tuple[npt.NDArray[Any], npt.NDArray[Any]]: ...
    def __enter__(self) -> Probe: ...
    def __exit__(self, *args: Any) -> None: ...

# --- experiments (palp/indent.hpp, palp/result.hpp) ---------------------------------------------
class IndentationParams:
    def __init__(self) -> None: ...
    force_constant_N_per_A: float
    contact_current_A: float
    spring_N_per_m: float
    tip_radius_m: float
    poisson: float
    bias_current_A: float
    window_lo_m: float
    window_hi_m: float
    local_half_width_m: float
    tangent_depths_m: list[float]
    min_points: int
    def to_dict(self) -> dict[str, Any]: ...

class IndentationSettings:
    def __init__(self) -> None: ...
    @staticmethod
    def preset(name: str) -> IndentationSettings: ...
    @staticmethod
    def from_dict(d: dict[str, Any]) -> IndentationSettings: ...
    start_A: float
    stop_A: float
    step_A: float
    dwell_s: float
    repetitions: int
    unload: bool
    displacement_limit_m: float
    stream_rate_Hz: float
    zero_pressure: bool
    zero_pressure_s: float
    settle_s: float
    analysis: IndentationParams
    def ramp_program(self) -> RampProgram: ...
    def ramp_duration_s(self) -> float: ...
    def validate(self) -> None: ...
    def to_dict(self) -> dict[str, Any]: ...

class IndentProgress:
    phase: str
    fraction: float
    repetition: int
    z_m: float
    i_A: float

class IndentationRun:
    settings: IndentationSettings
    recording: Recording
    device: DeviceInfo
    program: ProgramResult
    interrupted: bool
    samples_missing: int
    float_z_m: float
    analysis_reason: str
    pressure_reason: str
    has_analysis: bool
    def summary(self) -> dict[str, Any]: ...
    def write_result(self, dir: _Path, overwrite: bool = False) -> str: ...

def indent(probe: Probe, settings: IndentationSettings,
           progress: Optional[Callable[[IndentProgress], None]] = None) -> IndentationRun: ...

# --- identification (palp/identification.hpp) ---------------------------------------------------
class IdentificationSettings:
    def __init__(self) -> None: ...
    @staticmethod
    def preset(name: str) -> IdentificationSettings: ...
    @staticmethod
    def from_dict(d: dict[str, Any]) -> IdentificationSettings: ...
    in_contact: bool
    bias_A: float
    amplitude_A: float
    f_lo_Hz: float
    f_hi_Hz: float
    step_Hz: float
    fundamental_Hz: float
    line_step: int
    measured_periods: int
    stream_rate_Hz: float
    settle_s: float
    method: str
    def validate(self) -> None: ...
    def to_dict(self) -> dict[str, Any]: ...

class IdentificationRun:
    settings: IdentificationSettings
    recording: Recording
    program: ProgramResult
    interrupted: bool
    samples_missing: int
    analysis_reason: str
    has_analysis: bool
    def summary(self) -> dict[str, Any]: ...
    def frf_table(self) -> Optional[str]: ...
    def write_result(self, dir: _Path, overwrite: bool = False) -> str: ...

def identify(probe: Probe, settings: IdentificationSettings,
             progress: Optional[Callable[[str, float, float], None]] = None) -> IdentificationRun: ...
def _analyze_sweep(recording: Recording) -> dict[str, Any]: ...

# --- the K_f calibration (palp/identification.hpp) ----------------------------------------------
class KfCalibrationSettings:
    def __init__(self) -> None: ...
    start_A: float
    stop_A: float
    step_A: float
    dwell_s: float
    settled_fraction: float
    max_nodes: int
    k_v_N_per_m: float
    stream_rate_Hz: float
    write: bool
    commit: bool
    anchor: Optional[tuple[float, float]]
    def validate(self) -> None: ...

class KfCalibrationRun:
    settings: KfCalibrationSettings
    recording: Recording
    written: bool
    committed: bool
    interrupted: bool
    node_stroke_m: list[float]
    kf_N_per_A: list[float]
    warning: str
    def to_dict(self) -> dict[str, Any]: ...

def calibrate_kf(probe: Probe, settings: Optional[KfCalibrationSettings] = None,
                 progress: Optional[Callable[[str, float], None]] = None) -> KfCalibrationRun: ...

# --- the SDK recorder (palp/recorder.hpp) -------------------------------------------------------
class RecordProgress:
    samples: int
    expected_samples: int
    samples_missing: int
    finished: bool

class RecordResult:
    written: bool
    csv: pathlib.Path
    sidecar: pathlib.Path
    samples: int
    samples_missing: int
    gaps: int
    interrupted: bool
    program: Optional[ProgramResult]
    sidecar_written: Optional[dict[str, Any]]

def record(probe: Probe, out: _Path, *, duration_s: float = 0.0, rate_Hz: float = 1000.0,
           program: Optional[Union[HoldProgram, RampProgram, SineProgram, SweepProgram]] = None,
           zero_current: bool = False, zero_pressure: bool = False, zero_s: float = 0.5,
           reply_timeout_s: float = 2.0, overwrite: bool = False,
           progress: Optional[Callable[[RecordProgress], None]] = None) -> RecordResult: ...

# --- recordings and the offline analysis (palp/recording.hpp) -----------------------------------
class Recording:
    def __init__(self, columns: dict[str, Sequence[float]]) -> None: ...
    columns: dict[str, npt.NDArray[Any]]
    sidecar: Optional[dict[str, Any]]
    ignored_columns: list[str]
    def __len__(self) -> int: ...

def read_recording(csv: _Path) -> Recording: ...
def write_recording(csv: _Path, recording: Recording, overwrite: bool = False) -> None: ...
def _analyze_indentation(recording: Recording, params: IndentationParams) -> dict[str, Any]: ...
def _analyze_pressure(recording: Recording, params: IndentationParams) -> dict[str, Any]: ...

# --- the robot, rig and plan files, maps (palp/robot.hpp, palp/rig.hpp, palp/map.hpp) ---------
class Pose:
    def __init__(self, x_m: float = 0.0, y_m: float = 0.0, z_m: float = 0.0, a_rad: float = 0.0,
                 b_rad: float = 0.0, c_rad: float = 0.0) -> None: ...
    x_m: float
    y_m: float
    z_m: float
    a_rad: float
    b_rad: float
    c_rad: float

class RobotStatus:
    state: str
    status_bits: int
    result: str
    tool: int
    robot_time_s: float
    pose: Pose
    latched: Optional[Pose]
    force_N: Optional[float]
    joints_rad: list[float]

class GuardedApproach:
    def __init__(self) -> None: ...
    axis: str
    speed_m_per_s: float
    max_travel_m: float
    guard_host_stop: bool
    digital_input: int
    force_threshold_N: Optional[float]

class MotionResult:
    seq: int
    result: str
    guard_fired: list[str]
    latched: Optional[Pose]
    final_pose: Pose

class Robot:
    def __init__(self, uri: str) -> None: ...
    uri: str
    def status(self) -> RobotStatus: ...
    def pose(self) -> Pose: ...
    def move_lin(self, target: Pose, speed_m_per_s: float,
                 timeout_s: float = 120.0) -> MotionResult: ...
    def move_lin_rel(self, offset: Pose, speed_m_per_s: float,
                     timeout_s: float = 120.0) -> MotionResult: ...
    def move_ptp(self, target: Pose, speed_fraction: float,
                 timeout_s: float = 120.0) -> MotionResult: ...
    def guarded_approach(self, approach: GuardedApproach,
                         timeout_s: float = 120.0) -> MotionResult: ...
    def stop(self, timeout_s: float = 2.0) -> RobotStatus: ...
    def hold(self, timeout_s: float = 2.0) -> None: ...
    def set_tool(self, id: int, tcp_on_flange: Pose) -> None: ...
    def reset_fault(self) -> None: ...

class Rig:
    robot_uri: str
    probe_uri: str
    safe_height_m: float

class Plan:
    name: str
    work_object: str
    def point_count(self) -> int: ...

class StiffnessMap:
    plan_name: str
    rows: int
    columns: int
    complete: bool
    stopped_because: str
    def to_dict(self) -> dict[str, Any]: ...

class MapAnalysis:
    rows: int
    columns: int
    k_N_per_m: list[Optional[float]]
    column_mean_N_per_m: list[float]
    row_mean_N_per_m: list[float]
    median_N_per_m: float
    soft_columns: list[int]
    stiff_columns: list[int]
    soft_rows: list[int]
    stiff_rows: list[int]
    contrast: float

def load_rig(file: _Path) -> Rig: ...
def load_plan(file: _Path) -> Plan: ...
def load_map(dir: _Path) -> StiffnessMap: ...
def analyze_map(map: StiffnessMap, contrast: float = 0.1) -> MapAnalysis: ...
def map_plan(probe: Probe, robot: Robot, rig: Rig, plan: Plan, dir: _Path,
             settings: Optional[IndentationSettings] = None,
             progress: Optional[Callable[[int, int, str], None]] = None,
             resume: bool = False, *, adaptive: bool = False, max_points: int = 0,
             threshold: float = 0.1, max_force_N: Optional[float] = None,
             dynamic: bool = False, align: str = "none",
             trace: Optional[_Path] = None) -> StiffnessMap: ...

# --- surface tracing (palp/trace.hpp) ------------------------------------------------------------
class TracePoint:
    row: int
    column: int
    ok: bool
    reason: str
    x_m: float
    y_m: float
    z_m: float
    apex_m: tuple[float, float, float]
    normal: tuple[float, float, float]
    tilt_rad: float
    indentation_m: float
    stroke_at_rest_m: float
    detection_force_N: float
    contact_stiffness_N_per_m: Optional[float]
    overtravel_m: float

class TracedSurface:
    plan_name: str
    rows: int
    columns: int
    tip_radius_m: float
    contact_E_star_Pa: Optional[float]
    points: list[TracePoint]
    resume_index: int
    complete: bool
    normals_from_grid: bool
    stopped_because: str

def trace(probe: Probe, robot: Robot, rig: Rig, plan: Plan,
          progress: Optional[Callable[[int, int], None]] = None,
          resume: Optional[TracedSurface] = None) -> TracedSurface: ...
def save_trace(file: _Path, surface: TracedSurface) -> None: ...
def load_trace(file: _Path) -> TracedSurface: ...

# --- the SDK's log (palp/log.hpp) ----------------------------------------------------------------
def set_log_handler(handler: Optional[Callable[[str, str], None]]) -> None: ...
