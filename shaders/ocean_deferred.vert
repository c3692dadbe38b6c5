// The deferred ocean's screen tiles (OceanRenderer: rectangles in the
// framebuffer's pixels); ocean.frag's GEOCEAN_DEFERRED reads its
// inputs from the G-buffer at the pixel.
layout(location = 0) in vec2 aPixel;
uniform ivec2 uGOrigin;  // the viewport, pixels
uniform vec2 uGSize;
void main() { gl_Position = vec4((aPixel - vec2(uGOrigin)) / uGSize * 2.0 - 1.0, 0.0, 1.0); }
