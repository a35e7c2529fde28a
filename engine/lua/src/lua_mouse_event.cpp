// The event table OnMouse(world, event) receives (Scene::onMouse):
//   kind      "press", "release", "move" or "wheel"
//   button    "left", "right" or "middle" for a press or release; nil for a move or a wheel turn
//             (other buttons are not passed to the scene)
//   position  the cursor in world coordinates, a vec2 [m]
//   screen    the cursor in pixels from the window's top-left corner, y down, a vec2
//   shift, ctrl, alt   the modifier keys held, booleans
//   wheel     for "wheel" only: notches turned, > 0 away from the user; nil otherwise
// A fresh table per event: the scene may keep it or change it without affecting the next one.
#include "api_names.h"
#include "bindings.h"
#include "lua_args.h"

namespace rigidlab::lua {

void pushMouseEvent(lua_State* L, const MouseEvent& e) {
  lua_createtable(L, 0, 8);
  const std::string_view kind = api::kMouseEventKinds[static_cast<size_t>(e.kind)];
  lua_pushlstring(L, kind.data(), kind.size());
  lua_setfield(L, -2, "kind");
  if (e.button != MouseEvent::Button::None) {
    const std::string_view button = api::kMouseButtons[static_cast<size_t>(e.button) - 1];
    lua_pushlstring(L, button.data(), button.size());
    lua_setfield(L, -2, "button");
  }
  pushVec(L, e.position);
  lua_setfield(L, -2, "position");
  pushVec(L, e.screen);
  lua_setfield(L, -2, "screen");
  lua_pushboolean(L, e.shift);
  lua_setfield(L, -2, "shift");
  lua_pushboolean(L, e.ctrl);
  lua_setfield(L, -2, "ctrl");
  lua_pushboolean(L, e.alt);
  lua_setfield(L, -2, "alt");
  if (e.kind == MouseEvent::Kind::Wheel) {
    lua_pushnumber(L, e.wheel);
    lua_setfield(L, -2, "wheel");
  }
}

}  // namespace rigidlab::lua
