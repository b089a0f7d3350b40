// validation.hpp — invariants checked inside the hot loops, behind one switch.
//
// Why: the proxy is fast because of shortcuts that each claim to give the exact answer: the
// warm-start gather (a disc about the predicted motion instead of everything within reach), the
// walk's local scans (the pieces the last scan kept instead of all of them), nearest-first
// anticipation (the index's lower bounds instead of every segment) and the index's offset boxes
// (one box per segment for where its c-space pieces can be, at any pad angle). The tests compare
// them with slow references on chosen strokes; with validation on, every time a shortcut is taken
// it is also checked against the slow way, in every test that drives the proxy.
//
// The switch: CMake option CONTACTLAB_VALIDATION (default OFF: the product, `contactlab bench`
// and the Google benchmarks pay nothing; every check below compiles away). scripts/test turns it
// on for the sanitizer build (build-asan/), which runs haptics/ and its tests a second time.
// As Box2D's B2_ENABLE_VALIDATION: checks may cost as much as the work they check.
//
// A failed check calls the validation handler: by default it prints what failed and where to
// stderr and aborts (a broken invariant in the servo must not be survived quietly). Tests can
// install their own (set_validation_handler) to see that a check fires.
#pragma once

namespace contactlab {

#if defined(CONTACTLAB_VALIDATION) && CONTACTLAB_VALIDATION
inline constexpr bool kValidation = true;
#else
inline constexpr bool kValidation = false;
#endif

// `what`: the invariant, in words; file and line of the check.
using ValidationHandler = void (*)(const char* what, const char* file, int line);
// Installs `handler` (nullptr: the default, print and abort) and returns the one it replaces.
ValidationHandler set_validation_handler(ValidationHandler handler);
// Called by CONTACTLAB_VALIDATE when a check fails.
void validation_failed(const char* what, const char* file, int line);
// How many checks ran since the program started (0 when validation is off): lets a test see that
// validation really ran where it should. Lock-free (a relaxed atomic counter).
long long validation_checks();
void count_validation_check();

}  // namespace contactlab

// Checks `condition` when validation is on; nothing at all when it is off (the condition is
// compiled, so it stays valid code, but never evaluated).
#define CONTACTLAB_VALIDATE(condition, what)                                            \
    do {                                                                                \
        if constexpr (::contactlab::kValidation) {                                      \
            ::contactlab::count_validation_check();                                     \
            if (!(condition)) ::contactlab::validation_failed((what), __FILE__, __LINE__); \
        }                                                                               \
    } while (false)
