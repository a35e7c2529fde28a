// The Body panel (property_panels.h): the selected body's fields, and those of one of its shapes
// at a time (a chain can have hundreds). Editable while paused; each field left after a change is
// one undo step.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

#include "camera_follow.h"
#include "panel_inputs.h"
#include "property_panels.h"

namespace rigidlab::sandbox {

namespace {

const ImVec4 kDimColor(0.6f, 0.6f, 0.65f, 1.0f);

void bodyFields(BodyProps& edited, EditTracker& t) {
  ImGui::InputText("name", &edited.name);
  t.track();
  int type = static_cast<int>(edited.type);
  const char* types[] = {"static", "kinematic", "dynamic"};  // BodyType's order
  if (ImGui::Combo("type", &type, types, 3)) edited.type = static_cast<BodyType>(type);
  t.track();
  inputDouble("mass [kg]", &edited.mass);
  t.track();
  inputVec("position [m]", &edited.position);
  t.track();
  inputDegrees("angle [deg]", &edited.angle);
  t.track();
  inputVec("velocity [m/s]", &edited.velocity);
  t.track();
  inputDouble("angular velocity [rad/s]", &edited.angular_velocity);
  t.track();
  if (!ImGui::CollapsingHeader("options")) return;  // closed by default: the panel stays short
  inputDouble("linear damping [1/s]", &edited.linear_damping);
  t.track();
  inputDouble("angular damping [1/s]", &edited.angular_damping);
  t.track();
  inputDouble("gravity scale", &edited.gravity_scale);
  t.track();
  // Its own gravity (BodyDef::gravity) in place of the world's.
  bool own = edited.gravity.has_value();
  if (ImGui::Checkbox("own gravity", &own)) edited.gravity = own ? std::optional(Vec2(0.0, -9.80665)) : std::nullopt;
  t.track();
  if (edited.gravity) {
    ImGui::SameLine();
    inputVec("[m/s2]", &*edited.gravity);
    t.track();
  }
  ImGui::Checkbox("may sleep", &edited.sleeping_allowed);
  t.track();
  ImGui::Checkbox("fixed rotation", &edited.fixed_rotation);
  t.track();
  ImGui::SameLine();
  ImGui::Checkbox("bullet", &edited.bullet);
  t.track();
  ImGui::SameLine();
  ImGui::Checkbox("enabled", &edited.enabled);
  t.track();
}

void shapeFields(const World& w, const Body& b, BodyProps& edited, PanelState& p, EditTracker& t) {
  if (b.shapes.empty()) return;
  const int n = static_cast<int>(b.shapes.size());
  if (!ImGui::CollapsingHeader(n == 1 ? "shape" : "shapes")) return;
  p.shape_index = std::clamp(p.shape_index, 0, n - 1);
  if (n > 1) {
    int shown = p.shape_index + 1;
    if (ImGui::SliderInt("shape", &shown, 1, n)) p.shape_index = shown - 1;
  }
  const Shape& g = w.shape(b.shapes[p.shape_index]).geometry;
  ImGui::TextColored(kDimColor, "shape %d of %d: %s%s", p.shape_index + 1, n, shapeTypeName(g.type),
                     w.shape(b.shapes[p.shape_index]).chain ? " (of a chain)" : "");
  ShapeProps& sp = edited.shapes[p.shape_index];
  if (hasArea(g.type)) {
    inputDouble("density [kg/m2]", &sp.density);
    t.track();
  }
  inputDouble("restitution", &sp.material.restitution, "%.4g");
  t.track();
  inputDouble("friction", &sp.material.friction, "%.4g");
  t.track();
  inputDouble("static friction", &sp.material.static_friction, "%.4g");
  t.track();
  ImGui::Checkbox("sensor", &sp.sensor);
  t.track();
  inputBits("category", &sp.filter.category);
  t.track();
  inputBits("mask", &sp.filter.mask);
  t.track();
  int group = sp.filter.group;
  if (ImGui::InputInt("group", &group)) sp.filter.group = group;
  t.track();
  inputDouble("tangent speed [m/s]", &sp.tangent_speed, "%.4g");
  t.track();
  inputDouble("rolling resistance", &sp.rolling_resistance, "%.4g");
  t.track();
}

}  // namespace

void bodyWindow(Session& s, PanelState& p) {
  World& w = s.world();
  if (!w.isValid(s.selected)) {
    p.edit_before.reset();
    return;
  }
  if (p.shown_body != s.selected) p.shape_index = 0;
  p.shown_body = s.selected;
  if (!p.dock.begin("Body")) {  // in the left column, under the controls
    p.dock.end();
    return;
  }
  const Body& b = w.body(s.selected);
  const char* kind = b.shapes.size() == 1 ? shapeTypeName(w.shape(b.shapes[0]).geometry.type)
                     : b.shapes.empty() ? "no shape" : "compound";
  ImGui::Text("#%u %s   area %.4g m2   I %.4g kg m2", b.uid, kind, b.area, b.inertia);
  if (b.shapes.size() > 1) ImGui::TextColored(kDimColor, "%zu shapes, %zu joints", b.shapes.size(), w.jointsOf(s.selected).size());
  const bool editable = s.paused;
  if (!editable) ImGui::TextColored(kDimColor, "pause (Space) to edit");
  const BodyProps current = captureProps(w, s.selected);
  BodyProps edited = current;
  EditTracker t;
  ImGui::PushItemWidth(150);
  ImGui::BeginDisabled(!editable);
  bodyFields(edited, t);
  shapeFields(w, b, edited, p, t);
  ImGui::EndDisabled();
  ImGui::PopItemWidth();
  if (editable) {
    if (t.activated && !p.edit_before) {
      p.edit_before = current;
      p.edit_body = s.selected;
    }
    if (!(edited == current)) {
      try {
        // A mass edit scales the densities (World::setMass); any other edit is applied as props,
        // whose mass then follows from the densities.
        if (edited.mass != current.mass) w.setMass(s.selected, edited.mass);
        else applyProps(w, s.selected, edited);
        s.history.capture(w);
      } catch (const std::exception& e) {
        applyProps(w, s.selected, current);  // the last good values stay
        s.setStatus(std::string("refused: ") + e.what());
      }
    }
    if (t.committed && p.edit_before && p.edit_body == s.selected) {
      s.undo.recordModify(s.selected, *p.edit_before, captureProps(w, s.selected), "edit " + describe(w, s.selected));
      p.edit_before.reset();
    }
  }
  const bool following = s.follow == s.selected;
  if (ImGui::Button(following ? "Stop following" : "Follow")) followBody(s, following ? BodyId{} : s.selected);  // also C
  ImGui::SameLine();
  if (ImGui::Button("Delete")) deleteBody(s, s.selected);
  ImGui::SameLine();
  ImGui::TextColored(kDimColor, "(its joints too)");
  p.dock.end();
}

}  // namespace rigidlab::sandbox
