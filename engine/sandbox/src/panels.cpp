// Dear ImGui panels (panels.h), docked in two columns (panel_dock.h): controls, the selection's
// inspectors and the scene browser on the left, readouts on the right, the world in between; a
// panel can be collapsed, or dragged away (undocked).
#include "panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "panel_inputs.h"
#include "panel_layout.h"
#include "property_panels.h"
#include "renderer.h"
#include "rigidlab/lua/scene_writer.h"
#include "scene_controls_panel.h"
#include "tools.h"

namespace rigidlab::sandbox {

namespace {

const ImVec4 kErrorColor(1.0f, 0.45f, 0.4f, 1.0f), kWarnColor(1.0f, 0.8f, 0.3f, 1.0f), kDimColor(0.6f, 0.6f, 0.65f, 1.0f);

// Rewind (rewind.cpp): the kept states, their memory, a slider to scrub them, step back, save.
void timelineSection(Session& s) {
  Timeline& t = s.timeline;
  if (t.empty()) return;
  ImGui::Separator();
  ImGui::TextWrapped("timeline: %.1f s, %zu states (1 per %d steps), %.1f MiB (limit %.0f MiB)", t.span(), t.size(),
                     t.limits().every, static_cast<double>(t.bytes()) / (1 << 20),
                     static_cast<double>(t.limits().max_bytes) / (1 << 20));
  int index = static_cast<int>(t.cursor());
  ImGui::PushItemWidth(-1);
  if (ImGui::SliderInt("##timeline", &index, 0, static_cast<int>(t.size()) - 1, "", ImGuiSliderFlags_AlwaysClamp))
    seekState(s, static_cast<size_t>(index));
  ImGui::PopItemWidth();
  if (ImGui::Button("< Back")) stepBack(s);  // also Shift+N
  ImGui::SameLine();
  if (ImGui::Button("Save state")) {
    std::string message;
    saveState(s, suggestStatePath(s), message);
    std::printf("%s\n", message.c_str());
    s.setStatus(message, 8.0);
  }
  if (t.rewound())
    ImGui::TextColored(kWarnColor, "rewound to t = %.3f s: resuming or editing drops the %zu later states",
                       t.at(t.cursor()).time, t.size() - 1 - t.cursor());
}

void sceneSection(Session& s) {
  const lua::SceneSettings& settings = s.scene->settings();
  ImGui::TextWrapped("%s", overlayText(settings.title, 256).c_str());
  if (!s.file.empty()) ImGui::TextColored(kDimColor, "%s", s.file.filename().string().c_str());
  if (s.paused) ImGui::TextColored(kWarnColor, "PAUSED   t = %.3f s   step %ld", s.world().time(), s.world().stepCount());
  else ImGui::Text("running  t = %.3f s   step %ld", s.world().time(), s.world().stepCount());

  if (ImGui::Button(s.paused ? "Resume" : "Pause")) setPaused(s, !s.paused);
  ImGui::SameLine();
  if (ImGui::Button("Step")) stepOnce(s);
  ImGui::SameLine();
  if (ImGui::Button("Reset") && !s.file.empty()) requestLoad(s, s.file, LoadPurpose::Reset);
  ImGui::SameLine();
  if (ImGui::Button("Fit")) fitCamera(s);
  ImGui::BeginDisabled(!s.undo.canUndo());
  if (ImGui::Button("Undo")) undo(s);
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!s.undo.canRedo());
  if (ImGui::Button("Redo")) redo(s);
  ImGui::EndDisabled();
  ImGui::SameLine();
  if (ImGui::Button("Save as...")) {
    s.save = {true, suggestSavePath(s).string(), "", false};
  }
  ImGui::SameLine();
  if (ImGui::Button("Scenes")) s.show_browser = !s.show_browser;  // also Ctrl+O
  if (s.undo.canUndo()) ImGui::TextColored(kDimColor, "undo: %s", s.undo.undoLabel().c_str());
  timelineSection(s);
}

void jointToolSection(ToolState& t) {
  if (ImGui::BeginCombo("kind", jointTypeName(t.joint_kind))) {
    for (const JointType kind : kToolJoints)
      if (ImGui::Selectable(jointTypeName(kind), kind == t.joint_kind)) t.joint_kind = kind;
    ImGui::EndCombo();
  }
  if (t.joint_kind == JointType::Prismatic || t.joint_kind == JointType::Wheel)
    inputDouble("axis [deg]", &t.joint_axis_degrees, "%.4g");
  if (t.joint_kind == JointType::Distance) ImGui::Checkbox("rope (slack when shorter)", &t.joint_rope);
  ImGui::Checkbox("bodies collide", &t.joint_collide);
}

void toolsSection(Session& s) {
  ToolState& t = s.tools;
  for (const Tool tool : {Tool::Select, Tool::Circle, Tool::Box, Tool::Polygon, Tool::Capsule, Tool::Joint}) {
    if (ImGui::RadioButton(toolName(tool), t.tool == tool)) selectTool(s, tool);
    if (tool == Tool::Select || tool == Tool::Box || tool == Tool::Capsule) ImGui::SameLine();  // two per row
  }
  ImGui::PushItemWidth(120);
  if (t.tool == Tool::Circle) inputDouble("radius [m]", &t.circle_radius);
  if (t.tool == Tool::Box) {
    inputDouble("width [m]", &t.box_width);
    inputDouble("height [m]", &t.box_height);
  }
  if (t.tool == Tool::Capsule) {
    inputDouble("length [m]", &t.capsule_length);
    inputDouble("radius [m]", &t.capsule_radius);
  }
  if (t.tool == Tool::Joint) jointToolSection(t);
  if (t.tool != Tool::Select && t.tool != Tool::Joint) {
    inputDouble("density [kg/m2]", &t.density);
    inputDouble("restitution", &t.restitution, "%.3g");
    inputDouble("friction", &t.friction, "%.3g");
    ImGui::Checkbox("static", &t.make_static);
  }
  ImGui::PopItemWidth();
  t.circle_radius = std::max(t.circle_radius, 0.01);
  t.box_width = std::max(t.box_width, 0.01);
  t.box_height = std::max(t.box_height, 0.01);
  t.capsule_length = std::max(t.capsule_length, 0.01);
  t.capsule_radius = std::max(t.capsule_radius, 0.01);
  t.density = std::max(t.density, 1e-6);
  t.restitution = std::clamp(t.restitution, 0.0, 1.0);
  t.friction = std::max(t.friction, 0.0);
  if (t.tool == Tool::Polygon)
    ImGui::TextColored(kDimColor, "%zu point(s); Enter or click the first to close", t.polygon.size());
  if (t.tool == Tool::Joint)
    ImGui::TextColored(kDimColor, s.world().isValid(t.joint_body) ? "now click where the joint goes (empty space: the world)"
                                                                   : "click a body, then where the joint goes");
}

void worldSection(Session& s) {
  World& w = s.world();
  WorldOverrides& o = s.overrides;
  ImGui::PushItemWidth(150);
  Vec2 g = w.settings().gravity;
  if (inputVec("gravity [m/s2]", &g) && isFinite(g)) o.gravity = g;
  const std::string current(integratorName(w.settings().integrator));
  if (ImGui::BeginCombo("integrator", current.c_str())) {
    // Every integrator the core has: the enum counts up from 0 and unknown values have no name.
    for (int k = 0; k < 32; ++k) {
      const auto i = static_cast<Integrator>(k);
      const std::string name(integratorName(i));
      if (name.empty()) break;
      if (ImGui::Selectable(name.c_str(), i == w.settings().integrator)) o.integrator = i;
    }
    ImGui::EndCombo();
  }
  double dt_ms = s.dt() * 1000.0;
  if (inputDouble("dt [ms]", &dt_ms, "%.4g") && dt_ms > 0.01 && dt_ms <= 1000.0) o.dt = dt_ms / 1000.0;
  const std::string solver(contactSolverName(w.settings().contact_solver));
  if (ImGui::BeginCombo("contact solver", solver.c_str())) {
    for (ContactSolver c : {ContactSolver::Auto, ContactSolver::SequentialImpulses, ContactSolver::SoftStep})
      if (ImGui::Selectable(std::string(contactSolverName(c)).c_str(), c == w.settings().contact_solver)) o.solver = c;
    ImGui::EndCombo();
  }
  int iterations = w.settings().iterations;
  if (ImGui::InputInt("iterations", &iterations) && iterations >= 1 && iterations <= 10000) o.iterations = iterations;
  int substeps = w.settings().substeps;
  if (ImGui::InputInt("substeps", &substeps) && substeps >= 1 && substeps <= 64) o.substeps = substeps;
  bool warm = w.settings().warm_starting;
  if (ImGui::Checkbox("warm starting", &warm)) o.warm_starting = warm;
  ImGui::SameLine();
  bool sleeping = w.settings().sleeping;
  if (ImGui::Checkbox("sleeping", &sleeping)) o.sleeping = sleeping;
  applyOverrides(s);
  if (o.any()) {
    ImGui::TextColored(kWarnColor, "changed here: kept across reloads");
    if (ImGui::Button("use the scene's values")) clearOverrides(s);
  }

  ImGui::Separator();
  ImGui::TextUnformatted("loop");
  int mode = s.loop.mode == LoopMode::Fixed ? 0 : 1;
  if (ImGui::RadioButton("fixed step", &mode, 0) | ImGui::RadioButton("variable step", &mode, 1)) {
    s.loop.mode = mode == 0 ? LoopMode::Fixed : LoopMode::Variable;
    s.clock.reset();
  }
  ImGui::SliderInt("max steps/frame", &s.loop.max_steps_per_frame, 1, 64);
  float cap = static_cast<float>(s.loop.frame_cap_hz);
  if (ImGui::SliderFloat("frame cap [Hz]", &cap, 0.0f, 240.0f, cap == 0.0f ? "none" : "%.0f"))
    s.loop.frame_cap_hz = cap;
  float scale = static_cast<float>(s.loop.time_scale);
  if (ImGui::SliderFloat("time scale", &scale, 0.05f, 4.0f, "%.2fx", ImGuiSliderFlags_Logarithmic))
    s.loop.time_scale = scale;
  ImGui::PopItemWidth();
}

void drawSection(Session& s) {
  DrawToggles& d = s.draw;
  ImGui::Checkbox("grid", &d.grid);
  ImGui::SameLine();
  ImGui::Checkbox("springs", &d.springs);
  ImGui::SameLine();
  ImGui::Checkbox("forces", &d.forces);
  ImGui::SameLine();
  ImGui::Checkbox("joints (F10)", &d.joints);
  ImGui::Checkbox("contacts (F2)", &d.contacts);
  ImGui::SameLine();
  ImGui::Checkbox("normals (F3)", &d.normals);
  ImGui::Checkbox("impulses (F4)", &d.impulses);
  ImGui::SameLine();
  ImGui::Checkbox("bounds (F6)", &d.aabbs);
  ImGui::Checkbox("centres (F7)", &d.centers);
  ImGui::SameLine();
  ImGui::Checkbox("velocities (F8)", &d.velocities);
  ImGui::Checkbox("exact solution ghosts (scenes with Exact)", &d.exact);
}

void controlsWindow(Session& s, PanelState& p) {
  if (p.dock.begin("rigidlab")) {  // the column re-stacks as its sections open and close
    sceneSection(s);
    if (ImGui::CollapsingHeader("Tools", ImGuiTreeNodeFlags_DefaultOpen)) toolsSection(s);
    if (ImGui::CollapsingHeader("World settings")) worldSection(s);
    if (ImGui::CollapsingHeader("Draw")) drawSection(s);
    ImGui::TextColored(kDimColor, "F1: all shortcuts");
    if (p.dock.anyUndocked()) {
      ImGui::SameLine();
      if (ImGui::SmallButton("Dock panels")) p.dock.dockAll();  // the ones dragged away
    }
  }
  p.dock.end();
}

void browserWindow(Session& s, PanelState& p) {
  if (!s.show_browser) {
    p.browser_was_open = false;
    return;
  }
  if (!p.browser_was_open) p.scenes = browsableScenes();  // fresh list each time it opens
  p.browser_was_open = true;
  if (p.dock.begin("Scenes", &s.show_browser)) {
    ImGui::TextColored(kDimColor, "%s", (lua::scriptsDirectory() / "scenes").string().c_str());
    if (ImGui::SmallButton("refresh")) p.scenes = browsableScenes();
    if (p.scenes.empty()) ImGui::TextColored(kWarnColor, "no scenes found");
    for (const auto& file : p.scenes) {
      std::error_code ec;
      const bool current = !s.file.empty() && std::filesystem::equivalent(file, s.file, ec);
      if (ImGui::Selectable(file.stem().string().c_str(), current)) requestLoad(s, file, LoadPurpose::Open);
    }
    if (s.loader.busy()) ImGui::TextColored(kDimColor, "loading...");
  }
  p.dock.end();
}

void statisticsWindow(Session& s, PanelState& p) {
  const ImGuiIO& io = ImGui::GetIO();
  p.fps = p.fps == 0.0 ? io.Framerate : 0.9 * p.fps + 0.1 * io.Framerate;
  if (p.dock.begin("Statistics")) {
    const StepStats& st = s.world().stats();
    ImGui::Text("%.0f fps   frame work %.2f ms", p.fps, s.last_frame_ms);
    ImGui::Text("%d step(s) %.2f ms   step %.3f ms", s.steps_last_frame, s.last_steps_ms, st.total_ms());
    const double ratio = s.meter.ratio();
    if (!s.paused && ratio < 0.97 * s.loop.time_scale)
      ImGui::TextColored(kErrorColor, "slower than real time: %.0f%%", 100.0 * ratio / s.loop.time_scale);
    else
      ImGui::Text("sim/real time %.2f   %s", ratio, s.loop.mode == LoopMode::Fixed ? "fixed step" : "variable step");
    ImGui::Text("bodies %d (%d dynamic, %d awake)", st.bodies, st.dynamic_bodies, st.awake_bodies);
    ImGui::Text("forces %d   pairs %d", st.forces, st.pairs);
    ImGui::Text("contacts %d   points %d", st.contacts, st.contact_points);
    if (const auto& incidents = s.world().incidents(); !incidents.empty()) {
      ImGui::PushTextWrapPos(0.0f);
      ImGui::TextColored(kErrorColor, "%zu incident(s) (NaN firewall, blow-up); last: %s", incidents.size(),
                         incidents.back().message().c_str());
      ImGui::PopTextWrapPos();
    }
  }
  p.dock.end();
}

// Each step stage's last, average and largest time over the last seconds, and the step's time as
// a graph (as Box2D v3's samples show their profile).
void profileWindow(Session& s, PanelState& p, Renderer& r) {
  if (p.dock.begin("Profile")) {
    const ProfileHistory& h = s.profile;
    ImGui::TextColored(kDimColor, "%zu steps in the last %.0f s, ms", h.steps(), h.window());
    if (ImGui::BeginTable("stages", 4, ImGuiTableFlags_SizingStretchProp)) {
      for (const char* head : {"stage", "last", "average", "max"}) ImGui::TableSetupColumn(head);
      ImGui::TableHeadersRow();
      for (size_t k = 0; k < kProfileStages.size(); ++k) {
        const ProfileHistory::Figures f = h.stage(k);
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(kProfileStages[k]);
        for (const double ms : {f.last, f.average, f.maximum}) {
          ImGui::TableNextColumn();
          ImGui::Text("%.3f", ms);
        }
      }
      ImGui::EndTable();
    }
    const std::vector<float> steps = h.stepTimes();
    const double top = h.stage(kProfileStages.size() - 1).maximum;
    char label[48];
    std::snprintf(label, sizeof label, "step, max %.3f ms", top);
    ImGui::PlotLines("##steps", steps.data(), static_cast<int>(steps.size()), 0, label, 0.0f,
                     static_cast<float>(std::max(top, 1e-3)), ImVec2(ImGui::GetContentRegionAvail().x, 50));
    const StepStats& st = s.world().stats();
    ImGui::Text("force evaluations %ld   Lua calls %ld", st.force_evaluations, s.scene->luaCalls());
    ImGui::TextColored(kDimColor, "reloads %d   last load %.1f ms", s.reloads, s.last_load_ms);
    ImGui::TextColored(kDimColor, "watch: %s   %zu vertices drawn", s.watcher.usingInotify() ? "inotify" : "polling",
                       r.vertexCount());
    if (r.skippedFills() > 0)
      ImGui::TextColored(kWarnColor, "%d shapes drawn as outlines (fills over %.0f window areas)", r.skippedFills(),
                         Renderer::kFillScreens);
  }
  p.dock.end();
}

void energyWindow(Session& s, PanelState& p) {
  if (p.dock.begin("Energy")) {
    const float text_rows = 3 * ImGui::GetTextLineHeightWithSpacing() + 8;
    drawEnergyPlot(s.energy, std::max(60.0f, ImGui::GetContentRegionAvail().y - text_rows));
  }
  p.dock.end();
}

void exactWindow(Session& s, PanelState& p) {
  const ExactReadout& x = s.exact;
  if (!p.dock.begin("Exact solution")) {
    p.dock.end();
    return;
  }
  if (!x.error.empty()) {
    ImGui::PushTextWrapPos(0.0f);
    ImGui::TextColored(kErrorColor, "Exact failed (off until the scene reloads): %s", x.error.c_str());
    ImGui::PopTextWrapPos();
  } else {
    ImGui::Text("t = %.3f s   max |p - p_exact| = %.3e m", x.time, x.max_position);
    if (x.max_velocity >= 0.0) ImGui::Text("max |v - v_exact| = %.3e m/s", x.max_velocity);
    ImGui::Text("largest so far %.3e m", x.worst_position);
    ImGui::TextColored(kDimColor, "%s, dt = %.4g s", std::string(integratorName(s.world().settings().integrator)).c_str(),
                       s.dt());
    std::vector<float> values;
    for (const auto& [t, e] : x.history) values.push_back(static_cast<float>(e));
    if (values.size() >= 2)
      ImGui::PlotLines("##error", values.data(), static_cast<int>(values.size()), 0, "position error", 0.0f, FLT_MAX,
                       ImVec2(kRightPanelWidth - 20, 60));
    if (ImGui::BeginTable("bodies", 3, ImGuiTableFlags_SizingStretchProp)) {
      int shown = 0;
      for (const BodyError& e : x.bodies) {
        if (++shown > 8) break;
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::Text("%s", e.name.empty() ? ("#" + std::to_string(e.uid)).c_str() : e.name.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.2e m", e.position);
        ImGui::TableNextColumn();
        if (e.velocity >= 0.0) ImGui::Text("%.2e m/s", e.velocity);
      }
      ImGui::EndTable();
    }
  }
  p.dock.end();
}

void helpWindow(Session& s) {
  if (!s.show_help) return;
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(640, 0), ImGuiCond_Appearing);
  if (ImGui::Begin("Shortcuts (F1)", &s.show_help)) {
    if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
      for (const Shortcut& k : shortcuts()) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextColored(kWarnColor, "%s", k.keys);
        ImGui::TableNextColumn();
        ImGui::TextWrapped("%s", k.action);
      }
      ImGui::EndTable();
    }
  }
  ImGui::End();
}

