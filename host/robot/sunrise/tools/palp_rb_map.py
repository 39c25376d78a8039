# SPDX-License-Identifier: Apache-2.0
# GENERATED from protocol/include/palp/protocol/robot_bridge/map.hpp and check.hpp by
# protocol/tools/palp-rb-constants.cpp. Do not edit: change map.hpp, then run
#   build/release-with-assertions/protocol/palp-rb-constants python --write host/robot/sunrise/tools/palp_rb_map.py
# The test `sunrise_python_map_generated` fails while this file differs from the map.
"""The robot bridge's register map 1.0 (protocol/robot-bridge.md): absolute 0-based addresses, enumerations, limits."""

MAP_MAJOR = 1
MAP_MINOR = 0
MAGIC = 0x50414c50  # ASCII 'PALP'
DEFAULT_PORT = 30005
MAX_READ_REGISTERS = 125
MAX_WRITE_REGISTERS = 123
DEFAULT_WATCHDOG_MS = 500
MIN_WATCHDOG_MS = 100
MAX_WATCHDOG_MS = 10000
MAX_LIN_SPEED_UM_PER_S = 1000000
MAX_APPROACH_SPEED_UM_PER_S = 100000
MAX_APPROACH_TRAVEL_UM = 500000
MAX_FORCE_THRESHOLD_MN = 1000000


class RobotState:
    """The bridge's view of the robot (status register `state`)."""

    NOT_READY = 0
    IDLE = 1
    MOVING = 2
    FAULTED = 3
    SAFETY_STOP = 4
    NAMES = {0: "not_ready", 1: "idle", 2: "moving", 3: "faulted", 4: "safety_stop"}


class StatusBit:
    """Bit numbers of the status register `status_bits`."""

    DRIVES_ENABLED = 0
    DRIVES_ENABLED_MASK = 0x0001
    AUTOMATIC_MODE = 1
    AUTOMATIC_MODE_MASK = 0x0002
    HOST_HEARTBEAT_OK = 2
    HOST_HEARTBEAT_OK_MASK = 0x0004
    WATCHDOG_TRIPPED = 3
    WATCHDOG_TRIPPED_MASK = 0x0008
    LATCHED_POSE_VALID = 4
    LATCHED_POSE_VALID_MASK = 0x0010
    FORCE_VALID = 5
    FORCE_VALID_MASK = 0x0020
    TOOL_SET = 6
    TOOL_SET_MASK = 0x0040
    NAMES = {0: "drives_enabled", 1: "automatic_mode", 2: "host_heartbeat_ok", 3: "watchdog_tripped", 4: "latched_pose_valid", 5: "force_valid", 6: "tool_set"}


class CommandCode:
    """What the command block asks for (command register `code`)."""

    NONE = 0
    MOVE_LIN = 1
    MOVE_LIN_REL = 2
    MOVE_PTP = 3
    GUARDED_APPROACH = 4
    HOLD = 5
    SET_TOOL = 6
    RESET_FAULT = 7
    NAMES = {0: "none", 1: "move_lin", 2: "move_lin_rel", 3: "move_ptp", 4: "guarded_approach", 5: "hold", 6: "set_tool", 7: "reset_fault"}


class Axis:
    """The approach axis of a guarded approach."""

    NONE = 0
    TOOL_X = 1
    TOOL_Y = 2
    TOOL_Z = 3
    BASE_X = 4
    BASE_Y = 5
    BASE_Z = 6
    NAMES = {0: "none", 1: "tool_x", 2: "tool_y", 3: "tool_z", 4: "base_x", 5: "base_y", 6: "base_z"}


class GuardSource:
    """Bit numbers of `guard_sources` (command) and `guard_fired` (status)."""

    HOST_STOP = 0
    HOST_STOP_MASK = 0x0001
    DIGITAL_INPUT = 1
    DIGITAL_INPUT_MASK = 0x0002
    FORCE = 2
    FORCE_MASK = 0x0004
    NAMES = {0: "host_stop", 1: "digital_input", 2: "force"}


class Result:
    """How a command ended, or why it was rejected (status register `result`)."""

    NONE = 0
    DONE = 1
    GUARD_FIRED = 2
    MAX_TRAVEL = 3
    STOPPED = 4
    WATCHDOG = 5
    ROBOT_FAULT = 6
    SAFETY_STOPPED = 7
    SUPERSEDED = 8
    ACCEPTED = 9
    REJECTED_UNKNOWN_COMMAND = 32
    REJECTED_BAD_PARAMETER = 33
    REJECTED_BUSY = 34
    REJECTED_NOT_READY = 35
    REJECTED_FAULTED = 36
    REJECTED_UNREACHABLE = 37
    REJECTED_HEARTBEAT_STALE = 38
    NAMES = {0: "none", 1: "done", 2: "guard_fired", 3: "max_travel", 4: "stopped", 5: "watchdog", 6: "robot_fault", 7: "safety_stopped", 8: "superseded", 9: "accepted", 32: "rejected_unknown_command", 33: "rejected_bad_parameter", 34: "rejected_busy", 35: "rejected_not_ready", 36: "rejected_faulted", 37: "rejected_unreachable", 38: "rejected_heartbeat_stale"}


