// SHA-256 (FIPS 180-4), for content-hash geometry ids and the API keys' digests (OpenSSL underneath).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace footpoint {

std::array<std::uint8_t, 32> sha256(std::string_view data);
std::string sha256_hex(std::string_view data);

}  // namespace footpoint
