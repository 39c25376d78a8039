// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

/**
 * 32-bit values as two 16-bit registers, high word first, two's complement
 * (robot-bridge.md section 4). Registers are held as ints 0..65535.
 */
public final class Words {
  private Words() {}

  /** The register holding bits 31..16 of v (the lower address). */
  public static int hi(int v) {
    return (v >>> 16) & 0xFFFF;
  }

  /** The register holding bits 15..0 of v (the higher address). */
  public static int lo(int v) {
    return v & 0xFFFF;
  }

  /** The signed 32-bit value of two registers, high word first. */
  public static int toInt(int hi, int lo) {
    return ((hi & 0xFFFF) << 16) | (lo & 0xFFFF);
  }

  /** The unsigned 32-bit value of two registers, high word first. */
  public static long toUnsigned(int hi, int lo) {
    return toInt(hi, lo) & 0xFFFFFFFFL;
  }

  /** Writes v into regs[at] (high) and regs[at + 1] (low). */
  public static void put(int[] regs, int at, int v) {
    regs[at] = hi(v);
    regs[at + 1] = lo(v);
  }

  /** The signed value of regs[at], regs[at + 1]. */
  public static int get(int[] regs, int at) {
    return toInt(regs[at], regs[at + 1]);
  }
}
