// The edge of a step the robot is about to climb, measured from the tread planes as the paper's
// stair-climbing module does (Section 6 and [Gutmann et al., 2004a]): the map's 4 cm cells place
// a riser only to within a cell, and stereo smears the upper tread's edge towards the robot by
// about as much, so a foot placed from the map can land with its heel over the edge or its toes
// on the next riser. The labelled points of one view carry their plane's height; the edge lies
// where the points of the upper level begin along the robot's heading (stepping up) or where
// those of the level it stands on end (stepping down).
#ifndef FOGNAV_PERCEPTION_STEP_EDGE_H_
#define FOGNAV_PERCEPTION_STEP_EDGE_H_

#include <vector>

#include "perception/mapping.h"
#include "perception/types.h"

namespace fognav::perception {

struct StepEdgeParams {
  double level_tolerance = 0.01;  // a point is on a level if its plane's height is this close
  double half_width = 0.08;       // half the band across the heading that is looked at (soles)
  double behind = 0.10;           // the band starts this far behind the reference origin...
  double reach = 0.50;            // ...and ends this far ahead of it, metres
  double bin = 0.005;             // the band is cut into bins this long along the heading
  double density_share = 0.25;    // a bin belongs to the tread if it holds this share of the
                                  // median points per non-empty bin (sparser bins are smear)
  int min_points = 40;            // fewer points of the tread in the band: no measurement
  // points lower than the tread (the riser or the floor before it stepping up, the lower level
  // stepping down) must lie within this distance beyond the edge (a drop's shadow is a few
  // centimetres), so that the border of the image is not taken for an edge
  double beyond = 0.06;
};

// Distance along the heading of `reference_G` from its origin to the edge between the level
// floor_z (where the robot stands) and target_z (the tread it steps onto), from the labelled
// points of one view (grid frame): stepping up (target_z > floor_z), where the points on
// target_z in the band begin along the heading; stepping down, where those on floor_z end;
// in both cases at the first dense bin, counted from that side. NaN when the band holds fewer
// than min_points of them, when no point lower than the tread lies within `beyond` on the far
// side of the edge, or when a level is not finite or both are the same.
double MeasureStepEdge(const StepEdgeParams& params, const std::vector<LabelledPoint>& points_G,
                       const Pose2& reference_G, double floor_z, double target_z);

}  // namespace fognav::perception

#endif  // FOGNAV_PERCEPTION_STEP_EDGE_H_
