// A streamed projection's binary points read from the connection as they are answered
// (server/streamed_body.hpp): a client that reads while it sends gets its answers before it has
// sent all of its points, every answer checked against the sphere's closed form (radius 2: foot
// 2 p / |p|, signed distance 2 - |p| for this parametrisation, whose s_u x s_v points inwards);
// then what a body that turns out bad answers: before the answer starts (wrong length, NaN in
// the first window, rate limits: the status, without reading the body), after it (NaN: an NDJSON
// error line and the connection kept; binary cut), a body that ends short, and a client that
// leaves in the middle of its body.
#include <doctest/doctest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "server_support.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

const std::string& kSphere = kSphereRadius2;

// n points at radii 1.6 .. 2.4 in directions away from the poles, as float64 triples.
std::vector<double> sphere_points(std::size_t n) {
  std::vector<double> p;
  p.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(n);
    const double u = 0.1 + 6.0 * t, v = 0.4 + 2.3 * std::fmod(t * 7919.0, 1.0), r = 1.6 + 0.1 * (i % 9);
    p.insert(p.end(), {r * std::sin(v) * std::cos(u), r * std::sin(v) * std::sin(u), r * std::cos(v)});
  }
  return p;
}

std::string request_head(const std::string& target, const std::string& accept, std::size_t length) {
  return "POST " + target + " HTTP/1.1\r\nHost: x\r\nAccept: " + accept +
         "\r\nContent-Type: application/octet-stream\r\nContent-Length: " + std::to_string(length) +
         "\r\n\r\n";
}

// A response read from a raw socket: head, and the body decoded from its chunks (or its
// Content-Length); `complete` false when the connection closed before the body's end.
struct Answer {
  int status = -1;
  std::string head, body;
  bool complete = false;
  bool close = false;  // Connection: close
};

class Reader {
 public:
  explicit Reader(int fd) : fd_(fd) {
    timeval tv{60, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  }
  // Reads until `data` holds `n` bytes from `at`; false when the connection ended first.
  bool fill(std::size_t n) {
    char buf[65536];
    while (data_.size() - at_ < n) {
      const auto k = ::recv(fd_, buf, sizeof buf, 0);
      if (k <= 0) return false;
      data_.append(buf, static_cast<std::size_t>(k));
    }
    return true;
  }
  bool line(std::string& out) {
    for (;;) {
      const auto end = data_.find("\r\n", at_);
      if (end != std::string::npos) {
        out = data_.substr(at_, end - at_);
        at_ = end + 2;
        return true;
      }
      if (!fill(data_.size() - at_ + 1)) return false;
    }
  }
  // The next response; `on_piece` sees the body as it arrives (the bytes so far).
  Answer next(const std::function<void(const std::string&)>& on_piece = nullptr) {
    Answer a;
    std::string l;
    if (!line(l)) return a;
    a.status = std::stoi(l.substr(9, 3));
    std::size_t length = 0;
    bool chunked = false;
    while (line(l) && !l.empty()) {
      a.head += l + "\n";
      if (l.rfind("Content-Length: ", 0) == 0) length = std::stoul(l.substr(16));
      if (l == "Transfer-Encoding: chunked") chunked = true;
      if (l == "Connection: close") a.close = true;
    }
    if (!chunked) {
      a.complete = fill(length);
      a.body = data_.substr(at_, length);
      at_ += a.body.size();
      return a;
    }
    for (;;) {
      if (!line(l)) return a;
      const std::size_t size = std::stoul(l, nullptr, 16);
      if (!fill(size + 2)) {
        a.body += data_.substr(at_);
        at_ = data_.size();
        return a;
      }
      a.body += data_.substr(at_, size);
      at_ += size + 2;
      if (on_piece) on_piece(a.body);
      if (size == 0) break;
    }
    a.complete = true;
    return a;
  }

 private:
  int fd_;
  std::string data_;
  std::size_t at_ = 0;
};

std::size_t ndjson_line_count(const std::string& body) {
  std::size_t n = 0;
  for (const char c : body) n += c == '\n';
  return n;
}

std::string last_line(const std::string& body) {
  const auto end = body.size() - 1, start = body.rfind('\n', end - 1);
  return body.substr(start == std::string::npos ? 0 : start + 1,
                     end - (start == std::string::npos ? 0 : start + 1));
}

}  // namespace

