// Geometry ids are content hashes of a canonical definition: the same definition always gives the
// same id (on every replica), a different one a different id.
#include <doctest/doctest.h>

#include "compiled/compiled_geometry.hpp"
#include "compiled/sha256.hpp"

using footpoint::GeometryDefinition;
using footpoint::GeometryType;

TEST_CASE("SHA-256 matches the FIPS 180-4 test vectors") {
  CHECK(footpoint::sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(footpoint::sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(footpoint::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  CHECK(footpoint::sha256_hex(std::string(1000000, 'a')) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

namespace {
GeometryDefinition surface(const std::string& x, double umax, std::map<std::string, double> constants = {}) {
  GeometryDefinition d;
  d.type = GeometryType::parametric_surface;
  d.formulas = {{"x", x}, {"y", "sin(u)+2*cos(v)"}, {"z", "sin(u+v)"}};
  d.domain = {{"u", {-3.0, umax}}, {"v", {-3.0, 3.0}}};
  d.constants = std::move(constants);
  return d;
}
}  // namespace

TEST_CASE("the id ignores formatting and sees every meaningful difference") {
  const auto id = surface("u+v", 3.0).id();
  CHECK(id.size() == 32);
  CHECK(surface(" u + v ", 3.0).id() == id);
  CHECK(surface("u+v", 3.0000000000000004).id() != id);
  CHECK(surface("u-v", 3.0).id() != id);
  CHECK(surface("u+v", 3.0, {{"R", 2.0}}).id() != id);
  CHECK(surface("u+v", 3.0, {{"R", 2.0}}).id() != surface("u+v", 3.0, {{"R", 2.5}}).id());
  auto curve = surface("u+v", 3.0);
  curve.type = GeometryType::parametric_curve;
  CHECK(curve.id() != id);
  CHECK(surface("u+v", 3.0).canonical().find("domain.u=[-3,3]") != std::string::npos);
}
