# SPDX-License-Identifier: Apache-2.0
"""palp: the palp SDK for Python (docs/python.md).

    import palp
    with palp.Probe("sim://127.0.0.1:7070") as probe:
        probe.configure_stream(rate_Hz=1000)
        probe.start_stream()
        samples, gaps = probe.read(1000)      # numpy structured arrays, SI units in the names
        probe.stop_stream()

Units: SI everywhere in the API, the unit in every name (i_A, z_m, p1_Pa, t_s). Recordings and
results keep their files' lab-unit names (z_mm, k_linear_N_per_mm): they are the files' columns
and the keys of `palpctl ... --json`.
Errors: palp.Error and its subclasses, carrying the SDK's message. Ctrl-C during a blocking call
leaves the device safe (coil at 0 A) and then raises KeyboardInterrupt.
"""

from . import _palp
from ._palp import (
    analyze_map,
    calibrate_kf,
    Calibration,
    channel,
    ConfigError,
    ConnectionError,
    ContactWatchProgram,
    DataError,
    DeviceError,
    DeviceInfo,
    DeviceListing,
    Error,
    FaultError,
    FaultInfo,
    FlashError,
    gap_dtype,
    GuardedApproach,
    GAP_SOURCES,
    Handshake,
    Health,
    HoldProgram,
    IdentificationRun,
    IdentificationSettings,
    identify,
    indent,
    IndentationParams,
    IndentationRun,
    IndentationSettings,
    IndentProgress,
    KfCalibrationRun,
    KfCalibrationSettings,
    list_devices,
    load_map,
    load_plan,
    load_rig,
    load_trace,
    map_plan,
    MapAnalysis,
    MotionResult,
    MultisineProgram,
    Params,
    Plan,
    Pose,
    Probe,
    ProgramResult,
    ProgramStatus,
    ProtocolError,
    RampProgram,
    read_recording,
    record,
    RecordProgress,
    RecordResult,
    Recording,
    RecordingError,
    Rig,
    Robot,
    RobotFaultError,
    RobotLinkError,
    RobotRejectedError,
    RobotStatus,
    sample_dtype,
    save_trace,
    set_log_handler,
    sdk_version,
    SineProgram,
    Status,
    StiffnessMap,
    StreamInfo,
    SweepProgram,
    TimeoutError,
    trace,
    TracedSurface,
    TracePoint,
    VersionError,
    write_recording,
)
from . import analyze

__version__ = sdk_version

# the SDK's threads must not call a Python log handler while the interpreter shuts down
import atexit as _atexit

_atexit.register(set_log_handler, None)

__all__ = [name for name in dir() if not name.startswith("_") and name not in ("annotations",)]
