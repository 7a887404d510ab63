// The text a sweep gives a value (sweep_toml.h): it is both the `--set KEY=VALUE`
// a case runs with and the value in results.csv, so it must read back as the
// same number and be the text a user would write.
#include "sweep_toml.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace {

using armour::sweep_detail::shortest_float;

TEST(SweepValues, ShortestFloatReadsBackExactly) {
    for (const double v : {0.3, 0.1 + 0.2, 2050.0, 1685.0, 2475.5, 1e-3, 1.5e-5, 6.02e23, -0.125, 9.81,
                           123456789.123, 1e15, 0.0})
        EXPECT_EQ(std::strtod(shortest_float(v).c_str(), nullptr), v) << shortest_float(v);
}

TEST(SweepValues, ShortestFloatWritesEverydayNumbersInFull) {
    EXPECT_EQ(shortest_float(2050.0), "2050.0"); // %g alone gives 2.05e+03
    EXPECT_EQ(shortest_float(1685.0), "1685.0");
    EXPECT_EQ(shortest_float(100000.0), "100000.0");
    EXPECT_EQ(shortest_float(0.3), "0.3");
    EXPECT_EQ(shortest_float(0.0004), "0.0004");
    EXPECT_EQ(shortest_float(-1200.0), "-1200.0");
    EXPECT_EQ(shortest_float(5e7), "50000000.0"); // Young's modulus as the scenes write it
    EXPECT_EQ(shortest_float(1.5e-5), "1.5e-05"); // below 1e-4: the exponent is the shorter text
}

} // namespace
