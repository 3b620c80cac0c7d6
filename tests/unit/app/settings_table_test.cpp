// settings_table_test.cpp: the rasterizer's option table (engine/frame/settings_table.hpp) drives CLI parsing, help
// and JSON from one declaration: every row's flag parses, range and name errors name the option, defaults round-trip
// through get/set, and the JSON record and help text list every row.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/cli.hpp"
#include "frame/settings_table.hpp"

namespace idk::frame {
namespace {

core::CliArgs parse(const std::vector<std::string>& argv) { return core::parseCli(argv, withSettingOptions({})); }

TEST(SettingsTable, FlagsAreUniqueAndEveryRowIsComplete) {
    std::set<std::string> flags;
    for (const SettingOption& o : settingOptions()) {
        EXPECT_TRUE(flags.insert(o.flag).second) << o.flag << " twice";
        EXPECT_EQ(std::string(o.flag).rfind("--", 0), 0u) << o.flag;
        EXPECT_NE(o.get, nullptr) << o.flag;
        EXPECT_NE(o.set, nullptr) << o.flag;
        if (o.kind == OptionKind::Choice) {
            EXPECT_GE(o.choices.size(), 2u) << o.flag;
        }
        if (o.kind == OptionKind::Number || o.kind == OptionKind::Integer) {
            EXPECT_LT(o.min, o.max) << o.flag;
        }
    }
}

TEST(SettingsTable, DefaultsRoundTripThroughGetAndSet) {
    const render::RenderSettings defaults;
    for (const SettingOption& o : settingOptions()) {
        render::RenderSettings s;
        o.set(s, o.get(defaults));
        EXPECT_EQ(settingsJson(s), settingsJson(defaults)) << o.flag;
    }
}

TEST(SettingsTable, ParsesValuesIntoTheSettings) {
    render::RenderSettings s;
    applySettingOptions(parse({"--exposure", "2.5", "--env-intensity=0", "--shadow-lights", "3", "--shadow-size", "1024"}),
                        s);
    EXPECT_FLOAT_EQ(s.exposure, 2.5f);
    EXPECT_FLOAT_EQ(s.environmentIntensity, 0.0f);
    EXPECT_EQ(s.pointShadows.maxLights, 3u);
    EXPECT_EQ(s.pointShadows.resolution, 1024u);
    const nlohmann::json j = settingsJson(s);
    EXPECT_EQ(j.at("exposure"), 2.5);
    EXPECT_EQ(j.at("shadow-lights"), 3);
    EXPECT_EQ(j.at("shadow-size"), "1024");
    EXPECT_EQ(j.at("gi-resolution"), "half");  // VXGI's default (frame/vxgi_settings.hpp)
    applySettingOptions(parse({"--gi-resolution", "full"}), s);
    EXPECT_EQ(s.vxgi.resolution, frame::GiResolution::Full);
}

TEST(SettingsTable, BadValuesNameTheOptionAndWhatIsAccepted) {
    render::RenderSettings s;
    const auto message = [&](const std::vector<std::string>& argv) {
        try {
            applySettingOptions(parse(argv), s);
        } catch (const core::CliError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_NE(message({"--exposure", "-1"}).find("--exposure '-1'"), std::string::npos);
    EXPECT_NE(message({"--exposure", "nan"}).find("--exposure"), std::string::npos);
    EXPECT_NE(message({"--shadow-lights", "2.5"}).find("whole number"), std::string::npos);
    const std::string size = message({"--shadow-size", "300"});
    EXPECT_NE(size.find("128|256|512|1024|2048"), std::string::npos) << size;
    EXPECT_EQ(s.pointShadows.resolution, render::RenderSettings{}.pointShadows.resolution);  // untouched on error
}

// The voxel debug view: parsed with --gi vxgi; without it, or past the grid's last level (log2 voxels), an error
// naming the flag.
TEST(SettingsTable, GiDebugNeedsVxgiAndALevelTheGridHas) {
    render::RenderSettings s;
    applySettingOptions(parse({"--gi", "vxgi", "--voxels", "64", "--gi-debug", "voxels", "--gi-debug-level", "6"}), s);
    EXPECT_EQ(s.vxgi.debug, frame::GiDebug::Voxels);
    EXPECT_EQ(s.vxgi.debugLevel, 6u);
    EXPECT_EQ(settingsJson(s).at("gi-debug"), "voxels");
    const auto message = [](const std::vector<std::string>& argv) {
        render::RenderSettings t;
        try {
            applySettingOptions(parse(argv), t);
        } catch (const core::CliError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string none = message({"--gi-debug", "voxels"});
    EXPECT_NE(none.find("--gi-debug 'voxels'"), std::string::npos) << none;
    EXPECT_NE(none.find("--gi vxgi"), std::string::npos) << none;
    EXPECT_EQ(message({"--gi-debug", "off"}), "no error");
    const std::string level =
        message({"--gi", "vxgi", "--voxels", "64", "--gi-debug", "voxels", "--gi-debug-level", "7"});
    EXPECT_NE(level.find("--gi-debug-level '7'"), std::string::npos) << level;
    EXPECT_NE(level.find("levels 0 to 6"), std::string::npos) << level;
}

// Issue 12's selection `--aa none|taa [--upscale S]`: --aa taa with S < 1 runs the upscaler (--aa upscale is kept
// as its alias); --upscale with --aa none would run no temporal pass at all, so it is an error naming the flag.
TEST(SettingsTable, UpscaleScaleGoesWithTemporalAntiAliasing) {
    render::RenderSettings s;
    applySettingOptions(parse({"--aa", "taa", "--upscale", "0.5"}), s);
    EXPECT_EQ(s.temporal.aa, AntiAliasing::Taa);
    EXPECT_FLOAT_EQ(s.temporal.upscale, 0.5f);
    EXPECT_TRUE(upscalerRuns(s.temporal));
    render::RenderSettings alias;
    applySettingOptions(parse({"--aa", "upscale", "--upscale", "0.5"}), alias);
    EXPECT_TRUE(upscalerRuns(alias.temporal));
    render::RenderSettings none;
    try {
        applySettingOptions(parse({"--upscale", "0.5"}), none);
        ADD_FAILURE() << "--upscale without --aa taa was accepted";
    } catch (const core::CliError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("--upscale '0.5'"), std::string::npos) << m;
        EXPECT_NE(m.find("--aa taa"), std::string::npos) << m;
    }
}

TEST(SettingsTable, HelpAndJsonListEveryRow) {
    const std::string help = settingOptionsHelp();
    const nlohmann::json j = settingsJson(render::RenderSettings{});
    for (const SettingOption& o : settingOptions()) {
        EXPECT_NE(help.find(o.flag), std::string::npos) << o.flag;
        EXPECT_TRUE(j.contains(std::string(o.flag).substr(2))) << o.flag;
    }
    EXPECT_NE(help.find("default 512"), std::string::npos) << help;
}

}  // namespace
}  // namespace idk::frame
