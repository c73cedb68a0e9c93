// Off-screen rendering through OSMesa (no display): colour, metric depth and ground-truth
// surface ids for any pinhole camera in the world.
#ifndef FOGNAV_SIM_RENDER_H_
#define FOGNAV_SIM_RENDER_H_

#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "sim/model.h"

namespace fognav::sim {

// A pinhole camera in OpenCV convention (x right, y down, z forward). Pixel (u, v) has its
// centre at (u, v): cx = width / 2 - 0.5 for a centred principal point.
struct PinholeCamera {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();  // camera pose in the world
  int width_px = 176;
  int height_px = 144;
  double fx = 0, fy = 0, cx = 0, cy = 0;

  // A centred camera of square pixels with horizontal field of view hfov (rad).
  static PinholeCamera FromFov(const Eigen::Isometry3d& X_WC, int width_px, int height_px,
                               double hfov);
};

// Surface ids: a box geom's face f (0..5 for +x, -x, +y, -y, +z, -z of the box) is
// geom * 8 + f; any other geom (the floor plane, capsules, ...) is geom * 8 + 6 as one surface.
constexpr int kSurfacesPerGeom = 8;
constexpr int kWholeGeomSurface = 6;
inline int SurfaceGeom(int surface_id) { return surface_id < 0 ? -1 : surface_id / kSurfacesPerGeom; }

// Geom groups with a role in rendering. A solid's surface can have a separate skin: the colour
// pass draws skins and not solids, the surface-id pass solids and not skins, so depth and
// surface ids come from the solid while its looks come from the skin (which must coincide).
// Both groups lie outside MuJoCo's default visible groups 0-2 except the skin's.
constexpr int kSkinGroup = 2;
constexpr int kSolidGroup = 4;

// One rendered view. Rows are top to bottom.
struct RenderedView {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;         // 3 bytes per pixel
  std::vector<float> depth;         // metres along the optical axis; NaN where nothing is seen
  std::vector<int32_t> surface_id;  // see kSurfacesPerGeom; -1 where nothing is seen
};

// What to render; colour is always rendered.
struct RenderRequest {
  bool depth = true;
  bool surfaces = true;
  // Colour as a camera's pixel gathers it, over its area: the mean of pixel_samples^2 points
  // spread evenly over each pixel instead of its centre alone. Point samples alias texture finer
  // than a pixel, differently in each eye. Lowered as far as needed to fit the offscreen buffer;
  // depth and surface ids stay those of the pixel centres.
  int pixel_samples = 1;
};

// Owns an OSMesa context and MuJoCo's rendering context for one model. Not copyable; one
// renderer per thread.
class Renderer {
 public:
  // Creates the context. Throws SimError (naming OSMesa or MuJoCo) when it cannot be made.
  // The model's offscreen buffer must be at least as large as every view rendered.
  explicit Renderer(const mjModel* m);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Renders the world as it is in d (after mj_forward or mj_kinematics) from `camera`.
  // Throws SimError if the view is larger than the offscreen buffer.
  RenderedView Render(const mjModel* m, const mjData* d, const PinholeCamera& camera,
                      const RenderRequest& request = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fognav::sim

#endif  // FOGNAV_SIM_RENDER_H_
