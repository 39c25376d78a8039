// SPDX-License-Identifier: Apache-2.0
// palp-rb-constants: generates the robot bridge's register constants for the languages outside the
// C++ build from the one definition of the map, robot_bridge/map.hpp, through the same X-macro
// expansion the C++ codec uses: RegisterMap.java (the Sunrise bridge, host/robot/sunrise) and
// palp_rb_map.py (the commissioning tool beside it). Both files are checked in; ctest runs
// `--check` on each so that they never drift from map.hpp.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "palp/protocol/robot_bridge/check.hpp"
#include "palp/protocol/robot_bridge/codec.hpp"

namespace {

using namespace palp::proto::rb;

constexpr const char* kUsage = R"(palp-rb-constants: the robot bridge's register constants for Java and Python

usage: palp-rb-constants LANG print           write the file to standard output
       palp-rb-constants LANG --check FILE    exit 1 (naming the first difference) if FILE differs
       palp-rb-constants LANG --write FILE    rewrite FILE
LANG:  java (RegisterMap.java) or python (palp_rb_map.py)

exit codes: 0 success, 1 check failed, 2 usage error, 3 file error.
)";

constexpr const char* kJavaFile = "host/robot/sunrise/core/src/org/palp/bridge/RegisterMap.java";
constexpr const char* kPythonFile = "host/robot/sunrise/tools/palp_rb_map.py";

std::string regenerate(const char* lang, const char* file) {
  return std::string("build/release-with-assertions/protocol/palp-rb-constants ") + lang + " --write " + file;
}

std::string upper(const char* s) {
  std::string out;
  for (; *s != 0; ++s) out += static_cast<char>(*s >= 'a' && *s <= 'z' ? *s - 'a' + 'A' : *s);
  return out;
}

std::string escape(const char* s) {  // for a Javadoc comment: no "*/", no stray backslash-u
  std::string out;
  for (; *s != 0; ++s) {
    if (*s == '*' && s[1] == '/') out += "* /";
    else if (*s == '\\') out += "\\\\";
    else out += *s;
  }
  return out;
}

std::string hex4(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04X", v);
  return buf;
}

template <class E>
void put_enum(std::ostringstream& o, const EnumInfo<E>& info, bool bits) {
  o << "\n  /** " << escape(info.doc) << " */\n";
  o << "  public static final class " << info.name << " {\n";
  o << "    private " << info.name << "() {}\n";
  for (const EnumValueInfo& v : info.values) {
    o << "    /** " << v.value << ": " << escape(v.doc) << " */\n";
    o << "    public static final int " << upper(v.name) << " = " << v.value << ";\n";
    if (bits) o << "    public static final int " << upper(v.name) << "_MASK = " << hex4(1u << v.value) << ";\n";
  }
  o << "\n    /** The map's name of a value, or null for a value this map does not know. */\n";
  o << "    public static String name(int value) {\n      switch (value) {\n";
  for (const EnumValueInfo& v : info.values)
    o << "        case " << v.value << ": return \"" << v.name << "\";\n";
  o << "        default: return null;\n      }\n    }\n";
  if (bits) {
    unsigned all = 0;
    for (const EnumValueInfo& v : info.values) all |= 1u << v.value;
    o << "\n    /** Every bit this map knows. */\n";
    o << "    public static final int KNOWN_MASK = " << hex4(all) << ";\n";
  }
  o << "  }\n";
}

template <class B>
void put_block(std::ostringstream& o) {
  const bool writable = std::strcmp(B::kAccess, "RW") == 0;
  o << "\n  /** " << escape(B::kDoc) << " Access " << B::kAccess << ". */\n";
  o << "  public static final class " << B::kName << " {\n";
  o << "    private " << B::kName << "() {}\n";
  o << "    public static final int ADDRESS = " << B::kAddress << ";\n";
  o << "    public static final int LENGTH = " << B::kLength << ";\n";
  o << "    /** True when the host writes this block (access RW). */\n";
  o << "    public static final boolean HOST_WRITES = " << (writable ? "true" : "false") << ";\n";
  unsigned at = B::kAddress;
  for (const RegisterInfo& r : B::kRegisters) {
    o << "    /** " << type_name(r) << (r.unit[0] != 0 ? std::string(" [") + r.unit + "]" : std::string())
      << ", address " << at << (r.count == 2 ? "-" + std::to_string(at + 1) : std::string()) << ": "
      << escape(r.doc) << " */\n";
    o << "    public static final int " << upper(r.name) << " = " << at << ";\n";
    at += r.count;
  }
  o << "\n    /** The register's name at an absolute address of this block (the first of a pair), or null. */\n";
  o << "    public static String registerName(int address) {\n      switch (address) {\n";
  at = B::kAddress;
  for (const RegisterInfo& r : B::kRegisters) {
    o << "        case " << at << ": return \"" << r.name << "\";\n";
    at += r.count;
  }
  o << "        default: return null;\n      }\n    }\n";
  o << "\n    /** 2 for a register that starts an i32/u32 pair, 1 for u16 and enums, 0 elsewhere. */\n";
  o << "    public static int width(int address) {\n      switch (address) {\n";
  at = B::kAddress;
  bool pairs = false;
  for (const RegisterInfo& r : B::kRegisters) {
    if (r.count == 2) o << "        case " << at << ":\n";
    pairs = pairs || r.count == 2;
    at += r.count;
  }
  if (pairs) o << "          return 2;\n";
  o << "        default:\n          return registerName(address) != null ? 1 : 0;\n";
  o << "      }\n    }\n  }\n";
}

