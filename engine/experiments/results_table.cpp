// results_table.cpp — strict CSV for results files (results_table.hpp).
#include "engine/experiments/results_table.hpp"

#include <cerrno>
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

double ResultsTable::number(std::size_t row, std::size_t col) const {
    const std::string& s = rows.at(row).at(col);
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || !std::isfinite(v))
        throw ExperimentError(origin + ": line " + std::to_string(row + 2) + ", column " + columns[col] +
                              ": expected a number, found \"" + s + "\"");
    return v;
}

ResultsTable parse_results_csv(const std::string& text, const std::string& origin) {
    ResultsTable t;
    t.origin = origin;
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
    }
    return t;
}

ResultsTable read_results_csv(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw ExperimentError(path + ": cannot open (" + std::strerror(errno) + ")");
    std::ostringstream s;
    s << in.rdbuf();
    return parse_results_csv(s.str(), path);
}

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
