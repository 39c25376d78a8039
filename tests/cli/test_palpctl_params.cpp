// SPDX-License-Identifier: Apache-2.0
// palpctl params get|set|dump|restore against a real palp-sim: every parameter of the catalogue
// (compared with proto::Params::kFields, not with a list written here), values checked against
// the catalogue's ranges before anything is sent, a dump restored exactly.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cli_process.hpp"
#include "palp/protocol/messages.hpp"

namespace palpctl::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

class PalpctlParams : public SimCliTest {
 protected:
  PalpctlParams() : SimCliTest("palpctl-params") {}
  /// The device's parameters as `params get --json` prints them.
  json params() {
    const auto r = run({"params", "get", "--json"});
    EXPECT_EQ(r.code, 0) << r.err;
    return r.code == 0 ? json::parse(r.out) : json();
  }
  std::string file(const std::string& name, const std::string& text = {}) const {
    const fs::path p = dir_ / name;
    if (!text.empty()) std::ofstream(p) << text;
    return p.string();
  }
};

TEST_F(PalpctlParams, GetPrintsEveryCatalogueParameterAndNoOther) {
  const json j = params();
  ASSERT_TRUE(j.is_object());
  EXPECT_EQ(j.size(), palp::proto::Params::kFields.size());
  for (const auto& f : palp::proto::Params::kFields) EXPECT_TRUE(j.contains(f.name)) << f.name;
  EXPECT_EQ(j["current_clamp_A"], 3.2);  // the catalogue's default as its shortest decimal
  EXPECT_EQ(j["heartbeat_timeout_ms"], 500);
  EXPECT_EQ(j["contact_output"], "disabled");

  const auto r = run({"params", "get"});
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream lines(r.out);
  std::size_t k = 0;
  for (std::string line; std::getline(lines, line); ++k) {
    ASSERT_LT(k, palp::proto::Params::kFields.size()) << line;
    const auto& f = palp::proto::Params::kFields[k];
    EXPECT_EQ(line.rfind(f.name, 0), 0u) << "catalogue order: " << line;
    if (*f.unit != '\0') {
      EXPECT_NE(line.find(std::string(" ") + f.unit + " "), std::string::npos) << line;
    }
  }
  EXPECT_EQ(k, palp::proto::Params::kFields.size());
}

