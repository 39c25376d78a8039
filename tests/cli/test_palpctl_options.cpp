// SPDX-License-Identifier: Apache-2.0
// palpctl's renamed options (host/cli/README.md, "Renamed options"): the old spelling still
// works and means the new option, --help shows only the new one; and the shell completion.
#include <gtest/gtest.h>

#include <unistd.h>

#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "cli_process.hpp"

namespace palpctl::test {
namespace {

using Path = std::vector<std::string>;

struct Rename {
  Path command;
  std::string now, old, out_of_range;
};

// one row per rename and command family (sweep_options.cpp serves sweep, freeair, analyze sweep)
const std::vector<Rename> kRenames = {
    {{"sweep"}, "--bias-current-A", "--bias-A", "9"},
    {{"freeair"}, "--bias-current-A", "--bias-A", "9"},
    {{"analyze", "sweep"}, "--bias-current-A", "--bias-A", "9"},
    {{"sweep"}, "--start-Hz", "--f-lo-Hz", "-1"},
    {{"analyze", "sweep"}, "--stop-Hz", "--f-hi-Hz", "-1"},
    {{"calibrate", "current-offset"}, "--zero-s", "--seconds", "99"},
    {{"calibrate", "pressure-zero"}, "--zero-s", "--seconds", "99"},
};

std::string words(const Path& p) {
  std::string s;
  for (const auto& w : p) s += (s.empty() ? "" : " ") + w;
  return s;
}

bool help_lists(const std::string& help, const std::string& option) {
  return help.find("  " + option + " ") != std::string::npos ||
         help.find("  " + option + "\n") != std::string::npos;
}

TEST(PalpctlRenamedOptions, HelpShowsTheNewSpellingOnly) {
  for (const auto& r : kRenames) {
    Path args = r.command;
    args.push_back("--help");
    const auto h = palpctl(args);
    ASSERT_EQ(h.code, 0) << words(r.command) << ": " << h.err;
    EXPECT_TRUE(help_lists(h.out, r.now)) << words(r.command) << " does not list " << r.now << ":\n" << h.out;
    EXPECT_EQ(h.out.find(r.old + " "), std::string::npos) << words(r.command) << " lists " << r.old << ":\n" << h.out;
  }
}

TEST(PalpctlRenamedOptions, OldSpellingReachesTheNewOptionsCheckAndNotBothAtOnce) {
  for (const auto& r : kRenames) {
    Path bad = r.command;
    bad.insert(bad.end(), {r.old, r.out_of_range});
    const auto e = palpctl(bad);
    EXPECT_EQ(e.code, 2) << words(bad);
    // the new option's own range check ran on the value, and its error names the new spelling
    EXPECT_EQ(e.err.rfind(r.now + ": ", 0), 0u) << words(bad) << ": " << e.err;

    Path both = r.command;
    both.insert(both.end(), {r.now, "1", r.old, "1"});
    const auto b = palpctl(both);
    EXPECT_EQ(b.code, 2) << words(both);
    EXPECT_NE(b.err.find(r.old + ": is the old spelling of " + r.now + ": give one of them"), std::string::npos)
        << words(both) << ": " << b.err;
  }
}

TEST(PalpctlRenamedOptions, OldSpellingsGiveTheSameRunAsTheNew) {
  SimServer sim({"--phantom", "solid_1d", "--mount-mm", "27", "0", "-25"});
  ASSERT_TRUE(sim.ok());
  // the contact margin is checked with the given bias before anything moves: the same refusal
  const std::string margin =
      "palpctl: identification: bias 0.55 A - peak 0.1 A = 0.45 A is not above I_c 0.5 A: "
      "the tip would leave the specimen; raise bias_A or lower amplitude_A\n";
  for (const char* bias : {"--bias-current-A", "--bias-A"}) {
    const auto r = palpctl({"--uri", sim.uri(), "sweep", bias, "0.55"});
    EXPECT_EQ(r.code, 2) << bias;
    EXPECT_EQ(r.err, margin) << bias;
  }
  // the band reaches the free-air excursion check (its message names it)
  for (const Path& band : {Path{"--start-Hz", "2", "--stop-Hz", "5"}, Path{"--f-lo-Hz", "2", "--f-hi-Hz", "5"}}) {
    Path args = {"--uri", sim.uri(), "freeair", "--amplitude-A", "0.1"};
    args.insert(args.end(), band.begin(), band.end());
    const auto r = palpctl(args);
    EXPECT_EQ(r.code, 2) << words(band);
    EXPECT_NE(r.err.find("excursion") , std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" over 2-5 Hz "), std::string::npos) << words(band) << ": " << r.err;
  }
  const auto z = palpctl({"--uri", sim.uri(), "calibrate", "current-offset", "--seconds", "0.05", "--ram-only"});
  EXPECT_EQ(z.code, 0) << z.err;
}

TEST(PalpctlRenamedOptions, RepsIsLoadUnloadCyclesEverywhereAndZeroIsRefused) {
  const std::vector<std::pair<Path, Path>> commands = {  // the command, and what it needs besides
      {{"map"}, {"--rig", "/dev/null", "--plan", "/dev/null"}},
      {{"indent"}, {"--out-dir", "x"}},
      {{"run", "ramp"}, {}}};
  for (const auto& [cmd, needs] : commands) {
    Path args = cmd;
    args.insert(args.end(), needs.begin(), needs.end());
    args.insert(args.end(), {"--reps", "0"});
    const auto r = palpctl(args);
    EXPECT_EQ(r.code, 2) << words(args);
    EXPECT_EQ(r.err.rfind("--reps: Value 0 not in range 1 to 1000", 0), 0u) << words(args) << ": " << r.err;
    Path help = cmd;
    help.push_back("--help");
    const auto h = palpctl(help);
    const auto at = h.out.find("  --reps ");
    ASSERT_NE(at, std::string::npos) << words(cmd) << ":\n" << h.out;
    const std::string line = h.out.substr(at, h.out.find('\n', at) - at);
    EXPECT_NE(line.find("INT in [1 - 1000]"), std::string::npos) << words(cmd) << ": " << line;
    EXPECT_NE(h.out.find("Load/unload cycles"), std::string::npos) << words(cmd) << ":\n" << h.out;
  }
}

}  // namespace
}  // namespace palpctl::test

