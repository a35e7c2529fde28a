// World drawing: positions in metres relative to the camera centre (subtracted on the CPU in double
// precision, so a body far from the origin does not jitter in float), scaled to clip space.
#version 330 core

layout(location = 0) in vec2 a_position;  // [m], relative to the camera centre
layout(location = 1) in vec4 a_color;

uniform vec2 u_scale;  // 2 · pixels_per_metre / viewport size in pixels, per axis

out vec4 v_color;

void main() {
  gl_Position = vec4(a_position * u_scale, 0.0, 1.0);
  v_color = a_color;
}
