#include "sim/render.h"

#include <GL/osmesa.h>
#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

namespace fognav::sim {
namespace {

// near and far clipping planes of every view, metres
constexpr float kNear = 0.02f;
constexpr float kFar = 30.0f;

// face of a box hit at local point p: the face whose plane is closest
int BoxFace(const Eigen::Vector3d& p_B, const Eigen::Vector3d& half) {
  int best = 0;
  double best_gap = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    double gap = std::abs(std::abs(p_B[axis]) - half[axis]);
    if (gap < best_gap) {
      best_gap = gap;
      best = 2 * axis + (p_B[axis] < 0 ? 1 : 0);
    }
  }
  return best;
}

// OSMesa's entry points, opened at run time so that a machine without libOSMesa gets a clear
// error (exit code 3) instead of a program that cannot start. MuJoCo opens the library by the
// same name to load OpenGL, so both use one copy.
struct OSMesaApi {
  decltype(&OSMesaCreateContextExt) create = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&OSMesaDestroyContext) destroy = nullptr;
};

const OSMesaApi& LoadOSMesa() {
  static const OSMesaApi api = [] {
    const char* override_name = std::getenv("FOGNAV_OSMESA");
    const std::string name = override_name && *override_name ? override_name : "libOSMesa.so";
    void* library = dlopen(name.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (!library) library = dlopen((name + ".8").c_str(), RTLD_NOW | RTLD_GLOBAL);
    OSMesaApi a;
    if (!library) return a;
    a.create = reinterpret_cast<decltype(a.create)>(dlsym(library, "OSMesaCreateContextExt"));
    a.make_current = reinterpret_cast<decltype(a.make_current)>(dlsym(library, "OSMesaMakeCurrent"));
    a.destroy = reinterpret_cast<decltype(a.destroy)>(dlsym(library, "OSMesaDestroyContext"));
    return a;
  }();
  if (!api.create || !api.make_current || !api.destroy) {
    const char* override_name = std::getenv("FOGNAV_OSMESA");
    throw SimError(std::string("OSMesa: cannot load ") +
                   (override_name && *override_name ? override_name : "libOSMesa.so") +
                   " (install Debian's libosmesa6-dev, which provides it)");
  }
  return api;
}

}  // namespace

PinholeCamera PinholeCamera::FromFov(const Eigen::Isometry3d& X_WC, int width_px, int height_px,
                                     double hfov) {
  PinholeCamera c;
  c.X_WC = X_WC;
  c.width_px = width_px;
  c.height_px = height_px;
  c.fx = c.fy = 0.5 * width_px / std::tan(hfov / 2);
  c.cx = 0.5 * width_px - 0.5;
  c.cy = 0.5 * height_px - 0.5;
  return c;
}

struct Renderer::Impl {
  OSMesaContext osmesa = nullptr;
  std::vector<unsigned char> osmesa_buffer;
  mjvScene scene;
  mjvOption option;        // the colour pass
  mjvOption truth_option;  // the surface-id pass
  mjrContext context;
  bool scene_made = false, context_made = false;
  std::vector<unsigned char> rgb_flipped;
  std::vector<float> depth_flipped;

  ~Impl() {
    // MuJoCo frees its GL objects in the current context: make it this one, not another
    // renderer's (whose objects would go instead)
    if (osmesa && context_made) {
      LoadOSMesa().make_current(osmesa, osmesa_buffer.data(), GL_UNSIGNED_BYTE, 64, 64);
    }
    if (context_made) mjr_freeContext(&context);
    if (scene_made) mjv_freeScene(&scene);
    if (osmesa) LoadOSMesa().destroy(osmesa);
  }
};

