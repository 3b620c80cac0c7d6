// input.cpp: GLFW callbacks and the timed input script merged into one per-frame input stream.
#include "viewer/input.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cctype>
#include <fstream>
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
        e.frame = std::stoull(frameText);
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

void Input::attach(GLFWwindow* window) {
    window_ = window;
    glfwSetWindowUserPointer(window, this);
    glfwSetKeyCallback(window, &Input::keyCallback);
    glfwSetMouseButtonCallback(window, &Input::buttonCallback);
}

void Input::keyCallback(GLFWwindow* window, int key, int, int action, int mods) {
    auto* self = static_cast<Input*>(glfwGetWindowUserPointer(window));
    if (self && key >= 0 && action != GLFW_REPEAT) self->pending_.push_back({key, action == GLFW_PRESS, mods});
}

void Input::buttonCallback(GLFWwindow* window, int button, int action, int mods) {
    auto* self = static_cast<Input*>(glfwGetWindowUserPointer(window));
    if (self) self->pending_.push_back({mouseButtonCode(button), action == GLFW_PRESS, mods});
}

int Input::mods() const {
    int m = 0;
    if (down(GLFW_KEY_LEFT_CONTROL) || down(GLFW_KEY_RIGHT_CONTROL)) m |= GLFW_MOD_CONTROL;
    if (down(GLFW_KEY_LEFT_SHIFT) || down(GLFW_KEY_RIGHT_SHIFT)) m |= GLFW_MOD_SHIFT;
    return m;
}

void Input::beginFrame(uint64_t frame, bool cursorCaptured) {
    events_ = std::move(pending_);
    pending_.clear();
    mouseDelta_ = glm::vec2(0.0f);
    resize_ = glm::uvec2(0u);
    if (window_) {
        double x = 0, y = 0;
        glfwGetCursorPos(window_, &x, &y);
        const glm::vec2 real{float(x), float(y)};
        // Capturing the cursor re-centres it (GLFW's disabled mode): the first two frames after a change would
        // read that jump as mouse motion, so they only re-anchor.
        settleFrames_ = cursorCaptured != wasCaptured_ ? 2 : std::max(settleFrames_ - 1, 0);
        wasCaptured_ = cursorCaptured;
        if (haveRealCursor_ && cursorCaptured && settleFrames_ == 0) mouseDelta_ += real - lastRealCursor_;
        lastRealCursor_ = real;
        haveRealCursor_ = true;
        if (!scriptCursor_) cursor_ = real;
    }
    for (; nextScript_ < script_.size() && script_[nextScript_].frame <= frame; ++nextScript_) {
        const ScriptEvent& e = script_[nextScript_];
        switch (e.action) {
            case ScriptAction::Down:
                scriptedDown_.insert(e.key);
                events_.push_back({e.key, true, mods()});
                break;
            case ScriptAction::Up:
                scriptedDown_.erase(e.key);
                events_.push_back({e.key, false, mods()});
                break;
            case ScriptAction::Mouse: mouseDelta_ += e.value; break;
            case ScriptAction::Cursor:
                cursor_ = e.value;
                scriptCursor_ = true;
                break;
            case ScriptAction::Resize: resize_ = glm::uvec2(e.value); break;
        }
    }
}

bool Input::down(int key) const {
    if (scriptedDown_.count(key)) return true;
    if (!window_) return false;
    if (key > GLFW_KEY_LAST) return glfwGetMouseButton(window_, key - GLFW_KEY_LAST - 1) == GLFW_PRESS;
    return glfwGetKey(window_, key) == GLFW_PRESS;
}


}  // namespace idk::viewer
