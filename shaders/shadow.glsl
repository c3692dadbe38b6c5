// The sun's shadow on the water (issue 13 item 6; paper 001's shadow map):
// the host's depth pass from the sun (globe/render/GlobeRenderer: terrain
// and floating bodies, an orthographic view along the sun over the sea near
// the eye), sampled with percentage-closer filtering (bilinear). Depth is reversed
// (1 nearest the sun): a point is lit where nothing in the map is nearer.
// uShadow: 0 no map, 1 the sun's direct light removed in shadow (default),
// 2 paper 001's darkening of the shadowed pixel by 0.5.
uniform int uShadow;
uniform mat4 uShadowMatrix;  // eye-relative position -> map uv (xy) and depth (z), [0, 1]
// Depth offset for the water: 0.3 m over the map's depth range (the casters
// are terrain and hulls, never the water itself: no acne to hide, only the
// waterline's contact).
uniform float uShadowBias;
layout(binding = 14) uniform sampler2DShadow uShadowMap;

// The sun's visible share at a point (0 in full shadow, 1 lit or off the map).
float sunVisibility(vec3 eyeRel) {
  if (uShadow == 0) return 1.0;
  vec3 s = (uShadowMatrix * vec4(eyeRel, 1.0)).xyz;
  vec2 edge = min(s.xy, 1.0 - s.xy);
  if (min(edge.x, edge.y) <= 0.0) return 1.0;
  // PCF: one bilinear comparison, the 2 x 2 texels around the point
  // weighted (the edge a linear ramp one texel wide). Four such taps half a
  // texel apart (a 3 x 3 tent) cost the ocean 20 % more CPU on llvmpipe
  // (docs/PERFORMANCE.md) for a softer edge only where a texel spans pixels.
  float v = texture(uShadowMap, vec3(s.xy, s.z + uShadowBias));
  // Fades out over the map's outer 2 % so its edge draws no line.
  return mix(1.0, v, smoothstep(0.0, 0.02, min(edge.x, edge.y)));
}
