// SPDX-License-Identifier: Apache-2.0
// The firmware app (firmware/app/include/palp/app/app.hpp) over a fake board that records what
// the app asks of it: boot, the link, the tick, the tick guard, calibration storage, the
// bootloader. The same App<Board> that the QEMU image runs, compiled for the host.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "palp/app/app.hpp"
#include "palp/fw/calibration.hpp"
#include "palp/protocol/frame.hpp"

namespace palp::app {
namespace {

using namespace palp::proto;

class FakeBoard {
 public:
  // --- what the test sets ---
  std::vector<std::uint8_t> storage = std::vector<std::uint8_t>(fw::kCalibrationMaxBlockSize, 0xFF);
  std::vector<std::uint8_t> rx;            // bytes the host sent, not yet read
  std::size_t link_takes = 1 << 20;        // bytes link_write accepts per call
  std::uint32_t missed = 0;                // reported at the next read_inputs
  std::uint32_t stream_rate_Hz = 2000;     // identity().max_stream_rate_Hz (the link in use's)
  // --- what the app did ---
  std::vector<std::uint8_t> tx;            // bytes written to the link
  std::vector<std::uint32_t> tick_rates;   // start_tick calls
  std::vector<bool> tick_started_held;     // ...and whether the tick was held then
  TickHandler handler{};
  bool held = false;
  int holds = 0, releases = 0;
  int calibration_writes = 0;
  bool bootloader = false;
  std::size_t tx_at_bootloader = 0;
  float last_v_coil_V = 0.0f;
  std::uint64_t now = 1'000'000;

  fw::DeviceIdentity identity() const {
    fw::DeviceIdentity id;
    id.board = "fake-board";
    id.serial = "FAKE-1";
    id.max_stream_rate_Hz = stream_rate_Hz;
    return id;
  }
  std::size_t read_calibration(std::uint8_t* bytes, std::size_t size) {
    const std::size_t n = std::min(size, storage.size());
    std::copy_n(storage.begin(), n, bytes);
    return n;
  }
  bool write_calibration(const std::uint8_t* bytes, std::size_t size) {
    storage.assign(bytes, bytes + size);
    ++calibration_writes;
    return true;
  }
  bool start_tick(std::uint32_t rate_Hz, TickHandler h) {
    tick_rates.push_back(rate_Hz);
    tick_started_held.push_back(held);
    handler = h;
    return true;
  }
  void read_inputs(fw::TickInputs& in) {
    in.i_sense_A = 0.0f;
    in.missed_ticks = missed;
    missed = 0;
  }
  void apply_outputs(const fw::TickOutputs& out) { last_v_coil_V = out.v_coil_V; }
  void hold_tick() {
    EXPECT_FALSE(held) << "hold_tick nested";
    held = true;
    ++holds;
  }
  void release_tick() {
    held = false;
    ++releases;
  }
  std::uint64_t now_us() { return now; }
  std::size_t link_read(std::uint8_t* bytes, std::size_t size) {
    const std::size_t n = std::min(size, rx.size());
    std::copy_n(rx.begin(), n, bytes);
    rx.erase(rx.begin(), rx.begin() + static_cast<std::ptrdiff_t>(n));
    return n;
  }
  std::size_t link_write(const std::uint8_t* bytes, std::size_t size) {
    const std::size_t n = std::min(size, link_takes);
    tx.insert(tx.end(), bytes, bytes + n);
    return n;
  }
  void idle(HasWork, void*) {}
  void enter_bootloader() {
    bootloader = true;
    tx_at_bootloader = tx.size();
  }

