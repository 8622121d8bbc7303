// The command line's error contract, for the tests that run it: one line on stderr, "cudahull: error: ...".
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cli_runner.hpp"

using ::testing::HasSubstr;
using ::testing::StartsWith;

namespace {

// The CLI's error contract: one line on stderr, "cudahull: error: ...".
void expect_one_error_line(const CliRun& r, const std::string& must_mention) {
  EXPECT_THAT(r.err, StartsWith("cudahull: error: ")) << describe(r);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << describe(r);
  EXPECT_TRUE(!r.err.empty() && r.err.back() == '\n') << describe(r);
  EXPECT_THAT(r.err, HasSubstr(must_mention)) << describe(r);
}

}  // namespace
