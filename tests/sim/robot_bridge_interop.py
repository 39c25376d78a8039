#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Interoperability of palp-sim's robot bridge with an independent Modbus stack.

Debian's python3-pymodbus (3.0), run with the system interpreter /usr/bin/python3, talks to
`palp-sim --robot-port 0` (protocol/robot-bridge.md): it reads the identification block, writes
the host control block, commits set_tool and move_lin_rel, polls ack/done, and checks the
exceptions for a write into the status block, a read across blocks, a watchdog_ms out of range
and FC4. Exits 0 when everything matches; otherwise prints what differed and exits 1.

Usage: robot_bridge_interop.py <path to palp-sim>
"""
import re
import subprocess
import sys
import time


def import_pymodbus_tcp():
    # Debian's pymodbus 3.0 imports its serial client from pymodbus.client too: python3-serial
    # and python3-serial-asyncio come with it from scripts/install-deps
    from pymodbus.client import ModbusTcpClient
    return ModbusTcpClient


failures = []


def check(what, got, expected):
    if got != expected:
        failures.append(f"{what}: got {got!r}, expected {expected!r}")
        print(f"MISMATCH {what}: got {got!r}, expected {expected!r}", file=sys.stderr)


def s32(hi, lo):
    v = (hi << 16) | lo
    return v - (1 << 32) if v & 0x80000000 else v


def words(v):
    v &= 0xFFFFFFFF
    return [v >> 16, v & 0xFFFF]


def command_block(seq, code, speed=0, tool=0, x=0, y=0, z=0):
    regs = [seq, code, 0, 0, 0, tool] + words(speed) + words(0) + words(0)
    regs += words(x) + words(y) + words(z) + words(0) + words(0) + words(0)
    assert len(regs) == 24
    return regs


def main():
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    ModbusTcpClient = import_pymodbus_tcp()
    sim = subprocess.Popen([sys.argv[1], "--port", "0", "--control-port", "0", "--pace", "fast",
                            "--robot-port", "0"], stdout=subprocess.PIPE, text=True)
    client = None
    try:
        banner = sim.stdout.readline()
        m = re.search(r"robot bridge on tcp://127\.0\.0\.1:(\d+)", banner)
        if not m:
            print(f"FAIL: palp-sim's first line names no robot bridge port: {banner!r}", file=sys.stderr)
            return 1
        client = ModbusTcpClient("127.0.0.1", port=int(m.group(1)), timeout=3)
        if not client.connect():
            print("FAIL: cannot connect to the robot bridge", file=sys.stderr)
            return 1

        def read(address, count):
            rr = client.read_holding_registers(address, count, slave=1)
            if rr.isError():
                failures.append(f"read {address}+{count} answered {rr}")
                return [0] * count
            return list(rr.registers)

        def status():
            return read(100, 53)

        heartbeat = [0]

        def beat():
            heartbeat[0] += 1
            client.write_register(200, heartbeat[0], slave=1)

        def wait_done(seq, timeout_s=10.0):
            end = time.monotonic() + timeout_s
            st = status()
            while st[6] != seq and time.monotonic() < end:
                beat()
                time.sleep(0.02)
                st = status()
            return st

        check("identification", read(0, 10),
              [0x5041, 0x4C50, 1, 0, 100, 53, 200, 3, 300, 24])
        check("host control at start", read(200, 3), [0, 0, 500])
        beat()
        st = status()
        check("state idle", st[1], 1)
        z0 = s32(st[17], st[18])

        # set_tool 1: the probe's tip 200 mm along the flange's z
        client.write_registers(300, command_block(1, 6, tool=1, z=200000), slave=1)
        st = wait_done(1)
        check("set_tool ack_seq", st[3], 1)
        check("set_tool ack_result accepted", st[4], 9)
        check("set_tool result done", st[7], 1)
        check("tool", st[10], 1)
        z_tool = s32(st[17], st[18])
        check("tcp z with the tool (um)", z_tool, z0 - 200000)

        # move_lin_rel 5 mm along the tool's +z (down) at 10 mm/s
        client.write_registers(300, command_block(2, 2, speed=10000, z=5000), slave=1)
        beat()
        st = status()
        end = time.monotonic() + 5
        while st[3] != 2 and time.monotonic() < end:
            st = status()
        check("move ack_seq", st[3], 2)
        check("move ack_result accepted", st[4], 9)
        st = wait_done(2)
        check("move done_seq", st[6], 2)
        check("move result done", st[7], 1)
        check("state idle after the move", st[1], 1)
        check("tcp z after the move (um)", s32(st[17], st[18]), z_tool - 5000)

        # exceptions
        rr = client.write_registers(100, [1], slave=1)
        check("write into the status block: exception", getattr(rr, "exception_code", None), 2)
        rr = client.read_holding_registers(95, 10, slave=1)
        check("read across blocks: exception", getattr(rr, "exception_code", None), 2)
        rr = client.write_register(202, 50, slave=1)
        check("watchdog_ms 50: exception", getattr(rr, "exception_code", None), 3)
        rr = client.read_input_registers(0, 1, slave=1)
        check("FC4: exception", getattr(rr, "exception_code", None), 1)
        check("status still served", read(0, 2), [0x5041, 0x4C50])
    finally:
        if client is not None:
            client.close()
        sim.terminate()
        sim.wait(timeout=10)
    if failures:
        print(f"robot bridge interop: {len(failures)} mismatches", file=sys.stderr)
        return 1
    print("robot bridge interop: identification, control, set_tool, move_lin_rel and 4 exceptions match")
    return 0


if __name__ == "__main__":
    sys.exit(main())
