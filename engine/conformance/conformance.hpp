// conformance.hpp: the registry of conformance checks - GPU kernels against their CPU oracles, with the tolerances
// the tests state - and the runner shared by `idk conformance` (a driver self-test on the user's device) and the
// ctest label conformance (tests/conformance/registry/), so both run the same check bodies.
//
// Adding a check: write `void checkSomething(CheckEnv& env, Verdict& v)` in the area's *_checks.cpp (it runs
// the kernel on env.ctx, compares with its oracle through v.expect* and returns), then add ONE line to that
// area's list, e.g. in computeChecks():
//     {"scan/exclusive", "", "exact", checkExclusiveScan},
// A check whose kernel has several rungs names its ladder ({"float-atomics/splat", "float-atomics", ...}): it
// runs once per rung the device has, with env.rung set, and the kernel must run that rung. A new area (file)
// adds its list function to allChecks() in registry.cpp (one line) and declares it at the end of this header.
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vk/features.hpp"

namespace idk::vk {
class Context;
class ShaderLibrary;
}  // namespace idk::vk

namespace idk::conformance {

struct CheckEnv {
    vk::Context& ctx;
    vk::ShaderLibrary& shaders;
    std::optional<vk::Rung> rung;       // the rung under test, for checks registered on a ladder
    // --shader-dir: its gl/*.comp.glsl replace the GL-interop sources, and onRung re-applies its Vulkan shaders to
    // the contexts it creates; empty: the build's shaders_glsl/.
    std::filesystem::path glShaderDir;
};

// What a check found: failures with their first messages, and the largest error it measured (0 when exact).
class Verdict {
public:
    bool expect(bool ok, const std::string& what);  // records a failure naming `what` unless ok
    template <class T, class U>
    bool expectEq(const T& got, const U& want, const std::string& what) {
        return expect(got == want, what + ": got " + text(got) + ", expected " + text(want));
    }
    // |got - want| <= tolerance; the error is kept in maxError either way.
    bool expectNear(double got, double want, double tolerance, const std::string& what);
    void recordError(double error);  // an error measured outside expectNear (e.g. relative)
    // The check cannot run on this device (e.g. no OpenGL context): reported as skipped, with the reason.
    void skip(const std::string& why) { skipped_ = why; }
    const std::string& skipped() const noexcept { return skipped_; }

    bool passed() const noexcept { return failures_ == 0; }
    uint32_t failures() const noexcept { return failures_; }
    double maxError() const noexcept { return maxError_; }
    const std::string& messages() const noexcept { return messages_; }  // the first few, "; "-separated

private:
    template <class T>
    static std::string text(const T& value) {
        if constexpr (std::is_arithmetic_v<T>) return std::to_string(value);
        else return "(" + std::to_string(value.size()) + " values)";
    }
    uint32_t failures_ = 0;
    double maxError_ = 0.0;
    std::string messages_;
    std::string skipped_;
};

using CheckFn = void (*)(CheckEnv& env, Verdict& verdict);

// Recompiles every shader `dir` has a source for (DIR/<folder>/<entry>.<stage>.glsl; gl/ is left to the GL rung):
// `idk conformance --shader-dir`. An unknown file or a compile error throws, naming the file.
void overrideShaders(vk::ShaderLibrary& shaders, const std::filesystem::path& dir);

// For kernels that read their rung from the context's ladder (a whole Renderer feature): runs fn(ctx, shaders) on
// a context whose `ladder` chose `rung`: env.ctx when it already did, else a new context on the same device with
// the same validation settings, that rung forced (no GL probe unless the rung is gl-interop) and env.glShaderDir's
// shaders; that context's validation errors fail v. A new context costs a fraction of a second on lavapipe.
void onRung(CheckEnv& env, Verdict& v, const std::string& ladder, vk::Rung rung,
            const std::function<void(vk::Context&, vk::ShaderLibrary&)>& fn);

struct Check {
    std::string kernel;     // unique, "area/what", e.g. "scan/exclusive"
    std::string ladder;     // "" = one run (rung "-"); else one run per rung of this capability ladder
    std::string tolerance;  // as the tests state it: "exact", "1e-6 relative", ...
    CheckFn run;
};

const std::vector<Check>& allChecks();

enum class Status { Pass, Fail, Skip };
const char* statusName(Status status);  // "pass", "FAIL", "skip"

struct Outcome {
    std::string kernel;
    std::string rung;  // rung name, or "-"
    Status status = Status::Skip;
    double maxError = 0.0;
    std::string message;  // the failures, or why it was skipped
    double seconds = 0.0;
    std::string tolerance;
};

// Every (check, rung) pair, device independent (the rungs of each check's ladder): the test list of ctest.
struct PlannedRun {
    const Check* check;
    std::optional<vk::Rung> rung;
    std::string name() const;  // "kernel [rung]"
};
std::vector<PlannedRun> allRuns();
// Those matching `filter` ("" = all; '*' and '?' glob over name(), else a substring of it).
std::vector<PlannedRun> selectRuns(const std::string& filter);

// Runs one: Skip when the rung is unavailable on this device (message: the ladder's note); Fail on a mismatch,
// an exception (its message) or a validation-layer error raised during the check.
Outcome run(const PlannedRun& planned, vk::Context& ctx, vk::ShaderLibrary& shaders,
            const std::filesystem::path& glShaderDir = {});

// The areas (one list function per *_checks.cpp).
std::vector<Check> computeChecks();
std::vector<Check> splatChecks();
std::vector<Check> ptMathChecks();
std::vector<Check> subgroupChecks();
std::vector<Check> bvhChecks();
std::vector<Check> ptWavefrontChecks();
std::vector<Check> denoiseChecks();
std::vector<Check> textureChecks();
std::vector<Check> vrsChecks();
std::vector<Check> cullingChecks();
std::vector<Check> cullKernelChecks();
std::vector<Check> meshletCullChecks();
std::vector<Check> bvhRefitChecks();
std::vector<Check> atmosphereChecks();
std::vector<Check> vxgiChecks();
std::vector<Check> shadowChecks();

}  // namespace idk::conformance
