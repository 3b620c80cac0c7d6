// render_replay.cpp: `idk render [SCENE] --replay F.idkcap --video OUT.mp4`: renders every recorded frame of a
// camera capture (tools/camera_capture.hpp) headless with the same render::Renderer as a still image (the scene
// posed at the recorded scene time, the camera at the recorded position, yaw, pitch and field of view) and encodes
// them with ffmpeg at the capture's rate (tools/video_writer.hpp). Ports IDKEngine's "Is Video Render" replay, which
// wrote numbered JPEGs for a hand-run ffmpeg command. With --pathtrace every frame is path-traced instead (the
// original's video mode): the scene posed at the frame's time, the camera placed as `--camera` places a still
// (app/camera_spec.hpp: no lens of the file camera, near/far bracketing the scene) and the same --seed for every
// frame, so frame i equals `idk render --pathtrace --time T --camera ... --seed S` of that record. --out F.exr|F.png
// also writes each frame as F_0000.exr, ... A bad capture fails before any Vulkan work and writes nothing; so does
// any later error in the video (the video writer removes its partial file).
#include "app/render_replay.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <unistd.h>

#include "app/camera_spec.hpp"
#include "app/cli_context.hpp"
#include "app/render_pathtrace.hpp"
#include "core/cli.hpp"
#include "core/image_file.hpp"
#include "frame/culling_feature.hpp"
#include "render/path_tracer.hpp"
#include "render/scene_textures.hpp"
#include "scene/animation.hpp"
#include "scene/camera.hpp"
#include "tools/camera_capture.hpp"
#include "tools/video_writer.hpp"
#include "vk/memory_log.hpp"

namespace idk::app {

namespace {

uint64_t parseFrameIndex(const std::string& range, const std::string& text) {
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos || text.size() > 18)
        throw core::CliError("--frames '" + range + "': give a:b with frame numbers counted from 0");
    return std::stoull(text);
}

// A one-line bar on stderr, only on a terminal; erased at the end.
class ProgressBar {
public:
    explicit ProgressBar(uint64_t total) : total_(total), enabled_(isatty(STDERR_FILENO) != 0) {}
    ~ProgressBar() {
        if (enabled_ && shown_) std::fprintf(stderr, "\r%60s\r", "");
    }
    void update(uint64_t done) {
        if (!enabled_) return;
        const int width = 30;
        const int filled = total_ == 0 ? width : int(double(done) / double(total_) * width);
        std::fprintf(stderr, "\r[%.*s%*s] %llu/%llu frames", filled, "##############################",
                     width - filled, "", static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_));
        std::fflush(stderr);
        shown_ = true;
    }

private:
    uint64_t total_;
    bool enabled_;
    bool shown_ = false;
};

}  // namespace

FrameRange parseFrameRange(const std::string& text, uint64_t count) {
    FrameRange range{0, count};
    const size_t colon = text.find(':');
    if (colon == std::string::npos) {
        range.first = parseFrameIndex(text, text);
        range.end = range.first + 1;
    } else {
        const std::string a = text.substr(0, colon), b = text.substr(colon + 1);
        if (!a.empty()) range.first = parseFrameIndex(text, a);
        if (!b.empty()) range.end = parseFrameIndex(text, b);
    }
    if (range.first >= range.end || range.end > count)
        throw core::CliError("--frames '" + text + "': the capture has " + std::to_string(count) + " frames (0.." +
                             std::to_string(count - 1) + "); give a:b with a < b <= " + std::to_string(count));
    return range;
}

namespace {

std::filesystem::path framePath(const std::filesystem::path& out, uint64_t index) {
    std::string number = std::to_string(index);
    if (number.size() < 4) number.insert(0, 4 - number.size(), '0');
    return out.parent_path() / (out.stem().string() + "_" + number + out.extension().string());
}

// --replay --pathtrace: one PathTracer while the scene stands still, a new one per frame when it is animated (the
// tracer's BVHs are built from the posed scene).
int replayPathTraced(const core::CliArgs& args, scene::Scene& scene, const render::RenderSettings& settings,
                     uint32_t width, uint32_t height, const tools::Capture& capture, FrameRange range, int animation) {
    const std::optional<std::string> video = args.get("--video"), out = args.get("--out");
    const PathTraceCli cli = pathTraceFromCli(args, settings);
    std::unique_ptr<vk::Context> ctx = createContext(cli.contextDesc);
    vk::ShaderLibrary shaders(*ctx);
    std::optional<tools::VideoWriter> writer;
    if (video) writer.emplace(*video, width, height, videoOptionsFromCli(args, capture.rateHz));
    const bool animated = !scene.animations.empty();
    std::unique_ptr<render::PathTracer> tracer;
    ProgressBar progress(range.end - range.first);
    render::PtTraversal traversal = render::PtTraversal::Bvh;
    for (uint64_t i = range.first; i < range.end; ++i) {
        const tools::CaptureFrame& frame = capture.frames[i];
        if (animated || !tracer) {
            if (animated) scene::evaluateAnimations(scene, frame.sceneTime, animation);
            tracer.reset();
            tracer = std::make_unique<render::PathTracer>(*ctx, shaders, scene, cli.options);
        }
        scene::CameraView view = tools::captureCameraView(frame, scene::CameraView{});
        bracketScene(view, scene.bounds);
        const render::PathTraceResult result = tracer->render(view, width, height, cli.settings);
        traversal = result.traversal;
        const core::ImageRgba32f& image = cli.options.denoise && result.didDenoise ? result.denoised : result.image;
        if (out) {
            const std::filesystem::path path = framePath(*out, i);
            core::writeImage(path, path.extension() == ".png" ? displayImage(image, settings.exposure) : image);
        }
        if (writer) writer->addFrame(displayBytes(image, settings.exposure));
        progress.update(i + 1 - range.first);
    }
    if (ctx->validationErrors() != 0) {
        if (writer) writer->abort();
        std::fprintf(stderr, "idk render: %u Vulkan validation error(s); no video written\n", ctx->validationErrors());
        return 1;
    }
    if (writer) writer->finish();
    std::fprintf(stderr, "idk render: path-traced %llu frames %llu..%llu (%ux%u, %u spp, %s traversal)%s%s%s%s\n",
                 static_cast<unsigned long long>(range.end - range.first), static_cast<unsigned long long>(range.first),
                 static_cast<unsigned long long>(range.end - 1), width, height, cli.settings.spp,
                 render::traversalName(traversal), video ? " to " : "", video ? video->c_str() : "",
                 out ? " and " : "", out ? framePath(*out, range.first).c_str() : "");
    return 0;
}

}  // namespace

