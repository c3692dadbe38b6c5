// Reduced-rate shading of the deferred noise sea (OceanRenderer,
// OceanOptions::reducedRate). The coarse pass shaded the even pixels
// (2i, 2j) exactly (ocean.frag's GEOCEAN_COARSE: colour and alpha in a
// half-size float target); a pixel between them takes the mean of its 1, 2
// or 4 nearest (bilinear at the half-way points) where the sea is opaque
// there and at all of them and their colours agree within uRateTolerance per
// channel. Elsewhere it marks its block (uFullRateBlock: llvmpipe's 8 lanes)
// for the full-rate pass, which shades the block whole: llvmpipe runs both
// sides of a branch, so full rate cannot be a branch here. Checking the
// G-buffer's normal and distance at the 4 as well cost ~35 ms a 1280 x 720
// frame and marked almost no block the colours did not (docs/PERFORMANCE.md).
layout(binding = 15) uniform sampler2D uG0;  // eyeRel, alpha
layout(binding = 17) uniform sampler2D uG2;  // relief depth, ...
layout(binding = 18) uniform sampler2D uCoarse;
layout(binding = 7, r8ui) uniform writeonly uimage2D uFullRate;
uniform int uWriteData;
uniform ivec2 uFullRateBlock;  // pixels
uniform float uRateTolerance;  // display units, per channel
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outData;

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 g0 = texelFetch(uG0, px, 0);
  if (g0.w <= 0.0) discard;  // no sea here
  ivec2 c = px >> 1, o = px & 1;
  vec4 a = texelFetch(uCoarse, c, 0), b = texelFetch(uCoarse, c + ivec2(o.x, 0), 0);
  vec4 d = texelFetch(uCoarse, c + ivec2(0, o.y), 0), e = texelFetch(uCoarse, c + o, 0);
  vec4 lo = min(min(a, b), min(d, e)), hi = max(max(a, b), max(d, e));
  // Opaque only: the full-rate pass then overwrites its blocks' pixels
  // (blending twice would not), the even ones with the same value.
  if (min(lo.a, g0.w) < 1.0 || any(greaterThan(hi.rgb - lo.rgb, vec3(uRateTolerance)))) {
    imageStore(uFullRate, px / uFullRateBlock, uvec4(1u));
    discard;
  }
  outColor = vec4((a.rgb + b.rgb + d.rgb + e.rgb) * 0.25, 1.0);  // an even pixel: its own value, exactly
  outData = uWriteData == 2 ? vec4(texelFetch(uG2, px, 0).x, 0.0, 0.0, 2.0) : uWriteData != 0 ? vec4(g0.xyz, 1.0) : vec4(0.0);
}
