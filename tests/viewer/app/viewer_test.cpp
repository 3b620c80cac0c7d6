// viewer_test.cpp: idk-viewer end to end under Xvfb (lavapipe presents through VK_KHR_xcb/xlib_surface): the
// screenshot after 60 frames matches `idk render` of the same camera, a scripted Esc exits 0, no display gives a
// message that points to `idk render`, hot reload keeps the old pipeline on a broken edit and applies a valid
// one, the camera stops at a wall and slides along it, right-click picks the object under the cursor.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <thread>

#include "tools/camera_capture.hpp"
#include "viewer/app/viewer_harness.hpp"

namespace idk::test {
namespace {

const std::string kViewer = IDK_VIEWER_EXE;
const std::string kRender = IDK_RENDER_EXE;
const std::filesystem::path kShared = IDK_SHARED_DIR;

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// Tolerance of the viewer's screenshot against `idk render`: both run the same passes on the same device, so
// the only expected difference is the camera's round trip through the fly-camera state (yaw/pitch and back),
// a few ulps in the view matrix: at most 0.1% of the pixels may differ by more than 2 codes, mean below 0.1.
constexpr int kSameFrameCodes = 2;
constexpr double kSameFrameFraction = 0.001;
constexpr double kSameFrameMean = 0.1;

ProcessResult runViewer(const std::string& args) {
    return runCommand(kViewer + " " + args, "DISPLAY=" + xvfbDisplay());
}

Codes renderReference(const std::filesystem::path& folder, const std::filesystem::path& scene, const std::string& size) {
    std::filesystem::path out = folder / "reference.png";
    ProcessResult r = runCommand(kRender + " render " + quoted(scene) + " --size " + size + " --out " + quoted(out));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readCodes(out);
}

struct CameraLine {
    glm::vec3 position{0.0f};
    float yaw = 0, pitch = 0, radius = 0;
};
// Parses "camera position X Y Z yaw A pitch B radius R" (a stream, not std::regex: GCC 12 reports a false
// -Wmaybe-uninitialized inside <regex> in the sanitizer build).
CameraLine parseCamera(const std::string& output) {
    CameraLine c;
    const size_t at = output.find("camera position ");
    if (at == std::string::npos) {
        ADD_FAILURE() << "no camera line in:\n" << output;
        return c;
    }
    std::istringstream line(output.substr(at + std::string("camera position ").size()));
    std::string yawWord, pitchWord, radiusWord;
    line >> c.position.x >> c.position.y >> c.position.z >> yawWord >> c.yaw >> pitchWord >> c.pitch >> radiusWord >>
        c.radius;
    if (!line || yawWord != "yaw" || pitchWord != "pitch" || radiusWord != "radius")
        ADD_FAILURE() << "malformed camera line in:\n" << output;
    return c;
}

TEST(Viewer, SixtyFramesMatchIdkRenderAndScriptedEscExitsZero) {
    std::filesystem::path folder = testFolder("screenshot");
    std::filesystem::path scene = kShared / "scenes/DamagedHelmet/glTF-Binary/DamagedHelmet.glb";
    ASSERT_TRUE(std::filesystem::exists(scene)) << scene;
    writeText(folder / "script.txt", "# Esc after 60 rendered frames (0..59)\n60 press ESCAPE\n");
    // No --frames: only the scripted Esc ends the run. --sync-textures: every texture before frame 0, as idk render.
    ProcessResult r = runViewer(quoted(scene) + " --size 128x128 --sync-textures --script " +
                                quoted(folder / "script.txt") + " --screenshot " + quoted(folder / "viewer.png"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("idk-viewer: 60 frames"), std::string::npos) << r.output;

    Codes reference = renderReference(folder, scene, "128x128");
    Codes shot = readCodes(folder / "viewer.png");
    CodeDifference d = compareCodes(shot, reference, kSameFrameCodes);
    EXPECT_LE(d.fractionOver, kSameFrameFraction) << "max " << d.maxRgb << " mean " << d.meanRgb;
    EXPECT_LE(d.meanRgb, kSameFrameMean) << "max " << d.maxRgb;
    // Not trivially equal: the helmet covers a good part of the frame with varied colours.
    Codes black{reference.width, reference.height, std::vector<uint8_t>(reference.rgba.size(), 0)};
    EXPECT_GT(compareCodes(reference, black, 8).fractionOver, 0.2);
}

// Window changes mid-run: a resize (the swapchain and the renderer's scene image follow), vsync off and on again
// (V: the swapchain is recreated with another present mode), fullscreen and back (F11). The last frame has the
// new size and still matches `idk render` at that size; validation stays clean (exit 0).
TEST(Viewer, ResizeVsyncAndFullscreenTogglesKeepRendering) {
    std::filesystem::path folder = testFolder("resize");
    std::filesystem::path scene = kShared / "scenes/Box/glTF-Binary/Box.glb";
    writeText(folder / "script.txt",
              "2 resize 96 48\n4 press V\n6 press V\n8 press F11\n11 press F11\n14 resize 96 48\n18 press ESCAPE\n");
    ProcessResult r = runViewer(quoted(scene) + " --size 64x64 --script " + quoted(folder / "script.txt") +
                                " --screenshot " + quoted(folder / "viewer.png"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    Codes shot = readCodes(folder / "viewer.png");
    EXPECT_EQ(shot.width, 96u);
    EXPECT_EQ(shot.height, 48u);
    CodeDifference d = compareCodes(shot, renderReference(folder, scene, "96x48"), kSameFrameCodes);
    EXPECT_LE(d.fractionOver, kSameFrameFraction) << "max " << d.maxRgb << " mean " << d.meanRgb;
}

// Issue 17 part 4: the 25th queue submission (a frame after start-up) fails as VK_ERROR_DEVICE_LOST through the test
// hook. The viewer keeps its window, says so on stderr, and the scripted Enter retries at half the size with the
// portable rungs: the run goes on, exits 0 with clean validation, and its last frame is the 64x64 frame that
// `idk render --fallback` draws of the same scene (the recovered device renders for real).
TEST(Viewer, DeviceLostKeepsTheWindowAndEnterRetriesAtHalfSize) {
    std::filesystem::path folder = testFolder("device_lost");
    writeText(folder / "script.txt", "30 press ENTER\n45 press ESCAPE\n");
    ProcessResult r = runCommand(kViewer + " --size 128x128 --fixed-dt 0.02 --script " + quoted(folder / "script.txt") +
                                     " --screenshot " + quoted(folder / "viewer.png"),
                                 "DISPLAY=" + xvfbDisplay() + " IDK_TEST_FAIL_SUBMIT=device-lost:25");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(": device lost (vkQueueSubmit2 failed with VK_ERROR_DEVICE_LOST (submission 25"),
              std::string::npos) << r.output;
    EXPECT_NE(r.output.find("The window stays open: press Enter to retry"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("retry 1 at 64x64 with the portable feature rungs"), std::string::npos) << r.output;
    Codes shot = readCodes(folder / "viewer.png");
    ASSERT_EQ(shot.width, 64u);
    ASSERT_EQ(shot.height, 64u);
    std::filesystem::path reference = folder / "reference.png";
    ProcessResult ref = runCommand(kRender + " render --fallback --size 64x64 --out " + quoted(reference));
    ASSERT_EQ(ref.exitCode, 0) << ref.output;
    CodeDifference d = compareCodes(shot, readCodes(reference), kSameFrameCodes);
    EXPECT_LE(d.fractionOver, kSameFrameFraction) << "max " << d.maxRgb << " mean " << d.meanRgb;
    EXPECT_LE(d.meanRgb, kSameFrameMean) << "max " << d.maxRgb;
}

// Out of device memory, and the user quits (Esc) instead of retrying: exit code 4 (as `idk render`), the error
// named, no screenshot written (there is no frame to write).
TEST(Viewer, OutOfDeviceMemoryThenEscExitsFourWithoutAScreenshot) {
    std::filesystem::path folder = testFolder("device_oom");
    writeText(folder / "script.txt", "30 press ESCAPE\n");
    ProcessResult r = runCommand(kViewer + " --size 96x96 --fixed-dt 0.02 --script " + quoted(folder / "script.txt") +
                                     " --screenshot " + quoted(folder / "viewer.png"),
                                 "DISPLAY=" + xvfbDisplay() + " IDK_TEST_FAIL_SUBMIT=out-of-device-memory:25");
    EXPECT_EQ(r.exitCode, 4) << r.output;
    EXPECT_NE(r.output.find("exiting after out of device memory"), std::string::npos) << r.output;
    EXPECT_FALSE(std::filesystem::exists(folder / "viewer.png"));
}

TEST(Viewer, NoDisplayExitsOneAndPointsToIdkRender) {
    ProcessResult r = runCommand("env -u DISPLAY -u WAYLAND_DISPLAY " + kViewer + " --frames 1");
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("no display"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("idk render"), std::string::npos) << r.output;
}

TEST(Viewer, BadScriptIsRejectedWithFileAndLine) {
    std::filesystem::path folder = testFolder("bad_script");
    writeText(folder / "script.txt", "3 press ESCAPE\n7 jump W\n");
    ProcessResult r = runViewer("--size 64x64 --no-ui --script " + quoted(folder / "script.txt"));
    EXPECT_EQ(r.exitCode, 1) << r.output;
    EXPECT_NE(r.output.find("script.txt:2: unknown action 'jump'"), std::string::npos) << r.output;
}

// Key 1 recompiles every shader from --shader-dir: a syntax error keeps the old tonemap pipeline (the frame is
// unchanged) and the compiler's message is printed; a valid edit (inverted output) changes the frame.
TEST(Viewer, HotReloadKeepsOldPipelineOnErrorAndAppliesValidEdit) {
    std::filesystem::path folder = testFolder("hot_reload");
    std::filesystem::path shaders = folder / "shaders";
    std::filesystem::copy(std::filesystem::path(IDK_SOURCE_DIR) / "shaders_glsl", shaders,
                          std::filesystem::copy_options::recursive);
    std::filesystem::path tonemap = shaders / "tonemap/tonemap.frag.glsl";
    std::stringstream original;
    original << std::ifstream(tonemap).rdbuf();
    const std::string source = original.str();
    const std::string line = "outColor = vec4(srgbEncode(agx(radiance)), 1.0);";
    ASSERT_NE(source.find(line), std::string::npos);

    writeText(folder / "script.txt", "3 press 1\n8 press ESCAPE\n");
    const std::string common = "--size 64x64 --no-ui --shader-dir " + quoted(shaders) + " --script " +
                               quoted(folder / "script.txt") + " --screenshot ";
    Codes reference = renderReference(folder, kShared / "scenes/Box/glTF-Binary/Box.glb", "64x64");
    const std::string scene = quoted(kShared / "scenes/Box/glTF-Binary/Box.glb") + " ";

    writeText(tonemap, source + "\nthis is not glsl\n");
    ProcessResult broken = runViewer(scene + common + quoted(folder / "broken.png"));
    ASSERT_EQ(broken.exitCode, 0) << broken.output;
    EXPECT_NE(broken.output.find("shader reload failed: tonemap/tonemap.frag.glsl"), std::string::npos) << broken.output;
    EXPECT_NE(broken.output.find("ERROR"), std::string::npos) << broken.output;  // glslang's message
    CodeDifference kept = compareCodes(readCodes(folder / "broken.png"), reference, kSameFrameCodes);
    EXPECT_LE(kept.fractionOver, kSameFrameFraction) << "mean " << kept.meanRgb;

    std::string inverted = source;
    inverted.replace(inverted.find(line), line.size(), "outColor = vec4(1.0 - srgbEncode(agx(radiance)), 1.0);");
    writeText(tonemap, inverted);
    ProcessResult valid = runViewer(scene + common + quoted(folder / "valid.png"));
    ASSERT_EQ(valid.exitCode, 0) << valid.output;
    EXPECT_EQ(valid.output.find("shader reload failed"), std::string::npos) << valid.output;
    Codes shot = readCodes(folder / "valid.png");
    // The inverted frame: every code is 255 - reference (8-bit rounding of 1 - x: at most 1 code off).
    Codes expected = reference;
    for (size_t i = 0; i < expected.rgba.size(); ++i)
        if (i % 4 != 3) expected.rgba[i] = uint8_t(255 - expected.rgba[i]);
    CodeDifference applied = compareCodes(shot, expected, kSameFrameCodes);
    EXPECT_LE(applied.fractionOver, kSameFrameFraction) << "mean " << applied.meanRgb;
    EXPECT_GT(compareCodes(shot, reference, 16).fractionOver, 0.5);  // and it is not the old frame
}

// --watch: a shader edited while the viewer runs is recompiled by the per-frame poll and used from then on. The
// test edits only after the viewer has rendered a few frames (it waits for the capture file that a scripted
// Ctrl+R start/stop writes at frame 7), so the edit is a change to an already loaded shader.
TEST(Viewer, WatchRecompilesAnEditedShaderWhileRunning) {
    std::filesystem::path folder = testFolder("watch");
    std::filesystem::path shaders = folder / "shaders";
    std::filesystem::copy(std::filesystem::path(IDK_SOURCE_DIR) / "shaders_glsl", shaders,
                          std::filesystem::copy_options::recursive);
    std::filesystem::path tonemap = shaders / "tonemap/tonemap.frag.glsl";
    std::stringstream original;
    original << std::ifstream(tonemap).rdbuf();
    std::string source = original.str();
    const std::string line = "outColor = vec4(srgbEncode(agx(radiance)), 1.0);";
    ASSERT_NE(source.find(line), std::string::npos);
    std::filesystem::path capture = folder / "started.idkcap";
    writeText(folder / "script.txt",
              "5 down CTRL\n5 press R\n6 up CTRL\n7 down CTRL\n7 press R\n8 up CTRL\n400 press ESCAPE\n");
    std::filesystem::path scene = kShared / "scenes/Box/glTF-Binary/Box.glb";
    ProcessResult r;
    std::thread viewer([&] {
        r = runViewer(quoted(scene) + " --size 64x64 --no-ui --watch --shader-dir " + quoted(shaders) +
                      " --capture " + quoted(capture) + " --script " + quoted(folder / "script.txt") +
                      " --screenshot " + quoted(folder / "viewer.png"));
    });
    for (int i = 0; i < 6000 && !std::filesystem::exists(capture); ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    source.replace(source.find(line), line.size(), "outColor = vec4(1.0 - srgbEncode(agx(radiance)), 1.0);");
    writeText(tonemap, source);
    viewer.join();
    ASSERT_TRUE(std::filesystem::exists(capture)) << r.output;
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find("tonemap/tonemap.frag.glsl: reloaded"), std::string::npos) << r.output;
    Codes expected = renderReference(folder, scene, "64x64");
    for (size_t i = 0; i < expected.rgba.size(); ++i)
        if (i % 4 != 3) expected.rgba[i] = uint8_t(255 - expected.rgba[i]);
    CodeDifference d = compareCodes(readCodes(folder / "viewer.png"), expected, kSameFrameCodes);
    EXPECT_LE(d.fractionOver, kSameFrameFraction) << "mean " << d.meanRgb;
}

// FPS mode (E), turn 30 degrees right by mouse, hold W: the camera sphere reaches the wall z = 0, stops one radius
// in front of it (never behind: no tunnelling) and slides along +x. Ctrl+R records the run meanwhile.
TEST(Viewer, CameraStopsAtWallAndSlides) {
    std::filesystem::path folder = testFolder("wall");
    std::filesystem::path scene = writeWallScene(folder, 6.0f);
    std::filesystem::path capture = folder / "run.idkcap";
    writeText(folder / "script.txt",
              "0 press E\n"
              "1 mouse 333.333 0\n"    // 0.09 degrees per pixel: 30 degrees of yaw
              "1 down CTRL\n1 press R\n2 up CTRL\n"
              "2 down W\n62 up W\n"    // 60 frames of 20 ms
              "80 down CTRL\n80 press R\n81 up CTRL\n"
              "90 press ESCAPE\n");
    ProcessResult r = runViewer(quoted(scene) + " --size 64x64 --no-ui --fixed-dt 0.02 --capture " + quoted(capture) +
                                " --script " + quoted(folder / "script.txt"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    CameraLine c = parseCamera(r.output);
    EXPECT_NEAR(c.yaw, glm::radians(30.0f), 1e-3f);
    ASSERT_GT(c.radius, 0.0f);
    // Stopped at the wall: one radius in front of it (skin width 1e-3), not short of it and not through it.
    EXPECT_GE(c.position.z, c.radius * 0.99f) << r.output;
    EXPECT_LE(c.position.z, c.radius * 1.05f) << r.output;
    // Slid: the straight path meets the wall at x = (6 - r) tan 30deg; the slide carries it well beyond.
    const float contactX = (6.0f - c.radius) * std::tan(glm::radians(30.0f));
    EXPECT_GT(c.position.x, contactX + 1.0f) << r.output;
    EXPECT_NEAR(c.position.y, 0.0f, 1e-3f);

    // The recording: 30 Hz over frames 1..80 (79 frames of 20 ms = 1.58 s) gives floor(1.58 * 30) + 1 records.
    tools::Capture recorded = tools::readCapture(capture);
    EXPECT_NEAR(double(recorded.frames.size()), 48.0, 1.0);
    ASSERT_FALSE(recorded.frames.empty());
    EXPECT_NEAR(recorded.frames.front().position.z, 6.0f, 1e-4f);
    EXPECT_GE(recorded.frames.back().position.z, c.radius * 0.99f);
}

// Right-click in FPS mode shoots a point light from the camera towards the wall: four frames later it flies
// 2.7 m in front of the wall (45 m/s for 80 ms from 6 m) and lights the centre of the view, which the
// environment alone lights dimly. Same run without the shot: the reference.
TEST(Viewer, ShotLightLightsTheWall) {
    std::filesystem::path folder = testFolder("shot_light");
    std::filesystem::path scene = writeWallScene(folder, 6.0f);
    writeText(folder / "shot.txt", "0 press E\n1 press MOUSE_RIGHT\n5 press ESCAPE\n");
    writeText(folder / "dark.txt", "0 press E\n5 press ESCAPE\n");
    const std::string common = quoted(scene) + " --size 64x64 --no-ui --fixed-dt 0.02 --script ";
    ProcessResult shot = runViewer(common + quoted(folder / "shot.txt") + " --screenshot " + quoted(folder / "shot.png"));
    ASSERT_EQ(shot.exitCode, 0) << shot.output;
    ProcessResult dark = runViewer(common + quoted(folder / "dark.txt") + " --screenshot " + quoted(folder / "dark.png"));
    ASSERT_EQ(dark.exitCode, 0) << dark.output;
    Codes lit = readCodes(folder / "shot.png"), unlit = readCodes(folder / "dark.png");
    auto centreMean = [](const Codes& c) {
        double sum = 0.0;
        for (uint32_t y = 24; y < 40; ++y)
            for (uint32_t x = 24; x < 40; ++x) sum += c.rgba[(y * c.width + x) * 4];
        return sum / 256.0;
    };
    EXPECT_GT(centreMean(lit), centreMean(unlit) + 10.0) << "lit " << centreMean(lit) << " unlit " << centreMean(unlit);
}

// Right-click in GUI mode casts a ray through the BVH: the centre of the view hits the wall, a corner (beyond the
// 40 m wall seen from 60 m with a 45 degree field of view) hits nothing.
TEST(Viewer, RightClickPicksTheObjectUnderTheCursor) {
    std::filesystem::path folder = testFolder("pick");
    std::filesystem::path scene = writeWallScene(folder, 60.0f);
    writeText(folder / "script.txt",
              "0 cursor 32 32\n1 press MOUSE_RIGHT\n"
              "3 cursor 1 1\n4 press MOUSE_RIGHT\n"
              "6 press ESCAPE\n");
    ProcessResult r = runViewer(quoted(scene) + " --size 64x64 --script " + quoted(folder / "script.txt"));
    ASSERT_EQ(r.exitCode, 0) << r.output;
    size_t hit = r.output.find("selected instance 0 (node 0 'wall') at distance 60.00");  // 60 m, through the pixel centre next to the axis
    size_t miss = r.output.find("selected nothing");
    EXPECT_NE(hit, std::string::npos) << r.output;
    EXPECT_NE(miss, std::string::npos) << r.output;
    EXPECT_LT(hit, miss);
}

}  // namespace
}  // namespace idk::test
