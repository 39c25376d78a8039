// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import static org.junit.Assert.assertEquals;
import static org.junit.Assert.assertFalse;
import static org.junit.Assert.assertTrue;

import org.junit.Before;
import org.junit.Test;
import org.palp.bridge.RegisterMap.Axis;
import org.palp.bridge.RegisterMap.Command;
import org.palp.bridge.RegisterMap.CommandCode;
import org.palp.bridge.RegisterMap.GuardSource;
import org.palp.bridge.RegisterMap.HostControl;
import org.palp.bridge.RegisterMap.Result;
import org.palp.bridge.RegisterMap.RobotState;
import org.palp.bridge.RegisterMap.StatusBit;
import org.palp.bridge.RegisterMap.StatusBlock;

/** The bridge cycle (robot-bridge.md section 8) against a fake arm on a hand-driven clock. */
public class BridgeCoreTest {
  private static final Pose TARGET = new Pose(500000, -123456, 200000, 180000, 0, -179999);

  private RegisterStore store;
  private FakeArm arm;
  private FakeClock clock;
  private BridgeCore core;
  private int heartbeat;
  private int stop;

  @Before
  public void setUp() {
    store = new RegisterStore();
    arm = new FakeArm();
    clock = new FakeClock();
    core = new BridgeCore(store, arm, clock);
    beat();
  }

  private void beat() {
    write(HostControl.HOST_HEARTBEAT, ++heartbeat);
  }

  private void stopRequest() {
    write(HostControl.STOP_REQUEST, ++stop);
  }

  private void write(int address, int value) {
    try {
      store.write(address, new int[] {value});
    } catch (ModbusException e) {
      throw new AssertionError(e.getMessage());
    }
  }

  private void send(Blocks b) {
    try {
      store.write(Command.ADDRESS, b.regs());
    } catch (ModbusException e) {
      throw new AssertionError(e.getMessage());
    }
  }

  private Status cycle() {
    core.cycle();
    try {
      return Status.fromRegisters(store.read(StatusBlock.ADDRESS, StatusBlock.LENGTH));
    } catch (ModbusException e) {
      throw new AssertionError(e.getMessage());
    }
  }

  private static Blocks lin(int seq) {
    return Blocks.command(seq, CommandCode.MOVE_LIN).set32(Command.SPEED, 50000).pose(TARGET);
  }

  private static Blocks approach(int seq, int guards) {
    Blocks b = Blocks.command(seq, CommandCode.GUARDED_APPROACH).set(Command.GUARD_SOURCES, guards)
        .set(Command.AXIS, Axis.TOOL_Z).set32(Command.SPEED, 2000).set32(Command.MAX_TRAVEL_UM, 20000);
    if ((guards & GuardSource.FORCE_MASK) != 0) b.set32(Command.FORCE_THRESHOLD_MN, 2000);
    if ((guards & GuardSource.DIGITAL_INPUT_MASK) != 0) b.set(Command.DIGITAL_INPUT, 3);
    return b;
  }

  private static String outcome(Status s) {
    return "ack " + s.ackSeq + " " + Result.name(s.ackResult) + " " + s.rejectDetail + ", done " + s.doneSeq + " "
        + Result.name(s.result) + " guards " + s.guardFired + ", " + RobotState.name(s.state);
  }

  @Test
  public void heartbeatCountsCyclesAndRobotTimeIsTheBridgeClock() {
    Status a = cycle();
    clock.now = 0x1_0000_0005L;  // the u32 register wraps
    Status b = cycle();
    assertEquals(1, a.heartbeat);
    assertEquals(2, b.heartbeat);
    assertEquals(1000, a.robotTimeMs);
    assertEquals(5, b.robotTimeMs);
    assertEquals(StatusBit.DRIVES_ENABLED_MASK | StatusBit.AUTOMATIC_MODE_MASK | StatusBit.HOST_HEARTBEAT_OK_MASK
        | StatusBit.FORCE_VALID_MASK, a.statusBits);
    assertEquals(arm.pose, a.pose);
    assertEquals(-45000, a.jointsMdeg[6]);
  }

