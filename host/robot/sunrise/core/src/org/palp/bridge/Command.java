// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import org.palp.bridge.RegisterMap.Axis;
import org.palp.bridge.RegisterMap.CommandCode;
import org.palp.bridge.RegisterMap.GuardSource;
import org.palp.bridge.RegisterMap.Result;

/**
 * A command block (robot-bridge.md section 5.4) and its parameter checks (section 6, the same
 * rules as check.hpp). State checks are the core's.
 */
public final class Command {
  public final int seq;
  public final int code;
  public final int guardSources;
  public final int axis;
  public final int digitalInput;
  public final int tool;
  public final int speed;
  public final int forceThresholdMN;
  public final int maxTravelUm;
  /** x..c: target, offset or TCP frame, by code. */
  public final Pose pose;

  private Command(int[] r) {
    seq = r[at(RegisterMap.Command.SEQ)];
    code = r[at(RegisterMap.Command.CODE)];
    guardSources = r[at(RegisterMap.Command.GUARD_SOURCES)];
    axis = r[at(RegisterMap.Command.AXIS)];
    digitalInput = r[at(RegisterMap.Command.DIGITAL_INPUT)];
    tool = r[at(RegisterMap.Command.TOOL)];
    speed = Words.get(r, at(RegisterMap.Command.SPEED));
    forceThresholdMN = Words.get(r, at(RegisterMap.Command.FORCE_THRESHOLD_MN));
    maxTravelUm = Words.get(r, at(RegisterMap.Command.MAX_TRAVEL_UM));
    pose = new Pose(Words.get(r, at(RegisterMap.Command.X_UM)), Words.get(r, at(RegisterMap.Command.Y_UM)),
        Words.get(r, at(RegisterMap.Command.Z_UM)), Words.get(r, at(RegisterMap.Command.A_MDEG)),
        Words.get(r, at(RegisterMap.Command.B_MDEG)), Words.get(r, at(RegisterMap.Command.C_MDEG)));
  }

  /** The command of a whole command block's registers. */
  public static Command fromRegisters(int[] regs) {
    if (regs.length != RegisterMap.Command.LENGTH)
      throw new IllegalArgumentException("command block of " + regs.length + " registers, expected "
          + RegisterMap.Command.LENGTH);
    return new Command(regs);
  }

  public boolean isMotion() {
    return code == CommandCode.MOVE_LIN || code == CommandCode.MOVE_LIN_REL || code == CommandCode.MOVE_PTP
        || code == CommandCode.GUARDED_APPROACH;
  }

  /**
   * The parameter verdict: {Result.ACCEPTED, 0}, {REJECTED_UNKNOWN_COMMAND, 0} or
   * {REJECTED_BAD_PARAMETER, address of the offending register}.
   */
  public int[] checkParameters() {
    final int k = code;
    if (k == CommandCode.NONE || CommandCode.name(k) == null) return verdict(Result.REJECTED_UNKNOWN_COMMAND, 0);
    if (Axis.name(axis) == null) return bad(RegisterMap.Command.AXIS);  // an unknown enum value
    final boolean approach = k == CommandCode.GUARDED_APPROACH;
    final boolean pose = k == CommandCode.MOVE_LIN || k == CommandCode.MOVE_LIN_REL || k == CommandCode.MOVE_PTP
        || k == CommandCode.SET_TOOL;
    final boolean lin = k == CommandCode.MOVE_LIN || k == CommandCode.MOVE_LIN_REL;
    final boolean di = (guardSources & GuardSource.DIGITAL_INPUT_MASK) != 0;
    final boolean force = (guardSources & GuardSource.FORCE_MASK) != 0;

    if (approach ? guardSources == 0 || (guardSources & ~GuardSource.KNOWN_MASK) != 0 : guardSources != 0)
      return bad(RegisterMap.Command.GUARD_SOURCES);
    if (approach ? axis == Axis.NONE : axis != Axis.NONE) return bad(RegisterMap.Command.AXIS);
    if (approach && di ? !in(digitalInput, 1, RegisterMap.MAX_DIGITAL_INPUT) : digitalInput != 0)
      return bad(RegisterMap.Command.DIGITAL_INPUT);
    if (k == CommandCode.SET_TOOL ? !in(tool, 1, RegisterMap.MAX_TOOL) : tool != 0)
      return bad(RegisterMap.Command.TOOL);

    int maxSpeed = 0;
    if (lin) maxSpeed = RegisterMap.MAX_LIN_SPEED_UM_PER_S;
    if (approach) maxSpeed = RegisterMap.MAX_APPROACH_SPEED_UM_PER_S;
    if (k == CommandCode.MOVE_PTP) maxSpeed = RegisterMap.MAX_PTP_SPEED_PERMILLE;
    if (maxSpeed != 0 ? !in(speed, 1, maxSpeed) : speed != 0) return bad(RegisterMap.Command.SPEED);
    if (approach && force ? !in(forceThresholdMN, 1, RegisterMap.MAX_FORCE_THRESHOLD_MN) : forceThresholdMN != 0)
      return bad(RegisterMap.Command.FORCE_THRESHOLD_MN);
    if (approach ? maxTravelUm == 0
            || !in(maxTravelUm, -RegisterMap.MAX_APPROACH_TRAVEL_UM, RegisterMap.MAX_APPROACH_TRAVEL_UM)
        : maxTravelUm != 0)
      return bad(RegisterMap.Command.MAX_TRAVEL_UM);

    if (!pose) {
      if (this.pose.xUm != 0) return bad(RegisterMap.Command.X_UM);
      if (this.pose.yUm != 0) return bad(RegisterMap.Command.Y_UM);
      if (this.pose.zUm != 0) return bad(RegisterMap.Command.Z_UM);
    }
    final int limit = pose ? RegisterMap.MAX_ANGLE_MDEG : 0;
    if (!in(this.pose.aMdeg, -limit, limit)) return bad(RegisterMap.Command.A_MDEG);
    if (!in(this.pose.bMdeg, -limit, limit)) return bad(RegisterMap.Command.B_MDEG);
    if (!in(this.pose.cMdeg, -limit, limit)) return bad(RegisterMap.Command.C_MDEG);
    return verdict(Result.ACCEPTED, 0);
  }

  private static int at(int address) {
    return address - RegisterMap.Command.ADDRESS;
  }

  private static boolean in(int v, int lo, int hi) {
    return v >= lo && v <= hi;
  }

  private static int[] bad(int address) {
    return verdict(Result.REJECTED_BAD_PARAMETER, address);
  }

  private static int[] verdict(int result, int detail) {
    return new int[] {result, detail};
  }
}
