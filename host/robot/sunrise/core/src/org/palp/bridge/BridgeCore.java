// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import org.palp.bridge.RegisterMap.Axis;
import org.palp.bridge.RegisterMap.CommandCode;
import org.palp.bridge.RegisterMap.GuardSource;
import org.palp.bridge.RegisterMap.HostControl;
import org.palp.bridge.RegisterMap.Result;
import org.palp.bridge.RegisterMap.RobotState;
import org.palp.bridge.RegisterMap.StatusBit;

/**
 * The bridge's cycle (robot-bridge.md section 8.3): host heartbeat and watchdog on the bridge's
 * own clock, the stop edge, command commit by seq with the section 6 checks, ack and done, the
 * guarded approach's guards, and the status snapshot. Call {@link #cycle()} at most 20 ms apart,
 * always from the same thread; {@link #connectionClosed()} may be called from any thread.
 */
public final class BridgeCore implements ModbusTcpServer.Listener {
  private final RegisterStore store;
  private final Arm arm;
  private final Clock clock;

  private int hostHeartbeat;
  private long heartbeatChangedAtMs;
  private int stopSeen;
  private boolean stopPending;
  private int pendingStop;
  private volatile boolean connectionLost;

  private int heartbeat;
  private int ackSeq;
  private int ackResult = Result.NONE;
  private int rejectDetail;
  private int doneSeq;
  private int result = Result.NONE;
  private int guardFired;
  private int tool;
  private boolean toolSet;
  private boolean watchdogTripped;
  private boolean latchedValid;
  private Pose latched = Pose.ZERO;
  private int approachAxis = Axis.TOOL_Z;
  private int approachDirection = 1;

  private String lastArmError;
  private boolean armFailed;  // faulted until a reset_fault, after the arm threw

  /** The command being carried out (a motion or a hold), or null. */
  private Active active;

  private static final class Active {
    final Command command;
    int ending = -1;  // the Result it will finish with once the arm is stationary; -1: running
    int endingGuards;

    Active(Command command) {
      this.command = command;
    }
  }

  public BridgeCore(RegisterStore store, Arm arm, Clock clock) {
    this.store = store;
    this.arm = arm;
    this.clock = clock;
    heartbeatChangedAtMs = clock.millis();
    publish(heartbeatChangedAtMs);
  }

  /** One bridge cycle, steps 1..6 of section 8.3. */
  public void cycle() {
    final long now = clock.millis();
    // 1. the host control block
    final int[] control = store.hostControl();
    final int hb = control[HostControl.HOST_HEARTBEAT - HostControl.ADDRESS];
    if (hb != hostHeartbeat) {
      hostHeartbeat = hb;
      heartbeatChangedAtMs = now;
    }
    final int watchdogMs = control[HostControl.WATCHDOG_MS - HostControl.ADDRESS];
    final boolean stale = now - heartbeatChangedAtMs > watchdogMs;  // as palp-sim's emulator
    // a motion that ended before the bridge sees a stop keeps its own result (rule 8)
    pollArm();

    // 2. the stop edge
    final int stopRequest = control[HostControl.STOP_REQUEST - HostControl.ADDRESS];
    if (stopRequest != stopSeen && !(stopPending && stopRequest == pendingStop)) takeStop(stopRequest);

    // 3. the watchdog; a closed connection stops the arm as a stale heartbeat does
    final boolean lost = connectionLost;
    connectionLost = false;
    if ((stale || lost) && running()) {
      latch(arm.pose());
      arm.stop();
      active.ending = Result.WATCHDOG;
      watchdogTripped = true;
    }

    // 4. a new seq commits the command block
    final int[] command = store.command();
    final int seq = command[RegisterMap.Command.SEQ - RegisterMap.Command.ADDRESS];
    if (seq != 0 && seq != ackSeq) take(Command.fromRegisters(command), stale);

    // 5. the motion in progress
    advance();
    if (stopPending && !arm.isMoving()) {
      stopSeen = pendingStop;
      stopPending = false;
    }

    // 6. the snapshot
    heartbeat = (heartbeat + 1) & 0xFFFF;
    publish(now, stale);
  }

  /** The connection to the host closed: a motion in progress stops in the next cycle. */
  @Override
  public void connectionClosed() {
    connectionLost = true;
  }

  @Override
  public void connectionOpened() {}