Renderer::Renderer(const mjModel* m) : impl_(std::make_unique<Impl>()) {
  InstallMujocoErrorHandler();
  const OSMesaApi& osmesa = LoadOSMesa();
  impl_->osmesa = osmesa.create(OSMESA_RGBA, 24, 8, 0, nullptr);
  if (!impl_->osmesa) throw SimError("OSMesa: could not create an off-screen OpenGL context");
  // the default framebuffer only hosts the context; views go to MuJoCo's offscreen buffer
  impl_->osmesa_buffer.resize(size_t(64) * 64 * 4);
  if (!osmesa.make_current(impl_->osmesa, impl_->osmesa_buffer.data(), GL_UNSIGNED_BYTE, 64, 64)) {
    throw SimError("OSMesa: could not make the off-screen context current");
  }
  mjv_defaultScene(&impl_->scene);
  mjv_defaultOption(&impl_->option);
  impl_->option.geomgroup[kSkinGroup] = 1;
  impl_->option.geomgroup[kSolidGroup] = 0;
  impl_->truth_option = impl_->option;
  impl_->truth_option.geomgroup[kSkinGroup] = 0;
  impl_->truth_option.geomgroup[kSolidGroup] = 1;
  mjr_defaultContext(&impl_->context);
  mjv_makeScene(m, &impl_->scene, 2000);
  impl_->scene_made = true;
  mjr_makeContext(m, &impl_->context, mjFONTSCALE_100);
  impl_->context_made = true;
  mjr_setBuffer(mjFB_OFFSCREEN, &impl_->context);
  if (impl_->context.currentBuffer != mjFB_OFFSCREEN) {
    throw SimError("OSMesa: the OpenGL context has no off-screen framebuffer");
  }
}

Renderer::~Renderer() = default;

