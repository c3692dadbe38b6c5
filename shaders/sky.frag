#include "atmosphere.glsl"
in vec3 vDir;
flat in vec3 vSun;
uniform vec3 uSunDir;
uniform vec3 uEyeDir;
uniform float uEyeRadiusM;
layout(location = 0) out vec4 outColor;
void main() {
  vec3 d = normalize(vDir);
  vec3 c = skyRadianceLit(d, uEyeDir, uSunDir, uEyeRadiusM - kEarthRadiusM, uEyeRadiusM, 1.0, vSun);
  outColor = vec4(toDisplay(c), 1.0);
}