void saveDialog(Session& s) {
  SaveDialog& d = s.save;
  if (d.open) {
    ImGui::OpenPopup("Save world");
    d.open = false;
  }
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.3f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::BeginPopupModal("Save world", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
  ImGui::TextUnformatted("Save the world (bodies, shapes, joints, springs, dampers, settings, camera) as a new scene file:");
  ImGui::SetNextItemWidth(520);
  if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
  if (ImGui::InputText("##path", &d.path)) d.confirm_overwrite = false;
  std::error_code ec;
  const bool exists = std::filesystem::exists(d.path, ec);
  if (exists && !d.confirm_overwrite && d.message.empty())
    ImGui::TextColored(kWarnColor, "%s exists: saving replaces it", d.path.c_str());
  if (!d.message.empty()) ImGui::TextColored(kErrorColor, "%s", d.message.c_str());
  const char* label = exists && !d.confirm_overwrite ? "Replace..." : "Save";
  if (ImGui::Button(label) || (ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Enter)) && !exists)) {
    if (exists && !d.confirm_overwrite) {
      d.confirm_overwrite = true;  // a second click replaces
      d.message = "click Save again to replace " + d.path;
    } else if (saveWorld(s, d.path, d.message)) {
      ImGui::CloseCurrentPopup();
    }
  }
  ImGui::SameLine();
  if (ImGui::Button("Cancel") || ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape))) ImGui::CloseCurrentPopup();
  ImGui::EndPopup();
}

