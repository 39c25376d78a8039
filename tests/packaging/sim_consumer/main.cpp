// SPDX-License-Identifier: Apache-2.0
// Built against an installed palp with palp-sim linked in: connect to a simulated controller by
// URI (the real firmware core on the solid phantom, shipped inside the installed library), hold
// 0.2 A for 0.5 s of virtual time, and print what the device says.
#include <chrono>
#include <cstdio>

#include "palp/probe.hpp"

int main() {
  palp::Probe probe("sim+inproc://solid_1d?seed=3");
  std::printf("board %s serial %s\n", probe.info().board.c_str(), probe.info().serial.c_str());
  palp::HoldProgram hold;
  hold.current_A = 0.2f;
  hold.duration_s = 0.5f;
  const palp::ProgramResult r = probe.run(hold, std::chrono::seconds(10));
  std::printf("hold ended %s after %.1f s of device time\n",
              r.end == palp::proto::ProgramEnd::completed ? "completed" : "otherwise",
              r.t_device_s);
  probe.close();
  return 0;
}
