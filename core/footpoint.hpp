// footpoint as a C++ library: the orthogonal projection of points onto curves and surfaces given
// as formulas, the global nearest point with a certificate. This header is the public API; the
// package installs it and the headers it includes, nothing else of core/
// (`find_package(footpoint)`, target `footpoint::core`; examples/cpp builds against it).
//
// Define (compiled/geometry_definition.hpp): a GeometryDefinition names its type
// (parametric_surface: formulas x, y, z in u, v; parametric_curve: x, y[, z] in t; implicit_curve:
// one equation in x, y or two in x, y, z), its formulas in muparser syntax, the closed domain or box,
// user constants and periodic parameters. Its id() is a content hash of its canonical text.
//
// Compile (compiled/compiled_geometry.hpp): compile_geometry(definition, limits) parses the
// formulas, builds their tape and what `auto` precomputes (cells, samples, certificates' bounds),
// and returns an immutable CompiledGeometry shared by all threads. It throws GeometryError (a code
// such as "unknown_variable", "formula_too_long", "empty_curve", "compile_timeout", a message, and
// the formula and position at fault) for a definition that cannot be compiled.
//
// Project: geometry->method(name) looks a method up ("auto", the global one with its
// certificate, and the papers' methods of the type: methods()); an unknown name is an error value
// (UnknownMethod), never an exception. GeometryMethod::project(p, options) answers one point;
// project_batch(pool, request) (batch/batch.hpp) answers many on a ThreadPool, in order.
//
// Results (projection/projection_result.hpp): ProjectionResult holds the foot point, the distance,
// the parameters, and a Summary: the status (converged, or why not), iterations, residuals,
// location (interior, edge, corner, ...), multiplicity, and the Certificate
// (projection/certificate.hpp): a rigorous lower bound L of the distance over the whole domain and
// whether it meets the answer (d - L <= max(1e-9 d, 512 ulps)).
//
// Keep compiled geometries (cache/geometry_cache.hpp): GeometryCache holds them by id within a
// memory budget and compiles each id once however many threads ask. Look at them
// (mesh/mesh.hpp): meshes of surfaces and polylines of curves.
//
// Limits: formulas are compiled within CompileLimits (characters per formula, tape length, a
// compile deadline). `auto` bounds its work per point (a budget of boxes and local solves), and an
// answer it cannot prove says so in its certificate (reason budget_exhausted, non_finite,
// singular) instead of claiming more; Options (projection_result.hpp) set the tolerance, a start,
// all_minima, max_distance, certify and trace.
//
// Example:
//   footpoint::GeometryDefinition torus;
//   torus.type = footpoint::GeometryType::parametric_surface;
//   torus.formulas = {{"x", "(2+0.5*cos(v))*cos(u)"}, {"y", "(2+0.5*cos(v))*sin(u)"}, {"z", "0.5*sin(v)"}};
//   torus.domain = {{"u", {0.0, 6.283185307179586}}, {"v", {0.0, 6.283185307179586}}};
//   const auto surface = footpoint::compile_geometry(torus);
//   const double p[3] = {3.0, 0.0, 0.0};
//   const footpoint::ProjectionResult r = surface->method("auto").value().project(p, {});
//   // r.foot == {2.5, 0, 0}, r.distance == 0.5, r.summary.certificate.certified
#pragma once

#include "batch/batch.hpp"
#include "batch/thread_pool.hpp"
#include "cache/geometry_cache.hpp"
#include "compiled/compiled_geometry.hpp"
#include "mesh/mesh.hpp"
