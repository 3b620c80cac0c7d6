// input.cpp: GLFW callbacks and the timed input script merged into one per-frame input stream (the script's
// parser is input_script.cpp).
#include "viewer/input.hpp"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <algorithm>

namespace idk::viewer {

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
