#include "scenarios/params.h"

#include <cerrno>
#include <cstdlib>
#include <iomanip>
#include <limits>
#include <sstream>
#include <type_traits>

#include "scenarios/scenario.h"

namespace fognav::scenarios {
namespace {

namespace nav = navigation;
namespace per = perception;

constexpr double kInf = std::numeric_limits<double>::infinity();

// the sane range of a parameter, inclusive
struct Range {
  double min, max;
};
constexpr Range kShare{0, 1};         // a fraction or probability
// a probability whose log-odds must be finite
constexpr Range kOpenProbability{1e-6, 1 - 1e-6};
constexpr Range kMetres{0, 10};       // a length in the robot's world
constexpr Range kPositiveMetres{1e-6, 10};  // a length something divides by
constexpr Range kAnyMetres{0, kInf};  // a length where +inf turns a limit off
constexpr Range kAngle{0, M_PI};      // radians
constexpr Range kFactor{0, 100};      // a cost factor, ratio or count of sigmas
constexpr Range kPixels{0, 256};      // a size or tolerance in pixels
constexpr Range kCount{0, 1000000};   // a count
constexpr Range kFlag{0, 1};          // a bool

std::string Odd(double v) { return int(v) % 2 == 1 ? "" : "expected an odd number"; }
std::string Multiple16(double v) { return int(v) % 16 == 0 ? "" : "expected a multiple of 16"; }

// A row for the field reached from RunParams through `members` (a chain of member pointers).
template <typename... Members>
ParamInfo Row(std::string name, Range range, std::string meaning, Members... members) {
  using Field = std::remove_cv_t<
      std::remove_reference_t<decltype((std::declval<RunParams&>().*....*members))>>;
  static_assert(std::is_same_v<Field, double> || std::is_same_v<Field, int> ||
                    std::is_same_v<Field, bool> || std::is_enum_v<Field>,
                "parameters are double, int, bool or an enumeration");
  ParamInfo info;
  info.name = std::move(name);
  info.type = std::is_same_v<Field, double> ? ParamType::kDouble
              : std::is_same_v<Field, int>  ? ParamType::kInt
              : std::is_same_v<Field, bool> ? ParamType::kBool
                                            : ParamType::kChoice;
  info.min = range.min;
  info.max = range.max;
  info.meaning = std::move(meaning);
  info.get = [=](const RunParams& p) { return double((p.*....*members)); };
  info.set = [=](RunParams* p, double v) { ((*p).*....*members) = Field(v); };
  return info;
}

// the rows of one SegmentParams (stereo and ideal depth each have one)
void AddSegmentRows(const std::string& s, per::SegmentParams PerceptionParams::*which,
                    std::vector<ParamInfo>* t) {
  using S = per::SegmentParams;
  const auto P = &RunParams::perception;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(s + "." + key, r, meaning, P, which, field));
  };
  add("n_min", {2, 1000}, "N_min: fewest points of a line segment", &S::n_min);
  add("c_max", {1, 1000}, "C_max: consecutive same-side points that force a split", &S::c_max);
  add("r_seed", kFactor, "r_sigma threshold for the three lines of a seed (eq. 13)", &S::r_seed);
  add("r_grow", kFactor, "r_sigma threshold for growing a region by a line (eq. 14)", &S::r_grow);
  add("d_cord", kMetres, "UB split: chord distance threshold, metres", &S::d_cord);
  add("d_line", kMetres, "UB: end point distance to the plane for line membership, metres",
      &S::d_line);
  add("trade_window", {1, 99}, "side of the window for trading points, pixels (odd)",
      &S::trade_window);
  t->back().rule = Odd;
  add("sigma_min", kPositiveMetres, "floor on a line's sigma and a plane's rms in r_sigma, metres",
      &S::sigma_min);
  add("side_tolerance", kMetres, "residuals below this count as on the line, metres",
      &S::side_tolerance);
  add("jump_ratio", kFactor, "relative depth jump that cuts a scan line", &S::jump_ratio);
  add("max_gap_px", kPixels, "invalid pixels a line segment may bridge", &S::max_gap_px);
  add("min_plane_points", kCount, "planes with fewer points are dropped", &S::min_plane_points);
  add("trade_lines", kFlag, "post-processing: trade lines between planes", &S::trade_lines);
  add("trade_points", kFlag, "post-processing: trade points between planes", &S::trade_points);
  add("merge_planes", kFlag, "post-processing: merge neighbouring coplanar regions",
      &S::merge_planes);
  add("ray_noise", kFlag, "eq. (13, 14) use the spread of noise along the rays", &S::ray_noise);
  add("offset_sigmas", kFactor, "a line fits a plane only within this many standard errors",
      &S::offset_sigmas);
  add("correlation_px", {1, 256}, "neighbouring points that share one stereo window",
      &S::correlation_px);
  add("offset_min", kMetres, "offsets up to this always pass the offset test, metres",
      &S::offset_min);
  add("merge_across_missing", kFlag, "regions separated only by missing points are neighbours",
      &S::merge_across_missing);
  add("merge_coplanar", kFlag, "also merge coplanar regions that are not neighbours",
      &S::merge_coplanar);
}

