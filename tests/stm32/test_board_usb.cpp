// SPDX-License-Identifier: Apache-2.0
// The STM32G474 board's USB link (stm_board.hpp: Device<UsbFsdev<Io>>, the USB_LP interrupt, the
// UID serial) on the FSDEV register model (fsdev_model.hpp), with tests/usb's host playing the
// bus: the board enumerates, serves identity().serial as string 3, carries bulk bytes both ways,
// and the link that last delivered bytes is the one the app's bytes go to, with its stream rate.
#include <cstdint>
#include <string>
#include <vector>

#include "board_fixture.hpp"
#include "host.hpp"
#include "palp/protocol/usb.hpp"
#include "palp/usb/descriptors.hpp"

namespace palp::stm32::board_test {
namespace {

namespace dev = ::palp::usb;
using dev::test::Handshake;
using dev::test::Outcome;

/// tests/usb's Host over the board's FSDEV model (the host's side of fsdev_model.hpp).
class BoardUsbBus {
 public:
  explicit BoardUsbBus(test::FsdevModel& model) : model_(model) {}
  void bus_reset() { model_.bus_reset(); }
  Handshake setup(std::uint8_t address, const dev::SetupPacket& s) {
    model_.set_host_address(address);
    const std::uint8_t bytes[8] = {s.bmRequestType,
                                   s.bRequest,
                                   static_cast<std::uint8_t>(s.wValue),
                                   static_cast<std::uint8_t>(s.wValue >> 8),
                                   static_cast<std::uint8_t>(s.wIndex),
                                   static_cast<std::uint8_t>(s.wIndex >> 8),
                                   static_cast<std::uint8_t>(s.wLength),
                                   static_cast<std::uint8_t>(s.wLength >> 8)};
    return handshake(model_.setup(0, bytes));
  }
  dev::test::InAnswer in(std::uint8_t address, std::uint8_t number) {
    model_.set_host_address(address);
    test::InPacket p = model_.in(number);
    return {handshake(p.handshake), std::move(p.bytes)};
  }
  Handshake out(std::uint8_t address, std::uint8_t number, const std::uint8_t* bytes,
                std::size_t size) {
    model_.set_host_address(address);
    return handshake(model_.out(number, std::span<const std::uint8_t>(bytes, size)));
  }

