// SPDX-License-Identifier: Apache-2.0
// Writes a three-sample recording as HDF5 with the installed palp::hdf5 and reads it back.
#include <cstdio>
#include <filesystem>

#include "palp/hdf5.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  palp::Recording r;
  for (int k = 0; k < 3; ++k) r.append({.t_s = 0.001 * k, .i_A = 0.5, .z_mm = 0.25 * k, .rep = 0});
  const std::filesystem::path file = argv[1];
  palp::write_recording_hdf5(file, r, palp::Overwrite::yes);
  const palp::Recording back = palp::read_recording_hdf5(file);
  std::printf("hdf5 %s rows %zu z_mm[2] %.2f\n", palp::hdf5_content(file).c_str(), back.size(), back.z_mm[2]);
  return back.z_mm == r.z_mm ? 0 : 1;
}