// stereo matching (perception::StereoParams)
void AddStereoParamsRows(std::vector<ParamInfo>* t) {
  const auto P = &RunParams::perception;
  using S = per::StereoParams;
  const auto W = &PerceptionParams::stereo;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("stereo.") + key, r, meaning, P, W, field));
  };
  add("min_disparity", {-256, 256}, "smallest disparity searched, pixels", &S::min_disparity);
  add("num_disparities", {16, 256}, "disparity search range, pixels (a multiple of 16)",
      &S::num_disparities);
  t->back().rule = Multiple16;
  add("block_size", {1, 31}, "matching block side, pixels (odd)", &S::block_size);
  t->back().rule = Odd;
  add("p1", {0, 1e6}, "SGM small-change penalty; 0 = 8 * channels * block_size^2", &S::p1);
  add("p2", {0, 1e6}, "SGM large-change penalty; 0 = 32 * channels * block_size^2", &S::p2);
  add("disp12_max_diff", {-1, 256}, "OpenCV's left-right test, pixels; < 0 disables",
      &S::disp12_max_diff);
  add("pre_filter_cap", {1, 63}, "clip of the x-derivative prefilter", &S::pre_filter_cap);
  add("uniqueness_ratio", {0, 100}, "percent margin of the best over the second-best cost",
      &S::uniqueness_ratio);
  add("speckle_window_size", {0, 100000}, "largest speckle removed, pixels; 0 disables",
      &S::speckle_window_size);
  add("speckle_range", kPixels, "disparity variation within one speckle, pixels",
      &S::speckle_range);
  add("full_dp", kFlag, "OpenCV MODE_HH (full 8-path) instead of MODE_SGBM", &S::full_dp);
  add("three_way", kFlag, "OpenCV MODE_SGBM_3WAY instead of MODE_SGBM (unless full_dp)",
      &S::three_way);
  add("grey", kFlag, "match grey levels, not colours", &S::grey);
  add("range_margin", {-1, 256},
      "search what a half-resolution matching finds +- this, pixels; < 0 = whole range",
      &S::range_margin);
  add("range_min_pixels", {1, 100000},
      "disparities fewer half-resolution pixels have are left out of the search",
      &S::range_min_pixels);
  add("pad_left", kFlag, "pad the images on the left so border columns get disparities",
      &S::pad_left);
  add("max_depth", {0.1, 1000}, "farther points are dropped, metres", &S::max_depth);
  add("refine_iterations", {0, 100}, "Gauss-Newton steps refining disparities to sub-pixel",
      &S::refine_iterations);
  add("refine_window", {1, 31}, "side of the refinement window, pixels (odd)", &S::refine_window);
  t->back().rule = Odd;
  add("refine_left_right_tolerance", kPixels,
      "refined left and right disparities must agree within this, pixels; 0 = no check",
      &S::refine_left_right_tolerance);
  add("left_right_check", kFlag, "match a second time right to left and compare",
      &S::left_right_check);
  add("left_right_tolerance", kPixels, "the two matchings must agree within this, pixels",
      &S::left_right_tolerance);
  add("edge_margin", kPixels, "depth-edge rims: reach along a row, pixels; 0 marks nothing",
      &S::edge_margin);
  add("edge_jump", kPixels, "depth-edge rims: smallest disparity jump, pixels", &S::edge_jump);
  add("edge_depth_ratio", kShare, "depth-edge rims: smallest relative depth jump in a column",
      &S::edge_depth_ratio);
}

// plane segmentation, for stereo and for ideal depth (perception::SegmentParams)
void AddSegmentationRows(std::vector<ParamInfo>* t) {
  AddSegmentRows("segmentation", &PerceptionParams::segment, t);
  AddSegmentRows("segmentation_ideal", &PerceptionParams::segment_ideal, t);
}

// the perception cycle (PerceptionParams)
void AddPerceptionParamsRows(std::vector<ParamInfo>* t) {
  const auto P = &RunParams::perception;
  t->push_back(Row("perception.subsample", kFlag, "segment a 2x sub-sampled image", P,
                  &PerceptionParams::subsample));
  t->push_back(Row("perception.rim_keep_height", kAnyMetres,
                  "column-rim points this high above the robot's floor are kept, metres", P,
                  &PerceptionParams::rim_keep_height));
  t->push_back(Row("perception.view_every_steps", {0, 1000},
                  "with noisy odometry, a view every this many footsteps walked; 0 = none", P,
                  &PerceptionParams::view_every_steps));
}