 private:
  static Handshake handshake(test::Handshake h) {
    switch (h) {
      case test::Handshake::ack: return Handshake::ack;
      case test::Handshake::nak: return Handshake::nak;
      case test::Handshake::stall: return Handshake::stall;
      default: return Handshake::no_answer;
    }
  }
  test::FsdevModel& model_;
};

class StmBoardUsb : public ::testing::Test {
 protected:
  StmBoardUsb() {
    hw.poke(Board::kUidBase, 0x0012'ABCDu);  // facts §1.1: the UID, three words
    hw.poke(Board::kUidBase + 4, 0x3433'3231u);
    hw.poke(Board::kUidBase + 8, 0xFEDC'BA98u);
    hw.poke(lpuart1::Isr::reg, lpuart1::Isr::TXE.mask());  // TX FIFO has room
    board.init();
  }

  BoardPlatform platform() { return test_platform(pressure); }

  /// Reset, address 5, configuration 1: what a host does before it opens the vendor interface.
  void enumerate() {
    host.reset();
    ASSERT_EQ(host.control_out(dev::test::set_address(5)).outcome, Outcome::ok);
    host.address = 5;
    ASSERT_EQ(host.control_out(dev::test::set_configuration(1)).outcome, Outcome::ok);
    hw.usb_model.reset_host_toggles(1);  // as the host does after SET_CONFIGURATION
  }
  /// One bulk OUT packet from the host, then the USB interrupt.
  void host_sends(const std::vector<std::uint8_t>& bytes) {
    hw.usb_model.set_host_address(host.address);
    ASSERT_EQ(hw.usb_model.out(1, bytes), test::Handshake::ack);
    board.on_usb_irq();
  }
  /// Bulk IN packets until a NAK (the USB interrupt after each), concatenated.
  std::vector<std::uint8_t> host_receives(std::vector<std::size_t>* packets = nullptr) {
    std::vector<std::uint8_t> got;
    hw.usb_model.set_host_address(host.address);
    for (int k = 0; k < 64; ++k) {
      const test::InPacket p = hw.usb_model.in(1);
      board.on_usb_irq();
      if (p.handshake != test::Handshake::ack) break;
      if (packets != nullptr) packets->push_back(p.bytes.size());
      got.insert(got.end(), p.bytes.begin(), p.bytes.end());
    }
    return got;
  }
  std::vector<std::uint8_t> read_link() {
    std::vector<std::uint8_t> bytes(512);
    bytes.resize(board.link_read(bytes.data(), bytes.size()));
    return bytes;
  }
  std::size_t tdr_writes() const {
    std::size_t n = 0;
    for (const test::Write& w : hw.writes_since(0)) n += w.address == lpuart1::Tdr::reg.address();
    return n;
  }

  BoardHardware hw;
  RecordingCpu cpu;
  std::array<std::uint16_t, 6> pressure{};
  Board::Link link{hw};
  Board board{hw, cpu, link, platform()};
  BoardUsbBus bus{hw.usb_model};
  dev::test::Host<BoardUsbBus> host{bus, [this] { board.on_usb_irq(); }};
};

TEST_F(StmBoardUsb, InitAttachesWithIrq20EnabledBelowTheTickAndPa11Pa12Analog) {
  EXPECT_TRUE(hw.usb_model.attached()) << "BCDR.DPPU: the D+ pull-up (facts §5.1)";
  EXPECT_EQ(hw.count_writes(0xE000'E100u, 1u << 20), 1u) << "ISER0 bit 20: USB_LP";
  const std::uint32_t ipr5 = hw.peek(0xE000'E414u);  // IRQ 20's priority byte: IPR5 bits 7:0
  EXPECT_EQ(ipr5 & 0xFFu, 0x80u);
  EXPECT_GT(ipr5 & 0xFFu, (hw.peek(0xE000'E410u) >> 16) & 0xFFu) << "below the tick (IRQ 18)";
  const std::uint32_t moder = hw.peek(gpio::ModerA::reg);  // facts §5.1: analog (11)
  EXPECT_EQ((moder >> 22) & 0b11u, 0b11u) << "PA11 = USB DM";
  EXPECT_EQ((moder >> 24) & 0b11u, 0b11u) << "PA12 = USB DP";
  EXPECT_EQ(hw.usb_model.faults().total(), 0u);
}

TEST_F(StmBoardUsb, TheBoardEnumeratesAndItsSerialStringIsTheIdentitySerial) {
  host.reset();
  const dev::test::ControlResult device = host.control_in(dev::test::get_descriptor(0x01, 0, 18));
  ASSERT_EQ(device.outcome, Outcome::ok);
  const auto expected = dev::find_descriptor(0x01, 0, 0);
  EXPECT_EQ(device.data, std::vector<std::uint8_t>(expected.begin(), expected.end()));
  EXPECT_EQ(device.data[8] | device.data[9] << 8, proto::usb::kVendorId);
  EXPECT_EQ(device.data[10] | device.data[11] << 8, proto::usb::kProductId);

  ASSERT_EQ(host.control_out(dev::test::set_address(5)).outcome, Outcome::ok);
  host.address = 5;
  const dev::test::ControlResult serial =
      host.control_in(dev::test::get_descriptor(0x03, dev::kStringSerialNumber, 255, 0x0409));
  ASSERT_EQ(serial.outcome, Outcome::ok);
  ASSERT_GE(serial.data.size(), 2u);
  EXPECT_EQ(serial.data[0], serial.data.size());
  EXPECT_EQ(serial.data[1], 0x03);
  std::string text;  // UTF-16LE, ASCII only
  for (std::size_t k = 2; k + 1 < serial.data.size(); k += 2) {
    EXPECT_EQ(serial.data[k + 1], 0);
    text.push_back(static_cast<char>(serial.data[k]));
  }
  EXPECT_EQ(text, "0012ABCD34333231FEDCBA98");
  EXPECT_EQ(text, board.identity().serial);
  EXPECT_EQ(hw.usb_model.faults().total(), 0u);
  EXPECT_EQ(hw.usb_model.toggle_mismatches(), 0u);
}

TEST_F(StmBoardUsb, BulkOutBytesReachLinkReadAndLinkWriteBytesLeaveOnBulkIn) {
  enumerate();
  const std::vector<std::uint8_t> request = {0x00, 0x11, 0x22, 0x33, 0x00};
  host_sends(request);
  EXPECT_EQ(read_link(), request);
  EXPECT_EQ(board.active_link(), HostLinkId::usb);

  std::vector<std::uint8_t> reply(100);
  for (std::size_t k = 0; k < reply.size(); ++k) reply[k] = static_cast<std::uint8_t>(k * 7 + 1);
  const std::size_t from = hw.log_size();
  EXPECT_EQ(board.link_write(reply.data(), reply.size()), reply.size());
  EXPECT_EQ(hw.count_writes(0xE000'E200u, 1u << 20, from), 1u)
      << "ISPR0 bit 20: the USB interrupt pended to start the IN pipe";
  board.on_usb_irq();  // the pended interrupt
  std::vector<std::size_t> packets;
  EXPECT_EQ(host_receives(&packets), reply);
  EXPECT_EQ(packets, (std::vector<std::size_t>{64, 36}));
  EXPECT_EQ(tdr_writes(), 0u) << "nothing went to LPUART1";
  EXPECT_EQ(hw.usb_model.faults().total(), 0u);
  EXPECT_EQ(hw.usb_model.toggle_mismatches(), 0u);
}

TEST_F(StmBoardUsb, TheLinkThatLastDeliveredBytesTransmitsAndAdvertisesItsStreamRate) {
  const std::uint8_t out[3] = {7, 8, 9};
  // Before any byte: LPUART1.
  EXPECT_EQ(board.active_link(), HostLinkId::lpuart1);
  EXPECT_EQ(board.identity().max_stream_rate_Hz, 3840u);
  EXPECT_EQ(board.link_write(out, 3), 3u);
  EXPECT_EQ(tdr_writes(), 3u);

  // A USB host talks on the vendor interface: USB, the bulk figure (the core's maximum).
  enumerate();
  host_sends({1, 2, 3});
  EXPECT_EQ(read_link(), (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_EQ(board.identity().max_stream_rate_Hz, fw::Streamer::kMaxRate_Hz);
  EXPECT_EQ(board.link_write(out, 3), 3u);
  board.on_usb_irq();
  EXPECT_EQ(host_receives(), (std::vector<std::uint8_t>(out, out + 3)));
  EXPECT_EQ(tdr_writes(), 3u);

  // Bytes on LPUART1 still reach the core; while USB has bytes too, USB's come first.
  hw.uart_rx = {0x41, 0x42};
  board.link().on_irq();
  host_sends({4});
  EXPECT_EQ(read_link(), (std::vector<std::uint8_t>{4}));
  EXPECT_EQ(board.active_link(), HostLinkId::usb);
  EXPECT_EQ(read_link(), (std::vector<std::uint8_t>{0x41, 0x42}));
  EXPECT_EQ(board.active_link(), HostLinkId::lpuart1);
  EXPECT_EQ(board.identity().max_stream_rate_Hz, 3840u);
  EXPECT_EQ(board.link_write(out, 3), 3u);
  EXPECT_EQ(tdr_writes(), 6u);
  board.on_usb_irq();
  EXPECT_TRUE(host_receives().empty()) << "nothing more on USB";
}

TEST_F(StmBoardUsb, AHostOnTheHidInterfaceGetsTheHidStreamRate) {
  enumerate();
  hw.usb_model.reset_host_toggles(2);
  std::vector<std::uint8_t> report(proto::usb::kHidReportSize, 0);
  report[1] = 0x55;
  ASSERT_EQ(hw.usb_model.out(2, report), test::Handshake::ack);
  board.on_usb_irq();
  EXPECT_EQ(read_link(), report);  // the report's 64 bytes, padding included
  EXPECT_EQ(board.active_link(), HostLinkId::usb);
  EXPECT_EQ(board.identity().max_stream_rate_Hz, 2000u);
}

TEST_F(StmBoardUsb, IdleDoesNotSleepWhileUsbHoldsReceivedBytes) {
  enumerate();
  host_sends({1, 2});
  cpu.events.clear();
  board.idle([](void*) { return false; }, nullptr);
  EXPECT_EQ(cpu.events, (std::vector<std::string>{"cpsid", "cpsie"}));
  read_link();
  cpu.events.clear();
  board.idle([](void*) { return false; }, nullptr);
  EXPECT_EQ(cpu.events, (std::vector<std::string>{"cpsid", "wfi (masked)", "cpsie"}));
}

}  // namespace
}  // namespace palp::stm32::board_test
