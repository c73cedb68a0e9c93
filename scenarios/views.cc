#include "scenarios/views.h"

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "sim/controller.h"

namespace fognav::scenarios {

sim::WorldSpec MakeWorldSpec(const Scenario& scenario, bool with_robot) {
  sim::WorldSpec spec;
  spec.floor_size = scenario.floor_size;
  spec.floor_center = scenario.floor_center;
  spec.with_robot = with_robot;
  for (const Solid& solid : WorldSolids(scenario)) {
    spec.boxes.push_back({solid.name, solid.box.X_FB, solid.box.half_size});
  }
  return spec;
}

perception::CameraIntrinsics HeadIntrinsics(const SensorSettings& sensor) {
  auto camera = sim::PinholeCamera::FromFov(Eigen::Isometry3d::Identity(), sensor.width_px,
                                            sensor.height_px, sensor.hfov);
  perception::CameraIntrinsics k;
  k.width_px = sensor.width_px;
  k.height_px = sensor.height_px;
  k.fx = camera.fx;
  k.fy = camera.fy;
  k.cx = camera.cx;
  k.cy = camera.cy;
  k.baseline = sensor.baseline;
  return k;
}

Eigen::Isometry3d PlaceRobot(sim::World* world, const perception::Pose2& pose) {
  // the standing posture a mission starts from (throws SimError if there is no humanoid)
  sim::Controller controller(world->model());
  controller.Reset(pose, 0.0, world->model(), world->data());
  return sim::HeadCameraPoseInWorld(controller.humanoid(), world->data(), sim::Eye::kLeft);
}

StereoView RenderStereo(sim::Renderer* renderer, const sim::World& world,
                        const Eigen::Isometry3d& X_WL, const SensorSettings& sensor) {
  StereoView view;
  view.intrinsics = HeadIntrinsics(sensor);
  view.X_WL = X_WL;
  const int w = sensor.width_px, h = sensor.height_px;
  auto to_rgb = [&](const sim::RenderedView& r) {
    perception::RgbImage image(w, h);
    for (size_t i = 0; i < image.data.size(); ++i) {
      image.data[i] = {r.rgb[3 * i], r.rgb[3 * i + 1], r.rgb[3 * i + 2]};
    }
    return image;
  };
  auto left_camera = sim::PinholeCamera::FromFov(X_WL, w, h, sensor.hfov);
  sim::RenderedView left = renderer->Render(world.model(), world.data(), left_camera,
                                            {true, true, sensor.pixel_samples});
  auto right_camera = left_camera;
  right_camera.X_WC = X_WL * Eigen::Translation3d(sensor.baseline, 0, 0);
  sim::RenderedView right = renderer->Render(world.model(), world.data(), right_camera,
                                             {false, false, sensor.pixel_samples});
  view.left = to_rgb(left);
  view.right = to_rgb(right);
  view.depth.width = view.surfaces.width = w;
  view.depth.height = view.surfaces.height = h;
  view.depth.data = left.depth;
  view.surfaces.data.assign(left.surface_id.begin(), left.surface_id.end());
  return view;
}

Eigen::Isometry3d LookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  Eigen::Vector3d z = (target - eye).normalized();
  Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Vector3d y = z.cross(x);
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear() << x, y, z;
  X_WC.translation() = eye;
  return X_WC;
}

perception::RgbImage RenderOverview(sim::Renderer* renderer, const sim::World& world,
                                    const Scenario& scenario) {
  // behind the start, looking down the line from the start to the goal
  Eigen::Vector2d start(scenario.start.x, scenario.start.y);
  Eigen::Vector2d along = scenario.goal - start;
  double length = std::max(1.0, along.norm());
  along /= length;
  Eigen::Vector2d eye = start - 0.35 * length * along;
  Eigen::Vector2d target = start + 0.38 * length * along;
  auto camera = sim::PinholeCamera::FromFov(
      LookAt({eye.x(), eye.y(), 0.5 * length}, {target.x(), target.y(), 0.0}), 640, 400, 1.0);
  sim::RenderedView view = renderer->Render(world.model(), world.data(), camera, {false, false});
  perception::RgbImage image(view.width, view.height);
  for (size_t i = 0; i < image.data.size(); ++i) {
    image.data[i] = {view.rgb[3 * i], view.rgb[3 * i + 1], view.rgb[3 * i + 2]};
  }
  return image;
}

namespace {

void WriteImage(const std::string& path, const cv::Mat& image) {
  if (!cv::imwrite(path, image)) throw OutputError(path + ": could not write the image");
}

// a distinct, stable colour for each surface id
cv::Vec3b SurfaceColour(int id) {
  if (id < 0) return {0, 0, 0};
  uint32_t h = uint32_t(id) * 2654435761u;
  return {uint8_t(64 + (h & 0xbf)), uint8_t(64 + ((h >> 8) & 0xbf)), uint8_t(64 + ((h >> 16) & 0xbf))};
}

}  // namespace

void WritePng(const perception::RgbImage& image, const std::string& path) {
  cv::Mat mat(image.height, image.width, CV_8UC3);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const auto& p = image.at(u, v);
      mat.at<cv::Vec3b>(v, u) = {p.b, p.g, p.r};
    }
  }
  WriteImage(path, mat);
}

void WriteStereoView(const StereoView& view, const std::string& dir) {
  MakeOutputFolder(dir);
  const int w = view.left.width, h = view.left.height;
  WritePng(view.left, dir + "/left.png");
  WritePng(view.right, dir + "/right.png");
  cv::Mat depth_mm(h, w, CV_16UC1), surfaces(h, w, CV_8UC3);
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      float z = view.depth.at(u, v);
      depth_mm.at<uint16_t>(v, u) =
          std::isfinite(z) ? uint16_t(std::min(65535.0f, std::round(z * 1000.0f))) : 0;
      surfaces.at<cv::Vec3b>(v, u) = SurfaceColour(view.surfaces.at(u, v));
    }
  }
  WriteImage(dir + "/depth.png", depth_mm);
  WriteImage(dir + "/surfaces.png", surfaces);
  const auto& k = view.intrinsics;
  nlohmann::json intrinsics = {
      {"width", k.width_px}, {"height", k.height_px}, {"fx", k.fx},   {"fy", k.fy},
      {"cx", k.cx},          {"cy", k.cy},            {"baseline", k.baseline},
      {"convention", "OpenCV: x right, y down, z forward; pixel (u, v) centred at (u, v)"}};
  Eigen::Matrix4d X_WL = view.X_WL.matrix();
  for (int r = 0; r < 4; ++r) {
    intrinsics["X_WL"].push_back({X_WL(r, 0), X_WL(r, 1), X_WL(r, 2), X_WL(r, 3)});
  }
  WriteFileAtomically(dir + "/intrinsics.json", intrinsics.dump(2) + "\n");
}

}  // namespace fognav::scenarios
