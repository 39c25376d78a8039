// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge.sunrise;

import javax.inject.Inject;

import org.palp.bridge.BridgeCore;
import org.palp.bridge.Clock;
import org.palp.bridge.ModbusTcpServer;
import org.palp.bridge.RegisterMap;
import org.palp.bridge.RegisterStore;

import com.kuka.common.ThreadUtil;
import com.kuka.roboticsAPI.applicationModel.RoboticsAPIApplication;
import com.kuka.roboticsAPI.deviceModel.LBR;

/**
 * The palp robot bridge on KUKA Sunrise: serves the register map of protocol/robot-bridge.md over
 * Modbus TCP (port 30005 by default, process data "palpPort", 30000..30010 only) and runs the
 * bridge cycle every CYCLE_MS. The protocol is the core's (org.palp.bridge, tested on the host);
 * this class only wires it to the robot. NOT compiled in the palp build (no KUKA jars there).
 *
 * CHECK ON A REAL CONTROLLER (commissioning checklist, host/robot/sunrise/COMMISSIONING.md):
 * the cycle period actually achieved (the loop logs the worst period every minute), that
 * dispose() runs when the application is stopped from the smartPAD and frees the port.
 */
public class PalpBridgeApplication extends RoboticsAPIApplication {
  /** The bridge cycle's period; the map allows at most 20 ms. */
  private static final int CYCLE_MS = 10;
  /** A client silent for this long is closed (the host writes its heartbeat every <= 2.5 s). */
  private static final int IDLE_TIMEOUT_MS = 10000;

  @Inject
  private LBR lbr;

  private RegisterStore store;
  private SunriseArm arm;
  private BridgeCore core;
  private ModbusTcpServer server;
  private volatile boolean running = true;
  private String lastArmError;

  @Override
  public void initialize() {
    int port = RegisterMap.DEFAULT_PORT;
    Object configured = getApplicationData().getProcessData("palpPort").getValue();  // CHECK: process data defined
    if (configured instanceof Integer) port = ((Integer) configured).intValue();
    if (port < 30000 || port > 30010)
      throw new IllegalArgumentException("palpPort " + port + " is outside 30000..30010 (the KLI's open ports)");
    store = new RegisterStore();
    arm = new SunriseArm(lbr, getLogger());
    core = new BridgeCore(store, arm, Clock.SYSTEM);
    try {
      server = new ModbusTcpServer(store, core, new ModbusTcpServer.Log() {
        @Override
        public void info(String message) {
          getLogger().info(message);
        }
      }, null, port, IDLE_TIMEOUT_MS);
    } catch (java.io.IOException e) {
      throw new IllegalStateException("palp bridge: cannot listen on port " + port + ": " + e.getMessage(), e);
    }
  }

  @Override
  public void run() {
    long worstMs = 0;
    long reportAt = System.nanoTime() / 1000000L + 60000L;
    long last = System.nanoTime() / 1000000L;
    String lastError = null;
    while (running) {
      try {
        core.cycle();
      } catch (RuntimeException e) {
        // a Robotics API call failed in the cycle: log it (once per message) and go on; the host
        // sees no fresh status while it persists and treats the bridge as gone
        if (!String.valueOf(e).equals(lastError)) getLogger().error("palp bridge: cycle failed: " + e);
        lastError = String.valueOf(e);
      }
      if (core.lastArmError() != null && !core.lastArmError().equals(lastArmError)) {
        lastArmError = core.lastArmError();
        getLogger().error("palp bridge: the robot refused a motion: " + lastArmError);
      }
      ThreadUtil.milliSleep(CYCLE_MS);
      long now = System.nanoTime() / 1000000L;
      worstMs = Math.max(worstMs, now - last);
      last = now;
      if (now >= reportAt) {
        getLogger().info("palp bridge: worst cycle period in the last minute " + worstMs + " ms");
        if (worstMs > 20) getLogger().warn("palp bridge: cycle period above the map's 20 ms");
        worstMs = 0;
        reportAt = now + 60000L;
      }
    }
  }

  /** Stops the arm, closes the client and the listening socket (the port is free for a restart). */
  @Override
  public void dispose() {
    running = false;
    try {
      if (arm != null) arm.stop();
    } finally {
      if (server != null) server.close();
      super.dispose();
    }
  }
}
