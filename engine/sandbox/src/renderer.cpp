// OpenGL 3.3 drawing of the world and the overlays (renderer.h).
#include "renderer.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "assets.h"
#include "gl.h"

namespace rigidlab::sandbox {

namespace {

GLuint compileShader(GLenum type, const std::string& source, const std::string& name, std::string& error) {
  const GLuint shader = glCreateShader(type);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    error = name + ": " + log;
    glDeleteShader(shader);
    return 0;
  }
  return shader;
}

}  // namespace

Renderer::~Renderer() {
  if (vbo_) glDeleteBuffers(1, &vbo_);
  if (vao_) glDeleteVertexArrays(1, &vao_);
  if (program_) glDeleteProgram(program_);
}

bool Renderer::init(const std::filesystem::path& assets, std::string& error) {
  const auto vert_file = assets / "shaders" / "world.vert", frag_file = assets / "shaders" / "world.frag";
  const auto vert = readTextFile(vert_file), frag = readTextFile(frag_file);
  if (!vert || !frag) {
    error = "cannot read " + (!vert ? vert_file : frag_file).string() + " (set RIGIDLAB_ASSETS to the assets directory)";
    return false;
  }
  const GLuint vs = compileShader(GL_VERTEX_SHADER, *vert, vert_file.string(), error);
  if (!vs) return false;
  const GLuint fs = compileShader(GL_FRAGMENT_SHADER, *frag, frag_file.string(), error);
  if (!fs) {
    glDeleteShader(vs);
    return false;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    error = "linking the world shader: " + std::string(log);
    return false;
  }
  scale_location_ = glGetUniformLocation(program_, "u_scale");

  glGenVertexArrays(1, &vao_);
  glGenBuffers(1, &vbo_);
  glBindVertexArray(vao_);
  glBindBuffer(GL_ARRAY_BUFFER, vbo_);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, x)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex), reinterpret_cast<void*>(offsetof(Vertex, r)));
  glBindVertexArray(0);
  return true;
}

Vec2 Renderer::screenToWorld(const Vec2& px) const {
  if (!hud_) hud_ = ScreenRect{px, px};
  hud_->lower = hud_->lower.cwiseMin(px);
  hud_->upper = hud_->upper.cwiseMax(px);
  return camera_.screenToWorld(px);
}

std::optional<ScreenRect> Renderer::hud() const {
  if (!hud_) return std::nullopt;
  const Vec2 m(kHudMargin, kHudMargin);
  return ScreenRect{hud_->lower - m, hud_->upper + m};
}

void Renderer::begin(const Camera& camera) {
  camera_ = camera;
  vertices_.clear();
  texts_.clear();
  hud_.reset();
  fill_left_px_ = kFillScreens * camera.width_px * camera.height_px;
  last_skipped_fills_ = skipped_fills_;
  skipped_fills_ = 0;
  glViewport(0, 0, camera.width_px, camera.height_px);
  glClearColor(Palette::background.r, Palette::background.g, Palette::background.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

void Renderer::flush() {
  last_vertex_count_ = vertices_.size();
  if (!vertices_.empty()) {
    glUseProgram(program_);
    glUniform2f(scale_location_, static_cast<float>(2.0 * camera_.pixels_per_metre / camera_.width_px),
                static_cast<float>(2.0 * camera_.pixels_per_metre / camera_.height_px));
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertices_.size() * sizeof(Vertex)), vertices_.data(),
                 GL_STREAM_DRAW);
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size()));
    glBindVertexArray(0);
    glUseProgram(0);
  }
  vertices_.clear();
}

void Renderer::triangle(const Vec2& a, const Vec2& b, const Vec2& c, const Color& color) {
  // Camera-relative in double, then float: precision is spent where the view is.
  for (const Vec2* p : {&a, &b, &c}) {
    const Vec2 r = *p - camera_.center;
    vertices_.push_back({static_cast<float>(r.x()), static_cast<float>(r.y()), color.r, color.g, color.b, color.a});
  }
}

int Renderer::circleSegments(double radius) const {
  const double pixels = radius * camera_.pixels_per_metre;
  return std::clamp(static_cast<int>(pixels * 0.75), 16, 128);
}

void Renderer::drawSegment(const Vec2& a, const Vec2& b, const Color& color) {
  const Vec2 d = b - a;
  const double length = d.norm();
  if (!(length > 0.0) || !std::isfinite(length)) return;
  const Vec2 side = perp(d / length) * camera_.metres(0.5 * line_width_pixels);
  triangle(a - side, a + side, b + side, color);
  triangle(a - side, b + side, b - side, color);
}

void Renderer::drawPolyline(std::span<const Vec2> points, bool closed, const Color& color) {
  for (size_t i = 0; i + 1 < points.size(); ++i) drawSegment(points[i], points[i + 1], color);
  if (closed && points.size() > 2) drawSegment(points.back(), points.front(), color);
}

bool Renderer::fillAllowed(double area) {
  // Only what lands in the window costs: a shape larger than the window fills it once.
  const double px = std::min(area * camera_.pixels_per_metre * camera_.pixels_per_metre,
                             static_cast<double>(camera_.width_px) * camera_.height_px);
  if (!(px <= fill_left_px_)) {
    ++skipped_fills_;
    return false;
  }
  fill_left_px_ -= px;
  return true;
}

