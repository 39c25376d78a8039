// SPDX-License-Identifier: Apache-2.0
// palp-proto: the protocol's own tool. Prints the version, schema and SPEC tables, writes the
// golden vectors, decodes wire bytes, prints a firmware image's metadata, and runs the protocol
// demo (scripts/demo).
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "palp/protocol/examples.hpp"
#include "palp/protocol/image_file.hpp"
#include "palp/protocol/spec_tables.hpp"
#include "palp/protocol/text.hpp"
#include "palp/protocol/vectors.hpp"
#include "palp/protocol/verdict_text.hpp"

namespace {

using namespace palp::proto;

constexpr const char* kUsage = R"(palp-proto: the palp wire protocol's tool

usage: palp-proto <command> [arguments]

commands:
  version                 protocol version and schema hash of this build
  schema                  the catalogue's canonical text (its CRC-32 is the schema hash)
  spec --check FILE       exit 1 if FILE's generated blocks differ from this build's
  spec --write FILE       rewrite FILE's generated blocks (message/enum tables, stream rates,
                          schema) in place
  vectors DIR             write DIR/messages.txt and DIR/malformed.txt (golden vectors)
  seeds DIR OUT           write the wire bytes of every vector in DIR as one file each in
                          OUT (fuzzing seeds), plus all message vectors as one stream
  decode [HEX ...]        decode wire bytes (hex, from the arguments or standard input) and
                          print every message or reject reason
  image FILE              a firmware image's metadata (board, versions, size, CRC) from its
                          .elf, .bin or .dfu, after checking its size and CRC-32
  demo                    walk through a handshake, programs, a sample batch and bad input
  help, --help, -h        this text

exit codes: 0 success, 1 check failed or input rejected (a corrupt image), 2 usage error,
3 file error.
)";

bool read_file(const std::string& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::ostringstream s;
  s << in.rdbuf();
  out = s.str();
  return true;
}

bool write_file(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) return false;
    out << text;
    if (!out.flush()) return false;
  }
  return std::rename(tmp.c_str(), path.c_str()) == 0;
}

int cmd_spec(int argc, char** argv) {
  if (argc != 4 || (std::strcmp(argv[2], "--check") != 0 && std::strcmp(argv[2], "--write") != 0)) {
    std::fprintf(stderr, "palp-proto spec: expected --check FILE or --write FILE\n");
    return 2;
  }
  std::string spec, error;
  if (!read_file(argv[3], spec)) {
    std::fprintf(stderr, "palp-proto spec: cannot read %s\n", argv[3]);
    return 3;
  }
  const std::string fresh = refresh_spec(spec, error);
  if (!error.empty()) {
    std::fprintf(stderr, "palp-proto spec: %s: %s\n", argv[3], error.c_str());
    return 1;
  }
  if (std::strcmp(argv[2], "--check") == 0) {
    if (fresh != spec) {
      std::fprintf(stderr,
                   "palp-proto spec: %s is out of date with the catalogue; run "
                   "`palp-proto spec --write %s`\n",
                   argv[3], argv[3]);
      return 1;
    }
    std::printf("%s: generated blocks match the catalogue\n", argv[3]);
    return 0;
  }
  if (!write_file(argv[3], fresh)) {
    std::fprintf(stderr, "palp-proto spec: cannot write %s\n", argv[3]);
    return 3;
  }
  std::printf("%s: generated blocks rewritten\n", argv[3]);
  return 0;
}

int cmd_vectors(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "palp-proto vectors: expected a directory\n");
    return 2;
  }
  const std::string dir = argv[2];
  if (!write_file(dir + "/messages.txt", golden_vectors_text()) ||
      !write_file(dir + "/malformed.txt", malformed_vectors_text())) {
    std::fprintf(stderr, "palp-proto vectors: cannot write into %s\n", dir.c_str());
    return 3;
  }
  std::printf("wrote %s/messages.txt and %s/malformed.txt\n", dir.c_str(), dir.c_str());
  return 0;
}

int cmd_seeds(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "palp-proto seeds: expected a vectors directory and an output directory\n");
    return 2;
  }
  const std::string dir = argv[2], out = argv[3];
  std::vector<u8> stream;
  int written = 0;
  for (const char* file : {"messages.txt", "malformed.txt"}) {
    std::string text, error;
    if (!read_file(dir + "/" + file, text)) {
      std::fprintf(stderr, "palp-proto seeds: cannot read %s/%s\n", dir.c_str(), file);
      return 3;
    }
    std::vector<VectorRecord> recs;
    if (!parse_vectors(text, recs, error)) {
      std::fprintf(stderr, "palp-proto seeds: %s/%s: %s\n", dir.c_str(), file, error.c_str());
      return 1;
    }
    for (const VectorRecord& r : recs) {
      const std::string path = out + "/" + std::to_string(written++) + "-" + r.name + ".bin";
      if (!write_file(path, std::string(r.wire.begin(), r.wire.end()))) {
        std::fprintf(stderr, "palp-proto seeds: cannot write %s\n", path.c_str());
        return 3;
      }
      if (std::string(file) == "messages.txt") stream.insert(stream.end(), r.wire.begin(), r.wire.end());
    }
  }
  if (!write_file(out + "/all-messages.bin", std::string(stream.begin(), stream.end()))) {
    std::fprintf(stderr, "palp-proto seeds: cannot write into %s\n", out.c_str());
    return 3;
  }
  std::printf("wrote %d seeds and all-messages.bin into %s\n", written, out.c_str());
  return 0;
}