std::string generate_java() {
  std::ostringstream o;
  o << "// SPDX-License-Identifier: Apache-2.0\n"  // the licence line every source file carries
       "// GENERATED from protocol/include/palp/protocol/robot_bridge/map.hpp and check.hpp by\n"
       "// protocol/tools/palp-rb-constants.cpp. Do not edit: change map.hpp, then run\n"
       "//   "
    << regenerate("java", kJavaFile)
    << "\n"
       "// The test `sunrise_register_map_generated` fails while this file differs from the map.\n"
       "package org.palp.bridge;\n\n"
       "/** The robot bridge's register map "
    << kMapMajor << "." << kMapMinor
    << " (protocol/robot-bridge.md): absolute 0-based addresses, enumerations, limits. */\n"
       "public final class RegisterMap {\n"
       "  private RegisterMap() {}\n\n"
       "  public static final int MAP_MAJOR = "
    << kMapMajor << ";\n  public static final int MAP_MINOR = " << kMapMinor
    << ";\n  /** ASCII 'PALP'. */\n  public static final int MAGIC = 0x" << std::hex << kMagic << std::dec
    << ";\n  public static final int DEFAULT_PORT = " << kDefaultPort
    << ";\n  public static final int MAX_READ_REGISTERS = " << kMaxReadRegisters
    << ";\n  public static final int MAX_WRITE_REGISTERS = " << kMaxWriteRegisters
    << ";\n  public static final int DEFAULT_WATCHDOG_MS = " << kDefaultWatchdogMs
    << ";\n  public static final int MIN_WATCHDOG_MS = " << kMinWatchdogMs
    << ";\n  public static final int MAX_WATCHDOG_MS = " << kMaxWatchdogMs << ";\n\n"
    << "  // Command parameter limits (robot-bridge.md section 6, check.hpp).\n"
    << "  public static final int MAX_LIN_SPEED_UM_PER_S = " << kMaxLinSpeedUmPerS << ";\n"
    << "  public static final int MAX_APPROACH_SPEED_UM_PER_S = " << kMaxApproachSpeedUmPerS << ";\n"
    << "  public static final int MAX_PTP_SPEED_PERMILLE = " << kMaxPtpSpeedPermille << ";\n"
    << "  public static final int MAX_APPROACH_TRAVEL_UM = " << kMaxApproachTravelUm << ";\n"
    << "  public static final int MAX_FORCE_THRESHOLD_MN = " << kMaxForceThresholdMN << ";\n"
    << "  public static final int MAX_ANGLE_MDEG = " << kMaxAngleMdeg << ";\n"
    << "  public static final int MAX_DIGITAL_INPUT = " << kMaxDigitalInput << ";\n"
    << "  public static final int MAX_TOOL = " << kMaxTool << ";\n";
  for_each_enum([&](auto info) {
    using Info = decltype(info);
    const bool bits = std::strcmp(Info::name, "StatusBit") == 0 || std::strcmp(Info::name, "GuardSource") == 0;
    put_enum(o, info, bits);
  });
  for_each_block([&](auto block) { put_block<decltype(block)>(o); });
  o << "}\n";
  return o.str();
}

// ---- Python -----------------------------------------------------------------------------------
template <class E>
void put_py_enum(std::ostringstream& o, const EnumInfo<E>& info, bool bits) {
  o << "\n\nclass " << info.name << ":\n    \"\"\"" << info.doc << "\"\"\"\n\n";
  for (const EnumValueInfo& v : info.values) {
    o << "    " << upper(v.name) << " = " << v.value << "\n";
    if (bits) o << "    " << upper(v.name) << "_MASK = " << hex4(1u << v.value) << "\n";
  }
  o << "    NAMES = {";
  bool first = true;
  for (const EnumValueInfo& v : info.values) {
    o << (first ? "" : ", ") << v.value << ": \"" << v.name << "\"";
    first = false;
  }
  o << "}\n";
}

template <class B>
void put_py_block(std::ostringstream& o) {
  o << "\n\nclass " << B::kName << ":\n    \"\"\"" << B::kDoc << " Access " << B::kAccess << ".\"\"\"\n\n";
  o << "    ADDRESS = " << B::kAddress << "\n    LENGTH = " << B::kLength << "\n";
  unsigned at = B::kAddress;
  for (const RegisterInfo& r : B::kRegisters) {
    o << "    " << upper(r.name) << " = " << at << "\n";
    at += r.count;
  }
  o << "    # (name, address, type, unit): type u16, i32, u32 or an enumeration's name\n";
  o << "    REGISTERS = [\n";
  at = B::kAddress;
  for (const RegisterInfo& r : B::kRegisters) {
    o << "        (\"" << r.name << "\", " << at << ", \"" << type_name(r) << "\", \"" << r.unit << "\"),\n";
    at += r.count;
  }
  o << "    ]\n";
}

