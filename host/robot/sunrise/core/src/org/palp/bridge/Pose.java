// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

/**
 * A TCP pose in register units: x, y, z in micrometres, A, B, C (KUKA ZYX Euler angles) in
 * millidegrees. Immutable.
 */
public final class Pose {
  public final int xUm;
  public final int yUm;
  public final int zUm;
  public final int aMdeg;
  public final int bMdeg;
  public final int cMdeg;

  public Pose(int xUm, int yUm, int zUm, int aMdeg, int bMdeg, int cMdeg) {
    this.xUm = xUm;
    this.yUm = yUm;
    this.zUm = zUm;
    this.aMdeg = aMdeg;
    this.bMdeg = bMdeg;
    this.cMdeg = cMdeg;
  }

  public static final Pose ZERO = new Pose(0, 0, 0, 0, 0, 0);

  @Override
  public boolean equals(Object o) {
    if (!(o instanceof Pose)) return false;
    Pose p = (Pose) o;
    return xUm == p.xUm && yUm == p.yUm && zUm == p.zUm && aMdeg == p.aMdeg && bMdeg == p.bMdeg
        && cMdeg == p.cMdeg;
  }

  @Override
  public int hashCode() {
    return ((((xUm * 31 + yUm) * 31 + zUm) * 31 + aMdeg) * 31 + bMdeg) * 31 + cMdeg;
  }

  @Override
  public String toString() {
    return "(" + xUm + " um, " + yUm + " um, " + zUm + " um, " + aMdeg + " mdeg, " + bMdeg + " mdeg, "
        + cMdeg + " mdeg)";
  }
}
