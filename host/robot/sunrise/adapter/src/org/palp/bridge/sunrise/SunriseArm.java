// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge.sunrise;

import static com.kuka.roboticsAPI.motionModel.BasicMotions.lin;
import static com.kuka.roboticsAPI.motionModel.BasicMotions.linRel;
import static com.kuka.roboticsAPI.motionModel.BasicMotions.ptp;

import org.palp.bridge.Arm;
import org.palp.bridge.Pose;
import org.palp.bridge.RegisterMap.Axis;
import org.palp.bridge.RegisterMap.CommandCode;
import org.palp.bridge.RegisterMap.GuardSource;

import com.kuka.generated.ioAccess.ExtIOGroup;
import com.kuka.roboticsAPI.conditionModel.BooleanIOCondition;
import com.kuka.roboticsAPI.conditionModel.ForceCondition;
import com.kuka.roboticsAPI.conditionModel.ICondition;
import com.kuka.roboticsAPI.conditionModel.IFiredConditionInfo;
import com.kuka.roboticsAPI.deviceModel.JointPosition;
import com.kuka.roboticsAPI.deviceModel.LBR;
import com.kuka.roboticsAPI.deviceModel.OperationMode;
import com.kuka.roboticsAPI.geometricModel.Frame;
import com.kuka.roboticsAPI.geometricModel.ObjectFrame;
import com.kuka.roboticsAPI.geometricModel.Tool;
import com.kuka.roboticsAPI.geometricModel.World;
import com.kuka.roboticsAPI.geometricModel.math.CoordinateAxis;
import com.kuka.roboticsAPI.geometricModel.math.Transformation;
import com.kuka.roboticsAPI.geometricModel.math.Vector;
import com.kuka.roboticsAPI.motionModel.IMotion;
import com.kuka.roboticsAPI.motionModel.IMotionContainer;
import com.kuka.roboticsAPI.motionModel.RelativeLIN;
import com.kuka.roboticsAPI.safetyModel.SafetyStopType;
import com.kuka.task.ITaskLogger;

/**
 * The bridge's Arm on an LBR iiwa with the Sunrise Robotics API: every motion is moveAsync, a
 * guarded approach is a linRel with breakWhen conditions (force along the axis, the wired input),
 * stop() is IMotionContainer.cancel(). Called only from the application's cycle thread. Units
 * convert here: registers in um / mdeg / mN, Sunrise in mm / rad / N.
 *
 * Lines marked CHECK depend on the Sunrise release and the cell's configuration and must be
 * verified on the real controller (host/robot/sunrise/COMMISSIONING.md).
 */
final class SunriseArm implements Arm {
  // Workspace box of the base frame, mm: a target outside is rejected_unreachable. CHECK: set for
  // the cell (table, fixtures); the controller's own workspace monitoring stays active anyway.
  private static final double[] MIN_MM = {-800, -800, 0};
  private static final double[] MAX_MM = {800, 800, 1200};

  private final LBR lbr;
  private final ITaskLogger log;
  private final ExtIOGroup io;  // CHECK: the IO group WorkVisual generated for the probe's contact line
  private ObjectFrame tcp;
  private IMotionContainer container;
  private boolean approach;
  private boolean stopRequested;
  private int fired;
  private Pose guardPose = Pose.ZERO;
  private boolean faulted;

  SunriseArm(LBR lbr, ITaskLogger log) {
    this.lbr = lbr;
    this.log = log;
    this.io = new ExtIOGroup(lbr.getController());
    this.tcp = lbr.getFlange();
  }

  // ---- motions ---------------------------------------------------------------------------
  @Override
  public void moveLin(Pose target, int speedUmPerS) {
    start(lin(frame(target)).setCartVelocity(speedUmPerS / 1000.0), false);
  }

  @Override
  public void moveLinRel(Pose offset, int speedUmPerS) {
    start(linRel(transformation(offset), tcp).setCartVelocity(speedUmPerS / 1000.0), false);
  }

  @Override
  public void movePtp(Pose target, int speedPermille) {
    start(ptp(frame(target)).setJointVelocityRel(speedPermille / 1000.0), false);
  }

  @Override
  public void guardedApproach(int axis, int maxTravelUm, int speedUmPerS, int digitalInput, int forceThresholdMN) {
    double mm = maxTravelUm / 1000.0;
    ObjectFrame reference = axis <= Axis.TOOL_Z ? tcp : World.Current.getRootFrame();
    int k = (axis - 1) % 3;  // 0: x, 1: y, 2: z
    RelativeLIN motion = linRel(k == 0 ? mm : 0, k == 1 ? mm : 0, k == 2 ? mm : 0, reference);
    motion.setCartVelocity(speedUmPerS / 1000.0);
    if (forceThresholdMN > 0) {
      // CHECK: a normal force condition on the reference frame's axis, threshold in N; the sign
      // convention of the external force (push the tool by hand and read force_mN)
      CoordinateAxis c = k == 0 ? CoordinateAxis.X : k == 1 ? CoordinateAxis.Y : CoordinateAxis.Z;
      ICondition force = ForceCondition.createNormalForceCondition(reference, c, forceThresholdMN / 1000.0);
      motion.breakWhen(force);
    }
    if (digitalInput > 0) {
      // CHECK: the input's name in the IO group ("Input1".."Input16" here)
      motion.breakWhen(new BooleanIOCondition(io.getInput("Input" + digitalInput), true));
    }
    start(motion, true);
  }

  private void start(IMotion motion, boolean isApproach) {
    approach = isApproach;
    stopRequested = false;
    fired = 0;
    container = tcp.moveAsync(motion);
  }

