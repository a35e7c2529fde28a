// SDL mouse events as a scene's OnMouse(world, event) receives them (lua::MouseEvent): the cursor
// in pixels and, through the camera, in world coordinates; the button; the modifier keys; wheel
// notches. Buttons other than left, right and middle (the side buttons) give nothing.
#pragma once

#include <optional>

#include <SDL.h>

#include "camera.h"
#include "rigidlab/lua/scene.h"

namespace rigidlab::sandbox {

// The scene's event for `e`, or nothing if it is not one a scene gets. `cursor`: where the cursor
// is (a wheel event carries no position); `mod`: the modifier keys held (SDL_GetModState()).
std::optional<lua::MouseEvent> sceneMouseEvent(const SDL_Event& e, const Camera& camera, const Vec2& cursor, SDL_Keymod mod);

// Wheel notches of an SDL wheel event, > 0 away from the user whatever the system's direction.
double wheelNotches(const SDL_MouseWheelEvent& wheel);

}  // namespace rigidlab::sandbox