  @Test
  public void moveIsAcknowledgedThenDoneAtTheTarget() {
    send(lin(1));
    assertEquals("ack 1 accepted 0, done 0 none guards 0, moving", outcome(cycle()));
    assertEquals(1, arm.calls.size());
    assertEquals("ack 1 accepted 0, done 0 none guards 0, moving", outcome(cycle()));
    arm.end(Arm.MOTION_REACHED);
    assertEquals("ack 1 accepted 0, done 1 done guards 0, idle", outcome(cycle()));
  }

  @Test
  public void retryWithTheTakenSeqIsIgnoredAndSeqZeroNeverCommits() {
    send(lin(5));
    cycle();
    arm.end(Arm.MOTION_REACHED);
    cycle();
    send(lin(5));  // the host's retry after a timeout: the same block, the same seq
    assertEquals("ack 5 accepted 0, done 5 done guards 0, idle", outcome(cycle()));
    assertEquals(1, arm.calls.size());
    send(lin(0));
    assertEquals("ack 5 accepted 0, done 5 done guards 0, idle", outcome(cycle()));
    assertEquals(1, arm.calls.size());
    send(lin(6));
    assertEquals("ack 6 accepted 0, done 5 done guards 0, moving", outcome(cycle()));
    assertEquals(2, arm.calls.size());
  }

  @Test
  public void badParameterIsRejectedWithItsAddressAndNeverMovesDoneSeq() {
    send(lin(1));
    cycle();
    arm.end(Arm.MOTION_REACHED);
    cycle();
    send(lin(2).set32(Command.SPEED, 0));
    assertEquals("ack 2 rejected_bad_parameter 306, done 1 done guards 0, idle", outcome(cycle()));
    send(Blocks.command(3, 99));
    assertEquals("ack 3 rejected_unknown_command 0, done 1 done guards 0, idle", outcome(cycle()));
    assertEquals(1, arm.calls.size());
  }

  @Test
  public void motionWhileMovingIsBusyAndSoIsSetTool() {
    send(lin(1));
    cycle();
    send(lin(2));
    assertEquals("ack 2 rejected_busy 0, done 0 none guards 0, moving", outcome(cycle()));
    send(Blocks.command(3, CommandCode.SET_TOOL).set(Command.TOOL, 1));
    assertEquals("ack 3 rejected_busy 0, done 0 none guards 0, moving", outcome(cycle()));
    assertEquals(1, arm.calls.size());
  }

  @Test
  public void motionWhileNotReadyOrSafetyStoppedIsNotReady() {
    arm.ready = false;
    send(lin(1));
    assertEquals("ack 1 rejected_not_ready 0, done 0 none guards 0, not_ready", outcome(cycle()));
    send(Blocks.command(2, CommandCode.HOLD));
    assertEquals("ack 2 rejected_not_ready 0, done 0 none guards 0, not_ready", outcome(cycle()));
    arm.ready = true;
    arm.safety = true;
    send(lin(3));
    assertEquals("ack 3 rejected_not_ready 0, done 0 none guards 0, safety_stop", outcome(cycle()));
    assertTrue(arm.calls.isEmpty());
  }

  @Test
  public void faultedRejectsAllButResetFaultWhichClearsOrReportsTheFault() {
    arm.faulted = true;
    send(lin(1));
    assertEquals("ack 1 rejected_faulted 0, done 0 none guards 0, faulted", outcome(cycle()));
    send(Blocks.command(2, CommandCode.HOLD));
    assertEquals("ack 2 rejected_faulted 0, done 0 none guards 0, faulted", outcome(cycle()));
    arm.faultPersists = true;
    send(Blocks.command(3, CommandCode.RESET_FAULT));
    assertEquals("ack 3 accepted 0, done 3 robot_fault guards 0, faulted", outcome(cycle()));
    arm.faultPersists = false;
    send(Blocks.command(4, CommandCode.RESET_FAULT));
    assertEquals("ack 4 accepted 0, done 4 done guards 0, idle", outcome(cycle()));
    assertEquals("[resetFault, resetFault]", arm.calls.toString());
  }

