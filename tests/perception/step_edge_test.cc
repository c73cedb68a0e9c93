// The step edge from tread planes: stairs of analytic boxes seen by a perfect range camera with a
// perfect segmentation, at edges that lie anywhere within a 4 cm cell.
#include "perception/step_edge.h"

#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "perception/internal/map_synthetic.h"

namespace fognav::perception {
namespace {

using internal::AlignedBox;

const CameraIntrinsics kK = internal::MakeIntrinsics(176, 144, 45.0);

// Treads from `edge` along the robot's heading yaw (by default 0.25 m deep, 3 and 6 cm high),
// seen by the head camera 0.5 m up at `robot`, looking down at the floor 0.4 m ahead (the view's
// lower edge meets the floor 0.18 m ahead, its upper edge 0.78 m ahead).
struct Tread {
  double depth, height;
};
std::vector<LabelledPoint> StairsSeenFrom(const Pose2& robot, double edge, double yaw,
                                          const std::vector<Tread>& treads = {{0.25, 0.03},
                                                                              {0.25, 0.06}}) {
  // build the stairs in a frame along the heading, then rotate them into the grid frame
  const Eigen::Isometry3d X_GS = Planar({robot.x, robot.y, yaw});
  auto box = [&](double x0, double x1, double z1) {
    OrientedBox b = AlignedBox(x0, x1, -0.6, 0.6, z1 - 0.2, z1);
    b.X_FB = X_GS * b.X_FB;
    return b;
  };
  std::vector<OrientedBox> world = {box(-3, 3, 0.0)};
  double x = edge;
  for (const Tread& t : treads) {
    world.push_back(box(x, x + t.depth, t.height));
    x += t.depth;
  }
  const Eigen::Vector3d eye = X_GS * Eigen::Vector3d(0, 0, 0.5);
  const Eigen::Vector3d at = X_GS * Eigen::Vector3d(0.4, 0, 0.0);
  const Eigen::Isometry3d X_GC = internal::LookAt(eye, at);
  const internal::SyntheticFrame frame = internal::RenderBoxes(world, X_GC, kK);
  return LabelPoints(LabelParams{}, frame.points_C, frame.planes, X_GC, {});
}

TEST(StepEdge, FindsWhereTheUpperTreadBeginsAnywhereInACell) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> offset(0.0, 0.04), turn(-0.2, 0.2);
  for (int i = 0; i < 8; ++i) {
    const double edge = 0.24 + offset(rng), yaw = turn(rng);
    const Pose2 robot{0.3, -0.1, yaw};
    const std::vector<LabelledPoint> points = StairsSeenFrom(robot, edge, yaw);
    // measured from the robot, and from a pre-step pose 0.14 m further on
    EXPECT_NEAR(MeasureStepEdge({}, points, robot, 0.0, 0.03), edge, 0.005) << i;
    const Pose2 pre{robot.x + 0.14 * std::cos(yaw), robot.y + 0.14 * std::sin(yaw), yaw};
    EXPECT_NEAR(MeasureStepEdge({}, points, pre, 0.0, 0.03), edge - 0.14, 0.005) << i;
    // the second riser, from the first tread
    EXPECT_NEAR(MeasureStepEdge({}, points, pre, 0.03, 0.06), edge + 0.25 - 0.14, 0.005) << i;
    // where a single 0.15 m tread ends, stepping down to the floor beyond it
    const std::vector<LabelledPoint> block = StairsSeenFrom(robot, edge, yaw, {{0.15, 0.03}});
    EXPECT_NEAR(MeasureStepEdge({}, block, pre, 0.03, 0.0), edge + 0.15 - 0.14, 0.005) << i;
    // beyond the second tread's riser the floor is higher, not lower: no step down there
    EXPECT_TRUE(std::isnan(MeasureStepEdge({}, points, pre, 0.03, 0.0))) << i;
  }
}

TEST(StepEdge, NoMeasurementWithoutTheTreadInTheBand) {
  const Pose2 robot{0, 0, 0};
  const std::vector<LabelledPoint> points = StairsSeenFrom(robot, 0.25, 0.0);
  // no level 4.5 cm high; a tread beyond the reach; facing away
  EXPECT_TRUE(std::isnan(MeasureStepEdge({}, points, robot, 0.0, 0.045)));
  StepEdgeParams near;
  near.reach = 0.2;
  EXPECT_TRUE(std::isnan(MeasureStepEdge(near, points, robot, 0.0, 0.03)));
  EXPECT_TRUE(std::isnan(MeasureStepEdge({}, points, {0, 0, M_PI}, 0.0, 0.03)));
  EXPECT_TRUE(std::isnan(MeasureStepEdge({}, {}, robot, 0.0, 0.03)));
  // levels that are not finite, or the same
  EXPECT_TRUE(std::isnan(MeasureStepEdge({}, points, robot, 0.0, std::nan(""))));
  EXPECT_TRUE(std::isnan(MeasureStepEdge({}, points, robot, 0.03, 0.03)));
}

// A tread that runs out of the view's lower edge has no edge in the view.
TEST(StepEdge, TheImageBorderIsNoEdge) {
  const Pose2 robot{0, 0, 0};
  std::vector<LabelledPoint> points = StairsSeenFrom(robot, 0.10, 0.0);  // view begins at 0.18
  EXPECT_TRUE(std::isnan(MeasureStepEdge({}, points, robot, 0.0, 0.03)));
  // nor does the end of a tread that leaves the view's upper edge (0.73 m ahead on the tread),
  // looked at from a reference whose band holds it
  points = StairsSeenFrom(robot, 0.60, 0.0);
  const Pose2 on_tread{0.3, 0, 0};
  EXPECT_TRUE(std::isnan(MeasureStepEdge({}, points, on_tread, 0.03, 0.0)));
}

TEST(StepEdge, StrayPointsBeforeTheEdgeDoNotMoveIt) {
  const Pose2 robot{0, 0, 0};
  std::vector<LabelledPoint> points = StairsSeenFrom(robot, 0.26, 0.0);
  size_t on_tread = 0;
  for (const LabelledPoint& q : points) {
    on_tread += std::abs(q.h - 0.03f) < 0.005f && std::abs(q.p_G.y()) < 0.08f && q.p_G.x() < 0.5f;
  }
  // 2% of the tread's points in the band smeared up to 5 cm towards the robot, as stereo does
  // at an edge
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> where(0.21f, 0.26f), across(-0.08f, 0.08f);
  for (size_t i = 0; i < on_tread / 50; ++i) {
    LabelledPoint q;
    q.p_G = {where(rng), across(rng), 0.03f};
    q.h = 0.03f;
    points.push_back(q);
  }
  EXPECT_NEAR(MeasureStepEdge({}, points, robot, 0.0, 0.03), 0.26, 0.005);
}

}  // namespace
}  // namespace fognav::perception
