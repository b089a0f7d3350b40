// sha256.cpp — SHA-256 through OpenSSL's one-shot EVP digest (sha256.hpp).
#include "engine/experiments/base/sha256.hpp"

#include <openssl/evp.h>

#include <stdexcept>

namespace contactlab::experiments {

std::string sha256_hex(std::string_view bytes) {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int size = 0;
    if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1 || size != 32)
        throw std::runtime_error("SHA-256: OpenSSL's digest failed");
    static const char* hex = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < size; ++i) {
        out += hex[digest[i] >> 4];
        out += hex[digest[i] & 15];
    }
    return out;
}

}  // namespace contactlab::experiments
