// SPDX-License-Identifier: Apache-2.0
// palp-sim's robot bridge over a real socket (palp-sim --robot-port 0, a libmodbus client): one
// client, exceptions, a command round trip, guarded approaches onto solid_1d with the force guard
// and with the digital input (the controller's contact-output line), the watchdog, a connection
// closing mid-motion, a reply delay beyond the client's timeout, and the fault knobs.
#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include <array>
#include <bit>
#include <cerrno>
#include <chrono>
#include <functional>
#include <random>
#include <thread>

#include "palp/protocol/robot_bridge/codec.hpp"
#include "sim_process.hpp"

namespace palp::sim::test {
namespace {

namespace rb = proto::rb;
using rb::CommandCode;
using rb::Result;
using rb::RobotState;
using Clock = std::chrono::steady_clock;

class ModbusClient {
 public:
  explicit ModbusClient(std::uint16_t port, int timeout_ms = 2000) {
    ctx_ = modbus_new_tcp("127.0.0.1", port);
    modbus_set_response_timeout(ctx_, 0, static_cast<std::uint32_t>(timeout_ms) * 1000u);
    connected_ = modbus_connect(ctx_) == 0;
  }
  ~ModbusClient() {
    modbus_close(ctx_);
    modbus_free(ctx_);
  }
  bool connected() const { return connected_; }
  modbus_t* ctx() { return ctx_; }

  bool read(std::uint16_t address, std::uint16_t count, std::uint16_t* out) {
    return modbus_read_registers(ctx_, address, count, out) == count;
  }
  rb::StatusBlock status() {
    std::array<std::uint16_t, rb::StatusBlock::kLength> r{};
    rb::StatusBlock s{};
    if (read(rb::StatusBlock::kAddress, rb::StatusBlock::kLength, r.data()))
      rb::decode(std::span<const std::uint16_t>(r), s);
    return s;
  }
  bool beat() { return modbus_write_register(ctx_, 200, ++heartbeat_) == 1; }
  bool stop() {
    std::uint16_t v[3];
    if (!read(200, 3, v)) return false;
    return modbus_write_register(ctx_, 201, static_cast<std::uint16_t>(v[1] + 1)) == 1;
  }
  bool commit(const rb::Command& c) {
    std::array<std::uint16_t, rb::Command::kLength> r{};
    rb::encode(c, std::span<std::uint16_t, rb::Command::kLength>(r));
    return modbus_write_registers(ctx_, 300, rb::Command::kLength, r.data()) == rb::Command::kLength;
  }
  /// Polls the status (with heartbeats) until pred holds or timeout_ms of wall time pass.
  rb::StatusBlock wait(const std::function<bool(const rb::StatusBlock&)>& pred, int timeout_ms = 8000,
                       const std::function<void()>& each = [] {}) {
    const auto end = Clock::now() + std::chrono::milliseconds(timeout_ms);
    rb::StatusBlock s = status();
    while (!pred(s) && Clock::now() < end) {
      beat();
      each();
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
      s = status();
    }
    return s;
  }
  rb::StatusBlock wait_done(std::uint16_t seq, int timeout_ms = 8000) {
    return wait([seq](const rb::StatusBlock& s) { return s.done_seq == seq; }, timeout_ms);
  }