void errorOverlay(Session& s) {
  std::string heading, text;
  if (!s.run_error.empty()) {
    heading = "Script error: simulation paused (Space resumes, R resets)";
    text = s.run_error;
  } else if (!s.load_error.empty()) {
    heading = s.scene_loaded ? "Reload failed: the last good world keeps running until the next good save"
                             : "The scene did not load: fix the file and save it";
    text = s.load_error;
  } else if (!s.draw_error.empty()) {
    heading = "OnDraw failed: overlay off until the scene reloads";
    text = s.draw_error;
  } else if (s.draw_truncated) {
    heading = "OnDraw output truncated";
    text = "OnDraw asked for more than a frame draws: at most " + std::to_string(lua::Scene::kMaxDrawLines) + " lines, " +
           std::to_string(lua::Scene::kMaxDrawCircles) + " circles and " + std::to_string(lua::Scene::kMaxDrawTexts) +
           " texts (" + std::to_string(lua::Scene::kMaxDrawTextBytes >> 10) + " KiB of text) per frame; the rest is not drawn.";
  } else {
    return;
  }
  const ImGuiIO& io = ImGui::GetIO();
  // Over the world, between the panel columns.
  const ScreenRect free = freeViewArea(static_cast<int>(io.DisplaySize.x), static_cast<int>(io.DisplaySize.y), s.show_panels);
  const float width = std::min(760.0f, static_cast<float>(free.width()) - 2 * kPanelMargin);
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(free.middle().x()), kPanelMargin), ImGuiCond_Always, ImVec2(0.5f, 0.0f));
  ImGui::SetNextWindowSizeConstraints(ImVec2(std::min(300.0f, width), 0), ImVec2(width, 400));
  ImGui::PushStyleColor(ImGuiCol_WindowBg, ImVec4(0.35f, 0.05f, 0.05f, 0.92f));
  ImGui::Begin("##error", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoFocusOnAppearing |
                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove);
  ImGui::TextColored(kWarnColor, "%s", heading.c_str());
  ImGui::PushTextWrapPos(width - 20);
  ImGui::TextUnformatted(text.c_str());
  ImGui::PopTextWrapPos();
  ImGui::End();
  ImGui::PopStyleColor();
}

