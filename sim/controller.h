// Kinematic stepping controller of the humanoid: footsteps, stairs, crawling and head motion.
//
// Each control tick sets the base pose and joint angles (no dynamics), runs MuJoCo's forward
// kinematics and collision detection, and checks the robot's contacts with the world. Motion
// commands are queued and executed one after another; Tick() advances one control period.
// Odometry is footstep dead reckoning: the believed pose integrates the commanded strides,
// while the executed footsteps are perturbed by seeded Gaussian noise.
#ifndef FOGNAV_SIM_CONTROLLER_H_
#define FOGNAV_SIM_CONTROLLER_H_

#include <array>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>
#include <mujoco/mujoco.h>

#include "geometry/pose2.h"
#include "sim/humanoid.h"
#include "sim/internal/gait.h"

namespace fognav::sim {

using fognav::Pose2;

// Per-stride limits of the motion commands, chosen for the 0.58 m model (legs 0.2 m).
// A stride moves the robot frame once: the leading foot steps, the other joins it.
struct StepLimits {
  double max_forward = 0.08;   // m per stride
  double max_backward = 0.04;  // m per stride
  double max_sideways = 0.05;  // m per stride
  double max_turn = 0.35;      // rad per stride (20 deg)
  double max_climb_forward = 0.16;  // m, forward length of a step onto a tread (StepOnto)
  double max_climb_height = 0.065;  // m, rise or drop of a tread (StepOnto)
  double max_climb_sideways = 0.03;  // m, part of a step onto a tread across the heading
  double max_crawl_forward = 0.06;  // m per crawl cycle (negative: backward, half of it)
  double max_crawl_turn = 0.25;     // rad per crawl cycle
};

struct ControllerParams {
  double control_rate_hz = 100;  // control ticks per second
  double step_time = 0.5;        // s per footstep
  double double_support = 0.2;   // share of a footstep with both feet down (half at each end)
  double stance_width = 0.09;    // m between the soles' centres
  double hip_height = 0.18;      // m from ankle to hip while standing (knees bent)
  double max_leg = 0.195;        // m, longest hip-to-ankle distance used (keeps knees bent)
  double swing_clearance = 0.025;  // m, swing sole above the higher surface (floor or tread)
  // Side-steps and turns in place lift the sole less: the knee comes forward as the foot lifts
  // (0.09 m ahead of the origin at 0.025 m, 0.081 m at 0.012 m), and these are the moves that
  // pass between blocks, facing one of them. They cross floor the planner holds level (within
  // its h_floor, 1.5 cm), so a sole meets at most 3 mm of a rise, within support_depth.
  double side_clearance = 0.012;   // m
  double pelvis_sway = 0.012;      // m, pelvis shift towards the stance foot
  double head_speed = 2.0;         // rad/s of neck pan and tilt
  double crawl_cycle_time = 2.0;   // s per crawl cycle (each limb swings once)
  double transition_time = 3.0;    // s to get down to crawling or to get up
  double squat_height = 0.165;     // m, pelvis above the floor in the squat of a transition
  double squat_pitch = 0.5;        // rad, pelvis pitched forward in the squat
  double kneel_toe_angle = 1.45;   // rad, feet pivot on their toes while the knees come down
  double kneel_pitch = 0.6;        // rad, pelvis pitch when the knees touch down
  internal::CrawlShape crawl;
  StepLimits limits;
  double odometry_noise_xy = 0;   // m, std-dev per footstep along each axis
  double odometry_noise_yaw = 0;  // rad, std-dev per footstep
  // systematic odometry error, drawn once per Reset from the seed: every stride's length is
  // scaled by 1 + s with s ~ N(0, stride_scale), every footstep turns by b ~ N(0, yaw_bias)
  double odometry_stride_scale = 0;  // std-dev of s (0.03: strides about 3 % off)
  double odometry_yaw_bias = 0;      // rad, std-dev of b
  unsigned seed = 0;                 // of the odometry noise
  double collision_depth = 0.005;  // m, deeper robot-world contacts are collisions
  double support_depth = 0.02;     // m, deeper support contacts (soles etc.) count too
};

// One collision: a robot geom entered a world geom deeper than collision_depth.
struct Collision {
  int tick = 0;
  int robot_geom = -1, world_geom = -1;
  std::string robot_name, world_name;  // geom names (world: geom, else its body's name)
  double depth = 0;                   // m, deepest penetration while the contact lasted
};

// Neck angles, radians: pan positive looks left, tilt positive looks down.
struct HeadAngles {
  double pan = 0, tilt = 0;
};

struct LookAroundParams {
  std::vector<double> pans = {-1.2, -0.6, 0.0, 0.6, 1.2};  // rad
  std::vector<double> tilts = {1.1, 0.55};                 // rad, near ring first
  // The near ring's views pan at most this far aside (rad). Looking down 1.1 rad and 1.2 rad
  // aside, arm and shoulder hid the floor beside the feet from one eye: on the course's start
  // views 53% of those pixels got a stereo point, 83% at 1.0 rad, 87% looking straight down.
  double near_pan_limit = 1.0;
};

// Head views that cover the floor around and ahead of the feet (back and forth in pan, the
// near ring first, within near_pan_limit), ending looking ahead. The mission runner perceives
// once at each view.
std::vector<HeadAngles> LookAroundSweep(const LookAroundParams& params = {});

enum class Mode { kStanding, kCrawling };

// The standing posture at `pose` (world) on a surface of height surface_z, head looking ahead:
// soles flat under the hips, knees bent, 0.58 m tall. Controller::Reset starts from it.
JointPosture StandingPostureAt(const Humanoid& h, const Pose2& pose, double surface_z,
                          const ControllerParams& params = {});

class Controller {
 public:
  // Looks the humanoid up in m (throws SimError if it is not there).
  Controller(const mjModel* m, const ControllerParams& params = {});