 private:
  modbus_t* ctx_;
  bool connected_ = false;
  std::uint16_t heartbeat_ = 0;
};

rb::Command set_tool(std::uint16_t seq, rb::i32 z_um) {
  rb::Command c{};
  c.seq = seq;
  c.code = CommandCode::set_tool;
  c.tool = 1;
  c.z_um = z_um;
  return c;
}

rb::Command move_rel(std::uint16_t seq, rb::i32 x_um, rb::i32 z_um, rb::i32 speed) {
  rb::Command c{};
  c.seq = seq;
  c.code = CommandCode::move_lin_rel;
  c.x_um = x_um;
  c.z_um = z_um;
  c.speed = speed;
  return c;
}

rb::Command approach(std::uint16_t seq, std::uint16_t guards, rb::i32 speed, rb::i32 travel) {
  rb::Command c{};
  c.seq = seq;
  c.code = CommandCode::guarded_approach;
  c.guard_sources = guards;
  c.axis = rb::Axis::tool_z;
  c.speed = speed;
  c.max_travel_um = travel;
  if (guards & rb::bit(rb::GuardSource::force)) c.force_threshold_mN = 2000;
  if (guards & rb::bit(rb::GuardSource::digital_input)) c.digital_input = 1;
  return c;
}

// The probe tool, then over solid_1d's position 3 (x = 27 mm) with the tip (at stroke origin)
// `above_mm` over the surface (phantom z = 0 is base z = 300 mm by default).
void place_over_position_3(ModbusClient& r, double above_mm) {
  ASSERT_TRUE(r.beat());
  ASSERT_TRUE(r.commit(set_tool(1, 200000)));
  ASSERT_EQ(r.wait_done(1).result, Result::done);
  const auto down = static_cast<rb::i32>((50.0 - above_mm) * 1000);
  ASSERT_TRUE(r.commit(move_rel(2, 27000, down, 100000)));
  const rb::StatusBlock s = r.wait_done(2);
  ASSERT_EQ(s.result, Result::done);
  EXPECT_EQ(s.x_um, 627000);
  EXPECT_EQ(s.z_um, static_cast<rb::i32>(300000 + above_mm * 1000));
}

TEST(RobotSim, BannerNamesTheRobotPortAndTheUri) {
  SimProcess sim({"--robot-port", "0"}, false);
  ASSERT_TRUE(sim.ok()) << sim.banner();
  ASSERT_NE(sim.robot_port(), 0) << sim.banner();
  EXPECT_EQ(sim.robot_uri(), "modbus://127.0.0.1:" + std::to_string(sim.robot_port()));
  SimProcess plain({}, false);
  EXPECT_EQ(plain.robot_port(), 0);
  EXPECT_EQ(plain.banner().find("robot"), std::string::npos);
}

TEST(RobotSim, RobotStartPlacesTheTipInTheBaseFrame) {
  SimProcess sim({"--robot-port", "0", "--robot-start-mm", "550", "10", "320"}, false);
  ModbusClient r(sim.robot_port());
  ASSERT_TRUE(r.connected());
  ASSERT_TRUE(r.beat());
  ASSERT_TRUE(r.commit(set_tool(1, 200000)));
  const rb::StatusBlock s = r.wait_done(1);
  EXPECT_EQ(s.x_um, 550000);
  EXPECT_EQ(s.y_um, 10000);
  EXPECT_EQ(s.z_um, 320000);
  EXPECT_NE(sim.control("status").find("tip_phantom_x_mm=-50.000 tip_phantom_y_mm=-10.000 "
                                       "tip_phantom_z_mm=-20.000"),
            std::string::npos)
      << sim.control("status");
}

TEST(RobotSim, ServesOneClientAndClosesASecondAtOnce) {
  SimProcess sim({"--robot-port", "0"}, false);
  ModbusClient first(sim.robot_port());
  ASSERT_TRUE(first.connected());
  std::uint16_t id[10];
  ASSERT_TRUE(first.read(0, 10, id));
  ModbusClient second(sim.robot_port(), 500);
  std::uint16_t v[2];
  EXPECT_FALSE(second.connected() && second.read(0, 2, v));  // closed without an answer
  ASSERT_TRUE(first.read(0, 2, v));
  EXPECT_EQ(v[0], 0x5041);
  EXPECT_EQ(v[1], 0x4C50);
  EXPECT_NE(sim.control("status").find("modbus_refused=1"), std::string::npos);
}

TEST(RobotSim, AnswersTheSpecsExceptionsOverTheWire) {
  SimProcess sim({"--robot-port", "0"}, false);
  ModbusClient r(sim.robot_port());
  ASSERT_TRUE(r.connected());
  std::uint16_t buf[30]{};
  EXPECT_EQ(modbus_read_input_registers(r.ctx(), 0, 1, buf), -1);
  EXPECT_EQ(errno, EMBXILFUN);
  EXPECT_EQ(modbus_write_register(r.ctx(), 101, 1), -1);
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_read_registers(r.ctx(), 95, 10, buf), -1);
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_write_registers(r.ctx(), 300, 10, buf), -1);  // not the whole command block
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_write_register(r.ctx(), 300, 1), -1);  // FC6 into the command block
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(modbus_write_register(r.ctx(), 202, 50), -1);
  EXPECT_EQ(errno, EMBXILVAL);
  ASSERT_TRUE(r.read(200, 3, buf));
  EXPECT_EQ(buf[2], 500);
  EXPECT_NE(sim.control("status").find("modbus_exceptions=6"), std::string::npos)
      << sim.control("status");
}