void statusLine(Session& s) {
  ImDrawList* dl = ImGui::GetForegroundDrawList();
  const ImGuiIO& io = ImGui::GetIO();
  std::string line = std::string("tool: ") + toolName(s.tools.tool);
  if (s.paused) line += "   PAUSED";
  const double ratio = s.meter.ratio();
  const bool slow = !s.paused && ratio < 0.97 * s.loop.time_scale;
  if (slow) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "   SLOWER THAN REAL TIME (%.0f%%)", 100.0 * ratio / s.loop.time_scale);
    line += buffer;
  }
  if (Session::Clock::now() < s.status_until) line += "   " + s.status;
  const ImVec2 size = ImGui::CalcTextSize(line.c_str());
  const ImVec2 at((io.DisplaySize.x - size.x) * 0.5f, io.DisplaySize.y - size.y - 6);
  dl->AddRectFilled(ImVec2(at.x - 6, at.y - 3), ImVec2(at.x + size.x + 6, at.y + size.y + 3), IM_COL32(0, 0, 0, 150), 4);
  dl->AddText(at, slow ? IM_COL32(255, 120, 100, 255) : IM_COL32(220, 220, 225, 255), line.c_str());
}

}  // namespace

void drawPanels(Session& s, PanelState& p, Renderer& renderer) {
  // This frame's panels in their columns' order (panel_dock.h), with their first guesses of height.
  std::vector<DockedPanel> shown;
  const World& w = s.world();
  const bool body = w.isValid(s.selected);
  const bool joint = w.isValid(s.selected_joint) && s.selected_joint != s.tools.drag_joint;
  const bool exact = s.exact.active || !s.exact.error.empty();
  if (s.show_panels) {
    shown.push_back({"rigidlab", Column::Left, 420.0f});
    if (body) shown.push_back({"Body", Column::Left, 260.0f});
    if (joint) shown.push_back({"Joint", Column::Left, 260.0f});
  }
  if (s.show_browser) shown.push_back({"Scenes", Column::Left, 300.0f, true});
  if (s.show_panels) {
    shown.push_back({"Statistics", Column::Right, 130.0f});
    if (!s.scene->settings().controls.empty()) shown.push_back({"Controls", Column::Right, 100.0f});
    shown.push_back({"Energy", Column::Right, 200.0f, true});
    if (exact) shown.push_back({"Exact solution", Column::Right, 260.0f});
    shown.push_back({"Profile", Column::Right, 300.0f});
  }
  std::vector<ScreenRect> hud;
  if (const auto r = renderer.hud()) hud.push_back(*r);
  p.dock.layout(shown, ImGui::GetIO().DisplaySize, hud);

  if (s.show_panels) {
    controlsWindow(s, p);
    bodyWindow(s, p);
    jointWindow(s, p);
    statisticsWindow(s, p);
    sceneControlsWindow(s, p.dock);
    energyWindow(s, p);
    if (exact) exactWindow(s, p);
    profileWindow(s, p, renderer);
  }
  browserWindow(s, p);
  helpWindow(s);
  saveDialog(s);
  errorOverlay(s);
  statusLine(s);
}

}  // namespace rigidlab::sandbox
