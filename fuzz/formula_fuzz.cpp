// libFuzzer target: arbitrary text into formula::Program::compile over the variables u, v (the
// surface case), then, when it compiles, every evaluation mode at a few points and boxes.
//
// Input: up to three formulas separated by '\n' (compiled together, as x, y, z are, so common
// subexpressions are shared across them). Anything may happen to the text; what must not happen
// is a crash, a hang, a leak, undefined behaviour, or an exception other than FormulaError.
//
// Beyond "no crash", one property of the engine is checked, because a violation would be a wrong
// answer given as a certain one: a finite value at a point of a box lies inside the interval
// enclosure over that box (intervals are rigorous, outward rounded; a box whose enclosure misses a
// value taken in it could be excluded from the search although the nearest point lies in it).
// The check is skipped for formulas with an operator that turns NaN into a number (comparisons,
// logic, ?:, min, max, sign): at a point where an operand is undefined (u^1.5 at u < 0) the value
// is then finite while the interval, which clips each function to its domain, only encloses the
// defined part (0>=u^1.5-24 is 0 at u = -2.75, its enclosure over [-3,3] is [1,1]); an empty
// enclosure (no point of the box in the domain) is accepted for the same reason (sqrt(u-1)^0).
// Jets are evaluated for crashes and UB only: their value part may differ from values() in the
// last bits (x^k is x^(k-2)*x*x there), and cancellation can magnify that without bound.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "formula/program.hpp"

namespace {

using footpoint::formula::CompileLimits;
using footpoint::formula::FormulaError;
using footpoint::formula::Interval;
using footpoint::formula::Jet2;
using footpoint::formula::Jet3;
using footpoint::formula::NamedFormula;
using footpoint::formula::Program;

[[noreturn]] void fail(const char* what, const std::vector<NamedFormula>& formulas, std::size_t k, double u,
                       double v, double a, double b) {
  std::fprintf(stderr, "formula_fuzz: %s in formula %zu at (u, v) = (%.17g, %.17g): %.17g vs %.17g\n", what,
               k, u, v, a, b);
  for (const auto& f : formulas) std::fprintf(stderr, "  %s = %s\n", f.name.c_str(), f.expression.c_str());
  std::abort();
}

bool enclosed(double value, const Interval& range) {
  if (!std::isfinite(value) || std::isnan(range.lo) || std::isnan(range.hi)) return true;
  return range.lo <= value && value <= range.hi;
}

bool swallows_nan(std::string_view formula) {
  return formula.find_first_of("<>=!&|?") != std::string_view::npos ||
         formula.find("min") != std::string_view::npos || formula.find("max") != std::string_view::npos ||
         formula.find("sign") != std::string_view::npos;
}

struct Box {
  Interval u, v;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<NamedFormula> formulas;
  const char* names[] = {"x", "y", "z"};
  std::size_t start = 0;
  while (formulas.size() < 3) {
    const std::size_t end = text.find('\n', start);
    formulas.push_back({names[formulas.size()], std::string(text.substr(start, end - start))});
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  const std::map<std::string, double> constants{{"a", 2.5}, {"big", 1e300}, {"tiny", 1e-300}};
  CompileLimits limits;  // the defaults the server starts from: 4096 characters, 20,000 nodes

  Program program;
  try {
    program = Program::compile(formulas, {"u", "v"}, constants, limits);
  } catch (const FormulaError&) {
    return 0;  // the expected way to refuse a formula
  }
  // Any other exception escapes and libFuzzer reports it as a crash.
  if (program.num_inputs() != 2 || program.num_outputs() != static_cast<int>(formulas.size())) std::abort();

  const std::size_t n = formulas.size();
  const double points[][2] = {{0.0, 0.0},    {0.5, 0.5},        {1.0, -1.0},
                              {-2.75, 3.25}, {1e-300, -1e-300}, {1e300, -7.0}};
  // Each box holds the points listed after it in `inside`.
  const Box boxes[] = {{{0.0, 1.0}, {-1.0, 1.0}},
                       {{-3.0, 3.0}, {-4.0, 4.0}},
                       {{0.5, 0.5}, {0.5, 0.5}},
                       {{-1e300, 1e300}, {-10.0, 10.0}}};
  const bool inside[4][6] = {{true, true, true, false, true, false},
                             {true, true, true, true, true, false},
                             {false, true, false, false, false, false},
                             {true, true, true, true, true, true}};

  double values[3];
  Jet2<2> jets2[3];
  Jet3<2> jets3[3];
  Interval ranges[3];
  for (const auto& p : points) {
    program.values(p, values);
    program.jets2<2>(p, jets2);
    program.jets3<2>(p, jets3);
  }
  for (std::size_t b = 0; b < std::size(boxes); ++b) {
    const Interval box[2] = {boxes[b].u, boxes[b].v};
    program.intervals(box, ranges);
    for (std::size_t i = 0; i < std::size(points); ++i) {
      if (!inside[b][i]) continue;
      program.values(points[i], values);
      for (std::size_t k = 0; k < n; ++k)
        if (!swallows_nan(formulas[k].expression) && !enclosed(values[k], ranges[k]))
          fail("value outside its interval", formulas, k, points[i][0], points[i][1], values[k],
               ranges[k].lo <= values[k] ? ranges[k].hi : ranges[k].lo);
    }
  }
  return 0;
}