TEST(RobotSim, MoveLinRoundTripEndsExactlyAtTheTarget) {
  SimProcess sim({"--robot-port", "0"}, false);
  ModbusClient r(sim.robot_port());
  ASSERT_TRUE(r.connected());
  ASSERT_TRUE(r.beat());
  ASSERT_TRUE(r.commit(set_tool(1, 200000)));
  ASSERT_EQ(r.wait_done(1).result, Result::done);
  rb::Command c{};
  c.seq = 2;
  c.code = CommandCode::move_lin;
  c.speed = 200000;
  c.x_um = 550000, c.y_um = 20000, c.z_um = 380000, c.c_mdeg = 180000;
  ASSERT_TRUE(r.commit(c));
  const rb::StatusBlock s = r.wait_done(2);
  EXPECT_EQ(s.ack_result, Result::accepted);
  EXPECT_EQ(s.result, Result::done);
  EXPECT_EQ(s.state, RobotState::idle);
  EXPECT_EQ(s.x_um, 550000);
  EXPECT_EQ(s.y_um, 20000);
  EXPECT_EQ(s.z_um, 380000);
  EXPECT_EQ(s.c_mdeg, 180000);
  EXPECT_EQ(sim.control("mount 0 0 0").rfind("error: mount: the robot arm places the probe", 0), 0u);
}

TEST(RobotSim, ForceGuardStopsAnApproachOntoSolid1d) {
  SimProcess sim({"--robot-port", "0", "--phantom", "solid_1d"}, false);
  ModbusClient r(sim.robot_port());
  ASSERT_TRUE(r.connected());
  place_over_position_3(r, 3.0);
  ASSERT_TRUE(r.commit(approach(3, 0x0005, 5000, 20000)));
  const rb::StatusBlock s = r.wait_done(3, 15000);
  EXPECT_EQ(s.result, Result::guard_fired);
  EXPECT_EQ(s.guard_fired, 0x0004);
  EXPECT_NE(s.status_bits & rb::bit(rb::StatusBit::latched_pose_valid), 0);
  // the coil sits at its rear stop: 2 N of the resin's reaction is reached a few mm in
  EXPECT_LT(s.latched_z_um, 300000);
  EXPECT_GT(s.latched_z_um, 294000);
  EXPECT_LT(s.z_um, s.latched_z_um);  // braked on after the latch
  EXPECT_GE(s.force_mN, 1800);
}

