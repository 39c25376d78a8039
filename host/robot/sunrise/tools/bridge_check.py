#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""bridge_check: commissioning checks of a palp robot bridge (host/robot/sunrise/COMMISSIONING.md).

Its own Modbus TCP client over the standard library (no SDK, no libmodbus), with the register map
generated from map.hpp (palp_rb_map.py). Lengths in mm, forces in N, times in ms.

  bridge_check.py id ROBOT[:PORT]
  bridge_check.py status ROBOT[:PORT]
  bridge_check.py watchdog ROBOT[:PORT] [--watchdog-ms 500]
  bridge_check.py stop-latency ROBOT[:PORT] [--runs 20] [--speed-mm-per-s 10] [--distance-mm 20]
                  [--stop-after-ms 300]
  bridge_check.py approach ROBOT[:PORT] --max-travel-mm M [--speed-mm-per-s 1] [--force-N F]
                  [--input N] [--plate-z-mm Z] [--retreat-mm 5]

Exit status: 0 done, 1 a check failed or the bridge refused, 2 usage error, 3 no connection.
"""
import argparse
import os
import socket
import statistics
import struct
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import palp_rb_map as rb  # noqa: E402  (generated from map.hpp)


class BridgeError(Exception):
    pass


class Client:
    """One Modbus TCP connection; every block is read or written in one request."""

    def __init__(self, address, timeout_s=1.0):
        host, _, port = address.partition(":")
        self.where = "%s:%s" % (host, port or rb.DEFAULT_PORT)
        try:
            self.sock = socket.create_connection((host, int(port or rb.DEFAULT_PORT)), timeout=timeout_s)
        except OSError as e:
            raise ConnectionError("cannot connect to the bridge at %s: %s" % (self.where, e.strerror or e))
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.tid = 0

    def _recv(self, n):
        data = b""
        while len(data) < n:
            try:
                chunk = self.sock.recv(n - len(data))
            except socket.timeout:
                raise BridgeError("no reply from the bridge at %s within the timeout" % self.where)
            if not chunk:
                raise BridgeError("connection closed by the bridge at %s" % self.where)
            data += chunk
        return data

    def request(self, pdu):
        self.tid = (self.tid + 1) & 0xFFFF
        self.sock.sendall(struct.pack(">HHHB", self.tid, 0, len(pdu) + 1, 1) + pdu)
        tid, proto, length, _unit = struct.unpack(">HHHB", self._recv(7))
        reply = self._recv(length - 1)
        if tid != self.tid or proto != 0:
            raise BridgeError("reply out of step (transaction %d, expected %d)" % (tid, self.tid))
        if reply[0] & 0x80:
            raise BridgeError("the bridge answered exception %02d to function %d" % (reply[1], pdu[0]))
        return reply

    def read(self, address, count):
        reply = self.request(struct.pack(">BHH", 3, address, count))
        return list(struct.unpack(">%dH" % count, reply[2:2 + 2 * count]))

    def write(self, address, values):
        values = [v & 0xFFFF for v in values]
        self.request(struct.pack(">BHHB", 16, address, len(values), 2 * len(values))
                     + struct.pack(">%dH" % len(values), *values))

    def close(self):
        """Closes the connection; the bridge then serves the next client."""
        self.sock.close()


def i32(hi, lo):
    v = (hi << 16) | lo
    return v - (1 << 32) if v & 0x80000000 else v


def words(v):
    v &= 0xFFFFFFFF
    return [v >> 16, v & 0xFFFF]


def decode(block, regs):
    """A dict of a block's registers by name (i32/u32 combined)."""
    out = {}
    for name, address, kind, _unit in block.REGISTERS:
        at = address - block.ADDRESS
        if kind == "i32":
            out[name] = i32(regs[at], regs[at + 1])
        elif kind == "u32":
            out[name] = (regs[at] << 16) | regs[at + 1]
        else:
            out[name] = regs[at]
    return out


def bits(value, enum):
    return " ".join(name for bit, name in sorted(enum.NAMES.items()) if value & (1 << bit)) or "none"


