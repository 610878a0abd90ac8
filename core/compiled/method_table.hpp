// One table of methods per geometry type. A row names a method, says in one line what it computes
// and which paper it comes from, and holds the function that runs it: the compiled geometries
// dispatch through their table, GET /v1/methods lists the tables, and an unknown method name is
// answered with the names a table holds. Rows are structs, so that a method can carry more (its
// options, the statuses it reports) without a second list that could drift from the first.
#pragma once
#include <cstddef>
#include <string_view>
#include <vector>

#include "geometry/projection_result.hpp"
#include "geometry/vec.hpp"

namespace footpoint {

struct MethodInfo {
  std::string_view name;
  std::string_view description;  // one line
  std::string_view paper;        // the paper and its algorithm or equations; "" for a method of our own
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
