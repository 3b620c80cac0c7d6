// registry.cpp: allChecks() (one line per area), the Verdict, and the runner: rung availability, timing,
// exceptions and validation-layer errors turned into outcomes.
#include "conformance/conformance.hpp"

#include <fnmatch.h>

#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <sstream>

#include "vk/check.hpp"
#include "vk/context.hpp"
#include "vk/shader_library.hpp"

namespace idk::conformance {

const std::vector<Check>& allChecks() {
    static const std::vector<Check> checks = [] {
        std::vector<Check> all;
        for (std::vector<Check> (*area)() : {computeChecks, subgroupChecks, splatChecks, ptMathChecks, bvhChecks,
                                                ptWavefrontChecks, denoiseChecks, textureChecks,
                                                vrsChecks, cullingChecks, cullKernelChecks, meshletCullChecks, bvhRefitChecks,
                                                atmosphereChecks, vxgiChecks, shadowChecks}) {
            std::vector<Check> list = area();
            all.insert(all.end(), list.begin(), list.end());
        }
        return all;
    }();
    return checks;
}

const char* statusName(Status status) {
    switch (status) {
        case Status::Pass: return "pass";
        case Status::Fail: return "FAIL";
        case Status::Skip: return "skip";
    }
    return "?";
}

bool Verdict::expect(bool ok, const std::string& what) {
    if (ok) return true;
    if (++failures_ <= 3) messages_ += (messages_.empty() ? "" : "; ") + what;
    return false;
}

bool Verdict::expectNear(double got, double want, double tolerance, const std::string& what) {
    const double error = std::abs(got - want);
    recordError(error);
    return expect(error <= tolerance, what + ": got " + std::to_string(got) + ", expected " + std::to_string(want) +
                                          " within " + std::to_string(tolerance));
}

void Verdict::recordError(double error) {
    if (!(error <= maxError_)) maxError_ = error;  // NaN sticks
}

void overrideShaders(vk::ShaderLibrary& shaders, const std::filesystem::path& dir) {
    if (!std::filesystem::is_directory(dir)) throw std::runtime_error(dir.string() + ": --shader-dir is not a folder");
    for (const auto& file : std::filesystem::recursive_directory_iterator(dir)) {
        if (!file.is_regular_file() || file.path().extension() != ".glsl") continue;
        const std::string relative = std::filesystem::relative(file.path(), dir).generic_string();
        if (relative.rfind("gl/", 0) == 0) continue;  // GL sources are read by the GL rung itself
        const shaders::ShaderEntry* entry = nullptr;
        for (const shaders::ShaderEntry& e : shaders::allShaders())
            if (relative == e.sourcePath) entry = &e;
        if (!entry) throw std::runtime_error(file.path().string() + ": no shader of the build has this name");
        std::ifstream in(file.path());
        std::stringstream text;
        text << in.rdbuf();
        const vk::ReloadResult r = shaders.reload(vk::ShaderId(entry - shaders::allShaders().data()), text.str());
        if (!r.ok) throw std::runtime_error(file.path().string() + ": " + r.message);
    }
}

void onRung(CheckEnv& env, Verdict& v, const std::string& ladder, vk::Rung rung,
            const std::function<void(vk::Context&, vk::ShaderLibrary&)>& fn) {
    if (env.ctx.ladder(ladder).chosen == rung) {
        fn(env.ctx, env.shaders);
        return;
    }
    vk::ContextDesc desc = env.ctx.desc();
    desc.forcedRungs = {{ladder, rung}};
    desc.probeGlInterop = rung == vk::Rung::GlInterop;
    vk::Context ctx(desc);
    if (!v.expect(ctx.ladder(ladder).chosen == rung, ladder + ": the forced rung " + vk::rungName(rung) +
                                                         " was not taken: " + ctx.ladder(ladder).reason))
        return;
    uint32_t errors = 0;
    std::string first;
    {
        vk::ShaderLibrary shaders(ctx);
        if (!env.glShaderDir.empty()) overrideShaders(shaders, env.glShaderDir);  // a planted kernel runs here too
        fn(ctx, shaders);
        ctx.waitIdle();
        errors = ctx.validationErrors();
        if (errors && !ctx.validationMessages().empty()) first = ": " + ctx.validationMessages().front();
    }
    v.expect(errors == 0, std::to_string(errors) + " validation error(s) on the " + vk::rungName(rung) + " context" + first);
}

std::string PlannedRun::name() const {
    return check->kernel + " [" + (rung ? vk::rungName(*rung) : "-") + "]";
}

std::vector<PlannedRun> allRuns() {
    std::vector<PlannedRun> runs;
    for (const Check& check : allChecks()) {
        if (check.ladder.empty()) {
            runs.push_back({&check, std::nullopt});
            continue;
        }
        for (vk::Rung rung : vk::ladderRungs(check.ladder)) runs.push_back({&check, rung});
    }
    return runs;
}

std::vector<PlannedRun> selectRuns(const std::string& filter) {
    std::vector<PlannedRun> selected;
    const bool glob = filter.find_first_of("*?") != std::string::npos;
    std::string pattern;  // "[rung]" is literal text, not an fnmatch character class
    for (char c : filter) pattern += c == '[' ? std::string("[[]") : std::string(1, c);
    for (const PlannedRun& r : allRuns()) {
        const std::string name = r.name();
        if (filter.empty() || (glob ? fnmatch(pattern.c_str(), name.c_str(), 0) == 0 : name.find(filter) != std::string::npos))
            selected.push_back(r);
    }
    return selected;
}

Outcome run(const PlannedRun& planned, vk::Context& ctx, vk::ShaderLibrary& shaders,
            const std::filesystem::path& glShaderDir) {
    const Check& check = *planned.check;
    Outcome out;
    out.kernel = check.kernel;
    out.rung = planned.rung ? vk::rungName(*planned.rung) : "-";
    out.tolerance = check.tolerance;
    if (planned.rung) {
        for (const vk::RungOption& o : ctx.ladder(check.ladder).options) {
            if (o.rung == *planned.rung && !o.available) {
                out.status = Status::Skip;
                out.message = o.note;
                return out;
            }
        }
    }
    const uint32_t errorsBefore = ctx.validationErrors();
    const size_t messagesBefore = ctx.validationMessages().size();
    Verdict verdict;
    CheckEnv env{ctx, shaders, planned.rung, glShaderDir};
    const auto start = std::chrono::steady_clock::now();
    try {
        check.run(env, verdict);
    } catch (const vk::DeviceLostError&) {
        throw;  // no later check can run: idk reports the loss (exit 3)
    } catch (const vk::OutOfDeviceMemoryError&) {
        throw;
    } catch (const std::exception& e) {
        verdict.expect(false, std::string("threw: ") + e.what());
    }
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const uint32_t newErrors = ctx.validationErrors() - errorsBefore;
    if (newErrors) {
        const std::vector<std::string> messages = ctx.validationMessages();
        verdict.expect(false, std::to_string(newErrors) + " validation error(s)" +
                                  (messages.size() > messagesBefore ? ": " + messages[messagesBefore] : ""));
    }
    if (!verdict.skipped().empty() && verdict.passed()) {
        out.status = Status::Skip;
        out.message = verdict.skipped();
        return out;
    }
    out.status = verdict.passed() ? Status::Pass : Status::Fail;
    out.maxError = verdict.maxError();
    out.message = verdict.messages();
    if (verdict.failures() > 3) out.message += " (" + std::to_string(verdict.failures()) + " failures in all)";
    return out;
}

}  // namespace idk::conformance
