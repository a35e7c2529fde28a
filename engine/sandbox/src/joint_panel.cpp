// The Joint panel (property_panels.h): the selected joint's bodies and readings, and what
// World::updateJoint may change (limits, motor, spring, forces, break thresholds, name,
// collide_connected). Editable while running too: a joint's tunables change nothing of the state.
#include <imgui.h>
#include <imgui_stdlib.h>

#include <cmath>
#include <limits>

#include "panel_inputs.h"
#include "property_panels.h"

namespace rigidlab::sandbox {

namespace {

const ImVec4 kDimColor(0.6f, 0.6f, 0.65f, 1.0f);
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string bodyLabel(const World& w, BodyId id) { return id.isNull() ? "the world" : describe(w, id); }

void readings(const World& w, JointId id, const JointDef& d) {
  const JointState st = w.jointState(id);
  ImGui::TextColored(kDimColor, "a: %s   b: %s", bodyLabel(w, d.a).c_str(), bodyLabel(w, d.b).c_str());
  switch (d.type) {
    case JointType::Revolute:
      ImGui::Text("angle %.2f deg   speed %.3g rad/s", st.angle * 180.0 / std::numbers::pi, st.speed);
      break;
    case JointType::Prismatic:
      ImGui::Text("translation %.4g m   speed %.3g m/s", st.translation, st.speed);
      break;
    case JointType::Wheel:
      ImGui::Text("translation %.4g m   spin %.3g rad/s", st.translation, st.speed);
      break;
    case JointType::Distance:
      ImGui::Text("length %.4g m", st.translation);
      break;
    default:
      break;
  }
  ImGui::Text("reaction %.4g N   %.4g N m", st.reaction_force.norm(), st.reaction_torque);
}

// Limits, motor and spring of the kinds that have them.
void limitMotorSpring(JointDef& e, EditTracker& t) {
  const bool revolute = e.type == JointType::Revolute, distance = e.type == JointType::Distance;
  const bool axial = e.type == JointType::Prismatic || e.type == JointType::Wheel;
  if (revolute || axial) {
    ImGui::Checkbox("limit", &e.enable_limit);
    t.track();
    if (e.enable_limit) {
      if (revolute) {
        inputDegrees("lower [deg]", &e.lower);
        t.track();
        inputDegrees("upper [deg]", &e.upper);
      } else {
        inputDouble("lower [m]", &e.lower);
        t.track();
        inputDouble("upper [m]", &e.upper);
      }
      t.track();
    }
    ImGui::Checkbox("motor", &e.enable_motor);
    t.track();
    if (e.enable_motor) {
      inputDouble(e.type == JointType::Prismatic ? "speed [m/s]" : "speed [rad/s]", &e.motor_speed);
      t.track();
      if (e.type == JointType::Prismatic) inputDouble("max force [N]", &e.max_motor_force);
      else inputDouble("max torque [N m]", &e.max_motor_torque);
      t.track();
    }
  }
  if (distance) {
    inputDouble("length [m]", &e.length);
    t.track();
    ImGui::Checkbox("length range (rope)", &e.enable_limit);
    t.track();
    if (e.enable_limit) {
      inputDouble("min length [m]", &e.min_length);
      t.track();
      inputDouble("max length [m]", &e.max_length);
      t.track();
    }
  }
  if (revolute || axial || distance) {
    ImGui::Checkbox("spring", &e.enable_spring);
    t.track();
    if (e.enable_spring) {
      inputDouble("spring [Hz]", &e.spring_hertz);
      t.track();
      inputDouble("damping ratio", &e.spring_damping);
      t.track();
      if (distance) {
        inputDouble("max spring force [N]", &e.max_spring_force);
        t.track();
      }
    }
  }
}

void kindFields(JointDef& e, EditTracker& t) {
  switch (e.type) {
    case JointType::Weld:
      ImGui::TextColored(kDimColor, "springs (0 Hz: rigid)");
      inputDouble("linear [Hz]", &e.linear_hertz);
      t.track();
      inputDouble("linear damping", &e.linear_damping);
      t.track();
      inputDouble("angular [Hz]", &e.angular_hertz);
      t.track();
      inputDouble("angular damping", &e.angular_damping);
      t.track();
      break;
    case JointType::Motor:
      inputVec("target [m]", &e.linear_offset);
      t.track();
      inputDegrees("target angle [deg]", &e.angular_offset);
      t.track();
      inputDouble("spring [Hz]", &e.motor_hertz);
      t.track();
      inputDouble("damping ratio", &e.motor_damping);
      t.track();
      [[fallthrough]];
    case JointType::Friction:
      inputDouble("max force [N]", &e.max_force);
      t.track();
      inputDouble("max torque [N m]", &e.max_torque);
      t.track();
      break;
    case JointType::Pulley:
    case JointType::Gear:  // the coupling holds from where the bodies are when it changes
      inputDouble("ratio", &e.ratio, "%.4g");
      t.track();
      break;
    default:
      limitMotorSpring(e, t);
      break;
  }
}

}  // namespace

void jointWindow(Session& s, PanelState& p) {
  World& w = s.world();
  const JointId id = s.selected_joint;
  if (!w.isValid(id) || id == s.tools.drag_joint) {
    p.joint_before.reset();
    return;
  }
  if (!p.dock.begin("Joint")) {  // in the left column, under the controls
    p.dock.end();
    return;
  }
  const JointDef current = w.joint(id);
  ImGui::Text("%s joint", jointTypeName(current.type));
  readings(w, id, current);
  JointDef edited = current;
  EditTracker t;
  ImGui::PushItemWidth(150);
  ImGui::InputText("name", &edited.name);
  t.track();
  ImGui::Checkbox("collide connected", &edited.collide_connected);
  t.track();
  bool breaks = std::isfinite(edited.break_force) || std::isfinite(edited.break_torque);
  if (ImGui::Checkbox("breaks", &breaks)) {
    edited.break_force = breaks ? 1000.0 : kInf;
    edited.break_torque = breaks ? 1000.0 : kInf;
  }
  t.track();
  if (breaks) {
    inputDouble("break force [N]", &edited.break_force);
    t.track();
    inputDouble("break torque [N m]", &edited.break_torque);
    t.track();
  }
  kindFields(edited, t);
  ImGui::PopItemWidth();
  if (t.activated && !p.joint_before) {
    p.joint_before = current;
    p.edit_joint = id;
  }
  if (!sameTunables(edited, current)) {
    try {
      w.updateJoint(id, edited);
    } catch (const std::exception& e) {
      s.setStatus(std::string("refused: ") + e.what());  // the joint keeps its last good values
    }
  }
  if (t.committed && p.joint_before && p.edit_joint == id) {
    s.undo.recordModifyJoint(id, *p.joint_before, w.joint(id), "edit " + describe(w, id));
    p.joint_before.reset();
  }
  if (ImGui::Button("Delete joint")) deleteJoint(s, id);
  p.dock.end();
}

}  // namespace rigidlab::sandbox
