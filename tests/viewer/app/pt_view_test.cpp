// pt_view_test.cpp: the viewer's path-traced mode (P, --pathtrace; engine/viewer/pt_view.cpp) under Xvfb on the
// embedded Cornell box at 64x64, one sample per frame. Oracles: `idk render --pathtrace` of the same camera and
// seed (N frames are its N-spp image: the progressive sum is the same samples; the denoised one too), a 256-spp
// render with another seed (the error falls as frames accumulate), and the sample count the viewer reports
// (restarts when the camera moves or an animated scene's time runs, stops when P switches back to the rasterizer).
#include <gtest/gtest.h>

#include <cstdio>

#include "viewer/app/viewer_harness.hpp"

namespace idk::test {
namespace {

const std::string kViewer = IDK_VIEWER_EXE;
const std::string kRender = IDK_RENDER_EXE;

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

// The viewer's camera goes through the fly-camera state (yaw/pitch and back), a few ulps in the view matrix: as in
// viewer_test.cpp, at most 0.1% of the pixels may differ by more than 2 codes (measured: none differ at all).
constexpr int kSameCodes = 2;
constexpr double kSameFraction = 0.001;

// Runs the viewer with `script` for `frames` frames; returns its output and writes shot.png in `folder`.
ProcessResult runScripted(const std::filesystem::path& folder, const std::string& script, int frames,
                          const std::string& extra = "", const std::string& dt = "0.02") {
    writeText(folder / "script.txt", script);
    return runCommand(kViewer + " --size 64x64 --fixed-dt " + dt + " --frames " + std::to_string(frames) + " --script " +
                          quoted(folder / "script.txt") + " --screenshot " + quoted(folder / "shot.png") + " " + extra,
                      "DISPLAY=" + xvfbDisplay());
}

Codes renderPathTraced(const std::filesystem::path& folder, const std::string& name, const std::string& args) {
    const std::filesystem::path out = folder / (name + ".png");
    ProcessResult r = runCommand(kRender + " render --pathtrace --size 64x64 " + args + " --out " + quoted(out));
    EXPECT_EQ(r.exitCode, 0) << r.output;
    return readCodes(out);
}

std::string countLine(int samples, int restarts, bool on = true) {
    return "path tracer " + std::string(on ? "on" : "off") + ", " + std::to_string(samples) + " samples, " +
           std::to_string(restarts) + " restarts";
}

TEST(ViewerPathTracer, FramesAccumulateToIdkRenderAndConverge) {
    const std::filesystem::path folder = testFolder("pt_view_converge");
    const Codes reference = renderPathTraced(folder, "reference", "--spp 256 --seed 99");
    double previous = 1e9, first = 0.0;
    for (int frames : {1, 4, 16}) {
        ProcessResult r = runScripted(folder, "0 press P\n", frames);  // P at frame 0: every frame path-traced
        ASSERT_EQ(r.exitCode, 0) << r.output;
        EXPECT_NE(r.output.find(countLine(frames, 1)), std::string::npos) << r.output;
        const Codes shot = readCodes(folder / "shot.png");
        // N frames of one sample = `idk render --pathtrace --spp N` (seed 0, the default of both).
        const Codes same = renderPathTraced(folder, "spp" + std::to_string(frames), "--spp " + std::to_string(frames));
        const CodeDifference d = compareCodes(shot, same, kSameCodes);
        EXPECT_LE(d.fractionOver, kSameFraction) << frames << " frames: max " << d.maxRgb << " mean " << d.meanRgb;
        const double error = compareCodes(shot, reference, 255).meanRgb;
        std::printf("%d frames: %.4f codes mean from idk render --spp %d, %.3f codes mean error vs 256 spp\n", frames,
                    d.meanRgb, frames, error);
        EXPECT_LT(error, previous) << frames << " frames";
        if (frames == 1) first = error;
        previous = error;
    }
    // 16x the samples: 1/4 of the noise in theory; the reference's own noise and 8-bit rounding keep it above.
    EXPECT_LT(previous, 0.6 * first);
}

TEST(ViewerPathTracer, DenoisedOptionShowsTheDenoisedRender) {
    const std::filesystem::path folder = testFolder("pt_view_denoise");
    ProcessResult r = runScripted(folder, "# --pathtrace: path-traced from the first frame\n", 4, "--pathtrace --denoise");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(countLine(4, 1)), std::string::npos) << r.output;
    const Codes shot = readCodes(folder / "shot.png");
    const CodeDifference d = compareCodes(shot, renderPathTraced(folder, "denoised", "--spp 4 --denoise"), kSameCodes);
    EXPECT_LE(d.fractionOver, kSameFraction) << "max " << d.maxRgb << " mean " << d.meanRgb;
    // and it is not the raw image (the option reached the tracer)
    EXPECT_GT(compareCodes(shot, renderPathTraced(folder, "raw", "--spp 4"), kSameCodes).fractionOver, 0.05);
}

TEST(ViewerPathTracer, MovingTheCameraRestartsAndPSwitchesBack) {
    const std::filesystem::path folder = testFolder("pt_view_restart");
    // FPS mode (E) so the mouse turns the camera; it turns at frame 10: frames 10..15 are the new accumulation.
    ProcessResult moved = runScripted(folder, "0 press E\n0 press P\n10 mouse 20 0\n", 16);
    ASSERT_EQ(moved.exitCode, 0) << moved.output;
    EXPECT_NE(moved.output.find(countLine(6, 2)), std::string::npos) << moved.output;
    // P again at frame 5: the rasterizer from then on, the count stays at the 5 samples shown.
    ProcessResult back = runScripted(folder, "0 press P\n5 press P\n", 8);
    ASSERT_EQ(back.exitCode, 0) << back.output;
    EXPECT_NE(back.output.find(countLine(5, 1, false)), std::string::npos) << back.output;
}

TEST(ViewerPathTracer, AnimatedSceneRestartsWhileTimeRunsThenMatchesTheRenderAtThatTime) {
    const std::filesystem::path folder = testFolder("pt_view_animated");
    const std::filesystem::path fox = std::filesystem::path(IDK_SHARED_DIR) / "scenes/Fox/glTF-Binary/Fox.glb";
    ASSERT_TRUE(std::filesystem::exists(fox)) << fox;
    // 0.25 s per frame: frames 0, 1, 2 are at T = 0.25, 0.5, 0.75 (each a new accumulation; the tracer is built at
    // 0.25 and re-posed on the GPU, PathTracer::setPose); T pauses at frame 3, so frames 2..7 add 6 samples at 0.75.
    // --sync-textures: the rasterizer's textures load first (the tracer's own texture slots must survive that).
    ProcessResult r = runScripted(folder, "3 press T\n", 8, quoted(fox) + " --pathtrace --sync-textures", "0.25");
    ASSERT_EQ(r.exitCode, 0) << r.output;
    EXPECT_NE(r.output.find(countLine(6, 3)), std::string::npos) << r.output;
    const Codes expected = renderPathTraced(folder, "fox", quoted(fox) + " --time 0.75 --spp 6");
    const CodeDifference d = compareCodes(readCodes(folder / "shot.png"), expected, kSameCodes);
    EXPECT_LE(d.fractionOver, kSameFraction) << "max " << d.maxRgb << " mean " << d.meanRgb;
}

}  // namespace
}  // namespace idk::test
