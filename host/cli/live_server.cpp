// SPDX-License-Identifier: Apache-2.0
#include "live_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "palp/error.hpp"

namespace palpctl {

namespace {
using Clock = std::chrono::steady_clock;

// After an answer that closes the connection, what the client still sends is read and thrown
// away for this long (closing with unread input would reset the connection and lose the answer).
constexpr auto kLinger = std::chrono::seconds(2);

void set_nonblocking(int fd) { ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) | O_NONBLOCK); }

bool parse_ipv4(const std::string& text, in_addr& out) {
  return ::inet_pton(AF_INET, text.c_str(), &out) == 1;
}

// "GET /events?x HTTP/1.1" -> method, path without the query; false when malformed.
bool parse_request_line(std::string_view line, std::string_view& method, std::string_view& path) {
  const auto sp1 = line.find(' ');
  if (sp1 == std::string_view::npos || sp1 == 0) return false;
  const auto sp2 = line.find(' ', sp1 + 1);
  if (sp2 == std::string_view::npos) return false;
  method = line.substr(0, sp1);
  path = line.substr(sp1 + 1, sp2 - sp1 - 1);
  const auto version = line.substr(sp2 + 1);
  if (version != "HTTP/1.1" && version != "HTTP/1.0") return false;
  if (path.empty() || path.front() != '/') return false;
  for (const char c : method)
    if (c < 'A' || c > 'Z') return false;
  path = path.substr(0, path.find('?'));
  return true;
}

// The Host header's value (empty when there is none).
std::string_view host_header(std::string_view head) {
  std::size_t pos = head.find("\r\n");
  while (pos != std::string_view::npos && pos + 2 < head.size()) {
    const auto start = pos + 2;
    const auto end = head.find("\r\n", start);
    const auto line = head.substr(start, end == std::string_view::npos ? end : end - start);
    if (line.size() > 5 && ::strncasecmp(line.data(), "host:", 5) == 0) {
      auto v = line.substr(5);
      while (!v.empty() && (v.front() == ' ' || v.front() == '\t')) v.remove_prefix(1);
      return v;
    }
    pos = end;
  }
  return {};
}

// With a loopback bind, only a Host naming a loopback address or localhost is answered: a web
// page elsewhere that points a name of its own at 127.0.0.1 (DNS rebinding) cannot read the
// stream.
bool local_host(std::string_view host) {
  const auto colon = host.rfind(':');
  const std::string name(host.substr(0, colon));
  return name == "localhost" || is_loopback_ipv4(name);
}
}  // namespace

bool is_loopback_ipv4(const std::string& address) {
  in_addr a{};
  return parse_ipv4(address, a) && (ntohl(a.s_addr) >> 24) == 127;
}

LiveServer::LiveServer(const LiveServerOptions& o, std::string page_html)
    : address_(o.bind_address), page_(std::move(page_html)) {
  in_addr addr{};
  if (!parse_ipv4(o.bind_address, addr))
    throw palp::ConfigError("--bind: '" + o.bind_address + "' is not an IPv4 address");
  if (!o.allow_remote && !is_loopback_ipv4(o.bind_address))
    throw palp::ConfigError(
        "--bind " + o.bind_address +
        " is not a loopback address: the live view has no authentication and would show the "
        "instrument's signals to the network; add --allow-remote to serve it there anyway");
  allow_remote_ = o.allow_remote;
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (listen_fd_ < 0) throw palp::Error(std::string("live view: socket: ") + std::strerror(errno));
  const int one = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(o.port);
  a.sin_addr = addr;
  if (::bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 ||
      ::listen(listen_fd_, 16) != 0) {
    const std::string why = std::strerror(errno);
    ::close(listen_fd_);
    throw palp::Error("live view: cannot listen on " + o.bind_address + ":" +
                      std::to_string(o.port) + ": " + why);
  }
  socklen_t n = sizeof a;
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &n);
  port_ = ntohs(a.sin_port);
  set_nonblocking(listen_fd_);
}

LiveServer::~LiveServer() {
  for (auto& c : clients_)
    if (c.fd >= 0) ::close(c.fd);
  if (listen_fd_ >= 0) ::close(listen_fd_);
}

std::string LiveServer::url() const {
  return "http://" + address_ + ":" + std::to_string(port_) + "/";
}

std::size_t LiveServer::event_clients() const {
  return static_cast<std::size_t>(
      std::count_if(clients_.begin(), clients_.end(), [](const Client& c) { return c.events; }));
}

void LiveServer::accept_clients() {
  for (;;) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;  // EAGAIN: none waiting (or a transient error: try at the next poll)
    if (clients_.size() >= kMaxClients) {
      static constexpr char kBusy[] =
          "HTTP/1.1 503 Service Unavailable\r\nContent-Length: 0\r\nConnection: close\r\n\r\n";
      (void)::send(fd, kBusy, sizeof kBusy - 1, MSG_NOSIGNAL);
      ::close(fd);
      continue;
    }
    Client c;
    c.fd = fd;
    c.since = Clock::now();
    clients_.push_back(std::move(c));
  }
}

