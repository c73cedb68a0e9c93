// Environment maps of the paper's Section 5: 3D occupancy grid, floor height map and the
// Floor and Obstacle Grid (FOG). All maps live in the grid frame (the odometry frame).
//
// One perception cycle, as the mission runner calls it:
//   X_GC = odometry robot pose (grid frame) * head kinematic pose (robot frame);
//   MapInput in{robot_G, X_GC.translation(),
//               LabelPoints(label_params, points_C, planes, X_GC, body_boxes_G)};
//   UpdateMaps(map_params, in, &state);
//   Fog fog = ComputeFog(map_params, state);
//   FogScore s = ScoreFog(fog, GroundTruthFog(solids_G, fog.window, map_params.fog));
#ifndef FOGNAV_PERCEPTION_MAPPING_H_
#define FOGNAV_PERCEPTION_MAPPING_H_

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "perception/segmentation.h"
#include "perception/types.h"

namespace fognav::perception {

// Environment type of a FOG cell (paper Section 5.4).
enum class CellType : uint8_t { kUnknown = 0, kFloor, kStairs, kBorder, kTunnel, kObstacle };
inline constexpr int kNumCellTypes = 6;

// Lower-case name of a cell type ("floor", "stairs", ...).
const char* CellTypeName(CellType type);

// A square 2D window of cells in the grid frame. Cell (ix, iy) covers
// [(origin_ix + ix) * resolution, (origin_ix + ix + 1) * resolution) in x, likewise in y, so
// scrolling the window by whole cells keeps world-fixed content on the same global cells.
struct GridWindow {
  int size_x = 100;          // cells along x
  int size_y = 100;          // cells along y
  double resolution = 0.04;  // cell side in metres
  int origin_ix = -50;       // global index of local cell (0, *) along x
  int origin_iy = -50;       // global index of local cell (*, 0) along y

  int NumCells() const { return size_x * size_y; }
  int Index(int ix, int iy) const { return iy * size_x + ix; }
  bool Contains(int ix, int iy) const { return ix >= 0 && iy >= 0 && ix < size_x && iy < size_y; }
  // Local cell holding grid-frame point (x, y); may lie outside the window.
  void CellOf(double x, double y, int* ix, int* iy) const {
    *ix = int(std::floor(x / resolution)) - origin_ix;
    *iy = int(std::floor(y / resolution)) - origin_iy;
  }
  // Grid-frame centre of local cell (ix, iy).
  Eigen::Vector2d CellCenter(int ix, int iy) const {
    return {(origin_ix + ix + 0.5) * resolution, (origin_iy + iy + 0.5) * resolution};
  }
};

// The Floor and Obstacle Grid: a type and a height per cell (eq. 17, 25). Heights are metres in
// the grid frame; -infinity for unknown cells.
struct Fog {
  GridWindow window;
  std::vector<CellType> type;  // window.NumCells() entries, indexed by window.Index(ix, iy)
  std::vector<float> height;   // same indexing
  // Extension: per cell, 1 if the 3D grid has observed every layer between h_tunnel and
  // h_robot above the cell's floor (so a standing robot's head would be where the robot has
  // looked) and none of them is occupied; 0 if not or without a floor. Empty when not known
  // (GroundTruthFog: the geometry is exact); same indexing.
  std::vector<uint8_t> headroom_seen;
  // Extension: per tunnel cell the height of its ceiling (eq. 23: the bottom of the lowest
  // occupied layer above the floor), -infinity for other cells. Empty when not known
  // (GroundTruthFog); same indexing.
  std::vector<float> ceiling;
  // Extension filled by the mission loop, not by perception: 1 where the standing robot has
  // stood (its footprint), cells it came over whether or not its eyes ever saw them (it walks
  // forward onto cells seen from afar or not at all, and never sees them behind it). A blind
  // move may go back onto them (nav::PlannerParams::blind_moves_stay_known). Empty = none;
  // same indexing.
  std::vector<uint8_t> walked;

