// SPDX-License-Identifier: Apache-2.0
// Trace files (trace.hpp save_trace/load_trace): a round trip keeps what was measured and derives
// the rest again; malformed files give one line naming the file and the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numbers>

#include "palp/error.hpp"
#include "palp/trace.hpp"

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

std::filesystem::path temp_file(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("palp_trace_io_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

// A 2 x 2 grid on the flat plane z = 0 of a work object at (600, 0, 300) mm, C = 180 deg, the
// probe pointing down (tool z = base -z): each TCP 25 mm above the surface with the coil at
// 25 mm, so every apex touches z = 0; no detection force, so no indentation.
palp::TracedSurface flat_grid() {
  palp::TracedSurface s;
  s.plan_name = "flat";
  s.rows = 2;
  s.columns = 2;
  s.work_object = palp::Pose{0.600, 0.0, 0.300, 0, 0, 180 * kDeg};
  s.tip_radius_m = 2.5e-3;
  for (int r = 1; r <= 2; ++r)
    for (int c = 1; c <= 2; ++c) {
      palp::TracePoint p;
      p.row = r;
      p.column = c;
      p.ok = true;
      // work-object (x, y) = (10 c, 10 r) mm -> base (600 + x, -y, 300 + 25) mm
      p.tcp_at_rest = palp::Pose{0.600 + 0.010 * c, -0.010 * r, 0.325, 0, 0, 180 * kDeg};
      p.stroke_at_rest_m = 0.025;
      s.points.push_back(p);
    }
  s.resume_index = 4;
  s.complete = true;
  palp::finish_surface(s);
  return s;
}

TEST(TraceFile, AFlatGridDerivesContactPointsOnThePlaneWithUprightNormals) {
  const palp::TracedSurface s = flat_grid();
  ASSERT_TRUE(s.normals_from_grid);
  for (const auto& p : s.points) {
    EXPECT_NEAR(p.x_m, 0.010 * p.column, 1e-12);
    EXPECT_NEAR(p.y_m, 0.010 * p.row, 1e-12);
    EXPECT_NEAR(p.z_m, 0.0, 1e-12);
    EXPECT_NEAR(p.normal[2], 1.0, 1e-12);
    EXPECT_NEAR(p.tilt_rad, 0.0, 1e-9);
  }
}

TEST(TraceFile, RoundTripKeepsTheMeasurementsAndTheDerivedPoints) {
  palp::TracedSurface s = flat_grid();
  s.points[1].contact_stiffness_N_per_m = 600.0;
  s.points[1].detection_force_N = 0.009;
  s.contact_E_star_Pa = std::nullopt;
  palp::finish_surface(s);
  const auto file = temp_file("round_trip.json");
  palp::save_trace(file, s);
  const palp::TracedSurface back = palp::load_trace(file);
  ASSERT_EQ(back.points.size(), 4u);
  EXPECT_EQ(back.plan_name, "flat");
  EXPECT_EQ(back.resume_index, 4u);
  EXPECT_TRUE(back.complete);
  for (std::size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(back.points[k].z_m, s.points[k].z_m, 1e-12);
    EXPECT_NEAR(back.points[k].stroke_at_rest_m, s.points[k].stroke_at_rest_m, 1e-15);
  }
  ASSERT_TRUE(back.points[1].contact_stiffness_N_per_m);
  EXPECT_NEAR(*back.points[1].contact_stiffness_N_per_m, 600.0, 1e-9);
  // 1.5 F / k_c of indentation removed: the point lies 22.5 um deeper than its apex at rest
  EXPECT_NEAR(back.points[1].indentation_m, 1.5 * 0.009 / 600.0, 1e-12);
}

TEST(TraceFile, APartialTraceKeepsItsResumeIndex) {
  palp::TracedSurface s = flat_grid();
  s.points.resize(3);
  s.resume_index = 3;
  s.complete = false;
  s.stopped_because = "cancelled";
  palp::finish_surface(s);
  EXPECT_FALSE(s.normals_from_grid);
  const auto file = temp_file("partial.json");
  palp::save_trace(file, s);
  const palp::TracedSurface back = palp::load_trace(file);
  EXPECT_EQ(back.resume_index, 3u);
  EXPECT_EQ(back.stopped_because, "cancelled");
  EXPECT_FALSE(back.complete);
}

std::string load_error(const std::string& text) {
  const auto file = temp_file("bad.json");
  std::ofstream(file) << text;
  try {
    palp::load_trace(file);
  } catch (const palp::ConfigError& e) {
    return std::string(e.what()).substr(file.string().size());
  }
  return "no error";
}

// Found by fuzz_result_json: json::value threw a type_error (not a ConfigError) for a number.
TEST(TraceFile, AFormatThatIsNotAStringIsNotATraceFile) {
  EXPECT_EQ(load_error("{\"format\": 1}"), ": not a trace file (\"format\" is not \"palp.trace/1\")");
  EXPECT_EQ(load_error("{\"format\": [\"palp.trace/1\"]}"),
            ": not a trace file (\"format\" is not \"palp.trace/1\")");
}

TEST(TraceFile, MalformedFilesNameTheProblem) {
  EXPECT_EQ(load_error("{\"format\": \"palp.recording/1\"}"),
            ": not a trace file (\"format\" is not \"palp.trace/1\")");
  EXPECT_EQ(load_error("{\"format\": \"palp.trace/1\", \"rows\": \"two\"}"), ": \"rows\" must be a number");
  const std::string head =
      "{\"format\": \"palp.trace/1\", \"rows\": 1, \"columns\": 2, \"work_object_mm_deg\": [0,0,0,0,0,0], "
      "\"tip_radius_mm\": 2.5, \"resume_index\": ";
  EXPECT_EQ(load_error(head + "3, \"points\": []}"), ": 0 points, resume_index 3 do not fit a 1 x 2 grid");
  EXPECT_EQ(load_error(head + "1, \"points\": [{\"row\": 1, \"column\": 1, \"ok\": 1}]}"),
            ": points[0]: \"ok\" must be true or false");
  EXPECT_NE(load_error("{\"format\": ").find(": not JSON"), std::string::npos);
}

}  // namespace
