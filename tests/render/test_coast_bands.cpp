// Issue 15 item 4, "no visible boundary between bands" (paper 003's distance
// bands, shaders/coast_bands.glsl): the breaking foam of a spilling beach
// goes from the kernel's crests (near) to a foam texture moved along the
// crest lines (middle) as grid cells grow against the local wavelength. A
// view along the surf zone from 60 m is drawn with the bands (A), the near
// band everywhere (B) and the middle/far bands everywhere (C).
// Each pixel is binned by its band position: a grid cell's footprint along
// the view over the local breaking wavelength, r = cell / lambda, what
// ocean.vert fades the bands by (near below 1/8, middle above 1/3, the
// edge r_e = 0.229 where the fade is half way), computed here on the CPU
// at the pixel ray's sea-level point (WaveField::breakingFoamMean's
// wavelength, the renderer's cell angle). Per bin (ln r steps of 0.03),
// two statistics: the mean luma (Rec. 709 on the 8-bit values) minus B's
// over the same pixels (the view's own trend removed), and the log of the
// mean squared horizontal second difference of the luma (the crests'
// detail). Each is fitted by a line over 24 bins either side of the edge
// (2 bins either side left out: a cell's band weight is interpolated
// between its vertices); the step is the gap of the two fits at the edge.
// Its noise is the scatter of bins within one band, which the moving foam
// streaks make: the step is taken on 6 frames 3.7 s apart (the streaks move
// on by more than their width) and its mean must be within 3 standard
// errors of 0. Measured: luma -2.35 (se 1.61), detail -0.034 (se 0.064)
// (2026-12-05, the normal per fragment; before it -0.023, se 0.069).
// The test's negative control, the blend removed (B below r_e, C above:
// the hard switch per pixel, an edge along the curved r contour, looked
// at) must fail it: its detail steps by 0.225 (se 0.040; 0.237 before). Shown once with
// the blend removed in the shader (coast_bands.glsl's smoothstep a step at
// 0.229): the test fails on the detail step, 0.227 (se 0.043), not only on
// the mean. (Binned by screen row, as before, that switch failed only on
// the mean: the edge is not a row, lambda varies across the surf zone.)
// Over the middle band and the fade the mean luma is the near band's
// within 1 % (every band draws the near band's phase-averaged foam;
// measured 127.3 against 128.1).
#include "CoastScene.h"
#include "RenderFixture.h"

