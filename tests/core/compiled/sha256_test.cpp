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
GeometryDefinition id_surface(const std::string& x, double umax,
                              std::map<std::string, double> constants = {}) {
  GeometryDefinition d;
  d.type = GeometryType::parametric_surface;
  d.formulas = {{"x", x}, {"y", "sin(u)+2*cos(v)"}, {"z", "sin(u+v)"}};
  d.domain = {{"u", {-3.0, umax}}, {"v", {-3.0, 3.0}}};
  d.constants = std::move(constants);
  return d;
}
}  // namespace

TEST_CASE("the id ignores formatting and sees every meaningful difference") {
  const auto id = id_surface("u+v", 3.0).id();
  CHECK(id.size() == 32);
  CHECK(id_surface(" u + v ", 3.0).id() == id);
  CHECK(id_surface("u+v", 3.0000000000000004).id() != id);
  CHECK(id_surface("u-v", 3.0).id() != id);
  CHECK(id_surface("u+v", 3.0, {{"R", 2.0}}).id() != id);
  CHECK(id_surface("u+v", 3.0, {{"R", 2.0}}).id() != id_surface("u+v", 3.0, {{"R", 2.5}}).id());
  auto curve = id_surface("u+v", 3.0);
  curve.type = GeometryType::parametric_curve;
  CHECK(curve.id() != id);
  CHECK(id_surface("u+v", 3.0).canonical().find("domain.u=[-3,3]") != std::string::npos);
}

TEST_CASE("definitions without periodic keep the ids they always had; periodic is part of the id") {
  // Canonical text and id as computed before periodic existed (sha256sum of the text): pinned, so
  // that ids in clients' hands and in shared registries stay valid.
  const GeometryDefinition s1 = id_surface("u+v", 3.0);
  CHECK(s1.canonical() ==
        "footpoint/"
        "1;type=parametric_surface;x=u+v;y=sin(u)+2*cos(v);z=sin(u+v);domain.u=[-3,3];domain.v=[-3,3]");
  CHECK(s1.id() == "6eb4132bf22f865049048bc1e2fc6ee9");
  GeometryDefinition helix;
  helix.type = GeometryType::parametric_curve;
  helix.formulas = {{"x", "cos(t)"}, {"y", "sin(t)"}, {"z", "0.2*t"}};
  helix.domain = {{"t", {0.0, 12.566370614359172}}};
  CHECK(helix.id() == "3435dcdf6f7909f97ebfbb8af8d65bfb");
  // An empty list is no declaration.
  GeometryDefinition none = s1;
  none.periodic = {};
  CHECK(none.id() == s1.id());
  // Declared directions change the id; their order and repeats do not.
  GeometryDefinition u = s1, uv = s1, vu = s1;
  u.periodic = {"u"};
  uv.periodic = {"u", "v"};
  vu.periodic = {"v", "u", "u"};
  CHECK(u.id() != s1.id());
  CHECK(uv.id() != u.id());
  CHECK(vu.id() == uv.id());
  CHECK(uv.canonical() == s1.canonical() + ";periodic=u,v");
}