def result_name(v):
    return rb.Result.NAMES.get(v, "unknown result %d" % v)


class Bridge:
    """The bridge with the host's side of the handshake (robot-bridge.md section 8.1)."""

    def __init__(self, client):
        self.c = client
        ident = decode(rb.Identification, client.read(rb.Identification.ADDRESS, rb.Identification.LENGTH))
        if ident["magic"] != rb.MAGIC:
            raise BridgeError("%s is not a palp bridge (magic 0x%08x, expected 0x%08x)"
                              % (client.where, ident["magic"], rb.MAGIC))
        if ident["map_major"] != rb.MAP_MAJOR:
            raise BridgeError("the bridge serves register map %d.%d, this tool speaks %d.%d: deploy the bridge "
                              "of the SDK's palp version" % (ident["map_major"], ident["map_minor"],
                                                            rb.MAP_MAJOR, rb.MAP_MINOR))
        self.ident = ident
        control = decode(rb.HostControl, client.read(rb.HostControl.ADDRESS, rb.HostControl.LENGTH))
        self.heartbeat = control["host_heartbeat"]
        self.stop_value = control["stop_request"]
        self.watchdog_ms = control["watchdog_ms"]
        self.seq = self.status()["ack_seq"]

    def status(self):
        return decode(rb.StatusBlock, self.c.read(rb.StatusBlock.ADDRESS, rb.StatusBlock.LENGTH))

    def beat(self):
        self.heartbeat = (self.heartbeat + 1) & 0xFFFF
        self.c.write(rb.HostControl.HOST_HEARTBEAT, [self.heartbeat])

    def stop(self):
        self.stop_value = (self.stop_value + 1) & 0xFFFF
        self.c.write(rb.HostControl.STOP_REQUEST, [self.stop_value])
        return self.stop_value

    def command(self, code, **fields):
        """Writes a command block whole with the next seq and waits for its ack."""
        self.seq = self.seq % 0xFFFF + 1
        # a motion is refused while the host heartbeat is stale (rule 9): this process may have
        # started longer than watchdog_ms after the last beat, so beat first (the bridge takes
        # the control block before the command block in its cycle, section 8.3)
        self.beat()
        regs = [0] * rb.Command.LENGTH
        regs[0], regs[1] = self.seq, code
        for name, address, kind, _unit in rb.Command.REGISTERS:
            if name in fields:
                at = address - rb.Command.ADDRESS
                if kind in ("i32", "u32"):
                    regs[at:at + 2] = words(fields[name])
                else:
                    regs[at] = fields[name]
        self.c.write(rb.Command.ADDRESS, regs)
        s = self.wait(lambda s: s["ack_seq"] == self.seq, 1.0, "the ack of seq %d" % self.seq)
        if s["ack_result"] != rb.Result.ACCEPTED:
            detail = (" at register %d" % s["reject_detail"]) if s["reject_detail"] else ""
            raise BridgeError("command %d %s%s" % (self.seq, result_name(s["ack_result"]), detail))
        return self.seq

    def wait(self, ready, timeout_s, what):
        """Polls the status (beating) until ready(status); returns the status."""
        end = time.monotonic() + timeout_s
        while True:
            self.beat()
            s = self.status()
            if ready(s):
                return s
            if time.monotonic() > end:
                raise BridgeError("timed out after %.1f s waiting for %s" % (timeout_s, what))
            time.sleep(0.002)


def mm(um):
    return um / 1000.0


def pose_text(s, prefix=""):
    return "x %.3f y %.3f z %.3f mm, A %.3f B %.3f C %.3f deg" % tuple(
        s[prefix + k] / 1000.0 for k in ("x_um", "y_um", "z_um", "a_mdeg", "b_mdeg", "c_mdeg"))


def cmd_id(b, _args):
    i = b.ident
    print("palp bridge, register map %d.%d: status %d+%d, control %d+%d, command %d+%d"
          % (i["map_major"], i["map_minor"], i["status_address"], i["status_length"], i["control_address"],
             i["control_length"], i["command_address"], i["command_length"]))
    return 0


