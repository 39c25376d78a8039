// SPDX-License-Identifier: Apache-2.0
// palpctl analyze: the real palpctl on recordings of KNOWN truth written with the SDK's recording
// writer (a Hertz or linear object at a known contact point, the paper's instrument constants),
// the JSON values checked against that truth, and the exact one-line error for each kind of bad
// input. No device.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"
#include "palp/analysis/contact_models.hpp"
#include "palp/recording.hpp"
#ifdef PALP_HAVE_HDF5
#include "palp/hdf5.hpp"
#endif
#include "test_analysis_synth.hpp"

namespace palpctl::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
namespace an = palp::analysis;

constexpr double kContactZmm = 12.3456789;
constexpr double kR = 2.5e-3;

class AnalyzeDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("palpctl-analyze-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A 0.5 -> top A staircase by 0.01 A, symmetric unload, `reps` repetitions, the probe where the
  /// coil force balances k_v delta + F_o(delta); 1 um encoder and `noise_A` rms current noise.
  /// Pressure channel ch (1..6) = gain[ch-1] x F_o when pressures are given.
  std::string write(const std::string& name, std::function<double(double)> Fo, double top_A = 3.0,
                    int reps = 3, double noise_A = 0.002, std::array<double, 6> gain = {}) {
    an::test::SynthSpec s;
    s.object_force = std::move(Fo);
    s.contact_z_m = kContactZmm * 1e-3;
    s.i_top_A = top_A;
    s.i_step_A = 0.01;
    s.reps = reps;
    s.noise_A = noise_A;
    s.quantum_m = 1e-6;
    const an::Curve c = an::test::synth_curve(s);
    const bool pressures = std::any_of(gain.begin(), gain.end(), [](double g) { return g != 0; });
    palp::WriterOptions o;
    o.columns = palp::ColumnSet::required().with(palp::Column::rep);
    if (pressures)
      for (std::size_t ch = 0; ch < 6; ++ch) o.columns = o.columns.with(palp::pressure_column(ch));
    const std::string path = (dir_ / (name + ".csv")).string();
    palp::RecordingWriter w(path, o);
    for (Eigen::Index k = 0; k < c.z_m.size(); ++k) {
      palp::RecordingRow r;
      r.t_s = static_cast<double>(k) * 0.025;
      r.i_A = c.i_A[k];
      r.z_mm = c.z_m[k] * 1e3;
      r.rep = c.rep[k] - 1;
      const double delta = c.z_m[k] - s.contact_z_m;
      const double fo = s.object_force(delta);  // noise-free object force
      for (std::size_t ch = 0; ch < 6; ++ch) r.p_Pa[ch] = gain[ch] * fo;
      w.append(r);
    }
    w.finish({});
    return path;
  }

  std::string write_text(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  fs::path dir_;
};

json parse(const ProcessResult& r) {
  try {
    return json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON: " << e.what() << "\nstdout: " << r.out << "\nstderr: " << r.err;
    return json::object();
  }
}

double hertz_depth_at(double F, double Estar) {  // F = 4/3 E* sqrt(R) d^1.5
  return std::pow(3.0 * F / (4.0 * Estar * std::sqrt(kR)), 2.0 / 3.0);
}

TEST_F(AnalyzeDir, IndentationJsonHasExactlyTheSdkSummarysKeys) {
  const auto csv = write("hertz", [](double d) { return an::hertz_force_N(d, 2.0e6, kR); });
  const auto r = palpctl({"analyze", "indentation", "--input", csv, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = parse(r);
  std::set<std::string> want = {"params", "r2_linear", "r2_hertz", "r2_sneddon", "model_by_aic",
                                "k_at_depth_N_per_mm", "k_at_depth_N_per_mm_se",
                                "k_at_depth_N_per_mm_sd", "aic_linear", "aic_hertz", "aic_sneddon",
                                "F0_N", "has_baseline", "n_loading", "n_unloading", "repetitions"};
  for (const char* k : {"contact_point_mm", "k_linear_N_per_mm", "E_star_hertz_Pa", "E_hertz_Pa",
                        "E_star_sneddon_Pa", "E_sneddon_Pa", "delta0_mm", "k_tangent_N_per_mm",
                        "k_fd_N_per_mm", "k_ls_window_N_per_mm", "k_fd_paper_N_per_mm"})
    for (const char* suffix : {"", "_se", "_sd"}) want.insert(std::string(k) + suffix);
  for (const auto& k : want) EXPECT_TRUE(j.contains(k)) << "missing " << k << ":\n" << j.dump(2);
  // nothing else, except the reason beside a null
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    if (want.count(k)) continue;
    const auto base = k.size() > 7 ? k.substr(0, k.size() - 7) : std::string();
    EXPECT_TRUE(k.ends_with("_reason") && want.count(base) && j[base].is_null())
        << "unexpected key " << k;
  }
  for (const char* d : {"1_mm", "2_mm", "3_mm", "4_mm"})
    for (const char* k : {"k_at_depth_N_per_mm", "k_at_depth_N_per_mm_se", "k_at_depth_N_per_mm_sd"})
      EXPECT_TRUE(j[k].contains(d)) << k << " lacks " << d;
  // the model-free descriptors have no fit s.e.: null with the reason
  EXPECT_EQ(j["k_fd_N_per_mm_se_reason"],
            "model-free: no fit standard error (see the _sd over repetitions)");
  const json& p = j["params"];
  EXPECT_EQ(p["kf_N_per_A"], 2.918);
  EXPECT_EQ(p["ic_A"], 0.5);
  EXPECT_EQ(p["kv_N_per_mm"], 0.0439);
  EXPECT_EQ(p["tip_radius_mm"], 2.5);
  EXPECT_EQ(p["poisson"], 0.5);
  EXPECT_EQ(p["bias_current_A"], 1.0);
  EXPECT_NEAR(p["bias_force_N"].get<double>(), 1.459, 1e-12);
  EXPECT_TRUE(p["thickness_mm"].is_null());
  EXPECT_EQ(p["thickness_mm_reason"], "no finite-thickness correction asked for");
  EXPECT_EQ(p["input"], csv);
  EXPECT_EQ(p["kf_table"], false);
}

#ifdef PALP_HAVE_HDF5
TEST_F(AnalyzeDir, AnH5RecordingAnalysesToExactlyTheCsvsNumbers) {
  const auto csv = write("hertz", [](double d) { return an::hertz_force_N(d, 2.0e6, kR); }, 3.0, 3,
                         0.002, {10, 20, 30, 40, 50, 60});
  const std::string h5 = (dir_ / "hertz.h5").string();
  palp::write_recording_hdf5(h5, palp::read_recording(csv));
  for (const char* what : {"indentation", "pressure"}) {
    const auto a = palpctl({"analyze", what, "--input", csv, "--json"});
    const auto b = palpctl({"analyze", what, "--input", h5, "--json"});
    ASSERT_EQ(a.code, 0) << a.err;
    ASSERT_EQ(b.code, 0) << b.err;
    json ja = parse(a), jb = parse(b);
    for (json* j : {&ja, &jb}) {  // the input's name is the one difference
      j->erase("input");
      if (j->contains("params")) (*j)["params"].erase("input");
    }
    EXPECT_EQ(jb, ja) << what;
    EXPECT_TRUE(ja.contains(std::string(what) == "pressure" ? "channels" : "k_fd_N_per_mm")) << ja.dump();
  }
}
#endif

TEST_F(AnalyzeDir, IndentationOnAHertzSolidRecoversEstarContactPointDelta0AndTangents) {
  // E = 1.5 MPa (the paper's solid is 1.59): 1.44 mm deep at 3 A, 9 um steps at 0.25 mm
  const double Estar = 2.0e6;
  const auto csv = write("hertz", [&](double d) { return an::hertz_force_N(d, Estar, kR); });
  const auto r = palpctl({"analyze", "indentation", "--input", csv, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = parse(r);
  ASSERT_EQ(j["model_by_aic"], "hertz");
  EXPECT_NEAR(j["contact_point_mm"].get<double>(), kContactZmm, 0.005);
  EXPECT_NEAR(j["E_star_hertz_Pa"].get<double>(), Estar, 0.01 * Estar);
  EXPECT_NEAR(j["E_hertz_Pa"].get<double>(), 0.75 * j["E_star_hertz_Pa"].get<double>(), 1e-6);
  EXPECT_GT(j["r2_hertz"].get<double>(), 0.999);
  EXPECT_GT(j["E_star_hertz_Pa_se"].get<double>(), 0.0);
  EXPECT_LT(j["E_star_hertz_Pa_se"].get<double>(), 0.01 * Estar);
  EXPECT_GE(j["E_star_hertz_Pa_sd"].get<double>(), 0.0);
  // delta0 where F_o = 1.459 N; tangent 2 E* sqrt(R d)
  const double d0 = hertz_depth_at(1.459, Estar);
  EXPECT_NEAR(j["delta0_mm"].get<double>(), d0 * 1e3, 0.01 * d0 * 1e3);
  const double kt = 2.0 * Estar * std::sqrt(kR * d0) * 1e-3;
  EXPECT_NEAR(j["k_tangent_N_per_mm"].get<double>(), kt, 0.01 * kt);
  const double k1 = 2.0 * Estar * std::sqrt(kR * 1e-3) * 1e-3;
  EXPECT_NEAR(j["k_at_depth_N_per_mm"]["1_mm"].get<double>(), k1, 0.01 * k1);
  EXPECT_TRUE(j["k_at_depth_N_per_mm"]["2_mm"].is_null());
  EXPECT_EQ(j["k_at_depth_N_per_mm"]["2_mm_reason"].get<std::string>().rfind("depth 2 mm, beyond", 0), 0u)
      << j["k_at_depth_N_per_mm"].dump();
  // the delta method through E* (Hertz: delta0 ~ E*^(-2/3), k_t(delta0) ~ E*^(2/3), k_t(1 mm) ~ E*)
  const double rel = j["E_star_hertz_Pa_se"].get<double>() / j["E_star_hertz_Pa"].get<double>();
  {
    EXPECT_NEAR(j["delta0_mm_se"].get<double>(), 2.0 / 3.0 * j["delta0_mm"].get<double>() * rel,
                1e-3 * j["delta0_mm_se"].get<double>());
    EXPECT_NEAR(j["k_tangent_N_per_mm_se"].get<double>(),
                2.0 / 3.0 * j["k_tangent_N_per_mm"].get<double>() * rel,
                1e-3 * j["k_tangent_N_per_mm_se"].get<double>());
    EXPECT_NEAR(j["k_at_depth_N_per_mm_se"]["1_mm"].get<double>(),
                j["k_at_depth_N_per_mm"]["1_mm"].get<double>() * rel, 1e-12);
  }
  const double kfd = (an::hertz_force_N(0.75e-3, Estar, kR) - an::hertz_force_N(0.25e-3, Estar, kR)) / 0.5;
  EXPECT_NEAR(j["k_fd_N_per_mm"].get<double>(), kfd, 0.03 * kfd);
  EXPECT_NEAR(j["k_ls_window_N_per_mm"].get<double>(), kfd, 0.03 * kfd);
  EXPECT_TRUE(j["k_fd_paper_N_per_mm"].is_number());
}

TEST_F(AnalyzeDir, IndentationOnALinearHollowObjectPicksLinearWithThePapersDelta0) {
  const double k = 324.9;  // the paper's hollow object, N/m: delta0 = 1.459 / 324.9 = 4.49 mm
  const auto csv = write("linear", [&](double d) { return d > 0 ? k * d : 0.0; }, 3.0, 5);
  const auto r = palpctl({"analyze", "indentation", "--input", csv, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = parse(r);
  EXPECT_EQ(j["model_by_aic"], "linear");
  EXPECT_NEAR(j["k_linear_N_per_mm"].get<double>(), 0.3249, 0.01 * 0.3249);
  EXPECT_NEAR(j["delta0_mm"].get<double>(), 4.49, 0.01 * 4.49);
  EXPECT_NEAR(j["k_tangent_N_per_mm"].get<double>(), 0.3249, 0.01 * 0.3249);
  EXPECT_NEAR(j["contact_point_mm"].get<double>(), kContactZmm, 0.005);
  for (const char* d : {"1_mm", "2_mm", "3_mm", "4_mm"})
    EXPECT_NEAR(j["k_at_depth_N_per_mm"][d].get<double>(), 0.3249, 0.01 * 0.3249) << d;
  // --bias-force-N 0.9747 N is I_0 = 0.5 + 0.9747 / 2.918 = 0.834 A: delta0 = 3 mm
  const auto b = palpctl({"analyze", "indentation", "--input", csv, "--json", "--bias-force-N", "0.9747"});
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_NEAR(parse(b)["delta0_mm"].get<double>(), 3.0, 0.03);
}

TEST_F(AnalyzeDir, IndentationWithoutJsonPrintsTheSameValuesAsText) {
  const auto csv = write("linear", [](double d) { return d > 0 ? 324.9 * d : 0.0; }, 1.5, 2);
  const auto r = palpctl({"analyze", "indentation", "--input", csv});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("model_by_aic: linear\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("k_linear_N_per_mm: 0.32"), std::string::npos) << r.out;
}

/// One line on stderr, exit 1 (a RecordingError), and with --json the same message as an object.
void expect_input_error(const std::string& csv, const std::string& message) {
  const auto r = palpctl({"analyze", "indentation", "--input", csv});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(r.err, "palpctl: " + message + "\n");
  EXPECT_TRUE(r.out.empty()) << r.out;
  const auto j = palpctl({"--json", "analyze", "indentation", "--input", csv});
  EXPECT_EQ(j.code, 1);
  EXPECT_EQ(parse(j)["error"]["message"], message);
}

TEST_F(AnalyzeDir, BadInputIsOneLineNamingTheFileLineAndProblem) {
  auto f = write_text("missing.csv", "t_s,i_A\n0,0.6\n");
  expect_input_error(f, f + ":1: the header lacks the required column z_mm; a recording needs t_s, "
                            "i_A and z_mm (the header has: t_s, i_A)");
  f = write_text("nan.csv", "t_s,i_A,z_mm\n0,0.6,1\n0.001,abc,1\n");
  expect_input_error(f, f + ":3: column i_A: \"abc\" is not a number");
  f = write_text("time.csv", "t_s,i_A,z_mm\n0,0.6,1\n0.002,0.6,1\n# a comment\n0.001,0.6,1\n");
  expect_input_error(f, f + ":5: t_s decreases from 0.002 to 0.001; it must not decrease");
  std::string text = "t_s,i_A,z_mm\n";
  for (int k = 0; k < 20; ++k)
    text += std::to_string(k) + "," + std::to_string(0.3 + 0.01 * (k < 10 ? k : 19 - k)) + ",1\n";
  f = write_text("air.csv", text);
  expect_input_error(f, f + ":11: no contact: the highest current, i_A = 0.39 A here, stays below "
                            "the contact current I_c = 0.5 A (--ic-A)");
  text = "t_s,i_A,z_mm\n";
  for (int k = 0; k < 40; ++k)  // up to 0.54 A: 5 loading samples at i >= 0.5 A (lines 37-41)
    text += std::to_string(k) + "," + std::to_string(0.15 + 0.01 * (k < 40 ? k : 0)) + "," +
            std::to_string(1.0 + 0.001 * k) + "\n";
  f = write_text("few.csv", text);
  expect_input_error(f, f + ": too few points: 5 loading samples at i_A >= I_c = 0.5 A "
                            "(lines 37-41), the fits need at least 10");
}

TEST_F(AnalyzeDir, AGigabyteWithoutNewlineFailsOnItsFirstLineWithACutEscapedQuoteInTensOfMegabytes) {
  // a data row of 1 GB: an erase-screen escape, then NUL bytes (a sparse file, nothing written)
  const std::string f = write_text("huge.csv", "t_s,i_A,z_mm\n\x1b[2J");
  fs::resize_file(f, 1'000'000'000);
  std::string nuls;
  for (int k = 0; k < 56; ++k) nuls += "\\x00";
  const std::string message = f + ":2: the line is longer than the limit of 65536 bytes (64 KiB) "
                                  "(it starts \"\\x1b[2J" + nuls + "\u2026\")";
  expect_input_error(f, message);
  const auto r = palpctl({"analyze", "indentation", "--input", f}, 20);
  EXPECT_FALSE(r.timed_out);
  EXPECT_LT(r.max_rss_kB, 40'000) << "peak RSS of palpctl analyze, kB";
  const auto sweep = palpctl({"analyze", "sweep", "--input", f}, 20);
  EXPECT_EQ(sweep.code, 1);
  EXPECT_EQ(sweep.err, "palpctl: " + message + "\n");
  EXPECT_LT(sweep.max_rss_kB, 40'000) << "peak RSS of palpctl analyze sweep, kB";
}

TEST(PalpctlAnalyzeBoyle, PapersShallowAndDeepRisesGive15_5And4_86Mm3) {
  auto r = palpctl({"--json", "analyze", "boyle", "--pressure-change-Pa", "573"});
  ASSERT_EQ(r.code, 0) << r.err;
  json j = json::parse(r.out);
  ASSERT_EQ(j["channels"].size(), 1u);
  EXPECT_NEAR(j["channels"][0]["enclosed_volume_mm3"].get<double>(), 2756.80, 0.01);
  EXPECT_NEAR(j["channels"][0]["volume_change_isothermal_mm3"].get<double>(), 15.50, 0.01);
  r = palpctl({"--json", "analyze", "boyle", "--pressure-change-Pa", "167", "--channel-length-mm", "100"});
  ASSERT_EQ(r.code, 0) << r.err;
  j = json::parse(r.out);
  EXPECT_NEAR(j["channels"][0]["enclosed_volume_mm3"].get<double>(), 2953.15, 0.01);
  EXPECT_NEAR(j["channels"][0]["volume_change_isothermal_mm3"].get<double>(), 4.86, 0.01);
  EXPECT_LT(j["channels"][0]["volume_change_adiabatic_mm3"].get<double>(),
            j["channels"][0]["volume_change_isothermal_mm3"].get<double>());
  EXPECT_EQ(j["params"]["ambient_Pa"], 101325.0);
  // text form
  r = palpctl({"analyze", "boyle", "--pressure-change-Pa", "573"});
  EXPECT_EQ(r.out, "dP 573 Pa, V1 2756.81 mm3, dV 15.5023 mm3 isothermal (11.082 mm3 adiabatic)\n");
}

TEST(PalpctlAnalyzeBoyle, NeitherPressureNorInputIsAUsageError) {
  const auto r = palpctl({"analyze", "boyle"});
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("give --pressure-change-Pa or --input"), std::string::npos) << r.err;
  const auto both = palpctl({"analyze", "boyle", "--pressure-change-Pa", "5", "--input", "x.csv"});
  EXPECT_EQ(both.code, 2) << both.err;
  // and for indentation: both bias options, --unbonded without a thickness, a Poisson ratio > 0.5
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"--bias-current-A", "1", "--bias-force-N", "1.4"},
        std::vector<std::string>{"--unbonded"}, std::vector<std::string>{"--poisson", "0.7"},
        std::vector<std::string>{"--kf-N-per-A", "abc"}}) {
    std::vector<std::string> a = {"analyze", "indentation", "--input", "x.csv"};
    a.insert(a.end(), args.begin(), args.end());
    const auto u = palpctl(a);
    EXPECT_EQ(u.code, 2) << args.front() << ": " << u.err;
  }
}

TEST_F(AnalyzeDir, BoyleFromARecordingTakesEachChannelsPressureAtTheMaximumForce) {
  // 1 A above I_c at the top: F_o(top) = 2.918 N - k_v d with d from 0.3249 N/mm + 0.0439 N/mm
  const double k = 324.9;
  const auto csv = write("pressure", [&](double d) { return d > 0 ? k * d : 0.0; }, 1.5, 3, 0.0,
                         {57.0, 0, 0, 0, 0, 195.0});
  const auto r = palpctl({"--json", "analyze", "boyle", "--input", csv});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["channels"].size(), 6u);
  const double d_top = 2.918 / (k + 43.9);
  const double Fo_top = k * std::round(d_top * 1e6) * 1e-6;  // the 1 um encoder
  const json& ch1 = j["channels"][0];
  const json& ch6 = j["channels"][5];
  EXPECT_EQ(ch1["channel"], 1);
  EXPECT_EQ(ch1["channel_length_mm"], 100.0);  // the paper's deep channel
  EXPECT_EQ(ch6["channel_length_mm"], 90.0);   // and shallow one
  EXPECT_NEAR(ch1["pressure_change_Pa"].get<double>(), 57.0 * Fo_top, 0.5);
  EXPECT_NEAR(ch6["pressure_change_Pa"].get<double>(), 195.0 * Fo_top, 0.5);
  const double dV6 = 2756.80 * (195.0 * Fo_top) / (101325.0 + 195.0 * Fo_top);
  EXPECT_NEAR(ch6["volume_change_isothermal_mm3"].get<double>(), dV6, 0.01);
  EXPECT_EQ(ch6["repetitions"], 3);
  EXPECT_NEAR(ch6["pressure_change_Pa_sd"].get<double>(), 0.0, 1e-4);  // every rep alike
}

TEST_F(AnalyzeDir, PressureGivesEachChannelsSlopeAgainstObjectForceWithR2One) {
  const auto csv = write("pressure", [](double d) { return d > 0 ? 746.0 * d : 0.0; }, 3.0, 3, 0.0,
                         {57.0, 0, 0, 0, 0, 195.0});
  const auto r = palpctl({"--json", "analyze", "pressure", "--input", csv});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  ASSERT_EQ(j["channels"].size(), 6u);
  EXPECT_NEAR(j["channels"][0]["slope_Pa_per_N"].get<double>(), 57.0, 0.57);
  EXPECT_NEAR(j["channels"][5]["slope_Pa_per_N"].get<double>(), 195.0, 1.95);
  EXPECT_GT(j["channels"][5]["r2"].get<double>(), 0.999);
  EXPECT_NEAR(j["channels"][5]["hysteresis_ratio"].get<double>(), 0.0, 0.01);
  EXPECT_EQ(j["channels"][5]["hysteresis_per_rep"].size(), 3u);
  // a channel that stays at 0 Pa: slope 0, and no R^2
  EXPECT_EQ(j["channels"][2]["slope_Pa_per_N"], 0.0);
  EXPECT_TRUE(j["channels"][2]["r2"].is_null());
  EXPECT_EQ(j["channels"][2]["r2_reason"], "the pressure does not vary over the samples");
  // the text form: a row per channel
  const auto t = palpctl({"analyze", "pressure", "--input", csv});
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_NE(t.out.find("channel  slope_Pa_per_N          r2     rise_Pa  hysteresis_ratio\n"),
            std::string::npos) << t.out;
  EXPECT_NE(t.out.find("\n      6         194.99"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("\n      3               0           -"), std::string::npos) << t.out;
}

TEST_F(AnalyzeDir, ReanalysingPalpctlIndentsRecordingGivesTheSameValuesAsItsSummary) {
  // palp-sim's solid 1D phantom, the probe 3 mm above it: indent floats the coil onto it and ramps
  SimServer sim({"--phantom", "solid_1d", "--mount-mm", "0", "0", "-3"});
  ASSERT_TRUE(sim.ok()) << sim.banner();
  const std::string out = (dir_ / "solid").string();
  const auto ind = palpctl({"--uri", sim.uri(), "--json", "indent", "--preset", "2d", "--reps", "2",
                            "--out-dir", out});
  ASSERT_EQ(ind.code, 0) << ind.err;
  const json a = parse(ind);
  const auto r = palpctl({"--json", "analyze", "indentation", "--input", out + "/indentation.csv"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json b = parse(r);
  int compared = 0;
  for (auto it = b.begin(); it != b.end(); ++it) {
    if (it.key() == "params") continue;
    ASSERT_TRUE(a.contains(it.key())) << "indent's summary lacks " << it.key();
    EXPECT_EQ(a[it.key()], *it) << it.key();
    ++compared;
  }
  EXPECT_GE(compared, 40);
  // and it is the paper's solid: delta0 and k_o within 10 % of 2.935 mm and 0.746 N/mm
  EXPECT_NEAR(b["delta0_mm"].get<double>(), 2.935, 0.2935);
  EXPECT_NEAR(b["k_tangent_N_per_mm"].get<double>(), 0.746, 0.0746);
}

TEST_F(AnalyzeDir, PressureOnThePadAtRow8Column8RisesLinearlyOnChannels6And1WithTheirRatio) {
  // row 8, column 8 of palp-sim's pad (x 80 mm, y 75 mm): over shallow channel 6 and deep channel 1
  SimServer sim({"--phantom", "pad_2d", "--mount-mm", "80", "75", "-4"});
  ASSERT_TRUE(sim.ok()) << sim.banner();
  const std::string out = (dir_ / "r8c8").string();
  const auto ind = palpctl({"--uri", sim.uri(), "indent", "--preset", "2d", "--reps", "1",
                            "--out-dir", out});
  ASSERT_EQ(ind.code, 0) << ind.err;
  const auto r = palpctl({"--json", "analyze", "pressure", "--input", out + "/indentation.csv"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = parse(r);
  ASSERT_EQ(j["channels"].size(), 6u) << j.dump(2);
  const json& ch1 = j["channels"][0];
  const json& ch6 = j["channels"][5];
  EXPECT_GE(ch6["r2"].get<double>(), 0.98);  // issue 6's acceptance
  EXPECT_GE(ch1["r2"].get<double>(), 0.98);
  const double ratio = ch6["rise_Pa"].get<double>() / ch1["rise_Pa"].get<double>();
  EXPECT_GE(ratio, 2.5);
  EXPECT_LE(ratio, 4.5);
  for (int c : {3, 4}) {  // channels 4 and 5 (shallow, under columns 2 and 5) hardly move
    EXPECT_LT(std::abs(j["channels"][c]["rise_Pa"].get<double>()), 0.05 * ch6["rise_Pa"].get<double>())
        << "channel " << c + 1;
  }
  EXPECT_LT(std::abs(ch6["hysteresis_ratio"].get<double>()), 0.02);
}

}  // namespace
}  // namespace palpctl::test
