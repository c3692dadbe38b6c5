// The deferred ocean's screen tiles (OceanRenderer: rectangles in pixels
// from the viewport's origin); ocean.frag's GEOCEAN_DEFERRED reads its
// inputs from the G-buffer at the pixel.
layout(location = 0) in vec2 aPixel;
uniform vec2 uGSize;  // the viewport, pixels
void main() { gl_Position = vec4(aPixel / uGSize * 2.0 - 1.0, 0.0, 1.0); }
