// One table of methods per geometry type. A row names a method, says in one line what it computes
// and which paper it comes from, and holds the function that runs it: the compiled geometries
// dispatch through their table, GET /v1/methods lists the tables, and an unknown method name is
// answered with the names a table holds. Rows are structs, so that a method carries what it is
// (its full citation, the options it reads, the statuses it can report) without a second list
// that could drift from the first (tests/core/compiled/compiled_geometry_methods_test.cpp holds the options
// and statuses to what the methods do).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <string_view>
#include <vector>

#include "geometry/vec.hpp"
#include "projection/projection_result.hpp"

namespace footpoint {

// The options of a projection (projection/projection_result.hpp, Options), as bits.
enum MethodOption : std::uint32_t {
  option_tolerance = 1u << 0,
  option_max_iterations = 1u << 1,
  option_initial = 1u << 2,
  option_all_minima = 1u << 3,
  option_trace = 1u << 4,
  option_max_distance = 1u << 5,
  option_certify = 1u << 6,
  option_max_minima = 1u << 7,
};
inline constexpr std::uint32_t kMethodOptionCount = 8;
const char* option_name(std::uint32_t bit_index);  // "tolerance", ... in bit order

// A set of statuses as bits (1 << Status).
constexpr std::uint32_t statuses(std::initializer_list<Status> list) {
  std::uint32_t bits = 0;
  for (const Status s : list) bits |= 1u << static_cast<unsigned>(s);
  return bits;
}

// What the global methods read (options.initial: they need no start) and what the papers' local
// methods read (no all_minima: they find one foot point; curves' also honour max_distance).
inline constexpr std::uint32_t kGlobalOptions = option_tolerance | option_max_iterations | option_all_minima |
                                                option_trace | option_max_distance | option_certify;
inline constexpr std::uint32_t kLocalOptions =
    option_tolerance | option_max_iterations | option_initial | option_trace | option_certify;

// The full references the tables cite (README, References).
inline constexpr std::string_view kCitationGsa =
    "Xiaowu Li, Zhinan Wu, Feng Pan, Juan Liang, Jiafeng Zhang, Linke Hou. A Geometric Strategy Algorithm "
    "for "
    "Orthogonal Projection onto a Parametric Surface. Journal of Computer Science and Technology, Springer "
    "and "
    "Science Press, 2019";
inline constexpr std::string_view kCitationHybrid =
    "X. Li, L. Wang, Z. Wu, L. Hou, J. Liang, Q. Li. Hybrid Second-Order Iterative Algorithm for Orthogonal "
    "Projection onto a Parametric Surface. Symmetry 9(8), Article 146, MDPI, 2017";
inline constexpr std::string_view kCitationCurve =
    "Taixia Cheng, Zhinan Wu, Xiaowu Li, Chan Wang. Point Orthogonal Projection onto a Spatial Algebraic "
    "Curve. "
    "MDPI, Basel, 2020";
inline constexpr std::string_view kCitationHuWallner =
    "S.-M. Hu, J. Wallner. A second order algorithm for orthogonal projection onto curves and surfaces. "
    "Computer Aided Geometric Design 22, 251-260, 2005";

inline constexpr std::string_view kCitationHartmann =
    "E. Hartmann. On the curvature of curves and surfaces defined by normalforms. Computer Aided Geometric "
    "Design 16, 355-376, 1999";
inline constexpr std::string_view kCitationNocedalWright =
    "J. Nocedal, S. J. Wright. Numerical Optimization, 2nd ed. Springer, 2006";

struct MethodInfo {
  std::string_view name;
  std::string_view description;  // one line
  std::string_view paper;        // the paper and its algorithm or equations; "" for a method of our own
  std::array<std::string_view, 2> citations{};  // the full references of `paper` (unused: empty)
  std::uint32_t options = 0;                    // MethodOption bits: the options the method reads
  std::uint32_t statuses = 0;  // the statuses it can report (deadline_exceeded: every method)
};

// The points a method takes: planar curves' (2-D), spatial ones' (3-D), or both.
enum class PointDims { planar, spatial, any };

// A row of the table of the compiled geometry type `Geometry`.
template <class Geometry>
struct Method {
  MethodInfo info;
  // p has three coordinates (z = 0 for a planar curve).
  ProjectionResult (*project)(const Geometry& geometry, Vec3 p, const Options& options);
  PointDims dims = PointDims::any;
};

// The rows of a table that apply to the points of one dimension (PointDims::any: every row), in
// the table's order: what a compiled geometry offers and dispatches to.
template <class Geometry>
class MethodTable {
 public:
  template <std::size_t N>
  MethodTable(const Method<Geometry> (&rows)[N], PointDims dims) {
    for (const Method<Geometry>& row : rows)
      if (dims == PointDims::any || row.dims == PointDims::any || row.dims == dims) {
        rows_.push_back(&row);
        infos_.push_back(row.info);
      }
  }
  const std::vector<MethodInfo>& infos() const { return infos_; }
  ProjectionResult project(std::size_t index, const Geometry& geometry, Vec3 p,
                           const Options& options) const {
    return rows_[index]->project(geometry, p, options);
  }

 private:
  std::vector<const Method<Geometry>*> rows_;
  std::vector<MethodInfo> infos_;
};

}  // namespace footpoint
