// Synthetic range data of box worlds for the map tests and benchmarks: a perfect range sensor
// (ray casting analytic boxes) and a perfect segmentation (one plane per visible box face).
#ifndef FOGNAV_PERCEPTION_INTERNAL_MAP_SYNTHETIC_H_
#define FOGNAV_PERCEPTION_INTERNAL_MAP_SYNTHETIC_H_

#include <vector>

#include <Eigen/Geometry>

#include "perception/segmentation.h"
#include "perception/types.h"

namespace fognav::perception::internal {

// Pinhole intrinsics of a width x height image with the given horizontal field of view.
CameraIntrinsics MakeIntrinsics(int width, int height, double hfov_deg);

// Camera pose (OpenCV axes: x right, y down, z forward) at `eye` looking at `target`, world z up.
Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target);

// What a perfect range camera at X_WC sees of `solids_W`: the points in the camera frame (NaN
// where no box is hit within max_range) and a perfect segmentation, one plane per visible face
// (normals towards the camera, moments filled).
struct SyntheticFrame {
  PointImage points_C;
  PlaneSet planes;
};
SyntheticFrame RenderBoxes(const std::vector<OrientedBox>& solids_W, const Eigen::Isometry3d& X_WC,
                           const CameraIntrinsics& K, double max_range = 10.0);

// The plane a perfect segmentation gives of the vertical rectangle from floor point a to b
// (world x, y), 0 to `height` high, seen by a camera at X_WC: the moments of a 61 x 21 grid of
// its points in the camera frame, the normal towards the camera.
Plane WallPlane(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double height,
                const Eigen::Isometry3d& X_WC);

// A box with footprint [x0, x1] x [y0, y1] from z0 to z1, axis-aligned in the world.
OrientedBox AlignedBox(double x0, double x1, double y0, double y1, double z0, double z1);

// The paper's Fig. 9 world built in code: floor at z = 0 (a thin box, top at 0), a 3 cm level
// and an 11 cm level on it (three floor levels), a block whose rough top is 4 cm posts of
// random height (13 to 19 cm), and a table-like obstacle (slab from 0.38 to 0.42 m on four 4 cm
// legs, with 6 cm posts of random height on top). Object edges lie mid-cell on the default
// 4 cm grid. `seed` drives the post heights.
std::vector<OrientedBox> Fig9World(unsigned seed = 1);

// Camera poses that observe the Fig. 9 world fully: a ring at the standing camera height looking
// down at it, and low poses looking under the table.
std::vector<Eigen::Isometry3d> Fig9Cameras();

}  // namespace fognav::perception::internal

#endif  // FOGNAV_PERCEPTION_INTERNAL_MAP_SYNTHETIC_H_
