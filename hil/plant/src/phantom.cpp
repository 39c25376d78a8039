// SPDX-License-Identifier: Apache-2.0
// Phantom base class, and loading phantom files (kind dispatch, file reading).
#include "palp/plant/phantom.hpp"

#include <fstream>
#include <span>
#include <sstream>

#include "key_value_file.hpp"
#include "phantom_read.hpp"
#include "shipped_phantoms.hpp"

namespace palp::plant {
namespace {
std::span<const detail::ShippedPhantom> shipped() {
  return {detail::kShippedPhantoms, detail::kShippedPhantomCount};
}
}  // namespace

ProbeSite Phantom::position(int k) const {
  for (const ProbeSite& s : sites()) {
    if (s.row == 0 && s.column == k) return s;
  }
  throw std::out_of_range(name_ + ": no position " + std::to_string(k));
}

ProbeSite Phantom::grid_point(int row, int column) const {
  for (const ProbeSite& s : sites()) {
    if (s.row == row && s.column == column && row > 0) return s;
  }
  throw std::out_of_range(name_ + ": no grid point row " + std::to_string(row) + ", column " +
                          std::to_string(column));
}

std::array<double, kPressureChannels> Phantom::channel_pressures_Pa(const ContactParams&,
                                                                    double) const {
  return {};
}

std::shared_ptr<const Phantom> parse_phantom(std::string_view text, std::string_view source_name) {
  const auto file = detail::KeyValueFile::parse(text, std::string(source_name));
  file.require({"format_version", "kind"}, "every phantom");
  file.integer("format_version", 1, 1);
  const std::string kind = file.word("kind", {"line_1d", "pad_2d"});
  if (kind == "line_1d") return detail::read_line_phantom(file);
  return detail::read_pad_phantom(file);
}

std::shared_ptr<const Phantom> load_phantom(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw PhantomError(file.string() + ":0: cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  return parse_phantom(text.str(), file.filename().string());
}

std::vector<std::string_view> shipped_phantom_names() {
  std::vector<std::string_view> names;
  for (const auto& p : shipped()) names.push_back(p.name);
  return names;
}

std::string_view shipped_phantom_text(std::string_view name) {
  for (const auto& p : shipped())
    if (p.name == name) return p.text;
  std::string known;
  for (const auto& p : shipped()) known += (known.empty() ? "" : ", ") + std::string(p.name);
  throw PhantomError("no shipped phantom \"" + std::string(name) + "\" (the shipped ones: " +
                     known + ")");
}

std::shared_ptr<const Phantom> load_shipped_phantom(std::string_view name) {
  return parse_phantom(shipped_phantom_text(name), std::string(name) + ".phantom");
}

}  // namespace palp::plant
