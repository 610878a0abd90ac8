// What an operator sees: one version everywhere (CMake, openapi.yaml, --version, the start-up
// line, /metrics, the image's label and tags), the process_* metrics, and the log lines of the
// installed binary itself (started as a child process): the start-up line with the version and
// the settings in effect, request lines with JSON numbers, durations to the microsecond and the
// error's code, the shutdown lines and exit code 0 on SIGTERM.
#include <doctest/doctest.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "openapi_text.hpp"
#include "server_support.hpp"
#include "version.hpp"

using namespace footpoint::server;
using namespace footpoint::server::testing;
using json = nlohmann::json;

namespace {

// footpoint-server run as a child process, its stdout read line by line.
class ServerProcess {
 public:
  explicit ServerProcess(const std::vector<std::string>& args) {
    int fds[2];
    REQUIRE(::pipe(fds) == 0);
    pid_ = ::fork();
    REQUIRE(pid_ >= 0);
    if (pid_ == 0) {
      ::dup2(fds[1], 1);
      ::close(fds[0]);
      ::close(fds[1]);
      std::vector<char*> argv;
      std::string binary = FOOTPOINT_SERVER_BINARY;
      argv.push_back(binary.data());
      std::vector<std::string> copies = args;
      for (auto& a : copies) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(binary.c_str(), argv.data());
      ::_exit(127);
    }
    ::close(fds[1]);
    fd_ = fds[0];
  }
  ~ServerProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    ::close(fd_);
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  // The next line of output, or "" after `timeout` or at the end.
  std::string line(std::chrono::milliseconds timeout = std::chrono::milliseconds(10000)) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    for (;;) {
      if (const auto nl = buffer_.find('\n'); nl != std::string::npos) {
        std::string l = buffer_.substr(0, nl);
        buffer_.erase(0, nl + 1);
        return l;
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now())
              .count();
      pollfd p{fd_, POLLIN, 0};
      if (left <= 0 || ::poll(&p, 1, static_cast<int>(left)) <= 0) return "";
      char buf[4096];
      const auto n = ::read(fd_, buf, sizeof buf);
      if (n <= 0) return "";
      buffer_.append(buf, static_cast<std::size_t>(n));
    }
  }
  // The next log line whose "msg" is `msg` (other lines are skipped).
  json event(const std::string& msg) {
    for (std::string l; !(l = line()).empty();) {
      json j = json::parse(l, nullptr, false);
      if (!j.is_discarded() && j.value("msg", "") == msg) return j;
    }
    FAIL("no log line " << msg);
    return {};
  }
  // Sends `sig` and returns the exit status.
  int stop(int sig) {
    ::kill(pid_, sig);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string buffer_;
};

std::string run_output(const std::string& command) {
  std::string out;
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE(pipe);
  char buf[512];
  while (std::fgets(buf, sizeof buf, pipe)) out += buf;
  CHECK(::pclose(pipe) == 0);
  return out;
}

// The value of a metric_value line "name value" (or "name{labels} value"); NaN when absent.
double metric_value(const std::string& text, const std::string& name) {
  const std::regex line("^" + name + " ([0-9.e+-]+)$", std::regex::multiline);
  std::smatch m;
  return std::regex_search(text, m, line) ? std::stod(m[1]) : std::nan("");
}

}  // namespace

TEST_CASE("one version: CMake, openapi.yaml, --version, /metrics, the image's label and tags") {
  const std::string version(kVersion);
  CHECK(std::regex_match(version, std::regex("[0-9]+\\.[0-9]+\\.[0-9]+")));
  CHECK(openapi_text().find("\n  version: " + version + "\n") != std::string::npos);
  CHECK(run_output(std::string(FOOTPOINT_SERVER_BINARY) + " --version") ==
        "footpoint-server " + version + "\n");
  CHECK(run_output(std::string(FOOTPOINT_SERVER_BINARY) + " --help").find("--version") != std::string::npos);

  TestServer s;
  auto c = s.client();
  auto r = c->Get("/metrics");
  REQUIRE(r);
  CHECK(r->body.find("\nfootpoint_build_info{version=\"" + version + "\"} 1\n") != std::string::npos);

  const std::string cmake = read_text_file(FOOTPOINT_SOURCE_DIR "/CMakeLists.txt");
  CHECK(cmake.find("project(footpoint VERSION " + version + " ") != std::string::npos);
  const std::string dockerfile = read_text_file(FOOTPOINT_SOURCE_DIR "/deploy/Dockerfile");
  CHECK(dockerfile.find("org.opencontainers.image.version=\"" + version + "\"") != std::string::npos);
  for (const char* file :
       {"/deploy/Dockerfile", "/deploy/compose.yaml", "/deploy/k8s/deployment.yaml", "/docs/operations.md"}) {
    CAPTURE(file);
    const std::string text = read_text_file(std::string(FOOTPOINT_SOURCE_DIR) + file);
    const std::regex tag("footpoint:([0-9][0-9.]*)");
    int tags = 0;
    for (auto it = std::sregex_iterator(text.begin(), text.end(), tag); it != std::sregex_iterator();
         ++it, ++tags)
      CHECK((*it)[1] == version);
    CHECK(tags > 0);
  }
}

