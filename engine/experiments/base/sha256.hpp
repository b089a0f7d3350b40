// sha256.hpp — SHA-256 of a byte string as 64 lowercase hex digits, for provenance: a results
// file's meta names the protocol file's exact bytes (RESULTS.csv.meta.json, protocol_sha256), so
// two files can be told to come from the same protocol even after it was renamed or moved.
// OpenSSL's libcrypto computes it (libssl-dev, scripts/setup): no hand-written hash to trust.
#pragma once

#include <string>
#include <string_view>

namespace contactlab::experiments {

std::string sha256_hex(std::string_view bytes);

}  // namespace contactlab::experiments
