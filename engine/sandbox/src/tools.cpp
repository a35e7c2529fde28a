// Mouse tools and keyboard shortcuts (tools.h).
#include "tools.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "renderer.h"
#include "rigidlab/forces.h"

namespace rigidlab::sandbox {

namespace {

using Gesture = ToolState::Gesture;

constexpr double kClickPixels = 4.0;       // a press and release closer than this is a click
constexpr double kCloseLoopPixels = 10.0;  // clicking this close to the first point closes a polygon
constexpr double kMinSize = 0.05;          // [m] smallest body a drag makes
constexpr double kPanKeyFraction = 0.1;    // arrow keys pan by this fraction of the view height
constexpr double kZoomStep = 1.15;         // per wheel notch or +/- key
constexpr double kRotateKeyRadians = std::numbers::pi / 12.0;  // Q/E: 15°

constexpr Shortcut kShortcuts[] = {
    {"F1", "show or hide this help"},
    {"Space", "pause / resume"},
    {"N", "single step (pauses first)"},
    {"R", "reset: rebuild the scene from its file"},
    {"F5", "reload the scene now"},
    {"Ctrl+Z / Ctrl+Y (Ctrl+Shift+Z)", "undo / redo an edit"},
    {"Ctrl+S", "save the world as a new scene file"},
    {"1 2 3 4", "tools: select/drag, circle, box, polygon"},
    {"Left drag (select tool)", "running: pull a body with a capped spring force; paused: move it"},
    {"Shift + left drag (paused)", "rotate a body about its centre of mass"},
    {"Q / E (paused)", "rotate the selected body by +15° / -15°"},
    {"Left click / drag (circle, box)", "add a body of the panel's size / of the dragged size"},
    {"Left clicks (polygon)", "add points; click the first point or press Enter to close, Backspace to undo a point"},
    {"Delete / Backspace", "delete the selected body"},
    {"T", "toggle the selected body (or the one under the cursor) static / dynamic"},
    {"Esc", "cancel the gesture, drop the polygon, deselect"},
    {"Right or middle drag, arrow keys", "pan the camera"},
    {"Wheel, + / -", "zoom about the cursor / the centre"},
    {"F", "fit the scene in the window"},
    {"F2 F3 F4", "draw contact points / normals / impulses"},
    {"F6 F7 F8", "draw bounding boxes / centres of mass / velocities"},
    {"F9", "loop: fixed step / variable step"},
    {"Tab", "show or hide the panels"},
    {"Ctrl+O", "scene browser (scripts/scenes/)"},
    {"other keys", "passed to the scene's OnKey(world, key)"},
};

std::string keyName(SDL_Keycode key) {
  std::string name = SDL_GetKeyName(key);
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name;
}

Vec2 cursorWorld(const Session& s) { return s.camera.screenToWorld(s.tools.mouse_px); }

BodyDef newBodyDef(const ToolState& t) {
  BodyDef def;
  def.type = t.make_static ? BodyType::Static : BodyType::Dynamic;
  def.density = t.density;
  def.restitution = t.restitution;
  def.friction = t.friction;
  return def;
}

void pressSelect(Session& s, bool shift) {
  ToolState& t = s.tools;
  World& w = s.world();
  const Vec2 p = cursorWorld(s);
  const auto hit = w.bodyAt(p);
  if (!hit) {
    s.selected = {};
    return;
  }
  s.selected = *hit;
  const Body& b = w.body(*hit);
  t.body = *hit;
  if (s.paused) {
    t.before = captureProps(w, *hit);
    if (shift) {
      t.gesture = Gesture::Rotate;
      t.start_angle = b.angle;
      const Vec2 r = p - b.center;
      t.start_cursor_angle = std::atan2(r.y(), r.x());
    } else {
      t.gesture = Gesture::Move;
      t.grab_offset = b.xf.p - p;
    }
  } else if (!b.isStatic()) {
    // Running: pull with a damped spring whose force is capped (forces.h MouseForce).
    t.gesture = Gesture::Drag;
    t.drag_force = w.addForce(std::make_unique<MouseForce>(MouseForce::forBody(b, p)), *hit);
  } else {
    t.body = {};
  }
}

void moveGesture(Session& s) {
  ToolState& t = s.tools;
  World& w = s.world();
  if (!w.isValid(t.body)) {
    t.gesture = Gesture::None;
    return;
  }
  const Body& b = w.body(t.body);
  const Vec2 p = cursorWorld(s);
  if (t.gesture == Gesture::Move) {
    w.setTransform(t.body, p + t.grab_offset, b.angle);
  } else {
    const Vec2 r = p - b.center;
    if (r.norm() < s.camera.metres(2.0)) return;  // too close to the pivot for a stable angle
    const double angle = t.start_angle + std::remainder(std::atan2(r.y(), r.x()) - t.start_cursor_angle, 2 * std::numbers::pi);
    const Vec2 center = b.center;
    w.setTransform(t.body, center - Rot::fromAngle(angle).apply(b.local_center), angle);  // turns about the centre
  }
  s.history.capture(w);
}

void releaseCreate(Session& s) {
  ToolState& t = s.tools;
  const Vec2 p = cursorWorld(s);
  const bool click = (t.mouse_px - t.press_px).norm() < kClickPixels;
  BodyDef def = newBodyDef(t);
  try {
    if (t.tool == Tool::Circle) {
      const double r = click ? t.circle_radius : std::max((p - t.press_world).norm(), kMinSize);
      def.shape = makeCircle(r);
      def.position = t.press_world;
      addBody(s, def, "add circle");
    } else {
      Vec2 size(t.box_width, t.box_height), center = t.press_world;
      if (!click) {
        size = (p - t.press_world).cwiseAbs().cwiseMax(Vec2(kMinSize, kMinSize));
        center = 0.5 * (p + t.press_world);
      }
      def.shape = makeBox(size.x(), size.y());
      def.position = center;
      addBody(s, def, "add box");
    }
  } catch (const std::exception& e) {
    s.setStatus(std::string("cannot add the body: ") + e.what());
  }
}

void pressPolygon(Session& s) {
  ToolState& t = s.tools;
  const Vec2 p = cursorWorld(s);
  if (t.polygon.size() >= 3 && (s.camera.worldToScreen(t.polygon.front()) - t.mouse_px).norm() < kCloseLoopPixels) {
    finishPolygon(s);
    return;
  }
  t.polygon.push_back(p);
}

bool handleKey(Session& s, const SDL_KeyboardEvent& key) {
  const SDL_Keycode k = key.keysym.sym;
  const bool ctrl = key.keysym.mod & KMOD_CTRL, shift = key.keysym.mod & KMOD_SHIFT, alt = key.keysym.mod & KMOD_ALT;
  ToolState& t = s.tools;
  if (ctrl) {
    if (k == SDLK_z && !shift) undo(s);
    else if (k == SDLK_y || (k == SDLK_z && shift)) redo(s);
    else if (k == SDLK_o) s.show_browser = !s.show_browser;
    else if (k == SDLK_s) {
      s.save.open = true;
      s.save.path = suggestSavePath(s).string();
      s.save.message.clear();
      s.save.confirm_overwrite = false;
    } else return false;
    return true;
  }
  if (alt) return false;
  const Vec2 middle(0.5 * s.camera.width_px, 0.5 * s.camera.height_px);
  const double pan = kPanKeyFraction * s.camera.height_px;
  switch (k) {
    case SDLK_F1: s.show_help = !s.show_help; break;
    case SDLK_SPACE: setPaused(s, !s.paused); break;
    case SDLK_n: stepOnce(s); break;
    case SDLK_r:
    case SDLK_F5:
      if (s.file.empty()) s.setStatus("no scene file: open one with Ctrl+O");
      else requestLoad(s, s.file, k == SDLK_r ? LoadPurpose::Reset : LoadPurpose::Reload);
      break;
    case SDLK_1: selectTool(s, Tool::Select); break;
    case SDLK_2: selectTool(s, Tool::Circle); break;
    case SDLK_3: selectTool(s, Tool::Box); break;
    case SDLK_4: selectTool(s, Tool::Polygon); break;
    case SDLK_q: rotateSelected(s, kRotateKeyRadians); break;
    case SDLK_e: rotateSelected(s, -kRotateKeyRadians); break;
    case SDLK_RETURN:
    case SDLK_KP_ENTER: finishPolygon(s); break;
    case SDLK_BACKSPACE:
      if (t.tool == Tool::Polygon && !t.polygon.empty()) t.polygon.pop_back();
      else deleteBody(s, s.selected);
      break;
    case SDLK_DELETE: deleteBody(s, s.selected); break;
    case SDLK_t: {
      BodyId target = s.selected;
      if (!s.world().isValid(target)) target = s.world().bodyAt(cursorWorld(s)).value_or(BodyId{});
      toggleStatic(s, target);
      break;
    }
    case SDLK_ESCAPE:
      if (s.show_help) s.show_help = false;
      else if (t.gesture != Gesture::None) cancelGesture(s);
      else if (!t.polygon.empty()) t.polygon.clear();
      else s.selected = {};
      break;
    case SDLK_LEFT: s.camera.pan(Vec2(pan, 0)); break;
    case SDLK_RIGHT: s.camera.pan(Vec2(-pan, 0)); break;
    case SDLK_UP: s.camera.pan(Vec2(0, pan)); break;
    case SDLK_DOWN: s.camera.pan(Vec2(0, -pan)); break;
    case SDLK_PLUS:
    case SDLK_EQUALS:
    case SDLK_KP_PLUS: s.camera.zoomAbout(middle, kZoomStep); break;
    case SDLK_MINUS:
    case SDLK_KP_MINUS: s.camera.zoomAbout(middle, 1.0 / kZoomStep); break;
    case SDLK_f: fitCamera(s); break;
    case SDLK_F2: s.draw.contacts = !s.draw.contacts; break;
    case SDLK_F3: s.draw.normals = !s.draw.normals; break;
    case SDLK_F4: s.draw.impulses = !s.draw.impulses; break;
    case SDLK_F6: s.draw.aabbs = !s.draw.aabbs; break;
    case SDLK_F7: s.draw.centers = !s.draw.centers; break;
    case SDLK_F8: s.draw.velocities = !s.draw.velocities; break;
    case SDLK_F9:
      s.loop.mode = s.loop.mode == LoopMode::Fixed ? LoopMode::Variable : LoopMode::Fixed;
      s.clock.reset();
      s.setStatus(s.loop.mode == LoopMode::Fixed ? "fixed step" : "variable step");
      break;
    case SDLK_TAB: s.show_panels = !s.show_panels; break;
    default: return false;
  }
  return true;
}

void forwardKey(Session& s, SDL_Keycode key) {
  if (!s.scene->hasOnKey()) return;
  try {
    s.scene->onKey(keyName(key));
    s.history.capture(s.world());
  } catch (const std::exception& e) {
    s.run_error = e.what();
    setPaused(s, true);
  }
}

}  // namespace

std::span<const Shortcut> shortcuts() { return kShortcuts; }

const char* toolName(Tool tool) {
  switch (tool) {
    case Tool::Select: return "select / drag";
    case Tool::Circle: return "circle";
    case Tool::Box: return "box";
    case Tool::Polygon: return "polygon";
  }
  return "";
}

void selectTool(Session& s, Tool tool) {
  cancelGesture(s);
  s.tools.polygon.clear();
  s.tools.tool = tool;
}

void rotateSelected(Session& s, double radians) {
  World& w = s.world();
  if (!s.paused || !w.isValid(s.selected)) {
    if (!s.paused && w.isValid(s.selected)) s.setStatus("pause (Space) to rotate bodies");
    return;
  }
  const BodyProps before = captureProps(w, s.selected);
  const Body& b = w.body(s.selected);
  const double angle = b.angle + radians;
  const Vec2 center = b.center;
  w.setTransform(s.selected, center - Rot::fromAngle(angle).apply(b.local_center), angle);
  s.undo.recordModify(s.selected, before, captureProps(w, s.selected), "rotate");
  s.history.capture(w);
}

void finishPolygon(Session& s) {
  ToolState& t = s.tools;
  if (t.polygon.size() < 3) return;
  // The body origin at the mean of the points; the vertices relative to it.
  Vec2 mean = Vec2::Zero();
  for (const Vec2& p : t.polygon) mean += p;
  mean /= static_cast<double>(t.polygon.size());
  std::vector<Vec2> local;
  for (const Vec2& p : t.polygon) local.push_back(p - mean);
  BodyDef def = newBodyDef(t);
  try {
    def.shape = makePolygon(local);
  } catch (const std::exception& e) {
    s.setStatus(std::string("cannot make that polygon: ") + e.what(), 5.0);
    return;  // keep the points: Backspace can fix the outline
  }
  def.position = mean;
  if (addBody(s, def, "add polygon").isNull()) return;
  t.polygon.clear();
}

void handleEvent(Session& s, const SDL_Event& e, InputCapture capture) {
  ToolState& t = s.tools;
  switch (e.type) {
    case SDL_KEYDOWN:
      if (capture.keyboard) return;
      if (!handleKey(s, e.key) && !(e.key.keysym.mod & (KMOD_CTRL | KMOD_ALT | KMOD_GUI))) forwardKey(s, e.key.keysym.sym);
      return;
    case SDL_MOUSEMOTION: {
      const Vec2 previous = t.mouse_px;
      t.mouse_px = Vec2(e.motion.x, e.motion.y);
      if (t.gesture == Gesture::Pan) s.camera.pan(t.mouse_px - previous);
      else if (t.gesture == Gesture::Move || t.gesture == Gesture::Rotate) moveGesture(s);
      return;
    }
    case SDL_MOUSEWHEEL: {
      if (capture.mouse) return;
      const double notches = e.wheel.preciseY * (e.wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -1.0 : 1.0);
      s.camera.zoomAbout(t.mouse_px, std::pow(kZoomStep, notches));
      return;
    }
    case SDL_MOUSEBUTTONDOWN: {
      t.mouse_px = Vec2(e.button.x, e.button.y);
      if (capture.mouse || t.gesture != Gesture::None) return;
      t.press_px = t.mouse_px;
      t.press_world = cursorWorld(s);
      if (e.button.button == SDL_BUTTON_RIGHT || e.button.button == SDL_BUTTON_MIDDLE) {
        t.gesture = Gesture::Pan;
        return;
      }
      if (e.button.button != SDL_BUTTON_LEFT) return;
      switch (t.tool) {
        case Tool::Select: pressSelect(s, SDL_GetModState() & KMOD_SHIFT); break;
        case Tool::Circle:
        case Tool::Box: t.gesture = Gesture::Create; break;
        case Tool::Polygon: pressPolygon(s); break;
      }
      return;
    }
    case SDL_MOUSEBUTTONUP: {
      t.mouse_px = Vec2(e.button.x, e.button.y);
      const bool left = e.button.button == SDL_BUTTON_LEFT;
      if (t.gesture == Gesture::Pan && !left) {
        t.gesture = Gesture::None;
      } else if (left && t.gesture == Gesture::Create) {
        t.gesture = Gesture::None;
        releaseCreate(s);
      } else if (left && t.gesture != Gesture::None && t.gesture != Gesture::Pan) {
        cancelGesture(s);  // ends a drag, commits a move or turn
      }
      return;
    }
    default:
      return;
  }
}

void updateTools(Session& s) {
  ToolState& t = s.tools;
  if (t.gesture != Gesture::Drag) return;
  World& w = s.world();
  if (!w.isValid(t.drag_force)) {  // the body was removed (by a script, an undo, a reload)
    t.gesture = Gesture::None;
    t.drag_force = {};
    return;
  }
  if (auto* drag = dynamic_cast<MouseForce*>(&w.force(t.drag_force))) drag->setTarget(cursorWorld(s));
}

void drawToolOverlay(const Session& s, Renderer& r) {
  const ToolState& t = s.tools;
  const World& w = s.world();
  const Vec2 p = cursorWorld(s);
  if (t.gesture == Gesture::Drag && w.isValid(t.drag_force)) {
    // The pull as a spring from the grabbed point to the cursor, over the core's straight line.
    if (const auto* drag = dynamic_cast<const MouseForce*>(&w.force(t.drag_force))) {
      const Vec2 grabbed = w.body(drag->def().body).xf.apply(drag->def().local_point);
      r.drawSpring(grabbed, drag->def().target, s.camera.metres(10.0), Palette::drag);
    }
  }
  if (t.gesture == Gesture::Create) {
    const bool click = (t.mouse_px - t.press_px).norm() < kClickPixels;
    if (t.tool == Tool::Circle) {
      r.drawCircleOutline(t.press_world, click ? t.circle_radius : (p - t.press_world).norm(), Palette::preview);
    } else if (!click) {
      const Vec2 a = t.press_world, c = p;
      const Vec2 box[4] = {a, Vec2(c.x(), a.y()), c, Vec2(a.x(), c.y())};
      r.drawPolyline(box, true, Palette::preview);
    }
  }
  if (t.tool == Tool::Polygon && !t.polygon.empty()) {
    std::vector<Vec2> points = t.polygon;
    points.push_back(p);
    r.drawPolyline(points, false, Palette::preview);
    for (const Vec2& q : t.polygon) r.drawPoint(q, 6.0f, Palette::preview);
  }
}

}  // namespace rigidlab::sandbox
