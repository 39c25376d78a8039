// SPDX-License-Identifier: Apache-2.0
// palpctl's command line: every command's --help, the unit in every dimensional option's name,
// and the exit codes of usage and connection errors. No device needed except where stated.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"

namespace palpctl::test {
namespace {

using Path = std::vector<std::string>;

std::string joined(const Path& p) {
  std::string s;
  for (const auto& w : p) s += (s.empty() ? "" : " ") + w;
  return s.empty() ? "(top level)" : s;
}

/// The options a --help text lists (the option column, not the descriptions).
std::set<std::string> listed_options(const std::string& help) {
  std::set<std::string> out;
  std::istringstream in(help);
  std::string line;
  const std::regex option_line(R"(^\s+(?:-\w,)?(--[A-Za-z][A-Za-z0-9-]*))");
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, option_line)) out.insert(m[1]);
  return out;
}

bool has_unit_suffix(const std::string& option) {
  if (option == "--seconds") return true;  // the issue's own name: the unit is the whole word
  for (const char* unit : {"-A", "-s", "-Hz", "-mm", "-Pa", "-deg", "-N"}) {
    const std::string u = unit;
    if (option.size() > u.size() && option.compare(option.size() - u.size(), u.size(), u) == 0)
      return true;
  }
  return false;
}

TEST(PalpctlHelp, EveryCommandHasHelpAndEveryDimensionalOptionNamesItsUnit) {
  // options that are counts, names, files or switches: no unit to name
  const std::set<std::string> unitless = {
      "--help",     "--version",        "--uri",           "--json",         "--out",
      "--overwrite", "--reps",          "--no-unload",     "--cycles",       "--settle-cycles",
      "--measure-cycles", "--zero-current", "--zero-pressure", "--ram-only",
      "--rig", "--plan", "--out-dir", "--resume", "--name", "--contrast",
      "--input", "--poisson", "--unbonded", "--preset", "--kf-table", "--format",
      "--plot", "--port", "--bind", "--allow-remote", "--verbose",
      "--adaptive", "--max-points", "--threshold",  // map --adaptive: switch, count, fraction
      "--align", "--trace",   // map --align: a choice, a file
      "--dynamic", "--dynamic-measured-periods"};  // map --dynamic: a switch, a count
  const std::map<Path, std::vector<std::string>> must_list = {
      {{}, {"--uri", "--timeout-s", "--json"}},
      {{"list"}, {}},
      {{"info"}, {}},
      {{"monitor"},
       {"--seconds", "--interval-s", "--rate-Hz", "--plot", "--port", "--bind", "--allow-remote"}},
      {{"stream"}, {"--seconds", "--out", "--rate-Hz", "--zero-pressure", "--zero-current"}},
      {{"run"}, {}},
      {{"run", "hold"}, {"--current-A", "--seconds", "--out", "--rate-Hz"}},
      {{"run", "ramp"},
       {"--start-A", "--stop-A", "--step-A", "--dwell-s", "--reps", "--displacement-limit-mm",
        "--rate-Hz", "--out", "--zero-pressure"}},
      {{"run", "sine"}, {"--offset-A", "--amplitude-A", "--frequency-Hz", "--cycles", "--out"}},
      {{"run", "sweep"},
       {"--offset-A", "--amplitude-A", "--start-Hz", "--stop-Hz", "--step-Hz", "--settle-min-s",
        "--out"}},
      {{"calibrate"}, {}},
      {{"calibrate", "current-offset"}, {"--zero-s", "--ram-only"}},
      {{"calibrate", "pressure-zero"}, {"--zero-s", "--ram-only"}},
      {{"calibrate", "home"}, {"--current-A", "--seconds", "--ram-only"}},
      {{"fault"}, {}},
      {{"fault", "show"}, {}},
      {{"fault", "clear"}, {}},
      {{"trace"}, {"--rig", "--plan", "--out-dir", "--resume"}},
      {{"touch-off"}, {"--rig", "--p1-mm", "--p2-mm", "--p3-mm", "--abc-deg", "--contact-E-star-Pa"}},
      {{"map"}, {"--rig", "--plan", "--out-dir", "--resume", "--preset", "--reps", "--adaptive",
                 "--max-points", "--threshold"}},
      {{"analyze", "map"}, {"--input", "--contrast"}},
      {{"export"}, {"--format", "--input", "--out", "--overwrite"}},
      {{"analyze"}, {}},
      {{"analyze", "indentation"},
       {"--input", "--kf-N-per-A", "--ic-A", "--kv-N-per-mm", "--tip-radius-mm", "--poisson",
        "--bias-current-A", "--bias-force-N", "--thickness-mm", "--unbonded"}},
      {{"analyze", "pressure"}, {"--input", "--kf-N-per-A", "--ic-A", "--kv-N-per-mm"}},
      {{"analyze", "boyle"},
       {"--pressure-change-Pa", "--input", "--channel-diameter-mm", "--channel-length-mm",
        "--tube-bore-mm", "--tube-length-mm", "--ambient-Pa"}},
  };
  for (const auto& [path, wanted] : must_list) {
    Path args = path;
    args.push_back("--help");
    const auto r = palpctl(args);
    ASSERT_EQ(r.code, 0) << joined(path) << " --help: " << r.err;
    EXPECT_NE(r.out.find("Usage: palpctl"), std::string::npos) << joined(path);
    const auto options = listed_options(r.out);
    for (const auto& w : wanted) {
      EXPECT_TRUE(options.count(w)) << joined(path) << " --help does not list " << w << ":\n"
                                    << r.out;
    }
    for (const auto& o : options) {
      EXPECT_TRUE(unitless.count(o) || has_unit_suffix(o))
          << joined(path) << ": option " << o << " has no unit in its name";
    }
    if (!path.empty()) {  // the global options are named on every command's page
      EXPECT_NE(r.out.find("--uri URI, --timeout-s S, --json"), std::string::npos) << joined(path);
    }
  }
}

