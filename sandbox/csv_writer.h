#pragma once
/// CSV output for the `substep` command: numbers in shortest round-trip form (DESIGN.md: they
/// must read back exactly) and a writer that streams rows through one reused line buffer.

#include "atomic_file.h"

#include <cstdint>
#include <span>
#include <string>

namespace substep {

/// Appends the shortest decimal text that std::strtod reads back as exactly `value`
/// (std::to_chars). Non-finite values print as `nan`, `inf` and `-inf`.
void appendNumber(std::string& out, double value);
/// Appends a base-10 integer.
void appendInteger(std::string& out, std::int64_t value);

/// Writes a table row by row into an output file. A row is built cell by cell in a buffer that
/// is reused, so a long run allocates nothing per frame once the first row has been formatted.
class CsvWriter {
  public:
    explicit CsvWriter(AtomicFile& file) : file_(file) {}

    /// The header line: column names joined by commas.
    void writeHeader(std::span<const std::string> names);

    /// Cells of the current row, left to right.
    CsvWriter& integer(std::int64_t value);
    CsvWriter& number(double value);
    /// Ends the current row and hands it to the file.
    void endRow();

    /// A whole row: an integer key (the frame) followed by numbers.
    void writeRow(std::int64_t key, std::span<const double> values);

  private:
    void separate() {
        if (!line_.empty()) line_ += ',';
    }

    AtomicFile& file_;
    std::string line_;
};

}  // namespace substep
