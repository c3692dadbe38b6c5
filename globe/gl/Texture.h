// Textures of global lon/lat grids: longitude wraps, latitude clamps,
// optionally mipmapped. The host's world textures and the ocean's own are
// made by these, so the two sample the same data the same way.
#pragma once

#include <epoxy/gl.h>

#include <cstddef>

namespace geocean::gl {

// Immutable storage (all mip levels when `mipmaps`), wrap/filter set.
GLuint createGeoTexture(GLenum internalFormat, int width, int height, bool mipmaps);
// One channel of interleaved float values (`channels` per texel) as a
// GL_RED float upload into a new texture; mipmaps generated when asked.
GLuint redGeoTexture(const float* values, int channels, int width, int height, GLenum internalFormat, bool mipmaps);
// RGB 0..255 floats (`channels` >= 3 per texel) as sRGB8_ALPHA8, mipmapped.
GLuint srgbGeoTexture(const float* values, int channels, int width, int height);

}  // namespace geocean::gl