// labelled points (perception::LabelParams)
void AddLabelParamsRows(std::vector<ParamInfo>* t) {
  const auto P = &RunParams::perception;
  using S = per::LabelParams;
  const auto W = &PerceptionParams::label;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("label.") + key, r, meaning, P, W, field));
  };
  add("max_tilt_deg", {0, 90}, "a floor candidate's normal lies within this of +z, degrees",
      &S::max_tilt_deg);
  add("min_floor_length", kMetres, "a floor candidate's least length, metres",
      &S::min_floor_length);
  add("min_floor_width", kMetres, "a floor candidate's least width, metres", &S::min_floor_width);
  add("self_filter_margin", kMetres, "points within the body grown by this are dropped, metres",
      &S::self_filter_margin);
  add("max_range", kAnyMetres, "points farther from the camera are dropped, metres",
      &S::max_range);
  add("min_height_sigma", kMetres, "floor on a floor candidate's height sigma, metres",
      &S::min_height_sigma);
  add("face_clip", kMetres, "floor points smeared past a face lose their height within this",
      &S::face_clip);
}

// the 3D occupancy grid (perception::OccupancyParams)
void AddOccupancyParamsRows(std::vector<ParamInfo>* t) {
  const auto P = &RunParams::perception;
  const auto M = &PerceptionParams::map;
  using S = per::OccupancyParams;
  const auto W = &per::MapParams::grid;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("grid.") + key, r, meaning, P, M, W, field));
  };
  add("size_x", {8, 1000}, "cells along x", &S::size_x);
  add("size_y", {8, 1000}, "cells along y", &S::size_y);
  add("size_z", {4, 64}, "layers", &S::size_z);
  add("resolution", {0.01, 1}, "cell side, metres", &S::resolution);
  add("z_min", {-1, 1}, "bottom of layer 0 in the grid frame, metres", &S::z_min);
  add("p_hit", kOpenProbability, "eq. (18): P(occupied) for the cell a ray ends in", &S::p_hit);
  add("p_miss", kOpenProbability, "eq. (18): P(occupied) for a cell a ray crosses", &S::p_miss);
  add("p_min", kOpenProbability, "lower clamp of a cell's probability", &S::p_min);
  add("p_max", kOpenProbability, "upper clamp of a cell's probability", &S::p_max);
  add("one_ray_per_end_cell", kFlag, "trace one ray per end cell and frame",
      &S::one_ray_per_end_cell);
  add("min_hits_per_frame", {1, 1000}, "points that must end in a cell for a hit in a frame",
      &S::min_hits_per_frame);
  add("overrule_ratio", kFactor, "rays this many times nearer set far evidence free; 0 = off",
      &S::overrule_ratio);
  add("overrule_below", kMetres, "only cells below this height are overruled, metres",
      &S::overrule_below);
  add("p_occ", kOpenProbability, "P_occ of eq. (19, 22, 23): a cell above it is occupied",
      &S::p_occ);
}

// the floor height map (perception::FloorParams)
void AddFloorParamsRows(std::vector<ParamInfo>* t) {
  const auto M = &PerceptionParams::map;
  const auto P = &RunParams::perception;
  using S = per::FloorParams;
  const auto W = &per::MapParams::floor;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("floor.") + key, r, meaning, P, M, W, field));
  };
  add("gate", kMetres, "epsilon of eq. (21), metres", &S::gate);
  add("smoothing", kShare, "nu of eq. (21)", &S::smoothing);
  add("min_sigma", kMetres, "floor on a cell's height sigma, metres", &S::min_sigma);
  add("replace_ratio", kFactor, "variance ratio at which a height replaces a cell's",
      &S::replace_ratio);
  add("lower_doubt", kMetres, "a lower height within this is doubted, metres; 0 = off",
      &S::lower_doubt);
  add("on_plane_sigmas", kFactor, "a floor point counts within this many sigmas of its plane",
      &S::on_plane_sigmas);
  add("on_plane_min", kMetres, "... or within this, metres", &S::on_plane_min);
  add("minor_share", kShare, "a frame's minor lower height with fewer points is left out",
      &S::minor_share);
  add("minor_range", kMetres, "... if within this below the other, metres", &S::minor_range);
  add("verify_tolerance", kMetres, "eq. (19, 20) read the layers within this of h, metres",
      &S::verify_tolerance);
}