TEST_CASE("process metrics as Prometheus' clients name them") {
  TestServer s;
  auto c = s.client();
  auto r = c->Get("/metrics");
  REQUIRE(r);
  const std::string& m = r->body;
  for (const char* name :
       {"process_cpu_seconds_total", "process_resident_memory_bytes", "process_virtual_memory_bytes",
        "process_open_fds", "process_max_fds", "process_start_time_seconds"}) {
    CAPTURE(name);
    CHECK(m.find(std::string("# TYPE ") + name + " ") != std::string::npos);
  }
  CHECK(metric_value(m, "process_cpu_seconds_total") > 0.0);
  CHECK(metric_value(m, "process_resident_memory_bytes") > 1e6);
  CHECK(metric_value(m, "process_virtual_memory_bytes") >= metric_value(m, "process_resident_memory_bytes"));
  CHECK(metric_value(m, "process_open_fds") >= 3.0);  // stdin, stdout, stderr, the sockets
  CHECK(metric_value(m, "process_max_fds") >= metric_value(m, "process_open_fds"));
  const double now =
      std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  const double start = metric_value(m, "process_start_time_seconds");
  CHECK(start <= now + 1.0);
  CHECK(start > now - 3600.0);  // this test process started within the hour
}

TEST_CASE("the binary's log: start-up line with version and settings, request lines, shutdown") {
  ServerProcess server({"--host", "127.0.0.1", "--port", "0", "--threads", "2", "--log-level", "info"});
  const json listening = server.event("listening");
  CHECK(listening["version"] == std::string(kVersion));
  REQUIRE(listening["port"].is_number_integer());
  CHECK(listening["threads"] == 2);
  CHECK(listening["connection_threads"] == 128);
  const json& settings = listening["settings"];
  REQUIRE(settings.is_object());
  CHECK(settings["host"] == "127.0.0.1");
  CHECK(settings["threads"] == 2);
  CHECK(settings["max-body-bytes"] == 16777216);
  CHECK(settings["max-inflight"] == 112);           // 0: 7/8 of the connection threads
  CHECK(settings["compile-deadline-ms"] == 30000);  // 0: the request deadline
  CHECK(settings["ui"] == "on");
  CHECK(settings["registry-url"] == "");
  CHECK_FALSE(settings.contains("registry-password"));
  // every flag of --help, and nothing else
  const std::string help = run_output(std::string(FOOTPOINT_SERVER_BINARY) + " --help");
  const std::regex flag("^  --([a-z-]+) +FOOTPOINT_", std::regex::multiline);
  std::size_t flags = 0;
  for (auto it = std::sregex_iterator(help.begin(), help.end(), flag); it != std::sregex_iterator();
       ++it, ++flags)
    CHECK(settings.contains((*it)[1].str()));
  CHECK(settings.size() == flags);

  httplib::Client c("127.0.0.1", listening["port"].get<int>());
  auto r = c.Get("/v1/geometries/0123456789abcdef0123456789abcdef", {{"X-Request-Id", "ops-404"}});
  REQUIRE(r);
  CHECK(r->status == 404);
  r = c.Get("/healthz", {{"X-Request-Id", "ops-200"}});
  REQUIRE(r);
  CHECK(r->status == 200);
  const std::string garbage = raw_exchange(listening["port"].get<int>(), "GARBAGE\r\n\r\n");
  CHECK(raw_status(garbage) == 400);

  // The three request lines, in whatever order the connection threads wrote them.
  json missing, fine, malformed;
  for (int i = 0; i < 3; ++i) {
    const json e = server.event("request");
    const std::string id = e.value("request_id", "");
    (id == "ops-404" ? missing : id == "ops-200" ? fine : malformed) = e;
  }
  CHECK(missing["request_id"] == "ops-404");
  CHECK(missing["status"] == 404);
  CHECK(missing["code"] == "geometry_not_found");
  CHECK(missing["points"] == 0);
  CHECK(missing["body_bytes"] == 0);
  REQUIRE(missing["duration_ms"].is_number());
  const double ms = missing["duration_ms"];
  CHECK(std::round(ms * 1e3) / 1e3 == ms);  // microseconds
  CHECK(fine["request_id"] == "ops-200");
  CHECK(fine["status"] == 200);
  CHECK_FALSE(fine.contains("code"));
  CHECK(malformed["status"] == 400);
  CHECK(malformed["code"] == "bad_request");

  CHECK(server.stop(SIGTERM) == 0);
  // The lines written before the exit.
  CHECK(server.event("shutting down")["signal"] == "SIGTERM");
  server.event("stopped");
}

