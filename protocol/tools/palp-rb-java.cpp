// palp-rb-java: generates the Java register constants of the robot bridge (RegisterMap.java, for
// the Sunrise bridge in host/robot/sunrise) from the one definition of the map,
// robot_bridge/map.hpp, through the same X-macro expansion the C++ codec uses. The Java file is
// checked in; a ctest test runs `--check` so that it never drifts from map.hpp.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "palp/protocol/robot_bridge/check.hpp"
#include "palp/protocol/robot_bridge/codec.hpp"

namespace {

using namespace palp::proto::rb;

constexpr const char* kUsage = R"(palp-rb-java: the robot bridge's Java register constants

usage: palp-rb-java print            write RegisterMap.java to standard output
       palp-rb-java --check FILE     exit 1 (naming the first difference) if FILE differs
       palp-rb-java --write FILE     rewrite FILE

exit codes: 0 success, 1 check failed, 2 usage error, 3 file error.
)";

constexpr const char* kRegenerate =
    "build/release-with-assertions/protocol/palp-rb-java --write "
    "host/robot/sunrise/core/src/org/palp/bridge/RegisterMap.java";

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

std::string generate() {
  std::ostringstream o;
  o << "// GENERATED from protocol/include/palp/protocol/robot_bridge/map.hpp and check.hpp by\n"
       "// protocol/tools/palp-rb-java.cpp. Do not edit: change map.hpp, then run\n"
       "//   "
    << kRegenerate
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
  if (argc == 2 && std::strcmp(argv[1], "print") == 0) {
    std::fputs(generate().c_str(), stdout);
    return 0;
  }
  if (argc != 3 || (std::strcmp(argv[1], "--check") != 0 && std::strcmp(argv[1], "--write") != 0)) {
    std::fputs(kUsage, argc == 2 && (std::strcmp(argv[1], "--help") == 0 || std::strcmp(argv[1], "-h") == 0) ? stdout : stderr);
    return 2;
  }
  const std::string fresh = generate();
  if (std::strcmp(argv[1], "--check") == 0) {
    std::string file;
    if (!read_file(argv[2], file)) {
      std::fprintf(stderr, "palp-rb-java: cannot read %s\n", argv[2]);
      return 3;
    }
    if (file != fresh) {
      std::fprintf(stderr, "palp-rb-java: %s differs from map.hpp (%s); regenerate with `%s`\n", argv[2],
                   first_difference(file, fresh).c_str(), kRegenerate);
      return 1;
    }
    std::printf("%s matches map.hpp %u.%u\n", argv[2], static_cast<unsigned>(kMapMajor),
                static_cast<unsigned>(kMapMinor));
    return 0;
  }
  const std::string tmp = std::string(argv[2]) + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!(out << fresh) || !out.flush()) {
      std::fprintf(stderr, "palp-rb-java: cannot write %s\n", tmp.c_str());
      return 3;
    }
  }
  if (std::rename(tmp.c_str(), argv[2]) != 0) {
    std::fprintf(stderr, "palp-rb-java: cannot write %s\n", argv[2]);
    return 3;
  }
  std::printf("wrote %s\n", argv[2]);
  return 0;
}
