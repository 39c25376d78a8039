// SPDX-License-Identifier: Apache-2.0
// palpctl params get|set|dump|restore: the device's parameters, as the protocol catalogue
// (PALP_FIELDS_Params in protocol/include/palp/protocol/catalogue.hpp) names, types and bounds
// them. No parameter is listed here: every one is reached through Params::visit (its FieldInfo:
// name, unit, range, default, doc), and a value is judged by the protocol's own range check,
// Params::first_out_of_range, the one the device applies, before anything is sent.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "common.hpp"
#include "experiments/result_dir.hpp"
#include "format/text_input.hpp"
#include "palp/error.hpp"
#include "palp/result.hpp"

namespace palpctl {
namespace {

namespace proto = palp::proto;
using palp::Params;
using ojson = nlohmann::ordered_json;

static_assert(Params{}.first_out_of_range() == -1, "the catalogue's Params defaults are in range");

/// `params dump`'s file (host/cli/README.md): its "format" and "version", and the largest one
/// `params restore` reads (a dump is < 1 KiB).
constexpr const char* kDumpFormat = "palp-params";
constexpr int kDumpVersion = 1;
constexpr std::size_t kMaxDumpBytes = 1u << 20;

template <class T>
constexpr bool kAlwaysFalse = false;

// ---- the catalogue's parameters --------------------------------------------------------------

/// Calls f(info, member) for the parameter at `index` of p (catalogue order).
template <class P, class F>
void with_field(P& p, std::size_t index, F&& f) {
  std::size_t k = 0;
  p.visit([&](const proto::FieldInfo& info, auto& member) {
    if (k++ == index) f(info, member);
  });
}

/// A number as its shortest decimal ("4", "0.1", "-2147483648").
std::string number_text(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

/// A JSON value as a person reads it: a name without quotes, a number as its decimal.
std::string plain(const json& v) {
  if (v.is_string()) return v.get<std::string>();
  return v.is_number_float() ? number_text(v.get<double>()) : v.dump();
}

/// What the help, the messages and the checks need of one parameter.
struct Spec {
  std::string name, unit, doc;
  std::string range;                ///< "[0, 4] A" or "one of disabled, active_high, active_low"
  std::string fallback;             ///< the catalogue's default, as text
  bool choice = false;              ///< an enum: named values
  bool whole = false;               ///< an integer type
  double type_lo = 0, type_hi = 0;  ///< what the member's type holds (numbers only)
};

/// The catalogue bound `text` ("4.0", "NOLIM") as a number; NOLIM: the type's own limit.
double bound(const char* text, double type_limit) {
  return std::string(text) == "NOLIM" ? type_limit : std::strtod(text, nullptr);
}

/// The field's value: a number (an f32 at its shortest decimal) or an enum value's name.
json value_json(const Params& p, std::size_t index) {
  json out;
  with_field(p, index, [&](const proto::FieldInfo&, const auto& m) {
    using T = std::remove_cvref_t<decltype(m)>;
    if constexpr (std::is_enum_v<T>)
      out = name_of(m);
    else if constexpr (std::is_same_v<T, float>)
      out = f32(m);
    else if constexpr (std::is_arithmetic_v<T>)
      out = m;
    else
      static_assert(kAlwaysFalse<T>, "palpctl params handles scalar and enum parameters only");
  });
  return out;
}

/// Every parameter, in catalogue order, built once from the catalogue.
const std::vector<Spec>& specs() {
  static const std::vector<Spec> all = [] {
    std::vector<Spec> v;
    const Params defaults{};
    defaults.visit([&](const proto::FieldInfo& info, const auto& m) {
      using T = std::remove_cvref_t<decltype(m)>;
      Spec s{info.name, info.unit, info.doc, {}, plain(value_json(defaults, v.size()))};
      if constexpr (std::is_enum_v<T>) {
        s.choice = true;
        for (const auto& e : proto::EnumInfo<T>::values)
          s.range += (s.range.empty() ? "one of " : ", ") + std::string(e.name);
      } else {
        s.whole = std::is_integral_v<T>;
        s.type_lo = static_cast<double>(std::numeric_limits<T>::lowest());
        s.type_hi = static_cast<double>(std::numeric_limits<T>::max());
        s.range = "[" + number_text(bound(info.lo_text, s.type_lo)) + ", " +
                  number_text(bound(info.hi_text, s.type_hi)) + "]";
        if (!s.unit.empty()) s.range += " " + s.unit;
      }
      v.push_back(std::move(s));
    });
    return v;
  }();
  return all;
}

std::optional<std::size_t> index_of(const std::string& name) {
  for (std::size_t k = 0; k < specs().size(); ++k)
    if (specs()[k].name == name) return k;
  return std::nullopt;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

/// "unknown parameter "x": did you mean current_clamp_A? ...": the one name `name` begins (a
/// name without its unit), else the nearest within 3 edits.
std::string unknown_name(const std::string& name) {
  std::string guess;
  std::size_t prefixed = 0, best = 4;
  for (const Spec& s : specs())
    if (!name.empty() && s.name.rfind(name, 0) == 0 && ++prefixed == 1) guess = s.name;
  if (prefixed != 1) {
    guess.clear();
    for (const Spec& s : specs()) {
      const std::size_t d = edit_distance(name, s.name);
      if (d < best) best = d, guess = s.name;
    }
  }
  return "unknown parameter " + palp::format::quoted(name) +
         (guess.empty() ? "" : ": did you mean " + guess + "?") +
         " (palpctl params --help lists them)";
}

/// Stores v (`shown` as the user wrote it) into parameter `index` of p after checking its type;
/// the problem, or "" when stored. The range is not checked here (checked_store does).
std::string store(Params& p, std::size_t index, const json& v, const std::string& shown) {
  const Spec& s = specs()[index];
  std::string problem;
  with_field(p, index, [&](const proto::FieldInfo&, auto& m) {
    using T = std::remove_cvref_t<decltype(m)>;
    if constexpr (std::is_enum_v<T>) {
      for (const auto& e : proto::EnumInfo<T>::values)
        if (v.is_string() && v.get<std::string>() == e.name)
          return void(m = static_cast<T>(e.value));
      problem = shown + " is not " + s.range;
    } else {
      if (!v.is_number()) return void(problem = shown + " is not a number");
      const double x = v.get<double>();
      if (!std::isfinite(x)) return void(problem = shown + " is not a finite number");
      if (s.whole && x != std::trunc(x))
        return void(problem =
                        shown + " is not a whole number" + (s.unit.empty() ? "" : " of " + s.unit));
      if (x < s.type_lo || x > s.type_hi)
        return void(problem = shown + " is outside the range " + s.range);
      m = static_cast<T>(x);
    }
  });
  return problem;
}

/// store() after the catalogue's range check on a copy (the device's own check, so an f32 bound
/// is judged in f32 as the device judges it); p is unchanged on a problem.
std::string checked_store(Params& p, std::size_t index, const json& v, const std::string& shown) {
  Params trial{};  // the catalogue's defaults: in range (static_assert above)
  std::string problem = store(trial, index, v, shown);
  if (problem.empty() && trial.first_out_of_range() == static_cast<int>(index))
    problem = shown + " is outside the range " + specs()[index].range;
  if (problem.empty()) store(p, index, v, shown);
  return problem;
}

// ---- output ----------------------------------------------------------------------------------

struct Change {
  std::size_t index;
  json old_value, new_value;
};

std::vector<Change> changes(const Params& before, const Params& after) {
  std::vector<Change> out;
  for (std::size_t k = 0; k < specs().size(); ++k) {
    json a = value_json(before, k), b = value_json(after, k);
    if (a != b) out.push_back({k, std::move(a), std::move(b)});
  }
  return out;
}

std::string with_unit(const json& v, const Spec& s) {
  return plain(v) + (s.unit.empty() || s.choice ? "" : " " + s.unit);
}

/// "current_clamp_A: 3.2 -> 2.5 A" lines on stdout.
void print_changes(const std::vector<Change>& list) {
  for (const Change& c : list) {
    const Spec& s = specs()[c.index];
    std::cout << s.name << ": " << plain(c.old_value) << " -> " << with_unit(c.new_value, s)
              << '\n';
  }
  std::cout << std::flush;
}

json changes_json(const std::vector<Change>& list) {
  json j = json::object();
  for (const Change& c : list)
    j[specs()[c.index].name] = {{"old", c.old_value}, {"new", c.new_value}};
  return j;
}

/// Writes p, reads it back, and refuses a device that holds something else (exit 1). A value
/// inside the catalogue's range that the device refuses broke one of the device's own rules
/// (control_rate_Hz 20000 or 40000, travel_min_counts below travel_max_counts): the refusal
/// says so, with the parameter's value and its catalogue doc.
void write_params(palp::Probe& probe, const Params& p) {
  try {
    probe.set_params(p);
  } catch (const palp::DeviceError& e) {
    const std::size_t k = e.field_index();
    if (e.code() != static_cast<std::uint16_t>(proto::ErrorCode::out_of_range) ||
        k >= specs().size())
      throw;
    throw palp::DeviceError(std::string(e.what()) + ": " + specs()[k].name + " = " +
                                with_unit(value_json(p, k), specs()[k]) +
                                " is within the catalogue's range, so a rule of the device's (" +
                                specs()[k].doc + "); nothing was written",
                            e.request(), e.code(), e.field_index(), e.detail());
  }
  const Params held = probe.params();
  for (const Change& c : changes(p, held))
    throw palp::Error("the device holds " + specs()[c.index].name + " = " + plain(c.new_value) +
                      " after palpctl wrote " + plain(c.old_value));
}

/// The parameter list for --help: name, unit, range, default, doc.
std::string parameter_help() {
  std::size_t w = 0;
  for (const Spec& s : specs()) w = std::max(w, s.name.size());
  std::string t =
      "Parameters (the protocol catalogue's Params; each value in the unit its name ends with):\n";
  for (const Spec& s : specs())
    t += "  " + s.name + std::string(w + 2 - s.name.size(), ' ') + s.range + "; default " +
         s.fallback + "\n  " + std::string(w + 2, ' ') + s.doc + "\n";
  return t;
}

// ---- the commands ----------------------------------------------------------------------------

int get(const Context& ctx, const std::vector<std::string>& names) {
  std::vector<std::size_t> chosen;
  for (const std::string& n : names) {
    const auto k = index_of(n);
    if (!k) throw palp::ConfigError(unknown_name(n));
    chosen.push_back(*k);
  }
  if (names.empty())
    for (std::size_t k = 0; k < specs().size(); ++k) chosen.push_back(k);
  auto probe = ctx.connect();
  const Params p = probe.params();
  if (ctx.json) {
    json j = json::object();
    for (std::size_t k : chosen) j[specs()[k].name] = value_json(p, k);
    print_json(j);
    return kOk;
  }
  std::size_t wn = 0, wv = 0;
  for (std::size_t k : chosen) {
    wn = std::max(wn, specs()[k].name.size());
    wv = std::max(wv, with_unit(value_json(p, k), specs()[k]).size());
  }
  for (std::size_t k : chosen) {
    const Spec& s = specs()[k];
    const std::string v = with_unit(value_json(p, k), s);
    std::cout << s.name << std::string(wn + 2 - s.name.size(), ' ') << v
              << std::string(wv + 2 - v.size(), ' ') << (s.choice ? "" : "range ") << s.range
              << '\n';
  }
  return kOk;
}

int set(const Context& ctx, const std::vector<std::string>& assignments) {
  // every assignment checked against the catalogue before the device is asked anything
  Params wanted{};
  std::vector<std::pair<std::size_t, json>> given;
  for (const std::string& a : assignments) {
    const auto eq = a.find('=');
    if (eq == std::string::npos)
      throw palp::ConfigError(palp::format::quoted(a) +
                              ": expected NAME=VALUE (palpctl params set current_clamp_A=2.5)");
    const std::string name = a.substr(0, eq), text = a.substr(eq + 1);
    const auto k = index_of(name);
    if (!k) throw palp::ConfigError(unknown_name(name));
    for (const auto& g : given)
      if (g.first == *k) throw palp::ConfigError(name + " is given twice; nothing was written");
    json v = text;
    double x = 0;
    const auto r = std::from_chars(text.data(), text.data() + text.size(), x);
    if (!specs()[*k].choice && !text.empty() && r.ec == std::errc() &&
        r.ptr == text.data() + text.size())
      v = x;
    const std::string problem = checked_store(wanted, *k, v, palp::format::quoted(text));
    if (!problem.empty()) throw palp::ConfigError(name + ": " + problem + "; nothing was written");
    given.emplace_back(*k, std::move(v));
  }
  auto probe = ctx.connect();
  const Params before = probe.params();
  Params after = before;
  for (const auto& [k, v] : given) store(after, k, v, "");
  const std::vector<Change> diff = changes(before, after);
  if (!diff.empty()) write_params(probe, after);
  if (ctx.json) {
    print_json({{"changed", changes_json(diff)}, {"written", !diff.empty()}});
  } else if (diff.empty()) {
    std::cout << "nothing to change: the device already holds these values\n";
  } else {
    print_changes(diff);
  }
  return kOk;
}

const palp::OwnFileKind& dump_kind() {
  static const palp::OwnFileKind kind{"{\n  \"format\": \"palp-params\"",
                                      "is not a parameter dump palp wrote (not a regular file)",
                                      "was not written by palpctl params dump (it does not begin "
                                      "with {\"format\": \"palp-params\"})"};
  return kind;
}

int dump(const Context& ctx, const std::string& out, bool overwrite) {
  const auto ow = overwrite ? palp::Overwrite::yes : palp::Overwrite::no;
  if (!out.empty()) palp::check_own_file_replaceable(out, ow, dump_kind());  // before the device
  auto probe = ctx.connect();
  const Params p = probe.params();
  const palp::DeviceInfo& info = probe.info();
  ojson doc = {{"format", kDumpFormat},
               {"version", kDumpVersion},
               {"device", ojson(palp::device_json(info))},  // the sidecar's and result.json's block
               {"params", ojson::object()}};
  for (std::size_t k = 0; k < specs().size(); ++k)
    doc["params"][specs()[k].name] = value_json(p, k);
  if (out.empty()) {
    std::cout << doc.dump(2) << '\n';
    return kOk;
  }
  palp::write_own_file(out, ow, dump_kind(), [&] { return doc.dump(2) + "\n"; });
  if (ctx.json)
    print_json({{"file", out}, {"parameters", specs().size()}, {"serial", info.serial}});
  else
    std::cout << "wrote " << out << ": " << specs().size() << " parameters of " << info.serial
              << '\n';
  return kOk;
}

/// A dump file's parameters: index -> value, every one checked against the catalogue.
std::vector<std::pair<std::size_t, json>> read_dump(const std::string& file, std::string& serial) {
  const auto fail = [&](const std::string& problem) -> void {
    throw palp::ConfigError(file + ": " + problem);
  };
  const std::string text = palp::format::read_bounded_or(file, kMaxDumpBytes, fail);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    fail("not JSON: " + palp::format::escaped(e.what(), 240));
  }
  if (!j.is_object()) fail("not a parameter dump: the top level is not a JSON object");
  for (const auto& item : j.items())
    if (item.key() != "format" && item.key() != "version" && item.key() != "device" &&
        item.key() != "params")
      fail(palp::format::quoted(item.key()) +
           ": unknown key (a dump has format, version, device, params)");
  if (!j.contains("format") || j["format"] != kDumpFormat)
    fail(std::string("not a parameter dump: \"format\" is not \"") + kDumpFormat +
         "\" (palpctl params dump writes one)");
  if (!j.contains("version") || !j["version"].is_number_integer() || j["version"] != kDumpVersion)
    fail("\"version\" " +
         (j.contains("version") ? j["version"].dump() : std::string("is missing")) +
         ": this palpctl reads version " + std::to_string(kDumpVersion));
  if (j.contains("device")) {
    if (!j["device"].is_object()) fail("\"device\" is not an object");
    if (j["device"].contains("serial") && j["device"]["serial"].is_string())
      serial = j["device"]["serial"];
  }
  if (!j.contains("params") || !j["params"].is_object())
    fail("\"params\" is missing or not an object");
  std::vector<std::pair<std::size_t, json>> values;
  Params checked{};
  for (const auto& item : j["params"].items()) {
    const auto k = index_of(item.key());
    if (!k) fail("params: " + unknown_name(item.key()));
    const std::string problem =
        checked_store(checked, *k, item.value(), palp::format::escaped(item.value().dump()));
    if (!problem.empty()) fail("params." + item.key() + ": " + problem);
    values.emplace_back(*k, item.value());
  }
  return values;
}

int restore(const Context& ctx, const std::string& file, bool dry_run) {
  std::string serial;
  const auto values = read_dump(file, serial);
  auto probe = ctx.connect();
  if (!serial.empty() && serial != probe.info().serial)
    std::cerr << "palpctl: " << file << " holds the parameters of " << serial << "; this device is "
              << probe.info().serial << '\n';
  const Params before = probe.params();
  Params after = before;
  for (const auto& [k, v] : values) store(after, k, v, "");
  const std::vector<Change> diff = changes(before, after);
  if (!ctx.json) {
    print_changes(diff);  // before anything is written
    if (diff.empty())
      std::cout << "nothing to restore: the device already holds " << file << "'s values\n";
  }
  if (!diff.empty() && !dry_run) write_params(probe, after);
  if (ctx.json) {
    print_json({{"file", file},
                {"changed", changes_json(diff)},
                {"written", !diff.empty() && !dry_run},
                {"dry_run", dry_run}});
  } else if (!diff.empty()) {
    std::cout << (dry_run ? "dry run: nothing was written\n"
                          : "restored " + std::to_string(diff.size()) + " parameter(s) from " +
                                file + "\n");
  }
  return kOk;
}

struct ParamsCli {
  std::vector<std::string> names, assignments;
  std::string out, file;
  bool overwrite = false, dry_run = false;
};

}  // namespace

void add_params_command(CLI::App& app, Context& ctx) {
  auto o = std::make_shared<ParamsCli>();
  auto* cmd = app.add_subcommand(
      "params",
      "Read, change, save and restore the device's parameters (the current clamp, the "
      "I2t model, the travel limits, the heartbeat timeout, ...), named as the protocol "
      "catalogue names them, in the unit each name ends with");
  cmd->require_subcommand(1, 1);
  cmd->footer(parameter_help);

  auto* g = cmd->add_subcommand("get",
                                "Print the parameters' values (all, or the NAMEs) with their "
                                "units and ranges; --json: one object name -> value");
  g->add_option("NAME", o->names, "Parameters to print (default: all)");
  g->footer(parameter_help);
  g->callback([&ctx, o] { ctx.action = [&ctx, o] { return get(ctx, o->names); }; });

  auto* s = cmd->add_subcommand(
      "set",
      "Change parameters: reads the device's, checks every NAME=VALUE against the "
      "catalogue (unknown names, non-numbers, NaN and values outside the range are refused "
      "with exit 2 and nothing written), writes, reads back and prints what changed "
      "(name: old -> new); nothing is written when every value is already in force");
  s->add_option("NAME=VALUE", o->assignments, "e.g. current_clamp_A=2.5 contact_output=active_high")
      ->required();
  s->footer(parameter_help);
  s->callback([&ctx, o] { ctx.action = [&ctx, o] { return set(ctx, o->assignments); }; });

  auto* d = cmd->add_subcommand(
      "dump",
      "Write every parameter as JSON ({\"format\": \"palp-params\", \"version\": 1, "
      "\"device\": {serial, board, firmware_version, ...}, \"params\": {name: value}}) on "
      "stdout, or atomically to --out");
  d->add_option("--out", o->out, "The file (default: stdout)");
  d->add_flag("--overwrite", o->overwrite, "Replace --out if it is a dump palpctl wrote");
  d->callback([&ctx, o] { ctx.action = [&ctx, o] { return dump(ctx, o->out, o->overwrite); }; });

  auto* r = cmd->add_subcommand(
      "restore",
      "Write a dump's parameters back: the file is checked whole first (JSON, its "
      "format and version, unknown keys, types, the catalogue's ranges: exit 2 and "
      "nothing written), then the differences from the device print (name: old -> new) "
      "before anything is written, and only a differing device is written; a dump "
      "may name only some parameters (the others are kept)");
  r->add_option("FILE", o->file, "A file palpctl params dump wrote")->required();
  r->add_flag("--dry-run", o->dry_run, "Print the differences and write nothing");
  r->callback([&ctx, o] { ctx.action = [&ctx, o] { return restore(ctx, o->file, o->dry_run); }; });
}

}  // namespace palpctl
