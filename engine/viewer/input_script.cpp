// input_script.cpp: key names and the parser of the viewer's timed input scripts (format in input.hpp). Kept apart
// from the GLFW callbacks so the libFuzzer harness (tests/fuzz/fuzz_script.cpp) links it without a window system:
// only GLFW's key-code macros are used here.
#include "viewer/input.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

namespace idk::viewer {

int mouseButtonCode(int glfwButton) { return GLFW_KEY_LAST + 1 + glfwButton; }

int keyCodeFromName(const std::string& raw) {
    std::string name = raw;
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return char(std::toupper(c)); });
    if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
    if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
    static const std::map<std::string, int> named = {
        {"SPACE", GLFW_KEY_SPACE},           {"SHIFT", GLFW_KEY_LEFT_SHIFT},
        {"LEFT_SHIFT", GLFW_KEY_LEFT_SHIFT}, {"CTRL", GLFW_KEY_LEFT_CONTROL},
        {"LEFT_CONTROL", GLFW_KEY_LEFT_CONTROL}, {"ESCAPE", GLFW_KEY_ESCAPE},
        {"ESC", GLFW_KEY_ESCAPE},            {"F11", GLFW_KEY_F11},
        {"ENTER", GLFW_KEY_ENTER},           {"TAB", GLFW_KEY_TAB},
        {"MOUSE_LEFT", mouseButtonCode(GLFW_MOUSE_BUTTON_LEFT)},
        {"MOUSE_RIGHT", mouseButtonCode(GLFW_MOUSE_BUTTON_RIGHT)},
        {"MOUSE_MIDDLE", mouseButtonCode(GLFW_MOUSE_BUTTON_MIDDLE)},
    };
    auto it = named.find(name);
    return it == named.end() ? -1 : it->second;
}

std::vector<ScriptEvent> parseInputScriptText(const std::string& text, const std::string& name) {
    std::vector<ScriptEvent> events;
    std::istringstream lines(text);
    std::string line;
    for (int number = 1; std::getline(lines, line); ++number) {
        if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        std::string frameText, action;
        if (!(words >> frameText)) continue;  // blank or comment
        auto fail = [&](const std::string& cause) {
            throw std::runtime_error(name + ":" + std::to_string(number) + ": " + cause);
        };
        if (frameText.find_first_not_of("0123456789") != std::string::npos)
            fail("'" + frameText + "' is not a frame number");
        ScriptEvent e;
        // from_chars, not stoull: a number past 2^64 must be this file's error, not std::out_of_range (found by
        // tests/fuzz/fuzz_script.cpp). The last value is refused too: `press` needs frame + 1 for its key-up.
        const auto [end, error] = std::from_chars(frameText.data(), frameText.data() + frameText.size(), e.frame);
        if (error != std::errc() || end != frameText.data() + frameText.size() ||
            e.frame == std::numeric_limits<uint64_t>::max())
            fail("frame number " + frameText + " is too large");
        if (!(words >> action)) fail("missing action (down, up, press, mouse or cursor)");
        if (action == "down" || action == "up" || action == "press") {
            std::string key;
            if (!(words >> key)) fail("missing key name");
            e.key = keyCodeFromName(key);
            if (e.key < 0) fail("unknown key '" + key + "'");
            e.action = action == "up" ? ScriptAction::Up : ScriptAction::Down;
            events.push_back(e);
            if (action == "press") {
                ScriptEvent up = e;
                up.action = ScriptAction::Up;
                up.frame = e.frame + 1;
                events.push_back(up);
            }
        } else if (action == "mouse" || action == "cursor" || action == "resize") {
            if (!(words >> e.value.x >> e.value.y)) fail("'" + action + "' needs two numbers");
            if (action == "resize" && !(e.value.x >= 1 && e.value.y >= 1 && e.value.x <= 16384 && e.value.y <= 16384))
                fail("resize needs a width and height in 1..16384");
            e.action = action == "mouse" ? ScriptAction::Mouse : action == "cursor" ? ScriptAction::Cursor : ScriptAction::Resize;
            events.push_back(e);
        } else {
            fail("unknown action '" + action + "' (down, up, press, mouse, cursor or resize)");
        }
        std::string extra;
        if (words >> extra) fail("unexpected '" + extra + "'");
    }
    std::stable_sort(events.begin(), events.end(), [](const ScriptEvent& a, const ScriptEvent& b) { return a.frame < b.frame; });
    return events;
}

std::vector<ScriptEvent> parseInputScript(const std::filesystem::path& path) {
    std::ifstream file(path);
    if (!file) throw std::runtime_error(path.string() + ": cannot open the input script");
    std::stringstream text;
    text << file.rdbuf();
    return parseInputScriptText(text.str(), path.string());
}

}  // namespace idk::viewer