TEST_F(PalpctlParams, GetOneNamePrintsItsValueUnitAndRange) {
  auto r = run({"params", "get", "heartbeat_timeout_ms"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "heartbeat_timeout_ms  500 ms  range [50, 10000] ms\n");
  r = run({"params", "get", "travel_min_counts", "contact_output", "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(json::parse(r.out),
            json::parse(R"({"travel_min_counts": -1000, "contact_output": "disabled"})"));
  r = run({"params", "get", "travel_min_counts"});  // NOLIM: the i32's own range
  EXPECT_EQ(r.out, "travel_min_counts  -1000 counts  range [-2147483648, 2147483647] counts\n");
}

TEST_F(PalpctlParams, SetPrintsWhatChangedAndGetShowsTheNewValues) {
  const auto r = run({"params", "set", "current_clamp_A=2.5", "heartbeat_timeout_ms=800",
                      "contact_output=active_high", "i2t_limit_A2s=0.1"});
  ASSERT_EQ(r.code, 0) << r.err;
  // i2t_limit_A2s's lower bound 0.1 is judged in f32, as the device judges it
  EXPECT_EQ(r.out,
            "current_clamp_A: 3.2 -> 2.5 A\n"
            "i2t_limit_A2s: 60 -> 0.1 A^2*s\n"
            "heartbeat_timeout_ms: 500 -> 800 ms\n"
            "contact_output: disabled -> active_high\n");
  const json j = params();
  EXPECT_EQ(j["current_clamp_A"], 2.5);
  EXPECT_EQ(j["heartbeat_timeout_ms"], 800);
  EXPECT_EQ(j["contact_output"], "active_high");
  EXPECT_EQ(j["i2t_limit_A2s"], 0.1);
  EXPECT_EQ(j["supply_V"], 24) << "the others kept";

  const auto again = run({"params", "set", "current_clamp_A=2.5", "--json"});
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(json::parse(again.out), json::parse(R"({"changed": {}, "written": false})"));
}

TEST_F(PalpctlParams, SetRefusesBadValuesWithTheCatalogueRangeAndWritesNothing) {
  const json before = params();
  const std::pair<std::vector<std::string>, std::string> cases[] = {
      {{"current_clamp_A=5"},
       "current_clamp_A: \"5\" is outside the range [0, 4] A; nothing was written"},
      {{"current_clamp_A=2", "i2t_tau_s=0.5"},
       "i2t_tau_s: \"0.5\" is outside the range [1, 10000] s; nothing was written"},
      {{"heartbeat_timeout_ms=-1"},
       "heartbeat_timeout_ms: \"-1\" is outside the range [50, 10000] ms; nothing was written"},
      {{"current_clamp_A=nan"},
       "current_clamp_A: \"nan\" is not a finite number; nothing was written"},
      {{"supply_V=inf"}, "supply_V: \"inf\" is not a finite number; nothing was written"},
      {{"supply_V=12V"}, "supply_V: \"12V\" is not a number; nothing was written"},
      {{"heartbeat_timeout_ms=750.5"},
       "heartbeat_timeout_ms: \"750.5\" is not a whole number of ms; nothing was written"},
      {{"contact_output=high"},
       "contact_output: \"high\" is not one of disabled, active_high, active_low; nothing was "
       "written"},
      {{"current_clamp=2"},
       "unknown parameter \"current_clamp\": did you mean current_clamp_A? (palpctl params --help "
       "lists them)"},
      {{"hartbeat_timeout_ms=600"},
       "unknown parameter \"hartbeat_timeout_ms\": did you mean heartbeat_timeout_ms? (palpctl "
       "params --help lists them)"},
      {{"current_clamp_A"},
       "\"current_clamp_A\": expected NAME=VALUE (palpctl params set current_clamp_A=2.5)"},
      {{"supply_V=12", "supply_V=13"}, "supply_V is given twice; nothing was written"},
  };
  for (const auto& [args, message] : cases) {
    std::vector<std::string> a = {"params", "set"};
    a.insert(a.end(), args.begin(), args.end());
    const auto r = run(a);
    EXPECT_EQ(r.code, 2) << args[0];
    EXPECT_EQ(r.err, "palpctl: " + message + "\n");
    EXPECT_EQ(r.out, "");
  }
  EXPECT_EQ(params(), before) << "the device is unchanged";
}

TEST_F(PalpctlParams, ARuleOnlyTheDeviceKnowsIsItsRefusalExit1) {
  // control_rate_Hz is in the catalogue's [20000, 40000]; the device takes 20000 or 40000 only
  const json before = params();
  const auto r = run({"params", "set", "control_rate_Hz=30000"});
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("out_of_range"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(": control_rate_Hz = 30000 Hz is within the catalogue's range, so a rule of "
                       "the device's (Control tick rate; a device accepts 20000 and 40000"),
            std::string::npos)
      << r.err;
  const auto travel = run({"params", "set", "travel_min_counts=36000"});  // above travel_max
  EXPECT_EQ(travel.code, 1) << travel.err;
  EXPECT_NE(travel.err.find(": travel_min_counts = 36000 counts is within the catalogue's range"),
            std::string::npos)
      << travel.err;
  EXPECT_EQ(params(), before);
}

TEST_F(PalpctlParams, DumpChangeRestoreRestoresExactlyAfterPrintingTheDiff) {
  const std::string dump = file("device.json");
  auto r = run({"params", "dump", "--out", dump});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "wrote " + dump + ": " + std::to_string(palp::proto::Params::kFields.size()) +
                       " parameters of SIM-0001\n");
  std::stringstream text;
  text << std::ifstream(dump).rdbuf();
  EXPECT_EQ(text.str().rfind("{\n  \"format\": \"palp-params\",\n  \"version\": 1,", 0), 0u)
      << text.str();
  std::size_t at = text.str().find("\n  \"params\": {");
  for (const auto& f : palp::proto::Params::kFields) {  // in catalogue order
    const std::size_t next = text.str().find(std::string("\"") + f.name + "\":", at);
    ASSERT_NE(next, std::string::npos) << f.name;
    EXPECT_GT(next, at) << f.name;
    at = next;
  }
  const json saved = json::parse(text.str());
  EXPECT_EQ(saved["format"], "palp-params");
  EXPECT_EQ(saved["version"], 1);
  EXPECT_EQ(saved["device"]["serial"], "SIM-0001");
  EXPECT_EQ(saved["device"]["board"], "palp-sim");
  const json original = params();
  EXPECT_EQ(saved["params"], original);
  EXPECT_EQ(run({"params", "dump", "--out", dump}).code, 2) << "an existing file needs --overwrite";
  EXPECT_EQ(run({"params", "dump", "--out", dump, "--overwrite"}).code, 0);

  ASSERT_EQ(run({"params", "set", "current_clamp_A=1.5", "travel_max_counts=20000",
                 "contact_output=active_low"})
                .code,
            0);
  const json changed = params();

  r = run({"params", "restore", dump, "--dry-run"});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string diff =
      "current_clamp_A: 1.5 -> 3.2 A\n"
      "travel_max_counts: 20000 -> 35000 counts\n"
      "contact_output: active_low -> disabled\n";
  EXPECT_EQ(r.out, diff + "dry run: nothing was written\n");
  EXPECT_EQ(params(), changed);

  r = run({"params", "restore", dump});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, diff + "restored 3 parameter(s) from " + dump + "\n");
  EXPECT_EQ(params(), original);

  r = run({"params", "restore", dump, "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = json::parse(r.out);
  EXPECT_EQ(j["changed"], json::object());
  EXPECT_EQ(j["written"], false);

  // another device's dump, naming one parameter: said on stderr, the others kept
  std::ofstream(dump)
      << R"({"format": "palp-params", "version": 1, "device": {"serial": "SIM-0002"},
                             "params": {"supply_V": 12}})";
  r = run({"params", "restore", dump});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err,
            "palpctl: " + dump + " holds the parameters of SIM-0002; this device is SIM-0001\n");
  EXPECT_EQ(r.out, "supply_V: 24 -> 12 V\nrestored 1 parameter(s) from " + dump + "\n");
  json expected = original;
  expected["supply_V"] = 12;
  EXPECT_EQ(params(), expected);
}

