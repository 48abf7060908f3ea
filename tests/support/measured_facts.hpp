// measured_facts.hpp: the numbers a chapter quotes from its tests' own measurements.
// A test records what it measured; run with --facts=FILE, the test program writes every
// recorded value to FILE after a run in which every test passed, and the book build reads
// them there (book/AUTHORING.md, "Claims the build checks"), so the text never types a
// measured number by hand.
//
// Usage:
//   record_fact("ch06_far_float_absolute", worst);   // in a TEST_CASE, after measuring
//   test_ch06 --facts=build/figures/ch06_measured.txt  // one "NAME VALUE" line per fact
//
// Names are unique across a test program (recording a name twice keeps the last value);
// values are written with 17 significant digits, so a fact reads back as measured.
#pragma once

#include <filesystem>
#include <string>

namespace exactpixels::testing {

/// Records `value` under `name` (letters, digits, '_', '.', '-', '/') for --facts.
void record_fact(const std::string& name, double value);

/// Writes every recorded fact to `path`, one "NAME VALUE" line each, sorted by name, all
/// or nothing. Throws Error naming the path when it cannot be written.
void write_measured_facts(const std::filesystem::path& path);

} // namespace exactpixels::testing