  @Test
  public void unreachableTargetIsRejected() {
    arm.reachable = false;
    send(lin(1));
    assertEquals("ack 1 rejected_unreachable 0, done 0 none guards 0, idle", outcome(cycle()));
  }

  @Test
  public void staleHeartbeatRejectsMotionsButNotHoldOrSetTool() {
    cycle();  // the cycle sees the heartbeat change: the watchdog counts from here
    clock.now += 501;
    send(lin(1));
    Status s = cycle();
    assertEquals("ack 1 rejected_heartbeat_stale 0, done 0 none guards 0, idle", outcome(s));
    assertEquals(0, s.statusBits & StatusBit.HOST_HEARTBEAT_OK_MASK);
    send(Blocks.command(2, CommandCode.HOLD));
    assertEquals("ack 2 accepted 0, done 2 done guards 0, idle", outcome(cycle()));
    send(Blocks.command(3, CommandCode.SET_TOOL).set(Command.TOOL, 2).pose(TARGET));
    s = cycle();
    assertEquals("ack 3 accepted 0, done 3 done guards 0, idle", outcome(s));
    assertEquals(2, s.tool);
    assertTrue((s.statusBits & StatusBit.TOOL_SET_MASK) != 0);
    beat();
    send(lin(4));
    assertEquals("ack 4 accepted 0, done 3 done guards 0, moving", outcome(cycle()));
  }

  @Test
  public void watchdogStopsAMotionWhenTheHeartbeatIsUnchangedForLongerThanWatchdogMs() {
    send(lin(1));
    cycle();
    clock.now += 500;
    assertEquals("ack 1 accepted 0, done 0 none guards 0, moving", outcome(cycle()));
    assertEquals(0, arm.stops);
    arm.pose = new Pose(1, 2, 3, 4, 5, 6);
    clock.now += 1;
    Status s = cycle();
    assertEquals(1, arm.stops);
    assertEquals("ack 1 accepted 0, done 0 none guards 0, moving", outcome(s));  // braking
    assertEquals(StatusBit.WATCHDOG_TRIPPED_MASK, s.statusBits & (StatusBit.WATCHDOG_TRIPPED_MASK | StatusBit.HOST_HEARTBEAT_OK_MASK));
    arm.rest();
    s = cycle();
    assertEquals("ack 1 accepted 0, done 1 watchdog guards 0, idle", outcome(s));
    assertEquals(new Pose(1, 2, 3, 4, 5, 6), s.latched);
    beat();
    send(lin(2));
    s = cycle();
    assertEquals(0, s.statusBits & StatusBit.WATCHDOG_TRIPPED_MASK);
    assertTrue((s.statusBits & StatusBit.HOST_HEARTBEAT_OK_MASK) != 0);
  }

  @Test
  public void aLongerWatchdogMsTakesEffectAtOnce() {
    write(HostControl.WATCHDOG_MS, 2000);
    send(lin(1));
    cycle();
    clock.now += 2000;
    cycle();
    assertEquals(0, arm.stops);
    clock.now += 1;
    cycle();
    assertEquals(1, arm.stops);
  }

  @Test
  public void closedConnectionStopsAMotionLikeTheWatchdog() {
    send(lin(1));
    cycle();
    core.connectionClosed();
    cycle();
    assertEquals(1, arm.stops);
    arm.rest();
    assertEquals("ack 1 accepted 0, done 1 watchdog guards 0, idle", outcome(cycle()));
  }

