// The island table of the coast field (issue 15 item 2, paper 003 sec. 3),
// ONE source for the CPU (plugin/waves/CoastField.cpp, through the kd::Kernel
// of WaveKernel.h, WR = double) and the GPU (shaders/coast_islands_comp.glsl,
// WR = float). Per node and Gerstner component: (D_blo, theta_blo, D_obs,
// theta_def).
//  - Blocking (eq. 7): the sector of +-30 degrees toward the propagation
//    direction sampled at radius lambda / 2; the highest sample above the
//    node's bottom gives theta_blo, D_blo = sec(theta_blo). Kept in the
//    table; the kernel refracts with the eikonal's Snell turning and Kr
//    instead (applying both would refract twice).
//  - Occlusion (eq. 8-9, the paper's sector test toward the reverse
//    direction, counting land samples by side): rays in WV_ISL_DIRS
//    directions over the circle find the nearest land; the open directions
//    within +-75 degrees of the reverse direction are summed with Fresnel's
//    weights exp(i pi v^2 / 2) dv, v = tan(phi) sqrt(2 rho / lambda) (rho:
//    the distance to the nearest shadowing edge along the propagation,
//    lambda: the local wavelength), so D_obs = |sum open| / |sum all| is the
//    Fresnel-Kirchhoff amplitude behind an edge: 1/2 on the shadow line,
//    falling into the shadow, faster for shorter waves (and so lower in
//    shallower water). Land hits fade out between R/2 and R, so the shadow
//    recovers with distance behind an island. theta_def: the directions'
//    mean angle weighted by their share of the amplitude (toward the edge
//    in the shadow: the wrap-around). (1, 0, 1, 0) exactly where no land
//    is within R: the deep sea keeps its bits.
// The includer declares WR wvIslandElev[] (node elevation, m, > 0: land),
// int wvIslandLandSat[] (the land nodes' summed-area table, (n + 1)^2),
// WR4 wvIslandComps[] (travel direction x, y in the grid, omega, 0) and
// WR4 wvIslandTable[] and WR wvIslandShadow[] (out, component-major like
// wvCoastTexels; the shadow weight: how far D_obs replaces the eikonal's Kr).
#ifndef COAST_ISLANDS_GLSL
#define COAST_ISLANDS_GLSL

#define WV_ISL_DIRS 256
#define WV_ISL_HALF_RAD 1.3089969389957472  // 75 degrees
#define WV_ISL_BLO_RAD 0.52359877559829887  // 30 degrees
#define WV_ISL_BLO_N 9
#define WV_ISL_STEPS 128

// Fresnel's integrals (C(x), S(x), 0, 0), int_0^x of cos / sin(pi t^2 / 2):
// Abramowitz & Stegun 7.3.9-10 with the rational f, g of 7.3.32-33 (error
// <= 2e-3, well inside the table's use).
WR4 wv_fresnelCS(WR x) {
  WR ax = abs(x);
  WR f = (WR(1) + WR(0.926) * ax) / (WR(2) + WR(1.792) * ax + WR(3.104) * ax * ax);
  WR g = WR(1) / (WR(2) + ax * (WR(4.142) + ax * (WR(3.492) + ax * WR(6.670))));
  WR a = WR(0.5 * WV_PI) * ax * ax;
  WR cs = WR(0.5) + f * sin(a) - g * cos(a), sn = WR(0.5) - f * cos(a) - g * sin(a);
  WR sg = x < WR(0) ? WR(-1) : WR(1);
  return WR4(sg * cs, sg * sn, WR(0), WR(0));
}

