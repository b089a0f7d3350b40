// number_options.cpp — command-line numbers read as text, then checked (number_options.hpp).
#include "engine/app/number_options.hpp"

#include "engine/experiments/base/results_table.hpp"

#include <charconv>
#include <cmath>

namespace contactlab::app {

using experiments::number_text;

namespace {

// "--seed" of "-s,--seed": the name a message gives.
std::string long_name(const std::string& name) {
    const auto comma = name.rfind(',');
    return comma == std::string::npos ? name : name.substr(comma + 1);
}

// Where a cut may fall: not inside a UTF-8 sequence.
bool continuation(char c) { return (static_cast<unsigned char>(c) & 0xC0u) == 0x80u; }

}  // namespace

std::string given(const std::string& text) {
    constexpr std::size_t kLongest = 60, kKept = 28;
    if (text.size() <= kLongest) return "\"" + text + "\"";
    std::size_t head = kKept, tail = text.size() - kKept;
    while (head > 0 && continuation(text[head])) --head;
    while (tail < text.size() && continuation(text[tail])) ++tail;
    return "\"" + text.substr(0, head) + "...\" (" + std::to_string(text.size()) + " characters, shortened; ends \"..." +
           text.substr(tail) + "\")";
}

std::uint64_t whole_number(const std::string& text, const std::string& what, std::uint64_t lo, std::uint64_t hi) {
    const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
    const bool leading_zero = digits && text.size() > 1 && text[0] == '0';  // CLI11 read "010" as octal 8
    std::uint64_t v = 0;
    bool ok = digits && !leading_zero;
    if (ok) {
        // Too many digits for 64 bits is result_out_of_range: refused, never saturated.
        const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        ok = ec == std::errc() && end == text.data() + text.size() && v >= lo && v <= hi;
    }
    if (!ok) {
        const bool form = leading_zero || (!text.empty() && text[0] == '+');
        throw BadInput(what + ": expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                       (form ? " (decimal digits, without a sign or a leading zero)" : "") + ", got " + given(text));
    }
    return v;
}

std::string RealRange::text() const {
    return std::string(lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + (hi_open ? ")" : "]");
}

double real_number(const std::string& text, const std::string& what, const RealRange& range) {
    double v = 0.0;
    const experiments::NumberParse r = experiments::parse_number(text, v);
    const std::string hint = range.hint.empty() ? std::string() : ", " + range.hint;
    if (r == experiments::NumberParse::not_a_number)
        throw BadInput(what + ": expected a number in " + range.text() + hint + ", got " + given(text));
    const bool inside = r == experiments::NumberParse::ok && (range.lo_open ? v > range.lo : v >= range.lo) &&
                        (range.hi_open ? v < range.hi : v <= range.hi);
    if (!inside) throw BadInput(what + ": must lie in " + range.text() + hint + ", got " + given(text));
    return v;
}

CLI::Option* add_whole_option(CLI::App* app, const std::string& name, std::uint64_t lo, std::uint64_t hi,
                              std::function<void(std::uint64_t)> set, const std::string& shown_default,
                              const std::string& description) {
    const std::string what = long_name(name);
    return app
        ->add_option_function<std::string>(
            name, [what, lo, hi, set = std::move(set)](const std::string& text) { set(whole_number(text, what, lo, hi)); },
            description + " (" + std::to_string(lo) + ".." + std::to_string(hi) + ")")
        ->type_name("UINT")
        ->default_str(shown_default);
}

CLI::Option* add_real_option(CLI::App* app, const std::string& name, double& target, const RealRange& range,
                             const std::string& description) {
    const std::string what = long_name(name);
    return app
        ->add_option_function<std::string>(
            name, [what, range, &target](const std::string& text) { target = real_number(text, what, range); },
            description + " " + range.text())
        ->type_name("NUMBER")
        ->default_str(number_text(target));
}

}  // namespace contactlab::app