class Identification:
    """Who the bridge is: read first, checked before anything else. Access R."""

    ADDRESS = 0
    LENGTH = 10
    MAGIC = 0
    MAP_MAJOR = 2
    MAP_MINOR = 3
    STATUS_ADDRESS = 4
    STATUS_LENGTH = 5
    CONTROL_ADDRESS = 6
    CONTROL_LENGTH = 7
    COMMAND_ADDRESS = 8
    COMMAND_LENGTH = 9
    # (name, address, type, unit): type u16, i32, u32 or an enumeration's name
    REGISTERS = [
        ("magic", 0, "u32", ""),
        ("map_major", 2, "u16", ""),
        ("map_minor", 3, "u16", ""),
        ("status_address", 4, "u16", ""),
        ("status_length", 5, "u16", ""),
        ("control_address", 6, "u16", ""),
        ("control_length", 7, "u16", ""),
        ("command_address", 8, "u16", ""),
        ("command_length", 9, "u16", ""),
    ]


class StatusBlock:
    """Robot -> host: the robot's state, one consistent snapshot per read. Access R."""

    ADDRESS = 100
    LENGTH = 53
    HEARTBEAT = 100
    STATE = 101
    STATUS_BITS = 102
    ACK_SEQ = 103
    ACK_RESULT = 104
    REJECT_DETAIL = 105
    DONE_SEQ = 106
    RESULT = 107
    GUARD_FIRED = 108
    STOP_SEEN = 109
    TOOL = 110
    ROBOT_TIME_MS = 111
    X_UM = 113
    Y_UM = 115
    Z_UM = 117
    A_MDEG = 119
    B_MDEG = 121
    C_MDEG = 123
    LATCHED_X_UM = 125
    LATCHED_Y_UM = 127
    LATCHED_Z_UM = 129
    LATCHED_A_MDEG = 131
    LATCHED_B_MDEG = 133
    LATCHED_C_MDEG = 135
    FORCE_MN = 137
    A1_MDEG = 139
    A2_MDEG = 141
    A3_MDEG = 143
    A4_MDEG = 145
    A5_MDEG = 147
    A6_MDEG = 149
    A7_MDEG = 151
    # (name, address, type, unit): type u16, i32, u32 or an enumeration's name
    REGISTERS = [
        ("heartbeat", 100, "u16", ""),
        ("state", 101, "RobotState", ""),
        ("status_bits", 102, "u16", ""),
        ("ack_seq", 103, "u16", ""),
        ("ack_result", 104, "Result", ""),
        ("reject_detail", 105, "u16", ""),
        ("done_seq", 106, "u16", ""),
        ("result", 107, "Result", ""),
        ("guard_fired", 108, "u16", ""),
        ("stop_seen", 109, "u16", ""),
        ("tool", 110, "u16", ""),
        ("robot_time_ms", 111, "u32", "ms"),
        ("x_um", 113, "i32", "um"),
        ("y_um", 115, "i32", "um"),
        ("z_um", 117, "i32", "um"),
        ("a_mdeg", 119, "i32", "mdeg"),
        ("b_mdeg", 121, "i32", "mdeg"),
        ("c_mdeg", 123, "i32", "mdeg"),
        ("latched_x_um", 125, "i32", "um"),
        ("latched_y_um", 127, "i32", "um"),
        ("latched_z_um", 129, "i32", "um"),
        ("latched_a_mdeg", 131, "i32", "mdeg"),
        ("latched_b_mdeg", 133, "i32", "mdeg"),
        ("latched_c_mdeg", 135, "i32", "mdeg"),
        ("force_mN", 137, "i32", "mN"),
        ("a1_mdeg", 139, "i32", "mdeg"),
        ("a2_mdeg", 141, "i32", "mdeg"),
        ("a3_mdeg", 143, "i32", "mdeg"),
        ("a4_mdeg", 145, "i32", "mdeg"),
        ("a5_mdeg", 147, "i32", "mdeg"),
        ("a6_mdeg", 149, "i32", "mdeg"),
        ("a7_mdeg", 151, "i32", "mdeg"),
    ]


class HostControl:
    """Host -> robot: heartbeat, stop request, watchdog time. Access RW."""

    ADDRESS = 200
    LENGTH = 3
    HOST_HEARTBEAT = 200
    STOP_REQUEST = 201
    WATCHDOG_MS = 202
    # (name, address, type, unit): type u16, i32, u32 or an enumeration's name
    REGISTERS = [
        ("host_heartbeat", 200, "u16", ""),
        ("stop_request", 201, "u16", ""),
        ("watchdog_ms", 202, "u16", "ms"),
    ]


class Command:
    """Host -> robot: one command, written whole in one request, committed by a new seq. Access RW."""

    ADDRESS = 300
    LENGTH = 24
    SEQ = 300
    CODE = 301
    GUARD_SOURCES = 302
    AXIS = 303
    DIGITAL_INPUT = 304
    TOOL = 305
    SPEED = 306
    FORCE_THRESHOLD_MN = 308
    MAX_TRAVEL_UM = 310
    X_UM = 312
    Y_UM = 314
    Z_UM = 316
    A_MDEG = 318
    B_MDEG = 320
    C_MDEG = 322
    # (name, address, type, unit): type u16, i32, u32 or an enumeration's name
    REGISTERS = [
        ("seq", 300, "u16", ""),
        ("code", 301, "CommandCode", ""),
        ("guard_sources", 302, "u16", ""),
        ("axis", 303, "Axis", ""),
        ("digital_input", 304, "u16", ""),
        ("tool", 305, "u16", ""),
        ("speed", 306, "i32", "um/s"),
        ("force_threshold_mN", 308, "i32", "mN"),
        ("max_travel_um", 310, "i32", "um"),
        ("x_um", 312, "i32", "um"),
        ("y_um", 314, "i32", "um"),
        ("z_um", 316, "i32", "um"),
        ("a_mdeg", 318, "i32", "mdeg"),
        ("b_mdeg", 320, "i32", "mdeg"),
        ("c_mdeg", 322, "i32", "mdeg"),
    ]
