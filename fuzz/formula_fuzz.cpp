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
// The same for interval jets (formula/interval_jet.hpp): where `lipschitz` (or `smooth`) holds
// over a box of positive width, the point jets' gradient (and Hessian) at the listed points of the
// box lie in the interval jets' enclosures. Point jets are computed in their own order of
// operations (x^k is x^(k-2)*x*x there, polynomials term by term), so they carry their own
// rounding: they are compared with the enclosures widened by 1e-9 of their magnitude - a wrong
// derivative rule or a missed kink is off by far more. Formulas with a piecewise operator (abs,
// min, max, sign, comparisons, ?:) are skipped there: at an exact tie on the box's edge the point
// jets take the other branch's derivative (their documented convention) than the one the box is on.
// Ball jets (formula/ball.hpp) at each point: both they and the interval jets of the point box
// hold the exact value and gradient there, so where a ball jet is defined its balls must meet
// those intervals (a wrong radius bound or a wrong fast-path derivative misses them).
// Jets are otherwise evaluated for crashes and UB only: their value part may differ from values()
// in the last bits, and cancellation can magnify that without bound.
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

using footpoint::formula::Ball;
using footpoint::formula::BallJet1;
using footpoint::formula::CompileLimits;
using footpoint::formula::FormulaError;
using footpoint::formula::Interval;
using footpoint::formula::IntervalJet2;
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

bool piecewise(std::string_view formula) {
  return swallows_nan(formula) || formula.find("abs") != std::string_view::npos;
}

bool near_enclosed(double value, const Interval& range) {
  if (!std::isfinite(value) || !std::isfinite(range.lo) || !std::isfinite(range.hi)) return true;
  const double slack = 1e-9 * std::abs(value) + 1e-300;
  return range.lo - slack <= value && value <= range.hi + slack;
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
  CompileLimits limits;  // the defaults the server starts from: 19,999 characters, 20,000 nodes

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
  IntervalJet2<2> interval_jets[3];
  BallJet1<2> balls[3];
  // both hold the exact value at the point: a ball jet meets the interval jet of the point box
  auto meets = [](const Ball& b, const Interval& i) {
    return b.mid - b.rad <= i.hi && i.lo <= b.mid + b.rad;
  };
  for (const auto& p : points) {
    program.values(p, values);
    program.jets2<2>(p, jets2);
    program.jets3<2>(p, jets3);
    const Interval at[2] = {{p[0], p[0]}, {p[1], p[1]}};
    program.interval_jets2<2>(at, interval_jets);
    program.ball_jets1<2>(p, balls);
    for (std::size_t k = 0; k < n; ++k) {
      const IntervalJet2<2>& r = interval_jets[k];
      if (!balls[k].defined || swallows_nan(formulas[k].expression) || std::isnan(r.v.lo) ||
          std::isnan(r.v.hi) || r.v.partial)
        continue;
      if (!meets(balls[k].v, r.v))
        fail("ball value apart from the interval jet", formulas, k, p[0], p[1], balls[k].v.mid, r.v.lo);
      for (int d = 0; d < 2 && r.lipschitz && std::isfinite(balls[k].g[d].rad); ++d)
        if (!meets(balls[k].g[d], r.g[d]))
          fail("ball gradient apart from the interval jet", formulas, k, p[0], p[1], balls[k].g[d].mid,
               r.g[d].lo);
    }
  }
  for (std::size_t b = 0; b < std::size(boxes); ++b) {
    const Interval box[2] = {boxes[b].u, boxes[b].v};
    program.intervals(box, ranges);
    program.interval_jets2<2>(box, interval_jets);
    const bool wide = box[0].lo < box[0].hi && box[1].lo < box[1].hi && box[0].hi - box[0].lo < 1e3;
    for (std::size_t i = 0; i < std::size(points); ++i) {
      if (!inside[b][i]) continue;
      program.values(points[i], values);
      program.jets2<2>(points[i], jets2);
      for (std::size_t k = 0; k < n; ++k) {
        if (swallows_nan(formulas[k].expression)) continue;
        if (!enclosed(values[k], ranges[k]))
          fail("value outside its interval", formulas, k, points[i][0], points[i][1], values[k],
               ranges[k].lo <= values[k] ? ranges[k].hi : ranges[k].lo);
        if (!enclosed(values[k], interval_jets[k].v))
          fail("value outside its interval jet", formulas, k, points[i][0], points[i][1], values[k],
               interval_jets[k].v.lo);
        const IntervalJet2<2>& r = interval_jets[k];
        if (!wide || piecewise(formulas[k].expression) || !r.lipschitz) continue;
        for (int d = 0; d < 2; ++d) {
          if (!near_enclosed(jets2[k].g[d], r.g[d]))
            fail("gradient outside its interval jet", formulas, k, points[i][0], points[i][1], jets2[k].g[d],
                 r.g[d].lo <= jets2[k].g[d] ? r.g[d].hi : r.g[d].lo);
          for (int e = 0; e < 2 && r.smooth; ++e)
            if (!near_enclosed(jets2[k].h[d][e], r.h[d][e]))
              fail("Hessian outside its interval jet", formulas, k, points[i][0], points[i][1],
                   jets2[k].h[d][e], r.h[d][e].lo <= jets2[k].h[d][e] ? r.h[d][e].hi : r.h[d][e].lo);
        }
      }
    }
  }
  return 0;
}
