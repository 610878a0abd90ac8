#include "parametric/seeding/surface_refinement.hpp"

#include <utility>

namespace footpoint {

SubBox::SubBox(const formula::Program& program, const BoxEnclosure<2>& ancestor, const Params<2>& box_lo,
               const Params<2>& box_hi, bool evaluate)
    : lo(box_lo), hi(box_hi) {
  centre = enclose_point<2>(program, {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])});
  enclosure = derive_enclosure(ancestor, lo, hi, centre);
  if (evaluate || !enclosure.smooth) enclosure = intersect(enclose_box<2>(program, lo, hi), enclosure);
  const double wu = hi[0] - lo[0], wv = hi[1] - lo[1];
  split_u = !centre.valid || norm2(centre.ds[0]) * wu * wu >= norm2(centre.ds[1]) * wv * wv;
}

SubBox::~SubBox() { delete halves.load(std::memory_order_acquire); }

SubBoxPair::SubBoxPair(const formula::Program& program, const BoxEnclosure<2>& ancestor, const Params<2>& lo,
                       const Params<2>& hi, bool split_u, bool evaluate)
    : half{SubBox(program, ancestor, lo,
                  split_u ? Params<2>{0.5 * (lo[0] + hi[0]), hi[1]} : Params<2>{hi[0], 0.5 * (lo[1] + hi[1])},
                  evaluate),
           SubBox(program, ancestor,
                  split_u ? Params<2>{0.5 * (lo[0] + hi[0]), lo[1]} : Params<2>{lo[0], 0.5 * (lo[1] + hi[1])},
                  hi, evaluate)} {}

SurfaceRefinement::SurfaceRefinement(formula::Program program, std::size_t cells, std::size_t max_pairs)
    : program_(std::move(program)),
      sum_of_monomials_(program_.sum_of_monomials()),
      cells_(cells),
      max_pairs_(max_pairs),
      cell_halves_(new std::atomic<const SubBoxPair*>[cells]) {
  for (std::size_t i = 0; i < cells_; ++i) cell_halves_[i].store(nullptr, std::memory_order_relaxed);
}

SurfaceRefinement::~SurfaceRefinement() {
  for (std::size_t i = 0; i < cells_; ++i) delete cell_halves_[i].load(std::memory_order_acquire);
}

const SubBoxPair& SurfaceRefinement::halves(std::atomic<const SubBoxPair*>& slot,
                                            const BoxEnclosure<2>& ancestor, const Params<2>& lo,
                                            const Params<2>& hi, bool split_u, bool of_cell,
                                            std::unique_ptr<SubBoxPair>& scratch) const {
  const bool evaluate = of_cell || !sum_of_monomials_;
  if (const SubBoxPair* published = slot.load(std::memory_order_acquire)) return *published;
  // A place among the max_pairs is taken before the halves are published, and given back if they
  // are not: at no time are more than max_pairs kept, however many threads race.
  if (pairs_.fetch_add(1, std::memory_order_relaxed) >= max_pairs_) {
    pairs_.fetch_sub(1, std::memory_order_relaxed);
    scratch = std::make_unique<SubBoxPair>(program_, ancestor, lo, hi, split_u, evaluate);
    return *scratch;
  }
  auto fresh = std::make_unique<SubBoxPair>(program_, ancestor, lo, hi, split_u, evaluate);
  const SubBoxPair* expected = nullptr;
  if (slot.compare_exchange_strong(expected, fresh.get(), std::memory_order_acq_rel,
                                   std::memory_order_acquire)) {
    return *fresh.release();
  }
  pairs_.fetch_sub(1, std::memory_order_relaxed);
  return *expected;  // another thread published them first
}

}  // namespace footpoint
