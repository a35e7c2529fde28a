// The view's drawing (docs/design/thesis.md §11 "View"): implements the core's DebugDraw and the scenes'
// OverlayDraw with OpenGL 3.3. Every primitive becomes triangles in one vertex buffer, drawn in the
// order of the calls (later calls on top) with one draw call per frame. Lines are quads of a fixed
// width in pixels (core-profile GL has no wide lines), and sizes given in pixels are converted
// with the camera's scale.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "camera.h"
#include "rigidlab/debug_draw.h"
#include "rigidlab/lua/scene.h"

struct ImDrawList;

namespace rigidlab::sandbox {

struct Palette {
  static constexpr Color background{0.11f, 0.12f, 0.14f, 1.0f};
  static constexpr Color grid{0.16f, 0.17f, 0.20f, 1.0f};
  static constexpr Color axes{0.24f, 0.26f, 0.30f, 1.0f};
  static constexpr Color drag{0.3f, 0.95f, 0.45f, 1.0f};
  static constexpr Color preview{1.0f, 0.85f, 0.2f, 0.9f};
  static constexpr Color piece{1.0f, 0.85f, 0.2f, 0.35f};   // convex pieces of a polygon being drawn
  static constexpr Color refused{1.0f, 0.35f, 0.3f, 0.9f};  // an outline that crosses itself
};

class Renderer final : public DebugDraw, public lua::OverlayDraw {
 public:
  Renderer() = default;
  ~Renderer() override;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Compiles assets/shaders/world.{vert,frag}. False with `error` set if that fails.
  bool init(const std::filesystem::path& assets, std::string& error);

  // Starts a frame: clears the window and the batches.
  void begin(const Camera& camera);
  // A metre grid whose spacing adapts to the zoom (a power of ten, lines ≥ 40 px apart), and the axes.
  void drawGrid();
  // Sends the triangles to the GPU.
  void flush();
  // Overlay texts go through ImGui's font: call between ImGui::NewFrame and ImGui::Render.
  void drawTexts(ImDrawList* list);

  // DebugDraw
  void drawPolygon(std::span<const Vec2> vertices, const Color& fill, const Color& outline) override;
  void drawCircle(const Vec2& center, double radius, double angle, const Color& fill, const Color& outline) override;
  void drawSegment(const Vec2& a, const Vec2& b, const Color& color) override;
  void drawPoint(const Vec2& p, float size_pixels, const Color& color) override;

  // OverlayDraw (scene OnDraw hooks)
  void line(const Vec2& a, const Vec2& b, const Color& color) override;
  void circle(const Vec2& center, double radius, const Color& color) override;
  void text(const Vec2& position, const std::string& text, const Color& color) override;
  void polygon(std::span<const Vec2> points, const Color& color, const std::optional<Color>& fill) override;
  void capsule(const Vec2& a, const Vec2& b, double radius, const Color& color, const std::optional<Color>& fill) override;
  void disc(const Vec2& center, double radius, const Color& color, const Color& fill) override;
  Vec2 screenToWorld(const Vec2& px) const override;
  double metresPerPixel() const override { return 1.0 / camera_.pixels_per_metre; }
  // A scene's polygon of more points than this is drawn as its outline only (filling a concave one
  // splits it into convex pieces, which takes time cubic in the points at worst).
  static constexpr size_t kMaxFilledPolygonPoints = 64;

  // Outlines only (tool previews, overlay circles).
  void drawCircleOutline(const Vec2& center, double radius, const Color& color);
  void drawPolyline(std::span<const Vec2> points, bool closed, const Color& color);

  // The scene's HUD this frame: the pixels its draw.screen calls named (corners, centres, text
  // anchors), grown by kHudMargin (texts reach right of and below their anchor); none if it drew
  // nothing in screen space. The panels are docked clear of it.
  std::optional<ScreenRect> hud() const;
  static constexpr double kHudMargin = 12.0;

  size_t vertexCount() const { return last_vertex_count_; }  // of the last flush
  // Filled shapes of the last frame drawn as outlines only because the frame's fill budget was
  // spent (see kFillScreens).
  int skippedFills() const { return last_skipped_fills_; }
  float line_width_pixels = 1.5f;

  // The fills of one frame cover at most this many window areas (a shape larger than the window
  // counts once); the shapes past it are drawn as outlines. 3000 discs heaped on each other, each
  // as large as the window, made a frame take 4 s under a software renderer (Mesa llvmpipe, about
  // 850 M pixels blended); with this budget it takes 0.43 s, most of it their outlines. Ordinary
  // scenes fill a few window areas at most.
  static constexpr double kFillScreens = 16.0;

 private:
  struct Vertex {
    float x, y;
    float r, g, b, a;
  };
  void triangle(const Vec2& a, const Vec2& b, const Vec2& c, const Color& color);
  void fillConvex(std::span<const Vec2> vertices, const Color& color);  // within the fill budget
  void fillDisc(const Vec2& center, double radius, const Color& color);  // within the fill budget
  int circleSegments(double radius) const;
  // Takes `area` [m²] from the frame's fill budget; false (and counted) once it is spent.
  bool fillAllowed(double area);

  unsigned program_ = 0, vao_ = 0, vbo_ = 0;
  int scale_location_ = -1;
  Camera camera_;
  std::vector<Vertex> vertices_;
  size_t last_vertex_count_ = 0;
  double fill_left_px_ = 0.0;  // of this frame's budget
  int skipped_fills_ = 0, last_skipped_fills_ = 0;
  struct Text {
    Vec2 position;
    std::string text;
    Color color;
  };
  std::vector<Text> texts_;
  mutable std::optional<ScreenRect> hud_;  // screenToWorld's arguments this frame
};

}  // namespace rigidlab::sandbox