int decode_and_print(const std::vector<u8>& wire) {
  FrameReader reader;
  int rejected = 0;
  reader.feed(
      wire.data(), wire.size(),
      [&](const Frame& f) {
        std::printf("frame: major=%u minor=%u id=0x%02x flags=0x%02x seq=%u payload_len=%u\n",
                    f.header.major, f.header.minor, f.header.id, f.header.flags, f.header.seq,
                    f.header.payload_len);
        const std::string text =
            describe_payload(f.header.id, {f.payload, f.header.payload_len});
        if (text.rfind("rejected", 0) == 0) ++rejected;
        std::printf("  %s", text.c_str());
      },
      [&](Reject r) {
        ++rejected;
        std::printf("rejected frame: %s\n", reject_name(r));
      });
  if (reader.pending() > 0)
    std::printf("(%zu bytes wait for a 0x00 delimiter)\n", reader.pending());
  return rejected == 0 ? 0 : 1;
}

int cmd_decode(int argc, char** argv) {
  std::string text;
  if (argc > 2) {
    for (int k = 2; k < argc; ++k) text += std::string(argv[k]) + " ";
  } else {
    std::ostringstream s;
    s << std::cin.rdbuf();
    text = s.str();
  }
  std::string error;
  const auto bytes = parse_hex(text, &error);
  if (!bytes) {
    std::fprintf(stderr, "palp-proto decode: %s\n", error.c_str());
    return 2;
  }
  return decode_and_print(*bytes);
}

int cmd_image(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "palp-proto image: expected one file (.elf, .bin or .dfu)\n");
    return 2;
  }
  const char* path = argv[2];
  bool file_error = false;
  const ImageBytes file = read_image_file(path, file_error);
  if (!file.error.empty()) {
    std::fprintf(stderr, "palp-proto image: %s: %s\n", path, file.error.c_str());
    return file_error ? 3 : 1;
  }
  std::printf("file: %s (%s", path, image_container_name(file.container));
  if (file.has_load_address) std::printf(", load address %s", hash_text(file.load_address).c_str());
  std::printf(", %zu bytes of image)\n", file.image.size());
  const ImageParse p = parse_image_metadata(file.image.data(), file.image.size());
  if (p.error != ImageError::too_short && p.error != ImageError::no_magic &&
      p.error != ImageError::unknown_layout)
    std::fputs(format_image_metadata(p.metadata).c_str(), stdout);
  if (!p.ok()) {
    std::fprintf(stderr, "palp-proto image: %s: %s\n", path, describe_image_problem(p).c_str());
    return 1;
  }
  const std::string misplaced = describe_load_address_problem(file, p.metadata);
  if (!misplaced.empty()) {
    std::fprintf(stderr, "palp-proto image: %s: %s\n", path, misplaced.c_str());
    return 1;
  }
  std::printf("check: image_size and image_crc32 match the image\n");
  return 0;
}

template <class M>
std::vector<u8> wire_of(const M& m, u16 seq, u8 flags) {
  std::vector<u8> out(kMaxWireFrame);
  out.resize(encode_message(m, seq, flags, out.data(), out.size()));
  return out;
}