#include "globe/gl/Framebuffer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace geocean::render::test {
namespace {

// The 1:50 spilling beach (CoastScene.h).
constexpr double kShoreLon = kSpillingShoreLon, kSlope = kSpillingSlope;

// The band edge (coast_bands.glsl: smoothstep(0.125, 0.333, r) is 1/2
// there) and the bins of ln(r / kEdgeR).
constexpr double kEdgeR = 0.229, kBinLn = 0.03;
constexpr int kBinsSide = 28, kBins = 2 * kBinsSide;  // bin kBinsSide starts at the edge

double luma(const Image& im, int x, int y) {
  const std::uint8_t* p = &im.rgba[(std::size_t(y) * im.width + x) * 4];
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

// Per bin: (mean luma, log mean squared horizontal second difference) of
// `im` over the pixels whose bin is `bin` (-1: not sea).
struct Bins {
  std::vector<double> luma, hi;
};
Bins binStats(const Image& im, const std::vector<int>& bin) {
  std::vector<double> sl(kBins, 0.0), sh(kBins, 0.0), n(kBins, 0.0);
  for (int y = 0; y < im.height; ++y)
    for (int x = 1; x + 1 < im.width; ++x) {
      const int b = bin[std::size_t(y) * im.width + x];
      if (b < 0) continue;
      const double c = luma(im, x, y), d2 = luma(im, x - 1, y) - 2.0 * c + luma(im, x + 1, y);
      sl[std::size_t(b)] += c, sh[std::size_t(b)] += d2 * d2, n[std::size_t(b)] += 1.0;
    }
  Bins out;
  for (int b = 0; b < kBins; ++b) {
    out.luma.push_back(sl[std::size_t(b)] / n[std::size_t(b)]);
    out.hi.push_back(std::log(sh[std::size_t(b)] / n[std::size_t(b)] + 1e-3));
  }
  return out;
}

// A line fitted to v(i) over [from, to): its value at `at` and that
// value's standard error from the residuals.
struct Fit {
  double value = 0.0, se = 0.0;
};
Fit fitLine(const std::vector<double>& v, int from, int to, double at) {
  const int n = to - from;
  double sx = 0, sy = 0;
  for (int y = from; y < to; ++y) sx += y, sy += v[std::size_t(y)];
  const double mx = sx / n, my = sy / n;
  double sxx = 0, sxy = 0;
  for (int y = from; y < to; ++y) sxx += (y - mx) * (y - mx), sxy += (y - mx) * (v[std::size_t(y)] - my);
  const double slope = sxy / sxx;
  double rss = 0.0;
  for (int y = from; y < to; ++y) {
    const double r = v[std::size_t(y)] - (my + slope * (y - mx));
    rss += r * r;
  }
  const double s2 = rss / (n - 2);
  return {my + slope * (at - mx), std::sqrt(s2 * (1.0 / n + (at - mx) * (at - mx) / sxx))};
}

// The gap at the edge (between bins kBinsSide - 1 and kBinsSide) of lines
// fitted to the `window` bins either side, 2 left out next to it.
constexpr int kEdgeWindow = 24;
double stepAt(const std::vector<double>& v, int window = kEdgeWindow) {
  const double at = kBinsSide;
  return fitLine(v, kBinsSide - 2 - window, kBinsSide - 2, at).value -
         fitLine(v, kBinsSide + 2, kBinsSide + 2 + window, at).value;
}

// The negative controls' hard switch: `below` where pos < edge (and off
// the sea, pos -1), `above` from the edge on.
Image cutAt(const Image& below, const Image& above, const std::vector<double>& pos, double edge) {
  Image cut = below;
  for (std::size_t i = 0; i < pos.size(); ++i)
    if (pos[i] >= edge) std::memcpy(&cut.rgba[i * 4], &above.rgba[i * 4], 4);
  return cut;
}

// Each frame's steps at the edge: the drawn frame's (and the control's)
// mean luma over the reference's (the view's own trend and content
// removed), and its own log detail.
struct Steps {
  std::vector<double> luma, hi;
  void add(const Image& im, const Bins& ref, const std::vector<int>& bin, int window = kEdgeWindow) {
    const Bins s = binStats(im, bin);
    std::vector<double> dl;
    for (int k = 0; k < kBins; ++k) dl.push_back(s.luma[std::size_t(k)] - ref.luma[std::size_t(k)]);
    luma.push_back(stepAt(dl, window));
    hi.push_back(stepAt(s.hi, window));
  }
};

// Mean over frames and its standard error.
std::pair<double, double> meanSe(const std::vector<double>& v) {
  double m = 0.0, var = 0.0;
  for (double x : v) m += x / v.size();
  for (double x : v) var += (x - m) * (x - m) / (v.size() - 1);
  return {m, std::sqrt(var / v.size())};
}

}  // namespace

TEST(CoastBands, BreakingFoamBandEdgeHasNoStep) {
  session();
  const auto beach = spillingBeach();
  const auto& snap = beach->snap;
  ASSERT_NE(snap->waves->coastField(), nullptr);
  const auto ocean = std::make_shared<ocean_render::OceanRenderer>(beach->grids, snap->landSea, beach->options());
  // The near band's spray (Spray.h, its own test test_spray.cpp) is the same
  // in A, B and C but its bright dots add high-frequency power near the
  // eye, masking the foam's step. The bands' foam is tested alone.
  ocean->setSpray(false);

  // Over the surf zone (70 m off the shore) near the field's south edge,
  // looking north along it.
  ViewPose p;
  p.latDeg = 0.284, p.lonDeg = kShoreLon - 70.0 / 111320.0, p.altM = 60.0, p.headingDeg = 0.0, p.pitchDeg = -30.0;
  p.width = p.height = 384;
  GlobeRenderer renderer(beach->world);
  renderer.addLayer(std::make_shared<DirectOceanLayer>(ocean));
  Framebuffer fb(p.width, p.height, true);
  fb.bind();
  FrameSettings fs;
  fs.sunEcef = sunForView(p, 150.0, 40.0);
  using Bands = ocean_render::OceanRenderer::CoastBands;
  auto drawWith = [&](Bands mode, double timeS, const std::string& name) {
    ocean->setCoastBands(mode);
    fs.timeS = timeS;
    renderer.render(p, fs);
    const Image im = fb.readColor();
    if (!name.empty()) gl::writePng(::testing::TempDir() + "/coast_bands_" + name + ".png", im);
    return im;
  };
  const int w = p.width, h = p.height;

  // Each sea pixel's band position r and its bin (ocean.vert: the cell's
  // footprint |eyeRel| uCellRadians over the sine of the view's elevation
  // angle, at least 0.02; lambda: wv_breakingFoamMean's, no phase in it).
  const camera::Camera cam = renderer.camera(p);
  const double cellRadians = 2.0 * std::tan(0.5 * cam.vfovDeg() * 3.14159265358979 / 180.0) / h * ocean->cellPx();
  std::vector<int> bin(std::size_t(w) * h, -1);
  std::vector<double> bandR(std::size_t(w) * h, -1.0);
  std::vector<int> perBin(kBins, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      geo::Geodetic g;
      if (!seaPoint(cam, x, y, g)) continue;
      const double eastOfShoreM = (g.lonDeg - kShoreLon) * 111320.0;
      if (eastOfShoreM > -5.0) continue;  // the beach and the shoreline's fringe
      const double depth = std::max(1.0, std::min(200.0, -kSlope * eastOfShoreM));
      const glm::dvec3 rel = geo::toEcef(g) - cam.eyeEcef();
      const double sinE = std::abs(glm::dot(glm::normalize(rel), geo::surfaceNormal(g.latDeg, g.lonDeg)));
      const double cellAlongM = glm::length(rel) * cellRadians / std::max(sinE, 0.02);
      const double lambda = snap->waves->breakingFoamMean(g.latDeg, g.lonDeg, 30.0, depth).wavelengthM;
      const double rr = cellAlongM / std::max(lambda, 1e-3);
      bandR[std::size_t(y) * w + x] = rr;
      const int b = int(std::floor(std::log(rr / kEdgeR) / kBinLn)) + kBinsSide;
      if (b < 0 || b >= kBins) continue;
      bin[std::size_t(y) * w + x] = b;
      ++perBin[std::size_t(b)];
    }
  const int fewest = *std::min_element(perBin.begin(), perBin.end());
  std::printf("band position bins: ln r / r_e in steps of %.2f from %.2f, fewest pixels in a bin %d\n", kBinLn,
              -kBinsSide * kBinLn, fewest);
  ASSERT_GT(fewest, 200) << "the view does not cover the band edge's neighbourhood";

  // Frames 3.7 s apart (the streaks move on by more than their width): the
  // steps' noise is their scatter from frame to frame.
  constexpr int kFrames = 6;
  int fadeBottom = -1;
  Steps bands, hard;
  double sa = 0.0, sb = 0.0;
  for (int f = 0; f < kFrames; ++f) {
    const double t = 30.0 + 3.7 * f;
    const bool keep = f == 0;
    const Image a = drawWith(Bands::ByDistance, t, keep ? "bands" : ""), b = drawWith(Bands::NearOnly, t, keep ? "near" : ""),
                c = drawWith(Bands::FarOnly, t, keep ? "far" : "");
    if (f == 0) {
      // Far rows are above near ones: the fade ends at the lowest row A
      // differs from B.
      for (int y = h - 1; y >= 0 && fadeBottom < 0; --y)
        if (std::memcmp(&a.rgba[std::size_t(y) * w * 4], &b.rgba[std::size_t(y) * w * 4], std::size_t(w) * 4) != 0)
          fadeBottom = y;
      ASSERT_GE(fadeBottom, 0) << "no middle band on screen";
    }
    // The blend removed: per pixel, the near band below the edge, the
    // middle band above.
    const Image cut = cutAt(b, c, bandR, kEdgeR);
    if (keep) gl::writePng(::testing::TempDir() + "/coast_bands_hard.png", cut);
    // Luma over B's (the near band's content removed).
    const Bins near = binStats(b, bin);
    bands.add(a, near, bin);
    hard.add(cut, near, bin);
    for (int y = 0; y <= fadeBottom; ++y)
      for (int x = 0; x < w; ++x) sa += luma(a, x, y), sb += luma(b, x, y);
  }
  ocean->setCoastBands(Bands::ByDistance);
  for (auto [name, st] : {std::pair{"with the bands", &bands}, std::pair{"hard switch (no blend)", &hard}}) {
    const auto [ml, sl] = meanSe(st->luma);
    const auto [mh, sh] = meanSe(st->hi);
    const bool lumaOk = std::abs(ml) < 3.0 * sl, hiOk = std::abs(mh) < 3.0 * sh;
    std::printf("%s: mean luma step %.3f (se %.3f), log detail step %.3f (se %.3f) over %d frames\n", name, ml, sl,
                mh, sh, kFrames);
    if (st == &bands) {
      EXPECT_TRUE(lumaOk) << "mean luma steps by " << ml << " across the band edge (se " << sl << ")";
      EXPECT_TRUE(hiOk) << "the detail steps by " << mh << " across the band edge (se " << sh << ")";
    } else {
      EXPECT_FALSE(lumaOk && hiOk) << "the test cannot see a hard switch between the bands";
    }
  }
  // The mean: every band's foam is the near band's phase average, so over
  // the middle band and the fade A's mean luma is B's (printed; within 1 %).
  const double la = sa / (kFrames * (fadeBottom + 1.0) * w), lb = sb / (kFrames * (fadeBottom + 1.0) * w);
  std::printf("mean luma over the middle band and the fade: %.3f with the bands, %.3f near band everywhere\n", la, lb);
  EXPECT_NEAR(la, lb, 0.01 * lb);
}

// Issue 15 item 4, the middle -> far edge (coast_bands_frag.glsl): the
// middle band's crest-line texture fades into the far band's mean as a
// pixel along the view grows from 1/4 to 1 local wavelength, q = pixel /
// lambda, half way at q_e = 0.625. Tested as the near -> middle edge: the
// beach's surf zone along the shore from 150 m (the far band's foam is the
// breaking sea's, so only pixels whose CPU mean foam, WaveField::
// breakingFoamMean, is over 0.02 count), drawn by distance (A), with the
// middle band's texture everywhere (M, no fade) and the far band's mean
// everywhere (F); q per pixel on the CPU from the sea-level points of its
// neighbours (the longer of the two steps, as the shader's dFdx / dFdy)
// and the local lambda. The steps at q_e over 6 frames (lines over 12 bins
// either side): A's mean luma over M's and A's own log detail, within 3
// standard errors of 0; the control, M below q_e and F above (the fade
// removed), must fail. Measured (2026-12-05): luma -0.09 (se 0.36), detail
// 0.11 (se 0.08); the control -5.58 (se 0.60), 1.23 (se 0.12). Shown once
// with the fade a step at q_e in coast_bands_frag.glsl: the test fails,
// -5.52 (se 0.60) and 1.31 (se 0.14).
TEST(CoastBands, MiddleToFarFadeHasNoStep) {
  session();
  const auto beach = spillingBeach();
  const auto& snap = beach->snap;
  const auto ocean = std::make_shared<ocean_render::OceanRenderer>(beach->grids, snap->landSea, beach->options());
  ocean->setSpray(false);
  constexpr double kEdgeQ = 0.625;
  // Lines over 12 bins either side, not 24: A - M is the fade itself, a
  // sigmoid in ln q (the texture's display mean is not its mean foam's, the
  // tone curve being curved), and over 24 bins its curvature read as a
  // step of -1.14 (se 0.26).
  constexpr int kWindow = 12;
  ViewPose p;
  p.latDeg = 0.284, p.lonDeg = kShoreLon - 70.0 / 111320.0, p.altM = 150.0, p.headingDeg = 0.0, p.pitchDeg = -9.0;
  p.width = p.height = 512;
  GlobeRenderer renderer(beach->world);
  renderer.addLayer(std::make_shared<DirectOceanLayer>(ocean));
  Framebuffer fb(p.width, p.height, true);
  fb.bind();
  FrameSettings fs;
  fs.sunEcef = sunForView(p, 150.0, 40.0);
  using Bands = ocean_render::OceanRenderer::CoastBands;
  auto drawWith = [&](Bands mode, double timeS, const std::string& name) {
    ocean->setCoastBands(mode);
    fs.timeS = timeS;
    renderer.render(p, fs);
    const Image im = fb.readColor();
    if (!name.empty()) gl::writePng(::testing::TempDir() + "/far_fade_" + name + ".png", im);
    return im;
  };
  const int w = p.width, h = p.height;
  const camera::Camera cam = renderer.camera(p);
  std::vector<glm::dvec3> at(std::size_t(w) * h, glm::dvec3(0.0));
  std::vector<geo::Geodetic> geod(std::size_t(w) * h);
  std::vector<std::uint8_t> hit(std::size_t(w) * h, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      geo::Geodetic g;
      if (!seaPoint(cam, x, y, g)) continue;
      hit[std::size_t(y) * w + x] = 1, geod[std::size_t(y) * w + x] = g, at[std::size_t(y) * w + x] = geo::toEcef(g);
    }
  std::vector<int> bin(std::size_t(w) * h, -1);
  std::vector<double> qOf(std::size_t(w) * h, -1.0);
  std::vector<int> perBin(kBins, 0);
  for (int y = 0; y + 1 < h; ++y)
    for (int x = 0; x + 1 < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      if (!hit[i] || !hit[i + 1] || !hit[i + std::size_t(w)]) continue;
      const geo::Geodetic& g = geod[i];
      const double eastOfShoreM = (g.lonDeg - kShoreLon) * 111320.0;
      if (eastOfShoreM > -5.0) continue;
      const double depth = std::max(1.0, std::min(200.0, -kSlope * eastOfShoreM));
      const auto mean = snap->waves->breakingFoamMean(g.latDeg, g.lonDeg, 30.0, depth);
      if (!(mean.foam > 0.02)) continue;  // no breaking: every band draws no foam
      const double pixelM = std::max(glm::length(at[i + 1] - at[i]), glm::length(at[i + std::size_t(w)] - at[i]));
      const double q = pixelM / std::max(mean.wavelengthM, 1e-3);
      qOf[i] = q;
      const int b = int(std::floor(std::log(q / kEdgeQ) / kBinLn)) + kBinsSide;
      if (b < 0 || b >= kBins) continue;
      bin[i] = b;
      ++perBin[std::size_t(b)];
    }
  const int fewest = *std::min_element(perBin.begin(), perBin.end());
  std::printf("far fade bins: ln q / q_e in steps of %.2f from %.2f, fewest pixels in a bin %d\n", kBinLn,
              -kBinsSide * kBinLn, fewest);
  ASSERT_GT(fewest, 60) << "the view does not cover the fade's neighbourhood over breaking water";

  constexpr int kFrames = 6;
  Steps bands, hard;
  for (int f = 0; f < kFrames; ++f) {
    const double t = 30.0 + 3.7 * f;
    const bool keep = f == 0;
    const Image a = drawWith(Bands::ByDistance, t, keep ? "bands" : ""),
                m = drawWith(Bands::MiddleTextureOnly, t, keep ? "middle" : ""),
                c = drawWith(Bands::FarMeanOnly, t, keep ? "far" : "");
    const Image cut = cutAt(m, c, qOf, kEdgeQ);
    if (keep) gl::writePng(::testing::TempDir() + "/far_fade_hard.png", cut);
    const Bins middle = binStats(m, bin);
    bands.add(a, middle, bin, kWindow);
    hard.add(cut, middle, bin, kWindow);
  }
  ocean->setCoastBands(Bands::ByDistance);
  for (auto [name, st] : {std::pair{"with the fade", &bands}, std::pair{"hard switch (no fade)", &hard}}) {
    const auto [ml, sl] = meanSe(st->luma);
    const auto [mh, sh] = meanSe(st->hi);
    const bool lumaOk = std::abs(ml) < 3.0 * sl, hiOk = std::abs(mh) < 3.0 * sh;
    std::printf("%s: mean luma step %.3f (se %.3f), log detail step %.3f (se %.3f) over %d frames\n", name, ml, sl,
                mh, sh, kFrames);
    if (st == &bands) {
      EXPECT_TRUE(lumaOk) << "mean luma steps by " << ml << " across the middle -> far fade (se " << sl << ")";
      EXPECT_TRUE(hiOk) << "the detail steps by " << mh << " across the middle -> far fade (se " << sh << ")";
    } else {
      EXPECT_FALSE(lumaOk && hiOk) << "the test cannot see a hard switch from the middle band to the far band";
    }
  }
}

// Issue 15 item 4, paper 003's coarser mesh in the middle band
// (OceanOptions::coarseMiddle: blocks of 2 x 2 grid cells drawn as one
// where the cell along the view is at least kMiddleMeshFromR of
// middleWavelengthM over water kMiddleMeshMinDepth of it deep, the waves
// not faded, kMiddleMeshMaxFar; grid::coarseIndices stitches them to the
// fine cells with fans; the normal is the fragment's on both meshes). The 1:50
// beach from 150 m, 1.5 km off the shore, so the mesh edge (r = cell along
// the view / middleWavelengthM = kMiddleMeshFromR) lies across the deep
// water, the beach on the right: drawn with the coarse mesh (A), the fine
// mesh everywhere (B) and, the test's negative control, blocks of 8 x 8
// cells with the vertices' interpolated normal (C, a mesh too coarse for
// the waves drawn as before the fragment normal; with the fragment's the
// 8 x 8 blocks step the luma by only -0.19, se 0.06) cut in per pixel at
// the edge (B below it, C above: a hard switch). Pixels are binned by ln(r / edge),
// r computed on the CPU at the pixel ray's sea-level point as ocean.vert
// measures a cell (pixels over water the depth rule keeps fine left out);
// the steps across the edge as CoastBands.BreakingFoam-
// BandEdgeHasNoStep's (lines fitted to 24 bins either side, 2 left out):
// A's mean luma over B's, and A's own log high-frequency power, over 6
// frames 3.7 s apart, each within 3 standard errors of 0; the control must
// fail. And no crack: no pixel that B draws as sea, all 8 neighbours too,
// is left without sea in A (the data attachment), here and over open water.
TEST(CoastBands, MiddleMeshEdgeHasNoStepAndNoCrack) {
  session();
  const auto beach = spillingBeach();
  const auto& snap = beach->snap;
  ocean_render::OceanOptions oo = beach->options();
  oo.coarseMiddle = true;
  const auto ocean = std::make_shared<ocean_render::OceanRenderer>(beach->grids, snap->landSea, oo);
  ocean->setSpray(false);  // as the band test: the foam and the surface alone
  ocean->setWriteData(true);
  const double lambdaM = ocean->middleWavelengthM(), edgeR = ocean_render::OceanRenderer::kMiddleMeshFromR;
  std::printf("middle mesh: blocks of 2 x 2 cells from cell along the view / %.1f m >= %.2f\n", lambdaM, edgeR);
  ASSERT_GT(lambdaM, 0.0);

  // 1.5 km off the shore looking north-north-east: the beach on the right,
  // the mesh edge over water deeper than kMiddleMeshMinDepth x lambda.
  ViewPose p;
  p.latDeg = 0.284, p.lonDeg = kShoreLon - 1500.0 / 111320.0, p.altM = 150.0, p.headingDeg = 20.0, p.pitchDeg = -25.0;
  p.width = p.height = 384;
  GlobeRenderer renderer(beach->world);
  renderer.addLayer(std::make_shared<DirectOceanLayer>(ocean));
  Framebuffer fb(p.width, p.height, true);
  fb.bind();
  FrameSettings fs;
  fs.sunEcef = sunForView(p, 150.0, 40.0);
  struct Frame {
    Image im;
    std::vector<float> data;
    std::size_t blocks = 0;
  };
  auto drawWith = [&](const ViewPose& v, int block, double timeS, const std::string& name, bool fragmentNormal = true) {
    ocean->setMiddleMeshBlock(block);
    ocean->setFragmentNormal(fragmentNormal);
    fs.timeS = timeS;
    renderer.render(v, fs);
    ocean->setFragmentNormal(true);
    Frame f{fb.readColor(), fb.readData(), ocean->lastCoarseBlocks()};
    if (!name.empty()) gl::writePng(::testing::TempDir() + "/middle_mesh_" + name + ".png", f.im);
    return f;
  };
  const int w = p.width, h = p.height;
  const camera::Camera cam = renderer.camera(p);
  const double cellRadians = 2.0 * std::tan(0.5 * cam.vfovDeg() * 3.14159265358979 / 180.0) / h * ocean->cellPx();
  std::vector<int> bin(std::size_t(w) * h, -1);
  std::vector<double> bandR(std::size_t(w) * h, -1.0);
  std::vector<int> perBin(kBins, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      geo::Geodetic g;
      if (!seaPoint(cam, x, y, g)) continue;
      // Water the rule lets coarsen (a block, 2 x 16 m, further than its depth bound).
      if (-kSlope * (g.lonDeg - kShoreLon) * 111320.0 < ocean_render::OceanRenderer::kMiddleMeshMinDepth * lambdaM + 1.0)
        continue;
      const glm::dvec3 rel = geo::toEcef(g) - cam.eyeEcef();
      const double sinE = std::abs(glm::dot(glm::normalize(rel), geo::surfaceNormal(g.latDeg, g.lonDeg)));
      const double rr = glm::length(rel) * cellRadians / std::max(sinE, 0.02) / lambdaM;
      bandR[std::size_t(y) * w + x] = rr;
      const int b = int(std::floor(std::log(rr / edgeR) / kBinLn)) + kBinsSide;
      if (b < 0 || b >= kBins) continue;
      bin[std::size_t(y) * w + x] = b;
      ++perBin[std::size_t(b)];
    }
  const int fewest = *std::min_element(perBin.begin(), perBin.end());
  std::printf("mesh edge bins: fewest pixels in a bin %d\n", fewest);
  ASSERT_GT(fewest, 200) << "the view does not cover the mesh edge's neighbourhood";

  // A pixel is the sea's where the data attachment's eye-relative point
  // (the clear and the sky leave other values there) projects into it; a
  // crack: sea in B with its 8 neighbours, not in A.
  const auto seaMask = [&](const Frame& f, const camera::Camera& c) {
    std::vector<std::uint8_t> m(std::size_t(w) * h, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float* q = &f.data[(std::size_t(y) * w + x) * 4];
        const auto ndc = c.projectEyeRelative(glm::dvec3(q[0], q[1], q[2]));
        m[std::size_t(y) * w + x] = ndc && std::abs((ndc->x * 0.5 + 0.5) * w - (x + 0.5)) <= 1.0 &&
                                    std::abs((0.5 - ndc->y * 0.5) * h - (y + 0.5)) <= 1.0;
      }
    return m;
  };
  const auto cracks = [&](const Frame& a, const Frame& b, const camera::Camera& c, int& seaPixels) {
    const auto ma = seaMask(a, c), mb = seaMask(b, c);
    int n = 0;
    seaPixels = 0;
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        bool all = true;
        for (int dy = -1; dy <= 1 && all; ++dy)
          for (int dx = -1; dx <= 1 && all; ++dx) all = mb[std::size_t(y + dy) * w + x + dx] != 0;
        seaPixels += all;
        n += all && !ma[std::size_t(y) * w + x];
      }
    return n;
  };

