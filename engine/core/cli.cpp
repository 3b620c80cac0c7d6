// cli.cpp: argument parsing for the command line tools.
#include "core/cli.hpp"

#include <charconv>
#include <cstdint>

namespace idk::core {

std::optional<std::string> CliArgs::get(const std::string& option) const {
    auto it = options.find(option);
    if (it == options.end()) return std::nullopt;
    return it->second;
}

std::string CliArgs::get(const std::string& option, const std::string& fallback) const {
    return get(option).value_or(fallback);
}

std::vector<std::string> CliArgs::getAll(const std::string& option) const {
    std::vector<std::string> values;
    for (const auto& [name, value] : occurrences)
        if (name == option) values.push_back(value);
    return values;
}

CliArgs parseCli(const std::vector<std::string>& args, const CliSpec& spec) {
    CliArgs out;
    for (size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (a.size() < 2 || a.rfind("--", 0) != 0) {
            if (a.size() > 1 && a[0] == '-') throw CliError("unknown option '" + a + "'");
            out.positional.push_back(a);
            continue;
        }
        std::string name = a, value;
        bool inlineValue = false;
        if (size_t eq = a.find('='); eq != std::string::npos) {
            name = a.substr(0, eq);
            value = a.substr(eq + 1);
            inlineValue = true;
        }
        if (spec.flags.count(name)) {
            if (inlineValue) throw CliError("option '" + name + "' takes no value");
            out.flags.insert(name);
        } else if (spec.options.count(name)) {
            if (!inlineValue) {
                if (i + 1 >= args.size()) throw CliError("option '" + name + "' needs a value");
                value = args[++i];
            }
            out.options[name] = value;
            out.occurrences.emplace_back(name, value);
        } else {
            throw CliError("unknown option '" + name + "'");
        }
    }
    return out;
}

std::pair<uint32_t, uint32_t> parseSize(const std::string& text) {
    size_t x = text.find('x');
    uint32_t w = 0, h = 0;
    auto parse = [](const std::string& s, uint32_t& v) {
        auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        return ec == std::errc() && ptr == s.data() + s.size();
    };
    if (x == std::string::npos || !parse(text.substr(0, x), w) || !parse(text.substr(x + 1), h) || w == 0 || h == 0 ||
        w > 16384 || h > 16384) {
        throw CliError("size '" + text + "' is not WIDTHxHEIGHT with both in 1..16384");
    }
    return {w, h};
}

double parseNumber(const std::string& option, const std::string& text) {
    try {
        size_t used = 0;
        double v = std::stod(text, &used);
        if (used != text.size()) throw std::invalid_argument(text);
        return v;
    } catch (const std::exception&) {
        throw CliError("option '" + option + "' needs a number, got '" + text + "'");
    }
}

}  // namespace idk::core
