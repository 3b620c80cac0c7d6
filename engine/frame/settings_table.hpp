// settings_table.hpp: the user-settable options of the rasterized frame, declared once. The `idk render` and
// idk-viewer command lines, their --help text, the viewer's settings panels and the `--stats --json` record are
// all generated from this table, so a feature adds its options in one place (settings_table.cpp).
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "core/cli.hpp"
#include "render/render_settings.hpp"

namespace idk::frame {

enum class OptionKind : uint8_t {
    Number,   // --flag X, a float in [min, max]
    Integer,  // --flag N, a whole number in [min, max]
    Choice,   // --flag NAME, one of `choices` (the value is the index)
    Toggle,   // --flag alone switches it on (value 1; default off)
};

struct SettingOption {
    const char* flag;   // the CLI flag, e.g. "--exposure"; without its dashes it is the JSON key
    const char* panel;  // the viewer section that shows it
    const char* label;  // the viewer's label
    const char* help;   // one line for --help
    OptionKind kind = OptionKind::Number;
    double min = 0.0, max = 0.0;        // Number/Integer: accepted range, and the viewer slider's
    std::vector<const char*> choices;   // Choice: accepted names, in value order
    double (*get)(const render::RenderSettings&) = nullptr;
    void (*set)(render::RenderSettings&, double) = nullptr;
    bool logarithmic = false;           // the viewer slider's scale
};

const std::vector<SettingOption>& settingOptions();

// Adds every option's flag to a command's CliSpec.
core::CliSpec withSettingOptions(core::CliSpec spec);
// Applies the options present in `args` to `settings`; throws core::CliError naming the option and the range or
// the accepted names.
void applySettingOptions(const core::CliArgs& args, render::RenderSettings& settings);
// The options' --help lines, each with its default.
std::string settingOptionsHelp();
// Every option's current value, keyed by its flag without dashes (Choice: the name; Toggle: true/false).
nlohmann::json settingsJson(const render::RenderSettings& settings);
// The value of an option as text (Choice: its name), for the viewer and the JSON record.
std::string optionValueText(const SettingOption& option, const render::RenderSettings& settings);

}  // namespace idk::frame
