// The JSON layer's cost per point for a 10,000-point batch: reading the request body (pull
// reader, std::from_chars) and writing the response (std::to_chars), against nlohmann-json for
// reference (its DOM, and its SAX interface collecting the numbers), and the response trimmed by
// "fields" to foot_point and distance. Target (issue 5):
// parse + serialize <= 1 us per point. Prints medians of 31 runs.
//   build/bench/json_bench [points]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench_args.hpp"
#include "json_writer.hpp"
#include "project_request.hpp"
#include "result_json.hpp"

using namespace footpoint;
using namespace footpoint::server;
using Clock = std::chrono::steady_clock;

namespace {

template <class F>
double median_ns_per_point(F&& f, std::size_t points, int runs = 31) {
  std::vector<double> t;
  for (int r = 0; r < runs; ++r) {
    const auto start = Clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::nano>(Clock::now() - start).count() /
                static_cast<double>(points));
  }
  std::nth_element(t.begin(), t.begin() + runs / 2, t.end());
  return t[runs / 2];
}

volatile std::size_t sink;  // keeps results alive

// nlohmann's SAX interface at its cheapest: every number of the body appended to one vector, no
// field names, shapes or errors checked (a request reader on it would do more, not less).
struct CollectNumbers : nlohmann::json::json_sax_t {
  std::vector<double>* numbers;
  explicit CollectNumbers(std::vector<double>* out) : numbers(out) {}
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t x) override {
    return numbers->push_back(static_cast<double>(x)), true;
  }
  bool number_unsigned(number_unsigned_t x) override {
    return numbers->push_back(static_cast<double>(x)), true;
  }
  bool number_float(number_float_t x, const string_t&) override { return numbers->push_back(x), true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception&) override {
    return false;
  }
};

}  // namespace

int main(int argc, char** argv) {
  constexpr const char* kUsage = "usage: json_bench [points, default 10000]\n";
  bench::exit_on_help(argc, argv, kUsage);
  if (argc > 2) bench::refuse_argument(argv[0], "unexpected argument", argv[2], kUsage);
  const std::size_t n =
      argc > 1 ? static_cast<std::size_t>(bench::count_argument(argv[0], argv[1], kUsage)) : 10000;
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> d(-30.0, 30.0);

  // A request as a client sends it: full-precision coordinates.
  JsonWriter w(n * 64);
  w.begin_object();
  w.key("points");
  w.begin_array();
  for (std::size_t i = 0; i < n; ++i) {
    w.begin_array();
    for (int k = 0; k < 3; ++k) w.number(d(rng));
    w.end_array();
  }
  w.end_array();
  w.end_object();
  const std::string body = w.take();

  // Results as the solvers fill them: full-precision numbers everywhere.
  std::vector<ProjectionResult> results(n);
  for (auto& r : results) {
    r.foot = {d(rng), d(rng), d(rng)};
    r.params = {d(rng), d(rng)};
    r.distance = std::abs(d(rng));
    r.summary.method = "auto";
    r.summary.status = Status::converged;
    r.summary.iterations = 5;
    r.summary.step_norm = 1.2345678901234567e-9;
    r.summary.orthogonality = {3.2e-17, 1.1e-16};
    r.summary.starts = 3;
    r.summary.location = Location::interior;
  }

  const double parse =
      median_ns_per_point([&] { sink = read_project_request(body, false, n).coords.size(); }, n);
  std::size_t response_bytes = 0;
  const double write = median_ns_per_point(
      [&] {
        const std::string out = project_response("8ca9f0e028af69e7a85f954715c1f082", results, false,
                                                 ResultFields{ResultFields::kPlain}, 1.0);
        response_bytes = out.size();
        sink = out.size();
      },
      n);
  const std::string response = project_response("8ca9f0e028af69e7a85f954715c1f082", results, false,
                                                ResultFields{ResultFields::kPlain}, 1.0);
  // "fields": ["foot_point", "distance"]
  const ResultFields trimmed{ResultFields::foot_point | ResultFields::distance};
  std::size_t trimmed_bytes = 0;
  const double write_trimmed = median_ns_per_point(
      [&] {
        const std::string out =
            project_response("8ca9f0e028af69e7a85f954715c1f082", results, false, trimmed, 1.0);
        trimmed_bytes = out.size();
        sink = out.size();
      },
      n);
  const double sax_parse = median_ns_per_point(
      [&] {
        std::vector<double> numbers;
        numbers.reserve(3 * n);
        CollectNumbers collect(&numbers);
        nlohmann::json::sax_parse(body, &collect);
        sink = numbers.size();
      },
      n, 11);
  const double dom_parse =
      median_ns_per_point([&] { sink = nlohmann::json::parse(body)["points"].size(); }, n, 11);
  const double dom_write =
      median_ns_per_point([&] { sink = nlohmann::json::parse(response).dump().size(); }, n, 11) -
      median_ns_per_point([&] { sink = nlohmann::json::parse(response).size(); }, n, 11);

  std::printf("json_bench: %zu points, request %zu bytes, response %zu bytes (medians of 31 runs)\n", n,
              body.size(), response_bytes);
  std::printf("  parse request  (pull reader + from_chars): %7.1f ns/point\n", parse);
  std::printf("  write response (direct writer + to_chars): %7.1f ns/point\n", write);
  std::printf("  parse + write                            : %7.1f ns/point  (target <= 1000)\n",
              parse + write);
  std::printf(
      "  write with fields [foot_point, distance]: %7.1f ns/point, %zu bytes (%.0f%% of the full response)\n",
      write_trimmed, trimmed_bytes,
      100.0 * static_cast<double>(trimmed_bytes) / static_cast<double>(response_bytes));
  std::printf("  reference, nlohmann DOM: parse request %.1f ns/point, dump response %.1f ns/point\n",
              dom_parse, dom_write);
  std::printf("  reference, nlohmann SAX: numbers of the request into a vector %.1f ns/point\n", sax_parse);
  return parse + write <= 1000.0 ? 0 : 1;
}
