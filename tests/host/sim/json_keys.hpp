// SPDX-License-Identifier: Apache-2.0
// The key structure of a JSON document, for tests that compare two documents' keys but not their
// values (a sidecar written by the SDK against palpctl's, or against the doc's example): every
// object key as a path in file order ("device", "device.serial", ...), the elements of an array
// as "key[]" with the keys of all its elements merged in order of first appearance.
#pragma once

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace palp::test {

inline void add_key_paths(const nlohmann::ordered_json& j, const std::string& at,
                          std::vector<std::string>& out) {
  auto add = [&out](const std::string& p) {
    if (std::find(out.begin(), out.end(), p) == out.end()) out.push_back(p);
  };
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string p = at.empty() ? it.key() : at + "." + it.key();
      add(p);
      add_key_paths(*it, p, out);
    }
  } else if (j.is_array()) {
    for (const auto& e : j) add_key_paths(e, at + "[]", out);
  }
}

/// The key paths of a document, in order (see the top of this file).
inline std::vector<std::string> key_paths(const nlohmann::ordered_json& j) {
  std::vector<std::string> out;
  add_key_paths(j, "", out);
  return out;
}

/// A file parsed keeping its key order.
inline nlohmann::ordered_json read_ordered_json(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return nlohmann::ordered_json::parse(text.str());
}

/// The first line of a file.
inline std::string first_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

}  // namespace palp::test
