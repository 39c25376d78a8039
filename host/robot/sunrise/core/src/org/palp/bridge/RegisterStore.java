// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

/**
 * The bridge's holding registers and the access rules of robot-bridge.md section 3. The Modbus
 * server thread reads and writes here; the cycle takes the host's blocks and publishes the status
 * block as one snapshot. Every method is atomic (one lock), so a read of the status block is one
 * cycle's snapshot and a command block is handed to the cycle whole.
 */
public final class RegisterStore {
  private final int[] identification = new int[RegisterMap.Identification.LENGTH];
  private final int[] status = new int[RegisterMap.StatusBlock.LENGTH];
  private final int[] control = new int[RegisterMap.HostControl.LENGTH];
  private final int[] command = new int[RegisterMap.Command.LENGTH];

  public RegisterStore() {
    int[] id = identification;
    int base = RegisterMap.Identification.ADDRESS;
    Words.put(id, RegisterMap.Identification.MAGIC - base, RegisterMap.MAGIC);
    id[RegisterMap.Identification.MAP_MAJOR - base] = RegisterMap.MAP_MAJOR;
    id[RegisterMap.Identification.MAP_MINOR - base] = RegisterMap.MAP_MINOR;
    id[RegisterMap.Identification.STATUS_ADDRESS - base] = RegisterMap.StatusBlock.ADDRESS;
    id[RegisterMap.Identification.STATUS_LENGTH - base] = RegisterMap.StatusBlock.LENGTH;
    id[RegisterMap.Identification.CONTROL_ADDRESS - base] = RegisterMap.HostControl.ADDRESS;
    id[RegisterMap.Identification.CONTROL_LENGTH - base] = RegisterMap.HostControl.LENGTH;
    id[RegisterMap.Identification.COMMAND_ADDRESS - base] = RegisterMap.Command.ADDRESS;
    id[RegisterMap.Identification.COMMAND_LENGTH - base] = RegisterMap.Command.LENGTH;
    control[RegisterMap.HostControl.WATCHDOG_MS - RegisterMap.HostControl.ADDRESS] = RegisterMap.DEFAULT_WATCHDOG_MS;
  }

  /** FC3: count registers from address, inside one block (exception 02 otherwise, 03 for a bad count). */
  public synchronized int[] read(int address, int count) throws ModbusException {
    if (count < 1 || count > RegisterMap.MAX_READ_REGISTERS)
      throw new ModbusException(ModbusException.ILLEGAL_DATA_VALUE, "read of " + count + " registers (1.."
          + RegisterMap.MAX_READ_REGISTERS + ")");
    int[] block = blockAt(address, count);
    if (block == null)
      throw new ModbusException(ModbusException.ILLEGAL_DATA_ADDRESS, "read of " + count + " registers at "
          + address + " is not inside one block");
    int[] out = new int[count];
    System.arraycopy(block, address - blockAddress(address), out, 0, count);
    return out;
  }

  /**
   * FC6/FC16: values from address. Only the host's blocks (host control, command) are writable,
   * the command block only whole, watchdog_ms only within 100..10000. A refused write changes
   * nothing.
   */
  public synchronized void write(int address, int[] values) throws ModbusException {
    int count = values.length;
    int[] block = blockAt(address, count);
    if (block == null)
      throw new ModbusException(ModbusException.ILLEGAL_DATA_ADDRESS, "write of " + count + " registers at "
          + address + " is not inside one block");
    if (block != control && block != command)
      throw new ModbusException(ModbusException.ILLEGAL_DATA_ADDRESS, "write at " + address
          + ": the block is read-only");
    if (block == command && (address != RegisterMap.Command.ADDRESS || count != RegisterMap.Command.LENGTH))
      throw new ModbusException(ModbusException.ILLEGAL_DATA_ADDRESS, "write of " + count + " registers at "
          + address + ": the command block is written whole (" + RegisterMap.Command.ADDRESS + ", "
          + RegisterMap.Command.LENGTH + " registers)");
    for (int i = 0; i < count; ++i) {
      if (values[i] < 0 || values[i] > 0xFFFF)
        throw new ModbusException(ModbusException.ILLEGAL_DATA_VALUE, "register value " + values[i]);
      if (address + i == RegisterMap.HostControl.WATCHDOG_MS
          && (values[i] < RegisterMap.MIN_WATCHDOG_MS || values[i] > RegisterMap.MAX_WATCHDOG_MS))
        throw new ModbusException(ModbusException.ILLEGAL_DATA_VALUE, "watchdog_ms " + values[i] + " outside "
            + RegisterMap.MIN_WATCHDOG_MS + ".." + RegisterMap.MAX_WATCHDOG_MS);
    }
    System.arraycopy(values, 0, block, address - blockAddress(address), count);
  }

  /** The host control block as written so far (a copy). */
  public synchronized int[] hostControl() {
    return control.clone();
  }

  /** The command block as written so far (a copy). */
  public synchronized int[] command() {
    return command.clone();
  }

  /** Publishes the status block (StatusBlock.LENGTH registers) as one snapshot. */
  public synchronized void publishStatus(int[] regs) {
    if (regs.length != status.length)
      throw new IllegalArgumentException("status block of " + regs.length + " registers, expected " + status.length);
    System.arraycopy(regs, 0, status, 0, status.length);
  }

  private int[] blockAt(int address, int count) {
    int[] block = blockOf(address);
    if (block == null || count < 1) return null;
    int end = blockAddress(address) + block.length;
    return address + count <= end ? block : null;
  }

  private int[] blockOf(int address) {
    if (within(address, RegisterMap.Identification.ADDRESS, RegisterMap.Identification.LENGTH)) return identification;
    if (within(address, RegisterMap.StatusBlock.ADDRESS, RegisterMap.StatusBlock.LENGTH)) return status;
    if (within(address, RegisterMap.HostControl.ADDRESS, RegisterMap.HostControl.LENGTH)) return control;
    if (within(address, RegisterMap.Command.ADDRESS, RegisterMap.Command.LENGTH)) return command;
    return null;
  }

  private static int blockAddress(int address) {
    if (address >= RegisterMap.Command.ADDRESS) return RegisterMap.Command.ADDRESS;
    if (address >= RegisterMap.HostControl.ADDRESS) return RegisterMap.HostControl.ADDRESS;
    if (address >= RegisterMap.StatusBlock.ADDRESS) return RegisterMap.StatusBlock.ADDRESS;
    return RegisterMap.Identification.ADDRESS;
  }

  private static boolean within(int address, int start, int length) {
    return address >= start && address < start + length;
  }
}