// FOG classification (perception::FogParams)
void AddFogParamsRows(std::vector<ParamInfo>* t) {
  const auto M = &PerceptionParams::map;
  const auto P = &RunParams::perception;
  using S = per::FogParams;
  const auto W = &per::MapParams::fog;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("fog.") + key, r, meaning, P, M, W, field));
  };
  add("h_floor", kMetres, "largest floor change walked on ordinarily, metres", &S::h_floor);
  add("h_stairs", kMetres, "highest step, metres", &S::h_stairs);
  add("h_tunnel", kMetres, "lowest ceiling to crawl under, metres", &S::h_tunnel);
  add("h_robot", kMetres, "standing height, metres", &S::h_robot);
  add("neighbourhood_radius", {0, 10}, "U(x, y) of eq. (24): (2r+1)^2 cells",
      &S::neighbourhood_radius);
  add("max_height_sigma", kAnyMetres, "floor heights with more sigma are unreliable, metres",
      &S::max_height_sigma);
  add("obstacle_margin", kMetres, "a layer is above the floor from h_f + this, metres",
      &S::obstacle_margin);
  add("ignore_risers", kFlag, "risers in the lower neighbour's column are no obstacle",
      &S::ignore_risers);
  add("ignore_low_unknown", kFlag, "low points beside a floor leave a floorless cell unknown",
      &S::ignore_low_unknown);
  add("require_known_neighbourhood", kFlag,
      "floor or stairs at the edge of the seen stay unknown", &S::require_known_neighbourhood);
  add("min_unknown_around", {1, 1000}, "unknown cells around that make that edge",
      &S::min_unknown_around);
  add("infer_tops", kFlag, "infer tops that no plane covered", &S::infer_tops);
  add("top_band_share", kShare, "share of a top's cells in its two highest layers",
      &S::top_band_share);
  add("top_band_max_width", kMetres, "widest rough patch that is still a top, metres",
      &S::top_band_max_width);
  add("ceiling_gap", {0, 100}, "floor cells between tunnel cells that one slab spans; 0 = off",
      &S::ceiling_gap);
  add("camera_height", kMetres, "floor candidates no higher than this, metres",
      &S::camera_height);
  add("min_floor_length", kMetres, "a floor candidate's least length, metres",
      &S::min_floor_length);
  add("min_floor_width", kMetres, "a floor candidate's least width, metres", &S::min_floor_width);
  add("truth_samples", {1, 16}, "ground truth samples this squared points per cell",
      &S::truth_samples);
}

// where the floor ends (perception::VoidParams)
void AddVoidParamsRows(std::vector<ParamInfo>* t) {
  const auto M = &PerceptionParams::map;
  const auto P = &RunParams::perception;
  using S = per::VoidParams;
  const auto W = &per::MapParams::no_floor;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("void.") + key, r, meaning, P, M, W, field));
  };
  add("range", kMetres, "empty rays count up to this along the floor, metres", &S::range);
  add("min_distance", kMetres, "rays meeting the floor nearer do not count, metres",
      &S::min_distance);
  add("drop_floor", kFlag, "empty rays also take back a floor height", &S::drop_floor);
  add("texture_window", {1, 99}, "side of the texture window, pixels", &S::texture_window);
  add("max_contrast", {0, 255}, "grey levels the window may vary by", &S::max_contrast);
  add("min_width_px", kPixels, "narrowest region of empty pixels, pixels", &S::min_width_px);
  add("floor_tolerance", kMetres, "a height within this of the robot's floor may drop, metres",
      &S::floor_tolerance);
  add("min_pixels", {1, 100000}, "empty pixels landing in a cell for a frame's evidence",
      &S::min_pixels);
  add("min_frames", {0, 1000}, "frames of evidence for no floor; 0 = off", &S::min_frames);
}

// localization against vertical planes (perception::LocalizationParams)
void AddLocalizationParamsRows(std::vector<ParamInfo>* t) {
  const auto P = &RunParams::perception;
  using S = per::LocalizationParams;
  const auto W = &PerceptionParams::localization;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("localization.") + key, r, meaning, P, W, field));
  };
  add("max_normal_z", kShare, "|n_z| of a plane that counts as vertical", &S::max_normal_z);
  add("min_image_fraction", kShare, "fewest points, as a share of the image's pixels",
      &S::min_image_fraction);
  add("max_rms", kMetres, "largest RMS residual of a wall's points, metres", &S::max_rms);
  add("min_length", kMetres, "shortest horizontal extent of a wall, metres", &S::min_length);
  add("max_range", kMetres, "farthest plane centroid used, metres", &S::max_range);
  add("angle_sigma", kAngle, "measurement noise of a wall's angle, rad", &S::angle_sigma);
  add("offset_sigma", kMetres, "measurement noise of a wall's offset at range 0, metres",
      &S::offset_sigma);
  add("offset_sigma_per_m2", kMetres, "its growth per square metre of range",
      &S::offset_sigma_per_m2);
  add("gate", kFactor, "Mahalanobis distance within which a plane matches a landmark", &S::gate);
  add("near_angle", kAngle, "an unmatched plane this near a landmark is ambiguous, rad",
      &S::near_angle);
  add("near_offset", kMetres, "... and this near, metres", &S::near_offset);
  add("max_landmarks", {0, 100000}, "most landmarks kept", &S::max_landmarks);
  ParamInfo mode = Row("localization.mode", {0, 3},
                       "odometry (footsteps alone), walls, visual (odometry, visual odometry and "
                       "walls fused) or truth",
                       P, W, &S::mode);
  mode.choices = {"odometry", "walls", "visual", "truth"};
  t->push_back(mode);
}

