// number_options.hpp — the one reader of the numbers a user types on a command line (issue 49).
//
// CLI11's own conversion wraps and saturates (strtoull: `--seed -1` became 18446744073709551615,
// `--seed 99999999999999999999999` the same, `010` was octal 8). Every whole number and real an
// experiment command (and fuzz-contact, generate, edit) takes for --seed, --jobs, --participants
// and the like goes through here instead: read as the text given, then checked. A value that does
// not fit is refused with BadInput (exit 2) naming the option, the value as given (quoted,
// shortened when long) and the range allowed.
#pragma once

#include "engine/app/subcommands.hpp"
#include "engine/experiments/base/results_table.hpp"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>

namespace contactlab::app {

// The value as the user gave it, for a message: quoted; longer than 60 characters, its first and
// last 28 with the length between ("12345...(100000 characters)...67890").
std::string given(const std::string& text);

// The shortest text that reads back as exactly `v` ("20.0000001", not %g's "20").
using experiments::number_text;

// A whole number in [lo, hi]: decimal digits only (no sign, blank, '+', leading zero, hex or
// exponent), never wrapped or saturated. Throws BadInput "OPTION: expected a whole number from LO
// to HI, got "TEXT"" (`what` names it when the option is not the whole story, e.g. "--participants:
// sim:A-B: A").
std::uint64_t whole_number(const std::string& text, const std::string& what, std::uint64_t lo, std::uint64_t hi);

// A finite real: experiments::parse_number's form (an optional '+', no blanks, hex, inf or nan;
// 1e999 is out of range, not infinity). `lo`/`hi` bound it, each open or closed as `range` says
// ("(0, 1)", "[0, 1)"), and `hint` follows the range ("e.g. 0.05"). Throws BadInput
// "OPTION: must lie in RANGE, HINT, got "TEXT"".
struct RealRange {
    double lo = -std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::max();
    bool lo_open = false, hi_open = false;
    std::string hint;  // after the range, e.g. "e.g. 0.05"; may be empty
    std::string text() const;  // "(0, 1)"
};
double real_number(const std::string& text, const std::string& what, const RealRange& range);

// Options read through the above (CLI11 keeps the text; the check runs when the option is parsed,
// so a bad value fails before the command starts). `target` keeps its value when the option is not
// given, and that value is shown as the default in --help.
CLI::Option* add_whole_option(CLI::App* app, const std::string& name, std::uint64_t lo, std::uint64_t hi,
                              std::function<void(std::uint64_t)> set, const std::string& shown_default,
                              const std::string& description);
template <class T>
    requires std::is_integral_v<T>
CLI::Option* add_whole_option(CLI::App* app, const std::string& name, T& target, std::type_identity_t<T> lo,
                              std::type_identity_t<T> hi, const std::string& description) {
    static_assert(sizeof(T) <= sizeof(std::uint64_t));
    // Every whole-number option counts something or seeds something: none is negative.
    if constexpr (std::is_signed_v<T>) {
        if (lo < 0) lo = 0;
        if (hi < 0) hi = 0;
    }
    const auto low = static_cast<std::uint64_t>(lo), high = static_cast<std::uint64_t>(hi);
    return add_whole_option(app, name, low, high, [&target](std::uint64_t v) { target = static_cast<T>(v); },
                            std::to_string(target), description);
}
CLI::Option* add_real_option(CLI::App* app, const std::string& name, double& target, const RealRange& range,
                             const std::string& description);

// Seeds take any 64-bit value; jobs at most this many (0: every core).
inline constexpr std::uint64_t kMaxSeed = std::numeric_limits<std::uint64_t>::max();
inline constexpr int kMaxJobs = 1024;

}  // namespace contactlab::app
