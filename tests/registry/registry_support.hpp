// Real processes for the registry tests: a redis-server on 127.0.0.1 at a free port (no
// persistence, its own password, its own directory) and footpoint-server processes configured
// through their environment, as a deployment runs them. Each is stopped by its destructor.
#pragma once
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <doctest/doctest.h>
#include <httplib.h>
#include <nlohmann/json.hpp>

#include "redis/redis_client.hpp"

extern char** environ;

namespace footpoint::registry_testing {

using Clock = std::chrono::steady_clock;
using json = nlohmann::json;
using namespace std::chrono_literals;

// redis-server from FOOTPOINT_REDIS_SERVER, else /usr/bin or /usr/local/bin; empty when missing.
inline std::string redis_server_path() {
  if (const char* p = std::getenv("FOOTPOINT_REDIS_SERVER"); p && *p) return ::access(p, X_OK) == 0 ? p : "";
  for (const char* p : {"/usr/bin/redis-server", "/usr/local/bin/redis-server"})
    if (::access(p, X_OK) == 0) return p;
  return {};
}

inline std::string redis_cli_path() {
  const std::string server = redis_server_path();
  const std::string cli = std::filesystem::path(server).parent_path() / "redis-cli";
  return ::access(cli.c_str(), X_OK) == 0 ? cli : std::string();
}

inline int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  REQUIRE(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0);
  socklen_t len = sizeof addr;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
  ::close(fd);
  return ntohs(addr.sin_port);
}

inline std::string make_temp_dir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "footpoint-registry.XXXXXX").string();
  REQUIRE(::mkdtemp(pattern.data()) != nullptr);
  return pattern;
}

// A child process: argv, environment additions, stdout and stderr to `log`.
class Process {
 public:
  Process(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
          const std::string& log) {
    std::vector<std::string> env_strings;
    for (char** e = environ; *e; ++e) {
      const std::string entry = *e;
      if (entry.rfind("FOOTPOINT_", 0) != 0) env_strings.push_back(entry);
    }
    for (const auto& [k, v] : env) env_strings.push_back(k + "=" + v);
    std::vector<char*> args, envp;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    for (auto& e : env_strings) envp.push_back(e.data());
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    const int rc = posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    REQUIRE_MESSAGE(rc == 0, "cannot start " << argv[0]);
  }
  ~Process() { stop(SIGKILL); }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;

  // Sends `sig` and waits for the exit (SIGKILL after 10 s); the exit status, or -1.
  int stop(int sig = SIGTERM) {
    if (pid_ <= 0) return -1;
    ::kill(pid_, sig);
    int status = 0;
    for (int i = 0; i < 1000; ++i) {
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
      std::this_thread::sleep_for(10ms);
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return -1;
  }
  void signal(int sig) const { ::kill(pid_, sig); }
  bool running() const { return pid_ > 0 && ::waitpid(pid_, nullptr, WNOHANG) == 0; }

 private:
  pid_t pid_ = -1;
};

// A redis-server of the test's own: loopback, a free port, a password, no persistence.
class Redis {
 public:
  explicit Redis(std::string password = "test-secret-7f3a", int port = 0)
      : password_(std::move(password)), port_(port ? port : free_port()) {
    dir_ = make_temp_dir();
    start();
  }
  ~Redis() {
    process_.reset();
    std::filesystem::remove_all(dir_);
  }

  void start() {
    process_ = std::make_unique<Process>(
        std::vector<std::string>{redis_server_path(), "--port", std::to_string(port_), "--bind", "127.0.0.1",
                                 "--save", "", "--appendonly", "no", "--dir", dir_, "--requirepass",
                                 password_, "--enable-debug-command", "local", "--protected-mode", "yes"},
        std::map<std::string, std::string>{}, dir_ + "/redis.log");
    for (int i = 0; i < 500 && process_->running(); ++i) {
      try {
        if (command({"PING"}, "", 200ms).str == "PONG") return;
      } catch (const redis::Error&) {
      }
      std::this_thread::sleep_for(10ms);
    }
    std::ifstream log(dir_ + "/redis.log");
    std::stringstream ss;
    ss << log.rdbuf();
    FAIL("redis-server did not start on port " << port_ << ":\n" << ss.str());
  }
  // SIGKILL: gone at once, like a crashed or lost Redis; start() brings an empty one back.
  void kill() { process_.reset(); }

  // One command on a new connection (as the given password, default the server's).
  redis::Reply command(const std::vector<std::string_view>& args, const std::string& password = "",
                       std::chrono::milliseconds timeout = 2000ms) {
    redis::Connection c;
    redis::Endpoint e;
    e.host = "127.0.0.1";
    e.port = port_;
    e.password = password.empty() ? password_ : password;
    const auto deadline = Clock::now() + timeout;
    c.open("127.0.0.1", e, deadline);
    return c.command(args, deadline);
  }