// visual odometry against keyframes (perception::VisualOdometryParams)
void AddVisualOdometryRows(std::vector<ParamInfo>* t) {
  const auto P = &RunParams::perception;
  using S = per::VisualOdometryParams;
  const auto W = &PerceptionParams::visual_odometry;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("visual_odometry.") + key, r, meaning, P, W, field));
  };
  add("min_depth", kMetres, "nearer points are not used, metres", &S::min_depth);
  add("max_depth", kMetres, "farther points are not used, metres", &S::max_depth);
  add("max_depth_diff", kMetres, "largest depth difference of a correspondence, metres",
      &S::max_depth_diff);
  add("iterations", {1, 1000}, "iterations per pyramid level", &S::iterations);
  add("max_points_part", kShare, "share of the image's points used", &S::max_points_part);
  add("max_correction", kMetres, "largest correction of the seed used, metres",
      &S::max_correction);
  add("max_correction_angle", kAngle, "largest rotation of the seed used, rad",
      &S::max_correction_angle);
  add("agree_depth", kMetres, "a point agrees within this depth, metres", &S::agree_depth);
  add("agree_depth_per_m", kShare, "... plus this per metre of depth", &S::agree_depth_per_m);
  add("min_agreement", kShare, "fewest agreeing points, as a share", &S::min_agreement);
  add("min_overlap", kShare, "least keyframe overlap to register against it", &S::min_overlap);
  add("keyframe_overlap", kShare, "a new keyframe where no keyframe overlaps more",
      &S::keyframe_overlap);
  add("max_keyframes", {1, 10000}, "most keyframes kept", &S::max_keyframes);
  add("sigma_xy", kMetres, "registration noise of the position, metres", &S::sigma_xy);
  add("sigma_yaw", kAngle, "registration noise of the heading, rad", &S::sigma_yaw);
  add("gate", kFactor, "Mahalanobis distance to the odometry beyond which it is rejected",
      &S::gate);
}

// the planner (navigation::PlannerParams); goal_tolerance, kneel_offset, max_step_length and
// max_step_sideways come from the scenario's goal and the controller, so they are not here
void AddPlannerParamsRows(std::vector<ParamInfo>* t) {
  using S = nav::PlannerParams;
  const auto W = &RunParams::planner;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("planner.") + key, r, meaning, W, field));
  };
  add("shoulder_width", kMetres, "upright extent across the heading, metres", &S::shoulder_width);
  add("depth", kMetres, "upright extent along the heading, metres", &S::depth);
  add("crawl_length", kMetres, "crawling extent along the heading, metres", &S::crawl_length);
  add("crawl_width", kMetres, "crawling extent across the heading, metres", &S::crawl_width);
  add("crawl_offset", kMetres, "centre of the crawling extent ahead of the origin, metres",
      &S::crawl_offset);
  add("margin", kMetres, "safety margin on every side of both footprints, metres", &S::margin);
  add("level_margin", kMetres, "the floor under the footprint grown by this is level, metres",
      &S::level_margin);
  add("stance_width", kMetres, "width across which the soles stand level, metres",
      &S::stance_width);
  add("body_back", kMetres, "the standing body reaches this far behind the origin, metres",
      &S::body_back);
  add("body_front", kMetres, "... and this far ahead, metres", &S::body_front);
  add("arm_reach", kMetres, "the hands reach this far beside the origin, metres", &S::arm_reach);
  add("hand_low", kMetres, "tops higher than this above the floor meet the hands, metres",
      &S::hand_low);
  add("hidden_reach", kMetres, "unknown cells within this of such a top count as it, metres",
      &S::hidden_reach);
  add("body_touch_cost", kFactor, "cost of a move that touches the body rectangle",
      &S::body_touch_cost);
  add("edge_touch_cost", kFactor, "cost of a move that touches a maybe-top", &S::edge_touch_cost);
  add("head_reach", kMetres, "the standing head reaches this far from the origin, metres",
      &S::head_reach);
  add("head_low", kMetres, "nothing within head_reach may rise higher than this, metres",
      &S::head_low);
  add("h_floor", kMetres, "larger floor changes between neighbours are steps, metres",
      &S::h_floor);
  add("h_stairs", kMetres, "largest step climbed, metres", &S::h_stairs);
  add("max_stairs_heading_error", kAngle, "a step is taken facing it within this, rad",
      &S::max_stairs_heading_error);
  add("crawl_zone_radius", kMetres, "cells this near a tunnel allow crawling, metres",
      &S::crawl_zone_radius);
  add("kneel_clear_reach", kMetres, "getting down or up, the body is low beyond this, metres",
      &S::kneel_clear_reach);
  add("get_up_under_seen_headroom", kFlag, "get up only where the headroom has been seen",
      &S::get_up_under_seen_headroom);
  add("unseen_headroom_clearance", kMetres,
      "getting up under unseen headroom, this far from any tunnel cell, metres",
      &S::unseen_headroom_clearance);
  add("blind_moves_stay_known", kFlag, "backward and side moves keep to known cells",
      &S::blind_moves_stay_known);
  add("crawl_stays_known", kFlag, "forward crawls keep to known cells", &S::crawl_stays_known);
  add("walk_factor", kFactor, "cost per metre walking forward", &S::walk_factor);
  add("backward_factor", kFactor, "cost per metre walking backward", &S::backward_factor);
  add("sidestep_factor", kFactor, "cost per metre side-stepping", &S::sidestep_factor);
  add("stairs_factor", kFactor, "cost per metre on steps", &S::stairs_factor);
  add("crawl_factor", kFactor, "cost per metre crawling forward", &S::crawl_factor);
  add("turn_cost_per_rad", kFactor, "cost of turning in place per radian", &S::turn_cost_per_rad);
  add("posture_change_cost", kFactor, "cost of getting down or up", &S::posture_change_cost);
  add("unknown_penalty", kFactor, "cost added per metre on unknown cells", &S::unknown_penalty);
  add("clearance_weight", kFactor, "weight of the clearance cost", &S::clearance_weight);
  add("clearance_radius", kMetres, "obstacles within this add clearance cost, metres",
      &S::clearance_radius);
  add("clearance_height_ref", {0.001, 10}, "obstacle height of clearance cost 1, metres",
      &S::clearance_height_ref);
  add("clearance_height_cap", kMetres, "obstacle heights count up to this, metres",
      &S::clearance_height_cap);
  add("exit_factor", kFactor, "a path to the window's edge ends at this times the rest",
      &S::exit_factor);
  add("exit_band", kMetres, "width of the window's edge band a way out may end in, metres",
      &S::exit_band);
  add("start_escape_radius", kMetres, "a blocked start escapes to poses this near, metres",
      &S::start_escape_radius);
}

