// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import org.palp.bridge.RegisterMap.StatusBlock;

/** The status block's values (robot-bridge.md section 5.2) and their registers. */
public final class Status {
  public int heartbeat;
  public int state;
  public int statusBits;
  public int ackSeq;
  public int ackResult;
  public int rejectDetail;
  public int doneSeq;
  public int result;
  public int guardFired;
  public int stopSeen;
  public int tool;
  /** Unsigned 32-bit milliseconds of the bridge clock. */
  public long robotTimeMs;
  public Pose pose = Pose.ZERO;
  public Pose latched = Pose.ZERO;
  public int forceMN;
  public int[] jointsMdeg = new int[7];

  /** The block's StatusBlock.LENGTH registers. */
  public int[] toRegisters() {
    int[] r = new int[StatusBlock.LENGTH];
    r[at(StatusBlock.HEARTBEAT)] = heartbeat & 0xFFFF;
    r[at(StatusBlock.STATE)] = state;
    r[at(StatusBlock.STATUS_BITS)] = statusBits;
    r[at(StatusBlock.ACK_SEQ)] = ackSeq;
    r[at(StatusBlock.ACK_RESULT)] = ackResult;
    r[at(StatusBlock.REJECT_DETAIL)] = rejectDetail;
    r[at(StatusBlock.DONE_SEQ)] = doneSeq;
    r[at(StatusBlock.RESULT)] = result;
    r[at(StatusBlock.GUARD_FIRED)] = guardFired;
    r[at(StatusBlock.STOP_SEEN)] = stopSeen;
    r[at(StatusBlock.TOOL)] = tool;
    Words.put(r, at(StatusBlock.ROBOT_TIME_MS), (int) robotTimeMs);
    putPose(r, StatusBlock.X_UM, pose);
    putPose(r, StatusBlock.LATCHED_X_UM, latched);
    Words.put(r, at(StatusBlock.FORCE_MN), forceMN);
    int[] joints = {StatusBlock.A1_MDEG, StatusBlock.A2_MDEG, StatusBlock.A3_MDEG, StatusBlock.A4_MDEG,
        StatusBlock.A5_MDEG, StatusBlock.A6_MDEG, StatusBlock.A7_MDEG};
    for (int i = 0; i < joints.length; ++i) Words.put(r, at(joints[i]), jointsMdeg[i]);
    return r;
  }

  /** The values of a status block's registers (for tests and tools). */
  public static Status fromRegisters(int[] r) {
    if (r.length != StatusBlock.LENGTH)
      throw new IllegalArgumentException("status block of " + r.length + " registers, expected " + StatusBlock.LENGTH);
    Status s = new Status();
    s.heartbeat = r[at(StatusBlock.HEARTBEAT)];
    s.state = r[at(StatusBlock.STATE)];
    s.statusBits = r[at(StatusBlock.STATUS_BITS)];
    s.ackSeq = r[at(StatusBlock.ACK_SEQ)];
    s.ackResult = r[at(StatusBlock.ACK_RESULT)];
    s.rejectDetail = r[at(StatusBlock.REJECT_DETAIL)];
    s.doneSeq = r[at(StatusBlock.DONE_SEQ)];
    s.result = r[at(StatusBlock.RESULT)];
    s.guardFired = r[at(StatusBlock.GUARD_FIRED)];
    s.stopSeen = r[at(StatusBlock.STOP_SEEN)];
    s.tool = r[at(StatusBlock.TOOL)];
    s.robotTimeMs = Words.toUnsigned(r[at(StatusBlock.ROBOT_TIME_MS)], r[at(StatusBlock.ROBOT_TIME_MS) + 1]);
    s.pose = getPose(r, StatusBlock.X_UM);
    s.latched = getPose(r, StatusBlock.LATCHED_X_UM);
    s.forceMN = Words.get(r, at(StatusBlock.FORCE_MN));
    for (int i = 0; i < 7; ++i) s.jointsMdeg[i] = Words.get(r, at(StatusBlock.A1_MDEG) + 2 * i);
    return s;
  }

  private static int at(int address) {
    return address - StatusBlock.ADDRESS;
  }

  // x, y, z, a, b, c are consecutive i32 registers in the map, from xAddress.
  private static void putPose(int[] r, int xAddress, Pose p) {
    int i = at(xAddress);
    Words.put(r, i, p.xUm);
    Words.put(r, i + 2, p.yUm);
    Words.put(r, i + 4, p.zUm);
    Words.put(r, i + 6, p.aMdeg);
    Words.put(r, i + 8, p.bMdeg);
    Words.put(r, i + 10, p.cMdeg);
  }

  private static Pose getPose(int[] r, int xAddress) {
    int i = at(xAddress);
    return new Pose(Words.get(r, i), Words.get(r, i + 2), Words.get(r, i + 4), Words.get(r, i + 6),
        Words.get(r, i + 8), Words.get(r, i + 10));
  }
}