  int port() const { return port_; }
  const std::string& password() const { return password_; }
  std::string url() const { return "redis://127.0.0.1:" + std::to_string(port_) + "/0"; }

 private:
  std::string password_;
  int port_;
  std::string dir_;
  std::unique_ptr<Process> process_;
};

// A footpoint-server process (the built binary), configured by environment variables.
class Server {
 public:
  explicit Server(std::map<std::string, std::string> env) : port_(free_port()) {
    dir_ = make_temp_dir();
    env["FOOTPOINT_HOST"] = "127.0.0.1";
    env["FOOTPOINT_PORT"] = std::to_string(port_);
    env.try_emplace("FOOTPOINT_THREADS", "2");
    env.try_emplace("FOOTPOINT_CONNECTION_THREADS", "32");
    env.try_emplace("FOOTPOINT_LOG_LEVEL", "info");
    process_ = std::make_unique<Process>(std::vector<std::string>{FOOTPOINT_SERVER_BINARY}, env, log_path());
    for (int i = 0; i < 500; ++i) {
      if (auto r = client()->Get("/healthz"); r && r->status == 200) return;
      REQUIRE_MESSAGE(process_->running(), "footpoint-server exited at start:\n" << log());
      std::this_thread::sleep_for(10ms);
    }
    FAIL("footpoint-server did not answer /healthz:\n" << log());
  }
  ~Server() {
    process_.reset();
    std::filesystem::remove_all(dir_);
  }

  std::unique_ptr<httplib::Client> client() const {
    auto c = std::make_unique<httplib::Client>("127.0.0.1", port_);
    c->set_connection_timeout(10, 0);
    c->set_read_timeout(30, 0);
    c->set_keep_alive(true);
    c->set_tcp_nodelay(true);
    return c;
  }
  int stop() { return process_->stop(SIGTERM); }
  std::string log_path() const { return dir_ + "/server.log"; }
  std::string log() const {
    std::ifstream in(log_path());
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  int port() const { return port_; }

 private:
  int port_;
  std::string dir_;
  std::unique_ptr<Process> process_;
};

// The environment of a replica on `redis`.
inline std::map<std::string, std::string> replica_env(const Redis& redis,
                                                      std::map<std::string, std::string> more = {}) {
  more.try_emplace("FOOTPOINT_REGISTRY_URL", redis.url());
  more.try_emplace("FOOTPOINT_REGISTRY_PASSWORD", redis.password());
  more.try_emplace("FOOTPOINT_REGISTRY_TIMEOUT_MS", "200");
  return more;
}

struct Answer {
  int status = -1;
  json body;
  std::string retry_after;
  double seconds = 0.0;  // wall time of the request
};

inline Answer send(httplib::Client& c, const std::string& method, const std::string& path,
                   const std::string& body = "") {
  const auto start = Clock::now();
  httplib::Result r = method == "GET"      ? c.Get(path.c_str())
                      : method == "DELETE" ? c.Delete(path.c_str())
                                           : c.Post(path.c_str(), body, "application/json");
  Answer a;
  a.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  REQUIRE_MESSAGE(r, method << " " << path << ": no response");
  a.status = r->status;
  if (!r->body.empty() && r->get_header_value("Content-Type").rfind("application/json", 0) == 0)
    a.body = json::parse(r->body);
  a.retry_after = r->get_header_value("Retry-After");
  return a;
}

// The value of one sample of /metrics (0 when absent).
inline double metric(httplib::Client& c, const std::string& series) {
  auto r = c.Get("/metrics");
  REQUIRE(r);
  const auto at = r->body.find("\n" + series + " ");
  if (at == std::string::npos) return 0.0;
  return std::stod(r->body.substr(at + series.size() + 2));
}

// Polls `done` every 10 ms for at most `limit`; true when it held.
template <class F>
bool eventually(F&& done, std::chrono::milliseconds limit = 3000ms) {
  const auto end = Clock::now() + limit;
  while (Clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return done();
}

inline std::string surface(const std::string& z) {
  return R"({"type":"parametric_surface","x":"u","y":"v","z":")" + z +
         R"(","domain":{"u":[-2,2],"v":[-2,2]}})";
}

inline const char* const kPoints = R"({"points":[[0.3,0.2,1],[1.5,-1,0.25],[-2,2,3],[0,0,-1]]})";

}  // namespace footpoint::registry_testing
