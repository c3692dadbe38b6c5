// Issue 15 item 4: a breaking spray cluster (spray.vert), a soft round sprite.
in float vAlpha;
in vec3 vColor;
layout(location = 0) out vec4 outColor;

void main() {
  vec2 c = gl_PointCoord * 2.0 - 1.0;
  float r2 = dot(c, c);
  if (r2 > 1.0 || vAlpha <= 0.0) discard;
  outColor = vec4(vColor, vAlpha * (1.0 - r2));
}
