// Wave-field data shared by C++ (GLM) and GLSL: ONE definition.
// Included by plugin/waves/WaveKernel.h (twice: WR = double for the CPU
// query path, WR = float for the GPU upload layout) and by shaders that
// displace the ocean (after which they declare the SSBOs and include
// waves.glsl). Only the common subset of GLSL and GLM is used here: no
// swizzles, no out-parameters, no arrays, no global constants.
//
// Everything is "patch relative": the CPU computes, in double, each
// quantity that is large at Earth scale (lattice cells, phases ~1e6 rad) at a
// patch origin O and reduces it (integer cell + fraction, phase mod 2 pi).
// The GPU then only adds small float terms for offsets d = P - O of a few km.
// The CPU query path runs the same algebra in double with O = P (d = 0).
#ifndef WAVES_TYPES_GLSL
#define WAVES_TYPES_GLSL

#ifndef WV_CPU
#define WR float
#define WR2 vec2
#define WR3 vec3
#define WR4 vec4
#endif

#define WV_G 9.80665
#define WV_PI 3.14159265358979323846
// Waves fade out within this arc (rad; 50 km) of their great-circle source
// and antipode, where wave fronts shrink to points.
#define WV_TAPER_RAD 0.0078480615
#define WV_DEEP_KH 12.0
// Paper 003 eq. 5: the crest's phase lead over the trough (rad) at k h -> 0 on a plunging beach.
#define WV_CURL_RAD 1.2

// Patch frame at origin O (ECEF).
struct WvFrame {
  WR4 radial;    // xyz: O / |O| (geocentric unit), w: 1 / |O| (1/m)
  WR4 up;        // xyz: geodetic normal at O, w: 0
  WR4 upScale;   // xyz: diag(1/a^2, 1/a^2, 1/b^2) / |diag(..) O|: up(O + d) ~ up + upScale * d
};

// One octave of the solid (3D) fractal noise, seen from a patch origin.
// Lattice coordinate q(P, t) = M P + v t with M = rotation * frequency
// (rows stored exactly as floats so CPU and GPU use identical numbers).
struct WvOctave {
  WR4 row0;      // xyz: first row of M (lattice units per m), w: amplitude (m)
  WR4 row1;      // xyz: second row, w: seed (exact small integer as a real)
  WR4 row2;      // xyz: third row
  WR4 fracO;     // xyz: fract(q(O, t)), w: 0
  ivec4 cellO;   // xyz: floor(q(O, t))
  WR4 vel;       // xyz: v, lattice units per second (for the vertical velocity)
};

// One Gerstner component travelling along great circles away from a source
// point c, seen from a patch origin. Phase psi = phaseO + kR * (theta(P) - theta(O)),
// theta = arc from c.
struct WvWave {
  WR4 dirO;      // xyz: propagation direction at O (unit ECEF tangent), w: sin(thetaO)
  WR4 binO;      // xyz: radial x dir, w: cos(thetaO)
  WR4 phase;     // x: phase at O and time t (rad, reduced), y: k_ref * Rwave (rad per rad of arc),
                 // z: omega (rad/s), w: deep-water amplitude (m)
  WR4 extra;     // x: k_ref (rad/m) of the phase, y: choppiness (0..1), z, w: 0
};

// The FFT ocean (Tessendorf): per cascade a periodic N x N table of texels,
// 2 WR4 each: (h, Dx, Dy, dh/dt), (dh/du, dh/dv, dDx/dt, dDy/dt) in tile
// coordinates (u, v) (m); h and the choppy displacement D in m. The tile is laid on the ellipsoid triplanarly:
// each of the 3 ECEF axes e_i projects the point onto the plane normal to
// it. One WvFftPlane per (axis, cascade), seen from a patch origin O.
struct WvFftPlane {
  WR4 uAxis;     // xyz: U axis (unit ECEF) * texels per metre, w: fract of O's u texel coordinate
  WR4 vAxis;     // xyz: V axis * texels per metre, w: fract of O's v texel coordinate
  WR4 axis;      // xyz: the plane's normal e_i (unit ECEF), w: metres per texel
  ivec4 cell;    // x, y: floor of O's texel coordinates mod N, z: first texel of the table, w: N (power of 2)
};

// The near-shore phase field (plugin/waves/CoastField.h) seen from a patch
// origin: an N x N grid of nodes on the tangent plane at the region's centre,
// per Gerstner component and node one WR4 (phase offset from the reference
// phase (rad), sin and 1 - cos of the turning angle, Kr - 1), then one more
// slab per node: (Iribarren number, curl weight, break weight, tan beta); all exactly 0
// where the waves do not feel the coast, so deep water is unchanged bit for
// bit. cell.z == 0: no field (wv_gerstner).
struct WvCoast {
  WR4 eAxis;     // xyz: grid's x axis (unit ECEF) / cell size (nodes per m), w: fract of O's x node coordinate
  WR4 nAxis;     // xyz: grid's y axis / cell size, w: fract of O's y node coordinate
  ivec4 cell;    // x, y: floor of O's node coordinates, z: N (0: no field), w: first texel
#ifdef __cplusplus
#ifdef __clang__
#if __clang_major__ < 16
  WvCoast() = default;
  WvCoast(WR4 e, WR4 n, ivec4 c) : eAxis(e), nAxis(n), cell(c) {}
#endif
#endif
#endif
};

// Result of evaluating a model at a rest point (Lagrangian).
struct WvResult {
  WR4 disp;      // xyz: displacement (ECEF, m), w: vertical part (m, along the geodetic up)
  WR4 normal;    // xyz: unit surface normal (ECEF), w: vertical particle velocity (m/s)
  WR4 hvel;      // xyz: horizontal particle velocity (ECEF, m/s), w: breaking foam (0 .. 1; wv_gerstnerCoast)
  // Jacobian of the horizontal map x -> x + H(x) in the tangent frame
  // (t1, t2) of wv_tangentFrame: (a11, a12, a22, det); identity for the
  // noise model. The CPU uses it for Newton steps of the sea-height query.
  WR4 jac;
#ifdef __cplusplus
#ifdef __clang__
#if __clang_major__ < 16
  // C++ before Clang 16 (Debian's Clang 14 builds the fuzzers, tests/fuzz)
  // has no parenthesised aggregate initialisation, which the GLSL
  // constructor syntax WvResult(a, b, c, d) needs; the layout is unchanged.
  WvResult() = default;
  WvResult(WR4 d, WR4 n, WR4 h, WR4 j) : disp(d), normal(n), hvel(h), jac(j) {}
#endif
#endif
#endif
};

#endif
