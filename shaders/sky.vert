// Full-screen triangle; the view ray per pixel from the eye's basis. The
// sunlight at the eye's ground point is the same for every pixel: made
// here once per vertex instead of per pixel (its air mass costs a pow, an
// acos and exps).
#include "atmosphere.glsl"
uniform vec3 uForward;
uniform vec3 uRight;
uniform vec3 uUp;
uniform vec2 uTanHalf;  // tan(fov/2) * aspect, tan(fov/2)
uniform vec3 uSunDir;
uniform vec3 uEyeDir;
out vec3 vDir;
flat out vec3 vSun;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0;
  vDir = uForward + p.x * uTanHalf.x * uRight + p.y * uTanHalf.y * uUp;
  vSun = sunLight(dot(uSunDir, uEyeDir));
  gl_Position = vec4(p, 0.0, 1.0);  // depth 0: infinitely far in reversed Z
}
