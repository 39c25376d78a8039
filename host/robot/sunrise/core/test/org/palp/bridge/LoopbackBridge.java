// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import java.io.IOException;
import java.net.InetAddress;

/**
 * The bridge core with a SimulatedArm on a loopback ephemeral port, for the test of
 * bridge_check.py and the SDK interop test. Prints "port N", cycles every 5 ms, and ends when
 * standard input closes (with --ignore-stdin: when killed), after 60 s at the latest.
 *
 * The core keeps the wall clock (its heartbeat watchdog counts on it, as on the controller); the
 * arm moves on a clock that advances exactly one cycle, 5 ms, per cycle. Cycles are paced to the
 * wall clock; a late cycle (a loaded machine) delays the arm's time instead of making it jump.
 */
public final class LoopbackBridge {
  private static final long CYCLE_MS = 5;

  private LoopbackBridge() {}

  public static void main(String[] args) throws IOException, InterruptedException {
    RegisterStore store = new RegisterStore();
    final FakeClock armClock = new FakeClock();
    final BridgeCore core = new BridgeCore(store, new SimulatedArm(armClock, 300000, 310000), Clock.SYSTEM);
    ModbusTcpServer server = new ModbusTcpServer(store, core, new ModbusTcpServer.Log() {
      @Override
      public void info(String message) {
        System.err.println(message);
      }
    }, InetAddress.getByName("127.0.0.1"), 0, 10000);
    System.out.println("port " + server.port());
    System.out.flush();
    final boolean[] done = {false};
    Thread stdin = new Thread(new Runnable() {
      @Override
      public void run() {
        try {
          while (System.in.read() >= 0) {
            // until the test closes it
          }
        } catch (IOException e) {
          // closed
        }
        synchronized (done) {
          done[0] = true;
        }
      }
    });
    stdin.setDaemon(true);
    if (!(args.length > 0 && args[0].equals("--ignore-stdin"))) stdin.start();
    long next = Clock.SYSTEM.millis();
    final long end = next + 60000L;
    while (Clock.SYSTEM.millis() < end) {
      synchronized (done) {
        if (done[0]) break;
      }
      core.cycle();
      armClock.now += CYCLE_MS;
      next += CYCLE_MS;
      final long now = Clock.SYSTEM.millis();
      if (next > now) {
        Thread.sleep(next - now);
      } else {
        next = now;  // late: the arm's time does not catch up by jumping
      }
    }
    server.close();
  }
}
