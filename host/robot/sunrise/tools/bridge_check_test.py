#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""End-to-end test of bridge_check.py against the Java bridge core (ModbusTcpServer + BridgeCore)
with a simulated arm (LoopbackBridge) on a loopback ephemeral port.

usage: bridge_check_test.py JAVA CLASSPATH
"""
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, "bridge_check.py")
sys.path.insert(0, HERE)
import bridge_check  # noqa: E402
import palp_rb_map as rb  # noqa: E402


def run(where, *args):
    p = subprocess.run([sys.executable, CHECK, args[0], where] + list(args[1:]), capture_output=True, text=True,
                       timeout=30)
    return p.returncode, p.stdout + p.stderr


def connect(where):
    """A client of bridge_check's own. The bridge serves one client at a time and closes a second
    connection at once: until it has seen the previous client's close, try again (up to 2 s)."""
    for attempt in range(100):
        c = bridge_check.Client(where)
        try:
            c.read(rb.HostControl.WATCHDOG_MS, 1)
            return c
        except bridge_check.BridgeError:
            c.close()
            if attempt == 99:
                raise
            time.sleep(0.02)


def watchdog_ms(where, write=None):
    """Writes watchdog_ms when given and reads it back."""
    c = connect(where)
    try:
        if write is not None:
            c.write(rb.HostControl.WATCHDOG_MS, [write])
        return c.read(rb.HostControl.WATCHDOG_MS, 1)[0]
    finally:
        c.close()


def stale_start_command_accepted(where):
    """bridge_check's Bridge, first contact after the heartbeat went stale, a 5 mm move whose
    first poll comes 30 ms (six cycles) after the command block; True when the move is accepted."""
    c = connect(where)
    try:
        b = bridge_check.Bridge(c)
        prompt_wait = b.wait

        def late_wait(ready, timeout_s, what):
            time.sleep(0.03)
            return prompt_wait(ready, timeout_s, what)

        b.wait = late_wait
        try:
            seq = b.command(rb.CommandCode.MOVE_LIN_REL, speed=50000, z_um=5000)
        except bridge_check.BridgeError as e:
            print("command refused: %s" % e)
            return False
        b.wait = prompt_wait
        b.wait(lambda s: s["done_seq"] == seq, 2.0, "the move")
        seq = b.command(rb.CommandCode.MOVE_LIN_REL, speed=50000, z_um=-5000)  # back where it was
        b.wait(lambda s: s["done_seq"] == seq, 2.0, "the move back")
        return True
    finally:
        c.close()


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    bridge = subprocess.Popen([argv[1], "-cp", argv[2], "org.palp.bridge.LoopbackBridge"], stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    failures = []

    def expect(ok, what, out):
        if not ok:
            failures.append("%s\n%s" % (what, out))

    try:
        line = bridge.stdout.readline()
        m = re.match(r"port (\d+)", line)
        if not m:
            print("FAIL: LoopbackBridge printed %r, expected 'port N'" % line)
            return 1
        where = "127.0.0.1:" + m.group(1)

        rc, out = run(where, "id")
        expect(rc == 0 and out.strip() == "palp bridge, register map 1.0: status 100+53, control 200+3, command 300+24",
               "id: exit %d" % rc, out)

        rc, out = run(where, "status")
        expect(rc == 0 and re.search(r"^state idle; bits drives_enabled (host_heartbeat_ok )?force_valid$", out, re.M)
               and "pose    x 0.000 y 0.000 z 300.000 mm, A 180.000 B 0.000 C 180.000 deg" in out,
               "status: exit %d" % rc, out)

        rc, out = run(where, "watchdog", "--watchdog-ms", "100")
        m = re.search(r"host_heartbeat_ok cleared (\d+) ms", out)
        # stale after more than 100 ms, seen by the next 5 ms cycle, read by the next poll
        expect(rc == 0 and m and 95 <= int(m.group(1)) <= 500 and "watchdog_ms restored to 500" in out,
               "watchdog: exit %d, cleared after 95..500 ms, the bridge's 500 ms put back" % rc, out)
        watchdog = watchdog_ms(where)
        expect(watchdog == 500, "after watchdog: watchdog_ms %d, expected 500" % watchdog, "")

        # a tool that starts after the heartbeat went stale beats before its command, so the
        # command is not refused even when the tool's first poll comes a few cycles late (a loaded
        # machine): the late poll is made certain by holding the first wait back 30 ms
        watchdog_ms(where, 100)
        time.sleep(0.3)
        expect(stale_start_command_accepted(where), "a command after a stale heartbeat was refused", "")
        watchdog_ms(where, 500)

        rc, out = run(where, "stop-latency", "--runs", "3", "--speed-mm-per-s", "50", "--distance-mm", "20",
                      "--stop-after-ms", "60")
        runs = re.findall(r"run \d: stopped after ([\d.]+) ms, braked ([\d.]+) mm", out)
        expect(rc == 0 and len(runs) == 3 and all(10 <= float(t) < 200 for t, _ in runs)
               # 10 ms stop latency at 50 mm/s: 0.5 mm (+ up to a cycle's travel either side)
               and all(0.2 <= float(d) <= 1.2 for _, d in runs) and "stop latency (ms, stop write to stop_seen): n 3" in out,
               "stop-latency: exit %d, 3 runs stopped after 10..200 ms, braked 0.2..1.2 mm" % rc, out)

        rc, out = run(where, "approach", "--max-travel-mm", "20", "--speed-mm-per-s", "20", "--force-N", "2",
                      "--plate-z-mm", "310", "--retreat-mm", "5")
        m = re.search(r"latched z - plate z = ([-\d.]+) mm", out)
        # the force reaches 2 N 2 mm into the 1 N/mm plate; one 5 ms cycle at 20 mm/s is 0.1 mm (a
        # loaded CI machine may stretch a cycle: up to 50 ms late is accepted)
        expect(rc == 0 and "approach: guard_fired (force)" in out and m and 1.99 <= float(m.group(1)) <= 3.0,
               "approach: exit %d, guard_fired (force) 2.0..3.0 mm into the plate" % rc, out)

        rc, out = run(where, "approach", "--max-travel-mm", "-3", "--speed-mm-per-s", "50", "--force-N", "2",
                      "--retreat-mm", "0")
        expect(rc == 0 and "approach: max_travel (none)" in out, "approach upwards: exit %d, max_travel" % rc, out)

        rc, out = run("127.0.0.1:1", "id")
        expect(rc == 3 and "cannot connect to the bridge at 127.0.0.1:1" in out, "no bridge: exit %d, expected 3" % rc,
               out)
    finally:
        bridge.stdin.close()
        try:
            bridge.wait(timeout=5)
        except subprocess.TimeoutExpired:
            bridge.kill()
    for f in failures:
        print("FAIL: " + f)
    if not failures:
        print("bridge_check.py: id, status, watchdog (and its restore), a command after a stale heartbeat, "
              "stop-latency and approach pass against the Java bridge")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