  @Test
  public void stopDuringAMoveLatchesBrakesAndSetsStopSeenWhenStationary() {
    send(lin(1));
    cycle();
    arm.pose = new Pose(7, 8, 9, 10, 11, 12);
    stopRequest();
    Status s = cycle();
    assertEquals(1, arm.stops);
    assertEquals(0, s.stopSeen);
    assertEquals("ack 1 accepted 0, done 0 none guards 0, moving", outcome(s));
    assertEquals(new Pose(7, 8, 9, 10, 11, 12), s.latched);
    assertTrue((s.statusBits & StatusBit.LATCHED_POSE_VALID_MASK) != 0);
    arm.pose = new Pose(17, 8, 9, 10, 11, 12);  // where it comes to rest after braking
    arm.rest();
    s = cycle();
    assertEquals(1, s.stopSeen);
    assertEquals("ack 1 accepted 0, done 1 stopped guards 0, idle", outcome(s));
    assertEquals(new Pose(7, 8, 9, 10, 11, 12), s.latched);
    send(lin(2));  // a stop is an edge: the next command runs
    assertEquals("ack 2 accepted 0, done 1 stopped guards 0, moving", outcome(cycle()));
  }

  @Test
  public void stopWhileStationaryLatchesAndIsSeenAtOnce() {
    Status s = cycle();
    assertEquals(0, s.statusBits & StatusBit.LATCHED_POSE_VALID_MASK);
    stopRequest();
    s = cycle();
    assertEquals(1, s.stopSeen);
    assertEquals(arm.pose, s.latched);
    assertTrue((s.statusBits & StatusBit.LATCHED_POSE_VALID_MASK) != 0);
  }

  @Test
  public void stopRacingDoneKeepsDoneAndStillSetsStopSeen() {
    send(Blocks.command(43, CommandCode.MOVE_LIN_REL).set32(Command.SPEED, 10000).set32(Command.Z_UM, -5000));
    write(HostControl.STOP_REQUEST, 3);
    stop = 3;
    Status s = cycle();
    assertEquals(3, s.stopSeen);
    arm.end(Arm.MOTION_REACHED);  // the retreat reaches its target ...
    stopRequest();                // ... before the bridge reads the stop
    s = cycle();
    assertEquals("ack 43 accepted 0, done 43 done guards 0, idle", outcome(s));
    assertEquals(4, s.stopSeen);
    assertEquals(arm.pose, s.latched);
    assertEquals(0, arm.stops);
  }

  @Test
  public void forceGuardEndsTheApproachWithItsBitAndTheLatchedPose() {
    send(approach(42, GuardSource.HOST_STOP_MASK | GuardSource.FORCE_MASK));
    cycle();
    assertEquals("[guardedApproach axis 3 travel 20000 speed 2000 input 0 force 2000]", arm.calls.toString());
    arm.forceMN = 1999;
    cycle();
    assertEquals(0, arm.stops);
    arm.forceMN = 2000;
    arm.pose = new Pose(500000, -123456, 212350, 180000, 0, -179999);
    Status s = cycle();
    assertEquals(1, arm.stops);
    assertEquals(Axis.TOOL_Z, arm.forceAxis);
    assertEquals(1, arm.forceDirection);
    arm.pose = new Pose(500000, -123456, 212345, 180000, 0, -179999);
    arm.forceMN = 2500;
    arm.rest();
    s = cycle();
    assertEquals("ack 42 accepted 0, done 42 guard_fired guards 4, idle", outcome(s));
    assertEquals(212350, s.latched.zUm);
    assertEquals(212345, s.pose.zUm);
    assertEquals(2500, s.forceMN);
  }

  @Test
  public void digitalInputGuardFiredOnTheRobotLatchesTheArmsGuardPose() {
    send(approach(7, GuardSource.DIGITAL_INPUT_MASK));
    cycle();
    assertEquals("[guardedApproach axis 3 travel 20000 speed 2000 input 3 force 0]", arm.calls.toString());
    arm.fired = GuardSource.DIGITAL_INPUT_MASK;
    arm.guardPose = new Pose(1, 1, 1, 0, 0, 0);
    arm.end(Arm.MOTION_GUARD);
    Status s = cycle();
    assertEquals("ack 7 accepted 0, done 7 guard_fired guards 2, idle", outcome(s));
    assertEquals(new Pose(1, 1, 1, 0, 0, 0), s.latched);
  }

