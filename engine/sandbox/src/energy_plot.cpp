// Energy history and its ImGui plot (energy_plot.h).
#include "energy_plot.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rigidlab::sandbox {

void EnergyHistory::sample(const World& world) {
  // The thesis's figure splits the kinetic energy; the core's kineticEnergy() is their sum.
  EnergySample s;
  s.time = world.time();
  for (const BodyId id : world.bodyIds()) {
    const Body& b = world.body(id);
    if (b.isStatic()) continue;
    s.linear += 0.5 * b.mass * b.velocity.squaredNorm();
    s.rotational += 0.5 * b.inertia * b.angular_velocity * b.angular_velocity;
  }
  s.potential = world.potentialEnergy();
  add(s);
}

void EnergyHistory::add(const EnergySample& s) {
  if (!samples_.empty() && s.time < samples_.back().time) samples_.clear();
  if (!samples_.empty() && s.time == samples_.back().time) samples_.pop_back();  // paused: replace
  samples_.push_back(s);
  while (!samples_.empty() && samples_.front().time < s.time - window_) samples_.pop_front();
}

double EnergyHistory::totalDrift() const {
  if (samples_.empty()) return 0.0;
  double lo = samples_.front().total(), hi = lo;
  for (const EnergySample& s : samples_) {
    lo = std::min(lo, s.total());
    hi = std::max(hi, s.total());
  }
  return hi - lo;
}

void drawEnergyPlot(const EnergyHistory& history, float height) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = std::max(ImGui::GetContentRegionAvail().x, 50.0f);
  const ImVec2 end(origin.x + width, origin.y + height);
  dl->AddRectFilled(origin, end, IM_COL32(20, 22, 26, 255));
  dl->AddRect(origin, end, IM_COL32(90, 90, 100, 255));
  ImGui::Dummy(ImVec2(width, height));

  const auto& samples = history.samples();
  constexpr int kSeries = 4;
  const ImU32 colors[kSeries] = {IM_COL32(90, 200, 255, 255), IM_COL32(200, 120, 255, 255), IM_COL32(255, 170, 60, 255),
                                 IM_COL32(240, 240, 240, 255)};
  const char* names[kSeries] = {"linear", "rotational", "potential", "total"};
  const auto value = [](const EnergySample& s, int k) {
    return k == 0 ? s.linear : k == 1 ? s.rotational : k == 2 ? s.potential : s.total();
  };
  if (samples.size() >= 2) {
    double lo = INFINITY, hi = -INFINITY;
    for (const EnergySample& s : samples) {
      for (int k = 0; k < kSeries; ++k) {
        const double v = value(s, k);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
    }
    if (hi - lo < 1e-9 * std::max(1.0, std::abs(hi))) {  // flat: give it some room
      lo -= 0.5;
      hi += 0.5;
    }
    const double t1 = samples.back().time, t0 = std::max(samples.front().time, t1 - history.window());
    const double span = std::max(t1 - t0, 1e-9);
    // Values on the left, curves to their right, so labels never cover a curve.
    const float pad = 6.0f, axis = 64.0f;
    const auto toScreen = [&](double t, double v) {
      return ImVec2(origin.x + axis + static_cast<float>((t - t0) / span) * (width - axis - pad),
                    end.y - pad - static_cast<float>((v - lo) / (hi - lo)) * (height - 2 * pad));
    };
    dl->AddLine(ImVec2(origin.x + axis - 2, origin.y), ImVec2(origin.x + axis - 2, end.y), IM_COL32(70, 70, 80, 255));
    if (lo < 0.0 && hi > 0.0) {  // the zero line
      const float y = toScreen(t0, 0.0).y;
      dl->AddLine(ImVec2(origin.x + axis - 2, y), ImVec2(end.x, y), IM_COL32(70, 70, 80, 255));
    }
    // One polyline per series; ImGui caps vertex counts per call, so long histories are decimated.
    const size_t stride = std::max<size_t>(1, samples.size() / 800);
    std::vector<ImVec2> points;
    for (int k = 0; k < kSeries; ++k) {
      points.clear();
      for (size_t i = 0; i < samples.size(); i += stride) points.push_back(toScreen(samples[i].time, value(samples[i], k)));
      dl->AddPolyline(points.data(), static_cast<int>(points.size()), colors[k], 0, k == kSeries - 1 ? 2.0f : 1.5f);
    }
    char label[64];
    std::snprintf(label, sizeof label, "%.4g J", hi);
    dl->AddText(ImVec2(origin.x + 4, origin.y + 2), IM_COL32(160, 160, 170, 255), label);
    std::snprintf(label, sizeof label, "%.4g J", lo);
    dl->AddText(ImVec2(origin.x + 4, end.y - 16), IM_COL32(160, 160, 170, 255), label);
    std::snprintf(label, sizeof label, "%.3g s", span);
    dl->AddText(ImVec2(end.x - ImGui::CalcTextSize(label).x - 4, end.y - 16), IM_COL32(110, 110, 120, 255), label);
  }
  for (int k = 0; k < kSeries; ++k) {
    if (k > 0) ImGui::SameLine();
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(colors[k]), "%s", names[k]);
  }
  if (!samples.empty()) {
    const EnergySample& s = samples.back();
    ImGui::Text("K %.6g J   U %.6g J   E %.6g J", s.kinetic(), s.potential, s.total());
    ImGui::Text("drift of E over the plot: %.3g J", history.totalDrift());
  }
}

}  // namespace rigidlab::sandbox
