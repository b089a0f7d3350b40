// results_table.hpp — an experiment's results file: CSV with a header row, one row per trial
// (scenes/README.md, "Experiments: results"). Read strictly (a row with the wrong number of
// fields, an unterminated quote, an empty header name, a byte that is not UTF-8: an error naming
// the file, line and column), written atomically. A leading byte-order mark is skipped; CRLF and
// quoted fields (RFC 4180) are read.
//
// Room engine/experiments/base/: what every room uses: ExperimentError and the strict CSV table (here), SHA-256
// (sha256.hpp), the seeded random stream (random_stream.hpp) and the trial profile's stage timers
// (trial_profile.hpp). Includes haptics/ only.
// The rooms and their arrows: docs/ARCHITECTURE.md, "The experiments' rooms".
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace contactlab::experiments {

struct ExperimentError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

enum class NumberParse { ok, not_a_number, out_of_range };
// A whole cell as a finite double (an optional leading '+'; no blanks, hex, inf or nan).
NumberParse parse_number(const std::string& cell, double& value);
// The shortest text that reads back as exactly `v`, for messages: "20.0000001" (%g and an
// ostream's default both print "20"), "1e-09", "0.25".
std::string number_text(double v);

struct ResultsTable {
    std::string origin;  // the file, for messages
    std::vector<std::string> columns;
    std::vector<std::vector<std::string>> rows;  // each as long as `columns`
    std::vector<long> lines;                     // each row's line in its file (quoted line breaks count)
    // Pooled tables (several files): each row's file, an index into `files`; empty for one file.
    std::vector<std::string> files;
    std::vector<std::size_t> file_of;

    // The file line of a row, and "FILE: line N" for messages.
    long line(std::size_t row) const;
    std::string where(std::size_t row) const;

    // Index of a column, if present.
    std::optional<std::size_t> column(const std::string& name) const;
    // A cell as a number; throws ExperimentError naming the row (file line) and column if it is
    // not one. `row` indexes `rows`.
    double number(std::size_t row, std::size_t col) const;
};

ResultsTable parse_results_csv(const std::string& text, const std::string& origin);
ResultsTable read_results_csv(const std::string& path);

// A whole file's bytes; ExperimentError naming it when it cannot be opened.
std::string read_file_bytes(const std::string& path);

// One CSV line (no newline): fields with a comma, quote or line break are quoted.
std::string csv_line(const std::vector<std::string>& fields);

}  // namespace contactlab::experiments
