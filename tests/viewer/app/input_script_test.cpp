// input_script_test.cpp: the viewer's pure parts without a display: the timed input script parser (press
// expansion, ordering, errors naming file and line) and the cursor ray used by picking (the centre pixel's ray is
// the view direction; a corner pixel's ray makes the half field-of-view angles).
#include <gtest/gtest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>

#include "viewer/input.hpp"
#include "viewer/picking.hpp"

namespace idk::viewer {
namespace {

TEST(InputScript, PressExpandsToDownThenUpAndEventsSortByFrame) {
    auto events = parseInputScriptText("# comment\n10 press w\n2 mouse 3.5 -2\n\n2 down SHIFT # held\n5 resize 96 48\n",
                                       "s.txt");
    ASSERT_EQ(events.size(), 5u);
    EXPECT_EQ(events[0].frame, 2u);
    EXPECT_EQ(events[0].action, ScriptAction::Mouse);
    EXPECT_EQ(events[0].value, glm::vec2(3.5f, -2.0f));
    EXPECT_EQ(events[1].action, ScriptAction::Down);
    EXPECT_EQ(events[1].key, GLFW_KEY_LEFT_SHIFT);
    EXPECT_EQ(events[2].action, ScriptAction::Resize);
    EXPECT_EQ(events[3].frame, 10u);
    EXPECT_EQ(events[3].action, ScriptAction::Down);
    EXPECT_EQ(events[3].key, GLFW_KEY_W);
    EXPECT_EQ(events[4].frame, 11u);
    EXPECT_EQ(events[4].action, ScriptAction::Up);
    EXPECT_EQ(keyCodeFromName("mouse_right"), mouseButtonCode(GLFW_MOUSE_BUTTON_RIGHT));
    EXPECT_EQ(keyCodeFromName("F12"), -1);
}

TEST(InputScript, ErrorsNameFileLineAndCause) {
    auto message = [](const std::string& text) {
        try {
            parseInputScriptText(text, "s.txt");
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(message("1 press W\nx press W\n"), "s.txt:2: 'x' is not a frame number");
    EXPECT_EQ(message("1 press HYPER\n"), "s.txt:1: unknown key 'HYPER'");
    EXPECT_EQ(message("1 mouse 3\n"), "s.txt:1: 'mouse' needs two numbers");
    EXPECT_EQ(message("1 press W now\n"), "s.txt:1: unexpected 'now'");
    EXPECT_EQ(message("1 resize 0 10\n"), "s.txt:1: resize needs a width and height in 1..16384");
    // Past 2^64 (was std::out_of_range from stoull, found by fuzz_script) and the last uint64 (no frame after it).
    EXPECT_EQ(message("\n99999999999999999999 down W\n"), "s.txt:2: frame number 99999999999999999999 is too large");
    EXPECT_EQ(message("18446744073709551615 press W\n"), "s.txt:1: frame number 18446744073709551615 is too large");
    EXPECT_EQ(parseInputScriptText("18446744073709551614 press W\n", "s.txt").back().frame, 18446744073709551615u);
}

TEST(CursorRay, CentreFollowsTheViewAndCornersMakeHalfTheFieldOfView) {
    scene::CameraView camera;
    camera.position = {1.0f, 2.0f, 3.0f};
    camera.forward = glm::normalize(glm::vec3(1.0f, 0.0f, -1.0f));
    camera.up = {0.0f, 1.0f, 0.0f};
    camera.yfov = glm::radians(60.0f);
    glm::vec3 origin, direction;
    // Pixel (49.5 - 0.5) is the centre of a 100 x 50 view: the ray is the view direction from (near) the eye.
    cursorRay(camera, {49.5f, 24.5f}, 100, 50, origin, direction);
    EXPECT_NEAR(glm::dot(direction, camera.forward), 1.0f, 1e-5f);
    EXPECT_NEAR(glm::length(glm::cross(origin - camera.position, camera.forward)), 0.0f, 1e-4f);
    // The top edge's middle (y = -0.5 is the edge line): 30 degrees above the view direction, upwards.
    cursorRay(camera, {49.5f, -0.5f}, 100, 50, origin, direction);
    EXPECT_NEAR(std::acos(glm::dot(direction, camera.forward)), glm::radians(30.0f), 1e-4f);
    EXPECT_GT(direction.y, 0.0f);
}

}  // namespace
}  // namespace idk::viewer