int cmd_demo() {
  std::printf("== palp protocol %u.%u, schema hash %s ==\n\n", kProtocolMajor, kProtocolMinor,
              hash_text(kSchemaHash).c_str());
  std::printf("palp-sim, the simulated probe controller, does not exist yet (issue 3); this demo\n"
              "runs the wire protocol between an SDK side and a device side in one process.\n\n");

  // 1. handshake
  Hello hello;
  hello.host_major = kProtocolMajor;
  hello.host_minor = kProtocolMinor;
  hello.host_schema_hash = kSchemaHash;
  hello.host_software = "palp-proto demo";
  const auto hello_wire = wire_of(hello, 1, 0);
  std::printf("1. The SDK opens a session with Hello (%zu bytes on the wire):\n   %s\n",
              hello_wire.size(), to_hex(hello_wire).c_str());

  FrameReader device_rx;
  DeviceInfo reply;
  device_rx.feed(
      hello_wire.data(), hello_wire.size(),
      [&](const Frame& f) {
        decode_message(f.header.id, f.payload, f.header.payload_len, [&](const auto& m) {
          if constexpr (std::is_same_v<std::decay_t<decltype(m)>, Hello>) {
            const Verdict v = judge({m.host_major, m.host_minor, m.host_schema_hash}, kThisProtocol);
            reply = examples_device_info();
            reply.state = v.compatibility == Compatibility::incompatible ? DeviceState::incompatible
                                                                          : DeviceState::idle;
          }
        });
      },
      [](Reject) {});
  const auto info_wire = wire_of(reply, 1, kFlagResponse);
  std::printf("   The device answers DeviceInfo (%zu bytes):\n", info_wire.size());
  std::printf("%s", format_fields(reply, "     ").c_str());
  std::printf("   Verdict: %s\n\n",
              describe_verdict(judge(kThisProtocol, {reply.protocol_major, reply.protocol_minor,
                                                     reply.schema_hash}),
                               kThisProtocol, reply, {})
                  .c_str());

  // 2. other devices
  std::printf("2. The verdicts for devices that speak other versions:\n");
  struct Other {
    const char* what;
    u8 major, minor;
    u32 hash;
  };
  const Other others[] = {{"an unreleased build of the same version", kProtocolMajor,
                           kProtocolMinor, kSchemaHash ^ 0x5a5a5a5au},
                          {"firmware of the previous major version", static_cast<u8>(kProtocolMajor - 1),
                           9, 0x11111111u},
                          {"newer firmware of the same major version", kProtocolMajor,
                           static_cast<u8>(kProtocolMinor + 1), 0x33333333u},
                          {"the next major version", static_cast<u8>(kProtocolMajor + 1), 0, 0x22222222u}};
  for (const Other& o : others) {
    DeviceInfo d = examples_device_info();
    d.protocol_major = o.major;
    d.protocol_minor = o.minor;
    d.schema_hash = o.hash;
    const ProtocolVersion dv{o.major, o.minor, o.hash};
    std::printf("   - %s:\n     %s\n", o.what,
                describe_verdict(judge(kThisProtocol, dv), kThisProtocol, d,
                                 missing_feature_names(o.minor))
                    .c_str());
  }

  // 3. a program
  const LoadRamp ramp = example_ramp_2d();
  const auto ramp_wire = wire_of(ramp, 2, 0);
  std::printf("\n3. The paper's 2D indentation ramp as one LoadRamp frame (%zu bytes): the device\n"
              "   runs it; the host never sends set-points.\n   %s\n",
              ramp_wire.size(), to_hex(ramp_wire).c_str());
  std::printf("%s", format_fields(ramp, "     ").c_str());
  std::printf("   out-of-range check: first_out_of_range() = %d (all valid)\n",
              ramp.first_out_of_range());

  // 4. samples
  const SampleBatch batch = example_batch(4096, 1'234'567'890'123ull, 3);
  std::printf("\n4. A SampleBatch of %u samples at %.0f Hz, first index %u at device time %llu us:\n",
              batch.sample_count, 1e9 / batch.period_ns, batch.first_index,
              static_cast<unsigned long long>(batch.first_time_us));
  Reader r(batch.data.items.data(), batch.data.size);
  for (u16 k = 0; k < batch.sample_count; ++k) {
    RawSample s;
    unpack_sample(r, s, batch.channels);
    std::printf("   #%u  i_cmd %.4f A  i %.4f A  z %d um  p1 %.2f Pa  p6 %.2f Pa  v %.3f V\n",
                batch.first_index + k, s.i_cmd * kCurrentLsb_A, s.i_meas * kCurrentLsb_A,
                s.encoder, s.pressure[0] * kPressureLsb_Pa, s.pressure[5] * kPressureLsb_Pa,
                s.v_cmd * kVoltageLsb_V);
  }
  std::printf("   All 11 channels at 10 kHz in 40-sample batches: %u wire bytes/s (USB full-speed bulk\n"
              "   carries about 1,200,000; HID about 64,000).\n",
              stream_wire_bytes_per_s(kAllChannels, 10000, 40));

  // 5. bad input
  std::vector<u8> noisy = {0x42, 0x13, 0x00};
  std::vector<u8> corrupt = ramp_wire;
  corrupt[5] ^= 0x20;
  noisy.insert(noisy.end(), corrupt.begin(), corrupt.end());
  noisy.insert(noisy.end(), hello_wire.begin(), hello_wire.end());
  std::printf("\n5. Garbage, a corrupted frame and a good one on one stream:\n");
  decode_and_print(noisy);
  std::printf("\nThe bad bytes were rejected with a reason and counted; the good frame after them\n"
              "was read. Next: palp-sim (issue 3) and the SDK (issue 4).\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  const std::string cmd = argv[1];
  if (cmd == "help" || cmd == "--help" || cmd == "-h") {
    std::fputs(kUsage, stdout);
    return 0;
  }
  if (cmd == "version") {
    std::printf("palp protocol %u.%u, schema hash %s\n", kProtocolMajor, kProtocolMinor,
                hash_text(kSchemaHash).c_str());
    return 0;
  }
  if (cmd == "schema") {
    std::fputs(canonical_schema_text().c_str(), stdout);
    return 0;
  }
  if (cmd == "spec") return cmd_spec(argc, argv);
  if (cmd == "vectors") return cmd_vectors(argc, argv);
  if (cmd == "seeds") return cmd_seeds(argc, argv);
  if (cmd == "decode") return cmd_decode(argc, argv);
  if (cmd == "image") return cmd_image(argc, argv);
  if (cmd == "demo") return cmd_demo();
  std::fprintf(stderr, "palp-proto: unknown command '%s'\n\n%s", cmd.c_str(), kUsage);
  return 2;
}
