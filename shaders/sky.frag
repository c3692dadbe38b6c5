#include "atmosphere.glsl"
in vec3 vDir;
uniform vec3 uSunDir;
uniform vec3 uEyeDir;
uniform float uEyeRadiusM;
layout(location = 0) out vec4 outColor;
void main() {
  vec3 d = normalize(vDir);
  vec3 c = skyColor(d, uEyeDir, uSunDir, uEyeRadiusM - kEarthRadiusM, uEyeRadiusM);
  outColor = vec4(toDisplay(c), 1.0);
}
