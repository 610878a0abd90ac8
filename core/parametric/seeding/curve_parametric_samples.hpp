// Dense adaptive samples of a parametric curve for `auto`: the parameter interval is bisected
// until every pair of neighbouring samples is close (chord at most h_max) and the tangent turns
// little between them (at most max_turn at the ends and the midpoint), so that the arc between
// neighbours is at most the spacing h and the distance to p has at most one minimum there.
#pragma once
#include <cstddef>

#include "geometry/compile_budget.hpp"
#include "seeding/curve_samples.hpp"

namespace footpoint {

class CurveFormulas;
struct ParamInterval;

struct ParametricSampling {
  int initial_intervals = 64;
  // h_max as a fraction of the diagonal of the curve's bounding box.
  double chord_fraction = 1.0 / 256.0;
  // 0.15 rad: the arc exceeds the chord by at most 0.1 %.
  double max_turn = 0.15;
  // Intervals shorter than this fraction of the domain are not split (cusps, c'(t) = 0).
  double min_interval_fraction = 1e-9;
  std::size_t max_samples = 1000000;
  // The bytes each sample commits the compiled geometry to (CompileBudget::grow, counted as the
  // sample is taken): at least the sample's own in CurveSamples (a point, two links, a kind, a
  // parameter); a caller building more per sample says how much more.
  std::size_t bytes_per_sample = kSampleBytes;
  static constexpr std::size_t kSampleBytes = CurveSamples::kBytesPerSample + sizeof(double);
};

CurveSamples sample_parametric_curve(const CurveFormulas& formulas, const ParamInterval& domain,
                                     CompileBudget& budget, const ParametricSampling& settings = {});

}  // namespace footpoint
