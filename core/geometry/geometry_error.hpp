// Why a geometry definition cannot be compiled: thrown by the compilers of the definitions and by
// the seeding they run (a search structure too intricate for its budget or its deadline).
#pragma once
#include <stdexcept>
#include <string>
#include <utility>

namespace footpoint {

// A definition that cannot be compiled: `code` is a stable machine-readable code
// (formula_syntax, unknown_variable, unknown_function, empty_formula, formula_too_long,
// bad_domain, ...), `field` names the offending field ("x", "equations[1]", "domain.u"),
// `position` the character (or -1), `suggestion` what to write there instead (or empty).
struct GeometryError : std::runtime_error {
  GeometryError(std::string code, std::string field, int position, std::string message,
                std::string suggestion = {})
      : std::runtime_error(std::move(message)),
        code(std::move(code)),
        field(std::move(field)),
        position(position),
        suggestion(std::move(suggestion)) {}
  std::string code;
  std::string field;
  int position;
  std::string suggestion;
};

}  // namespace footpoint