def cmd_status(b, _args):
    s = b.status()
    print("state %s; bits %s" % (rb.RobotState.NAMES.get(s["state"], s["state"]), bits(s["status_bits"], rb.StatusBit)))
    print("ack %d %s (detail %d); done %d %s, guards %s; stop_seen %d; tool %d; robot time %d ms; heartbeat %d"
          % (s["ack_seq"], result_name(s["ack_result"]), s["reject_detail"], s["done_seq"], result_name(s["result"]),
             bits(s["guard_fired"], rb.GuardSource), s["stop_seen"], s["tool"], s["robot_time_ms"], s["heartbeat"]))
    print("pose    " + pose_text(s))
    print("latched " + pose_text(s, "latched_"))
    print("force %.3f N; joints %s deg" % (s["force_mN"] / 1000.0,
                                          " ".join("%.3f" % (s["a%d_mdeg" % k] / 1000.0) for k in range(1, 8))))
    return 0


def cmd_watchdog(b, args):
    """Measures the bridge's watchdog at --watchdog-ms, then restores the watchdog it had."""
    b.c.write(rb.HostControl.WATCHDOG_MS, [args.watchdog_ms])
    try:
        return measure_watchdog(b, args)
    finally:
        b.beat()
        b.c.write(rb.HostControl.WATCHDOG_MS, [b.watchdog_ms])
        print("watchdog_ms restored to %d" % b.watchdog_ms)


def measure_watchdog(b, args):
    end = time.monotonic() + 2.0
    while time.monotonic() < end:
        b.beat()
        time.sleep(args.watchdog_ms / 8000.0)
    ok = rb.StatusBit.HOST_HEARTBEAT_OK_MASK
    b.beat()  # the last beat: the bridge must clear the bit watchdog_ms after it
    t0 = time.monotonic()
    if not b.status()["status_bits"] & ok:
        print("FAIL: host_heartbeat_ok is not set while the host beats")
        return 1
    while b.status()["status_bits"] & ok:
        if time.monotonic() - t0 > args.watchdog_ms / 1000.0 + 2.0:
            print("FAIL: host_heartbeat_ok still set %.0f ms after the last beat" % ((time.monotonic() - t0) * 1e3))
            return 1
        time.sleep(0.001)
    print("watchdog_ms %d: host_heartbeat_ok cleared %.0f ms after the last beat"
          % (args.watchdog_ms, (time.monotonic() - t0) * 1e3))
    return 0