TEST_CASE(
    "streamed body: 200,000 points answered while they are sent, every answer the sphere's closed form") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kSphere);
  const std::size_t n = 200000;
  const std::vector<double> p = sphere_points(n);
  const std::string body = float64_bytes(p);
  const int fd = raw_connect(s.port());
  REQUIRE(send_all(fd, request_head("/v1/geometries/" + id + "/project?fields=foot_point,signed_distance",
                                    "application/octet-stream", body.size())) > 0);
  // The client sends half its points, then waits for 10,000 answers before it sends the rest: a
  // server that read the whole body before answering would never answer.
  std::atomic<bool> answered{false};
  std::atomic<std::size_t> sent{0};
  std::thread sender([&] {
    const std::size_t half = body.size() / 2;
    sent += send_all(fd, body.substr(0, half));
    for (int i = 0; i < 60000 && !answered.load(); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (answered.load()) sent += send_all(fd, body.substr(half));
  });
  Reader reader(fd);
  std::size_t sent_at_first_answers = 0;
  const Answer a = reader.next([&](const std::string& got) {
    if (!answered.load() && got.size() >= 10000 * 32) {
      sent_at_first_answers = sent.load();
      answered = true;
    }
  });
  sender.join();
  ::close(fd);
  REQUIRE(a.status == 200);
  CHECK(a.head.find("X-Footpoint-Record: foot_point:3,signed_distance:1") != std::string::npos);
  CHECK(sent_at_first_answers < body.size());
  REQUIRE(a.complete);
  REQUIRE(a.body.size() == n * 32);
  std::vector<double> x(n * 4);
  std::memcpy(x.data(), a.body.data(), a.body.size());
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double* q = &p[3 * i];
    const double r = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
    const double* rec = &x[4 * i];
    bool ok = std::fabs(rec[3] - (2.0 - r)) <= 1e-12;
    for (int k = 0; k < 3; ++k) ok = ok && std::fabs(rec[k] - 2.0 * q[k] / r) <= 1e-12;
    if (!ok && wrong++ < 5)
      FAIL_CHECK("point " << i << ": " << rec[0] << " " << rec[1] << " " << rec[2] << " " << rec[3]);
  }
  CHECK(wrong == 0);
}

TEST_CASE("streamed body: what is wrong before the answer starts is answered with its status, unread") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kSphere);
  const std::string target = "/v1/geometries/" + id + "/project";
  for (const std::string accept : {"application/octet-stream", "application/x-ndjson"}) {
    INFO(accept);
    // no whole number of points: known from Content-Length, answered before any byte of the body
    std::string r = raw_exchange(s.port(), request_head(target, accept, 2400001));
    CHECK(raw_status(r) == 400);
    CHECK(raw_json(r)["error"]["code"] == "wrong_shape");
    CHECK(raw_json(r)["error"]["message"].get<std::string>().find("2400001 bytes") != std::string::npos);
    CHECK(r.find("Connection: close") != std::string::npos);
    // a NaN in the first window of a long body: 400 naming it, before the rest is sent
    // (as much as the first window: more, left unread when the server closes, would reset the
    // connection, which may drop the answer before it is read)
    std::vector<double> p = sphere_points(100000);
    p[3 * 17 + 2] = std::nan("");
    const std::string body = float64_bytes(p);
    r = raw_exchange(s.port(), request_head(target, accept, body.size()) + body.substr(0, 8192 * 24));
    CHECK(raw_status(r) == 400);
    CHECK(raw_json(r)["error"]["code"] == "number_out_of_range");
    CHECK(raw_json(r)["error"]["field"] == "points[17][2]");
    CHECK(r.find("Connection: close") != std::string::npos);
  }
  CHECK(s.server().api().in_flight() == 0);
}

