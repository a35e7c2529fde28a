// Mouse tools and keyboard shortcuts (tools.h).
#include "tools.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>

#include "camera_follow.h"
#include "joint_tool.h"
#include "mouse_drag.h"
#include "mouse_event.h"
#include "picking.h"
#include "renderer.h"
#include "rigidlab/error.h"

namespace rigidlab::sandbox {

namespace {

using Gesture = ToolState::Gesture;

constexpr double kClickPixels = 4.0;       // a press and release closer than this is a click
constexpr double kCloseLoopPixels = 10.0;  // clicking this close to the first point closes a polygon
constexpr double kMinSize = 0.05;          // [m] smallest body a drag makes
constexpr double kPanKeyFraction = 0.1;    // arrow keys pan by this fraction of the view height
constexpr double kZoomStep = 1.15;         // per wheel notch or +/- key
constexpr double kRotateKeyRadians = std::numbers::pi / 12.0;  // Q/E: 15°
constexpr double kPickPixels = 6.0;        // joints' anchors and segments are picked this close
// The polygon tool previews the convex pieces of the outline being drawn up to this many points
// (decomposeConcave is cubic in the worst case; past it the pieces show once it is closed).
constexpr size_t kPreviewPoints = 64;

constexpr Shortcut kShortcuts[] = {
    {"F1", "show or hide this help"},
    {"Space", "pause / resume"},
    {"N", "single step (pauses first); rewound: the next kept state"},
    {"Shift+N", "step backwards through the kept states (rewind)"},
    {"R", "reset: rebuild the scene from its file"},
    {"F5", "reload the scene now"},
    {"Ctrl+Z / Ctrl+Y (Ctrl+Shift+Z)", "undo / redo an edit"},
    {"Ctrl+S", "save the world as a new scene file"},
    {"1 2 3 4 5 6", "tools: select/drag, circle, box, polygon, capsule, joint"},
    {"Left click (select tool)", "select a body, or a joint by its anchor"},
    {"Left drag (select tool)", "running: pull a body (a motor joint, at most 100 times its weight); paused: move it"},
    {"Shift + left drag (paused)", "rotate a body about its centre of mass"},
    {"Q / E (paused)", "rotate the selected body by +15° / -15°"},
    {"Left click / drag (circle, box, capsule)", "add a body of the panel's size / of the dragged size (capsule: from end to end)"},
    {"Left clicks (polygon)", "add points; click the first point or press Enter to close, Backspace to undo a point; a concave outline becomes a body of convex pieces, a crossing one is refused"},
    {"Left clicks (joint)", "a body, then where the joint goes: on a second body joins the two, on empty space pins to the world (distance: the first click is the first anchor); the kind in the panel"},
    {"Delete / Backspace", "delete the selected joint, or body (with its joints)"},
    {"T", "toggle the selected body (or the one under the cursor) static / dynamic"},
    {"Esc", "cancel the gesture, drop the polygon or the joint's first click, deselect"},
    {"Right or middle drag, arrow keys", "pan the camera"},
    {"Wheel, + / -", "zoom about the cursor / the centre"},
    {"F", "fit the scene in the window (stops following)"},
    {"C", "camera: follow the selected body, or stop following (a pan stops it too)"},
    {"F2 F3 F4", "draw contact points / normals / impulses"},
    {"F6 F7 F8", "draw bounding boxes / centres of mass / velocities"},
    {"F10", "draw joints"},
    {"F9", "loop: fixed step / variable step"},
    {"Tab", "show or hide the panels"},
    {"Ctrl+O", "scene browser (scripts/scenes/)"},
    {"other keys", "passed to the scene's OnKey(world, key); a scene may take bound keys too (scene.keys)"},
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
  const double tolerance = s.camera.metres(kPickPixels);
  if (const auto joint = pickJoint(w, p, tolerance)) {  // anchors are small: they come first
    select(s, {}, *joint);
    return;
  }
  const auto hit = pickBody(w, p, tolerance);
  if (!hit) {
    select(s, {});
    return;
  }
  select(s, *hit);
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
  } else if (b.isDynamic()) {
    try {
      t.drag_joint = startDrag(w, *hit, p);
      t.gesture = Gesture::Drag;
    } catch (const InputError& e) {
      s.setStatus(std::string("cannot pull it: ") + e.what());
      t.body = {};
    }
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
    } else if (t.tool == Tool::Capsule) {
      // A click: a level capsule of the panel's length; a drag: from where it started to the cursor.
      Vec2 a = t.press_world - Vec2(0.5 * t.capsule_length, 0.0), b = t.press_world + Vec2(0.5 * t.capsule_length, 0.0);
      if (!click) {
        a = t.press_world;
        b = p;
      }
      const Vec2 half = 0.5 * (b - a);
      def.shape = makeCapsule(-half, half, t.capsule_radius);
      def.position = 0.5 * (a + b);
      addBody(s, def, "add capsule");
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

// A pan by the user: the view is theirs, so the camera stops following a body.
void panCamera(Session& s, const Vec2& delta_px) {
  if (delta_px.isZero()) return;
  followBody(s, {});
  s.camera.pan(delta_px);
}

void deleteSelected(Session& s) {
  if (s.world().isValid(s.selected_joint)) deleteJoint(s, s.selected_joint);
  else deleteBody(s, s.selected);
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
    case SDLK_n:
      if (shift) stepBack(s);  // rewind.cpp
      else stepOnce(s);
      break;
    case SDLK_r:
    case SDLK_F5:
      if (s.file.empty()) s.setStatus("no scene file: open one with Ctrl+O");
      else requestLoad(s, s.file, k == SDLK_r ? LoadPurpose::Reset : LoadPurpose::Reload);
      break;
    case SDLK_1: selectTool(s, Tool::Select); break;
    case SDLK_2: selectTool(s, Tool::Circle); break;
    case SDLK_3: selectTool(s, Tool::Box); break;
    case SDLK_4: selectTool(s, Tool::Polygon); break;
    case SDLK_5: selectTool(s, Tool::Capsule); break;
    case SDLK_6: selectTool(s, Tool::Joint); break;
    case SDLK_q: rotateSelected(s, kRotateKeyRadians); break;
    case SDLK_e: rotateSelected(s, -kRotateKeyRadians); break;
    case SDLK_RETURN:
    case SDLK_KP_ENTER: finishPolygon(s); break;
    case SDLK_BACKSPACE:
      if (t.tool == Tool::Polygon && !t.polygon.empty()) t.polygon.pop_back();
      else deleteSelected(s);
      break;
    case SDLK_DELETE: deleteSelected(s); break;
    case SDLK_t: {
      BodyId target = s.selected;
      if (!s.world().isValid(target)) target = pickBody(s.world(), cursorWorld(s), s.camera.metres(kPickPixels)).value_or(BodyId{});
      toggleStatic(s, target);
      break;
    }
    case SDLK_ESCAPE:
      if (s.show_help) s.show_help = false;
      else if (t.gesture != Gesture::None) cancelGesture(s);
      else if (!t.polygon.empty()) t.polygon.clear();
      else if (!t.joint_body.isNull()) t.joint_body = {};
      else select(s, {});
      break;
    case SDLK_LEFT: panCamera(s, Vec2(pan, 0)); break;
    case SDLK_RIGHT: panCamera(s, Vec2(-pan, 0)); break;
    case SDLK_UP: panCamera(s, Vec2(0, pan)); break;
    case SDLK_DOWN: panCamera(s, Vec2(0, -pan)); break;
    case SDLK_c:
      if (!s.follow.isNull()) followBody(s, {});
      else if (s.world().isValid(s.selected)) followBody(s, s.selected);
      else s.setStatus("select a body to follow (C)");
      break;
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
    case SDLK_F10: s.draw.joints = !s.draw.joints; break;
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
  runSceneHook(s, [&] {
    s.scene->onKey(keyName(key));
    return true;
  });
}

// A key the scene took from the sandbox's bindings (scene.keys): plain, without Ctrl or Alt.
bool claimedByScene(const Session& s, const SDL_KeyboardEvent& key) {
  if (key.keysym.mod & (KMOD_CTRL | KMOD_ALT | KMOD_GUI)) return false;
  const auto& keys = s.scene->settings().keys;
  return std::find(keys.begin(), keys.end(), keyName(key.keysym.sym)) != keys.end();
}

// Offers a mouse event to the scene's OnMouse; true if the scene consumed it. Not while a script
// error is shown (until Space resumes or the scene reloads): a failing OnMouse would otherwise
// fail again at every move of the cursor.
bool offerToScene(Session& s, const SDL_Event& e) {
  if (!s.scene->hasOnMouse() || !s.run_error.empty()) return false;
  const auto event = sceneMouseEvent(e, s.camera, s.tools.mouse_px, SDL_GetModState());
  return event && runSceneHook(s, [&] { return s.scene->onMouse(*event); });
}

}  // namespace

std::span<const Shortcut> shortcuts() { return kShortcuts; }

const char* toolName(Tool tool) {
  switch (tool) {
    case Tool::Select: return "select / drag";
    case Tool::Circle: return "circle";
    case Tool::Box: return "box";
    case Tool::Polygon: return "polygon";
    case Tool::Capsule: return "capsule";
    case Tool::Joint: return "joint";
  }
  return "";
}

void selectTool(Session& s, Tool tool) {
  cancelGesture(s);
  s.tools.polygon.clear();
  s.tools.joint_body = {};
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
  // A concave outline is the body the user drew only as a compound of convex pieces, never as
  // its hull: split it, and refuse an outline that crosses itself.
  std::vector<std::vector<Vec2>> pieces;
  try {
    pieces = decomposeConcave(local);
  } catch (const std::exception& e) {
    s.setStatus(std::string("cannot make that polygon: ") + e.what(), 5.0);
    return;  // keep the points: Backspace can fix the outline
  }
  BodyDef def = newBodyDef(t);
  def.position = mean;
  std::vector<ShapeDef> more;
  try {
    def.shape = makePolygon(pieces[0]);
    for (size_t i = 1; i < pieces.size(); ++i) {
      ShapeDef piece;
      piece.shape = makePolygon(pieces[i]);
      piece.density = def.density;
      piece.material = {def.restitution, def.friction, def.friction};
      more.push_back(piece);
    }
  } catch (const std::exception& e) {
    s.setStatus(std::string("cannot make that polygon: ") + e.what(), 5.0);
    return;
  }
  const std::string label = pieces.size() == 1 ? "add polygon" : "add concave polygon (" + std::to_string(pieces.size()) + " convex pieces)";
  if (addCompound(s, def, more, label).isNull()) return;
  if (pieces.size() > 1) s.setStatus(label);
  t.polygon.clear();
}

void handleEvent(Session& s, const SDL_Event& e, InputCapture capture) {
  ToolState& t = s.tools;
  switch (e.type) {
    case SDL_KEYDOWN:
      if (capture.keyboard) return;
      if (claimedByScene(s, e.key)) {
        forwardKey(s, e.key.keysym.sym);
        return;
      }
      if (!handleKey(s, e.key) && !(e.key.keysym.mod & (KMOD_CTRL | KMOD_ALT | KMOD_GUI))) forwardKey(s, e.key.keysym.sym);
      return;
    case SDL_MOUSEMOTION: {
      const Vec2 previous = t.mouse_px;
      t.mouse_px = Vec2(e.motion.x, e.motion.y);
      if (!capture.mouse && offerToScene(s, e)) return;
      if (t.gesture == Gesture::Pan) panCamera(s, t.mouse_px - previous);
      else if (t.gesture == Gesture::Move || t.gesture == Gesture::Rotate) moveGesture(s);
      return;
    }
    case SDL_MOUSEWHEEL: {
      if (capture.mouse || offerToScene(s, e)) return;
      s.camera.zoomAbout(t.mouse_px, std::pow(kZoomStep, wheelNotches(e.wheel)));
      return;
    }
    case SDL_MOUSEBUTTONDOWN: {
      t.mouse_px = Vec2(e.button.x, e.button.y);
      if (capture.mouse || offerToScene(s, e) || t.gesture != Gesture::None) return;
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
        case Tool::Box:
        case Tool::Capsule: t.gesture = Gesture::Create; break;
        case Tool::Polygon: pressPolygon(s); break;
        case Tool::Joint: pressJointTool(s, cursorWorld(s)); break;
      }
      return;
    }
    case SDL_MOUSEBUTTONUP: {
      t.mouse_px = Vec2(e.button.x, e.button.y);
      const bool left = e.button.button == SDL_BUTTON_LEFT;
      // A release the scene consumed still ends a gesture its press started (nothing is left
      // stuck to the cursor), but makes no body.
      const bool consumed = !capture.mouse && offerToScene(s, e);
      if (t.gesture == Gesture::Pan && !left) {
        t.gesture = Gesture::None;
      } else if (left && t.gesture == Gesture::Create) {
        t.gesture = Gesture::None;
        if (!consumed) releaseCreate(s);
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
  if (!w.isValid(t.drag_joint)) {  // the body was removed (by a script, an undo, a reload)
    t.gesture = Gesture::None;
    t.drag_joint = {};
    return;
  }
  moveDrag(w, t.drag_joint, cursorWorld(s));
}

void drawToolOverlay(const Session& s, Renderer& r) {
  const ToolState& t = s.tools;
  const World& w = s.world();
  const Vec2 p = cursorWorld(s);
  if (t.gesture == Gesture::Drag && w.isValid(t.drag_joint)) {
    // The pull as a line from the grabbed point on the body to the cursor, both ends marked (as
    // Box2D's samples draw their mouse joint).
    const DragLine line = dragLine(w, t.drag_joint);
    r.drawSegment(line.grabbed, line.target, Palette::drag);
    r.drawPoint(line.grabbed, 7.0f, Palette::drag);
    r.drawPoint(line.target, 7.0f, Palette::drag);
  }
  if (w.isValid(s.selected_joint)) {  // rings round the selected joint's anchors
    const JointState js = w.jointState(s.selected_joint);
    for (const Vec2& q : {js.world_anchor_a, js.world_anchor_b}) r.drawCircleOutline(q, s.camera.metres(9.0), Palette::preview);
  }
  if (t.gesture == Gesture::Create) {
    const bool click = (t.mouse_px - t.press_px).norm() < kClickPixels;
    const Color none{0, 0, 0, 0};
    if (t.tool == Tool::Circle) {
      r.drawCircleOutline(t.press_world, click ? t.circle_radius : (p - t.press_world).norm(), Palette::preview);
    } else if (t.tool == Tool::Capsule) {
      const Vec2 half(0.5 * t.capsule_length, 0.0);
      if (click) r.drawCapsule(t.press_world - half, t.press_world + half, t.capsule_radius, none, Palette::preview);
      else r.drawCapsule(t.press_world, p, t.capsule_radius, none, Palette::preview);
    } else if (!click) {
      const Vec2 a = t.press_world, c = p;
      const Vec2 box[4] = {a, Vec2(c.x(), a.y()), c, Vec2(a.x(), c.y())};
      r.drawPolyline(box, true, Palette::preview);
    }
  }
  if (t.tool == Tool::Polygon && !t.polygon.empty()) {
    std::vector<Vec2> points = t.polygon;
    points.push_back(p);
    // The convex pieces the outline would be made of, or red if it crosses itself.
    bool crossing = false;
    if (points.size() >= 3 && points.size() <= kPreviewPoints) {
      try {
        for (const auto& piece : decomposeConcave(points)) r.drawPolyline(piece, true, Palette::piece);
      } catch (const std::exception&) {
        crossing = true;
      }
    }
    r.drawPolyline(points, false, crossing ? Palette::refused : Palette::preview);
    for (const Vec2& q : t.polygon) r.drawPoint(q, 6.0f, Palette::preview);
  }
  if (t.tool == Tool::Joint) drawJointToolOverlay(s, r, p);
}

}  // namespace rigidlab::sandbox