  @Test
  public void digitalInputSeenByTheCycleAlsoEndsTheApproach() {
    send(approach(7, GuardSource.DIGITAL_INPUT_MASK));
    cycle();
    arm.inputs[3] = true;
    cycle();
    assertEquals(1, arm.stops);
    arm.rest();
    assertEquals("ack 7 accepted 0, done 7 guard_fired guards 2, idle", outcome(cycle()));
  }

  @Test
  public void hostStopIsAGuardOnlyWhenItIsAGuardSource() {
    send(approach(1, GuardSource.HOST_STOP_MASK));
    cycle();
    stopRequest();
    cycle();
    arm.rest();
    assertEquals("ack 1 accepted 0, done 1 guard_fired guards 1, idle", outcome(cycle()));
    send(approach(2, GuardSource.FORCE_MASK));
    cycle();
    stopRequest();
    cycle();
    arm.rest();
    assertEquals("ack 2 accepted 0, done 2 stopped guards 0, idle", outcome(cycle()));
  }

  @Test
  public void approachWithoutAGuardEndsWithMaxTravel() {
    Blocks b = approach(1, GuardSource.FORCE_MASK).set32(Command.MAX_TRAVEL_UM, -3000);
    send(b);
    cycle();
    assertEquals(-1, arm.forceDirection);  // the force is reported against the motion in -z
    arm.end(Arm.MOTION_REACHED);
    assertEquals("ack 1 accepted 0, done 1 max_travel guards 0, idle", outcome(cycle()));
  }

  @Test
  public void holdSupersedesTheMotionAndIsDoneWhenStationary() {
    send(lin(1));
    cycle();
    send(Blocks.command(2, CommandCode.HOLD));
    Status s = cycle();
    assertEquals("ack 2 accepted 0, done 1 superseded guards 0, moving", outcome(s));
    assertEquals(1, arm.stops);
    arm.rest();
    assertEquals("ack 2 accepted 0, done 2 done guards 0, idle", outcome(cycle()));
  }

  @Test
  public void robotFaultAndSafetyStopEndTheMotion() {
    send(lin(1));
    cycle();
    arm.faulted = true;
    arm.end(Arm.MOTION_FAULT);
    assertEquals("ack 1 accepted 0, done 1 robot_fault guards 0, faulted", outcome(cycle()));
    arm.faulted = false;
    send(lin(2));
    cycle();
    arm.safety = true;
    arm.end(Arm.MOTION_SAFETY);
    assertEquals("ack 2 accepted 0, done 2 safety_stopped guards 0, safety_stop", outcome(cycle()));
  }

  @Test
  public void anArmThatThrowsOnStartFaultsTheBridgeUntilResetFault() {
    arm.failNextStart = new IllegalStateException("workspace violation");
    send(lin(1));
    assertEquals("ack 1 accepted 0, done 1 robot_fault guards 0, faulted", outcome(cycle()));
    assertEquals("workspace violation", core.lastArmError());
    send(lin(2));
    assertEquals("ack 2 rejected_faulted 0, done 1 robot_fault guards 0, faulted", outcome(cycle()));
    send(Blocks.command(3, CommandCode.RESET_FAULT));
    assertEquals("ack 3 accepted 0, done 3 done guards 0, idle", outcome(cycle()));
    send(lin(4));
    assertEquals("ack 4 accepted 0, done 3 done guards 0, moving", outcome(cycle()));
  }

  @Test
  public void forceIsReportedOnlyWhileValid() {
    arm.forceMN = 1234;
    assertEquals(1234, cycle().forceMN);
    arm.forceValid = false;
    Status s = cycle();
    assertEquals(0, s.forceMN);
    assertFalse((s.statusBits & StatusBit.FORCE_VALID_MASK) != 0);
  }
}