void LiveServer::answer(Client& c, int status, std::string_view reason,
                        std::string_view content_type, std::string_view body) {
  c.out += "HTTP/1.1 " + std::to_string(status) + " " + std::string(reason) +
           "\r\nContent-Type: " + std::string(content_type) +
           "\r\nContent-Length: " + std::to_string(body.size()) +
           "\r\nCache-Control: no-store\r\nX-Content-Type-Options: nosniff"
           "\r\nConnection: close\r\n\r\n";
  c.out += body;
  c.close_when_sent = true;
  c.in.clear();
}

void LiveServer::read_request(Client& c) {
  char buf[4096];
  for (;;) {
    const ssize_t n = ::recv(c.fd, buf, sizeof buf, 0);
    if (n == 0) return drop(c);  // the client went
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) break;
      return drop(c);
    }
    if (c.close_when_sent || c.events) continue;  // answered already: input is thrown away
    c.in.append(buf, static_cast<std::size_t>(n));
    if (c.in.size() > kMaxRequestBytes) break;
  }
  if (c.close_when_sent || c.events || c.fd < 0) return;
  const auto end = c.in.find("\r\n\r\n");
  if (end == std::string::npos || end + 4 > kMaxRequestBytes) {
    if (c.in.size() > kMaxRequestBytes)
      answer(c, 431, "Request Header Fields Too Large", "text/plain; charset=utf-8",
             "request head longer than " + std::to_string(kMaxRequestBytes) + " bytes\n");
    return;  // else: wait for the rest
  }
  const std::string_view head(c.in.data(), end);
  std::string_view method, path;
  if (!parse_request_line(head.substr(0, head.find("\r\n")), method, path))
    return answer(c, 400, "Bad Request", "text/plain; charset=utf-8", "malformed request line\n");
  if (!allow_remote_ && !local_host(host_header(head)))
    return answer(c, 403, "Forbidden", "text/plain; charset=utf-8",
                  "Host is not a loopback address or localhost\n");
  if (method != "GET")
    return answer(c, 405, "Method Not Allowed", "text/plain; charset=utf-8", "only GET\n");
  if (path == "/") return answer(c, 200, "OK", "text/html; charset=utf-8", page_);
  if (path == "/events") {
    c.events = true;
    c.in.clear();
    c.out +=
        "HTTP/1.1 200 OK\r\nContent-Type: text/event-stream\r\nCache-Control: no-store\r\n"
        "X-Content-Type-Options: nosniff\r\nConnection: keep-alive\r\n\r\nretry: 1000\n\n";
    return;
  }
  answer(c, 404, "Not Found", "text/plain; charset=utf-8",
         "not found: the live view serves / and /events\n");
}

void LiveServer::flush(Client& c) {
  while (c.fd >= 0 && !c.out.empty()) {
    const ssize_t n = ::send(c.fd, c.out.data(), c.out.size(), MSG_NOSIGNAL);
    if (n < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) return;
      return drop(c);
    }
    c.out.erase(0, static_cast<std::size_t>(n));
  }
  if (c.fd >= 0 && c.out.empty() && c.close_when_sent && !c.lingering) {
    ::shutdown(c.fd, SHUT_WR);  // the answer is complete; read what is left, then close
    c.lingering = true;
    c.since = Clock::now();
  }
}

void LiveServer::drop(Client& c) {
  if (c.fd >= 0) ::close(c.fd);
  c.fd = -1;
  c.events = false;
}

void LiveServer::broadcast(std::string_view event, std::string_view data) {
  std::string message = "event: ";
  message += event;
  message += "\ndata: ";
  message += data;
  message += "\n\n";
  for (auto& c : clients_) {
    if (!c.events || c.fd < 0) continue;
    if (c.out.size() + message.size() > kMaxUnsentBytes) {  // not reading: let it go
      ++slow_dropped_;
      drop(c);
      continue;
    }
    c.out += message;
    flush(c);
  }
}

void LiveServer::serve(std::chrono::milliseconds timeout) {
  const auto deadline = Clock::now() + timeout;
  for (;;) {
    const auto now = Clock::now();
    for (auto& c : clients_) {
      if (c.fd < 0 || c.events) continue;
      if ((c.lingering && now - c.since > kLinger) ||
          (!c.close_when_sent && now - c.since > kRequestTimeout))
        drop(c);
    }
    std::erase_if(clients_, [](const Client& c) { return c.fd < 0; });

    std::vector<pollfd> fds;
    fds.push_back({listen_fd_, POLLIN, 0});
    for (const auto& c : clients_)
      fds.push_back({c.fd, static_cast<short>(POLLIN | (c.out.empty() ? 0 : POLLOUT)), 0});
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now());
    const int r = ::poll(fds.data(), fds.size(), static_cast<int>(std::max<long>(0, left.count())));
    if (r < 0) return;  // EINTR: a signal (Ctrl-C) ends the wait
    if (r > 0) {
      // clients first (accepting appends to clients_, whose order matches fds from index 1)
      for (std::size_t k = 1; k < fds.size(); ++k) {
        Client& c = clients_[k - 1];
        if (fds[k].revents & (POLLIN | POLLHUP | POLLERR)) read_request(c);
        if (c.fd >= 0) flush(c);  // sends what is queued; an answer sent starts lingering
      }
      if (fds[0].revents & POLLIN) accept_clients();
    }
    if (Clock::now() >= deadline) return;
  }
}

}  // namespace palpctl