void Renderer::fillConvex(std::span<const Vec2> vertices, const Color& color) {
  if (vertices.size() < 3) return;
  double area = 0.0;
  for (size_t i = 1; i + 1 < vertices.size(); ++i) area += 0.5 * cross(vertices[i] - vertices[0], vertices[i + 1] - vertices[0]);
  if (fillAllowed(std::abs(area)))
    for (size_t i = 1; i + 1 < vertices.size(); ++i) triangle(vertices[0], vertices[i], vertices[i + 1], color);
}

void Renderer::drawPolygon(std::span<const Vec2> vertices, const Color& fill, const Color& outline) {
  if (vertices.size() < 3) return;
  fillConvex(vertices, fill);
  drawPolyline(vertices, true, outline);
}

void Renderer::fillDisc(const Vec2& center, double radius, const Color& color) {
  if (!fillAllowed(std::numbers::pi * radius * radius)) return;
  const int n = circleSegments(radius);
  Vec2 prev = center + Vec2(radius, 0.0);
  for (int i = 1; i <= n; ++i) {
    const double t = 2.0 * std::numbers::pi * i / n;
    const Vec2 p = center + radius * Vec2(std::cos(t), std::sin(t));
    triangle(center, prev, p, color);
    prev = p;
  }
}

void Renderer::drawCircle(const Vec2& center, double radius, double angle, const Color& fill, const Color& outline) {
  fillDisc(center, radius, fill);
  drawCircleOutline(center, radius, outline);
  drawSegment(center, center + radius * Vec2(std::cos(angle), std::sin(angle)), outline);  // shows rotation
}

void Renderer::drawCircleOutline(const Vec2& center, double radius, const Color& color) {
  const int n = circleSegments(radius);
  Vec2 prev = center + Vec2(radius, 0.0);
  for (int i = 1; i <= n; ++i) {
    const double t = 2.0 * std::numbers::pi * i / n;
    const Vec2 p = center + radius * Vec2(std::cos(t), std::sin(t));
    drawSegment(prev, p, color);
    prev = p;
  }
}

void Renderer::drawPoint(const Vec2& p, float size_pixels, const Color& color) {
  const double h = camera_.metres(0.5 * size_pixels);
  const Vec2 a = p + Vec2(-h, -h), b = p + Vec2(h, -h), c = p + Vec2(h, h), d = p + Vec2(-h, h);
  triangle(a, b, c, color);
  triangle(a, c, d, color);
}

void Renderer::drawGrid() {
  // Spacing: the smallest power of ten that puts lines at least 40 px apart.
  const double spacing = std::pow(10.0, std::ceil(std::log10(camera_.metres(40.0))));
  const Vec2 lo = camera_.screenToWorld(Vec2(0, camera_.height_px)), hi = camera_.screenToWorld(Vec2(camera_.width_px, 0));
  if (!std::isfinite(spacing) || (hi.x() - lo.x()) / spacing > 1000 || (hi.y() - lo.y()) / spacing > 1000) return;
  for (double x = std::floor(lo.x() / spacing) * spacing; x <= hi.x(); x += spacing)
    drawSegment(Vec2(x, lo.y()), Vec2(x, hi.y()), Palette::grid);
  for (double y = std::floor(lo.y() / spacing) * spacing; y <= hi.y(); y += spacing)
    drawSegment(Vec2(lo.x(), y), Vec2(hi.x(), y), Palette::grid);
  if (lo.x() <= 0.0 && hi.x() >= 0.0) drawSegment(Vec2(0.0, lo.y()), Vec2(0.0, hi.y()), Palette::axes);
  if (lo.y() <= 0.0 && hi.y() >= 0.0) drawSegment(Vec2(lo.x(), 0.0), Vec2(hi.x(), 0.0), Palette::axes);
}

void Renderer::line(const Vec2& a, const Vec2& b, const Color& color) { drawSegment(a, b, color); }

void Renderer::circle(const Vec2& center, double radius, const Color& color) { drawCircleOutline(center, radius, color); }

void Renderer::text(const Vec2& position, const std::string& text, const Color& color) {
  texts_.push_back({position, text, color});
}

void Renderer::polygon(std::span<const Vec2> points, const Color& color, const std::optional<Color>& fill) {
  if (fill && points.size() <= kMaxFilledPolygonPoints) {
    try {  // a concave outline is filled piece by piece; one that crosses itself is not filled
      for (const auto& piece : decomposeConcave(points)) fillConvex(piece, *fill);
    } catch (const std::exception&) {
    }
  }
  drawPolyline(points, true, color);
}

void Renderer::capsule(const Vec2& a, const Vec2& b, double radius, const Color& color, const std::optional<Color>& fill) {
  drawCapsule(a, b, radius, fill.value_or(Color{0, 0, 0, 0}), color);
}

void Renderer::disc(const Vec2& center, double radius, const Color& color, const Color& fill) {
  fillDisc(center, radius, fill);
  drawCircleOutline(center, radius, color);
}

void Renderer::drawTexts(ImDrawList* list) {
  for (const Text& t : texts_) {
    const Vec2 p = camera_.worldToScreen(t.position);
    if (!isFinite(p) || std::abs(p.x()) > 1e6 || std::abs(p.y()) > 1e6) continue;
    list->AddText(ImVec2(static_cast<float>(p.x()), static_cast<float>(p.y())),
                  ImGui::ColorConvertFloat4ToU32(ImVec4(t.color.r, t.color.g, t.color.b, t.color.a)), t.text.c_str());
  }
}

}  // namespace rigidlab::sandbox