namespace {

// Sends `request` from a thread while it reads the answer to the server's end of stream; returns
// the answer, and in `ended` whether the server closed (not the 5 s receive timeout).
std::string exchange_to_end(int port, const std::string& request, bool& ended) {
  const int fd = raw_connect(port);
  timeval tv{5, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
  std::thread sender([&] { send_all(fd, request); });
  std::string response;
  char buf[4096];
  for (;;) {
    const auto n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) {
      ended = n == 0;
      break;
    }
    response.append(buf, static_cast<std::size_t>(n));
  }
  ::shutdown(fd, SHUT_RDWR);  // lets the sender's write fail if it still waits
  sender.join();
  ::close(fd);
  return response;
}

std::size_t answers_in(const std::string& response) {
  std::size_t n = 0;
  for (auto at = response.find("HTTP/1.1 "); at != std::string::npos; at = response.find("HTTP/1.1 ", at + 1))
    ++n;
  return n;
}

}  // namespace

TEST_CASE("a request refused before its body is read ends its connection: the body is no next request") {
  ServerConfig config;
  config.max_body_bytes = 1 << 20;
  TestServer s(config);
  auto c = s.client();
  // The bodies hold a request of their own; were the connection kept, the server would read it as
  // the next request and answer it (a smuggled request; thousands of 400s for binary points).
  const std::string smuggled = "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";
  std::string body;
  while (body.size() < (std::size_t{2} << 20)) body += smuggled;
  // over --max-body-bytes: 413 from Content-Length, in pre-routing
  bool ended = false;
  std::string r =
      exchange_to_end(s.port(),
                      "POST /v1/geometries HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
                      "Content-Length: " +
                          std::to_string(body.size()) + "\r\n\r\n" + body,
                      ended);
  CHECK(raw_status(r) == 413);
  CHECK(raw_json(r)["error"]["code"] == "body_too_large");
  CHECK(ended);
  CHECK(answers_in(r) == 1);
  // a NaN in the first window of a streamed body: 400 from the handler, the rest unread
  const std::string id = create(*c, kSphere);
  std::vector<double> p = sphere_points(20000);
  p[3 * 3 + 1] = std::nan("");
  std::string points = float64_bytes(p);
  points.replace(points.size() - 100 * smuggled.size(), 100 * smuggled.size(), [&] {
    std::string many;
    for (int i = 0; i < 100; ++i) many += smuggled;
    return many;
  }());
  for (const std::string accept : {"application/octet-stream", "application/x-ndjson"}) {
    INFO(accept);
    ended = false;
    r = exchange_to_end(
        s.port(), request_head("/v1/geometries/" + id + "/project", accept, points.size()) + points, ended);
    CHECK(raw_status(r) == 400);
    CHECK(raw_json(r)["error"]["field"] == "points[3][1]");
    CHECK(ended);
    CHECK(answers_in(r) == 1);
  }
  // the server goes on with the next connection
  auto ok = c->Get("/healthz");
  REQUIRE(ok);
  CHECK(ok->status == 200);
}

TEST_CASE("streamed body: the rate limit takes a stream's points from its Content-Length, before the body") {
  ServerConfig config;
  config.rate_limit = 1;  // a point a second: nothing refills during the test
  config.rate_burst = 150000;
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kSphere);
  const std::string target = "/v1/geometries/" + id + "/project";
  // over the burst: 413 from the length alone
  std::string r = raw_exchange(s.port(), request_head(target, "application/octet-stream", 160000 * 24));
  CHECK(raw_status(r) == 413);
  CHECK(raw_json(r)["error"]["code"] == "points_over_burst");
  // a stream of 100,000 takes them from the bucket at its start, so that the next one is refused
  // with 429 before its body is read
  const std::string body = float64_bytes(sphere_points(100000));
  auto ok = c->Post(target + "?fields=distance", httplib::Headers{{"Accept", "application/octet-stream"}},
                    body, "application/octet-stream");
  REQUIRE(ok);
  CHECK(ok->status == 200);
  CHECK(ok->body.size() == 100000 * 8);
  r = raw_exchange(s.port(), request_head(target, "application/octet-stream", body.size()));
  CHECK(raw_status(r) == 429);
  CHECK(raw_json(r)["error"]["code"] == "rate_limited");
  CHECK(r.find("Retry-After: ") != std::string::npos);
}

