// The JSON form of a geometry definition (see openapi.yaml, GeometryDefinition):
//   {"type":"parametric_surface", "x":"…", "y":"…", "z":"…", "domain":{"u":[a,b],"v":[c,d]}}
//   {"type":"parametric_curve", "x":"…", "y":"…"[, "z":"…"], "domain":{"t":[a,b]}}
//   {"type":"implicit_curve", "equations":["f1"[, "f2"]], "domain":{"x":[..],"y":[..][,"z":[..]]}}
//   {"type":"implicit_surface", "equation":"f", "domain":{"x":[..],"y":[..],"z":[..]}}
// each with optional "constants":{"name": number}, parametric ones with optional "periodic": ["u",
// "v"] / ["t"] (the parameters declared periodic). Shape problems are 400 ApiErrors naming the
// field (an unknown or repeated periodic name too); whether the formulas compile, the domain is
// sound and a declared direction really is periodic is decided by compile_geometry.
#pragma once
#include <string>

#include "compiled/compiled_geometry.hpp"
#include "json_reader.hpp"
#include "json_writer.hpp"

namespace footpoint::server {

// Reads the definition object at the reader's position. Field names in errors start with
// `prefix` ("" for a body that is the definition, "geometry." for an inline one).
GeometryDefinition read_geometry(JsonReader& reader, const std::string& prefix);

// Writes the definition in the same JSON form.
void write_geometry(JsonWriter& writer, const GeometryDefinition& def);

// Writes the member "closure" of a parametric geometry (seams, poles, what was declared; see
// openapi.yaml, Closure), nothing for an implicit curve.
void write_closure(JsonWriter& writer, const CompiledGeometry& geometry);

}  // namespace footpoint::server
