// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import static org.junit.Assert.assertEquals;

import org.junit.Test;
import org.palp.bridge.RegisterMap.Axis;
import org.palp.bridge.RegisterMap.Command;
import org.palp.bridge.RegisterMap.CommandCode;
import org.palp.bridge.RegisterMap.GuardSource;
import org.palp.bridge.RegisterMap.Result;

/** Every parameter rule of robot-bridge.md section 6, with the register each rejection names. */
public class CommandCheckTest {
  private static final Pose TARGET = new Pose(500000, -123456, 200000, 180000, 0, -179999);

  private static Blocks lin() {
    return Blocks.command(1, CommandCode.MOVE_LIN).set32(Command.SPEED, 50000).pose(TARGET);
  }

  private static Blocks approach() {
    return Blocks.command(1, CommandCode.GUARDED_APPROACH).set(Command.GUARD_SOURCES, GuardSource.FORCE_MASK)
        .set(Command.AXIS, Axis.TOOL_Z).set32(Command.SPEED, 2000).set32(Command.FORCE_THRESHOLD_MN, 2000)
        .set32(Command.MAX_TRAVEL_UM, 20000);
  }

  private static String verdict(Blocks b) {
    int[] v = b.decoded().checkParameters();
    String name = Result.name(v[0]);
    return v[0] == Result.REJECTED_BAD_PARAMETER ? name + " " + v[1] + " (" + Command.registerName(v[1]) + ")" : name;
  }

  private static final String ACCEPTED = "accepted";

  private static String bad(int address) {
    return "rejected_bad_parameter " + address + " (" + Command.registerName(address) + ")";
  }

  @Test
  public void validCommandsAtTheirLimitsAreAccepted() {
    assertEquals(ACCEPTED, verdict(lin()));
    assertEquals(ACCEPTED, verdict(lin().set32(Command.SPEED, 1000000).set32(Command.A_MDEG, -180000)));
    assertEquals(ACCEPTED, verdict(Blocks.command(1, CommandCode.MOVE_LIN_REL).set32(Command.SPEED, 1)));
    assertEquals(ACCEPTED, verdict(Blocks.command(1, CommandCode.MOVE_PTP).set32(Command.SPEED, 1000).pose(TARGET)));
    assertEquals(ACCEPTED, verdict(approach()));
    assertEquals(ACCEPTED, verdict(approach().set32(Command.MAX_TRAVEL_UM, -500000).set32(Command.SPEED, 100000)));
    assertEquals(ACCEPTED, verdict(approach().set(Command.GUARD_SOURCES, GuardSource.KNOWN_MASK)
        .set(Command.DIGITAL_INPUT, 16).set(Command.AXIS, Axis.BASE_Z)));
    assertEquals(ACCEPTED, verdict(Blocks.command(1, CommandCode.HOLD)));
    assertEquals(ACCEPTED, verdict(Blocks.command(1, CommandCode.SET_TOOL).set(Command.TOOL, 15).pose(TARGET)));
    assertEquals(ACCEPTED, verdict(Blocks.command(1, CommandCode.RESET_FAULT)));
  }

  @Test
  public void codeNoneOrUnknownIsRejectedAsUnknownCommand() {
    assertEquals("rejected_unknown_command", verdict(Blocks.command(1, CommandCode.NONE)));
    assertEquals("rejected_unknown_command", verdict(Blocks.command(1, 8)));
    assertEquals("rejected_unknown_command", verdict(Blocks.command(1, 0xFFFF)));
  }

  @Test
  public void guardSourcesMustBeKnownBitsOnApproachAndZeroElsewhere() {
    assertEquals(bad(Command.GUARD_SOURCES), verdict(approach().set(Command.GUARD_SOURCES, 0)));
    assertEquals(bad(Command.GUARD_SOURCES), verdict(approach().set(Command.GUARD_SOURCES, 0x0008 | GuardSource.FORCE_MASK)));
    assertEquals(bad(Command.GUARD_SOURCES), verdict(lin().set(Command.GUARD_SOURCES, GuardSource.HOST_STOP_MASK)));
  }

  @Test
  public void axisMustBeAKnownAxisOnApproachAndNoneElsewhere() {
    assertEquals(bad(Command.AXIS), verdict(approach().set(Command.AXIS, Axis.NONE)));
    assertEquals(bad(Command.AXIS), verdict(approach().set(Command.AXIS, 7)));
    assertEquals(bad(Command.AXIS), verdict(lin().set(Command.AXIS, Axis.TOOL_Z)));
    assertEquals(bad(Command.AXIS), verdict(Blocks.command(1, CommandCode.HOLD).set(Command.AXIS, 9)));
  }