TEST(RobotSim, DigitalInputGuardFiresOnTheControllersContactLine) {
  SimProcess sim({"--robot-port", "0", "--phantom", "solid_1d"});
  ASSERT_TRUE(sim.ok()) << sim.banner();
  ModbusClient r(sim.robot_port());
  ASSERT_TRUE(r.connected());
  // the tip 30 mm over the surface: the coil floats 25 mm forward at 0.5 A
  place_over_position_3(r, 30.0);
  using namespace proto;
  Params p;
  sim.send(GetParams{}, 1);
  ASSERT_TRUE(sim.await(1, p));
  p.contact_output = ContactOutputMode::active_high;
  sim.send(std::bit_cast<SetParams>(p), 2);
  ASSERT_TRUE(sim.await(2, p));
  Ack a;
  sim.send(LoadHold{0.5f, 0.0f}, 3);
  ASSERT_TRUE(sim.await(3, a));
  sim.send(ProgramStart{}, 4);
  ASSERT_TRUE(sim.await(4, a));
  Status st;
  u16 seq = 5;
  std::uint64_t settled_us = 0;
  for (; seq < 3000; ++seq) {  // 1 s of device time for the coil to float and settle
    r.beat();
    sim.send(GetStatus{}, seq);
    ASSERT_TRUE(sim.await(seq, st));
    if (settled_us == 0) settled_us = st.device_time_us + 1'000'000;
    if (st.device_time_us >= settled_us) break;
  }
  // swap the hold for a contact watch at the same current, from the floating position
  std::vector<u8> burst, w(kMaxWireFrame);
  w.resize(encode_message(ProgramStop{}, ++seq, 0, w.data(), w.size()));
  burst.insert(burst.end(), w.begin(), w.end());
  w.resize(kMaxWireFrame);
  w.resize(encode_message(LoadContactWatch{0.5f, 200, 0.0f}, ++seq, 0, w.data(), w.size()));
  burst.insert(burst.end(), w.begin(), w.end());
  w.resize(kMaxWireFrame);
  w.resize(encode_message(ProgramStart{}, ++seq, 0, w.data(), w.size()));
  burst.insert(burst.end(), w.begin(), w.end());
  sim.send_bytes(burst);
  ASSERT_TRUE(sim.await(seq, a));

  ASSERT_TRUE(r.commit(approach(3, 0x0002, 5000, 20000)));
  bool contact = false;
  const rb::StatusBlock s = r.wait(
      [](const rb::StatusBlock& b) { return b.done_seq == 3; }, 15000, [&] {
        // keep the controller's heartbeat fed; note the contact event
        sim.send(GetStatus{}, ++seq);
        sim.await_collecting(seq, st, [&](const auto& m) {
          if constexpr (std::is_same_v<std::decay_t<decltype(m)>, EventContact>) contact = true;
        });
      });
  EXPECT_TRUE(contact);
  EXPECT_EQ(s.result, Result::guard_fired);
  EXPECT_EQ(s.guard_fired, 0x0002);
  // the tip touched z = 300 mm with the coil 25 mm forward: the flange-side TCP is ~25 mm higher
  EXPECT_GT(s.latched_z_um, 320000);
  EXPECT_LT(s.latched_z_um, 330000);
}

TEST(RobotSim, StaleHeartbeatStopsTheArmWithWatchdog) {
  SimProcess sim({"--robot-port", "0"}, false);
  ModbusClient r(sim.robot_port());
  ASSERT_TRUE(r.connected());
  ASSERT_TRUE(r.beat());
  std::uint16_t wd = 200;
  ASSERT_EQ(modbus_write_register(r.ctx(), 202, wd), 1);
  ASSERT_TRUE(r.commit(set_tool(1, 200000)));
  ASSERT_EQ(r.wait_done(1).result, Result::done);
  ASSERT_TRUE(r.commit(move_rel(2, 0, 40000, 100)));  // 400 s at 0.1 mm/s
  ASSERT_EQ(r.wait([](const rb::StatusBlock& s) { return s.state == RobotState::moving; }).ack_seq, 2);
  // no heartbeat from now on: read only
  const auto end = Clock::now() + std::chrono::seconds(3);
  rb::StatusBlock s = r.status();
  while (s.done_seq != 2 && Clock::now() < end) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    s = r.status();
  }
  EXPECT_EQ(s.result, Result::watchdog);
  EXPECT_NE(s.status_bits & rb::bit(rb::StatusBit::watchdog_tripped), 0);
  EXPECT_EQ(s.status_bits & rb::bit(rb::StatusBit::host_heartbeat_ok), 0);
}

