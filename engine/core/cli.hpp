// cli.hpp: a small command-line parser for the `idk` subcommands: positional arguments, `--flag`, and
// `--option value` / `--option=value`. Unknown options and missing values are errors that name the option.
#pragma once
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace idk::core {

class CliError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

struct CliSpec {
    std::set<std::string> flags;    // e.g. "--json"
    std::set<std::string> options;  // take a value, e.g. "--out"
};

struct CliArgs {
    std::vector<std::string> positional;
    std::set<std::string> flags;
    std::map<std::string, std::string> options;  // the last value of each option
    std::vector<std::pair<std::string, std::string>> occurrences;  // every option and value, in order

    bool has(const std::string& flag) const { return flags.count(flag) != 0; }
    std::optional<std::string> get(const std::string& option) const;
    std::string get(const std::string& option, const std::string& fallback) const;
    std::vector<std::string> getAll(const std::string& option) const;  // a repeatable option's values, in order
};

CliArgs parseCli(const std::vector<std::string>& args, const CliSpec& spec);

// "256x128" -> {256, 128}; throws CliError naming the text.
std::pair<uint32_t, uint32_t> parseSize(const std::string& text);
double parseNumber(const std::string& option, const std::string& text);

}  // namespace idk::core