  private boolean running() {
    return active != null && active.ending < 0 && active.command.isMotion();
  }

  private void takeStop(int stopRequest) {
    latch(arm.pose());
    if (running()) {
      arm.stop();
      final Command c = active.command;
      if (c.code == CommandCode.GUARDED_APPROACH && (c.guardSources & GuardSource.HOST_STOP_MASK) != 0) {
        active.ending = Result.GUARD_FIRED;
        active.endingGuards = GuardSource.HOST_STOP_MASK;
      } else {
        active.ending = Result.STOPPED;
      }
    } else if (arm.isMoving()) {
      arm.stop();
    }
    if (arm.isMoving()) {
      stopPending = true;
      pendingStop = stopRequest;
    } else {
      stopPending = false;
      stopSeen = stopRequest;
    }
  }

  private void take(Command c, boolean stale) {
    int[] verdict = c.checkParameters();
    if (verdict[0] == Result.ACCEPTED) verdict = checkState(c, stale);
    ackSeq = c.seq;
    ackResult = verdict[0];
    rejectDetail = verdict[1];
    if (verdict[0] == Result.ACCEPTED) {
      watchdogTripped = false;
      start(c);
    }
  }

  private int[] checkState(Command c, boolean stale) {
    final int state = state();
    final boolean motion = c.isMotion();
    if (state == RobotState.FAULTED && c.code != CommandCode.RESET_FAULT) return verdict(Result.REJECTED_FAULTED);
    if ((state == RobotState.NOT_READY || state == RobotState.SAFETY_STOP) && (motion || c.code == CommandCode.HOLD))
      return verdict(Result.REJECTED_NOT_READY);
    if (active != null && (motion || c.code == CommandCode.SET_TOOL)) return verdict(Result.REJECTED_BUSY);
    if (motion && stale) return verdict(Result.REJECTED_HEARTBEAT_STALE);
    if (motion && c.code != CommandCode.GUARDED_APPROACH && !arm.reachable(c.code, c.pose))
      return verdict(Result.REJECTED_UNREACHABLE);
    return verdict(Result.ACCEPTED);
  }

  private static int[] verdict(int r) {
    return new int[] {r, 0};
  }

  private void start(Command c) {
    try {
      startOnArm(c);
    } catch (RuntimeException e) {
      // the robot refused or failed to start it (a Sunrise exception): a robot error, not a crash
      // of the bridge; the motion ends with robot_fault once the arm is stationary
      lastArmError = String.valueOf(e.getMessage());
      active = new Active(c);
      active.ending = Result.ROBOT_FAULT;
      armFailed = true;
    }
  }

  /** The message of the last exception the arm threw when a command started, or null. */
  public String lastArmError() {
    return lastArmError;
  }

  private void startOnArm(Command c) {
    switch (c.code) {
      case CommandCode.MOVE_LIN:
        arm.moveLin(c.pose, c.speed);
        active = new Active(c);
        break;
      case CommandCode.MOVE_LIN_REL:
        arm.moveLinRel(c.pose, c.speed);
        active = new Active(c);
        break;
      case CommandCode.MOVE_PTP:
        arm.movePtp(c.pose, c.speed);
        active = new Active(c);
        break;
      case CommandCode.GUARDED_APPROACH:
        approachAxis = c.axis;
        approachDirection = c.maxTravelUm > 0 ? 1 : -1;
        arm.guardedApproach(c.axis, c.maxTravelUm, c.speed,
            (c.guardSources & GuardSource.DIGITAL_INPUT_MASK) != 0 ? c.digitalInput : 0,
            (c.guardSources & GuardSource.FORCE_MASK) != 0 ? c.forceThresholdMN : 0);
        active = new Active(c);
        break;
      case CommandCode.HOLD:
        if (active != null) finish(active.command.seq, active.ending >= 0 ? active.ending : Result.SUPERSEDED,
            active.endingGuards);
        arm.stop();
        active = new Active(c);
        active.ending = Result.DONE;
        break;
      case CommandCode.SET_TOOL:
        arm.setTool(c.tool, c.pose);
        tool = c.tool;
        toolSet = true;
        finish(c.seq, Result.DONE, 0);
        break;
      case CommandCode.RESET_FAULT:
        armFailed = false;
        finish(c.seq, !arm.faulted() || arm.resetFault() ? Result.DONE : Result.ROBOT_FAULT, 0);
        break;
      default:
        throw new IllegalStateException("unchecked command code " + c.code);
    }
  }