  // Stands the robot at `start` (world) on a surface of height surface_z, clears the queue
  // and collisions, and sets the believed pose to `start` (or to `believed` if given).
  void Reset(const Pose2& start, double surface_z, const mjModel* m, mjData* d);
  void Reset(const Pose2& start, double surface_z, const Pose2& believed, const mjModel* m, mjData* d);

  // Motion commands, queued. Displacements are in the robot frame at the start of the command.
  // Walk splits (dx, dy, dyaw) into equal strides within the limits; walking on level ground.
  void Walk(double dx, double dy, double dyaw);
  // One stride of dx forward (and dy to the left) onto a surface dz higher (negative: down)
  // than the current one, swinging the feet clear of the riser; dz comes from perception
  // (tread planes). Throws std::invalid_argument beyond max_climb_forward / max_climb_height /
  // max_climb_sideways.
  void StepOnto(double dx, double dz, double dy = 0.0);
  // Kneels down onto hands and knees (crawl posture, 0.28 m tall).
  void GetDown();
  // Crawls (dx, dyaw) in cycles within the crawl limits.
  void Crawl(double dx, double dyaw);
  // Gets up from crawling to standing.
  void GetUp();
  // How far ahead of the standing frame the crawling frame (the knees) lands on GetDown; GetUp
  // moves the frame back as far. Metres.
  double KneelOffset() const;
  // Turns the head to the given neck angles at head_speed (clamped to the joint ranges).
  void MoveHead(const HeadAngles& target);
  // Walk, StepOnto and GetDown need the robot standing, Crawl and GetUp crawling, at the end
  // of the queue; otherwise they throw std::logic_error.

  // True when the queue is empty.
  bool Idle() const { return queue_.empty(); }
  // The mode the robot is in (at the current tick).
  Mode mode() const { return mode_; }

  // One control tick: next posture, mj_kinematics, mj_camlight, mj_collision, collision check.
  void Tick(const mjModel* m, mjData* d);
  // Ticks until idle (or max_ticks); calls on_tick after each tick. Returns the ticks run.
  int RunUntilIdle(const mjModel* m, mjData* d, const std::function<void(int tick)>& on_tick = {},
                   int max_ticks = 1000000);

  // Footstep odometry: where the robot believes it is (odometry frame = world at Reset).
  const Pose2& believed_pose() const { return believed_; }
  // Replaces the believed pose with a localized one (odometry frame); later strides compose
  // onto it.
  void CorrectBelievedPose(const Pose2& pose) { believed_ = pose; }
  // Ground truth from MuJoCo's kinematics (for scoring): the robot frame in the world.
  Pose2 TruePose(const mjData* d) const;
  // Footsteps executed so far (each foot placement counts one; crawl cycles count 4).
  int steps() const { return steps_; }
  // Whether the last footstep completed a stride or crawl cycle: the feet (or knees and hands)
  // are where the believed pose says, up to the odometry's error. Mid-stride the believed pose
  // still holds the stride's start.
  bool settled() const { return settled_; }
  // The systematic errors drawn at Reset: the stride scale s and the yaw per footstep b (rad).
  double stride_scale_error() const { return stride_scale_error_; }
  double yaw_bias_error() const { return yaw_bias_error_; }
  int ticks() const { return tick_; }
  double dt() const { return 1.0 / params_.control_rate_hz; }

  // Collisions so far, in order of onset; a contact that lasts several ticks counts once.
  const std::vector<Collision>& collisions() const { return collisions_; }