TEST_F(PalpctlParams, RestoreRefusesAMalformedFileBeforeTouchingTheDevice) {
  ASSERT_EQ(run({"params", "set", "current_clamp_A=1"}).code, 0);
  const json before = params();
  const std::string head = R"({"format": "palp-params", "version": 1, )";
  const std::pair<std::string, std::string> cases[] = {
      {head + R"("params": {"current_clamp_A": 2,})", "not JSON: "},
      {R"([1, 2])", "not a parameter dump: the top level is not a JSON object"},
      {R"({"format": "palp-rig", "version": 1, "params": {}})",
       "not a parameter dump: \"format\" is not \"palp-params\""},
      {R"({"format": "palp-params", "version": 2, "params": {}})",
       "\"version\" 2: this palpctl reads version 1"},
      {head + R"("params": {}, "comment": "x"})", "\"comment\": unknown key"},
      {head + R"("params": {"current_clamp_A": 2, "clamp_A": 2}})",
       "params: unknown parameter \"clamp_A\""},
      {head + R"("params": {"current_clamp_A": 4.5}})",
       "params.current_clamp_A: 4.5 is outside the range [0, 4] A"},
      {head + R"("params": {"current_clamp_A": "2"}})",
       "params.current_clamp_A: \"2\" is not a number"},
      {head + R"("params": {"heartbeat_timeout_ms": true}})",
       "params.heartbeat_timeout_ms: true is not a number"},
      {head + R"("params": {"contact_output": 1}})",
       "params.contact_output: 1 is not one of disabled, active_high, active_low"},
      {head + R"("params": [3.2]})", "\"params\" is missing or not an object"},
  };
  int n = 0;
  for (const auto& [text, message] : cases) {
    const std::string f = file("bad" + std::to_string(n++) + ".json", text);
    const auto r = run({"params", "restore", f});
    EXPECT_EQ(r.code, 2) << text;
    EXPECT_EQ(r.err.rfind("palpctl: " + f + ": " + message, 0), 0u) << r.err;
    EXPECT_EQ(r.out, "") << text;
  }
  const auto big = run({"params", "restore", file("big.json", std::string((1u << 20) + 1, ' '))});
  EXPECT_EQ(big.code, 2);
  EXPECT_EQ(big.err, "palpctl: " + file("big.json") +
                         ": the file has 1048577 bytes, more than the limit of 1048576 bytes (1 MiB)\n");
  const auto missing = run({"params", "restore", file("absent.json")});
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("cannot open"), std::string::npos) << missing.err;
  EXPECT_EQ(params(), before) << "the device is unchanged";
}

TEST_F(PalpctlParams, HelpListsEveryCatalogueParameterWithItsRange) {
  const auto r = palpctl({"params", "get", "--help"});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const auto& f : palp::proto::Params::kFields)
    EXPECT_NE(r.out.find(std::string("  ") + f.name + " "), std::string::npos) << f.name;
  EXPECT_NE(r.out.find("  current_clamp_A         [0, 4] A; default 3.2\n"), std::string::npos)
      << r.out;
}

}  // namespace
}  // namespace palpctl::test
