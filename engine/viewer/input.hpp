// input.hpp: the viewer's input as one stream, whether it comes from GLFW or from a timed script (tests drive
// the viewer with the same code path a user does). Keys are GLFW key codes; mouse buttons get codes above
// GLFW_KEY_LAST. A script is a text file of lines
//     FRAME down KEY | FRAME up KEY | FRAME press KEY | FRAME mouse DX DY | FRAME cursor X Y | FRAME resize W H
// (FRAME = the 0-based rendered frame the event applies to, '#' starts a comment). `press` is down at FRAME and
// up at FRAME + 1; `mouse` adds a relative motion (mouse look), `cursor` places the cursor (picking), `resize`
// asks the window system for a new window size.
#pragma once
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>

struct GLFWwindow;

namespace idk::viewer {

int mouseButtonCode(int glfwButton);    // GLFW_MOUSE_BUTTON_* -> input code
int keyCodeFromName(const std::string& name);  // "W", "SPACE", "MOUSE_RIGHT"...; -1 if unknown

enum class ScriptAction : uint8_t { Down, Up, Mouse, Cursor, Resize };
struct ScriptEvent {
    uint64_t frame = 0;
    ScriptAction action = ScriptAction::Down;
    int key = -1;
    glm::vec2 value{0.0f};
};
// Throws std::runtime_error "FILE:LINE: cause". Events come back sorted by frame (stable).
std::vector<ScriptEvent> parseInputScript(const std::filesystem::path& path);
std::vector<ScriptEvent> parseInputScriptText(const std::string& text, const std::string& name);

struct KeyEvent {
    int key = 0;
    bool down = true;
    int mods = 0;  // GLFW_MOD_* of the keys held when it happened
};

class Input {
public:
    // Installs GLFW key/button callbacks on the window (call before ImGui's GLFW backend, which chains them).
    void attach(GLFWwindow* window);
    void setScript(std::vector<ScriptEvent> events) { script_ = std::move(events); }

    // Collects this frame's events (call after glfwPollEvents): GLFW callbacks and the script's events of `frame`.
    void beginFrame(uint64_t frame, bool cursorCaptured);

    bool down(int key) const;                        // held (real or scripted)
    const std::vector<KeyEvent>& events() const { return events_; }  // transitions this frame, in order
    glm::vec2 mouseDelta() const { return mouseDelta_; }              // pixels since the last frame
    glm::vec2 cursor() const { return cursor_; }                      // window pixels
    // A scripted window size for this frame (0x0: none).
    glm::uvec2 resizeRequest() const { return resize_; }

private:
    static void keyCallback(GLFWwindow* window, int key, int scancode, int action, int mods);
    static void buttonCallback(GLFWwindow* window, int button, int action, int mods);
    int mods() const;

    GLFWwindow* window_ = nullptr;
    std::vector<ScriptEvent> script_;
    size_t nextScript_ = 0;
    std::vector<KeyEvent> pending_;  // from callbacks since the last beginFrame
    std::vector<KeyEvent> events_;
    std::set<int> scriptedDown_;
    glm::vec2 mouseDelta_{0.0f}, cursor_{0.0f}, lastRealCursor_{0.0f};
    glm::uvec2 resize_{0u};
    bool haveRealCursor_ = false;
    bool wasCaptured_ = false;
    int settleFrames_ = 0;
    bool scriptCursor_ = false;
};

}  // namespace idk::viewer
