// SDL mouse events → lua::MouseEvent (mouse_event.h).
#include "mouse_event.h"

namespace rigidlab::sandbox {

namespace {

std::optional<lua::MouseEvent::Button> button(Uint8 b) {
  switch (b) {
    case SDL_BUTTON_LEFT: return lua::MouseEvent::Button::Left;
    case SDL_BUTTON_RIGHT: return lua::MouseEvent::Button::Right;
    case SDL_BUTTON_MIDDLE: return lua::MouseEvent::Button::Middle;
    default: return std::nullopt;
  }
}

}  // namespace

double wheelNotches(const SDL_MouseWheelEvent& wheel) {
  return wheel.preciseY * (wheel.direction == SDL_MOUSEWHEEL_FLIPPED ? -1.0 : 1.0);
}

std::optional<lua::MouseEvent> sceneMouseEvent(const SDL_Event& e, const Camera& camera, const Vec2& cursor, SDL_Keymod mod) {
  using Kind = lua::MouseEvent::Kind;
  lua::MouseEvent m;
  m.screen = cursor;
  switch (e.type) {
    case SDL_MOUSEBUTTONDOWN:
    case SDL_MOUSEBUTTONUP: {
      const auto b = button(e.button.button);
      if (!b) return std::nullopt;
      m.kind = e.type == SDL_MOUSEBUTTONDOWN ? Kind::Press : Kind::Release;
      m.button = *b;
      m.screen = Vec2(e.button.x, e.button.y);
      break;
    }
    case SDL_MOUSEMOTION:
      m.kind = Kind::Move;
      m.screen = Vec2(e.motion.x, e.motion.y);
      break;
    case SDL_MOUSEWHEEL:
      m.kind = Kind::Wheel;
      m.wheel = wheelNotches(e.wheel);
      break;
    default:
      return std::nullopt;
  }
  m.position = camera.screenToWorld(m.screen);
  m.shift = mod & KMOD_SHIFT;
  m.ctrl = mod & KMOD_CTRL;
  m.alt = mod & KMOD_ALT;
  return m;
}

}  // namespace rigidlab::sandbox
