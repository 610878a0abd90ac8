#include "access.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <openssl/crypto.h>

namespace footpoint::server {

const char* scope_name(Scope scope) {
  switch (scope) {
    case kScopeProject:
      return "project";
    case kScopeWrite:
      return "write";
    case kScopeDelete:
      return "delete";
    case kScopeAdmin:
      return "admin";
    case kScopeNone:
      break;
  }
  return "none";
}

Scope required_scope(Route route, std::string_view method, bool metrics_key_free) {
  switch (route) {
    case Route::healthz:
    case Route::readyz:
    case Route::openapi:
    case Route::ui_playground:
    case Route::ui_docs:
    case Route::ui_asset:
    case Route::none:
      return kScopeNone;
    case Route::metrics:
      return metrics_key_free ? kScopeNone : kScopeAdmin;
    case Route::geometries:
      return method == "POST" ? kScopeWrite : kScopeProject;
    case Route::geometry:
      return method == "DELETE" ? kScopeDelete : kScopeProject;
    case Route::methods:
    case Route::geometry_project:
    case Route::geometry_mesh:
    case Route::geometry_evaluate:
    case Route::project:
      return kScopeProject;
  }
  return kScopeAdmin;
}

bool valid_key_name(std::string_view name) {
  if (name.empty() || name.size() > 64) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-';
  });
}

namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

unsigned parse_scopes(std::string_view text, const std::string& where) {
  unsigned scopes = 0;
  std::size_t start = 0;
  while (start <= text.size()) {
    const auto comma = std::min(text.find(',', start), text.size());
    const std::string_view s = text.substr(start, comma - start);
    start = comma + 1;
    bool known = false;
    for (const Scope scope : {kScopeProject, kScopeWrite, kScopeDelete, kScopeAdmin})
      if (s == scope_name(scope)) {
        scopes |= scope;
        known = true;
      }
    if (!known)
      throw KeyFileError(where + ": unknown scope '" + std::string(s) +
                         "' (scopes: project, write, delete, admin, comma-separated)");
  }
  return scopes;
}

}  // namespace

KeyRing KeyRing::parse(std::string_view text, const std::string& source) {
  KeyRing ring;
  std::set<std::string> names;
  std::set<std::array<unsigned char, 32>> digests;
  std::size_t line_number = 0, start = 0;
  while (start < text.size()) {
    const auto end = std::min(text.find('\n', start), text.size());
    std::string line(text.substr(start, end - start));
    start = end + 1;
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream fields(line);
    std::string name, scopes, hex, extra;
    fields >> name;
    if (name.empty() || name[0] == '#') continue;
    fields >> scopes >> hex >> extra;
    const std::string where = source + " line " + std::to_string(line_number);
    if (hex.empty() || !extra.empty()) throw KeyFileError(where + ": expected NAME SCOPES SHA256HEX");
    if (!valid_key_name(name))
      throw KeyFileError(where + ": the name must be 1 to 64 letters, digits, '.', '_' or '-'");
    ApiKey key;
    key.name = name;
    key.scopes = parse_scopes(scopes, where);
    if (hex.size() != 64)
      throw KeyFileError(where + ": the digest must be 64 hex digits (printf %s \"$SECRET\" | sha256sum)");
    for (std::size_t i = 0; i < 32; ++i) {
      const int hi = hex_value(hex[2 * i]), lo = hex_value(hex[2 * i + 1]);
      if (hi < 0 || lo < 0) throw KeyFileError(where + ": the digest must be 64 hex digits");
      key.digest[i] = static_cast<unsigned char>(hi * 16 + lo);
    }
    if (!names.insert(key.name).second) throw KeyFileError(where + ": the name " + name + " is given twice");
    if (!digests.insert(key.digest).second)
      throw KeyFileError(where + ": the secret of " + name + " is another key's too");
    ring.keys_.push_back(std::move(key));
  }
  return ring;
}

KeyRing KeyRing::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw KeyFileError("cannot read the keys file " + path);
  std::stringstream text;
  text << in.rdbuf();
  return parse(text.str(), path);
}

const ApiKey* KeyRing::authenticate(std::string_view secret) const {
  if (secret.empty()) return nullptr;
  const auto digest = sha256(secret);
  const ApiKey* found = nullptr;
  for (const ApiKey& key : keys_) {
    const bool same = CRYPTO_memcmp(key.digest.data(), digest.data(), digest.size()) == 0;
    found = same ? &key : found;
  }
  return found;
}

RateLimiter::Bucket& RateLimiter::refill(const std::string& key, Clock::time_point now) {
  auto it = buckets_.find(key);
  if (it == buckets_.end()) it = buckets_.emplace(key, Bucket{burst_, now}).first;
  Bucket& b = it->second;
  const double seconds = std::chrono::duration<double>(now - b.updated).count();
  if (seconds > 0) {
    b.tokens = std::min(burst_, b.tokens + seconds * rate_);
    b.updated = now;
  }
  return b;
}

RateLimiter::Decision RateLimiter::refusal(const Bucket& b, double points) const {
  const double wait = (points - b.tokens) / rate_;
  return Decision{false, static_cast<int>(std::clamp(std::ceil(wait), 1.0, 86400.0))};
}

RateLimiter::Decision RateLimiter::take(const std::string& key, double points, Clock::time_point now) {
  std::lock_guard lock(mutex_);
  Bucket& b = refill(key, now);
  if (b.tokens < points) return refusal(b, points);
  b.tokens -= points;
  return {};
}

RateLimiter::Decision RateLimiter::check(const std::string& key, Clock::time_point now) {
  std::lock_guard lock(mutex_);
  Bucket& b = refill(key, now);
  return b.tokens >= 1.0 ? Decision{} : refusal(b, 1.0);
}

}  // namespace footpoint::server
