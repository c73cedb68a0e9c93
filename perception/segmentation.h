// Stereo range data and plane segmentation by extended scan-line grouping (paper Section 3),
// and its score against ground-truth surfaces.
#ifndef FOGNAV_PERCEPTION_SEGMENTATION_H_
#define FOGNAV_PERCEPTION_SEGMENTATION_H_

#include <vector>

#include <Eigen/Core>

#include "perception/types.h"

namespace fognav::perception {

// A planar region found in a point image (paper Section 3.5: P_i = (n, d, N, b, A, B)).
// Camera frame: points p on the plane satisfy p . n = d.
struct Plane {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();  // unit normal, pointing towards the camera
  double d = 0;                                  // signed distance to the origin, metres
  int num_points = 0;                            // N
  Eigen::Vector3d b = Eigen::Vector3d::Zero();   // sum of points
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();   // sum of p p^T
  // Border per scan line: for each row v of the image the plane touches, the first and
  // last column (inclusive) of its pixels on that row.
  struct RowSpan {
    int v = 0, u_begin = 0, u_end = 0;
  };
  std::vector<RowSpan> border;
};

// The planes of one point image and a label image of the same size: the index of the plane
// each pixel belongs to, or -1 for none.
struct PlaneSet {
  std::vector<Plane> planes;
  LabelImage labels;
};

}  // namespace fognav::perception

#endif  // FOGNAV_PERCEPTION_SEGMENTATION_H_
