// native/cli_args: the strict flag parser and its ranged numbers. Errors are checked by
// their messages (which must name the flag, the value and the range), not by their
// StatusCode.
#include <gtest/gtest.h>

#include <climits>
#include <string>
#include <vector>

#include "native/cli_args.h"

namespace prt {
namespace {

const FlagSpec kSpecs[] = {
    {"--order", true},
    {"--out", true},
    {"--json", false},
    {"--verbose", false},
};

Status parse(const std::vector<std::string>& args, ParsedArgs* out) { return parseArgs(args, kSpecs, out); }

ParsedArgs parseOk(const std::vector<std::string>& args) {
  ParsedArgs p;
  const Status s = parse(args, &p);
  EXPECT_TRUE(s.isOk()) << s.toString();
  return p;
}

std::string parseError(const std::vector<std::string>& args) {
  ParsedArgs p;
  const Status s = parse(args, &p);
  EXPECT_FALSE(s.isOk());
  return s.message();
}

TEST(ParseArgs, SpaceAndEqualsFormsAgree) {
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--order", "3"}, {"--order=3"}}) {
    const ParsedArgs p = parseOk(args);
    ASSERT_TRUE(p.has("--order"));
    ASSERT_NE(p.value("--order"), nullptr);
    EXPECT_EQ(*p.value("--order"), "3");
    EXPECT_TRUE(p.positionals.empty());
    EXPECT_EQ(p.values.size(), 1u);
  }
  // Only the first '=' splits: the value may hold more.
  EXPECT_EQ(*parseOk({"--out=a=b.prt"}).value("--out"), "a=b.prt");
  // A value may look like a negative number or a single dash.
  EXPECT_EQ(*parseOk({"--order", "-1"}).value("--order"), "-1");
  EXPECT_EQ(*parseOk({"--out", "-"}).value("--out"), "-");
}

TEST(ParseArgs, SwitchesAndPositionals) {
  const ParsedArgs p = parseOk({"in.exr", "--json", "--order", "4", "out.prt", "-", "--verbose"});
  EXPECT_TRUE(p.has("--json"));
  EXPECT_TRUE(p.has("--verbose"));
  EXPECT_EQ(*p.value("--json"), "");
  EXPECT_EQ(*p.value("--order"), "4");
  EXPECT_FALSE(p.has("--out"));
  EXPECT_EQ(p.value("--out"), nullptr);
  EXPECT_EQ(p.positionals, (std::vector<std::string>{"in.exr", "out.prt", "-"}));
}

TEST(ParseArgs, DoubleDashEndsTheFlags) {
  const ParsedArgs p = parseOk({"--order=2", "--", "--json", "--order", "--", "-x", "--bogus=1"});
  EXPECT_EQ(*p.value("--order"), "2");
  EXPECT_FALSE(p.has("--json"));
  EXPECT_EQ(p.positionals, (std::vector<std::string>{"--json", "--order", "--", "-x", "--bogus=1"}));
}

TEST(ParseArgs, ReplacesWhatOutHeld) {
  ParsedArgs p;
  p.positionals = {"old"};
  p.values["--json"] = "";
  ASSERT_TRUE(parse({"new"}, &p).isOk());
  EXPECT_EQ(p.positionals, (std::vector<std::string>{"new"}));
  EXPECT_FALSE(p.has("--json"));
}

TEST(ParseArgs, UnknownFlag) {
  EXPECT_EQ(parseError({"--ordr", "3"}), "unknown option '--ordr'");
  EXPECT_EQ(parseError({"--ordr=3"}), "unknown option '--ordr'");
  EXPECT_EQ(parseError({"-o"}), "unknown option '-o'");
  EXPECT_EQ(parseError({"in.exr", "--JSON"}), "unknown option '--JSON'");
  EXPECT_EQ(parseError({"--order", "3", "--jsonx"}), "unknown option '--jsonx'");
}

TEST(ParseArgs, MissingValue) {
  EXPECT_EQ(parseError({"--order"}), "option --order needs a value");
  EXPECT_EQ(parseError({"--order="}), "option --order needs a value");
  // The next flag is not taken as the value.
  EXPECT_EQ(parseError({"--order", "--json"}), "option --order needs a value");
  EXPECT_EQ(parseError({"--out", "--"}), "option --out needs a value");
  EXPECT_EQ(parseError({"in.exr", "--out"}), "option --out needs a value");
}

TEST(ParseArgs, ValueGivenToASwitch) {
  EXPECT_EQ(parseError({"--json=1"}), "option --json takes no value");
  EXPECT_EQ(parseError({"--json="}), "option --json takes no value");
  EXPECT_EQ(parseError({"--verbose=false"}), "option --verbose takes no value");
}

TEST(ParseArgs, FlagGivenTwice) {
  EXPECT_EQ(parseError({"--order", "3", "--order", "4"}), "option --order given more than once");
  EXPECT_EQ(parseError({"--order=3", "--order", "3"}), "option --order given more than once");
  EXPECT_EQ(parseError({"--json", "x", "--json"}), "option --json given more than once");
}

TEST(WantsHelp, OnlyBeforeDoubleDash) {
  using Args = std::vector<std::string>;
  EXPECT_TRUE(wantsHelp(Args{"--help"}));
  EXPECT_TRUE(wantsHelp(Args{"-h"}));
  EXPECT_TRUE(wantsHelp(Args{"in.exr", "--bogus", "--order", "--help"}));  // help wins over errors
  EXPECT_TRUE(wantsHelp(Args{"--order", "3", "-h", "--"}));
  EXPECT_FALSE(wantsHelp(Args{}));
  EXPECT_FALSE(wantsHelp(Args{"--", "--help"}));
  EXPECT_FALSE(wantsHelp(Args{"x", "--", "-h"}));
  EXPECT_FALSE(wantsHelp(Args{"--helpme", "-help", "--help=1", "help", "-H"}));
}

TEST(ParseIntArg, AcceptsTheWholeRange) {
  int v = -99;
  ASSERT_TRUE(parseIntArg("--order", "3", 1, 16, &v).isOk());
  EXPECT_EQ(v, 3);
  ASSERT_TRUE(parseIntArg("--order", "1", 1, 16, &v).isOk());
  EXPECT_EQ(v, 1);
  ASSERT_TRUE(parseIntArg("--order", "16", 1, 16, &v).isOk());
  EXPECT_EQ(v, 16);
  ASSERT_TRUE(parseIntArg("--x", "-7", -10, 10, &v).isOk());
  EXPECT_EQ(v, -7);
  ASSERT_TRUE(parseIntArg("--x", "007", 0, 10, &v).isOk());
  EXPECT_EQ(v, 7);
  ASSERT_TRUE(parseIntArg("--x", "2147483647", INT_MIN, INT_MAX, &v).isOk());
  EXPECT_EQ(v, INT_MAX);
  ASSERT_TRUE(parseIntArg("--x", "-2147483648", INT_MIN, INT_MAX, &v).isOk());
  EXPECT_EQ(v, INT_MIN);
}

TEST(ParseIntArg, OutOfRangeNamesFlagValueAndRange) {
  int v = 77;
  Status s = parseIntArg("--order", "0", 1, 16, &v);
  EXPECT_FALSE(s.isOk());
  EXPECT_EQ(s.message(), "--order '0' is out of range; expected an integer in [1, 16]");
  s = parseIntArg("--order", "17", 1, 16, &v);
  EXPECT_EQ(s.message(), "--order '17' is out of range; expected an integer in [1, 16]");
  s = parseIntArg("--order", "-5", 1, 16, &v);
  EXPECT_EQ(s.message(), "--order '-5' is out of range; expected an integer in [1, 16]");
  // Beyond int, and beyond long long.
  s = parseIntArg("--x", "2147483648", INT_MIN, INT_MAX, &v);
  EXPECT_EQ(s.message(), "--x '2147483648' is out of range; expected an integer in [-2147483648, 2147483647]");
  s = parseIntArg("--x", "-2147483649", INT_MIN, INT_MAX, &v);
  EXPECT_FALSE(s.isOk());
  s = parseIntArg("--order", "99999999999999999999", 1, 16, &v);
  EXPECT_EQ(s.message(), "--order '99999999999999999999' is out of range; expected an integer in [1, 16]");
  s = parseIntArg("--order", "-99999999999999999999", 1, 16, &v);
  EXPECT_EQ(s.message(), "--order '-99999999999999999999' is out of range; expected an integer in [1, 16]");
  EXPECT_EQ(v, 77);  // untouched by every failure
}

TEST(ParseIntArg, NotAWholeIntegerNamesFlagRangeAndText) {
  int v = 77;
  for (const char* text : {"", "abc", "3x", "3 ", " 3", "+3", "3.0", "3e1", "0x10", "--", "-", "1,000", "٣"}) {
    const Status s = parseIntArg("--order", text, 1, 16, &v);
    EXPECT_FALSE(s.isOk()) << text;
    EXPECT_EQ(s.message(), std::string("--order expects an integer in [1, 16], got '") + text + "'");
  }
  EXPECT_EQ(v, 77);
}

TEST(ParseFloatArg, AcceptsTheWholeRange) {
  float v = -99.0f;
  ASSERT_TRUE(parseFloatArg("--exposure", "0.5", 0.0f, 1.0f, &v).isOk());
  EXPECT_EQ(v, 0.5f);
  ASSERT_TRUE(parseFloatArg("--exposure", "0", 0.0f, 1.0f, &v).isOk());
  EXPECT_EQ(v, 0.0f);
  ASSERT_TRUE(parseFloatArg("--exposure", "1", 0.0f, 1.0f, &v).isOk());
  EXPECT_EQ(v, 1.0f);
  ASSERT_TRUE(parseFloatArg("--exposure", "1e-3", 0.0f, 1.0f, &v).isOk());
  EXPECT_EQ(v, 1e-3f);
  ASSERT_TRUE(parseFloatArg("--exposure", "-2.25", -10.0f, 10.0f, &v).isOk());
  EXPECT_EQ(v, -2.25f);
  ASSERT_TRUE(parseFloatArg("--exposure", "0.1", 0.0f, 1.0f, &v).isOk());
  EXPECT_EQ(v, 0.1f);  // rounded as a float literal is
}

TEST(ParseFloatArg, OutOfRangeNamesFlagValueAndRange) {
  float v = 77.0f;
  Status s = parseFloatArg("--exposure", "1.5", 0.0f, 1.0f, &v);
  EXPECT_FALSE(s.isOk());
  EXPECT_EQ(s.message(), "--exposure '1.5' is out of range; expected a number in [0, 1]");
  s = parseFloatArg("--exposure", "-0.1", 0.0f, 1.0f, &v);
  EXPECT_EQ(s.message(), "--exposure '-0.1' is out of range; expected a number in [0, 1]");
  s = parseFloatArg("--width", "0.0005", 0.001f, 1000.0f, &v);
  EXPECT_EQ(s.message(), "--width '0.0005' is out of range; expected a number in [0.001, 1000]");
  // Too large for a float at all.
  s = parseFloatArg("--exposure", "1e39", 0.0f, 1.0f, &v);
  EXPECT_EQ(s.message(), "--exposure '1e39' is out of range; expected a number in [0, 1]");
  s = parseFloatArg("--exposure", "-1e300", -1.0f, 1.0f, &v);
  EXPECT_EQ(s.message(), "--exposure '-1e300' is out of range; expected a number in [-1, 1]");
  EXPECT_EQ(v, 77.0f);
}

TEST(ParseFloatArg, NotAFiniteNumberNamesFlagRangeAndText) {
  float v = 77.0f;
  for (const char* text : {"", "abc", "0.5x", "0.5 ", " 0.5", "+0.5", "0,5", "1e", "nan", "NaN", "-nan", "nan(1)",
                           "inf", "-inf", "INF", "infinity", "-Infinity", "0x1p-2"}) {
    const Status s = parseFloatArg("--exposure", text, -1.0f, 1.0f, &v);
    EXPECT_FALSE(s.isOk()) << text;
    EXPECT_EQ(s.message(), std::string("--exposure expects a number in [-1, 1], got '") + text + "'");
  }
  EXPECT_EQ(v, 77.0f);
}

}  // namespace
}  // namespace prt
