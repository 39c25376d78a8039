// SPDX-License-Identifier: Apache-2.0
// palp-hdf5-fixture DIR: writes DIR/recording.h5, DIR/result.h5, DIR/map.h5 (of the map directory
// DIR/map) and DIR/identification.h5 from the known synthetic recording, result, map and
// identification (hdf5_fixture.hpp), for the independent readers h5py and h5dump.
#include <cstdio>
#include <exception>
#include <filesystem>

#include "hdf5_fixture.hpp"
#include "palp/hdf5.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: palp-hdf5-fixture DIR\n");
    return 2;
  }
  try {
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    palp::write_recording_hdf5(dir / "recording.h5", palp_test::known_recording(), palp::Overwrite::yes);
    palp::write_result_hdf5(dir / "result.h5", palp_test::known_result(), palp::Overwrite::yes);
    std::filesystem::remove_all(dir / "map");
    palp::write_map_hdf5(dir / "map.h5", palp_test::known_map(dir / "map"), palp::Overwrite::yes);
    palp::write_identification_hdf5(dir / "identification.h5", palp_test::known_identification(),
                                    palp::Overwrite::yes);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "palp-hdf5-fixture: %s\n", e.what());
    return 1;
  }
  return 0;
}
