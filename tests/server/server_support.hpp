// In-process servers for the server tests: an HttpServer on 127.0.0.1 and an ephemeral port,
// run on its own thread, with an httplib client and a raw-socket client for requests httplib's
// client cannot send (chunked bodies, lying Content-Length, malformed HTTP).
#pragma once
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <doctest/doctest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include "http_server.hpp"

namespace footpoint::server::testing {

inline ServerConfig test_config(ServerConfig c = {}) {
  c.host = "127.0.0.1";
  c.port = 0;
  c.log_level = "off";
  if (c.threads == 0) c.threads = 2;
  if (c.connection_threads == ServerConfig{}.connection_threads) c.connection_threads = 16;
  return c;
}

class TestServer {
 public:
  explicit TestServer(ServerConfig config = {}, HttpServer::Handler handler = nullptr)
      : server_(test_config(std::move(config)), std::move(handler)) {
    port_ = server_.bind();
    thread_ = std::thread([this] { server_.run(); });
  }
  ~TestServer() { stop(); }
  TestServer(const TestServer&) = delete;
  TestServer& operator=(const TestServer&) = delete;

  // Graceful shutdown; returns when run() has returned.
  void stop() {
    server_.shutdown();
    if (thread_.joinable()) thread_.join();
  }

  int port() const { return port_; }
  HttpServer& server() { return server_; }

  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("http://127.0.0.1:" + std::to_string(port_));
    c->set_read_timeout(120, 0);
    c->set_write_timeout(120, 0);
    c->set_keep_alive(true);
    c->set_tcp_nodelay(true);  // else Nagle + delayed ACK add ~40 ms to each small request
    return c;
  }

  // An HTTPS client (--tls-cert servers) that trusts only the certificates in `ca_file` and checks
  // that the certificate names 127.0.0.1.
  std::unique_ptr<httplib::SSLClient> tls_client(const std::string& ca_file) const {
    auto c = std::make_unique<httplib::SSLClient>("127.0.0.1", port_);
    c->set_ca_cert_path(ca_file.c_str());
    c->enable_server_certificate_verification(true);
    c->set_read_timeout(120, 0);
    c->set_write_timeout(120, 0);
    c->set_tcp_nodelay(true);
    return c;
  }

 private:
  HttpServer server_;
  int port_ = -1;
  std::thread thread_;
};

// A new connection to the server on 127.0.0.1:port (a socket to close).
inline int raw_connect(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  REQUIRE(fd >= 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  REQUIRE(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);
  return fd;
}

// Sends all of `data` on fd (or as much as the peer takes before it closes); the bytes sent.
inline std::size_t send_all(int fd, const std::string& data) {
  std::size_t sent = 0;
  while (sent < data.size()) {
    const auto n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) break;
    sent += static_cast<std::size_t>(n);
  }
  return sent;
}

// Sends `request` as it is on a new connection and returns the first response the server
// writes (headers and a Content-Length body), or what arrived before the server closed the
// connection or `timeout` passed.
inline std::string raw_exchange(int port, const std::string& request,
                                std::chrono::milliseconds timeout = std::chrono::milliseconds(10000)) {
  const int fd = raw_connect(port);
  timeval tv{};
  tv.tv_sec = static_cast<long>(timeout.count() / 1000);
  tv.tv_usec = static_cast<long>(timeout.count() % 1000) * 1000;
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  send_all(fd, request);
  std::string response;
  char buf[4096];
  for (;;) {
    const auto end = response.find("\r\n\r\n");
    if (end != std::string::npos) {
      const auto at = response.find("Content-Length: ");
      if (at != std::string::npos && at < end &&
          response.size() >= end + 4 + std::stoul(response.substr(at + 16)))
        break;
    }
    const auto n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    response.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return response;
}

// The status code of the first response in a raw exchange.
inline int raw_status(const std::string& response) {
  if (response.rfind("HTTP/1.1 ", 0) != 0) return -1;
  return std::stoi(response.substr(9, 3));
}

// The JSON body of the first response in a raw exchange (after the blank line).
inline nlohmann::json raw_json(const std::string& response) {
  const auto start = response.find("\r\n\r\n");
  REQUIRE(start != std::string::npos);
  const auto length_at = response.find("Content-Length: ");
  REQUIRE(length_at != std::string::npos);
  const std::size_t length = std::stoul(response.substr(length_at + 16));
  return nlohmann::json::parse(response.substr(start + 4, length));
}

// A sphere of radius 2 about the origin, (u, v) longitude and colatitude: its s_u x s_v points
// inwards, so that the signed distance of p is 2 - |p| and its foot 2 p / |p|.
inline const std::string kSphereRadius2 =
    R"J({"type":"parametric_surface","x":"2*sin(v)*cos(u)","y":"2*sin(v)*sin(u)","z":"2*cos(v)",)J"
    R"J("domain":{"u":[0,"2*_pi"],"v":[0,"_pi"]}})J";

// Numbers as a binary body: little-endian float64 (this machine's order, checked by the tests'
// decoding against closed forms).
inline std::string float64_bytes(const std::vector<double>& x) {
  std::string body(x.size() * 8, '\0');
  std::memcpy(body.data(), x.data(), body.size());
  return body;
}

// Waits up to `limit` for the server to answer no API request; true when it does not.
inline bool wait_until_idle(HttpServer& server, std::chrono::seconds limit = std::chrono::seconds(60)) {
  const auto start = std::chrono::steady_clock::now();
  while (server.api().in_flight() > 0 && std::chrono::steady_clock::now() - start < limit)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  return server.api().in_flight() == 0;
}

// Posts a geometry definition (201 or 200) and returns its id.
inline std::string create(httplib::Client& c, const std::string& definition) {
  auto r = c.Post("/v1/geometries", definition, "application/json");
  REQUIRE(r);
  REQUIRE_MESSAGE((r->status == 201 || r->status == 200), r->body);
  return nlohmann::json::parse(r->body)["geometry_id"].get<std::string>();
}

// j with its member `key` set to `value`.
inline nlohmann::json with(nlohmann::json j, const std::string& key, const nlohmann::json& value) {
  j[key] = value;
  return j;
}

inline std::string read_text_file(const std::string& path) {
  std::ifstream in(path);
  REQUIRE_MESSAGE(in.good(), "cannot read " << path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace footpoint::server::testing
