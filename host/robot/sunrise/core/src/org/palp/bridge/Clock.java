// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

/** The bridge's own clock (the watchdog counts on it, never on the host's). */
public interface Clock {
  /** Milliseconds from an arbitrary origin, monotonic. */
  long millis();

  /** The JVM's monotonic clock. */
  Clock SYSTEM = new Clock() {
    @Override
    public long millis() {
      return System.nanoTime() / 1000000L;
    }
  };
}