  const Humanoid& humanoid() const { return humanoid_; }
  const ControllerParams& params() const { return params_; }
  // Planned placement of a sole at the end of the queue (world).
  const internal::FootPlacement& planned_foot(Side s) const { return plan_.feet[int(s)]; }

 private:
  enum class Kind { kStep, kHead, kTransition, kCrawlCycle };
  // One queued motion primitive, evaluated at a phase in [0, 1].
  struct Segment {
    Kind kind = Kind::kStep;
    int ticks = 1;
    Mode mode_after = Mode::kStanding;
    // kStep: feet before and after, the swinging side and its lift height
    std::array<internal::FootPlacement, 2> feet_from, feet_to;
    int swing = 0;
    double lift_z = 0;
    // kHead and the head during transitions
    HeadAngles head_from, head_to;
    // kTransition: the standing frame it starts (GetDown) or ends (GetUp) in
    internal::GroundFrame stand;
    bool getting_up = false;
    // kCrawlCycle: crawl frames before and after
    internal::GroundFrame crawl_from, crawl_to;
    // on completion: the commanded displacement (odometry) and the footsteps it counts
    Pose2 odometry;
    int steps = 0;
    bool settles = false;  // completes a stride or crawl cycle
  };
  // State of the robot at the end of the queue, for planning the next command.
  struct Plan {
    Mode mode = Mode::kStanding;
    std::array<internal::FootPlacement, 2> feet;
    internal::GroundFrame crawl;
    HeadAngles head;
  };

  void RequireMode(Mode mode, const char* command) const;
  void PushStride(double dx, double dy, double dyaw, double dz);
  internal::FootPlacement NoisyFoot(const internal::GroundFrame& frame, int side);
  JointPosture StandingPosture(const std::array<internal::FootPlacement, 2>& feet) const;
  JointPosture Evaluate(const Segment& seg, double u, HeadAngles* head) const;
  JointPosture StepPosture(const Segment& seg, double u) const;
  JointPosture CrawlCyclePosture(const Segment& seg, double u) const;
  JointPosture CrawlPostureAt(const internal::GroundFrame& frame) const;
  // kneeling down from the standing frame `stand`: s = 0 stands, s = 1 crawls
  JointPosture TransitionPosture(const internal::GroundFrame& stand, double s) const;
  void CheckContacts(const mjModel* m, const mjData* d);

  Humanoid humanoid_;
  ControllerParams params_;
  std::mt19937 rng_;
  double stride_scale_error_ = 0, yaw_bias_error_ = 0;
  bool settled_ = true;
  std::deque<Segment> queue_;
  int segment_tick_ = 0;  // ticks done in the front segment
  Plan plan_;
  Mode mode_ = Mode::kStanding;
  HeadAngles head_;
  JointPosture current_;
  Pose2 believed_;
  int steps_ = 0;
  int tick_ = 0;
  std::vector<Collision> collisions_;
  std::map<std::pair<int, int>, int> touching_;  // (robot geom, world geom) -> collision index
};

class Renderer;  // sim/render.h

// What a clip of a motion looks like: frames from an external camera that keeps its offset
// from the robot's position (not its heading) as set at the first frame.
struct ClipParams {
  std::string dir;                // written into, created if missing
  std::string prefix = "frame";   // files are <dir>/<prefix>_00000.png, ...
  int every = 5;                  // control ticks between frames
  int width_px = 320, height_px = 240;
  double hfov = 1.0;                                     // rad
  Eigen::Vector3d eye_R = Eigen::Vector3d(0.9, -1.0, 0.7);    // camera, robot frame at start
  Eigen::Vector3d target_R = Eigen::Vector3d(0.1, 0.0, 0.25);  // looked-at point, same frame
};

// Dumps a clip of the robot's motion for review: call it after every tick (it fits
// RunUntilIdle's on_tick through a lambda); it renders off-screen every `every` ticks.
class ClipRecorder {
 public:
  // Makes an off-screen renderer for m; throws SimError if it cannot, std::runtime_error if
  // dir cannot be created.
  ClipRecorder(const mjModel* m, const Humanoid& humanoid, ClipParams params);
  ~ClipRecorder();
  ClipRecorder(const ClipRecorder&) = delete;
  ClipRecorder& operator=(const ClipRecorder&) = delete;

  // Renders and writes a frame if tick is a multiple of `every` (d after Controller::Tick).
  void operator()(const mjModel* m, const mjData* d, int tick);
  int frames() const { return frames_; }

 private:
  const Humanoid* humanoid_;
  ClipParams params_;
  std::unique_ptr<Renderer> renderer_;
  bool anchored_ = false;
  Eigen::Vector3d eye_offset_W_, target_offset_W_;
  int frames_ = 0;
};

}  // namespace fognav::sim

#endif  // FOGNAV_SIM_CONTROLLER_H_
