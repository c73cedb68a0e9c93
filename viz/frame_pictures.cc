// Pictures of camera frames: segments and disparity.
#include <algorithm>
#include <cmath>

#include "viz/pictures.h"

namespace fognav::viz {

using perception::Rgb;
using perception::RgbImage;

RgbImage DrawSegments(const perception::PlaneSet& planes) {
  const perception::LabelImage& lab = planes.labels;
  RgbImage out(lab.width, lab.height, Rgb{255, 255, 255});
  // distinct colours by golden-ratio hue steps, bright and saturated
  auto colour = [](int k) {
    const double hue = std::fmod(0.13 + 0.618033988749895 * k, 1.0) * 6.0;
    const double sat = (k % 3 == 2) ? 0.45 : 0.75, val = (k % 2) ? 0.8 : 0.97;
    const int sector = int(hue);
    const double f = hue - sector;
    const double pp = val * (1 - sat), q = val * (1 - sat * f), t = val * (1 - sat * (1 - f));
    double r = 0, g = 0, b = 0;
    switch (sector % 6) {
      case 0: r = val, g = t, b = pp; break;
      case 1: r = q, g = val, b = pp; break;
      case 2: r = pp, g = val, b = t; break;
      case 3: r = pp, g = q, b = val; break;
      case 4: r = t, g = pp, b = val; break;
      default: r = val, g = pp, b = q; break;
    }
    return Rgb{uint8_t(255 * r), uint8_t(255 * g), uint8_t(255 * b)};
  };
  for (int v = 0; v < lab.height; ++v) {
    for (int u = 0; u < lab.width; ++u) {
      const int k = lab.at(u, v);
      if (k < 0) continue;
      // a border pixel has a 4-neighbour outside its plane
      const bool border = u == 0 || v == 0 || u + 1 == lab.width || v + 1 == lab.height ||
                          lab.at(u - 1, v) != k || lab.at(u + 1, v) != k ||
                          lab.at(u, v - 1) != k || lab.at(u, v + 1) != k;
      out.at(u, v) = border ? Rgb{0, 0, 0} : colour(k);
    }
  }
  return out;
}

RgbImage DrawDisparity(const perception::Image<float>& disparity_px) {
  RgbImage out(disparity_px.width, disparity_px.height);
  float max_disp = 0;
  for (float d : disparity_px.data)
    if (std::isfinite(d)) max_disp = std::max(max_disp, d);
  if (max_disp <= 0) return out;
  // jet colour map over [0, max]: blue (far) -> cyan -> yellow -> red (near)
  auto channel = [](double x) {
    return uint8_t(std::lround(255 * std::clamp(1.5 - std::abs(x), 0.0, 1.0)));
  };
  for (size_t i = 0; i < out.data.size(); ++i) {
    const float d = disparity_px.data[i];
    if (!std::isfinite(d)) continue;
    const double t = 4.0 * d / max_disp;
    out.data[i] = Rgb{channel(t - 3), channel(t - 2), channel(t - 1)};
  }
  return out;
}

}  // namespace fognav::viz
