// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

/**
 * The robot as the bridge core sees it. The Sunrise adapter implements it with the Robotics API
 * (moveAsync, breakWhen, IMotionContainer.cancel); the tests with a fake arm. Units are the
 * registers': micrometres, millidegrees, micrometres per second, millinewtons.
 *
 * Motions start asynchronously and return at once; the core polls {@link #motionStatus()} and
 * {@link #isMoving()} every cycle. Only the core's cycle thread calls these methods.
 */
public interface Arm {
  /** motionStatus(): the last motion started is still running. */
  int MOTION_RUNNING = 0;
  /** motionStatus(): it reached its target (a guarded approach: its maximum travel). */
  int MOTION_REACHED = 1;
  /** motionStatus(): one of its break conditions fired; see firedGuards() and guardPose(). */
  int MOTION_GUARD = 2;
  /** motionStatus(): it ended because stop() was called. */
  int MOTION_STOPPED = 3;
  /** motionStatus(): a robot error ended it (the arm is faulted). */
  int MOTION_FAULT = 4;
  /** motionStatus(): the safety controller ended it. */
  int MOTION_SAFETY = 5;

  /** Linear motion of the TCP to a pose in the base frame. */
  void moveLin(Pose target, int speedUmPerS);

  /** Linear motion by an offset in the active tool frame. */
  void moveLinRel(Pose offset, int speedUmPerS);

  /** Joint-interpolated motion to a pose in the base frame at a fraction of the joints' speed. */
  void movePtp(Pose target, int speedPermille);

  /**
   * Linear motion along axis (RegisterMap.Axis) by maxTravelUm (its sign is the direction), with
   * break conditions: digitalInput 1..16 going high (0: none) and the force along the axis
   * reaching forceThresholdMN (0: none). The arm latches the pose where a condition fires.
   */
  void guardedApproach(int axis, int maxTravelUm, int speedUmPerS, int digitalInput, int forceThresholdMN);

  /** Brakes the motion in progress on its path (stop category 2) and holds. No-op when still. */
  void stop();

  /** True while the arm moves, including while it brakes. */
  boolean isMoving();

  /** How the last motion started stands: one of the MOTION_* values. */
  int motionStatus();

  /** GuardSource bits of the break conditions that fired (motionStatus() MOTION_GUARD). */
  int firedGuards();

  /** The TCP pose where the break condition fired (motionStatus() MOTION_GUARD). */
  Pose guardPose();

  /** The actual TCP pose of the active tool in the base frame. */
  Pose pose();

  /** Joints A1..A7 in millidegrees (7 values). */
  int[] jointsMdeg();

  /** False when no force estimate is available. */
  boolean forceValid();

  /**
   * The external force along axis (RegisterMap.Axis), positive when it pushes against motion in
   * the direction of the sign of direction (+1 or -1).
   */
  int forceMN(int axis, int direction);

  /** The level of digital input 1..16. */
  boolean digitalInput(int input);

  /** True when the target of a motion command lies inside the workspace and joint limits. */
  boolean reachable(int commandCode, Pose target);

  /** Makes tool 1..15 active with its TCP frame on the flange. */
  void setTool(int tool, Pose tcpOnFlange);

  boolean drivesEnabled();

  /** True in AUT mode (false in T1, T2, CRR). */
  boolean automaticMode();

  /** True when the robot can be commanded (drives on, application running, mode allowed). */
  boolean ready();

  /** True while a robot error keeps the arm stopped. */
  boolean faulted();

  /** True while the safety controller keeps the arm stopped (E-stop, protective stop). */
  boolean safetyStopped();

  /** Acknowledges a robot error; true when the arm is no longer faulted. */
  boolean resetFault();
}
