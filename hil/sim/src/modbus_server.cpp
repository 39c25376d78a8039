// SPDX-License-Identifier: Apache-2.0
#include "palp/sim/modbus_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <stdexcept>

namespace palp::sim {

namespace {

constexpr std::size_t kMbapHeader = 7;  // transaction id, protocol id, length, unit id
constexpr int kMappedRegisters = rb::Command::kAddress + rb::Command::kLength;

constexpr std::size_t kRxLimit = 4096;   // unparsed bytes kept
constexpr std::size_t kMaxReplies = 64;  // replies waiting (a reply delay) before reading stops

std::uint16_t be16(const std::uint8_t* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }

std::string peer_of(int fd) {
  sockaddr_in a{};
  socklen_t len = sizeof a;
  if (::getpeername(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) return "an unknown peer";
  char ip[INET_ADDRSTRLEN] = "?";
  ::inet_ntop(AF_INET, &a.sin_addr, ip, sizeof ip);
  return std::string(ip) + ":" + std::to_string(ntohs(a.sin_port));
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

}  // namespace

ModbusServer::ModbusServer(const std::string& address, std::uint16_t port) : listen_address_(address) {
  ctx_ = modbus_new_tcp(address.c_str(), port);
  if (ctx_ == nullptr) throw std::runtime_error("robot bridge: cannot create a Modbus context: " +
                                                std::string(modbus_strerror(errno)));
  mapping_ = modbus_mapping_new_start_address(0, 0, 0, 0, 0, kMappedRegisters, 0, 0);
  listen_ = modbus_tcp_listen(ctx_, 1);
  if (mapping_ == nullptr || listen_ < 0) {
    const std::string why = modbus_strerror(errno);
    if (mapping_ != nullptr) modbus_mapping_free(mapping_);
    modbus_free(ctx_);
    throw std::runtime_error("robot bridge: cannot listen on " + address + ":" +
                             std::to_string(port) + ": " + why);
  }
  ::fcntl(listen_, F_SETFL, ::fcntl(listen_, F_GETFL) | O_NONBLOCK);
  sockaddr_in a{};
  socklen_t len = sizeof a;
  ::getsockname(listen_, reinterpret_cast<sockaddr*>(&a), &len);
  port_ = ntohs(a.sin_port);
}

ModbusServer::~ModbusServer() {
  if (client_ >= 0) ::close(client_);
  if (listen_ >= 0) ::close(listen_);
  modbus_set_socket(ctx_, -1);
  modbus_mapping_free(mapping_);
  modbus_free(ctx_);
}

std::string ModbusServer::address() const {
  return "tcp://" + listen_address_ + ":" + std::to_string(port_);
}

void ModbusServer::poll(ModbusHandler& handler, std::uint64_t wall_us) {
  accept_clients(handler, wall_us);
  if (client_ >= 0 && receive(handler, wall_us) && !send_due(wall_us)) close_client(handler);
  if (client_ < 0) return;
  // the one slot is not held by a client that does not talk, or stops mid-request
  const bool partial_stuck = partial_since_us_ != 0 && wall_us > partial_since_us_ &&
                             wall_us - partial_since_us_ > partial_us_;
  const bool idle = wall_us > last_request_us_ && wall_us - last_request_us_ > idle_us_;
  if (partial_stuck || idle) {
    ++counters_.timeouts;
    close_client(handler);
  }
}

void ModbusServer::accept_clients(ModbusHandler& handler, std::uint64_t wall_us) {
  for (;;) {
    const int fd = ::accept4(listen_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;
    // a client that closed and reconnected at once is no second client: see its close first
    if (client_ >= 0) receive(handler, wall_us);
    if (client_ >= 0) {  // one client at a time: close the second at once, saying why
      ++counters_.refused;
      const std::string busy = "palp-sim: busy: another host is connected from " + client_from_ +
                               " since " + client_since_ + "\n";
      [[maybe_unused]] const auto w = ::send(fd, busy.data(), busy.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
      ::close(fd);
      continue;
    }
    ++counters_.connections;
    client_ = fd;
    client_from_ = peer_of(fd);
    client_since_ = utc_now();
    last_request_us_ = wall_us;
    partial_since_us_ = 0;
    rx_.clear();
    replies_.clear();
    modbus_set_socket(ctx_, fd);
  }
}

bool ModbusServer::receive(ModbusHandler& handler, std::uint64_t wall_us) {
  std::uint8_t buf[1024];
  // bounded: at most kRxLimit unparsed bytes and kMaxReplies waiting replies; the rest of a
  // flood waits in the socket for the next poll
  while (rx_.size() < kRxLimit && replies_.size() < kMaxReplies) {
    const ssize_t n = ::recv(client_, buf, std::min(sizeof buf, kRxLimit - rx_.size()), MSG_DONTWAIT);
    if (n > 0) {
      rx_.insert(rx_.end(), buf, buf + n);
      continue;
    }
    if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      close_client(handler);
      return false;
    }
    break;
  }
  // cut out whole requests; a partial one waits for the rest
  std::size_t at = 0;
  while (rx_.size() - at >= kMbapHeader) {
    const std::uint8_t* h = rx_.data() + at;
    const std::uint16_t protocol = be16(h + 2), length = be16(h + 4);
    if (protocol != 0 || length < 2 || length > 254) {
      ++counters_.malformed;
      close_client(handler);
      return false;
    }
    const std::size_t total = 6u + length;
    if (rx_.size() - at < total) break;
    serve(handler, std::vector<std::uint8_t>(h, h + total), wall_us);
    last_request_us_ = wall_us;
    at += total;
  }
  rx_.erase(rx_.begin(), rx_.begin() + static_cast<std::ptrdiff_t>(at));
  if (rx_.empty()) partial_since_us_ = 0;
  else if (partial_since_us_ == 0 || at > 0) partial_since_us_ = wall_us | 1;  // never 0: none
  return true;
}

void ModbusServer::serve(ModbusHandler& handler, std::vector<std::uint8_t> req, std::uint64_t wall_us) {
  ++counters_.requests;
  const std::uint8_t* pdu = req.data() + kMbapHeader;
  const std::size_t pdu_len = req.size() - kMbapHeader;
  Reply r{wall_us + reply_delay_us_, {}, ModbusException::none, 0, {}};
  const std::uint8_t fc = pdu[0];
  if (fc == MODBUS_FC_READ_HOLDING_REGISTERS) {
    if (pdu_len != 5) {
      r.exception = ModbusException::illegal_data_value;
    } else {
      r.address = be16(pdu + 1);
      const std::uint16_t count = be16(pdu + 3);
      r.values.assign(count, 0);
      r.exception = handler.read(r.address, count, r.values.data());
    }
  } else if (fc == MODBUS_FC_WRITE_SINGLE_REGISTER) {
    if (pdu_len != 5) {
      r.exception = ModbusException::illegal_data_value;
    } else {
      const std::uint16_t v[1] = {be16(pdu + 3)};
      r.exception = handler.write(be16(pdu + 1), v, true);
    }
  } else if (fc == MODBUS_FC_WRITE_MULTIPLE_REGISTERS) {
    const std::uint16_t count = pdu_len >= 6 ? be16(pdu + 3) : 0;
    if (pdu_len < 6 || pdu[5] != count * 2u || pdu_len != 6u + pdu[5]) {
      r.exception = ModbusException::illegal_data_value;
    } else {
      std::vector<std::uint16_t> regs(count);
      for (std::size_t k = 0; k < count; ++k) regs[k] = be16(pdu + 6 + 2 * k);
      r.exception = handler.write(be16(pdu + 1), regs, false);
    }
  } else {
    r.exception = ModbusException::illegal_function;
  }
  if (r.exception != ModbusException::none) ++counters_.exceptions;
  r.request = std::move(req);
  replies_.push_back(std::move(r));
}

bool ModbusServer::send_due(std::uint64_t wall_us) {
  while (!replies_.empty() && replies_.front().due_us <= wall_us) {
    Reply& r = replies_.front();
    const int len = static_cast<int>(r.request.size());
    int rc;
    if (r.exception != ModbusException::none) {
      rc = modbus_reply_exception(ctx_, r.request.data(), static_cast<unsigned>(r.exception));
    } else {
      for (std::size_t k = 0; k < r.values.size(); ++k) mapping_->tab_registers[r.address + k] = r.values[k];
      rc = modbus_reply(ctx_, r.request.data(), len, mapping_);  // writes land in the scratch map
    }
    replies_.pop_front();
    if (rc < 0) return false;
  }
  return true;
}

void ModbusServer::drop_client(ModbusHandler& handler) {
  if (client_ >= 0) close_client(handler);
}

void ModbusServer::close_client(ModbusHandler& handler) {
  ::close(client_);
  client_ = -1;
  modbus_set_socket(ctx_, -1);
  rx_.clear();
  replies_.clear();
  handler.closed();
}

}  // namespace palp::sim