  void run_ticks(int n) {
    for (int k = 0; k < n; ++k) handler.run(handler.ctx);
  }
  template <class M>
  void host_sends(const M& m, std::uint16_t seq) {
    std::vector<std::uint8_t> w(kMaxWireFrame);
    w.resize(encode_message(m, seq, 0, w.data(), w.size()));
    rx.insert(rx.end(), w.begin(), w.end());
  }
  /// Every message of type M the app wrote to the link.
  template <class M>
  std::vector<M> received() {
    std::vector<M> out;
    FrameReader reader;
    reader.feed_messages(
        tx.data(), tx.size(),
        [&](const FrameHeader&, const auto& m) {
          if constexpr (std::is_same_v<std::decay_t<decltype(m)>, M>) out.push_back(m);
        },
        [](Reject r) { ADD_FAILURE() << "the app wrote a bad frame: " << static_cast<int>(r); });
    return out;
  }
};

static_assert(Board<FakeBoard>);

Hello hello() { return Hello{kProtocolMajor, kProtocolMinor, kSchemaHash, "app test"}; }

TEST(App, ErasedStorageBootsWithTheDefaultCalibrationAndStartsTheTickAt20kHz) {
  FakeBoard board;
  App<FakeBoard> app(board);
  app.boot();
  EXPECT_EQ(app.calibration_status(), fw::CalibrationStatus::blank);
  EXPECT_EQ(app.controller().calibration().current_gain, 1.0f);
  ASSERT_EQ(board.tick_rates, std::vector<std::uint32_t>{20000});
}

TEST(App, AStoredCalibrationBlockIsLoadedAtBoot) {
  FakeBoard board;
  fw::CalibrationData c;
  c.current_gain = 1.25f;
  const fw::CalibrationBlock block = fw::serialize_calibration(c);
  std::copy(block.begin(), block.end(), board.storage.begin());
  App<FakeBoard> app(board);
  app.boot();
  EXPECT_EQ(app.calibration_status(), fw::CalibrationStatus::ok);
  EXPECT_EQ(app.controller().calibration().current_gain, 1.25f);
}

TEST(App, AHelloOnTheLinkIsAnsweredWithTheBoardsDeviceInfoOnTheLink) {
  FakeBoard board;
  App<FakeBoard> app(board);
  app.boot();
  board.host_sends(hello(), 5);
  app.step();
  const auto infos = board.received<DeviceInfo>();
  ASSERT_EQ(infos.size(), 1u);
  EXPECT_STREQ(infos[0].board.bytes.data(), "fake-board");
  EXPECT_EQ(infos[0].max_stream_rate_Hz, 2000u);
}

TEST(App, WhenTheBoardsStreamRateChangesWithItsLinkTheNextDeviceInfoAndStreamLimitFollow) {
  FakeBoard board;
  App<FakeBoard> app(board);
  app.boot();
  board.stream_rate_Hz = 5000;  // e.g. a second, faster link delivered these bytes
  board.host_sends(hello(), 1);
  board.host_sends(GetDeviceInfo{}, 2);
  app.step();
  const auto infos = board.received<DeviceInfo>();
  ASSERT_EQ(infos.size(), 2u);
  EXPECT_EQ(infos[0].max_stream_rate_Hz, 5000u) << "re-read before the bytes are handled";
  EXPECT_EQ(app.controller().max_stream_rate_Hz(), 5000u);
}

TEST(App, ALinkThatTakesFewBytesAtATimeStillGetsEveryByteInOrder) {
  FakeBoard board;
  board.link_takes = 3;
  App<FakeBoard> app(board);
  app.boot();
  board.host_sends(hello(), 1);
  board.host_sends(GetStatus{}, 2);
  for (int k = 0; k < 200; ++k) app.step();
  EXPECT_EQ(board.received<DeviceInfo>().size(), 1u);
  EXPECT_EQ(board.received<Status>().size(), 1u);
}

TEST(App, CommandsHoldTheTickThroughTheBoardAndReleaseIt) {
  FakeBoard board;
  App<FakeBoard> app(board);
  app.boot();
  board.host_sends(hello(), 1);
  board.host_sends(LoadHold{0.3f, 0.0f}, 2);
  app.step();
  EXPECT_GT(board.holds, 0);
  EXPECT_EQ(board.holds, board.releases);
  EXPECT_FALSE(board.held);
}

TEST(App, ARateChangeReprogramsTheTickWhileItIsHeld) {
  FakeBoard board;
  App<FakeBoard> app(board);
  app.boot();
  board.host_sends(hello(), 1);
  app.step();
  SetParams p = fields_as<SetParams>(app.controller().params());
  p.control_rate_Hz = 40000;
  board.host_sends(p, 2);
  app.step();
  ASSERT_EQ(board.tick_rates, (std::vector<std::uint32_t>{20000, 40000}));
  EXPECT_TRUE(board.tick_started_held[1]);
  EXPECT_FALSE(board.held);
}

TEST(App, ACommitWritesTheCommittedBlockToTheBoardsStorage) {
  FakeBoard board;
  App<FakeBoard> app(board);
  app.boot();
  board.host_sends(hello(), 1);
  board.host_sends(CommitCalibration{}, 2);
  app.step();
  ASSERT_EQ(board.calibration_writes, 1);
  const fw::CalibrationBlock& b = app.controller().committed_block();
  EXPECT_EQ(board.storage, std::vector<std::uint8_t>(b.begin(), b.end()));
  app.step();
  EXPECT_EQ(board.calibration_writes, 1);  // once per commit
}

TEST(App, TheBootloaderIsEnteredOnlyOnceItsAckIsOnTheLink) {
  FakeBoard board;
  board.link_takes = 2;
  App<FakeBoard> app(board);
  app.boot();
  board.host_sends(hello(), 1);
  for (int k = 0; k < 100; ++k) app.step();
  board.host_sends(EnterBootloader{0x544F4F42u}, 2);
  app.step();
  EXPECT_FALSE(board.bootloader);  // the Ack is still being written
  for (int k = 0; k < 100 && !board.bootloader; ++k) app.step();
  ASSERT_TRUE(board.bootloader);
  EXPECT_EQ(board.tx_at_bootloader, board.tx.size());
  EXPECT_EQ(board.received<Ack>().size(), 1u);
}

TEST(App, TheTickRunsTheControllerOnTheBoardsInputsAndMissedTicksAreOverruns) {
  FakeBoard board;
  App<FakeBoard> app(board);
  app.boot();
  board.host_sends(hello(), 1);
  board.host_sends(LoadHold{0.3f, 0.0f}, 2);
  board.host_sends(ProgramStart{}, 3);
  app.step();
  board.run_ticks(1);
  EXPECT_GT(board.last_v_coil_V, 0.0f);  // the loop drives the coil toward 0.3 A
  board.missed = 7;
  board.run_ticks(2);
  EXPECT_EQ(app.controller().health().control_overruns, 7u);
  EXPECT_EQ(app.controller().ticks(), 3u);
}

}  // namespace
}  // namespace palp::app
