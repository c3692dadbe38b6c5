// Floating bodies: flat-shaded (the face normal from the position's screen
// derivatives, turned towards the eye), lit by the sun with a sky ambient.
// The data attachment gets the eye-relative position with w = 2 (the
// ocean writes w = 1), so tests find the boat's pixels and where they are.
in vec3 vEyeRel;

uniform vec3 uColor;
uniform vec3 uSunDir;
uniform vec3 uUp;  // ellipsoid normal at the boat

layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outData;

void main() {
  vec3 n = normalize(cross(dFdx(vEyeRel), dFdy(vEyeRel)));
  if (dot(n, vEyeRel) > 0.0) n = -n;
  float sun = max(dot(n, uSunDir), 0.0) * smoothstep(-0.05, 0.1, dot(uUp, uSunDir));
  float sky = 0.35 + 0.15 * dot(n, uUp);
  outColor = vec4(uColor * (0.85 * sun + sky), 1.0);
  outData = vec4(vEyeRel, 2.0);
}