namespace palpctl::test {
namespace {

/// What the generated bash completion offers for a command line whose last word is `cur`.
std::string completions(const std::string& words, int cword) {
  const std::string script = std::string("source <(") + PALPCTL_BINARY + " completion bash) && COMP_WORDS=(" +
                             words + ") && COMP_CWORD=" + std::to_string(cword) +
                             "; _palpctl; echo \"${COMPREPLY[*]}\"";
  const auto r = run_process({"/bin/bash", "-c", script});
  EXPECT_EQ(r.code, 0) << words << ": " << r.err;
  return r.out;
}

TEST(PalpctlCompletion, BashCompletesCommandsAndTheirOptionsButNoHiddenAlias) {
  EXPECT_EQ(completions("palpctl ma", 1), "map\n");
  EXPECT_EQ(completions("palpctl run ''", 2), "hold ramp sine sweep\n");
  EXPECT_EQ(completions("palpctl --json calibrate kf --st", 4), "--start-A --stop-A --step-A\n");
  EXPECT_EQ(completions("palpctl sweep --bias", 2), "--bias-current-A\n");  // not --bias-A
  EXPECT_EQ(completions("palpctl freeair --f-", 2), "\n");                 // --f-lo-Hz is hidden
  EXPECT_EQ(completions("palpctl calibrate current-offset --", 3),
            "--help --ram-only --zero-s --uri --timeout-s --json --verbose\n");  // no --seconds
  EXPECT_EQ(completions("palpctl analyze sweep --ti", 3), "--tip-radius-mm --timeout-s\n");
  EXPECT_EQ(completions("palpctl compl", 1), "\n");  // the completion command itself is hidden
}

}  // namespace
}  // namespace palpctl::test

namespace palpctl::test {
namespace {

// -v: the SDK's log lines (palp/log.hpp) on stderr with a UTC timestamp; without it none
TEST(PalpctlVerbose, StreamWithLostFramesPrintsGapLinesOnlyWithVerbose) {
  SimServer sim;
  ASSERT_TRUE(sim.ok());
  const std::regex stamp(R"(palpctl: \d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\.\d{3}Z )");
  const std::regex gap(R"((^|\n)palpctl: \S+ warning: stream gap: \d+ samples missing from index \d+ \(transport\)\n)");
  const std::string out = ::testing::TempDir() + "palpctl-verbose-" + std::to_string(::getpid());
  for (const bool verbose : {true, false}) {
    ASSERT_EQ(sim.control("drop-frames 25"), "ok\n");  // every 25th device frame lost
    Path args = {"--uri", sim.uri(), "stream", "--seconds", "1", "--rate-Hz", "1000", "--overwrite",
                 "--out", out + (verbose ? "-v.csv" : ".csv")};
    if (verbose) args.insert(args.begin(), "-v");
    const auto r = palpctl(args);
    ASSERT_EQ(sim.control("drop-frames 0"), "ok\n");
    ASSERT_EQ(r.code, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex(R"(, ([1-9]\d*) missing\))"))) << r.out;  // frames were lost
    if (verbose) {
      EXPECT_TRUE(std::regex_search(r.err, gap)) << r.err;
      EXPECT_NE(r.err.find(" info: connected to " + sim.uri() + ": device SIM-0001\n"), std::string::npos) << r.err;
      EXPECT_TRUE(std::regex_search(r.err, stamp)) << r.err;
    } else {
      EXPECT_FALSE(std::regex_search(r.err, stamp)) << r.err;  // only the progress lines
      EXPECT_EQ(r.err.find("stream gap"), std::string::npos) << r.err;
    }
    ASSERT_TRUE(sim.wait_no_client());
  }
}

}  // namespace
}  // namespace palpctl::test