// the mission's behaviour (ExecutionLimits)
void AddExecutionLimitsRows(std::vector<ParamInfo>* t) {
  using S = ExecutionLimits;
  const auto W = &RunParams::mission;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("mission.") + key, r, meaning, W, field));
  };
  add("walk", {0.01, 10}, "longest walk per motion command, metres", &S::walk);
  add("sidestep", {0.01, 10}, "longest side-step per motion command, metres", &S::sidestep);
  add("crawl", {0.01, 10}, "longest crawl per motion command, metres", &S::crawl);
  add("min_approach", kMetres, "without a way, approach the goal if that gains this, metres",
      &S::min_approach);
  add("fresh_look_keep", kShare, "share of the grid's evidence kept for a fresh look",
      &S::fresh_look_keep);
  add("fresh_look_distance", kMetres, "no second fresh look within this, metres",
      &S::fresh_look_distance);
  add("explore_beyond", kMetres, "explorations go this far past the window's edge, metres",
      &S::explore_beyond);
  add("max_explorations", {0, 1000}, "explorations per mission", &S::max_explorations);
  add("explore_patience", {1, 1000}, "cycles an exploration goes without a way showing",
      &S::explore_patience);
  add("inspect_range", kMetres, "evidence seen only from farther is inspected, metres",
      &S::inspect_range);
  add("inspect_near_range", kMetres, "the same, second round, metres", &S::inspect_near_range);
  add("inspect_reach", kMetres, "an inspection goes to within this of its pose, metres",
      &S::inspect_reach);
  add("peek_reach", kMetres, "a peek goes to within this of its pose, metres", &S::peek_reach);
  add("peek_lead", kMetres, "a peek looks this far beyond the blind move, metres", &S::peek_lead);
  add("back_off", kMetres, "with nothing else left, back off this far to look again, metres",
      &S::back_off);
  add("thrash_cycles", {1, 100000}, "cycles that may count as going back and forth",
      &S::thrash_cycles);
  add("thrash_radius", kMetres, "positions within this count as going back and forth, metres",
      &S::thrash_radius);
  add("circling_arrivals", {1, 100000}, "arrivals at one pose that call for a look",
      &S::circling_arrivals);
  add("lost_yaw", kAngle, "crawling with more yaw sigma looks to both sides, rad", &S::lost_yaw);
  add("side_look_pan", {0, 1.6}, "pan of the side looks, rad", &S::side_look_pan);
  add("high_ceiling", kMetres, "a ceiling this high is barely seen standing, metres",
      &S::high_ceiling);
  add("high_ceiling_range", kMetres, "such a ceiling within this is near, metres",
      &S::high_ceiling_range);
  add("underside_elevation", {0, 1.6}, "look this far above the horizon before crawling, rad",
      &S::underside_elevation);
  add("look_ahead", kMetres, "the looks aim at the plan's pose this far on, metres",
      &S::look_ahead);
  add("level_views", kFlag, "near a high ceiling every other view looks level", &S::level_views);
  add("keep_plan_margin", kFactor, "keep a plan costing at most this more than a new one",
      &S::keep_plan_margin);
  add("keep_plan_share", kShare, "... or this share of the new plan's cost, if more",
      &S::keep_plan_share);
  add("edge_lookahead", kMetres, "step edges on the plan within this are measured, metres",
      &S::edge_lookahead);
  add("edge_min_range", kMetres, "not nearer than this, metres", &S::edge_min_range);
  add("edge_look_range", kMetres, "a look of its own at a step edge within this, metres",
      &S::edge_look_range);
  add("heel_margin", kMetres, "a step lands the heel this far past the edge, metres",
      &S::heel_margin);
  add("toe_margin", kMetres, "a walk up to a riser stops the toes this short, metres",
      &S::toe_margin);
  add("edge_correction", kMetres, "largest correction of a step from the plan, metres",
      &S::edge_correction);
}

