// A MuJoCo world built from plain geometry: a textured floor, textured boxes and (optionally)
// the shipped humanoid. Knows which geom is which, for ground truth and collision checks.
#ifndef FOGNAV_SIM_WORLD_H_
#define FOGNAV_SIM_WORLD_H_

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/model.h"

namespace fognav::sim {

// A solid box of the world: centre pose in the world frame and half extents.
struct WorldBox {
  std::string name;  // unique; becomes the geom name "obj:<name>"
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  Eigen::Vector3d half_size = Eigen::Vector3d::Zero();
};

struct WorldSpec {
  Eigen::Vector2d floor_size{8.0, 4.0};  // full extent x, y in metres; the floor is at z = 0
  Eigen::Vector2d floor_center{0.0, 0.0};
  std::vector<WorldBox> boxes;
  bool with_robot = true;  // include models/humanoid.xml
};

// The largest view the world's offscreen buffer holds, in pixels: every camera image a
// scenario asks for must fit.
constexpr int kMaxViewWidth = 1280, kMaxViewHeight = 1024;

// The MJCF text of a world (includes "humanoid.xml" when spec.with_robot).
std::string WorldXml(const WorldSpec& spec);

// A compiled world: MuJoCo model and data plus the geom ids of the floor and each box.
class World {
 public:
  // Compiles the world. Throws SimError if MuJoCo rejects it.
  explicit World(const WorldSpec& spec);

  const mjModel* model() const { return model_.get(); }
  mjModel* mutable_model() { return model_.get(); }
  mjData* data() { return data_.get(); }
  const mjData* data() const { return data_.get(); }
  const WorldSpec& spec() const { return spec_; }

  int floor_geom() const { return floor_geom_; }
  // geom id of spec().boxes[i] (a box in render group kSolidGroup: contacts, depth, surface ids)
  int box_geom(size_t i) const { return box_geoms_[i]; }
  // geom id of its skin (a textured mesh in kSkinGroup without contacts: what cameras see)
  int skin_geom(size_t i) const { return skin_geoms_[i]; }
  // true for geoms of the robot (bodies below the robot's root body)
  bool IsRobotGeom(int geom_id) const;

 private:
  WorldSpec spec_;
  ModelPtr model_;
  DataPtr data_;
  int floor_geom_ = -1;
  int robot_root_body_ = -1;
  std::vector<int> box_geoms_;
  std::vector<int> skin_geoms_;
};

}  // namespace fognav::sim

#endif  // FOGNAV_SIM_WORLD_H_