TEST_CASE("SIGTERM: idle keep-alive connections close at once, the request in flight finishes, exit 0") {
  ServerProcess server(
      {"--host", "127.0.0.1", "--port", "0", "--threads", "1", "--keep-alive-timeout-s", "60"});
  const int port = server.event("listening")["port"];
  httplib::Client c("127.0.0.1", port);
  c.set_keep_alive(true);
  c.set_read_timeout(120, 0);
  auto r = c.Post(
      "/v1/geometries",
      R"J({"type":"parametric_surface","x":"u+v","y":"sin(u)+2*cos(v)","z":"sin(u+v)","domain":{"u":[-25,25],"v":[-25,25]}})J",
      "application/json");
  REQUIRE(r);
  REQUIRE(r->status == 201);
  const std::string id = json::parse(r->body)["geometry_id"];
  std::string batch = R"J({"points":[)J";
  for (int i = 0; i < 20000; ++i)
    batch += (i ? ",[" : "[") + std::to_string(-9 + 18.0 * (i % 97) / 97) + "," +
             std::to_string(-9 + 18.0 * (i % 89) / 89) + "," + std::to_string(-9 + 18.0 * (i % 83) / 83) +
             "]";
  batch += R"J(],"options":{"certify":false}})J";  // the search alone: a while, not minutes under a sanitizer
  httplib::Result in_flight{nullptr, httplib::Error::Unknown};
  std::thread slow([&] {
    httplib::Client b("127.0.0.1", port);
    b.set_read_timeout(120, 0);
    in_flight = b.Post("/v1/geometries/" + id + "/project", batch, "application/json");
  });
  // `c` stays open, idle: it waits for the batch to be in flight.
  for (int i = 0; i < 2000; ++i) {
    auto m = c.Get("/metrics");
    REQUIRE(m);
    if (m->body.find("\nfootpoint_http_requests_in_flight 1\n") != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const auto start = std::chrono::steady_clock::now();
  const int code = server.stop(SIGTERM);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  slow.join();
  CHECK(code == 0);
  CHECK(seconds <
        40.0);  // the batch's time (longer on a loaded machine), not the idle connection's 60 s keep-alive
  REQUIRE(in_flight);
  CHECK(in_flight->status == 200);
  CHECK(json::parse(in_flight->body)["results"].size() == 20000);
  MESSAGE("SIGTERM to exit with an idle keep-alive connection and a 20,000-point batch in flight: " << seconds
                                                                                                    << " s");
}

TEST_CASE("a misspelled FOOTPOINT_* variable is warned about at start, by name") {
  REQUIRE(::setenv("FOOTPOINT_PROT", "1", 1) == 0);
  ServerProcess server({"--host", "127.0.0.1", "--port", "0", "--threads", "1", "--log-level", "info"});
  ::unsetenv("FOOTPOINT_PROT");
  const json warning = server.event("unknown environment variable");
  CHECK(warning["level"] == "warning");
  CHECK(warning["variable"] == "FOOTPOINT_PROT");
  CHECK(server.event("listening")["port"].is_number_integer());
  CHECK(server.stop(SIGTERM) == 0);
}
