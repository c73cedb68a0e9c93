// Pure pieces of the stepping controller: foot placements, smooth profiles, the swing-foot
// and pelvis trajectories of one footstep, splitting a displacement into strides, and the
// whole-body postures of standing, walking and crawling from limb targets.
#ifndef FOGNAV_SIM_INTERNAL_GAIT_H_
#define FOGNAV_SIM_INTERNAL_GAIT_H_

#include <array>
#include <vector>

#include <Eigen/Geometry>

#include "sim/humanoid.h"

namespace fognav::sim::internal {

// A flat foot: sole centre in the world (z = the surface it stands on) and heading, radians.
struct FootPlacement {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  double yaw = 0;
};

// A planar frame on a surface: x, y, heading and the surface height z (world).
struct GroundFrame {
  double x = 0, y = 0, yaw = 0, z = 0;
  // The frame composed with a displacement (dx, dy, dyaw) expressed in it.
  GroundFrame Then(double dx, double dy, double dyaw) const;
  Eigen::Vector3d PointAt(double dx, double dy, double dz) const;
  Eigen::Isometry3d Isometry() const;
};

// Smooth 0 -> 1 ramp over [a, b] with zero slope at both ends (cubic smoothstep).
double SmoothRamp(double t, double a, double b);

// Angle a + s * (b - a) along the short way round.
double LerpAngle(double a, double b, double s);
double WrapAngle(double a);

// Swing-foot placement at swing phase u in [0, 1]: rises to lift_z over [0, 0.3], moves
// across over [0.25, 0.75], descends onto `to` over [0.7, 1]; the sole stays level.
FootPlacement SwingFoot(const FootPlacement& from, const FootPlacement& to, double lift_z, double u);

// Splits a displacement into n equal strides, n the least count within the per-stride limits.
int StrideCount(double dx, double dy, double dyaw, double max_forward, double max_backward,
                double max_sideways, double max_turn);

// Upper-body joint angles kept fixed while standing and walking (arms hanging).
void SetStandingArms(JointPosture* posture);

// Base pose and leg angles that put both soles at the given placements, with the pelvis
// upright at (p_xy, base_z) and heading `yaw`. Returns false if a foot was out of reach.
bool SolveStance(const Humanoid& h, const std::array<FootPlacement, 2>& feet, const Eigen::Vector2d& p_xy,
                 double base_z, double yaw, JointPosture* posture);

// Highest base height (world z) at which both ankles stay within `max_leg` of the hips for a
// pelvis upright at p_xy with heading yaw.
double MaxBaseHeight(const Humanoid& h, const std::array<FootPlacement, 2>& feet,
                     const Eigen::Vector2d& p_xy, double yaw, double max_leg);

// Crawl posture, relative to the crawl frame C (origin on the floor midway between the knees,
// x forward). Limb contact points are sphere centres (knee pads, hands).
struct CrawlShape {
  double base_x = 0.01;        // pelvis origin ahead of the knees, in C
  double base_pitch = 1.4;     // rad, pelvis pitched forward (1.57 = torso horizontal)
  double knee_y = 0.05;        // knee pads at (0, +-knee_y)
  double hand_x = 0.20;        // hands at (hand_x, +-hand_y)
  double hand_y = 0.10;
  double knee_angle = 1.85;    // rad, with the thigh vertical: shins slope up backwards
  double ankle_pitch = -0.1;   // rad, toes tucked under, just off the floor
  double neck_tilt = -1.4;     // rad, head raised against the torso's pitch to look ahead
  double limb_lift = 0.02;     // m, a swinging hand or knee rises this much
};

// Whole-body posture for crawling: base from the crawl frame X_WC and the shape, legs pointing
// the thighs at the knee targets, arms reaching the hand targets (all world points). The base
// height is chosen so the lowest knee target is met.
JointPosture CrawlPosture(const Humanoid& h, const CrawlShape& shape, const GroundFrame& frame,
                     const std::array<Eigen::Vector3d, 2>& knees_W,
                     const std::array<Eigen::Vector3d, 2>& hands_W,
                     const std::array<bool, 2>& knee_planted);

// Interpolates two postures: base position linearly, base rotation by slerp, joints linearly.
JointPosture LerpPosture(const JointPosture& a, const JointPosture& b, double s);

}  // namespace fognav::sim::internal

#endif  // FOGNAV_SIM_INTERNAL_GAIT_H_