def histogram(name, values, bucket):
    print("%s: n %d, min %.1f, median %.1f, p95 %.1f, max %.1f" % (
        name, len(values), min(values), statistics.median(values),
        sorted(values)[max(0, int(round(0.95 * len(values))) - 1)], max(values)))
    counts = {}
    for v in values:
        counts[int(v // bucket)] = counts.get(int(v // bucket), 0) + 1
    for k in sorted(counts):
        print("  %6.1f..%6.1f %s %d" % (k * bucket, (k + 1) * bucket, "#" * counts[k], counts[k]))


def cmd_stop_latency(b, args):
    latencies, brakes = [], []
    for run in range(args.runs):
        sign = 1 if run % 2 == 0 else -1
        b.command(rb.CommandCode.MOVE_LIN_REL, speed=int(args.speed_mm_per_s * 1000),
                  z_um=int(sign * args.distance_mm * 1000))
        t_end = time.monotonic() + args.stop_after_ms / 1000.0
        while time.monotonic() < t_end:
            b.beat()
            time.sleep(0.005)
        t0 = time.monotonic()
        value = b.stop()
        s = b.wait(lambda s: s["stop_seen"] == value, 5.0, "stop_seen %d" % value)
        latencies.append((time.monotonic() - t0) * 1e3)
        brakes.append(mm(abs(s["z_um"] - s["latched_z_um"])))
        if s["done_seq"] != b.seq:
            s = b.wait(lambda s: s["done_seq"] == b.seq, 2.0, "done of seq %d" % b.seq)
        print("run %d: %s after %.1f ms, braked %.3f mm after the latch"
              % (run + 1, result_name(s["result"]), latencies[-1], brakes[-1]))
    histogram("stop latency (ms, stop write to stop_seen)", latencies, 10.0)
    histogram("braking distance after the latch (mm)", brakes, 0.1)
    return 0


def cmd_approach(b, args):
    guards = 0
    fields = dict(axis=rb.Axis.TOOL_Z, speed=int(args.speed_mm_per_s * 1000), max_travel_um=int(args.max_travel_mm * 1000))
    if args.force_N is not None:
        guards |= rb.GuardSource.FORCE_MASK
        fields["force_threshold_mN"] = int(args.force_N * 1000)
    if args.input is not None:
        guards |= rb.GuardSource.DIGITAL_INPUT_MASK
        fields["digital_input"] = args.input
    if not guards:
        print("approach: give --force-N, --input or both (the guards)", file=sys.stderr)
        return 2
    seq = b.command(rb.CommandCode.GUARDED_APPROACH, guard_sources=guards, **fields)
    timeout = abs(args.max_travel_mm) / args.speed_mm_per_s + 5.0
    s = b.wait(lambda s: s["done_seq"] == seq, timeout, "the approach (seq %d) to finish" % seq)
    print("approach: %s (%s)" % (result_name(s["result"]), bits(s["guard_fired"], rb.GuardSource)))
    print("latched z %.3f mm, z at rest %.3f mm, force at rest %.3f N"
          % (mm(s["latched_z_um"]), mm(s["z_um"]), s["force_mN"] / 1000.0))
    if args.plate_z_mm is not None:
        print("latched z - plate z = %.3f mm" % (mm(s["latched_z_um"]) - args.plate_z_mm))
    if args.retreat_mm:
        seq = b.command(rb.CommandCode.MOVE_LIN_REL, speed=int(max(args.speed_mm_per_s, 5.0) * 1000),
                        z_um=int(-args.retreat_mm * 1000 * (1 if args.max_travel_mm > 0 else -1)))
        b.wait(lambda s: s["done_seq"] == seq, 30.0, "the retreat")
    return 0 if s["result"] in (rb.Result.GUARD_FIRED, rb.Result.MAX_TRAVEL) else 1


def main(argv):
    p = argparse.ArgumentParser(prog="bridge_check.py", description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="command", required=True)
    for name in ("id", "status", "watchdog", "stop-latency", "approach"):
        q = sub.add_parser(name)
        q.add_argument("robot", help="ROBOT[:PORT], port %d by default" % rb.DEFAULT_PORT)
        if name == "watchdog":
            q.add_argument("--watchdog-ms", type=int, default=rb.DEFAULT_WATCHDOG_MS)
        if name == "stop-latency":
            q.add_argument("--runs", type=int, default=20)
            q.add_argument("--speed-mm-per-s", type=float, default=10.0)
            q.add_argument("--distance-mm", type=float, default=20.0)
            q.add_argument("--stop-after-ms", type=float, default=300.0)
        if name == "approach":
            q.add_argument("--max-travel-mm", type=float, required=True)
            q.add_argument("--speed-mm-per-s", type=float, default=1.0)
            q.add_argument("--force-N", type=float)
            q.add_argument("--input", type=int)
            q.add_argument("--plate-z-mm", type=float)
            q.add_argument("--retreat-mm", type=float, default=5.0)
    args = p.parse_args(argv[1:])
    try:
        bridge = Bridge(Client(args.robot))
    except ConnectionError as e:
        print("bridge_check: %s" % e, file=sys.stderr)
        return 3
    except BridgeError as e:
        print("bridge_check: %s" % e, file=sys.stderr)
        return 1
    handler = {"id": cmd_id, "status": cmd_status, "watchdog": cmd_watchdog, "stop-latency": cmd_stop_latency,
               "approach": cmd_approach}[args.command]
    try:
        return handler(bridge, args)
    except BridgeError as e:
        print("bridge_check: %s" % e, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        bridge.stop()
        print("bridge_check: interrupted; stop requested", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
