// validation.cpp — the validation handler and counter (see validation.hpp).
#include "haptics/validation.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace contactlab {
namespace {

void print_and_abort(const char* what, const char* file, int line) {
    std::fprintf(stderr, "contactlab validation failed: %s (%s:%d)\n", what, file, line);
    std::abort();
}

std::atomic<ValidationHandler> g_handler{&print_and_abort};
std::atomic<long long> g_checks{0};

}  // namespace

ValidationHandler set_validation_handler(ValidationHandler handler) {
    return g_handler.exchange(handler ? handler : &print_and_abort);
}

void validation_failed(const char* what, const char* file, int line) { g_handler.load()(what, file, line); }

long long validation_checks() { return g_checks.load(std::memory_order_relaxed); }

void count_validation_check() { g_checks.fetch_add(1, std::memory_order_relaxed); }

}  // namespace contactlab
