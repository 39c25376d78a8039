// SPDX-License-Identifier: Apache-2.0
#include "svd_reader.hpp"

#include <cstdio>
#include <cstdlib>

namespace palp::stm32::svd {
namespace {

constexpr std::size_t kMaxInput = 64u << 20;
constexpr std::size_t kMaxElements = 200'000;  // peripherals + registers + fields
constexpr std::uint32_t kMaxIrq = 239;         // ARMv7-M: at most 240 external interrupts

// The element blocks <tag …>…</tag> directly findable in `text`, in order. "<field>" does not
// match "<fields>": the character after the tag name must be '>' or a space.
bool blocks(std::string_view text, std::string_view tag, std::vector<std::string_view>& out,
            std::string& error) {
  const std::string open = "<" + std::string(tag);
  const std::string close = "</" + std::string(tag) + ">";
  std::size_t at = 0;
  while ((at = text.find(open, at)) != std::string_view::npos) {
    const std::size_t after = at + open.size();
    if (after >= text.size() || (text[after] != '>' && text[after] != ' ')) {
      at = after;
      continue;
    }
    const std::size_t end = text.find(close, after);
    if (end == std::string_view::npos) {
      error = "<" + std::string(tag) + "> without " + close;
      return false;
    }
    out.push_back(text.substr(at, end + close.size() - at));
    if (out.size() > kMaxElements) {
      error = "more than " + std::to_string(kMaxElements) + " <" + std::string(tag) + "> elements";
      return false;
    }
    at = end + close.size();
  }
  return true;
}

// The text of the first <tag>…</tag> in `block`, trimmed; nothing if absent.
std::optional<std::string_view> child(std::string_view block, std::string_view tag) {
  const std::string open = "<" + std::string(tag) + ">";
  const std::string close = "</" + std::string(tag) + ">";
  const std::size_t at = block.find(open);
  if (at == std::string_view::npos) {
    return std::nullopt;
  }
  const std::size_t end = block.find(close, at + open.size());
  if (end == std::string_view::npos) {
    return std::nullopt;
  }
  std::string_view text = block.substr(at + open.size(), end - at - open.size());
  while (!text.empty() && (text.front() == ' ' || text.front() == '\n' || text.front() == '\t' ||
                           text.front() == '\r')) {
    text.remove_prefix(1);
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == '\n' || text.back() == '\t' ||
                           text.back() == '\r')) {
    text.remove_suffix(1);
  }
  return text;
}

// A decimal or 0x-hexadecimal SVD number.
std::optional<std::uint32_t> number(std::optional<std::string_view> text) {
  if (!text || text->empty() || text->size() > 20) {
    return std::nullopt;
  }
  const std::string s(*text);
  char* end = nullptr;
  const unsigned long long value = std::strtoull(s.c_str(), &end, 0);
  if (end != s.c_str() + s.size() || value > 0xFFFF'FFFFull) {
    return std::nullopt;
  }
  return static_cast<std::uint32_t>(value);
}

// The header of a block (up to its first child of `stop`), so the block's own <name> is found
// before the names nested deeper.
std::string_view head(std::string_view block, std::string_view stop) {
  const std::size_t at = block.find(stop, 1);
  return at == std::string_view::npos ? block : block.substr(0, at);
}

bool parse_field(std::string_view block, SvdField& field, std::string& error) {
  const auto name = child(block, "name");
  if (!name) {
    error = "a <field> without <name>";
    return false;
  }
  field.name = std::string(*name);
  const auto offset = number(child(block, "bitOffset"));
  const auto width = number(child(block, "bitWidth"));
  const auto lsb = number(child(block, "lsb"));
  const auto msb = number(child(block, "msb"));
  if (offset && width) {
    field.position = *offset;
    field.width = *width;
  } else if (lsb && msb && *msb >= *lsb) {
    field.position = *lsb;
    field.width = *msb - *lsb + 1;
  } else if (const auto range = child(block, "bitRange")) {  // [msb:lsb]
    const std::size_t colon = range->find(':');
    if (range->size() < 5 || range->front() != '[' || range->back() != ']' ||
        colon == std::string_view::npos) {
      error = "field " + field.name + ": bitRange '" + std::string(*range) + "' is not [msb:lsb]";
      return false;
    }
    const auto hi = number(range->substr(1, colon - 1));
    const auto lo = number(range->substr(colon + 1, range->size() - colon - 2));
    if (!hi || !lo || *hi < *lo) {
      error = "field " + field.name + ": bitRange '" + std::string(*range) + "' is not [msb:lsb]";
      return false;
    }
    field.position = *lo;
    field.width = *hi - *lo + 1;
  } else {
    error = "field " + field.name + " has no bitOffset/bitWidth, lsb/msb or bitRange";
    return false;
  }
  if (field.width == 0 || field.position + field.width > 32) {
    error = "field " + field.name + " lies outside 32 bits";
    return false;
  }
  return true;
}

bool parse_register(std::string_view block, SvdRegister& reg, std::string& error) {
  const std::string_view top = head(block, "<fields>");
  const auto name = child(top, "name");
  const auto offset = number(child(top, "addressOffset"));
  if (!name || !offset) {
    error = "a <register> without <name> or a numeric <addressOffset>";
    return false;
  }
  reg.name = std::string(*name);
  reg.offset = *offset;
  std::vector<std::string_view> fields;
  if (!blocks(block, "field", fields, error)) {
    return false;
  }
  for (const std::string_view f : fields) {
    SvdField field;
    if (!parse_field(f, field, error)) {
      error = reg.name + ": " + error;
      return false;
    }
    reg.fields.push_back(std::move(field));
  }
  return true;
}

// Adds the <interrupt> elements of one peripheral block to `device.interrupts` (sorted, once).
bool parse_interrupts(std::string_view block, const std::string& peripheral, Device& device,
                      std::string& error) {
  std::vector<std::string_view> interrupts;
  if (!blocks(block, "interrupt", interrupts, error)) {
    return false;
  }
  for (const std::string_view i : interrupts) {
    const auto name = child(i, "name");
    const auto value = number(child(i, "value"));
    if (!name || name->empty() || !value) {
      error = peripheral + ": an <interrupt> without <name> or a numeric <value>";
      return false;
    }
    if (*value > kMaxIrq) {
      error = peripheral + ": interrupt " + std::string(*name) + " has number " +
              std::to_string(*value) + ", above " + std::to_string(kMaxIrq);
      return false;
    }
    auto at = device.interrupts.begin();
    while (at != device.interrupts.end() && at->number < *value) {
      ++at;
    }
    if (at != device.interrupts.end() && at->number == *value) {
      if (at->name != *name) {
        error = peripheral + ": interrupt " + std::to_string(*value) + " named both " + at->name +
                " and " + std::string(*name);
        return false;
      }
      continue;
    }
    device.interrupts.insert(at, SvdInterrupt{std::string(*name), *value});
  }
  return true;
}

std::string hex(std::uint32_t value, int digits) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%0*X", digits, static_cast<unsigned>(value));
  return text;
}

}  // namespace

