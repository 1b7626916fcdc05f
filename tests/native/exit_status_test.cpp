// native/exit_status: every StatusCode has an exit status from the documented set, a few
// rows checked exactly, and the --help paragraph lists every status the table returns.
#include <gtest/gtest.h>

#include <cstdlib>
#include <set>
#include <sstream>
#include <string>

#include "native/exit_status.h"

namespace prt {
namespace {

constexpr int kFirstCode = static_cast<int>(StatusCode::kOk);
constexpr int kLastCode = static_cast<int>(StatusCode::kInternal);

TEST(ExitStatus, EveryCodeMapsIntoTheDocumentedSet) {
  const std::set<int> documented = {0, 2, 3, 4, 5, 6, 7};
  for (int c = kFirstCode; c <= kLastCode; ++c) {
    const auto code = static_cast<StatusCode>(c);
    const int status = exitStatusFor(code);
    EXPECT_TRUE(documented.count(status)) << statusCodeName(code) << " -> " << status;
    // Only success exits 0.
    EXPECT_EQ(status == 0, code == StatusCode::kOk) << statusCodeName(code);
  }
}

TEST(ExitStatus, Rows) {
  EXPECT_EQ(exitStatusFor(StatusCode::kOk), 0);
  EXPECT_EQ(exitStatusFor(StatusCode::kUsage), 2);
  EXPECT_EQ(exitStatusFor(StatusCode::kNotFound), 3);
  EXPECT_EQ(exitStatusFor(StatusCode::kIoError), 3);
  EXPECT_EQ(exitStatusFor(StatusCode::kInvalidArgument), 4);
  EXPECT_EQ(exitStatusFor(StatusCode::kTruncated), 4);
  EXPECT_EQ(exitStatusFor(StatusCode::kCorrupt), 4);
  EXPECT_EQ(exitStatusFor(StatusCode::kChecksumMismatch), 4);
  EXPECT_EQ(exitStatusFor(StatusCode::kInternal), 5);
  EXPECT_EQ(exitStatusFor(StatusCode::kResourceExhausted), 6);
  EXPECT_EQ(exitStatusFor(StatusCode::kUnavailable), 7);
  // The named constants are the same numbers.
  EXPECT_EQ(kExitOk, 0);
  EXPECT_EQ(kExitUsage, 2);
  EXPECT_EQ(kExitNotFound, 3);
  EXPECT_EQ(kExitInvalidInput, 4);
  EXPECT_EQ(kExitInternal, 5);
  EXPECT_EQ(kExitResourceExhausted, 6);
  EXPECT_EQ(kExitUnavailable, 7);
}

// A code outside the enumerators (a value added to StatusCode without a row) is internal.
TEST(ExitStatus, UnknownCodeIsInternal) {
  EXPECT_EQ(exitStatusFor(static_cast<StatusCode>(kLastCode + 1)), kExitInternal);
}

// The help paragraph: a heading line, then one "  N  text" line per status; every status
// the table can return is listed, and each listed number once.
TEST(ExitStatus, HelpListsEveryStatus) {
  const std::string help = exitStatusHelp();
  ASSERT_FALSE(help.empty());
  EXPECT_EQ(help.back(), '\n');
  std::istringstream lines(help);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "Exit status:");
  std::set<int> listed;
  while (std::getline(lines, line)) {
    ASSERT_EQ(line.rfind("  ", 0), 0u) << line;
    const std::string number = line.substr(2, line.find(' ', 2) - 2);
    if (number == "128+N") continue;  // signals
    char* end = nullptr;
    const long n = std::strtol(number.c_str(), &end, 10);
    ASSERT_EQ(*end, '\0') << line;
    EXPECT_TRUE(listed.insert(static_cast<int>(n)).second) << "listed twice: " << line;
    EXPECT_GT(line.size(), number.size() + 4) << "no description: " << line;
  }
  for (int c = kFirstCode; c <= kLastCode; ++c) {
    const auto code = static_cast<StatusCode>(c);
    EXPECT_TRUE(listed.count(exitStatusFor(code)))
        << statusCodeName(code) << " -> " << exitStatusFor(code) << " not in help";
  }
  EXPECT_TRUE(listed.count(kExitInternal));
  EXPECT_EQ(listed, (std::set<int>{0, 2, 3, 4, 5, 6, 7}));
}

}  // namespace
}  // namespace prt
