// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

/**
 * A kinematic arm for LoopbackBridge: straight-line motion at the commanded speed, a 10 ms stop
 * latency, tool frame = base frame, and a rigid plate at plateZUm with a stiffness of 1 N/mm that
 * pushes back on the tool below it. Enough to run bridge_check.py.
 *
 * It moves on the clock it is given, which LoopbackBridge steps by one cycle (5 ms) per bridge
 * cycle: what the arm does between two cycles never depends on how the JVM was scheduled (on the
 * wall clock, a cycle thread preempted between the core's latch of the pose and its stop, or a
 * late cycle, moved the arm further: issue 17's flaky force-guard test).
 */
final class SimulatedArm implements Arm {
  private static final long STOP_LATENCY_MS = 10;
  private final Clock clock;
  private final int plateZUm;
  private double x;
  private double y;
  private double z;
  private double[] from = new double[3];
  private double[] dir = new double[3];
  private double distanceUm;
  private double speedUmPerMs;
  private long startMs;
  private long stopAtMs = -1;
  private boolean active;
  private boolean stopped;

  SimulatedArm(Clock clock, int startZUm, int plateZUm) {
    this.clock = clock;
    this.z = startZUm;
    this.plateZUm = plateZUm;
  }

  private long now() {
    return clock.millis();
  }

  private synchronized void update() {
    if (!active) return;
    long t = now();
    if (stopAtMs >= 0 && t >= stopAtMs) t = stopAtMs;
    double s = Math.min(distanceUm, speedUmPerMs * (t - startMs));
    x = from[0] + dir[0] * s;
    y = from[1] + dir[1] * s;
    z = from[2] + dir[2] * s;
    if (s >= distanceUm || (stopAtMs >= 0 && now() >= stopAtMs)) active = false;
  }

  private synchronized void start(double dx, double dy, double dz, int speedUmPerS) {
    update();
    from = new double[] {x, y, z};
    distanceUm = Math.sqrt(dx * dx + dy * dy + dz * dz);
    dir = distanceUm == 0 ? new double[3] : new double[] {dx / distanceUm, dy / distanceUm, dz / distanceUm};
    speedUmPerMs = speedUmPerS / 1000.0;
    startMs = now();
    stopAtMs = -1;
    stopped = false;
    active = true;
  }

  @Override
  public void moveLin(Pose target, int speedUmPerS) {
    update();
    start(target.xUm - x, target.yUm - y, target.zUm - z, speedUmPerS);
  }

  @Override
  public void moveLinRel(Pose offset, int speedUmPerS) {
    start(offset.xUm, offset.yUm, offset.zUm, speedUmPerS);
  }

  @Override
  public void movePtp(Pose target, int speedPermille) {
    moveLin(target, speedPermille * 250);
  }

  @Override
  public void guardedApproach(int axis, int maxTravelUm, int speedUmPerS, int digitalInput, int forceThresholdMN) {
    int k = (axis - 1) % 3;
    start(k == 0 ? maxTravelUm : 0, k == 1 ? maxTravelUm : 0, k == 2 ? maxTravelUm : 0, speedUmPerS);
  }

  @Override
  public synchronized void stop() {
    update();
    if (active && stopAtMs < 0) {
      stopAtMs = now() + STOP_LATENCY_MS;
      stopped = true;
    }
  }

  @Override
  public synchronized boolean isMoving() {
    update();
    return active;
  }

  @Override
  public synchronized int motionStatus() {
    update();
    if (active) return MOTION_RUNNING;
    return stopped ? MOTION_STOPPED : MOTION_REACHED;
  }

  @Override
  public int firedGuards() {
    return 0;
  }

  @Override
  public Pose guardPose() {
    return pose();
  }

  @Override
  public synchronized Pose pose() {
    update();
    return new Pose((int) Math.round(x), (int) Math.round(y), (int) Math.round(z), 180000, 0, 180000);
  }

  @Override
  public int[] jointsMdeg() {
    return new int[] {0, 30000, 0, -90000, 0, 60000, -45000};
  }

  @Override
  public boolean forceValid() {
    return true;
  }

  @Override
  public synchronized int forceMN(int axis, int direction) {
    update();
    double pushUp = Math.max(0, z - plateZUm);  // um into the plate; 1 N/mm = 1 mN/um, along base -z
    int k = (axis - 1) % 3;
    return k == 2 ? (int) Math.round(direction * pushUp) : 0;
  }

  @Override
  public boolean digitalInput(int input) {
    return false;
  }

  @Override
  public boolean reachable(int commandCode, Pose target) {
    return true;
  }

  @Override
  public void setTool(int tool, Pose tcpOnFlange) {}

  @Override
  public boolean drivesEnabled() {
    return true;
  }

  @Override
  public boolean automaticMode() {
    return false;
  }

  @Override
  public boolean ready() {
    return true;
  }

  @Override
  public boolean faulted() {
    return false;
  }

  @Override
  public boolean safetyStopped() {
    return false;
  }

  @Override
  public boolean resetFault() {
    return true;
  }
}