  @Test
  public void digitalInputMustBe1To16WithTheInputGuardAndZeroElsewhere() {
    Blocks di = approach().set(Command.GUARD_SOURCES, GuardSource.DIGITAL_INPUT_MASK).set32(Command.FORCE_THRESHOLD_MN, 0);
    assertEquals(ACCEPTED, verdict(di.set(Command.DIGITAL_INPUT, 1)));
    assertEquals(bad(Command.DIGITAL_INPUT), verdict(di.set(Command.DIGITAL_INPUT, 0)));
    assertEquals(bad(Command.DIGITAL_INPUT), verdict(di.set(Command.DIGITAL_INPUT, 17)));
    assertEquals(bad(Command.DIGITAL_INPUT), verdict(approach().set(Command.DIGITAL_INPUT, 1)));
    assertEquals(bad(Command.DIGITAL_INPUT), verdict(lin().set(Command.DIGITAL_INPUT, 1)));
  }

  @Test
  public void toolMustBe1To15OnSetToolAndZeroElsewhere() {
    assertEquals(bad(Command.TOOL), verdict(Blocks.command(1, CommandCode.SET_TOOL).set(Command.TOOL, 0)));
    assertEquals(bad(Command.TOOL), verdict(Blocks.command(1, CommandCode.SET_TOOL).set(Command.TOOL, 16)));
    assertEquals(bad(Command.TOOL), verdict(lin().set(Command.TOOL, 1)));
  }

  @Test
  public void speedMustLieInTheCommandsRangeAndBeZeroWhereUnused() {
    assertEquals(bad(Command.SPEED), verdict(lin().set32(Command.SPEED, 0)));
    assertEquals(bad(Command.SPEED), verdict(lin().set32(Command.SPEED, 1000001)));
    assertEquals(bad(Command.SPEED), verdict(lin().set32(Command.SPEED, -5)));
    assertEquals(bad(Command.SPEED), verdict(approach().set32(Command.SPEED, 100001)));
    assertEquals(bad(Command.SPEED), verdict(Blocks.command(1, CommandCode.MOVE_PTP).set32(Command.SPEED, 1001)));
    assertEquals(bad(Command.SPEED), verdict(Blocks.command(1, CommandCode.HOLD).set32(Command.SPEED, 1)));
  }

  @Test
  public void forceThresholdMustBePositiveWithTheForceGuardAndZeroElsewhere() {
    assertEquals(bad(Command.FORCE_THRESHOLD_MN), verdict(approach().set32(Command.FORCE_THRESHOLD_MN, 0)));
    assertEquals(bad(Command.FORCE_THRESHOLD_MN), verdict(approach().set32(Command.FORCE_THRESHOLD_MN, 1000001)));
    assertEquals(bad(Command.FORCE_THRESHOLD_MN), verdict(approach().set(Command.GUARD_SOURCES, GuardSource.HOST_STOP_MASK)));
    assertEquals(bad(Command.FORCE_THRESHOLD_MN), verdict(lin().set32(Command.FORCE_THRESHOLD_MN, 1)));
  }

  @Test
  public void maxTravelMustBeNonZeroWithinHalfAMetreOnApproachAndZeroElsewhere() {
    assertEquals(bad(Command.MAX_TRAVEL_UM), verdict(approach().set32(Command.MAX_TRAVEL_UM, 0)));
    assertEquals(bad(Command.MAX_TRAVEL_UM), verdict(approach().set32(Command.MAX_TRAVEL_UM, 500001)));
    assertEquals(bad(Command.MAX_TRAVEL_UM), verdict(approach().set32(Command.MAX_TRAVEL_UM, -500001)));
    assertEquals(bad(Command.MAX_TRAVEL_UM), verdict(lin().set32(Command.MAX_TRAVEL_UM, 1)));
  }

  @Test
  public void poseRegistersMustBeZeroWhereUnusedAndAnglesWithin180Degrees() {
    assertEquals(bad(Command.X_UM), verdict(Blocks.command(1, CommandCode.HOLD).set32(Command.X_UM, 1)));
    assertEquals(bad(Command.Y_UM), verdict(approach().set32(Command.Y_UM, -1)));
    assertEquals(bad(Command.Z_UM), verdict(Blocks.command(1, CommandCode.RESET_FAULT).set32(Command.Z_UM, 1)));
    assertEquals(bad(Command.A_MDEG), verdict(Blocks.command(1, CommandCode.HOLD).set32(Command.A_MDEG, 1)));
    assertEquals(bad(Command.A_MDEG), verdict(lin().set32(Command.A_MDEG, 180001)));
    assertEquals(bad(Command.B_MDEG), verdict(lin().set32(Command.B_MDEG, -180001)));
    assertEquals(bad(Command.C_MDEG), verdict(Blocks.command(1, CommandCode.SET_TOOL).set(Command.TOOL, 1)
        .set32(Command.C_MDEG, Integer.MIN_VALUE)));
  }

  @Test
  public void rejectionsAreTheResultCodesFrom32() {
    assertEquals(32, Result.REJECTED_UNKNOWN_COMMAND);
    assertEquals(33, Result.REJECTED_BAD_PARAMETER);
    assertEquals(38, Result.REJECTED_HEARTBEAT_STALE);
  }
}
