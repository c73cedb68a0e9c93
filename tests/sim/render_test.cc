#include "sim/render.h"

#include <cmath>
#include <map>
#include <vector>

#include <gtest/gtest.h>

#include "sim/world.h"

namespace fognav::sim {
namespace {

// camera at (0, 0, h) looking along world +x (OpenCV: z forward = world x, x right = -world y)
Eigen::Isometry3d LookAlongX(double height) {
  Eigen::Matrix3d R_WC;
  R_WC.col(0) = -Eigen::Vector3d::UnitY();
  R_WC.col(1) = -Eigen::Vector3d::UnitZ();
  R_WC.col(2) = Eigen::Vector3d::UnitX();
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear() = R_WC;
  X_WC.translation() = Eigen::Vector3d(0, 0, height);
  return X_WC;
}

WorldBox Box(const std::string& name, const Eigen::Vector3d& center, const Eigen::Vector3d& half,
             double yaw = 0) {
  WorldBox box;
  box.name = name;
  box.X_WB = Eigen::Translation3d(center) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  box.half_size = half;
  return box;
}

// A world without the robot: the floor centred 2 m ahead of the origin and one box.
WorldSpec OneBoxWorld(const WorldBox& box) {
  WorldSpec spec;
  spec.with_robot = false;
  spec.floor_center = {2, 0};
  spec.boxes.push_back(box);
  return spec;
}

// A wall whose face lies at x = 1.0 exactly, seen head-on from the eyes' height at 176x144.
WorldSpec WallAtOneMetre() { return OneBoxWorld(Box("wall", {1.25, 0, 1.0}, {0.25, 2.0, 1.0})); }

RenderedView ViewAlongX(const World& world) {
  Renderer renderer(world.model());
  auto camera = PinholeCamera::FromFov(LookAlongX(0.5), 176, 144, M_PI / 4);
  return renderer.Render(world.model(), world.data(), camera);
}

TEST(Render, DepthOfAWallAtOneMetreWithinTwoMillimetres) {
  const World world(WallAtOneMetre());
  const RenderedView view = ViewAlongX(world);
  int checked = 0;
  for (int v = 0; v < view.height; v += 7) {
    for (int u = 0; u < view.width; u += 7) {
      float z = view.depth[size_t(v) * view.width + u];
      ASSERT_TRUE(std::isfinite(z));
      // pixels on the wall (the floor shows only below the horizon, beyond 1 m never)
      if (view.surface_id[size_t(v) * view.width + u] / kSurfacesPerGeom == world.box_geom(0)) {
        EXPECT_NEAR(z, 1.0, 0.002) << "pixel " << u << "," << v;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 200);
}

// Stereo needs texture on every face. MuJoCo's own mapping of a 2D texture onto a box
// projects it along the box's z, so side faces showed streaks: no change down an image column.
// A box's skin textures each face in its own plane, so a side face seen head-on varies along
// both image axes, about as much down a column as along a row.
TEST(Render, ABoxSideFaceIsTexturedAlongBothImageAxes) {
  const World world(WallAtOneMetre());
  const RenderedView view = ViewAlongX(world);
  auto on_wall = [&](int u, int v) {
    return SurfaceGeom(view.surface_id[size_t(v) * view.width + u]) == world.box_geom(0);
  };
  auto grey = [&](int u, int v) {
    const uint8_t* c = &view.rgb[(size_t(v) * view.width + u) * 3];
    return (int(c[0]) + int(c[1]) + int(c[2])) / 3.0;
  };
  double along_row = 0, down_column = 0;
  int pairs = 0;
  for (int v = 0; v + 1 < view.height; ++v) {
    for (int u = 0; u + 1 < view.width; ++u) {
      if (!on_wall(u, v) || !on_wall(u + 1, v) || !on_wall(u, v + 1)) continue;
      along_row += std::abs(grey(u + 1, v) - grey(u, v));
      down_column += std::abs(grey(u, v + 1) - grey(u, v));
      ++pairs;
    }
  }
  ASSERT_GT(pairs, 5000);
  along_row /= pairs;
  down_column /= pairs;
  EXPECT_GT(along_row, 3.0);
  EXPECT_GT(down_column, 0.6 * along_row) << "along rows " << along_row;
  EXPECT_LT(down_column, along_row / 0.6) << "along rows " << along_row;
}

TEST(Render, SurfaceIdsNameTheFacesOfABox) {
  // a box turned 45 degrees: the camera sees its -x and +y faces side by side, and its top
  World world(OneBoxWorld(Box("cube", {1.5, 0, 0.15}, {0.15, 0.15, 0.15}, M_PI / 4)));
  Renderer renderer(world.model());
  auto camera = PinholeCamera::FromFov(LookAlongX(0.5), 176, 144, M_PI / 4);
  RenderedView view = renderer.Render(world.model(), world.data(), camera);
  const int geom = world.box_geom(0);
  // project known points on the faces into the image and check the id there
  auto id_at = [&](const Eigen::Vector3d& p_W) {
    Eigen::Vector3d p_C = camera.X_WC.inverse() * p_W;
    int u = int(std::lround(camera.fx * p_C.x() / p_C.z() + camera.cx));
    int v = int(std::lround(camera.fy * p_C.y() / p_C.z() + camera.cy));
    EXPECT_TRUE(u >= 0 && v >= 0 && u < view.width && v < view.height) << p_W.transpose();
    if (u < 0 || v < 0 || u >= view.width || v >= view.height) return -2;
    return view.surface_id[size_t(v) * view.width + u];
  };
  // box-frame points (-0.15, -0.05) on the -x face and (0.05, 0.15) on the +y face, turned by
  // 45 degrees about the box centre (1.5, 0)
  const Eigen::Rotation2Dd R_WB(M_PI / 4);
  Eigen::Vector2d on_minus_x = Eigen::Vector2d(1.5, 0) + R_WB * Eigen::Vector2d(-0.15, -0.05);
  Eigen::Vector2d on_plus_y = Eigen::Vector2d(1.5, 0) + R_WB * Eigen::Vector2d(0.05, 0.15);
  EXPECT_EQ(id_at({on_minus_x.x(), on_minus_x.y(), 0.15}), geom * kSurfacesPerGeom + 1);
  EXPECT_EQ(id_at({on_plus_y.x(), on_plus_y.y(), 0.15}), geom * kSurfacesPerGeom + 2);
  EXPECT_EQ(id_at({1.5, 0, 0.30}), geom * kSurfacesPerGeom + 4);  // top
  EXPECT_EQ(id_at({2.0, 0.3, 0.0}), world.floor_geom() * kSurfacesPerGeom + kWholeGeomSurface);
  // far above the horizon there is nothing
  EXPECT_EQ(view.surface_id[0], -1);
  EXPECT_TRUE(std::isnan(view.depth[0]));
}

// Every surface carries texture for stereo to match, seen close (0.3 m, as a crawling robot's
// eyes) and far (2.5 m): on each face of a box and on the floor the grey level varies between
// horizontal neighbours (the matching direction), standard deviation of the difference at
// least 4 grey levels (rendered: 11 to 27).
TEST(Render, EverySurfaceIsTexturedNearAndFar) {
  for (double distance : {0.3, 2.5}) {
    // a box turned 30 degrees: two side faces and the top in view
    const double half = distance < 1 ? 0.05 : 0.3;
    World world(
        OneBoxWorld(Box("cube", {distance + half * 1.5, 0, half}, {half, half, half}, M_PI / 6)));
    Renderer renderer(world.model());
    Eigen::Isometry3d X_WC = LookAlongX(distance < 1 ? 0.2 : 0.9);
    X_WC.linear() = X_WC.linear() * Eigen::AngleAxisd(-0.35, Eigen::Vector3d::UnitX()).matrix();
    auto camera = PinholeCamera::FromFov(X_WC, 176, 144, M_PI / 4);
    RenderedView view = renderer.Render(world.model(), world.data(), camera);
    std::map<int, std::vector<double>> differences;  // per surface
    for (int v = 0; v < view.height; ++v) {
      for (int u = 0; u + 1 < view.width; ++u) {
        const size_t i = size_t(v) * view.width + u;
        if (view.surface_id[i] < 0 || view.surface_id[i] != view.surface_id[i + 1]) continue;
        auto grey = [&](size_t k) {
          return (view.rgb[3 * k] + view.rgb[3 * k + 1] + view.rgb[3 * k + 2]) / 3.0;
        };
        differences[view.surface_id[i]].push_back(grey(i + 1) - grey(i));
      }
    }
    int surfaces = 0;
    for (const auto& [id, d] : differences) {
      // surfaces seen edge-on (the top at 2.5 m) blur into their mean: not enough to judge
      if (d.size() < 500) continue;
      double sum2 = 0;
      for (double x : d) sum2 += x * x;
      EXPECT_GT(std::sqrt(sum2 / double(d.size())), 4.0) << "surface " << id << " at " << distance;
      ++surfaces;
    }
    EXPECT_GE(surfaces, 3) << distance;  // the floor and at least two faces
  }
}

TEST(Render, IntrinsicsReprojectAKnownPointWithinHalfAPixel) {
  // a small marker box; its top-front corner is a known 3D point
  World world(OneBoxWorld(Box("marker", {1.6, 0.25, 0.35}, {0.1, 0.1, 0.05})));
  Renderer renderer(world.model());
  // an off-centre principal point and a non-square image exercise the frustum
  PinholeCamera camera = PinholeCamera::FromFov(LookAlongX(0.45), 200, 120, 0.9);
  camera.cx += 7.0;
  camera.cy -= 4.0;
  RenderedView view = renderer.Render(world.model(), world.data(), camera);
  // the image column where the marker's left edge (world y = 0.35) starts on row of its front face
  Eigen::Vector3d p_W(1.5, 0.35, 0.35);  // centre of the front face's left edge
  Eigen::Vector3d p_C = camera.X_WC.inverse() * p_W;
  double u_expected = camera.fx * p_C.x() / p_C.z() + camera.cx;
  int v = int(std::lround(camera.fy * p_C.y() / p_C.z() + camera.cy));
  // find the first pixel from the left on row v that shows the marker
  const int geom = world.box_geom(0);
  int u_first = -1;
  for (int u = 0; u < view.width; ++u) {
    if (SurfaceGeom(view.surface_id[size_t(v) * view.width + u]) == geom) {
      u_first = u;
      break;
    }
  }
  ASSERT_GE(u_first, 0);
  // the edge lies between the centres of the last background pixel and the first marker pixel
  EXPECT_NEAR(u_first - 0.5, u_expected, 0.5 + 1e-6);
  // and the depth there is the front face's distance
  EXPECT_NEAR(view.depth[size_t(v) * view.width + u_first + 2], 1.5, 0.002);
}

// With pixel_samples k each pixel gathers its whole area: it is the mean of the k x k pixels of
// a view k times as fine of the same field, while depth and surface ids stay those of the pixel
// centres. A box turned 30 degrees in front of the floor gives edges and texture finer than a
// pixel.
TEST(Render, PixelSamplesAverageTheirPixelsArea) {
  World world(OneBoxWorld(Box("cube", {1.8, 0.1, 0.25}, {0.25, 0.25, 0.25}, M_PI / 6)));
  Renderer renderer(world.model());
  const Eigen::Isometry3d X_WC = LookAlongX(0.5);
  const int w = 176, h = 144, k = 3;
  const auto camera = PinholeCamera::FromFov(X_WC, w, h, M_PI / 4);
  const RenderedView point = renderer.Render(world.model(), world.data(), camera);
  const RenderedView area = renderer.Render(world.model(), world.data(), camera, {true, true, k});
  const RenderedView fine = renderer.Render(world.model(), world.data(),
                                            PinholeCamera::FromFov(X_WC, k * w, k * h, M_PI / 4),
                                            {false, false});
  ASSERT_EQ(area.rgb.size(), point.rgb.size());
  int differs_from_centre = 0;
  for (int v = 0; v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int dv = 0; dv < k; ++dv) {
          for (int du = 0; du < k; ++du) {
            sum += fine.rgb[((size_t(v) * k + dv) * k * w + size_t(u) * k + du) * 3 + c];
          }
        }
        const int got = area.rgb[(size_t(v) * w + u) * 3 + c];
        ASSERT_NEAR(got, sum / double(k * k), 0.5 + 1e-9) << u << "," << v << " channel " << c;
        differs_from_centre += got != point.rgb[(size_t(v) * w + u) * 3 + c];
      }
    }
  }
  EXPECT_GT(differs_from_centre, 3 * w * h / 4);  // texture finer than a pixel, edges
  EXPECT_EQ(area.surface_id, point.surface_id);
  ASSERT_EQ(area.depth.size(), point.depth.size());
  int sky = 0;
  for (size_t i = 0; i < point.depth.size(); ++i) {
    if (std::isnan(point.depth[i])) {
      EXPECT_TRUE(std::isnan(area.depth[i])) << i;
      ++sky;
    } else {
      EXPECT_EQ(area.depth[i], point.depth[i]) << i;
    }
  }
  EXPECT_GT(sky, 0);
}

// Two renderers in one process (the Python module's missions): destroying one leaves the
// other's textures and buffers alone, so it renders the same view as before.
TEST(Render, DestroyingARendererLeavesAnotherIntact) {
  const World world(WallAtOneMetre());
  auto camera = PinholeCamera::FromFov(LookAlongX(0.5), 176, 144, M_PI / 4);
  Renderer kept(world.model());
  RenderedView before;
  {
    Renderer other(world.model());
    other.Render(world.model(), world.data(), camera);
    before = kept.Render(world.model(), world.data(), camera);  // the current context: kept's
  }
  const RenderedView after = kept.Render(world.model(), world.data(), camera);
  EXPECT_EQ(after.rgb, before.rgb);
  EXPECT_EQ(after.surface_id, before.surface_id);
}
}  // namespace
}  // namespace fognav::sim
