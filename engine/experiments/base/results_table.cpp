// results_table.cpp — strict CSV for results files (results_table.hpp).
#include "engine/experiments/base/results_table.hpp"

#include <cerrno>
#include <charconv>
#include <string_view>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>

namespace contactlab::experiments {

std::optional<std::size_t> ResultsTable::column(const std::string& name) const {
    for (std::size_t i = 0; i < columns.size(); ++i)
        if (columns[i] == name) return i;
    return std::nullopt;
}

NumberParse parse_number(const std::string& s, double& value) {
    // from_chars, not strtod: no locale, no leading blanks or hex, and out of range is told
    // apart ("1e999" is not infinity).
    const char* b = s.data();
    const char* e = s.data() + s.size();
    if (b != e && *b == '+') ++b;  // spreadsheets write "+1"
    if (b == e) return NumberParse::not_a_number;
    const auto [end, ec] = std::from_chars(b, e, value);
    if (ec == std::errc::result_out_of_range) return NumberParse::out_of_range;
    if (ec != std::errc() || end != e) return NumberParse::not_a_number;
    if (!std::isfinite(value)) return NumberParse::not_a_number;  // "inf", "nan"
    return NumberParse::ok;
}

std::string number_text(double v) {
    char buf[64];
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    return ec == std::errc() ? std::string(buf, end) : std::string("?");
}

long ResultsTable::line(std::size_t row) const { return row < lines.size() ? lines[row] : static_cast<long>(row) + 2; }

std::string ResultsTable::where(std::size_t row) const {
    const std::string& file = row < file_of.size() ? files.at(file_of[row]) : origin;
    return file + ": line " + std::to_string(line(row));
}

double ResultsTable::number(std::size_t row, std::size_t col) const {
    const std::string& s = rows.at(row).at(col);
    double v = 0.0;
    const NumberParse r = parse_number(s, v);
    if (r == NumberParse::out_of_range)
        throw ExperimentError(where(row) + ", column " + columns[col] + ": \"" + s + "\" is out of the range of a double");
    if (r != NumberParse::ok)
        throw ExperimentError(where(row) + ", column " + columns[col] +
                              ": expected a number, found \"" + s + "\"");
    return v;
}

namespace {

// The line (1-based) of the first byte that is not UTF-8, or 0 when all are: the analysis writes
// labels into JSON, which must be UTF-8, so a bad byte is refused here with its line rather than
// later by the JSON library without one. Overlong forms, surrogates and code points above
// U+10FFFF are refused as RFC 3629 says.
long first_bad_utf8_line(const std::string& text) {
    long line = 1;
    const auto* p = reinterpret_cast<const unsigned char*>(text.data());
    const std::size_t n = text.size();
    for (std::size_t i = 0; i < n;) {
        const unsigned char c = p[i];
        if (c == '\n') ++line;
        if (c < 0x80) {
            ++i;
            continue;
        }
        std::size_t len = 0;
        unsigned lo = 0x80, hi = 0xBF;  // the second byte's range
        if (c >= 0xC2 && c <= 0xDF) len = 2;
        else if (c == 0xE0) len = 3, lo = 0xA0;
        else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) len = 3;
        else if (c == 0xED) len = 3, hi = 0x9F;
        else if (c == 0xF0) len = 4, lo = 0x90;
        else if (c >= 0xF1 && c <= 0xF3) len = 4;
        else if (c == 0xF4) len = 4, hi = 0x8F;
        else return line;
        if (i + len > n || p[i + 1] < lo || p[i + 1] > hi) return line;
        for (std::size_t k = 2; k < len; ++k)
            if (p[i + k] < 0x80 || p[i + k] > 0xBF) return line;
        i += len;
    }
    return 0;
}

}  // namespace

ResultsTable parse_results_csv(const std::string& input, const std::string& origin) {
    ResultsTable t;
    t.origin = origin;
    if (const long bad = first_bad_utf8_line(input))
        throw ExperimentError(origin + ": line " + std::to_string(bad) + ": not UTF-8 (save the file as UTF-8)");
    // A byte-order mark (spreadsheets write one) is not part of the first column's name.
    const std::string_view text = std::string_view(input).substr(input.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0);
    std::vector<std::vector<std::string>> records;
    std::vector<std::string> record;
    std::string field;
    bool quoted = false, any = false;
    long line = 1, record_line = 1;
    std::vector<long> lines;
    for (std::size_t i = 0; i <= text.size(); ++i) {
        const char c = i < text.size() ? text[i] : '\n';
        if (quoted) {
            if (i == text.size()) throw ExperimentError(origin + ": line " + std::to_string(record_line) + ": unterminated quote");
            if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
                field += '"';
                ++i;
            } else if (c == '"') {
                quoted = false;
            } else {
                if (c == '\n') ++line;
                field += c;
            }
            continue;
        }
        if (c == '"' && field.empty()) {
            quoted = any = true;
        } else if (c == ',') {
            record.push_back(field);
            field.clear();
            any = true;
        } else if (c == '\n' || c == '\r') {
            if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
            if (any || !field.empty()) {
                record.push_back(field);
                records.push_back(record);
                lines.push_back(record_line);
            }
            record.clear();
            field.clear();
            any = false;
            ++line;
            record_line = line;
        } else {
            field += c;
            any = true;
        }
    }
    if (records.empty()) throw ExperimentError(origin + ": empty (expected a header row)");
    t.columns = records.front();
    for (std::size_t i = 0; i < t.columns.size(); ++i) {
        if (t.columns[i].empty()) throw ExperimentError(origin + ": line 1: column " + std::to_string(i + 1) + " has no name");
        for (std::size_t j = 0; j < i; ++j)
            if (t.columns[j] == t.columns[i]) throw ExperimentError(origin + ": line 1: column \"" + t.columns[i] + "\" appears twice");
    }
    for (std::size_t r = 1; r < records.size(); ++r) {
        if (records[r].size() != t.columns.size())
            throw ExperimentError(origin + ": line " + std::to_string(lines[r]) + ": " + std::to_string(records[r].size()) +
                                  " fields, the header has " + std::to_string(t.columns.size()));
        t.rows.push_back(std::move(records[r]));
        t.lines.push_back(lines[r]);
    }
    return t;
}

std::string read_file_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ExperimentError(path + ": cannot open (" + std::strerror(errno) + ")");
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

ResultsTable read_results_csv(const std::string& path) { return parse_results_csv(read_file_bytes(path), path); }

std::string csv_line(const std::vector<std::string>& fields) {
    std::string out;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        if (i) out += ',';
        const std::string& f = fields[i];
        if (f.find_first_of(",\"\n\r") == std::string::npos) {
            out += f;
            continue;
        }
        out += '"';
        for (char c : f) out += c == '"' ? std::string("\"\"") : std::string(1, c);
        out += '"';
    }
    return out;
}

}  // namespace contactlab::experiments
