// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import java.util.ArrayList;
import java.util.List;

/** A test double of the robot: records calls, moves only when the test says so. */
final class FakeArm implements Arm {
  final List<String> calls = new ArrayList<String>();
  Pose pose = new Pose(100000, 0, 300000, 180000, 0, 180000);
  int[] joints = {0, 30000, 0, -90000, 0, 60000, -45000};
  boolean moving;
  int status = MOTION_RUNNING;
  int fired;
  Pose guardPose = Pose.ZERO;
  boolean forceValid = true;
  int forceMN;
  int forceAxis;
  int forceDirection;
  boolean[] inputs = new boolean[17];
  boolean reachable = true;
  boolean drives = true;
  boolean automatic = true;
  boolean ready = true;
  boolean faulted;
  boolean safety;
  boolean faultPersists;
  int stops;

  RuntimeException failNextStart;

  private void start(String call) {
    if (failNextStart != null) {
      RuntimeException e = failNextStart;
      failNextStart = null;
      throw e;
    }
    calls.add(call);
    moving = true;
    status = MOTION_RUNNING;
  }

  @Override
  public void moveLin(Pose target, int speedUmPerS) {
    start("moveLin " + target + " " + speedUmPerS);
  }

  @Override
  public void moveLinRel(Pose offset, int speedUmPerS) {
    start("moveLinRel " + offset + " " + speedUmPerS);
  }

  @Override
  public void movePtp(Pose target, int speedPermille) {
    start("movePtp " + target + " " + speedPermille);
  }

  @Override
  public void guardedApproach(int axis, int maxTravelUm, int speedUmPerS, int digitalInput, int forceThresholdMN) {
    start("guardedApproach axis " + axis + " travel " + maxTravelUm + " speed " + speedUmPerS + " input "
        + digitalInput + " force " + forceThresholdMN);
  }

  @Override
  public void stop() {
    ++stops;
    if (moving && status == MOTION_RUNNING) status = MOTION_STOPPED;
  }

  /** The arm comes to rest (after braking, or at its target with the given status). */
  void rest() {
    moving = false;
  }

  void end(int how) {
    status = how;
    moving = false;
  }

  @Override
  public boolean isMoving() {
    return moving;
  }

  @Override
  public int motionStatus() {
    return status;
  }

  @Override
  public int firedGuards() {
    return fired;
  }

  @Override
  public Pose guardPose() {
    return guardPose;
  }

  @Override
  public Pose pose() {
    return pose;
  }

  @Override
  public int[] jointsMdeg() {
    return joints.clone();
  }

  @Override
  public boolean forceValid() {
    return forceValid;
  }

  @Override
  public int forceMN(int axis, int direction) {
    forceAxis = axis;
    forceDirection = direction;
    return forceMN;
  }

  @Override
  public boolean digitalInput(int input) {
    return inputs[input];
  }

  @Override
  public boolean reachable(int commandCode, Pose target) {
    return reachable;
  }

  @Override
  public void setTool(int tool, Pose tcpOnFlange) {
    calls.add("setTool " + tool + " " + tcpOnFlange);
  }

  @Override
  public boolean drivesEnabled() {
    return drives;
  }

  @Override
  public boolean automaticMode() {
    return automatic;
  }

  @Override
  public boolean ready() {
    return ready;
  }

  @Override
  public boolean faulted() {
    return faulted;
  }

  @Override
  public boolean safetyStopped() {
    return safety;
  }

  @Override
  public boolean resetFault() {
    calls.add("resetFault");
    if (!faultPersists) faulted = false;
    return !faulted;
  }
}
