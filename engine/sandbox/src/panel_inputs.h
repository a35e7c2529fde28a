// Dear ImGui input fields for doubles and vectors, and the bookkeeping that makes one undo step
// of a field edit (not one per keystroke). Shared by the panels.
#pragma once

#include <imgui.h>

#include <numbers>

#include "rigidlab/math.h"

namespace rigidlab::sandbox {

inline bool inputDouble(const char* label, double* v, const char* format = "%.6g", bool read_only = false) {
  return ImGui::InputScalar(label, ImGuiDataType_Double, v, nullptr, nullptr, format,
                            read_only ? ImGuiInputTextFlags_ReadOnly : 0);
}
inline bool inputVec(const char* label, Vec2* v, const char* format = "%.6g", bool read_only = false) {
  return ImGui::InputScalarN(label, ImGuiDataType_Double, v->data(), 2, nullptr, nullptr, format,
                             read_only ? ImGuiInputTextFlags_ReadOnly : 0);
}
// An angle kept in radians, shown and typed in degrees.
inline bool inputDegrees(const char* label, double* radians) {
  double degrees = *radians * 180.0 / std::numbers::pi;
  if (!inputDouble(label, &degrees)) return false;
  *radians = degrees * std::numbers::pi / 180.0;
  return true;
}
// 64 collision-filter bits, typed in hexadecimal.
inline bool inputBits(const char* label, uint64_t* bits) {
  return ImGui::InputScalar(label, ImGuiDataType_U64, bits, nullptr, nullptr, "%016llX",
                            ImGuiInputTextFlags_CharsHexadecimal);
}

// Call track() after each field: `activated` when one became active this frame, `committed` when
// one was left after a change (the moment to record the edit in the undo history).
struct EditTracker {
  bool activated = false, committed = false;
  void track() {
    activated = activated || ImGui::IsItemActivated();
    committed = committed || ImGui::IsItemDeactivatedAfterEdit();
  }
};

}  // namespace rigidlab::sandbox