std::string generate_python() {
  std::ostringstream o;
  o << "# SPDX-License-Identifier: Apache-2.0\n"
       "# GENERATED from protocol/include/palp/protocol/robot_bridge/map.hpp and check.hpp by\n"
       "# protocol/tools/palp-rb-constants.cpp. Do not edit: change map.hpp, then run\n"
       "#   "
    << regenerate("python", kPythonFile)
    << "\n"
       "# The test `sunrise_python_map_generated` fails while this file differs from the map.\n"
       "\"\"\"The robot bridge's register map "
    << kMapMajor << "." << kMapMinor
    << " (protocol/robot-bridge.md): absolute 0-based addresses, enumerations, limits.\"\"\"\n\n"
    << "MAP_MAJOR = " << kMapMajor << "\nMAP_MINOR = " << kMapMinor << "\nMAGIC = 0x" << std::hex << kMagic
    << std::dec << "  # ASCII 'PALP'\nDEFAULT_PORT = " << kDefaultPort
    << "\nMAX_READ_REGISTERS = " << kMaxReadRegisters << "\nMAX_WRITE_REGISTERS = " << kMaxWriteRegisters
    << "\nDEFAULT_WATCHDOG_MS = " << kDefaultWatchdogMs << "\nMIN_WATCHDOG_MS = " << kMinWatchdogMs
    << "\nMAX_WATCHDOG_MS = " << kMaxWatchdogMs << "\nMAX_LIN_SPEED_UM_PER_S = " << kMaxLinSpeedUmPerS
    << "\nMAX_APPROACH_SPEED_UM_PER_S = " << kMaxApproachSpeedUmPerS
    << "\nMAX_APPROACH_TRAVEL_UM = " << kMaxApproachTravelUm << "\nMAX_FORCE_THRESHOLD_MN = " << kMaxForceThresholdMN
    << "\n";
  for_each_enum([&](auto info) {
    using Info = decltype(info);
    const bool bits = std::strcmp(Info::name, "StatusBit") == 0 || std::strcmp(Info::name, "GuardSource") == 0;
    put_py_enum(o, info, bits);
  });
  for_each_block([&](auto block) { put_py_block<decltype(block)>(o); });
  return o.str();
}

bool read_file(const char* path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream s;
  s << in.rdbuf();
  out = s.str();
  return true;
}

// The first line where a and b differ, 1-based, with both lines.
std::string first_difference(const std::string& file, const std::string& fresh) {
  std::istringstream a(file), b(fresh);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool ha = static_cast<bool>(std::getline(a, la));
    const bool hb = static_cast<bool>(std::getline(b, lb));
    if (!ha && !hb) return "line endings differ";
    if (!ha || !hb || la != lb)
      return "line " + std::to_string(line) + ": file has \"" + (ha ? la : "<end of file>") +
             "\", the map gives \"" + (hb ? lb : "<end of file>") + "\"";
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool java = argc >= 2 && std::strcmp(argv[1], "java") == 0;
  const bool python = argc >= 2 && std::strcmp(argv[1], "python") == 0;
  if (argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0)) {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (!java && !python) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const std::string fresh = java ? generate_java() : generate_python();
  const char* lang = argv[1];
  if (argc == 3 && std::strcmp(argv[2], "print") == 0) {
    std::fputs(fresh.c_str(), stdout);
    return 0;
  }
  if (argc != 4 || (std::strcmp(argv[2], "--check") != 0 && std::strcmp(argv[2], "--write") != 0)) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const char* path = argv[3];
  if (std::strcmp(argv[2], "--check") == 0) {
    std::string file;
    if (!read_file(path, file)) {
      std::fprintf(stderr, "palp-rb-constants: cannot read %s\n", path);
      return 3;
    }
    if (file != fresh) {
      std::fprintf(stderr, "palp-rb-constants: %s differs from map.hpp (%s); regenerate with `%s`\n", path,
                   first_difference(file, fresh).c_str(), regenerate(lang, java ? kJavaFile : kPythonFile).c_str());
      return 1;
    }
    std::printf("%s matches map.hpp %u.%u\n", path, static_cast<unsigned>(kMapMajor), static_cast<unsigned>(kMapMinor));
    return 0;
  }
  const std::string tmp = std::string(path) + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!(out << fresh) || !out.flush()) {
      std::fprintf(stderr, "palp-rb-constants: cannot write %s\n", tmp.c_str());
      return 3;
    }
  }
  if (std::rename(tmp.c_str(), path) != 0) {
    std::fprintf(stderr, "palp-rb-constants: cannot write %s\n", path);
    return 3;
  }
  std::printf("wrote %s\n", path);
  return 0;
}