const SvdPeripheral* Device::find(std::string_view name) const {
  for (const SvdPeripheral& p : peripherals) {
    if (p.name == name) {
      return &p;
    }
  }
  return nullptr;
}

const std::vector<SvdRegister>* Device::registers_of(const SvdPeripheral& peripheral) const {
  if (!peripheral.registers.empty() || peripheral.derived_from.empty()) {
    return &peripheral.registers;
  }
  const SvdPeripheral* source = find(peripheral.derived_from);
  return source == nullptr ? nullptr : &source->registers;
}

std::optional<Device> parse(std::string_view xml, std::string& error) {
  std::vector<std::string_view> peripherals;
  if (!blocks(xml, "peripheral", peripherals, error)) {
    return std::nullopt;
  }
  if (peripherals.empty()) {
    error = "no <peripheral> elements";
    return std::nullopt;
  }
  Device device;
  for (const std::string_view block : peripherals) {
    SvdPeripheral p;
    const std::string_view tag = block.substr(0, block.find('>'));
    const std::size_t derived = tag.find("derivedFrom=\"");
    if (derived != std::string_view::npos) {
      const std::size_t from = derived + 13;
      const std::size_t to = tag.find('"', from);
      if (to == std::string_view::npos) {
        error = "unterminated derivedFrom attribute";
        return std::nullopt;
      }
      p.derived_from = std::string(tag.substr(from, to - from));
    }
    const std::string_view top = head(block, "<registers>");
    const auto name = child(top, "name");
    const auto base = number(child(top, "baseAddress"));
    if (!name || !base) {
      error = "a <peripheral> without <name> or a numeric <baseAddress>";
      return std::nullopt;
    }
    p.name = std::string(*name);
    p.base = *base;
    if (!parse_interrupts(top, p.name, device, error)) {
      return std::nullopt;
    }
    std::vector<std::string_view> registers;
    if (!blocks(block, "register", registers, error)) {
      return std::nullopt;
    }
    for (const std::string_view r : registers) {
      SvdRegister reg;
      if (!parse_register(r, reg, error)) {
        error = p.name + "." + error;
        return std::nullopt;
      }
      p.registers.push_back(std::move(reg));
    }
    device.peripherals.push_back(std::move(p));
  }
  return device;
}

