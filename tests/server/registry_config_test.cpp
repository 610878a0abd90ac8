// The registry's settings: redis:// URLs (a password in one is refused without being repeated),
// the password from the environment or a file, never both.
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "config.hpp"
#include "redis/redis_client.hpp"

using namespace footpoint;
using namespace footpoint::server;

TEST_CASE("registry URLs: host, port, database, ACL user; a password is refused") {
  const auto e = redis::parse_url("redis://redis:6380/2");
  CHECK(e.host == "redis");
  CHECK(e.port == 6380);
  CHECK(e.db == 2);
  CHECK(e.user.empty());
  const auto d = redis::parse_url("redis://footpoint@10.0.0.7");
  CHECK(d.host == "10.0.0.7");
  CHECK(d.port == 6379);
  CHECK(d.db == 0);
  CHECK(d.user == "footpoint");
  const auto v6 = redis::parse_url("redis://[::1]:7000/");
  CHECK(v6.host == "::1");
  CHECK(v6.port == 7000);
  for (const char* bad : {"http://redis:6379", "redis://", "redis://:6379", "redis://h:0", "redis://h:65536",
                          "redis://h:x", "redis://h/db", "redis://[::1", "redis://@h"}) {
    INFO(bad);
    CHECK_THROWS_AS(redis::parse_url(bad), std::invalid_argument);
  }
  try {
    redis::parse_url("redis://user:s3cret-Pw@redis:6379/0");
    FAIL("accepted a password in the URL");
  } catch (const std::invalid_argument& error) {
    CHECK(std::string(error.what()).find("s3cret-Pw") == std::string::npos);
    CHECK(std::string(error.what()).find("FOOTPOINT_REGISTRY_PASSWORD") != std::string::npos);
  }
}

TEST_CASE("the registry password comes from the environment or a file, not both") {
  bool help = false;
  const char* argv0[] = {"footpoint-server"};
  std::map<std::string, std::string> vars = {{"FOOTPOINT_REGISTRY_URL", "redis://r:6379/0"},
                                             {"FOOTPOINT_REGISTRY_PASSWORD", "from-env"}};
  auto env = [&](const char* name) -> const char* {
    auto it = vars.find(name);
    return it == vars.end() ? nullptr : it->second.c_str();
  };
  ServerConfig c = load_config(1, argv0, env, help);
  CHECK(c.registry_url == "redis://r:6379/0");
  CHECK(c.registry_password == "from-env");
  CHECK(c.registry_timeout.count() == 250);
  CHECK(c.registry_ttl.count() == 604800);

  const std::string file =
      (std::filesystem::temp_directory_path() / "footpoint-registry-password-test").string();
  std::ofstream(file) << "from-file\n";
  vars.erase("FOOTPOINT_REGISTRY_PASSWORD");
  const std::string flag = "--registry-password-file=" + file;
  const char* argv1[] = {"footpoint-server", flag.c_str(), "--registry-ttl-s", "0"};
  c = load_config(4, argv1, env, help);
  CHECK(c.registry_password == "from-file");  // the trailing newline dropped
  CHECK(c.registry_ttl.count() == 0);
  vars["FOOTPOINT_REGISTRY_PASSWORD"] = "from-env";
  CHECK_THROWS_AS(load_config(4, argv1, env, help), ConfigError);
  std::remove(file.c_str());
  vars.erase("FOOTPOINT_REGISTRY_PASSWORD");
  CHECK_THROWS_AS(load_config(4, argv1, env, help), ConfigError);  // the file is gone

  const char* with_password[] = {"footpoint-server", "--registry-url", "redis://u:pw@r:6379"};
  CHECK_THROWS_AS(load_config(3, with_password, nullptr, help), ConfigError);
  const char* no_flag[] = {"footpoint-server", "--registry-password", "x"};  // environment only
  CHECK_THROWS_AS(load_config(3, no_flag, nullptr, help), ConfigError);
}

TEST_CASE("FOOTPOINT_* variables that are no setting's are named, the others not") {
  const char* environment[] = {"FOOTPOINT_PROT=1",
                               "FOOTPOINT_PORT=8080",
                               "PATH=/usr/bin",
                               "FOOTPOINT_THREADS=0",
                               "FOOTPOINT_REGISTRY_PASSWORD=x",
                               "FOOTPOINT_max_points=3",
                               "FOOTPOINTLESS=1",
                               nullptr};
  CHECK(unknown_environment(environment) ==
        std::vector<std::string>{"FOOTPOINT_PROT", "FOOTPOINT_max_points"});
  const char* none[] = {nullptr};
  CHECK(unknown_environment(none).empty());
}