// Distance (cells) to the first land node along direction (cx, cy) from
// node (i, j), in half-cell steps up to rCells (at most WV_ISL_STEPS steps:
// on fine grids land is many cells wide); -1 if none (leaving the grid
// counts as open sea).
WR wv_islandHit(int n, int i, int j, WR cx, WR cy, WR rCells) {
  int steps = min(int(rCells * WR(2)), WV_ISL_STEPS);
  WR dt = rCells / WR(steps);
  for (int s = 1; s <= steps; ++s) {
    WR t = dt * WR(s);
    int ix = i + int(floor(t * cx + WR(0.5))), iy = j + int(floor(t * cy + WR(0.5)));
    if (ix < 0 || iy < 0 || ix >= n || iy >= n) return WR(-1);
    if (wvIslandElev[iy * n + ix] > WR(0)) return t;
  }
  return WR(-1);
}

// The table at node (i, j) for `comps` components; cellM: node spacing (m),
// rCells: the occlusion radius (nodes). Writes wvIslandTable[(c n + j) n + i].
void wv_islandNode(int n, int i, int j, int comps, WR cellM, WR rCells) {
  int p = j * n + i;
  WR elevP = wvIslandElev[p];
  WR depth = max(-elevP, WR(0.05));
  // Rays only where land is within the radius (summed-area box), each
  // direction traced on first use (-2: not yet).
  int rb = int(ceil(rCells)) + 1;
  int x0 = max(i - rb, 0), y0 = max(j - rb, 0), x1 = min(i + rb + 1, n), y1 = min(j + rb + 1, n);
  int m = n + 1;
  int land = wvIslandLandSat[y1 * m + x1] - wvIslandLandSat[y0 * m + x1] - wvIslandLandSat[y1 * m + x0] +
             wvIslandLandSat[y0 * m + x0];
  bool anyHit = elevP <= WR(0) && land > 0;
  WR hits[WV_ISL_DIRS];
  for (int d = 0; d < WV_ISL_DIRS; ++d) hits[d] = WR(-2);
  WR dA = WR(2.0 * WV_PI) / WR(WV_ISL_DIRS);
  for (int c = 0; c < comps; ++c) {
    WR4 comp = wvIslandComps[c];
    WR omega = comp.z;
    WR kDeep = omega * omega / WR(WV_G);
    WR k = kDeep * depth < WR(WV_DEEP_KH) ? wv_waveNumber(omega, depth) : kDeep;
    WR lambda = WR(2.0 * WV_PI) / k;
    WR4 outV = WR4(1, 0, 1, 0);
    WR shadow = WR(0);
    WR aProp = atan(comp.y, comp.x);
    // Blocking (eq. 7), only where the wave feels the bottom.
    if (elevP <= WR(0) && kDeep * depth < WR(WV_DEEP_KH)) {
      WR rBlo = max(WR(0.5) * lambda / cellM, WR(1));
      WR best = elevP, bestA = WR(0);
      for (int s = 0; s < WV_ISL_BLO_N; ++s) {
        WR da = WR(WV_ISL_BLO_RAD) * (WR(2) * WR(s) / WR(WV_ISL_BLO_N - 1) - WR(1));
        int ix = i + int(floor(rBlo * cos(aProp + da) + WR(0.5))), iy = j + int(floor(rBlo * sin(aProp + da) + WR(0.5)));
        if (ix < 0 || iy < 0 || ix >= n || iy >= n) continue;
        WR e = wvIslandElev[iy * n + ix];
        if (e > best) {
          best = e;
          bestA = da;
        }
      }
      outV.x = WR(1) / cos(bestA);
      outV.y = bestA;
    }
    if (anyHit) {
      WR aRev = aProp + WR(WV_PI);
      // Nearest shadowing edge along the propagation: a land direction next
      // to an open one (else the nearest land at all).
      WR rhoEdge = WR(1e30), rhoAny = WR(1e30);
      int dLo = int(floor((aRev - WR(WV_ISL_HALF_RAD)) / dA)), dHi = int(floor((aRev + WR(WV_ISL_HALF_RAD)) / dA)) + 1;
      for (int dd = dLo - 1; dd <= dHi + 1; ++dd) {
        int d = ((dd % WV_ISL_DIRS) + WV_ISL_DIRS) % WV_ISL_DIRS;
        if (hits[d] > WR(-1.5)) continue;
        WR a = (WR(d) + WR(0.5)) * dA;
        hits[d] = wv_islandHit(n, i, j, cos(a), sin(a), rCells);
      }
      for (int dd = dLo; dd <= dHi; ++dd) {
        int d = ((dd % WV_ISL_DIRS) + WV_ISL_DIRS) % WV_ISL_DIRS;
        WR phi = (WR(d) + WR(0.5)) * dA - aRev;
        phi -= WR(2.0 * WV_PI) * floor(phi / WR(2.0 * WV_PI) + WR(0.5));
        if (abs(phi) > WR(WV_ISL_HALF_RAD) || hits[d] < WR(0)) continue;
        WR rho = hits[d] * cellM * cos(phi);
        rhoAny = min(rhoAny, rho);
        int dm = (d + WV_ISL_DIRS - 1) % WV_ISL_DIRS, dp = (d + 1) % WV_ISL_DIRS;
        if (hits[dm] < WR(0) || hits[dp] < WR(0)) rhoEdge = min(rhoEdge, rho);
      }
      if (rhoAny < WR(1e30)) {
        WR rho = max(rhoEdge < WR(1e30) ? rhoEdge : rhoAny, WR(0.25) * cellM);
        WR sc = sqrt(WR(2) * rho / lambda);
        // U = E(+inf) - E(-inf) - sum over land bins of (1 - open) (E(v1) - E(v0)):
        // each direction bin integrated exactly (the integrand turns faster
        // than the bins far out), directions beyond the window open.
        WR uRe = WR(1), uIm = WR(1), bRe = WR(0), bIm = WR(0), fRe = WR(0), fIm = WR(0);
        WR rM = rCells * cellM;
        for (int dd = dLo; dd <= dHi; ++dd) {
          int d = ((dd % WV_ISL_DIRS) + WV_ISL_DIRS) % WV_ISL_DIRS;
          WR phi = (WR(d) + WR(0.5)) * dA - aRev;
          phi -= WR(2.0 * WV_PI) * floor(phi / WR(2.0 * WV_PI) + WR(0.5));
          if (abs(phi) > WR(WV_ISL_HALF_RAD)) continue;
          WR4 e0 = wv_fresnelCS(tan(phi - WR(0.5) * dA) * sc), e1 = wv_fresnelCS(tan(phi + WR(0.5) * dA) * sc);
          WR gRe = e1.x - e0.x, gIm = e1.y - e0.y;
          // Open, or land far enough away to let the wave around it.
          WR open = hits[d] < WR(0) ? WR(1) : smoothstep(WR(0.5) * rM, rM, hits[d] * cellM);
          bRe += (WR(1) - open) * gRe;
          bIm += (WR(1) - open) * gIm;
          fRe += open * gRe * phi;
          fIm += open * gIm * phi;
        }
        uRe -= bRe;
        uIm -= bIm;
        WR u2 = uRe * uRe + uIm * uIm;
        outV.z = sqrt(u2 * WR(0.5));
        // Re(conj(U) * sum(open g phi)) / |U|^2: the arriving energy's mean angle.
        outV.w = u2 > WR(1e-30) ? clamp((uRe * fRe + uIm * fIm) / u2, -WR(WV_ISL_HALF_RAD), WR(WV_ISL_HALF_RAD))
                                : WR(0);
        // How much of the first Fresnel zones the land takes (0 .. 1): there
        // the ray-tube Kr of the eikonal has no meaning and D_obs replaces it.
        shadow = min(WR(1), sqrt(WR(2) * (bRe * bRe + bIm * bIm)));
      }
    }
    wvIslandShadow[(c * n + j) * n + i] = shadow;
    wvIslandTable[(c * n + j) * n + i] = outV;
  }
}

#endif
