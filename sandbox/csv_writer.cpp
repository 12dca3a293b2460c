#include "csv_writer.h"

#include <charconv>
#include <cmath>

namespace substep {

void appendNumber(std::string& out, double value) {
    // to_chars would print NaN as "nan" or "-nan" by its sign bit; readers expect one spelling.
    if (std::isnan(value)) {
        out += "nan";
        return;
    }
    char buffer[32];  // the longest shortest form, "-2.2250738585072014e-308", is 24 characters
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out.append(buffer, result.ptr);
}

void appendInteger(std::string& out, std::int64_t value) {
    char buffer[24];
    const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out.append(buffer, result.ptr);
}

void CsvWriter::writeHeader(std::span<const std::string> names) {
    line_.clear();
    for (const std::string& name : names) {
        separate();
        line_ += name;
    }
    endRow();
}

CsvWriter& CsvWriter::integer(std::int64_t value) {
    separate();
    appendInteger(line_, value);
    return *this;
}

CsvWriter& CsvWriter::number(double value) {
    separate();
    appendNumber(line_, value);
    return *this;
}

void CsvWriter::endRow() {
    line_ += '\n';
    file_.write(line_);
    line_.clear();
}

void CsvWriter::writeRow(std::int64_t key, std::span<const double> values) {
    integer(key);
    for (const double value : values)
        number(value);
    endRow();
}

}  // namespace substep