TEST_CASE("streamed body: a NaN after the answer started ends NDJSON with an error line, cuts binary") {
  TestServer s;
  auto c = s.client();
  const std::string id = create(*c, kSphere);
  const std::string target = "/v1/geometries/" + id + "/project?fields=signed_distance";
  const std::size_t n = 60000, bad = 41234;
  std::vector<double> p = sphere_points(n);
  p[3 * bad + 1] = -HUGE_VAL;
  const std::string body = float64_bytes(p);

  // NDJSON: the points before it answered, then the error; the rest of the body is read and
  // dropped, and the connection carries the next request
  int fd = raw_connect(s.port());
  std::thread sender([&] { send_all(fd, request_head(target, "application/x-ndjson", body.size()) + body); });
  Reader reader(fd);
  Answer a = reader.next();
  sender.join();
  REQUIRE(a.status == 200);
  REQUIRE(a.complete);
  CHECK_FALSE(a.close);
  CHECK(ndjson_line_count(a.body) == bad + 1);
  const json error = json::parse(last_line(a.body));
  CHECK(error["error"]["code"] == "number_out_of_range");
  CHECK(error["error"]["field"] == "points[41234][1]");
  CHECK(error["error"]["message"].get<std::string>().find("infinite") != std::string::npos);
  const json first = json::parse(a.body.substr(0, a.body.find('\n')));
  CHECK(first["signed_distance"].get<double>() == doctest::Approx(2.0 - 1.6).epsilon(1e-12));
  const std::string small = float64_bytes(sphere_points(10));
  send_all(fd, request_head(target, "application/x-ndjson", small.size()) + small);
  a = reader.next();
  CHECK(a.status == 200);
  CHECK(ndjson_line_count(a.body) == 11);
  ::close(fd);

  // binary: the records before it, then the answer is cut (no last chunk, the connection closes)
  fd = raw_connect(s.port());
  std::thread binary_sender(
      [&] { send_all(fd, request_head(target, "application/octet-stream", body.size()) + body); });
  Reader binary_reader(fd);
  a = binary_reader.next();
  binary_sender.join();
  ::close(fd);
  REQUIRE(a.status == 200);
  CHECK_FALSE(a.complete);
  CHECK(a.body.size() == bad * 8);
}

TEST_CASE("streamed body: a body that stops short cuts the answer after its last whole point") {
  ServerConfig config;
  config.io_timeout_s = 1;  // the read timeout: a client silent for 1 s has sent what it will
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kSphere);
  const std::size_t n = 50000, arrived = 30000;
  const std::string body = float64_bytes(sphere_points(n));
  for (const std::string accept : {"application/octet-stream", "application/x-ndjson"}) {
    INFO(accept);
    const int fd = raw_connect(s.port());
    // the points up to `arrived` and half of the next one, then nothing (the connection open)
    send_all(fd, request_head("/v1/geometries/" + id + "/project?fields=distance", accept, body.size()) +
                     body.substr(0, arrived * 24 + 12));
    Reader reader(fd);
    const Answer a = reader.next();
    ::close(fd);
    REQUIRE(a.status == 200);
    CHECK_FALSE(a.complete);
    if (accept == "application/octet-stream")
      CHECK(a.body.size() == arrived * 8);
    else
      CHECK(ndjson_line_count(a.body) == arrived);
  }
  CHECK(s.server().api().in_flight() == 0);
}

TEST_CASE("streamed body: a client that leaves in the middle of its body stops the work") {
  ServerConfig config;
  config.threads = 1;
  config.max_body_bytes = 64 << 20;
  TestServer s(config);
  auto c = s.client();
  const std::string id = create(*c, kSphere);
  const std::size_t n = 2000000;  // 48 MB announced; 100,000 points sent
  const std::string part = float64_bytes(sphere_points(100000));
  const int fd = raw_connect(s.port());
  send_all(fd, request_head("/v1/geometries/" + id + "/project", "application/octet-stream", n * 24));
  send_all(fd, part);
  Reader reader(fd);
  std::string l;
  REQUIRE(reader.line(l));
  CHECK(l.rfind("HTTP/1.1 200", 0) == 0);
  ::shutdown(fd, SHUT_RDWR);
  ::close(fd);
  CHECK(wait_until_idle(s.server()));
}
