#include "perception/step_edge.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace fognav::perception {

double MeasureStepEdge(const StepEdgeParams& params, const std::vector<LabelledPoint>& points_G,
                       const Pose2& reference_G, double floor_z, double target_z) {
  if (!std::isfinite(floor_z) || !std::isfinite(target_z) || target_z == floor_z) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const bool up = target_z > floor_z;
  const double tread = up ? target_z : floor_z;
  const double c = std::cos(reference_G.yaw), s = std::sin(reference_G.yaw);
  std::vector<double> along, lower;  // points on the tread's level, and points below it
  for (const LabelledPoint& q : points_G) {
    const double dx = double(q.p_G.x()) - reference_G.x, dy = double(q.p_G.y()) - reference_G.y;
    const double u = c * dx + s * dy, v = -s * dx + c * dy;
    if (std::abs(v) > params.half_width || u < -params.behind || u > params.reach) continue;
    const bool on_tread =
        std::isfinite(q.h) && std::abs(double(q.h) - tread) <= params.level_tolerance;
    if (on_tread) {
      along.push_back(u);
    } else if (double(q.p_G.z()) < tread - params.level_tolerance) {
      lower.push_back(u);
    }
  }
  if (int(along.size()) < std::max(params.min_points, 1)) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  // points per bin along the heading; the edge is the first bin (stepping up; the last stepping
  // down) that holds a fair share of the tread's typical density, so that sparse points smeared
  // past the edge do not move it while the tread's own points are used whatever its depth
  const int num_bins = std::max(1, int(std::ceil((params.behind + params.reach) / params.bin)));
  std::vector<int> count(size_t(num_bins), 0);
  auto bin_of = [&](double u) {
    return std::clamp(int((u + params.behind) / params.bin), 0, num_bins - 1);
  };
  for (double u : along) ++count[size_t(bin_of(u))];
  std::vector<int> filled;
  for (int n : count) {
    if (n > 0) filled.push_back(n);
  }
  std::nth_element(filled.begin(), filled.begin() + std::ptrdiff_t(filled.size() / 2),
                   filled.end());
  const double dense = params.density_share * filled[filled.size() / 2];
  int edge_bin = -1;
  for (int i = 0; i < num_bins; ++i) {
    const int b = up ? i : num_bins - 1 - i;
    if (count[size_t(b)] >= dense) {
      edge_bin = b;
      break;
    }
  }
  // the outermost point of that bin
  double edge =
      up ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
  for (double u : along) {
    if (bin_of(u) == edge_bin) edge = up ? std::min(edge, u) : std::max(edge, u);
  }
  // the view must show what lies beyond the tread there (the riser or the floor before it
  // stepping up, the lower level stepping down): else the tread ends at the image's border
  const bool seen_beyond = std::any_of(lower.begin(), lower.end(), [&](double u) {
    return up ? u < edge && u >= edge - params.beyond : u > edge && u <= edge + params.beyond;
  });
  return seen_beyond ? edge : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace fognav::perception