TEST(PalpctlExitCodes, UsageErrorsExitWith2) {
  for (const Path& args : std::vector<Path>{
           {},
           {"run", "ramp", "--bogus"},
           {"run", "ramp", "--rate-Hz", "abc"},
           {"run", "hold", "--current-A", "9", "--seconds", "1"},
           {"stream"},  // --seconds is required
           {"calibrate"},
           {"fault", "reset"},
           {"--uri", "bogus://x", "info"},
       }) {
    const auto r = palpctl(args);
    EXPECT_EQ(r.code, 2) << joined(args) << "\nstdout: " << r.out << "\nstderr: " << r.err;
    EXPECT_FALSE(r.err.empty()) << joined(args);
  }
}

// issue 17, item 3: NaN passed every range check (every comparison with it is false) and
// crashed analyze indentation (SIGSEGV), emptied a map, reached the device as a hold current.
// No device is given: each must be refused while parsing, before anything runs.
TEST(PalpctlExitCodes, NanAndInfinityAreRefusedNamingTheOptionBeforeAnythingRuns) {
  const std::string csv = "/nonexistent/indentation.csv";  // never read: parsing refuses first
  // touch-off checks that its rig file exists before the numbers: any existing file does
  const std::string rig = (std::filesystem::temp_directory_path() /
                           ("palpctl-nan-rig-" + std::to_string(::getpid()) + ".json")).string();
  std::ofstream(rig) << "{}";
  const struct {
    Path args;
    std::string first_line;
  } cases[] = {
      {{"analyze", "indentation", "--input", csv, "--ic-A", "nan"},
       "--ic-A: 'nan' is not a finite number"},
      {{"analyze", "pressure", "--input", csv, "--kv-N-per-mm", "-inf"},
       "--kv-N-per-mm: '-inf' is not a number"},  // kNonNegative's own message
      {{"analyze", "map", "--input", "/nonexistent", "--ic-A", "NaN"},
       "--ic-A: 'NaN' is not a finite number"},
      {{"run", "hold", "--current-A", "nan", "--seconds", "1"},
       "--current-A: 'nan' is not a finite number"},
      {{"touch-off", "--rig", rig, "--name", "pad", "--p1-mm", "1", "nan", "3",
        "--p2-mm", "1", "2", "3", "--p3-mm", "1", "2", "3"},
       "--p1-mm: 'nan' is not a finite number"},
      {{"--timeout-s", "inf", "info"}, "--timeout-s: 'inf' is not a number"},
  };
  for (const auto& c : cases) {
    const auto r = palpctl(c.args);
    EXPECT_EQ(r.code, 2) << joined(c.args) << "\nstderr: " << r.err;
    EXPECT_EQ(r.err.substr(0, r.err.find('\n')), c.first_line) << joined(c.args);
  }
  std::filesystem::remove(rig);
}

TEST(PalpctlExitCodes, UnreachableUriExitsWith3AndOneLine) {
  const std::string uri = "sim://127.0.0.1:" + std::to_string(unused_port());
  const auto r = palpctl({"--uri", uri, "info"});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.rfind("palpctl: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find(uri), std::string::npos) << "the message names the URI: " << r.err;

  const auto j = palpctl({"--uri", uri, "--json", "info"});
  EXPECT_EQ(j.code, 3);
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["error"]["exit_code"], 3);
  EXPECT_EQ(doc["error"]["kind"], "connection");
}

TEST(PalpctlList, ListsWithoutADeviceAndExits0) {
  const auto r = palpctl({"--json", "list"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::parse(r.out).is_array()) << r.out;
}

TEST(PalpctlVersion, IncompatibleDeviceExitsWith5) {
  SimServer sim;
  ASSERT_TRUE(sim.ok()) << sim.banner();
  ASSERT_EQ(sim.control("announce 9.0").rfind("ok", 0), 0u);
  const auto r = palpctl({"--uri", sim.uri(), "info"});
  EXPECT_EQ(r.code, 5) << r.err;
  EXPECT_NE(r.err.find("9.0"), std::string::npos) << "names the device's version: " << r.err;
}

}  // namespace
}  // namespace palpctl::test
