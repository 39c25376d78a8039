// SPDX-License-Identifier: Apache-2.0
package org.palp.bridge;

/** A clock the test advances by hand. */
final class FakeClock implements Clock {
  long now = 1000;

  @Override
  public long millis() {
    return now;
  }
}
