// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

/** A request the register store refuses, answered with a Modbus exception code (section 9.3). */
public final class ModbusException extends Exception {
  private static final long serialVersionUID = 1L;

  public static final int ILLEGAL_FUNCTION = 1;
  public static final int ILLEGAL_DATA_ADDRESS = 2;
  public static final int ILLEGAL_DATA_VALUE = 3;
  public static final int SERVER_DEVICE_FAILURE = 4;

  private final int code;

  public ModbusException(int code, String message) {
    super(message);
    this.code = code;
  }

  /** The Modbus exception code, 1..4. */
  public int code() {
    return code;
  }
}
