// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

import org.palp.bridge.RegisterMap.Command;

/** Builds command blocks for the tests, register by register through the generated map. */
final class Blocks {
  private final int[] regs = new int[Command.LENGTH];

  static Blocks command(int seq, int code) {
    Blocks b = new Blocks();
    b.set(Command.SEQ, seq).set(Command.CODE, code);
    return b;
  }

  Blocks set(int address, int value) {
    regs[address - Command.ADDRESS] = value & 0xFFFF;
    return this;
  }

  Blocks set32(int address, int value) {
    Words.put(regs, address - Command.ADDRESS, value);
    return this;
  }

  Blocks pose(Pose p) {
    return set32(Command.X_UM, p.xUm).set32(Command.Y_UM, p.yUm).set32(Command.Z_UM, p.zUm)
        .set32(Command.A_MDEG, p.aMdeg).set32(Command.B_MDEG, p.bMdeg).set32(Command.C_MDEG, p.cMdeg);
  }

  int[] regs() {
    return regs.clone();
  }

  org.palp.bridge.Command decoded() {
    return org.palp.bridge.Command.fromRegisters(regs);
  }
}
