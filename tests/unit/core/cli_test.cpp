// cli_test.cpp: the command-line parser: positional arguments, flags, options with values, and the errors.
#include <gtest/gtest.h>

#include "core/cli.hpp"

namespace idk::core {
namespace {

const CliSpec kSpec{{"--json", "--stats"}, {"--out", "--size"}};

TEST(Cli, ParsesPositionalFlagsAndOptions) {
    CliArgs a = parseCli({"scene.glb", "--json", "--out", "x.png", "--size=64x32"}, kSpec);
    ASSERT_EQ(a.positional.size(), 1u);
    EXPECT_EQ(a.positional[0], "scene.glb");
    EXPECT_TRUE(a.has("--json"));
    EXPECT_FALSE(a.has("--stats"));
    EXPECT_EQ(a.get("--out").value(), "x.png");
    EXPECT_EQ(a.get("--size").value(), "64x32");
    EXPECT_EQ(a.get("--missing", "fallback"), "fallback");
}

TEST(Cli, RepeatedOptionsKeepEveryValueInOrder) {
    CliArgs a = parseCli({"--out", "a", "--size=1x1", "--out=b", "--out", "c"}, kSpec);
    EXPECT_EQ(a.getAll("--out"), (std::vector<std::string>{"a", "b", "c"}));
    EXPECT_EQ(a.get("--out").value(), "c");  // get: the last one
    EXPECT_EQ(a.getAll("--size"), std::vector<std::string>{"1x1"});
    EXPECT_TRUE(a.getAll("--missing").empty());
}

TEST(Cli, RejectsUnknownOptionsAndMissingValues) {
    EXPECT_THROW(parseCli({"--bogus"}, kSpec), CliError);
    EXPECT_THROW(parseCli({"-x"}, kSpec), CliError);
    EXPECT_THROW(parseCli({"--out"}, kSpec), CliError);
    EXPECT_THROW(parseCli({"--json=1"}, kSpec), CliError);
}

TEST(Cli, ParsesSizes) {
    EXPECT_EQ(parseSize("256x128"), (std::pair<uint32_t, uint32_t>{256, 128}));
    EXPECT_THROW(parseSize("256"), CliError);
    EXPECT_THROW(parseSize("0x10"), CliError);
    EXPECT_THROW(parseSize("10x"), CliError);
    EXPECT_THROW(parseSize("-5x10"), CliError);
    EXPECT_THROW(parseSize("99999x10"), CliError);
    EXPECT_THROW(parseSize("12ax10"), CliError);
}

TEST(Cli, ParsesNumbers) {
    EXPECT_DOUBLE_EQ(parseNumber("--time", "1.5"), 1.5);
    EXPECT_THROW(parseNumber("--time", "1.5s"), CliError);
    EXPECT_THROW(parseNumber("--time", ""), CliError);
}

}  // namespace
}  // namespace idk::core