// measuring step edges (perception::StepEdgeParams)
void AddStepEdgeParamsRows(std::vector<ParamInfo>* t) {
  using S = per::StepEdgeParams;
  const auto W = &RunParams::step_edge;
  auto add = [&](const char* key, Range r, const char* meaning, auto field) {
    t->push_back(Row(std::string("step_edge.") + key, r, meaning, W, field));
  };
  add("level_tolerance", kMetres, "a point is on a level within this, metres",
      &S::level_tolerance);
  add("half_width", kMetres, "half the band across the heading, metres", &S::half_width);
  add("behind", kMetres, "the band starts this far behind the origin, metres", &S::behind);
  add("reach", kMetres, "... and ends this far ahead, metres", &S::reach);
  add("bin", {0.001, 1}, "bin length along the heading, metres", &S::bin);
  add("density_share", kShare, "a bin with this share of the median points is the tread's",
      &S::density_share);
  add("min_points", {1, 1000000}, "fewer points of the tread: no measurement", &S::min_points);
  add("beyond", kMetres, "lower points must lie within this beyond the edge, metres", &S::beyond);
}

std::vector<ParamInfo> MakeTable() {
  std::vector<ParamInfo> t;
  AddStereoParamsRows(&t);
  AddSegmentationRows(&t);
  AddPerceptionParamsRows(&t);
  AddLabelParamsRows(&t);
  AddOccupancyParamsRows(&t);
  AddFloorParamsRows(&t);
  AddFogParamsRows(&t);
  AddVoidParamsRows(&t);
  AddLocalizationParamsRows(&t);
  AddVisualOdometryRows(&t);
  AddPlannerParamsRows(&t);
  AddExecutionLimitsRows(&t);
  AddStepEdgeParamsRows(&t);
  return t;
}

}  // namespace

const std::vector<ParamInfo>& ParamTable() {
  static const std::vector<ParamInfo> kTable = MakeTable();
  return kTable;
}

