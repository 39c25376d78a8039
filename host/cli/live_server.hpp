// SPDX-License-Identifier: Apache-2.0
// The live view's HTTP server (palpctl monitor --plot): one page and one server-sent-events
// stream, on POSIX sockets with poll(), run from the caller's thread (no threads of its own).
//
//   GET /        the page (the HTML given to the constructor), then the connection closes
//   GET /events  text/event-stream: every broadcast() from then on, until the client goes
//   other paths  404; other methods 405; a request head over kMaxRequestBytes 431 (a request
//                line alone over it: 414 would be the textbook answer, 431 is what a client
//                sees here either way), a malformed request line 400, and (unless
//                allow_remote) a Host header that is not a loopback address or localhost 403:
//                a web page elsewhere cannot reach the stream by pointing a name at 127.0.0.1
//
// Several clients may watch at once (up to kMaxClients connections). A client that disconnects
// is forgotten and never disturbs the others or the stream; a client that does not read (its
// unsent events pass kMaxUnsentBytes) is dropped rather than buffered without bound; a client
// that does not finish its request head within kRequestTimeout is dropped too.
//
// Bound to a loopback address unless told otherwise: the page has no authentication, and what
// it shows is the instrument's signals, so serving another address needs allow_remote.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace palpctl {

struct LiveServerOptions {
  std::string bind_address = "127.0.0.1";  ///< an IPv4 address
  std::uint16_t port = 0;                  ///< 0: any free port (url() says which)
  bool allow_remote = false;               ///< needed for a bind address outside 127.0.0.0/8
};

class LiveServer {
 public:
  static constexpr std::size_t kMaxRequestBytes = 8 * 1024;
  static constexpr std::size_t kMaxUnsentBytes = 4u << 20;  ///< per event client
  static constexpr std::size_t kMaxClients = 32;
  static constexpr std::chrono::seconds kRequestTimeout{5};

  /// Listens at once. Throws palp::ConfigError for an address that is not IPv4 or is not
  /// loopback without allow_remote, and palp::Error when the socket cannot be bound.
  LiveServer(const LiveServerOptions& options, std::string page_html);
  ~LiveServer();
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  /// "http://127.0.0.1:PORT/" with the port actually bound.
  std::string url() const;
  std::uint16_t port() const { return port_; }

  /// Accepts, reads requests, answers and sends queued output for up to timeout (returns
  /// earlier when the deadline passes; a signal ends the wait early too).
  void serve(std::chrono::milliseconds timeout);
  /// Queues one server-sent event (name and a one-line data payload) for every event client.
  void broadcast(std::string_view event, std::string_view data);
  /// How many clients are subscribed to /events now.
  std::size_t event_clients() const;
  /// Clients dropped because they did not read their events (since the start).
  std::uint64_t slow_clients_dropped() const { return slow_dropped_; }

 private:
  struct Client {
    int fd = -1;
    std::string in;    ///< the request head read so far
    std::string out;   ///< bytes not yet sent
    bool events = false;          ///< subscribed to /events
    bool close_when_sent = false;  ///< answered: close once out is empty
    bool lingering = false;        ///< answer sent: input read and thrown away, then closed
    std::chrono::steady_clock::time_point since;
  };

  void accept_clients();
  void read_request(Client& c);
  void answer(Client& c, int status, std::string_view reason, std::string_view content_type,
              std::string_view body);
  void flush(Client& c);
  void drop(Client& c);

  int listen_fd_ = -1;
  std::uint16_t port_ = 0;
  std::string address_;
  bool allow_remote_ = false;
  std::string page_;
  std::vector<Client> clients_;
  std::uint64_t slow_dropped_ = 0;
};

/// Whether an IPv4 address text is a loopback address (127.0.0.0/8); false for non-addresses.
bool is_loopback_ipv4(const std::string& address);

}  // namespace palpctl
