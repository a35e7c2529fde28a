// The camera following a body (docs/sandbox.md "Camera"): `scene.camera = {follow = body}`, the C
// key or the Body panel's Follow button. Each frame the body's centre of mass, where it is drawn
// (interpolated between steps), is put at the middle of the part of the window the panels leave
// free; the scale stays, so the wheel still zooms. Panning, Fit or the body's removal stop it.
#pragma once

#include "session.h"

namespace rigidlab::sandbox {

// Follows `body` (null: stops following), with a status line saying so.
void followBody(Session& s, BodyId body);
// After the frame's steps, before drawing: moves the camera to the followed body.
void updateFollow(Session& s);
// Where a live `body`'s centre of mass is drawn this frame (interpolated between the last two
// steps while running).
Vec2 drawnCenter(Session& s, BodyId body);

}  // namespace rigidlab::sandbox
