#include "sim/world.h"

#include <iomanip>
#include <sstream>

namespace fognav::sim {
namespace {

// shades of the object materials; the texture's random marks give stereo something to match.
// MuJoCo projects a 2D texture along the box's z, so vertical faces show vertical streaks: they
// vary along image rows, which is what horizontal stereo matching needs (a cube map was tried
// and gives radial streaks that run along rows on tread tops).
constexpr const char* kObjectColours[] = {"0.85 0.55 0.35", "0.45 0.65 0.85", "0.55 0.8 0.45",
                                          "0.85 0.8 0.4",   "0.75 0.5 0.75",  "0.5 0.75 0.75"};

std::string Vec(const Eigen::Vector3d& v) {
  std::ostringstream out;
  out << std::setprecision(9) << v.x() << " " << v.y() << " " << v.z();
  return out.str();
}

}  // namespace

std::string WorldXml(const WorldSpec& spec) {
  // texels of 3.9 mm (a 512-texel texture per 2 m): finer ones alias at the close range of a
  // crawling robot's views (1.4 mm pixels at 0.3 m) into patterns that differ between the two
  // eyes, so stereo matches garbage there; on the course's start views this also halves the
  // median disparity error (0.10 -> 0.05 px)
  constexpr double kTexRepeatPerMetre = 0.5;
  std::ostringstream xml;
  xml << std::setprecision(9);
  xml << "<mujoco model=\"fognav_world\">\n";
  if (spec.with_robot) xml << "  <include file=\"humanoid.xml\"/>\n";
  // offscreen buffer large enough for the sensor sizes scenarios allow; no multisampling, so
  // that segmentation colours are exact ids
  xml << "  <visual>\n"
         "    <global offwidth=\"1280\" offheight=\"1024\"/>\n"
         "    <quality offsamples=\"0\" shadowsize=\"2048\"/>\n"
         "    <headlight ambient=\"0.45 0.45 0.45\" diffuse=\"0.5 0.5 0.5\" specular=\"0 0 0\"/>\n"
         "  </visual>\n";
  xml << "  <asset>\n"
         "    <texture name=\"fognav_floor_tex\" type=\"2d\" builtin=\"flat\" width=\"512\" height=\"512\"\n"
         "             rgb1=\"0.6 0.6 0.6\" rgb2=\"0.6 0.6 0.6\" mark=\"random\" random=\"0.45\"\n"
         "             markrgb=\"0.15 0.15 0.15\"/>\n"
         "    <texture name=\"fognav_object_tex\" type=\"2d\" builtin=\"flat\" width=\"512\" height=\"512\"\n"
         "             rgb1=\"1 1 1\" rgb2=\"1 1 1\" mark=\"random\" random=\"0.45\" markrgb=\"0.2 0.2 0.2\"/>\n"
         "    <material name=\"fognav_floor_mat\" texture=\"fognav_floor_tex\" texrepeat=\""
      << kTexRepeatPerMetre << " " << kTexRepeatPerMetre << "\"\n"
         "              texuniform=\"true\" specular=\"0\" shininess=\"0\" reflectance=\"0\"/>\n";
  for (size_t i = 0; i < std::size(kObjectColours); ++i) {
    xml << "    <material name=\"fognav_object_mat" << i
        << "\" texture=\"fognav_object_tex\" texrepeat=\"" << kTexRepeatPerMetre << " "
        << kTexRepeatPerMetre << "\" texuniform=\"true\" rgba=\""
        << kObjectColours[i] << " 1\" specular=\"0\" shininess=\"0\" reflectance=\"0\"/>\n";
  }
  xml << "  </asset>\n";
  xml << "  <worldbody>\n";
  xml << "    <light name=\"fognav_sun\" directional=\"true\" pos=\"0 0 5\" dir=\"0.3 0.2 -1\"\n"
         "           diffuse=\"0.45 0.45 0.45\" specular=\"0 0 0\" castshadow=\"false\"/>\n";
  xml << "    <geom name=\"floor\" type=\"plane\" pos=\"" << spec.floor_center.x() << " "
      << spec.floor_center.y() << " 0\" size=\"" << spec.floor_size.x() / 2 << " "
      << spec.floor_size.y() / 2 << " 0.05\" material=\"fognav_floor_mat\"/>\n";
  for (size_t i = 0; i < spec.boxes.size(); ++i) {
    const WorldBox& box = spec.boxes[i];
    Eigen::Quaterniond q(box.X_WB.rotation());
    xml << "    <geom name=\"obj:" << box.name << "\" type=\"box\" pos=\""
        << Vec(box.X_WB.translation()) << "\" quat=\"" << q.w() << " " << q.x() << " " << q.y()
        << " " << q.z() << "\" size=\"" << Vec(box.half_size) << "\" material=\"fognav_object_mat"
        << i % std::size(kObjectColours) << "\"/>\n";
  }
  xml << "  </worldbody>\n</mujoco>\n";
  return xml.str();
}

World::World(const WorldSpec& spec) : spec_(spec) {
  model_ = LoadModelFromXml(WorldXml(spec));
  data_ = MakeData(model_.get());
  mj_forward(model_.get(), data_.get());
  floor_geom_ = mj_name2id(model_.get(), mjOBJ_GEOM, "floor");
  for (const WorldBox& box : spec.boxes) {
    box_geoms_.push_back(mj_name2id(model_.get(), mjOBJ_GEOM, ("obj:" + box.name).c_str()));
  }
  robot_root_body_ = mj_name2id(model_.get(), mjOBJ_BODY, "robot_base");
}

bool World::IsRobotGeom(int geom_id) const {
  if (robot_root_body_ < 0 || geom_id < 0 || geom_id >= model_->ngeom) return false;
  return model_->body_rootid[model_->geom_bodyid[geom_id]] == robot_root_body_;
}

}  // namespace fognav::sim