std::string read_xz(const std::string& path, std::string& error) {
  const std::string command = "xz -dc -- '" + path + "'";
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) {
    error = "cannot run " + command;
    return {};
  }
  std::string out;
  char buffer[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) {
    out.append(buffer, n);
    if (out.size() > kMaxInput) {
      pclose(pipe);
      error = command + ": more than 64 MiB";
      return {};
    }
  }
  const int status = pclose(pipe);
  if (status != 0) {
    error = command + " failed (status " + std::to_string(status) + ")";
    return {};
  }
  return out;
}

std::vector<std::string> check(const Device& device, const Register& reg) {
  std::vector<std::string> mismatches;
  const std::string where = std::string(reg.peripheral) + "." + reg.name;
  const SvdPeripheral* peripheral = device.find(reg.peripheral);
  if (peripheral == nullptr) {
    return {std::string(reg.peripheral) + ": no such peripheral in the SVD"};
  }
  if (peripheral->base != reg.base) {
    mismatches.push_back(std::string(reg.peripheral) + ": base " + hex(reg.base, 8) +
                         " in regs/, " + hex(peripheral->base, 8) + " in the SVD");
  }
  const std::vector<SvdRegister>* registers = device.registers_of(*peripheral);
  if (registers == nullptr) {
    mismatches.push_back(where + ": " + reg.peripheral + " derives from '" +
                         peripheral->derived_from + "', not in the SVD");
    return mismatches;
  }
  const SvdRegister* found = nullptr;
  for (const SvdRegister& r : *registers) {
    if (r.name == reg.name) {
      found = &r;
    }
  }
  if (found == nullptr) {
    mismatches.push_back(where + ": no such register in the SVD");
    return mismatches;
  }
  if (found->offset != reg.offset) {
    mismatches.push_back(where + ": offset " + hex(reg.offset, 2) + " in regs/, " +
                         hex(found->offset, 2) + " in the SVD");
  }
  for (const Field& field : reg.fields) {
    const SvdField* svd_field = nullptr;
    for (const SvdField& f : found->fields) {
      if (f.name == field.name) {
        svd_field = &f;
      }
    }
    const std::string at = where + "." + field.name;
    if (svd_field == nullptr) {
      mismatches.push_back(at + ": no such field in the SVD");
      continue;
    }
    if (svd_field->position != field.position || svd_field->width != field.width) {
      mismatches.push_back(at + ": bit " + std::to_string(field.position) + " width " +
                           std::to_string(field.width) + " in regs/, bit " +
                           std::to_string(svd_field->position) + " width " +
                           std::to_string(svd_field->width) + " in the SVD");
    }
  }
  return mismatches;
}

std::vector<std::string> check_interrupts(const Device& device,
                                          const std::vector<TableEntry>& table) {
  std::vector<std::string> mismatches;
  const auto quoted = [](std::string_view name) { return "'" + std::string(name) + "'"; };
  for (const TableEntry& entry : table) {
    const SvdInterrupt* found = nullptr;
    for (const SvdInterrupt& i : device.interrupts) {
      if (i.number == entry.number) {
        found = &i;
      }
    }
    if (found == nullptr) {
      mismatches.push_back("IRQ " + std::to_string(entry.number) + ": " + quoted(entry.name) +
                           " in the vector table, none in the SVD");
    } else if (found->name != entry.name) {
      mismatches.push_back("IRQ " + std::to_string(entry.number) + ": " + quoted(entry.name) +
                           " in the vector table, " + quoted(found->name) + " in the SVD");
    }
  }
  for (const SvdInterrupt& i : device.interrupts) {
    bool listed = false;
    for (const TableEntry& entry : table) {
      listed = listed || entry.number == i.number;
    }
    if (!listed) {
      mismatches.push_back("IRQ " + std::to_string(i.number) + ": none in the vector table, " +
                           quoted(i.name) + " in the SVD");
    }
  }
  return mismatches;
}

}  // namespace palp::stm32::svd