  constexpr int kFrames = 6;
  Steps mesh, hard;
  for (int f = 0; f < kFrames; ++f) {
    const double t = 30.0 + 3.7 * f;
    const bool keep = f == 0;
    const Frame a = drawWith(p, 2, t, keep ? "coarse" : ""), b = drawWith(p, 1, t, keep ? "fine" : ""),
                c = drawWith(p, 8, t, keep ? "coarse8" : "", false);
    if (f == 0) {
      std::printf("coarse blocks: %zu of 2 x 2, %zu of 8 x 8\n", a.blocks, c.blocks);
      ASSERT_GT(a.blocks, 100u) << "no middle-band mesh in the view";
    }
    int sea = 0;
    const int crack = cracks(a, b, cam, sea);
    if (f == 0) std::printf("beach: %d sea pixels (with their neighbours) in the fine frame\n", sea);
    EXPECT_GT(sea, w * h / 2);
    EXPECT_EQ(crack, 0) << "sea pixels left open by the coarse mesh, frame " << f;
    const Image cut = cutAt(b.im, c.im, bandR, edgeR);
    if (keep) gl::writePng(::testing::TempDir() + "/middle_mesh_hard.png", cut);
    const Bins fine = binStats(b.im, bin);
    mesh.add(a.im, fine, bin);
    hard.add(cut, fine, bin);
  }
  ocean->setMiddleMeshBlock(2);
  for (auto [name, st] : {std::pair{"coarse middle mesh", &mesh}, std::pair{"8 x 8 blocks cut in (hard)", &hard}}) {
    const auto [ml, sl] = meanSe(st->luma);
    const auto [mh, sh] = meanSe(st->hi);
    // Luma: half an 8-bit unit (Render.FarShadingBandEdgeHasNoStep's
    // bound; A differs from B only above the edge, so the frames' scatter
    // of A - B is small, and a step of 0.1 unit would be significant and
    // invisible); the detail: 3 standard errors of the frames' scatter.
    const bool lumaOk = std::abs(ml) < 0.5, hiOk = std::abs(mh) < 3.0 * sh;
    std::printf("%s: mean luma step %.3f (se %.3f), log detail step %.3f (se %.3f) over %d frames\n", name, ml, sl, mh,
                sh, kFrames);
    if (st == &mesh) {
      EXPECT_TRUE(lumaOk) << "mean luma steps by " << ml << " across the mesh edge (se " << sl << ")";
      EXPECT_TRUE(hiOk) << "the detail steps by " << mh << " across the mesh edge (se " << sh << ")";
    } else {
      EXPECT_FALSE(lumaOk && hiOk) << "the test cannot see a hard switch to a too coarse mesh";
    }
  }

  // Open water: 1.2 km off the shore (24 m deep and more), steeper, the
  // raster's water alone in sight.
  ViewPose o = p;
  o.lonDeg = kShoreLon - 1200.0 / 111320.0;
  o.pitchDeg = -35.0;
  const Frame a = drawWith(o, 2, 30.0, "open_coarse"), b = drawWith(o, 1, 30.0, "open_fine");
  int sea = 0;
  const int crack = cracks(a, b, renderer.camera(o), sea);
  std::printf("open water: %zu coarse blocks, %d sea pixels, %d cracks\n", a.blocks, sea, crack);
  EXPECT_GT(a.blocks, 100u);
  EXPECT_GT(sea, w * h / 2);
  EXPECT_EQ(crack, 0) << "sea pixels left open by the coarse mesh over open water";
}

}  // namespace geocean::render::test