  /** Brakes on the path. CHECK: cancel() of a running container brakes on the path (stop category 2). */
  @Override
  public void stop() {
    stopRequested = true;
    if (container != null && !container.isFinished()) container.cancel();
  }

  @Override
  public boolean isMoving() {
    // CHECK: the container finishes when the robot is stationary after a cancel or a break
    return container != null && !container.isFinished();
  }

  @Override
  public int motionStatus() {
    if (container == null || !container.isFinished()) return MOTION_RUNNING;
    if (safetyStopped()) return MOTION_SAFETY;
    if (container.hasError()) {
      faulted = true;
      log.error("palp bridge: motion error: " + container.getErrorMessage());
      return MOTION_FAULT;
    }
    IFiredConditionInfo info = container.getFiredBreakConditionInfo();
    if (approach && info != null) {
      // CHECK: the position where the condition fired, not where the arm came to rest
      guardPose = pose(info.getPositionInfo().getCurrentCartesianPosition());
      fired = info.getFiredCondition() instanceof BooleanIOCondition ? GuardSource.DIGITAL_INPUT_MASK
                                                                      : GuardSource.FORCE_MASK;
      return MOTION_GUARD;
    }
    return stopRequested ? MOTION_STOPPED : MOTION_REACHED;
  }

  @Override
  public int firedGuards() {
    return fired;
  }

  @Override
  public Pose guardPose() {
    return guardPose;
  }

  // ---- measurements ----------------------------------------------------------------------
  @Override
  public Pose pose() {
    return pose(lbr.getCurrentCartesianPosition(tcp));
  }

  @Override
  public int[] jointsMdeg() {
    JointPosition j = lbr.getCurrentJointPosition();
    int[] out = new int[7];
    for (int i = 0; i < 7; ++i) out[i] = (int) Math.round(Math.toDegrees(j.get(i)) * 1000.0);
    return out;
  }

  @Override
  public boolean forceValid() {
    return lbr.isReadyToMove();  // CHECK: torque sensors referenced; the estimate is poor near singularities
  }

  @Override
  public int forceMN(int axis, int direction) {
    ObjectFrame orientation = axis <= Axis.TOOL_Z ? tcp : World.Current.getRootFrame();
    Vector f = lbr.getExternalForceTorque(tcp, orientation).getForce();
    int k = (axis - 1) % 3;
    double along = k == 0 ? f.getX() : k == 1 ? f.getY() : f.getZ();
    // positive against the motion: the specimen pushing back. CHECK the sign on the robot.
    return (int) Math.round(-direction * along * 1000.0);
  }

  @Override
  public boolean digitalInput(int input) {
    return io.getBooleanIOValue("Input" + input, false);  // CHECK: input names as in guardedApproach
  }

  @Override
  public boolean reachable(int commandCode, Pose target) {
    if (commandCode == CommandCode.MOVE_LIN_REL) {
      Frame goal = lbr.getCurrentCartesianPosition(tcp).transform(transformation(target));
      return inBox(goal.getX(), goal.getY(), goal.getZ());
    }
    return inBox(target.xUm / 1000.0, target.yUm / 1000.0, target.zUm / 1000.0);
  }

  private static boolean inBox(double x, double y, double z) {
    double[] p = {x, y, z};
    for (int i = 0; i < 3; ++i)
      if (p[i] < MIN_MM[i] || p[i] > MAX_MM[i]) return false;
    return true;
  }

  @Override
  public void setTool(int tool, Pose tcpOnFlange) {
    Tool t = new Tool("palp_tool_" + tool);
    t.attachTo(lbr.getFlange(), transformation(tcpOnFlange));  // CHECK: TCP = the tool's root frame here
    tcp = t.getDefaultMotionFrame();
  }

  // ---- state -----------------------------------------------------------------------------
  @Override
  public boolean drivesEnabled() {
    return lbr.isReadyToMove();  // CHECK: Sunrise has no separate drives flag in the public API
  }

  @Override
  public boolean automaticMode() {
    return lbr.getSafetyState().getOperationMode() == OperationMode.AUT;
  }

  @Override
  public boolean ready() {
    return lbr.isReadyToMove();
  }

  @Override
  public boolean faulted() {
    return faulted;
  }

  @Override
  public boolean safetyStopped() {
    return lbr.getSafetyState().getSafetyStopSignal() != SafetyStopType.NOSTOP;
  }

  @Override
  public boolean resetFault() {
    faulted = !lbr.isReadyToMove();  // CHECK: errors needing acknowledgement at the smartPAD stay
    return !faulted;
  }

  // ---- conversions -----------------------------------------------------------------------
  private static Frame frame(Pose p) {
    return new Frame(World.Current.getRootFrame(), transformation(p));
  }

  private static Transformation transformation(Pose p) {
    return Transformation.ofDeg(p.xUm / 1000.0, p.yUm / 1000.0, p.zUm / 1000.0, p.aMdeg / 1000.0, p.bMdeg / 1000.0,
        p.cMdeg / 1000.0);
  }

  private static Pose pose(Frame f) {
    return new Pose(um(f.getX()), um(f.getY()), um(f.getZ()), mdeg(f.getAlphaRad()), mdeg(f.getBetaRad()),
        mdeg(f.getGammaRad()));
  }

  private static int um(double mm) {
    return (int) Math.round(mm * 1000.0);
  }

  private static int mdeg(double rad) {
    return (int) Math.round(Math.toDegrees(rad) * 1000.0);
  }
}
