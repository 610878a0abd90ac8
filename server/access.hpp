// Who may call the API and how much: API keys with scopes (--api-keys) and a token bucket of
// points per key (--rate-limit, --rate-burst). No HTTP library types.
//
// The keys file holds one key per line, `NAME SCOPES SHA256HEX`: a name (letters, digits, '.',
// '_', '-'; at most 64) that appears in logs and metrics, scopes comma-separated (project, write,
// delete, admin) and the SHA-256 of the secret in hex (`printf %s "$SECRET" | sha256sum`). Blank
// lines and lines starting with '#' are skipped. Only the digests are held: a client presents the
// secret, whose digest is compared with every key's by CRYPTO_memcmp (constant time, and every
// key is compared whatever matched), so neither the timing nor the file reveals a secret.
#pragma once
#include <array>
#include <chrono>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>
#include "compiled/sha256.hpp"

#include "route.hpp"

namespace footpoint::server {

// What a key allows; admin allows everything.
enum Scope : unsigned {
  kScopeNone = 0,
  kScopeProject = 1,  // projections, evaluate, meshes, reading geometries and methods
  kScopeWrite = 2,    // posting geometries
  kScopeDelete = 4,   // deleting geometries
  kScopeAdmin = 8,    // everything, /metrics included
};
const char* scope_name(Scope scope);

// A key's name: 1 to 64 letters, digits, '.', '_' or '-'.
bool valid_key_name(std::string_view name);

// The scope a request needs: kScopeNone for the probes (and /openapi.yaml and the pages, which
// hold no data), kScopeAdmin for /metrics unless `metrics_key_free`.
Scope required_scope(Route route, std::string_view method, bool metrics_key_free);

struct ApiKey {
  std::string name;
  unsigned scopes = 0;
  std::array<unsigned char, 32> digest{};
  bool allows(Scope s) const { return s == kScopeNone || (scopes & (s | kScopeAdmin)) != 0; }
};

struct KeyFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class KeyRing {
 public:
  // Parses a keys file's text; `source` names it in errors ("keys.txt line 3: ...").
  static KeyRing parse(std::string_view text, const std::string& source);
  // Reads and parses the file. Throws KeyFileError.
  static KeyRing load(const std::string& path);

  // The key whose secret this is, or nullptr.
  const ApiKey* authenticate(std::string_view secret) const;
  std::size_t size() const { return keys_.size(); }

 private:
  std::vector<ApiKey> keys_;
};

// SHA-256 of a secret: the core's (compiled/sha256.hpp, OpenSSL's EVP).
using footpoint::sha256;

// Token buckets of points, one per key name: each holds at most `burst` points and gains
// `rate` points a second; a request takes its points or is refused.
class RateLimiter {
 public:
  using Clock = std::chrono::steady_clock;
  RateLimiter(double rate, double burst) : rate_(rate), burst_(burst) {}

  struct Decision {
    bool allowed = true;
    int retry_after_s = 0;  // when refused: whole seconds until the bucket holds the points
  };
  // Takes `points` from `key`'s bucket when it holds them.
  Decision take(const std::string& key, double points, Clock::time_point now = Clock::now());
  // Whether `key`'s bucket holds at least one point (checked before a body is read).
  Decision check(const std::string& key, Clock::time_point now = Clock::now());
  double burst() const { return burst_; }

 private:
  struct Bucket {
    double tokens;
    Clock::time_point updated;
  };
  Bucket& refill(const std::string& key, Clock::time_point now);
  Decision refusal(const Bucket& b, double points) const;

  double rate_, burst_;
  std::mutex mutex_;
  std::map<std::string, Bucket, std::less<>> buckets_;
};

}  // namespace footpoint::server