RenderedView Renderer::Render(const mjModel* m, const mjData* d, const PinholeCamera& camera,
                              const RenderRequest& request) {
  const int w = camera.width_px, h = camera.height_px;
  if (w > impl_->context.offWidth || h > impl_->context.offHeight) {
    throw SimError("render: view " + std::to_string(w) + "x" + std::to_string(h) +
                   " is larger than the model's offscreen buffer");
  }
  LoadOSMesa().make_current(impl_->osmesa, impl_->osmesa_buffer.data(), GL_UNSIGNED_BYTE, 64, 64);
  mjr_setBuffer(mjFB_OFFSCREEN, &impl_->context);
  mjvScene& scn = impl_->scene;

  // scene at the data's state
  mjvCamera free_camera;
  mjv_defaultCamera(&free_camera);
  mjv_updateScene(m, const_cast<mjData*>(d), &impl_->option, nullptr, &free_camera, mjCAT_ALL,
                  &scn);
  // mjv_updateScene sets the scene's cameras; each pass replaces them by the pinhole
  // (OpenGL looks along -z, y up)
  const Eigen::Vector3d pos = camera.X_WC.translation();
  const Eigen::Vector3d forward = camera.X_WC.rotation().col(2);
  const Eigen::Vector3d up = -camera.X_WC.rotation().col(1);
  auto set_cameras = [&](mjvScene* scene) {
    for (int eye = 0; eye < 2; ++eye) {
      mjvGLCamera& gl = scene->camera[eye];
      for (int i = 0; i < 3; ++i) {
        gl.pos[i] = float(pos[i]);
        gl.forward[i] = float(forward[i]);
        gl.up[i] = float(up[i]);
      }
      // frustum at the near plane; pixel edges lie half a pixel beyond the centres
      gl.frustum_near = kNear;
      gl.frustum_far = kFar;
      gl.frustum_top = float(kNear * (camera.cy + 0.5) / camera.fy);
      gl.frustum_bottom = float(-kNear * (h - 0.5 - camera.cy) / camera.fy);
      gl.frustum_center =
          float(kNear * ((w - 0.5 - camera.cx) - (camera.cx + 0.5)) / (2 * camera.fx));
    }
    scene->stereo = mjSTEREO_NONE;
  };
  set_cameras(&scn);
  const mjrRect viewport = {0, 0, w, h};

  RenderedView view;
  view.width = w;
  view.height = h;
  view.rgb.resize(size_t(w) * h * 3);
  impl_->depth_flipped.resize(size_t(w) * h);

  // colour pass at k x k samples per pixel, each pixel the mean of its samples (the rows come
  // bottom to top); with one sample it also gives the depth
  const int k = std::max(1, std::min({request.pixel_samples, impl_->context.offWidth / w,
                                      impl_->context.offHeight / h}));
  const bool need_depth = request.depth || request.surfaces;
  scn.flags[mjRND_SEGMENT] = 0;
  scn.flags[mjRND_IDCOLOR] = 0;
  const mjrRect sample_viewport = {0, 0, k * w, k * h};
  impl_->rgb_flipped.resize(size_t(k * w) * (k * h) * 3);
  mjr_render(sample_viewport, &scn, &impl_->context);
  mjr_readPixels(impl_->rgb_flipped.data(), need_depth && k == 1 ? impl_->depth_flipped.data() : nullptr,
                 sample_viewport, &impl_->context);
  const int samples = k * k;
  for (int v = 0; k == 1 && v < h; ++v) {
    // one sample per pixel: the rows as they are, bottom to top
    std::copy_n(&impl_->rgb_flipped[size_t(h - 1 - v) * w * 3], size_t(w) * 3,
                &view.rgb[size_t(v) * w * 3]);
  }
  for (int v = 0; k > 1 && v < h; ++v) {
    for (int u = 0; u < w; ++u) {
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int row = (h - 1 - v) * k; row < (h - v) * k; ++row) {
          for (int col = u * k; col < (u + 1) * k; ++col) {
            sum += impl_->rgb_flipped[(size_t(row) * k * w + col) * 3 + c];
          }
        }
        view.rgb[(size_t(v) * w + u) * 3 + c] = uint8_t((sum + samples / 2) / samples);
      }
    }
  }
  if (need_depth && k > 1) {
    mjr_render(viewport, &scn, &impl_->context);
    mjr_readPixels(nullptr, impl_->depth_flipped.data(), viewport, &impl_->context);
  }
  if (need_depth) {
    // OpenGL depth buffer value z in [0, 1] to metric depth along the optical axis
    view.depth.resize(size_t(w) * h);
    for (int v = 0; v < h; ++v) {
      for (int u = 0; u < w; ++u) {
        float z = impl_->depth_flipped[size_t(h - 1 - v) * w + u];
        view.depth[size_t(v) * w + u] = z >= 1.0f ? std::numeric_limits<float>::quiet_NaN()
                                                  : kNear * kFar / (kFar - z * (kFar - kNear));
      }
    }
  }

  if (request.surfaces) {
    // segmentation pass: each scene geom drawn in the colour segid + 1
    mjv_updateScene(m, const_cast<mjData*>(d), &impl_->truth_option, nullptr, &free_camera,
                    mjCAT_ALL, &scn);
    set_cameras(&scn);
    scn.flags[mjRND_SEGMENT] = 1;
    scn.flags[mjRND_IDCOLOR] = 1;
    mjr_render(viewport, &scn, &impl_->context);
    mjr_readPixels(impl_->rgb_flipped.data(), nullptr, viewport, &impl_->context);
    scn.flags[mjRND_SEGMENT] = 0;
    scn.flags[mjRND_IDCOLOR] = 0;
    view.surface_id.assign(size_t(w) * h, -1);
    const Eigen::Matrix3d R_WC = camera.X_WC.rotation();
    for (int v = 0; v < h; ++v) {
      for (int u = 0; u < w; ++u) {
        const unsigned char* c = &impl_->rgb_flipped[(size_t(h - 1 - v) * w + u) * 3];
        int segid = int(c[0]) + (int(c[1]) << 8) + (int(c[2]) << 16) - 1;
        if (segid < 0 || segid >= scn.ngeom) continue;
        const mjvGeom& g = scn.geoms[segid];
        if (g.objtype != mjOBJ_GEOM || g.objid < 0) continue;
        int geom = g.objid;
        int face = kWholeGeomSurface;
        float depth = view.depth[size_t(v) * w + u];
        if (m->geom_type[geom] == mjGEOM_BOX && std::isfinite(depth)) {
          // the face follows from where the pixel's ray meets the box
          Eigen::Vector3d p_C((u - camera.cx) / camera.fx * depth, (v - camera.cy) / camera.fy * depth,
                              depth);
          Eigen::Vector3d p_W = camera.X_WC.translation() + R_WC * p_C;
          Eigen::Map<const Eigen::Matrix<mjtNum, 3, 3, Eigen::RowMajor>> R_WB(d->geom_xmat + 9 * geom);
          Eigen::Map<const Eigen::Vector3d> p_WB(d->geom_xpos + 3 * geom);
          Eigen::Vector3d p_B = R_WB.transpose() * (p_W - p_WB);
          face = BoxFace(p_B, Eigen::Map<const Eigen::Vector3d>(m->geom_size + 3 * geom));
        }
        view.surface_id[size_t(v) * w + u] = geom * kSurfacesPerGeom + face;
      }
    }
  }
  return view;
}

}  // namespace fognav::sim