int runRenderReplay(const core::CliArgs& args, scene::Scene& scene, render::RenderSettings settings, uint32_t width,
                    uint32_t height) {
    const std::string capturePath = *args.get("--replay");
    const bool pathTrace = args.has("--pathtrace");
    std::optional<std::string> video = args.get("--video"), out = args.get("--out");
    if (!video && !(pathTrace && out)) throw core::CliError("--replay needs --video OUT.mp4 (or --pathtrace --out F.exr)");
    if (video && std::filesystem::path(*video).extension() != ".mp4")
        throw core::CliError("--video '" + *video + "': the file must end in .mp4");
    if (out && !pathTrace) throw core::CliError("--out cannot be combined with --replay without --pathtrace");
    for (const char* option : {"--time", "--graph", "--camera", "--orbit", "--camera-index", "--orbit-frames",
                               "--background"}) {
        if (args.get(option)) throw core::CliError(std::string(option) + " cannot be combined with --replay");
    }
    for (const char* flag : {"--stats", "--json"}) {
        if (args.has(flag)) throw core::CliError(std::string(flag) + " cannot be combined with --replay");
    }
    if (settings.shading != render::Shading::Pbr)
        throw core::CliError("--replay renders with --shading pbr (the viewer's frames), not lambert");
    int animation = -1;
    if (std::optional<std::string> a = args.get("--animation")) animation = int(core::parseNumber("--animation", *a));

    // The capture first: a bad file fails here, before any Vulkan work, and nothing is written.
    const tools::Capture capture = tools::readCapture(capturePath);
    if (capture.frames.empty()) throw tools::CaptureError(capturePath + ": the capture has no frames");
    FrameRange range{0, capture.frames.size()};
    if (std::optional<std::string> frames = args.get("--frames")) range = parseFrameRange(*frames, capture.frames.size());
    if (pathTrace) return replayPathTraced(args, scene, settings, width, height, capture, range, animation);

    // The lens of the scene's default camera with the output's aspect ratio (the viewer renders to its window's).
    scene::CameraView lens = scene::defaultCamera(scene);
    lens.aspectRatio = 0.0f;
    settings.output = render::OutputKind::Display;

    std::unique_ptr<vk::Context> context = createContext(contextDescFromCli(args));
    vk::Context& ctx = *context;
    if (std::string e = frame::CullingFeature::geometryError(ctx, settings.culling); !e.empty()) throw core::CliError(e);
    vk::ShaderLibrary shaders(ctx);
    {
        render::Renderer renderer(ctx, shaders, settings);
        renderer.setScene(scene);
        render::SceneTextureStream textures(ctx, renderer, scene);
        textures.finishSynchronously();
        tools::VideoWriter writer(*video, width, height, videoOptionsFromCli(args, capture.rateHz));
        const bool animated = !scene.animations.empty();
        ProgressBar progress(range.end - range.first);
        std::optional<vk::MemoryLog> memoryLog = vk::MemoryLog::fromEnvironment();  // soak runs (scripts/soak.sh)
        for (uint64_t i = range.first; i < range.end; ++i) {
            const tools::CaptureFrame& frame = capture.frames[i];
            if (animated) {
                scene::evaluateAnimations(scene, frame.sceneTime, animation);
                renderer.setPose(scene);
            }
            const render::FrameResult result = renderer.renderOffscreen(tools::captureCameraView(frame, lens), width, height);
            writer.addFrame(result.display);
            if (memoryLog) memoryLog->sample(i - range.first, ctx.allocator());
            progress.update(i + 1 - range.first);
        }
        if (ctx.validationErrors() != 0) {
            writer.abort();
            std::fprintf(stderr, "idk render: %u Vulkan validation error(s); no video written\n", ctx.validationErrors());
            return 1;
        }
        writer.finish();
    }
    std::fprintf(stderr, "idk render: wrote %s (%llu frames %llu..%llu of %s, %ux%u, %g Hz)\n", video->c_str(),
                 static_cast<unsigned long long>(range.end - range.first), static_cast<unsigned long long>(range.first),
                 static_cast<unsigned long long>(range.end - 1), capturePath.c_str(), width, height,
                 double(capture.rateHz));
    return 0;
}

}  // namespace idk::app
