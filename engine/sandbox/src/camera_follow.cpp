// Keeping a body in view (camera_follow.h).
#include "camera_follow.h"

#include "panel_layout.h"

namespace rigidlab::sandbox {

void followBody(Session& s, BodyId body) {
  const World& w = s.world();
  if (body == s.follow) return;
  if (!s.follow.isNull() && body.isNull()) s.setStatus("camera: no longer following " + (w.isValid(s.follow) ? describe(w, s.follow) : "the body"));
  s.follow = w.isValid(body) ? body : BodyId{};
  if (!s.follow.isNull()) s.setStatus("camera: following " + describe(w, s.follow) + " (C or a pan stops)");
}

void updateFollow(Session& s) {
  const World& w = s.world();
  if (s.follow.isNull()) return;
  if (!w.isValid(s.follow)) {  // removed (by the scene, an edit, an undo)
    s.follow = {};
    return;
  }
  s.camera.placeAt(drawnCenter(s, s.follow), freeViewArea(s.camera.width_px, s.camera.height_px, s.show_panels).middle());
}

Vec2 drawnCenter(Session& s, BodyId body) {
  const Body& b = s.world().body(body);
  if (s.paused) return b.center;
  const auto poses = s.history.interpolate(s.world(), s.alpha);
  return body.index < poses.size() ? poses[body.index].apply(b.local_center) : b.center;
}

}  // namespace rigidlab::sandbox