TEST(RobotSim, AConnectionClosingMidMotionStopsTheArm) {
  SimProcess sim({"--robot-port", "0"}, false);
  {
    ModbusClient r(sim.robot_port());
    ASSERT_TRUE(r.connected());
    ASSERT_TRUE(r.beat());
    ASSERT_TRUE(r.commit(set_tool(1, 200000)));
    ASSERT_EQ(r.wait_done(1).result, Result::done);
    ASSERT_TRUE(r.commit(move_rel(2, 0, 40000, 100)));  // 400 s
    ASSERT_EQ(r.wait([](const rb::StatusBlock& s) { return s.state == RobotState::moving; }).ack_seq, 2);
  }
  ModbusClient again(sim.robot_port());
  ASSERT_TRUE(again.connected());
  std::uint16_t v[2];
  ASSERT_TRUE(again.read(0, 2, v)) << modbus_strerror(errno) << " " << sim.control("status");
  const rb::StatusBlock s = again.wait([](const rb::StatusBlock& b) { return b.done_seq == 2; }, 3000);
  EXPECT_EQ(s.result, Result::watchdog);
  EXPECT_EQ(s.state, RobotState::idle);
}

TEST(RobotSim, AReplyDelayBeyondTheClientsTimeoutTimesOutButTheWriteIsTaken) {
  SimProcess sim({"--robot-port", "0"}, false);
  ModbusClient r(sim.robot_port(), 200);
  ASSERT_TRUE(r.connected());
  ASSERT_TRUE(r.beat());
  EXPECT_EQ(sim.control("robot-reply-delay 400"), "ok");
  EXPECT_FALSE(r.commit(set_tool(1, 200000)));
  EXPECT_EQ(errno, ETIMEDOUT);
  EXPECT_EQ(sim.control("robot-reply-delay 0"), "ok");
  // as the SDK does after a timeout (§9.1): reconnect, then read ack_seq
  modbus_close(r.ctx());
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  ModbusClient again(sim.robot_port());
  ASSERT_TRUE(again.connected());
  const rb::StatusBlock s = again.wait_done(1, 3000);
  EXPECT_EQ(s.ack_seq, 1);
  EXPECT_EQ(s.result, Result::done);
}

TEST(RobotSim, FaultKnobsActOnTheBridge) {
  SimProcess sim({"--robot-port", "0"}, false);
  ModbusClient r(sim.robot_port());
  ASSERT_TRUE(r.connected());
  ASSERT_TRUE(r.beat());
  EXPECT_EQ(sim.control("robot-reject rejected_not_ready 1"), "ok");
  ASSERT_TRUE(r.commit(set_tool(1, 200000)));
  rb::StatusBlock s = r.wait([](const rb::StatusBlock& b) { return b.ack_seq == 1; });
  EXPECT_EQ(s.ack_result, Result::rejected_not_ready);

  EXPECT_EQ(sim.control("robot-fault"), "ok");
  s = r.wait([](const rb::StatusBlock& b) { return b.state == RobotState::faulted; });
  EXPECT_EQ(s.state, RobotState::faulted);
  EXPECT_NE(sim.control("status").find("robot_state=faulted"), std::string::npos);

  EXPECT_EQ(sim.control("robot-freeze-heartbeat on"), "ok");
  const std::uint16_t hb = r.status().heartbeat;
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(r.status().heartbeat, hb);
  EXPECT_EQ(sim.control("robot-freeze-heartbeat off"), "ok");
  EXPECT_NE(r.wait([hb](const rb::StatusBlock& b) { return b.heartbeat != hb; }).heartbeat, hb);

  EXPECT_EQ(sim.control("robot-drop"), "ok");
  std::uint16_t v[2];
  EXPECT_FALSE(r.read(0, 2, v));
  EXPECT_EQ(sim.control("robot-drop"), "ok no client");
}