  Fog() = default;
  explicit Fog(const GridWindow& w)
      : window(w),
        type(size_t(w.NumCells()), CellType::kUnknown),
        height(size_t(w.NumCells()), -std::numeric_limits<float>::infinity()) {}
  CellType TypeAt(int ix, int iy) const { return type[size_t(window.Index(ix, iy))]; }
  float HeightAt(int ix, int iy) const { return height[size_t(window.Index(ix, iy))]; }
};

// ---------------------------------------------------------------------------------------------
// Labelled points (paper Section 5 intro and 5.1).

// How segmented range data becomes labelled points in the grid frame.
struct LabelParams {
  // A plane is a floor candidate if its upward normal is within this angle of grid +z.
  double max_tilt_deg = 10.0;
  // ... and if its points in the grid frame extend at least a sole along both principal
  // directions (extent = sqrt(12 * variance), exact for a uniformly covered rectangle). The
  // same rule defines floor candidates in GroundTruthFog; 0 disables it.
  double min_floor_length = 0.10;
  double min_floor_width = 0.06;
  // Self-filter: points inside a body box grown by this margin (metres) are dropped.
  double self_filter_margin = 0.02;
  // Points farther than this from the camera (metres) are dropped.
  double max_range = std::numeric_limits<double>::infinity();
  // Floor on the height sigma of a floor-candidate plane, metres.
  double min_height_sigma = 0.001;
  // Points on a column rim only (kColumnRim: a farther surface above or below, none beside)
  // higher than this (grid frame z, metres) are kept although not on a floor candidate. A
  // table top's edge at eye height is a band a few rows high seen edge-on between farther
  // surfaces, all of it column rim: dropped, it left no trace in the map, and a standing
  // robot's head met a top at 0.49-0.52 m. The caller sets it per view from the floor under
  // the robot (PerceptionParams::rim_keep_height); fattened points up there only widen a
  // ceiling a little. +inf keeps no rim point.
  double keep_column_rims_above = std::numeric_limits<double>::infinity();
  // Extension: where a floor candidate meets a vertical plane (within max_tilt_deg of vertical)
  // in the image, within two pixels along a row or a column, its points smeared past the face
  // lose their height, within the face's extent along it (its extents: mean +- sqrt(3)
  // standard deviations of its points): a floor within face_clip of the face's foot, up to
  // face_clip behind the face; a top within face_clip of the face's top, up to face_clip before
  // it. Stereo smears points along the rays by 1-2 cm at a few metres: the floor at a wall's
  // foot reached into the wall's first cells, which then took the floor's height (a border at
  // floor height that hands and knees may pass over), and a top reached a cell beyond its face.
  // The points still count in the grid. 0 turns it off (the paper).
  double face_clip = 0.03;  // metres
};

// A range point in the grid frame with the height h of the horizontal plane it belongs to, or
// h = -infinity if it is not on a floor candidate (the paper's (x_i^G, y_i^G, z_i^G, h_i^G)).
struct LabelledPoint {
  Eigen::Vector3f p_G = Eigen::Vector3f::Zero();
  float h = -std::numeric_limits<float>::infinity();
  // Standard deviation of h in metres: the RMS residual of the plane's points across it, which
  // grows with range for stereo (depth error ~ z^2). 0 = unknown (then eq. 21 applies as is).
  float h_sigma = 0;
};

// Transforms the valid points of `points_C` (camera frame) into the grid frame with the camera
// pose X_GC (odometry robot pose composed with the head's kinematic pose; the caller computes
// it), labels each with the height of its floor-candidate plane (mean z of the plane's points in
// the grid frame) or -infinity and with that height's sigma (the plane's RMS residual, at least
// params.min_height_sigma), and drops NaN points, points beyond max_range and points inside
// the robot's own body `body_G` (boxes in the grid frame from the robot's kinematic pose).
// `planes.labels` must have the size of `points_C`; label -1 or an empty label image means no
// plane. Plane normals may point either way; only their axis is used.
// Extension: where `rims` (the size of `points_C`) is not 0, a point lies on the rim of a
// nearer surface in stereo data (DepthEdgeRims), where its position may be the nearer
// surface's although it sees the background; it still counts for its plane's height, but is
// kept only if that plane is a floor candidate (or, on a column rim only, if it lies above
// params.keep_column_rims_above), so that fattened stereo puts no obstacles beside objects.
std::vector<LabelledPoint> LabelPoints(const LabelParams& params, const PointImage& points_C,
                                       const PlaneSet& planes, const Eigen::Isometry3d& X_GC,
                                       const std::vector<OrientedBox>& body_G,
                                       const Image<uint8_t>* rims = nullptr);

// ---------------------------------------------------------------------------------------------
// Map parameters.

// 3D occupancy grid (eq. 15, 18). The window is centred on the robot in x and y and fixed in z.
struct OccupancyParams {
  int size_x = 100;          // cells along x (paper: 100)
  int size_y = 100;          // cells along y (paper: 100)
  int size_z = 16;           // layers (paper: 16)
  double resolution = 0.04;  // cell side in metres (paper: 4 cm)
  // Bottom of layer 0 in the grid frame. The default puts the floor (z = 0) in the middle of
  // layer 0 so that floor points do not straddle two layers; layers span [-0.02, 0.62).
  double z_min = -0.02;
  // Sensor model of eq. (18), as the inverse model P(c | p) (the Bayes update of eq. 18 with
  // P(p|c) / P(p|!c) = p / (1 - p)). Kept as log-odds internally, clamped to [p_min, p_max].
  double p_hit = 0.7;   // for the cell holding the end point of a ray
  double p_miss = 0.4;  // for every other cell the ray crosses
  double p_min = 0.12;
  double p_max = 0.97;
  // Trace one ray per end cell and frame (the first point's; OctoMap's "discretize"): rays to
  // points in one cell cross nearly the same cells, and near the camera dozens of points share a
  // cell. Every point still marks its end cell occupied.
  bool one_ray_per_end_cell = true;
  // Extension: a cell counts as hit in a frame only if at least this many points end in it
  // (else as crossed, if a ray crossed it), so that a stray stereo point does not make an
  // obstacle; 1 = the paper.
  int min_hits_per_frame = 1;
  // Extension: stereo depth errors grow with the square of the range, so obstacle evidence
  // seen only from afar may be a phantom (at 2.5 m a 0.3 px error moves a wall 0.2 m). Each
  // column keeps the smallest range of the points that ended in it off its floor; its cells
  // crossed in a frame in which a ray crossed the column from at most 1 / overrule_ratio of
  // that range are set free at once (log-odds of one miss) instead of adding a miss; 0 = the
  // paper's update. Only cells whose bottom lies below overrule_below (h_tunnel): rays to a
  // ceiling's farther parts graze the layer of its nearer ones, which would lose a table's
  // underside.
  double overrule_ratio = 0.0;
  double overrule_below = 0.30;
  // P_occ of eq. (19, 22, 23): a cell is occupied if its probability exceeds this.
  double p_occ = 0.6;
};

// Floor height map (eq. 16, 19-21).
struct FloorParams {
  double gate = 0.01;       // epsilon of eq. (21), metres
  double smoothing = 0.8;   // nu of eq. (21)
  // Extension for heights with a sigma (LabelledPoint::h_sigma > 0); each cell then keeps the
  // variance of its height, so that a noisy far view cannot overwrite a precise close one.
  // Eq. (21) becomes: within the gate epsilon the cell and the measurement are averaged by
  // inverse variance (each plane counts once per cell and frame; the cell variance never drops
  // below min_sigma^2, so a cell still follows new data); a higher floor replaces the cell if its
  // variance is at most replace_ratio times the cell's, a lower one if the cell's is at least
  // replace_ratio times its own (a precise close view corrects a noisy far one); else the
  // measurement is ignored.
  double min_sigma = 0.002;
  double replace_ratio = 4.0;
  double lower_doubt = 0.05;  // metres; 0 turns the doubt off
  // Extensions for heights with a sigma, against the points of one surface that segmentation
  // joins to a neighbouring lower plane (the riser of a step, the foot of a block's face, a rim
  // smeared by stereo), which would lower the height of a cell the lower plane does not reach.
  // Both only ever leave a lower height out, so a cell keeps the highest floor in it, as the
  // paper prefers:
  // - a floor point gives its cell its plane's height only if it lies no more than
  //   max(on_plane_sigmas * sigma, on_plane_min) above it (on_plane_sigmas 0: always);
  // - of the heights one frame gives a cell, one up to minor_range below another is left out if
  //   it has fewer than minor_share of the two's points (minor_share 0: none left out).
  double on_plane_sigmas = 2.0;
  double on_plane_min = 0.01;   // metres
  double minor_share = 0.25;
  double minor_range = 0.05;    // metres
  // Eq. (19, 20) read OG(x, y, h) as the highest probability of the layers that
  // [h - verify_tolerance, h + verify_tolerance] touches, so a floor lying on a layer boundary
  // is verified by either layer.
  double verify_tolerance = 0.01;
};

// FOG classification (eq. 22-25, algorithm classify). Defaults are QRIO's (Section 6).
struct FogParams {
  double h_floor = 0.015;  // largest floor change walked on ordinarily, metres
  double h_stairs = 0.05;  // highest step, metres
  double h_tunnel = 0.30;  // lowest ceiling to crawl under, metres
  double h_robot = 0.58;   // standing height, metres
  int neighbourhood_radius = 1;  // U(x, y) of eq. (24): (2r+1)^2 cells
  // Extension: a floor height whose sigma (MapState::floor_var) exceeds this, in metres, cannot
  // tell floor from a step of h_floor: it is left out of eq. (24) for its neighbours and its
  // cell is unknown unless an obstacle or tunnel lies above it. Heights without a sigma are
  // reliable. The default is h_floor; infinity turns it off (the paper).
  double max_height_sigma = 0.015;
  // Eq. (22, 23) read "z > h_f" for a layer as "layer bottom >= h_f + obstacle_margin", so the
  // layer holding the floor itself never counts as an obstacle. In GroundTruthFog: a solid counts
  // above the floor where its top exceeds h_f + obstacle_margin.
  double obstacle_margin = 0.02;
  // A vertical face on a cell boundary (the riser of a step) leaves points in the lower
  // neighbour's column. If set, occupied layers of a cell with a floor count as obstacles only
  // above the highest floor in U(x, y) + obstacle_margin; a higher neighbour then makes the cell
  // at least stairs or border through eq. (24) anyway.
  bool ignore_risers = true;
  // The same for a cell without a floor next to cells with one (the strip behind a step down
  // that the eyes cannot see, where smeared stereo points of the surfaces around land):
  // occupied layers count as obstacles only above the highest floor in U(x, y) +
  // obstacle_margin, else the cell stays unknown. Estimates only; GroundTruthFog is exact.
  bool ignore_low_unknown = true;
  // Eq. (24) runs over the known heights of U(x, y) only, so a floor change is a lower bound
  // while U holds unknown cells: the rim of a wall top whose far side the eyes cannot see
  // comes out floor though the drop behind it makes it border. If set, a cell that eq. (24)
  // makes floor or stairs stays unknown while U holds an unknown cell (or a place beyond the
  // window) and U grown by one cell holds at least min_unknown_around of them: the edge of
  // what was seen, not a stereo hole of a cell or two inside it (those stay as the paper has
  // them, or every hole would grow a ring and the planner lose the floor around it). Border is
  // certain either way. Estimates only; GroundTruthFog knows every cell. On the course's start
  // sweep this took FOG accuracy from 0.90 to 0.96 with ideal depth, 0.78 to 0.83 with stereo.
  bool require_known_neighbourhood = true;
  int min_unknown_around = 5;  // of the (2r+3)^2 cells; 1 = any unknown cell in U
  // Extension: tops that no plane covered. A wall's 0.1 m top seen from a metre is a strip of
  // two or three pixels, too thin for scan-line grouping, so its cells hold occupied layers over
  // the floor (or over none) and eq. (22) makes them obstacles, where the ground truth (floor
  // candidates as below) makes them border. If set, a cell whose highest occupied layer ends no
  // higher than camera_height, below the grid's top layer and more than h_stairs + one layer
  // above the highest floor of the cell and U(x, y), with no layer between them seen free (a
  // solid standing on the floor, not a table's top), is part of a top. An 8-connected patch of
  // such cells (neighbours' tops within one layer) that is flat (its tops span at most two
  // layers: a rough top of posts stays an obstacle) and at least a sole large
  // (min_floor_length x min_floor_width, from the spread of the cell centres) counts in eq.
  // (24) with one floor height: the middle of its layer, or the boundary of its two (a top on
  // a layer boundary). Its cells are then border or floor if eq. (24) makes them so (the
  // height is too rough to tell stairs) and as before otherwise; the neighbours' floor change
  // sees the drop, and occupied layers count for them as without it.
  bool infer_tops = true;
  // Extension of infer_tops: a far wall's top is seen as tops of two layers in most of its
  // cells, but lower along its rim, where the eyes saw its face and not up to the top edge (its
  // patch spans up to five layers). A patch whose tops span more than two layers is still a top
  // if it is at most top_band_max_width wide, its two highest layers (the band) hold at least
  // top_band_share of its cells and every cell below them lies on its rim (has a neighbour
  // outside it). All its cells then take the band's height: the top is never lower than a cell
  // saw it. Wider patches stay obstacles: in a wide patch of rough posts (the paper's Fig. 9)
  // too, most cells' highest layers lie in two, and cells of 4 cm cannot tell the two apart.
  double top_band_share = 2.0 / 3.0;
  double top_band_max_width = 0.20;
  // Extension: an underside seen from below at a grazing angle (a table top just above the
  // eyes) leaves points in only some of the columns under it, so eq. (23) makes a patchwork of
  // tunnel cells and floor cells between them. A floor cell whose headroom no ray has seen free
  // (Fog::headroom_seen) becomes tunnel if tunnel cells lie on both sides of it along a row, a
  // column or a diagonal with at most this many floor cells between them, their ceilings within
  // one layer of each other: one slab spans the gap. 0 turns it off (the paper). At the
  // course's end 100 of the table's cells were still floor with 3 (FOG 0.776), 27 with 6
  // (0.808). A gap also joins two tops of one layer up to 0.24 m apart, a way the standing
  // robot's hands (0.30 m across) could not take between them anyway.
  int ceiling_gap = 6;
  // Floor candidates no higher than this (the standing camera height) and at least a sole
  // large (LabelParams' sizes); GroundTruthFog's floor candidates and infer_tops.
  double camera_height = 0.50;
  double min_floor_length = 0.10;
  double min_floor_width = 0.06;
  int truth_samples = 4;  // ground truth samples truth_samples^2 points per cell
};

// Extension: where the floor ends (the edge of the world's floor, a hole whose bottom lies out
// of sight) the eyes see nothing where a floor would be, and the paper's maps, which only hold
// what was seen, keep such cells unknown: cells the planner may cross. Each frame, the pixels
// with neither range nor texture (the image within texture_window pixels around them varies by
// at most max_contrast grey levels: not a stereo mismatch or occlusion shadow on a textured
// surface) that look down, lie in a region of such pixels at least min_width_px wide, and
// either have a floor point as the nearest point below them in their image column (the floor
// runs up to the emptiness; not the sky above a wall) or lie in a column empty from top to
// bottom (the eyes look beyond the drop) are followed to the plane of the floor under the
// robot; a cell where at least min_pixels of them land no farther than `range` (along the floor
// from the camera, metres: the textured floor gives range well beyond it) gets one frame of
// evidence. In the FOG a cell with no floor height, no occupied layer and at least min_frames
// frames of evidence has no floor: border without a height, which the planner never stands on.
// min_frames 0 turns it off.
// Rays that meet the robot's own body before the floor (EmptyRays' body_G: it is untextured and
// may have no range) and rays that meet the floor nearer than min_distance to the eyes do not
// count: within 0.4 m one blob of the floor's texture fills the texture window (the crawling
// eyes, 0.14 m above a platform, saw its blobs 20 px wide).
// If drop_floor is set, the rays also take back a floor height: stereo smears a floor's edge
// seen from afar by a cell or two beyond it, and the paper's maps keep a height while the grid
// holds it (eq. 20), so the cells beyond the world's floor that the smeared points reached stayed
// floor however near the robot came (a robot walked off the floor on them). A height on the
// level of the floor under the robot (within floor_tolerance) whose cell the rays meet in
// min_frames frames in which no floor point fell in it (frames before it had a height count
// too) is dropped, and the grid's layers that held it lose their evidence. Off by default: on
// 80 open rooms it won one mission (76 of 80 against 75), but on 38 fresh ones it lost two
// (36 of 38 against 38), both unsafe: a sole past the floor's edge, and a walk into a
// divider's end.
struct VoidParams {
  double range = 1.5;
  double min_distance = 0.45;  // metres, from the camera to where the ray meets the floor
  bool drop_floor = false;
  int texture_window = 5;
  int max_contrast = 4;
  int min_width_px = 3;
  double floor_tolerance = 0.03;  // metres
  int min_pixels = 2;
  int min_frames = 2;
};

struct MapParams {
  OccupancyParams grid;
  FloorParams floor;
  FogParams fog;
  VoidParams no_floor;
};

// ---------------------------------------------------------------------------------------------
// Map state and update.

// The accumulated maps. Default-constructed empty; the first UpdateMaps sizes and centres it.
// Memory with default parameters: 160k cells * (4 + 1) bytes for the grid, 40 kB for the floor
// map, plus a same-sized scratch buffer for scrolling: about 1.5 MB.
struct MapState {
  GridWindow window;       // x-y window shared by the 3D grid and the floor map
  int size_z = 0;          // layers of the 3D grid
  double z_min = 0;        // bottom of layer 0, metres
  // Log-odds of occupancy per 3D cell, index (window.Index(ix, iy)) * size_z + iz; 0 = P 0.5.
  std::vector<float> log_odds;
  // Floor height per 2D cell (eq. 16), metres, -infinity where there is no floor information.
  std::vector<float> floor;
  // Variance of each floor height in m^2; 0 where unknown or where heights had no sigma.
  std::vector<float> floor_var;
  // Per 2D cell: the smallest distance (metres) from the camera of the points that ended in
  // its column off its floor; +infinity if none. Kept whether or not near views overrule
  // (OccupancyParams::overrule_ratio): the mission asks which obstacles were seen only afar.
  std::vector<float> obstacle_range;
  // Scratch, reused between updates: per-cell marks of the current frame (points ended in the
  // cell), per column the bit mask of the layers a ray crossed this frame, scroll buffer, floor
  // heights in layer units.
  std::vector<uint8_t> marks;
  std::vector<uint64_t> crossed;
  std::vector<uint64_t> floor_layers;  // per column: the layers its floor height spares
  std::vector<float> scratch;
  std::vector<float> floor_local;
  // Per cell, the planes whose floor points the current frame put in it (heights with a sigma):
  // up to kFloorVotes heights in the order they came, each with its sigma, how many points
  // voted for it and how many of them lie in the middle half of the cell.
  static constexpr int kFloorVotes = 3;
  struct FloorVote {
    float h[kFloorVotes];
    float sigma[kFloorVotes];
    uint16_t count[kFloorVotes];
    uint16_t middle[kFloorVotes];
  };
  std::vector<FloorVote> floor_votes;
  std::vector<int> floor_voted_cells;  // cells with votes this frame, in the order first voted
  // per cell: its height confirmed / a lower one seen / floor points fell in it, this frame
  std::vector<uint8_t> floor_frame_marks;
  // per 2D cell: the nearest a ray crossed it this frame (only while overrule_ratio > 0)
  std::vector<float> free_range;
  // Per 2D cell: frames in which rays without range met the floor plane there (VoidParams),
  // up to 255; with drop_floor, not those in which floor points fell in a cell with a height.
  std::vector<uint8_t> no_floor_frames;
  std::vector<uint16_t> no_floor_pixels;  // scratch: this frame's rays per cell

