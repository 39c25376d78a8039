// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import static org.junit.Assert.assertArrayEquals;
import static org.junit.Assert.assertEquals;
import static org.junit.Assert.assertTrue;
import static org.junit.Assert.fail;

import java.io.BufferedReader;
import java.io.FileInputStream;
import java.io.IOException;
import java.io.InputStreamReader;
import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;

import org.junit.BeforeClass;
import org.junit.Test;
import org.palp.bridge.RegisterMap.Axis;
import org.palp.bridge.RegisterMap.CommandCode;
import org.palp.bridge.RegisterMap.GuardSource;
import org.palp.bridge.RegisterMap.Result;
import org.palp.bridge.RegisterMap.RobotState;

/**
 * The golden vectors of protocol/vectors/robot_bridge.txt (path in the system property
 * palp.vectors), read from the file: every int32 conversion both ways, and every block through
 * the Java store, encoders and core.
 */
public class GoldenVectorsTest {
  private static final List<long[]> int32s = new ArrayList<long[]>();  // value, hi, lo
  private static final Map<String, int[]> blocks = new LinkedHashMap<String, int[]>();
  private static final Map<String, Integer> addresses = new LinkedHashMap<String, Integer>();

  @BeforeClass
  public static void readVectors() throws IOException {
    String path = System.getProperty("palp.vectors");
    if (path == null) fail("set -Dpalp.vectors=<protocol/vectors/robot_bridge.txt>");
    BufferedReader in = new BufferedReader(new InputStreamReader(new FileInputStream(path), "UTF-8"));
    try {
      String line;
      String block = null;
      while ((line = in.readLine()) != null) {
        String[] w = line.trim().split("\\s+");
        if (w[0].length() == 0 || w[0].startsWith("#")) continue;
        if (w[0].equals("int32")) {
          int32s.add(new long[] {Long.parseLong(w[1]), Integer.parseInt(w[2], 16), Integer.parseInt(w[3], 16)});
        } else if (w[0].equals("block")) {
          block = w[1];
          addresses.put(block, Integer.valueOf(w[2]));
        } else if (w[0].equals("regs")) {
          int[] regs = new int[w.length - 1];
          for (int i = 1; i < w.length; ++i) regs[i - 1] = Integer.parseInt(w[i], 16);
          blocks.put(block, regs);
        } else {
          fail(path + ": unknown record '" + w[0] + "'");
        }
      }
    } finally {
      in.close();
    }
  }

  @Test
  public void everyVectorInTheFileHasACheckHere() {
    assertEquals(7, int32s.size());
    assertEquals("[Identification.this, StatusBlock.after_guard, HostControl.example, Command.guarded_approach, "
        + "Command.move_lin]", blocks.keySet().toString());
  }

  @Test
  public void int32ConvertsHighWordFirstBothWays() {
    for (long[] v : int32s) {
      int value = (int) v[0];
      assertEquals("hi of " + value, v[1], Words.hi(value));
      assertEquals("lo of " + value, v[2], Words.lo(value));
      assertEquals("value of " + v[1] + " " + v[2], value, Words.toInt((int) v[1], (int) v[2]));
    }
  }

  @Test
  public void identificationBlockIsTheVector() throws ModbusException {
    assertEquals(Integer.valueOf(RegisterMap.Identification.ADDRESS), addresses.get("Identification.this"));
    assertArrayEquals(blocks.get("Identification.this"),
        new RegisterStore().read(RegisterMap.Identification.ADDRESS, RegisterMap.Identification.LENGTH));
  }

  @Test
  public void statusBlockAfterTheGuardEncodesAndDecodesToTheVector() {
    int[] regs = blocks.get("StatusBlock.after_guard");
    assertEquals(Integer.valueOf(RegisterMap.StatusBlock.ADDRESS), addresses.get("StatusBlock.after_guard"));
    Status s = new Status();
    s.heartbeat = 4660;
    s.state = RobotState.IDLE;
    s.statusBits = 0x0077;
    s.ackSeq = 42;
    s.ackResult = Result.ACCEPTED;
    s.doneSeq = 42;
    s.result = Result.GUARD_FIRED;
    s.guardFired = GuardSource.FORCE_MASK;
    s.stopSeen = 3;
    s.tool = 1;
    s.robotTimeMs = 123456789L;
    s.pose = new Pose(500000, -123456, 212345, 180000, 0, -179999);
    s.latched = new Pose(500000, -123456, 212350, 180000, 0, -179999);
    s.forceMN = 2500;
    s.jointsMdeg = new int[] {0, 30000, 0, -90000, 0, 60000, -45000};
    assertArrayEquals(regs, s.toRegisters());
    assertArrayEquals(regs, Status.fromRegisters(regs).toRegisters());
    assertEquals(s.latched, Status.fromRegisters(regs).latched);
  }

  @Test
  public void hostControlVectorWrittenIsReadBack() throws ModbusException {
    RegisterStore store = new RegisterStore();
    store.write(RegisterMap.HostControl.ADDRESS, blocks.get("HostControl.example"));
    assertArrayEquals(blocks.get("HostControl.example"), store.hostControl());
    assertArrayEquals(new int[] {7, 3, 500}, store.hostControl());
  }

  @Test
  public void guardedApproachVectorDecodesAndStartsTheApproach() throws ModbusException {
    Command c = Command.fromRegisters(blocks.get("Command.guarded_approach"));
    assertEquals(42, c.seq);
    assertEquals(CommandCode.GUARDED_APPROACH, c.code);
    assertEquals(GuardSource.HOST_STOP_MASK | GuardSource.FORCE_MASK, c.guardSources);
    assertEquals(Axis.TOOL_Z, c.axis);
    assertEquals(2000, c.speed);
    assertEquals(2000, c.forceThresholdMN);
    assertEquals(20000, c.maxTravelUm);
    assertArrayEquals(new int[] {Result.ACCEPTED, 0}, c.checkParameters());
    FakeArm arm = run(blocks.get("Command.guarded_approach"));
    assertEquals("[guardedApproach axis 3 travel 20000 speed 2000 input 0 force 2000]", arm.calls.toString());
  }

  @Test
  public void moveLinVectorDecodesAndStartsTheMove() throws ModbusException {
    Command c = Command.fromRegisters(blocks.get("Command.move_lin"));
    assertEquals(41, c.seq);
    assertEquals(new Pose(500000, -123456, 200000, 180000, 0, -179999), c.pose);
    assertArrayEquals(new int[] {Result.ACCEPTED, 0}, c.checkParameters());
    FakeArm arm = run(blocks.get("Command.move_lin"));
    assertEquals("[moveLin (500000 um, -123456 um, 200000 um, 180000 mdeg, 0 mdeg, -179999 mdeg) 50000]",
        arm.calls.toString());
  }

  /** Writes a command block through the store and runs one cycle with a fresh heartbeat. */
  private static FakeArm run(int[] command) throws ModbusException {
    RegisterStore store = new RegisterStore();
    FakeArm arm = new FakeArm();
    BridgeCore core = new BridgeCore(store, arm, new FakeClock());
    store.write(RegisterMap.HostControl.HOST_HEARTBEAT, new int[] {1});
    store.write(RegisterMap.Command.ADDRESS, command);
    core.cycle();
    Status s = Status.fromRegisters(store.read(RegisterMap.StatusBlock.ADDRESS, RegisterMap.StatusBlock.LENGTH));
    assertEquals(command[0], s.ackSeq);
    assertEquals(Result.ACCEPTED, s.ackResult);
    assertTrue(s.state == RobotState.MOVING);
    return arm;
  }
}