int raw_connect(std::uint16_t port) { return palp::sim::test::connect_loopback(port); }

TEST(RobotSim, APartialRequestNeitherBlocksTheSimulatorNorLosesTheRequest) {
  SimProcess sim({"--robot-port", "0"}, false);
  const int fd = raw_connect(sim.robot_port());
  ASSERT_GE(fd, 0);
  // FC3, 2 registers from 0, unit 7: the first 5 bytes now, the rest later
  const std::uint8_t req[12] = {0x12, 0x34, 0, 0, 0, 6, 7, 3, 0, 0, 0, 2};
  ASSERT_EQ(::write(fd, req, 5), 5);
  const auto t0 = Clock::now();
  EXPECT_EQ(sim.control("status").rfind("ok ", 0), 0u);  // the loop still serves
  EXPECT_LT(Clock::now() - t0, std::chrono::milliseconds(500));
  ASSERT_EQ(::write(fd, req + 5, 7), 7);
  std::uint8_t rsp[64];
  pollfd p{fd, POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 2000), 1);
  const ssize_t n = ::read(fd, rsp, sizeof rsp);
  ::close(fd);
  // the same transaction and unit, 4 bytes: 'PALP'
  const std::uint8_t expected[13] = {0x12, 0x34, 0, 0, 0, 7, 7, 3, 4, 0x50, 0x41, 0x4c, 0x50};
  ASSERT_EQ(n, 13);
  for (int k = 0; k < 13; ++k) EXPECT_EQ(rsp[k], expected[k]) << k;
}

TEST(RobotSim, AnFc16ByteCountThatDoesNotMatchItsQuantityIsIllegalDataValue) {
  SimProcess sim({"--robot-port", "0"}, false);
  const int fd = raw_connect(sim.robot_port());
  ASSERT_GE(fd, 0);
  // FC16 at 200, quantity 2, byte count 3 (not 4), 3 data bytes
  const std::uint8_t req[16] = {0, 9, 0, 0, 0, 10, 1, 0x10, 0, 200, 0, 2, 3, 0, 1, 0};
  ASSERT_EQ(::write(fd, req, 16), 16);
  std::uint8_t rsp[64];
  pollfd p{fd, POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 2000), 1);
  const ssize_t n = ::read(fd, rsp, sizeof rsp);
  ::close(fd);
  const std::uint8_t expected[9] = {0, 9, 0, 0, 0, 3, 1, 0x90, 0x03};
  ASSERT_EQ(n, 9);
  for (int k = 0; k < 9; ++k) EXPECT_EQ(rsp[k], expected[k]) << k;
}

TEST(RobotSim, GarbageBytesCloseTheConnectionAndTheNextClientIsServed) {
  SimProcess sim({"--robot-port", "0"}, false);
  std::mt19937 rng(5);
  for (int round = 0; round < 3; ++round) {
    const int fd = raw_connect(sim.robot_port());
    ASSERT_GE(fd, 0);
    std::vector<std::uint8_t> junk(4096);
    for (auto& b : junk) b = static_cast<std::uint8_t>(rng());
    (void)::write(fd, junk.data(), junk.size());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ::close(fd);
  }
  ModbusClient r(sim.robot_port());
  ASSERT_TRUE(r.connected());
  std::uint16_t v[2];
  ASSERT_TRUE(r.read(0, 2, v));
  EXPECT_EQ(v[0], 0x5041);
  EXPECT_TRUE(sim.alive());
}

TEST(RobotSim, RobotKnobsSayTheBridgeIsOffWithoutRobotPort) {
  SimProcess sim({}, false);
  EXPECT_EQ(sim.control("robot-drop"),
            "error: robot-drop: the robot bridge is off (start palp-sim with --robot-port)");
}

}  // namespace
}  // namespace palp::sim::test
