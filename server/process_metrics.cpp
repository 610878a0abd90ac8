#include "process_metrics.hpp"

#include <dirent.h>
#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "prometheus_text.hpp"

namespace footpoint::server {

namespace {

// The fields of /proc/self/stat after the command name (whose parentheses may hold anything):
// fields[0] is the state, field k of proc(5) (1-based) is fields[k - 3].
std::vector<std::string> stat_fields() {
  std::ifstream in("/proc/self/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = text.rfind(')');
  std::vector<std::string> fields;
  if (close == std::string::npos) return fields;
  std::istringstream rest(text.substr(close + 1));
  for (std::string f; rest >> f;) fields.push_back(f);
  return fields;
}

// The boot time, seconds since the Unix epoch ("btime" of /proc/stat), or -1.
long long boot_time() {
  std::ifstream in("/proc/stat");
  for (std::string key; in >> key;) {
    if (key == "btime") {
      long long t = -1;
      in >> t;
      return t;
    }
    in.ignore(1 << 20, '\n');
  }
  return -1;
}

}  // namespace

void render_process_metrics(std::string& out) {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) {
    const double seconds = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
                           static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) * 1e-6;
    header(out, "process_cpu_seconds_total", "counter", "Total user and system CPU time spent in seconds.");
    line(out, "process_cpu_seconds_total", "", seconds);
  }
  const long page = sysconf(_SC_PAGESIZE);
  {
    std::ifstream statm("/proc/self/statm");
    double pages_virtual = 0, pages_resident = 0;
    if (statm >> pages_virtual >> pages_resident) {
      header(out, "process_virtual_memory_bytes", "gauge", "Virtual memory size in bytes.");
      line(out, "process_virtual_memory_bytes", "", pages_virtual * static_cast<double>(page));
      header(out, "process_resident_memory_bytes", "gauge", "Resident memory size in bytes.");
      line(out, "process_resident_memory_bytes", "", pages_resident * static_cast<double>(page));
    }
  }
  if (DIR* dir = opendir("/proc/self/fd")) {
    double open = 0;
    while (const dirent* entry = readdir(dir))
      if (entry->d_name[0] != '.') ++open;
    closedir(dir);
    header(out, "process_open_fds", "gauge", "Number of open file descriptors.");
    line(out, "process_open_fds", "", open - 1);  // less the one reading the directory
  }
  rlimit files{};
  if (getrlimit(RLIMIT_NOFILE, &files) == 0 && files.rlim_cur != RLIM_INFINITY) {
    header(out, "process_max_fds", "gauge", "Maximum number of open file descriptors.");
    line(out, "process_max_fds", "", static_cast<double>(files.rlim_cur));
  }
  const std::vector<std::string> fields = stat_fields();
  const long long boot = boot_time();
  const long ticks = sysconf(_SC_CLK_TCK);
  if (fields.size() > 19 && boot >= 0 && ticks > 0) {
    const double start = static_cast<double>(boot) + std::stod(fields[19]) / static_cast<double>(ticks);
    header(out, "process_start_time_seconds", "gauge",
           "Start time of the process since unix epoch in seconds.");
    line(out, "process_start_time_seconds", "", start);
  }
}

}  // namespace footpoint::server
