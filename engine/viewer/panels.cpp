// panels.cpp: the viewer's ImGui panels: renderer settings, frame and per-pass GPU timings, device and capability
// ladders, scene tree with the selected object's transform, camera/time/recording, shader reload log. Ports the
// panels of IDKEngine's Gui.cs (reduced to what this renderer has).
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/matrix_decompose.hpp>

#include "frame/settings_table.hpp"
#include "frame/vxgi_memory.hpp"
#include "viewer/viewer_app.hpp"

namespace idk::viewer {
namespace {

// One widget per row of the settings table (frame/settings_table.cpp), grouped by the row's panel.
bool settingWidget(const frame::SettingOption& o, render::RenderSettings& s) {
    const double value = o.get(s);
    switch (o.kind) {
    case frame::OptionKind::Number: {
        float v = float(value);
        if (!ImGui::SliderFloat(o.label, &v, float(o.min), float(o.max), "%.3g",
                                o.logarithmic ? ImGuiSliderFlags_Logarithmic : 0))
            return false;
        o.set(s, double(std::clamp(v, float(o.min), float(o.max))));
        return true;
    }
    case frame::OptionKind::Integer: {
        int v = int(value);
        if (!ImGui::SliderInt(o.label, &v, int(o.min), int(o.max))) return false;
        o.set(s, double(std::clamp(v, int(o.min), int(o.max))));
        return true;
    }
    case frame::OptionKind::Choice: {
        int v = int(value);
        if (!ImGui::Combo(o.label, &v, o.choices.data(), int(o.choices.size()))) return false;
        o.set(s, double(v));
        return true;
    }
    case frame::OptionKind::Toggle: {
        bool v = value != 0.0;
        if (!ImGui::Checkbox(o.label, &v)) return false;
        o.set(s, v ? 1.0 : 0.0);
        return true;
    }
    }
    return false;
}

void rendererPanel(Viewer& v) {
    if (!ImGui::CollapsingHeader("Renderer", ImGuiTreeNodeFlags_DefaultOpen)) return;
    render::RenderSettings& s = v.renderer->settings();
    ImGui::Text("shading: %s (fixed per scene)", s.shading == render::Shading::Pbr ? "PBR (deferred)" : "Lambert");
    ImGui::Text("output: Display (AgX tonemap, sRGB)");
    std::string env = s.environment ? (s.environment->empty() ? "constant grey" : s.environment->string())
                                    : render::defaultEnvironmentPath().string();
    ImGui::TextWrapped("environment: %s", env.c_str());
    std::string panel;
    const frame::VxgiSettings vxgiBefore = s.vxgi;
    for (const frame::SettingOption& o : frame::settingOptions()) {
        if (panel != o.panel) {
            panel = o.panel;
            ImGui::Separator();
            ImGui::TextDisabled("%s", o.panel);
        }
        settingWidget(o, s);
    }
    // A grid size (or turning VXGI on) the device memory cannot hold is refused here, before the frame would
    // release the old grid: the setting reverts and the status line says why.
    if (std::string refused = frame::refuseVxgiChange(*v.ctx, vxgiBefore, s.vxgi, v.renderer->vxgi().heldBytes());
        !refused.empty()) {
        v.state.status = refused;
        std::fprintf(stderr, "idk-viewer: %s\n", refused.c_str());
    }
    ImGui::Separator();
    bool vsync = v.swapchain->vsync();
    if (ImGui::Checkbox("vsync (V)", &vsync)) v.swapchain->setVsync(vsync);
    const char* mode = v.swapchain->presentMode() == VK_PRESENT_MODE_FIFO_KHR        ? "FIFO"
                       : v.swapchain->presentMode() == VK_PRESENT_MODE_MAILBOX_KHR ? "MAILBOX"
                                                                                   : "IMMEDIATE";
    ImGui::SameLine();
    ImGui::Text("present mode %s, %ux%u", mode, v.swapchain->extent().width, v.swapchain->extent().height);
}

// GPU culling's counters of the previous frame, one row per view (the camera, then point-shadow cube faces).
void cullingTable(const render::FrameInfo& frame) {
    if (frame.culling.empty()) {
        ImGui::TextDisabled("culling: off (geometry path %s)", frame.geometryPath.empty() ? "-" : frame.geometryPath.c_str());
        return;
    }
    ImGui::Text("culling (previous frame), camera geometry path: %s", frame.geometryPath.c_str());
    if (!ImGui::BeginTable("culling", 4, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) return;
    ImGui::TableSetupColumn("view");
    ImGui::TableSetupColumn("instances drawn/tested");
    ImGui::TableSetupColumn("meshlets drawn/tested");
    ImGui::TableSetupColumn("triangles");
    ImGui::TableHeadersRow();
    for (const passes::CullingViewStats& c : frame.culling) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(c.view.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%u / %u", c.instancesDrawn, c.instancesTested);
        ImGui::TableNextColumn();
        if (c.meshlets) ImGui::Text("%u / %u", c.meshletsDrawn, c.meshletsTested);
        else ImGui::TextDisabled("-");
        ImGui::TableNextColumn();
        ImGui::Text("%u", c.trianglesDrawn);
    }
    ImGui::EndTable();
}

void framePanel(Viewer& v) {
    if (!ImGui::CollapsingHeader("Frame", ImGuiTreeNodeFlags_DefaultOpen)) return;
    std::vector<float> ms(v.state.frameMs.begin(), v.state.frameMs.end());
    float average = ms.empty() ? 0.0f : std::accumulate(ms.begin(), ms.end(), 0.0f) / float(ms.size());
    ImGui::Text("frame %llu, %.2f ms (%.1f fps) average over %zu frames", static_cast<unsigned long long>(v.state.frame),
                average, average > 0 ? 1000.0f / average : 0.0f, ms.size());
    if (!ms.empty()) ImGui::PlotLines("frame ms", ms.data(), int(ms.size()), 0, nullptr, 0.0f, average * 2.0f, ImVec2(0, 60));
    const auto& times = v.state.lastFrame.passTimes;
    double total = 0.0;
    if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
        ImGui::TableSetupColumn("pass");
        ImGui::TableSetupColumn("GPU ms");
        ImGui::TableHeadersRow();
        for (const vk::ScopeTiming& t : times) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(t.name.c_str());
            ImGui::TableNextColumn();
            ImGui::Text("%.3f", t.milliseconds);
            total += t.milliseconds;
        }
        ImGui::EndTable();
    }
    ImGui::Text("GPU total %.3f ms (previous frame)", total);
    cullingTable(v.state.lastFrame);
    const ui::UiFrameStats& u = v.ui->lastFrame();
    ImGui::Text("UI: %u draws, %u vertices", u.drawCalls, u.vertices);
}

void devicePanel(Viewer& v) {
    if (!ImGui::CollapsingHeader("Device")) return;
    const vk::DeviceInfo& info = v.ctx->info();
    ImGui::Text("%s (%s)", info.name.c_str(), info.driverName.c_str());
    if (ImGui::BeginTable("ladders", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
        ImGui::TableSetupColumn("feature");
        ImGui::TableSetupColumn("rung");
        ImGui::TableSetupColumn("mechanism");
        ImGui::TableHeadersRow();
        for (const vk::Ladder& l : v.ctx->ladders()) {
            ImGui::TableNextRow();
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(l.feature.c_str());
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(vk::rungName(l.chosen));
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(l.chosenMechanism.c_str());
        }
        ImGui::EndTable();
    }
}

void nodeTree(Viewer& v, uint32_t index) {
    const scene::Node& node = v.scene.nodes[index];
    ImGuiTreeNodeFlags flags = ImGuiTreeNodeFlags_OpenOnArrow | ImGuiTreeNodeFlags_SpanAvailWidth;
    if (node.children.empty()) flags |= ImGuiTreeNodeFlags_Leaf;
    if (v.state.selected && v.state.selected->node == index) flags |= ImGuiTreeNodeFlags_Selected;
    std::string label = (node.name.empty() ? "node " + std::to_string(index) : node.name) + "##" + std::to_string(index);
    bool open = ImGui::TreeNodeEx(label.c_str(), flags);
    if (ImGui::IsItemClicked() && !ImGui::IsItemToggledOpen()) {
        // Select the node's first instance (a node without a mesh selects just the node).
        Pick pick;
        pick.node = index;
        pick.instance = UINT32_MAX;
        for (uint32_t i = 0; i < v.scene.instances.size(); ++i)
            if (v.scene.instances[i].node == index) {
                pick.instance = i;
                break;
            }
        v.state.selected = pick;
    }
    if (open) {
        for (uint32_t child : node.children) nodeTree(v, child);
        ImGui::TreePop();
    }
}

void scenePanel(Viewer& v) {
    if (!ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Text("%zu nodes, %zu instances, %zu lights (+%zu shot), %zu animations", v.scene.nodes.size(),
                v.scene.instances.size(), v.scene.lights.size(), v.shotLights.lights().size(), v.scene.animations.size());
    if (ImGui::BeginChild("tree", ImVec2(0, 160), true)) {
        for (uint32_t root : v.scene.rootNodes) nodeTree(v, root);
    }
    ImGui::EndChild();
    if (!v.state.selected) {
        ImGui::TextUnformatted("right-click an object in GUI mode (or a tree entry) to select it");
        return;
    }
    const Pick& p = *v.state.selected;
    const scene::Node& node = v.scene.nodes[p.node];
    ImGui::Text("selected: %s (node %u, instance %s)", node.name.c_str(), p.node,
                p.instance == UINT32_MAX ? "-" : std::to_string(p.instance).c_str());
    glm::vec3 scale, translation, skew;
    glm::quat rotation;
    glm::vec4 perspective;
    glm::decompose(node.world, scale, rotation, translation, skew, perspective);
    glm::vec3 euler = glm::degrees(glm::eulerAngles(rotation));
    ImGui::InputFloat3("world translation", &translation.x, "%.3f", ImGuiInputTextFlags_ReadOnly);
    ImGui::InputFloat3("world rotation (deg)", &euler.x, "%.1f", ImGuiInputTextFlags_ReadOnly);
    ImGui::InputFloat3("world scale", &scale.x, "%.3f", ImGuiInputTextFlags_ReadOnly);
    if (p.distance > 0) ImGui::Text("hit at (%.3f, %.3f, %.3f), distance %.3f", p.point.x, p.point.y, p.point.z, p.distance);
}

// The path-traced mode (P, pt_view.hpp): a change here restarts the accumulation.
void pathTracerPanel(Viewer& v) {
    if (!ImGui::CollapsingHeader("Path tracer", ImGuiTreeNodeFlags_DefaultOpen)) return;
    PtViewSettings& pt = v.state.pt;
    ImGui::Checkbox("path traced (P)", &pt.enabled);
    if (!pt.enabled) return;
    if (v.pathTracer) {
        ImGui::Text("%u samples (accumulation %u)", v.pathTracer->samples(), v.pathTracer->restarts());
        if (!v.pathTracer->error().empty()) ImGui::TextWrapped("pose not applied: %s", v.pathTracer->error().c_str());
    }
    ImGui::Checkbox("denoise", &pt.denoise);
    int depth = int(pt.maxDepth), perFrame = int(pt.samplesPerFrame), seed = int(pt.seed);
    if (ImGui::SliderInt("max depth", &depth, 1, 32)) pt.maxDepth = uint32_t(std::clamp(depth, 1, 32));
    if (ImGui::SliderInt("samples per frame", &perFrame, 1, 16)) pt.samplesPerFrame = uint32_t(std::clamp(perFrame, 1, 16));
    if (ImGui::InputInt("seed", &seed)) pt.seed = uint32_t(std::max(seed, 0));
}

void cameraPanel(Viewer& v) {
    if (!ImGui::CollapsingHeader("Camera and time", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Text("mode: %s (E)   GUI: G   time: %s (T)", v.state.guiMode ? "GUI" : "FPS", v.state.timePaused ? "paused" : "running");
    ImGui::Text("position (%.3f, %.3f, %.3f) yaw %.1f pitch %.1f", v.camera.position.x, v.camera.position.y,
                v.camera.position.z, glm::degrees(v.camera.yaw), glm::degrees(v.camera.pitch));
    ImGui::Text("speed %.3f, scene time %.2f s", glm::length(v.camera.velocity), v.state.sceneTime);
    ImGui::Text("recording (Ctrl+R): %s   replay (Ctrl+Space): %s", v.recorder.recording() ? "on" : "off",
                v.state.replaying ? "on" : "off");
    if (!v.state.status.empty()) ImGui::TextWrapped("%s", v.state.status.c_str());
}

void shaderPanel(Viewer& v) {
    const auto& errors = v.reloader->currentErrors();
    if (!ImGui::CollapsingHeader("Shaders", errors.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::Button("recompile all (1)")) v.reloader->reloadAll();
    ImGui::SameLine();
    ImGui::Text("watch: %s", v.options.watch ? "on" : "off (--watch)");
    for (const ReloadLogEntry& e : errors) {
        ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.4f, 1.0f));
        ImGui::TextWrapped("%s: %s", e.shader.c_str(), e.message.c_str());
        ImGui::PopStyleColor();
    }
    if (errors.empty() && !v.reloader->log().empty()) ImGui::TextWrapped("%s", v.reloader->log().back().message.c_str());
}

}  // namespace

void drawPanels(Viewer& v) {
    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    const ImVec2 display = ImGui::GetIO().DisplaySize;  // small windows keep most of the frame visible
    ImGui::SetNextWindowSize(ImVec2(std::min(420.0f, display.x * 0.45f), std::min(560.0f, display.y - 16.0f)),
                             ImGuiCond_FirstUseEver);
    ImGui::Begin("idk-viewer");
    rendererPanel(v);
    framePanel(v);
    pathTracerPanel(v);
    cameraPanel(v);
    scenePanel(v);
    shaderPanel(v);
    devicePanel(v);
    ImGui::End();
}

}  // namespace idk::viewer
