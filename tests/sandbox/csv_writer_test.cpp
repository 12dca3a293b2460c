// Tests sandbox/csv_writer.cpp: numbers read back exactly, and rows come out as the contract says.

#include "csv_writer.h"
#include "atomic_file.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <vector>

namespace substep {
namespace {

std::string formatted(double value) {
    std::string text;
    appendNumber(text, value);
    return text;
}

// Bitwise equality, so -0.0 must come back as -0.0.
void expectRoundTrip(double value) {
    const std::string text = formatted(value);
    char* end = nullptr;
    const double back = std::strtod(text.c_str(), &end);
    EXPECT_EQ(end, text.c_str() + text.size()) << text;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(back), std::bit_cast<std::uint64_t>(value))
        << text << " read back as " << back;
}

TEST(CsvNumber, SpecialValuesRoundTrip) {
    using limits = std::numeric_limits<double>;
    for (const double value : {0.0,
                               -0.0,
                               1.0,
                               -1.0,
                               0.1,
                               1.0 / 3.0,
                               1.0 / 60.0,
                               2.0 / 60.0,
                               1e-300,
                               1e300,
                               -9.81,
                               limits::min(),
                               -limits::min(),
                               limits::max(),
                               limits::lowest(),
                               limits::denorm_min(),
                               limits::epsilon(),
                               1.0 + limits::epsilon(),
                               std::nextafter(1.0, 0.0),
                               M_PI,
                               123456789.0,
                               9007199254740993.0,
                               0.30000000000000004}) {
        expectRoundTrip(value);
    }
}

TEST(CsvNumber, RandomBitPatternsRoundTrip) {
    std::mt19937_64 random(20240601);  // fixed seed: the same cases every run
    int checked = 0;
    while (checked < 200000) {
        const double value = std::bit_cast<double>(random());
        if (!std::isfinite(value)) continue;
        expectRoundTrip(value);
        ++checked;
    }
}

TEST(CsvNumber, IsShortest) {
    EXPECT_EQ(formatted(0.1), "0.1");
    EXPECT_EQ(formatted(1.0), "1");
    EXPECT_EQ(formatted(-0.0), "-0");
    EXPECT_EQ(formatted(1e300), "1e+300");
    EXPECT_EQ(formatted(0.016666666666666666), "0.016666666666666666");
}

TEST(CsvNumber, NonFiniteHaveOneSpelling) {
    EXPECT_EQ(formatted(std::numeric_limits<double>::quiet_NaN()), "nan");
    EXPECT_EQ(formatted(-std::numeric_limits<double>::quiet_NaN()), "nan");
    EXPECT_EQ(formatted(std::numeric_limits<double>::infinity()), "inf");
    EXPECT_EQ(formatted(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(CsvNumber, Integers) {
    std::string text;
    appendInteger(text, 0);
    text += ' ';
    appendInteger(text, 10000000);
    text += ' ';
    appendInteger(text, std::numeric_limits<std::int64_t>::min());
    EXPECT_EQ(text, "0 10000000 -9223372036854775808");
}

TEST(CsvWriter, WritesHeaderAndRows) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                       ("csv_writer_test_" + std::to_string(getpid()) + ".csv");
    {
        AtomicFile file(path.string());
        CsvWriter csv(file);
        const std::vector<std::string> names = {"frame", "t", "x"};
        csv.writeHeader(names);
        const std::vector<double> row0 = {0.0, 1.5};
        const std::vector<double> row1 = {0.25, -2.0};
        csv.writeRow(0, row0);
        csv.writeRow(1, row1);
        csv.integer(7).number(0.5).endRow();
        file.commit();
    }
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_EQ(text.str(), "frame,t,x\n0,0,1.5\n1,0.25,-2\n7,0.5\n");
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace substep