const ParamInfo* FindParam(const std::string& name) {
  for (const ParamInfo& info : ParamTable()) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

std::vector<std::string> ParamSections() {
  std::vector<std::string> sections;
  for (const ParamInfo& info : ParamTable()) {
    std::string section = info.name.substr(0, info.name.find('.'));
    if (sections.empty() || sections.back() != section) sections.push_back(section);
  }
  return sections;
}

std::string FormatParamValue(const ParamInfo& info, double value) {
  if (info.type == ParamType::kBool) return value != 0 ? "true" : "false";
  if (info.type == ParamType::kChoice) {
    const size_t i = size_t(value);
    return i < info.choices.size() ? info.choices[i] : "?";
  }
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  if (info.type == ParamType::kInt) return std::to_string(static_cast<long long>(value));
  // the shortest of 15 and 17 digits that reads back as the same double
  for (int digits : {15, 17}) {
    std::ostringstream out;
    out << std::setprecision(digits) << value;
    if (digits == 17 || std::strtod(out.str().c_str(), nullptr) == value) return out.str();
  }
  return "";
}

std::string ParseParamValue(const ParamInfo& info, const std::string& text, double* value) {
  const std::string got = ", got '" + text + "'";
  if (info.type == ParamType::kBool) {
    if (text == "true") {
      *value = 1;
    } else if (text == "false") {
      *value = 0;
    } else {
      return "expected true or false" + got;
    }
    return "";
  }
  if (info.type == ParamType::kChoice) {
    for (size_t i = 0; i < info.choices.size(); ++i) {
      if (text == info.choices[i]) {
        *value = double(i);
        return "";
      }
    }
    std::string names;
    for (const std::string& c : info.choices) names += (names.empty() ? "" : ", ") + c;
    return "expected one of " + names + got;
  }
  const bool is_int = info.type == ParamType::kInt;
  const char* what = is_int ? "expected an integer" : "expected a number";
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return what + got;
  // YAML writes infinity .inf
  std::string number = text;
  if (!is_int && (number == ".inf" || number == "+.inf" || number == ".Inf" || number == ".INF")) {
    number = "inf";
  }
  errno = 0;
  char* end = nullptr;
  double parsed = 0;
  if (is_int) {
    const long long n = std::strtoll(number.c_str(), &end, 10);
    parsed = double(n);
  } else {
    parsed = std::strtod(number.c_str(), &end);
  }
  if (end == number.c_str() || *end != '\0' || errno == ERANGE || std::isnan(parsed)) {
    return what + got;
  }
  const bool infinite_ok = std::isinf(info.max) && parsed == kInf;
  if (!infinite_ok && (parsed < info.min || parsed > info.max)) {
    return std::string(is_int ? "expected an integer" : "expected a number") + " from " +
           FormatParamValue(info, info.min) + " to " + FormatParamValue(info, info.max) + got;
  }
  if (info.rule) {
    const std::string wrong = info.rule(parsed);
    if (!wrong.empty()) return wrong + got;
  }
  *value = parsed;
  return "";
}

void ApplySetFlag(const std::string& assignment, ParamOverrides* overrides) {
  const std::string flag = "--set " + assignment + ": ";
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos) {
    throw InputError(flag + "expected section.key=value");
  }
  const std::string name = assignment.substr(0, eq);
  const ParamInfo* info = FindParam(name);
  if (info == nullptr) {
    std::string sections;
    for (const std::string& s : ParamSections()) sections += (sections.empty() ? "" : ", ") + s;
    throw InputError(flag + name + ": unknown parameter (sections: " + sections +
                     "; `fognav params` lists them all)");
  }
  double value = 0;
  const std::string wrong = ParseParamValue(*info, assignment.substr(eq + 1), &value);
  if (!wrong.empty()) throw InputError(flag + name + ": " + wrong);
  (*overrides)[name] = value;
}

RunParams ResolveParams(const ParamOverrides& overrides) {
  RunParams params;
  for (const auto& [name, value] : overrides) {
    const ParamInfo* info = FindParam(name);
    if (info == nullptr) throw std::logic_error("ResolveParams: unknown parameter " + name);
    info->set(&params, value);
  }
  return params;
}

std::vector<std::pair<std::string, double>> ChangedParams(const RunParams& params) {
  static const RunParams kDefaults;
  std::vector<std::pair<std::string, double>> changed;
  for (const ParamInfo& info : ParamTable()) {
    const double value = info.get(params);
    if (value != info.get(kDefaults)) changed.emplace_back(info.name, value);
  }
  return changed;
}

nlohmann::json ParamsJson(const RunParams& params) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, value] : ChangedParams(params)) {
    const ParamInfo& info = *FindParam(name);
    if (info.type == ParamType::kBool) {
      out[name] = value != 0;
    } else if (info.type == ParamType::kChoice) {
      out[name] = FormatParamValue(info, value);
    } else if (info.type == ParamType::kInt) {
      out[name] = static_cast<long long>(value);
    } else if (std::isinf(value)) {
      out[name] = FormatParamValue(info, value);
    } else {
      out[name] = value;
    }
  }
  return out;
}

void PrintParamTable(std::ostream& out) {
  static const RunParams kDefaults;
  const char* kTypes[] = {"number", "integer", "bool", "choice"};
  for (const ParamInfo& info : ParamTable()) {
    out << info.name << "\t" << kTypes[int(info.type)] << "\t"
        << FormatParamValue(info, info.get(kDefaults)) << "\t";
    if (info.type == ParamType::kBool) {
      out << "true/false";
    } else if (info.type == ParamType::kChoice) {
      for (size_t i = 0; i < info.choices.size(); ++i) out << (i ? "/" : "") << info.choices[i];
    } else {
      out << FormatParamValue(info, info.min) << ".." << FormatParamValue(info, info.max);
    }
    out << "\t" << info.meaning << "\n";
  }
}

void ApplyParam(const std::string& name, const std::string& value_text, const std::string& source,
                ParamOverrides* overrides) {
  const ParamInfo* info = FindParam(name);
  if (info == nullptr) {
    std::string sections;
    for (const std::string& s : ParamSections()) sections += (sections.empty() ? "" : ", ") + s;
    throw InputError(source + ": " + name + ": unknown parameter (sections: " + sections +
                     "; `fognav params` lists them all)");
  }
  double value = 0;
  const std::string wrong = ParseParamValue(*info, value_text, &value);
  if (!wrong.empty()) throw InputError(source + ": " + name + ": " + wrong);
  (*overrides)[name] = value;
}

}  // namespace fognav::scenarios
