// camera_spec_test.cpp: `idk render --camera/--orbit/--camera-index/--orbit-frames` (engine/app/camera_spec.hpp):
// spec parsing, the errors that name the flag, and the placement against the Khronos render-fidelity convention
// computed here independently (theta = azimuth around +Y from +Z, phi = polar angle from +Y).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

#include "app/camera_spec.hpp"
#include "core/cli.hpp"

namespace idk::app {
namespace {

scene::Aabb box(glm::vec3 lo, glm::vec3 hi) {
    scene::Aabb b;
    b.min = lo;
    b.max = hi;
    return b;
}

void expectVec(const glm::vec3& a, const glm::vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

TEST(CameraSpec, LookAtParsesEveryKey) {
    const LookAtSpec s = parseLookAtSpec("eye=1,2,3:target=0,0.5,-1e1:up=0,0,1:yfov=30");
    expectVec(s.eye, {1, 2, 3}, 0.0f);
    expectVec(s.target, {0, 0.5f, -10}, 0.0f);
    expectVec(s.up, {0, 0, 1}, 0.0f);
    EXPECT_EQ(s.yfovDegrees, 30.0);
    const LookAtSpec d = parseLookAtSpec("target=0,0,0:eye=0,0,5");  // order free; up and yfov defaulted
    expectVec(d.up, {0, 1, 0}, 0.0f);
    EXPECT_EQ(d.yfovDegrees, 45.0);
}

TEST(CameraSpec, MalformedLookAtNamesTheFlag) {
    for (const char* bad : {"", "eye=1,2,3", "eye=1,2:target=0,0,0", "eye=1,2,3:target=0,0,0:fov=3",
                            "eye=1,2,3:target=1,2,3", "eye=0,0,1:target=0,0,0:up=0,0,2", "eye=a,0,0:target=0,0,0",
                            "eye=0,0,1:target=0,0,0:yfov=180", "eye=0,0,1:target=0,0,0:yfov=0", "eye=nan,0,0:target=0,0,0",
                            "eye=0,0,1:target=0,0,0:eye=1,1,1", "eye=0,0,1;target=0,0,0"}) {
        try {
            parseLookAtSpec(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const core::CliError& e) {
            EXPECT_NE(std::string(e.what()).find("--camera"), std::string::npos) << e.what();
        }
    }
}

TEST(CameraSpec, OrbitParsesTargetWithCommas) {
    const OrbitSpec s = parseOrbitSpec("theta=30,phi=60,radius=2.5,target=1,2,3,yfov=50");
    EXPECT_EQ(s.thetaDegrees, 30.0);
    EXPECT_EQ(s.phiDegrees, 60.0);
    ASSERT_TRUE(s.radius && s.target);
    EXPECT_EQ(*s.radius, 2.5f);
    expectVec(*s.target, {1, 2, 3}, 0.0f);
    EXPECT_EQ(s.yfovDegrees, 50.0);
    EXPECT_FALSE(parseOrbitSpec("phi=10,theta=-720").radius);
}

TEST(CameraSpec, MalformedOrbitNamesTheFlag) {
    for (const char* bad : {"theta=0", "phi=90", "theta=0,phi=181", "theta=0,phi=-1", "theta=0,phi=90,radius=0",
                            "theta=0,phi=90,radius=-1", "theta=0,phi=90,target=1,2", "theta=x,phi=90", "1,theta=0,phi=9",
                            "theta=0,phi=90,zoom=2"}) {
        try {
            parseOrbitSpec(bad);
            ADD_FAILURE() << "accepted '" << bad << "'";
        } catch (const core::CliError& e) {
            EXPECT_NE(std::string(e.what()).find("--orbit"), std::string::npos) << e.what();
        }
    }
}

TEST(CameraSpec, OrbitFollowsTheRenderFidelityConvention) {
    const scene::Aabb bounds = box({-1, -1, -1}, {1, 1, 1});
    OrbitSpec s;
    s.thetaDegrees = 30.0;
    s.phiDegrees = 60.0;
    s.radius = 4.0f;
    s.target = glm::vec3(0.5f, 0.0f, 0.0f);
    const scene::CameraView v = orbitCamera(s, bounds);
    const double t = 30.0 * std::numbers::pi / 180.0, p = 60.0 * std::numbers::pi / 180.0;
    const glm::vec3 expected = glm::vec3(0.5f, 0, 0) + 4.0f * glm::vec3(float(std::sin(p) * std::sin(t)), float(std::cos(p)),
                                                                        float(std::sin(p) * std::cos(t)));
    expectVec(v.position, expected);
    expectVec(v.forward, glm::normalize(glm::vec3(0.5f, 0, 0) - expected));
    EXPECT_NEAR(glm::dot(v.up, v.forward), 0.0f, 1e-6f);
    EXPECT_GT(v.up.y, 0.0f);  // +Y stays up
    // The depth range encloses the bounding sphere (radius sqrt 3) seen from the eye.
    const float d = glm::length(v.position);
    EXPECT_LT(v.znear, d - std::sqrt(3.0f));
    EXPECT_GT(v.zfar, d + std::sqrt(3.0f));
}

TEST(CameraSpec, OrbitWithoutRadiusFitsTheSphereLikeTheAutoFitCamera) {
    const scene::Aabb bounds = box({1, 2, 3}, {3, 4, 7});
    OrbitSpec s;  // theta 0, phi 90: the eye on +Z of the centre
    const scene::CameraView v = orbitCamera(s, bounds);
    const scene::CameraView fit = scene::autoFitCamera(bounds);
    expectVec(v.position, fit.position, 1e-4f);
    expectVec(v.forward, fit.forward);
    EXPECT_NEAR(v.znear, fit.znear, 1e-4f);
    EXPECT_NEAR(v.zfar, fit.zfar, 1e-4f);
    // Any theta: the same distance from the centre.
    s.thetaDegrees = 123.0;
    EXPECT_NEAR(glm::length(orbitCamera(s, bounds).position - bounds.centre()), glm::length(fit.position - bounds.centre()), 1e-4f);
}

TEST(CameraSpec, LookAtPlacesTheCamera) {
    const scene::CameraView v = lookAtCamera(parseLookAtSpec("eye=0,0,5:target=0,0,0:yfov=60"), box({-1, -1, -1}, {1, 1, 1}));
    expectVec(v.position, {0, 0, 5}, 0.0f);
    expectVec(v.forward, {0, 0, -1}, 0.0f);
    expectVec(v.up, {0, 1, 0}, 0.0f);
    EXPECT_FLOAT_EQ(v.yfov, float(std::numbers::pi / 3.0));
}

TEST(CameraSpec, CliChoosesAndChecksTheCameras) {
    scene::Scene scene;
    scene.bounds = box({-1, -1, -1}, {1, 1, 1});
    auto cli = [](std::vector<std::string> argv) {
        return core::parseCli(argv, {{}, {"--camera", "--orbit", "--camera-index", "--orbit-frames"}});
    };
    const auto frames = camerasFromCli(cli({"--orbit-frames", "4", "--orbit", "theta=10,phi=90,radius=3"}), scene);
    ASSERT_EQ(frames.size(), 4u);
    const double t = (10.0 + 90.0) * std::numbers::pi / 180.0;  // the second frame: 360/4 degrees further
    expectVec(frames[1].position, 3.0f * glm::vec3(float(std::sin(t)), 0.0f, float(std::cos(t))));
    EXPECT_THROW(camerasFromCli(cli({"--camera", "eye=0,0,1:target=0,0,0", "--orbit", "theta=0,phi=90"}), scene),
                 core::CliError);
    EXPECT_THROW(camerasFromCli(cli({"--camera-index", "0"}), scene), core::CliError);  // the scene has none
    EXPECT_THROW(camerasFromCli(cli({"--orbit-frames", "0"}), scene), core::CliError);
    EXPECT_THROW(camerasFromCli(cli({"--orbit-frames", "2.5"}), scene), core::CliError);
    scene.cameras.resize(2);
    scene.cameras[1].world = glm::translate(glm::mat4(1.0f), glm::vec3(7, 8, 9));
    expectVec(camerasFromCli(cli({"--camera-index", "1"}), scene).at(0).position, {7, 8, 9}, 0.0f);
    EXPECT_THROW(camerasFromCli(cli({"--camera-index", "2"}), scene), core::CliError);
}

}  // namespace
}  // namespace idk::app
