// The process metrics Prometheus' client libraries export under the same names, read from the
// kernel (Linux /proc) when /metrics is scraped:
//   process_cpu_seconds_total        counter  user + system CPU time
//   process_resident_memory_bytes    gauge    resident set size
//   process_virtual_memory_bytes     gauge    virtual memory size
//   process_open_fds                 gauge    open file descriptors
//   process_max_fds                  gauge    the limit on them (RLIMIT_NOFILE)
//   process_start_time_seconds       gauge    start time, seconds since the Unix epoch
// A value the kernel does not give is left out.
#pragma once
#include <string>

namespace footpoint::server {

void render_process_metrics(std::string& out);

}  // namespace footpoint::server