  /** Takes how a running motion ended from the arm, if it did (its natural result). */
  private void pollArm() {
    if (!running()) return;
    switch (arm.motionStatus()) {
      case Arm.MOTION_RUNNING:
        return;
      case Arm.MOTION_REACHED:
        active.ending = active.command.code == CommandCode.GUARDED_APPROACH ? Result.MAX_TRAVEL : Result.DONE;
        return;
      case Arm.MOTION_GUARD:
        latch(arm.guardPose());
        active.ending = Result.GUARD_FIRED;
        active.endingGuards = arm.firedGuards() & active.command.guardSources;
        return;
      case Arm.MOTION_FAULT:
        active.ending = Result.ROBOT_FAULT;
        return;
      case Arm.MOTION_SAFETY:
        active.ending = Result.SAFETY_STOPPED;
        return;
      default:
        active.ending = Result.STOPPED;
    }
  }

  private void advance() {
    if (active == null) return;
    if (running() && active.command.code == CommandCode.GUARDED_APPROACH) checkGuards(active.command);
    pollArm();
    if (active.ending >= 0 && !arm.isMoving()) {
      finish(active.command.seq, active.ending, active.endingGuards);
      active = null;
    }
  }

  /** The cycle's own look at the guards, behind the arm's break conditions. */
  private void checkGuards(Command c) {
    int fired = 0;
    if ((c.guardSources & GuardSource.DIGITAL_INPUT_MASK) != 0 && arm.digitalInput(c.digitalInput))
      fired |= GuardSource.DIGITAL_INPUT_MASK;
    if ((c.guardSources & GuardSource.FORCE_MASK) != 0 && arm.forceValid()
        && arm.forceMN(c.axis, approachDirection) >= c.forceThresholdMN)
      fired |= GuardSource.FORCE_MASK;
    if (fired == 0) return;
    latch(arm.pose());
    arm.stop();
    active.ending = Result.GUARD_FIRED;
    active.endingGuards = fired;
  }

  private void finish(int seq, int how, int guards) {
    result = how;
    guardFired = how == Result.GUARD_FIRED ? guards : 0;
    doneSeq = seq;
  }

  private void latch(Pose p) {
    latched = p;
    latchedValid = true;
  }

  private int state() {
    if (arm.safetyStopped()) return RobotState.SAFETY_STOP;
    if (arm.faulted() || (armFailed && active == null)) return RobotState.FAULTED;
    if (!arm.ready()) return RobotState.NOT_READY;
    return active != null ? RobotState.MOVING : RobotState.IDLE;
  }

  private void publish(long now) {
    publish(now, true);
  }

  private void publish(long now, boolean stale) {
    final Status s = new Status();
    s.heartbeat = heartbeat;
    s.state = state();
    int bits = 0;
    if (arm.drivesEnabled()) bits |= StatusBit.DRIVES_ENABLED_MASK;
    if (arm.automaticMode()) bits |= StatusBit.AUTOMATIC_MODE_MASK;
    if (!stale) bits |= StatusBit.HOST_HEARTBEAT_OK_MASK;
    if (watchdogTripped) bits |= StatusBit.WATCHDOG_TRIPPED_MASK;
    if (latchedValid) bits |= StatusBit.LATCHED_POSE_VALID_MASK;
    final boolean forceValid = arm.forceValid();
    if (forceValid) bits |= StatusBit.FORCE_VALID_MASK;
    if (toolSet) bits |= StatusBit.TOOL_SET_MASK;
    s.statusBits = bits;
    s.ackSeq = ackSeq;
    s.ackResult = ackResult;
    s.rejectDetail = rejectDetail;
    s.doneSeq = doneSeq;
    s.result = result;
    s.guardFired = guardFired;
    s.stopSeen = stopSeen;
    s.tool = tool;
    s.robotTimeMs = now & 0xFFFFFFFFL;
    s.pose = arm.pose();
    s.latched = latched;
    s.forceMN = forceValid ? arm.forceMN(approachAxis, approachDirection) : 0;
    s.jointsMdeg = arm.jointsMdeg();
    store.publishStatus(s.toRegisters());
  }
}