  bool Empty() const { return log_odds.empty(); }
  // Occupancy probability of local cell (ix, iy, iz) (must be inside).
  double Probability(int ix, int iy, int iz) const;
  // Occupancy probability at grid-frame point p_G; NaN outside the grid.
  double ProbabilityAt(const Eigen::Vector3d& p_G) const;
  // Floor height at grid-frame (x, y); -infinity if none or outside the window.
  float FloorAt(double x, double y) const;
  // Layer holding height z (may lie outside [0, size_z)).
  int LayerOf(double z) const;
  double LayerBottom(int iz) const;
  // Bytes held by the maps and their scratch buffers.
  size_t MemoryBytes() const;
};

// One frame's input to the maps.
struct MapInput {
  Pose2 robot_G;            // odometry pose of the robot in the grid frame (centres the window)
  Eigen::Vector3d p_GC = Eigen::Vector3d::Zero();  // camera origin in the grid frame
  std::vector<LabelledPoint> points;               // from LabelPoints; NaN points are skipped
  // Directions (grid frame, any length) of the pixels that saw nothing (EmptyRays) and the
  // height of the floor under the robot they are followed to (VoidParams).
  std::vector<Eigen::Vector3f> empty_rays_G;
  double floor_z = 0;
};

// Pixels of `image` around which (texture_window square) the grey level varies by at most
// max_contrast: 255, else 0 (VoidParams).
Image<uint8_t> TexturelessPixels(const VoidParams& params, const RgbImage& image);

// The directions, in the grid frame, of the pixels of `points_C` without a point and
// `textureless` (the same size) that lie in a region of such pixels at least
// params.min_width_px wide, look down and have a floor point (within floor_tolerance of
// floor_z) as the nearest point below them in their column or lie in a column without points,
// and whose way to the floor plane meets none of the robot's body boxes `body_G` grown by
// body_margin, but for one the camera lies in (VoidParams); K is the intrinsics of `points_C`,
// X_GC the camera's pose in the grid frame.
std::vector<Eigen::Vector3f> EmptyRays(const VoidParams& params, const PointImage& points_C,
                                       const Image<uint8_t>& textureless,
                                       const CameraIntrinsics& K, const Eigen::Isometry3d& X_GC,
                                       double floor_z,
                                       const std::vector<OrientedBox>& body_G = {},
                                       double body_margin = 0);

// Window of the given size centred on the robot: the robot's cell is (size_x/2, size_y/2).
GridWindow CenteredWindow(const OccupancyParams& params, const Pose2& robot_G);

// Empties the state and centres it on the robot.
void ResetMaps(const MapParams& params, const Pose2& robot_G, MapState* state);

// Scrolls the maps to the window centred on the robot (whole cells; cells that leave the window
// are erased, entering ones are unknown). Resets the state if it is empty or sized differently.
void ScrollMaps(const MapParams& params, const Pose2& robot_G, MapState* state);

// Weakens what the 3D grid holds to keep times its log-odds (0 forgets, 1 keeps all), except
// the layers that hold each cell's floor height (those eq. 20 verifies it against, within
// verify_tolerance): a fresh look then outvotes old evidence without dropping known floors,
// among them a table top held by a single weak layer whose floor seen below would take its cell.
// A state that was never updated (empty) stays as it is.
void FadeGrid(const MapParams& params, double keep, MapState* state);

// One perception cycle (Sections 5.1-5.3): scroll to the robot, update the 3D grid by ray
// tracing from the camera to every point (Amanatides-Woo traversal, rays clipped to the grid;
// within one frame a cell is updated at most once, as occupied if any ray ends in it, else as
// free if any ray crosses it), verify the floor map against the grid (eq. 20) and insert the
// floor points that the grid confirms (eq. 19, 21). Sensor model detail: a 4 cm layer holding a
// horizontal floor is only partly free where a ray passes above the floor inside it, so a crossed
// cell of the layer touching [g - verify_tolerance, g + verify_tolerance] is not updated while the
// ray stays above g - verify_tolerance in it, for g the column's known floor height and for g the
// height h of the floor plane the ray ends on. Without this, grazing rays erase far floor cells.
void UpdateMaps(const MapParams& params, const MapInput& input, MapState* state);

// The FOG of the state's window (eq. 22-25 and algorithm classify). Obstacle heights are the top
// of the highest occupied layer; other heights are floor heights.
Fog ComputeFog(const MapParams& params, const MapState& state);

// ---------------------------------------------------------------------------------------------
// Ground truth and scores.

// The FOG of exact geometry: the paper's classification applied to `solids_G`, boxes in the grid
// frame. The floor is NOT added: pass it as a box whose top face is at z = 0 (e.g. centre z =
// -0.005, half height 0.005). Rule per cell: sample truth_samples^2 points at the centres of a
// regular sub-grid of the cell; at each, the floor is the highest exposed top (no other solid
// right above it) of a floor candidate (an upward-facing box top within 10 deg of horizontal,
// no higher than camera_height, at least min_floor_length x min_floor_width). The cell's floor
// h_f is the highest sample floor (as the floor map keeps the highest floor); obstacle and
// ceiling heights are the highest top and lowest bottom (clamped to h_f) over all samples of the
// solid parts whose top exceeds h_f + obstacle_margin; eq. (24) and classify then apply as on the
// estimated maps. A cell with no solid under any sample has no floor to stand on: border
// without a height, as VoidParams makes it on the estimated maps.
Fog GroundTruthFog(const std::vector<OrientedBox>& solids_G, const GridWindow& window,
                   const FogParams& params);

// What the planner makes of a cell type: floor and stairs are standable, a tunnel is crawl-only,
// border and obstacle are blocked.
enum class Traversability : uint8_t { kUnknown = 0, kStandable, kCrawlOnly, kBlocked };
Traversability TraversabilityOf(CellType type);

// How a cell of an estimated FOG compares with the ground truth by traversability. The cell is
// right at a truth cell whose class is its own and, for a standable cell, whose height is within
// h_floor of its own (params.h_floor); a cell right at none of its 8 neighbours nor itself is
// wrong. A standable cell is unsafe where the truth at it and at all 8 neighbours is blocked or
// crawl-only.
enum class FogCellComparison : uint8_t {
  kUnobserved = 0,  // unknown in the estimate or in the truth, or outside the truth's window
  kRight,           // right at the cell itself
  kRightNearby,     // right at a neighbour only (a class edge smeared by a cell)
  kStandableEdge,   // standable, right at a neighbour, but blocked or crawl-only at the cell
  kWrongHeight,     // standable where the truth nearby is standable, at no height within h_floor
  kWrongClass,      // not standable, and right nowhere nearby (a floor lost, tunnel for blocked)
  kUnsafe,          // standable where the truth at the cell and all 8 neighbours is not
};
inline constexpr int kNumFogCellComparisons = 7;

// Lower-case name of a comparison ("right", "unsafe", ...).
const char* FogCellComparisonName(FogCellComparison c);

// Per cell of the estimate's window (window.Index order): its comparison with `truth`.
std::vector<FogCellComparison> CompareFog(const Fog& estimate, const Fog& truth,
                                          const FogParams& params);

// Agreement of an estimated FOG with the ground truth, over the cells of the estimate's window
// that the truth's window also holds (docs/scores.md).
struct FogScore {
  int observed = 0;       // cells whose estimated type is not unknown
  int correct = 0;        // observed cells whose type matches the truth
  double accuracy = 0;    // correct / observed, the six-type match (0 if none observed)
  // confusion[truth][estimate], CellType values as indices, over all common cells.
  std::array<std::array<int, kNumCellTypes>, kNumCellTypes> confusion{};
  // Cells counted per comparison (CompareFog), FogCellComparison values as indices.
  std::array<int, kNumFogCellComparisons> comparisons{};
  int traversability_cells = 0;  // observed cells whose truth is known
  double traversability = 0;     // share of them right by traversability (0 if none)
  int unsafe_cells = 0;          // standable where the truth at the cell and around is not
  int unsafe_cells_strict = 0;   // standable where the truth at the cell is not
  // |estimated - true| floor height over cells both hold standable, metres.
  int height_cells = 0;
  double height_error_median = 0;
  double height_error_p95 = 0;
  double height_error_max = 0;
};
FogScore ScoreFog(const Fog& estimate, const Fog& truth, const FogParams& params);

// A file that cannot be written (a folder that cannot be created, a full disk); the message
// names the file. The program maps it to its own exit code.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace fognav::perception

#endif  // FOGNAV_PERCEPTION_MAPPING_H_
