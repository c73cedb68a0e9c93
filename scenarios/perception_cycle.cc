#include "scenarios/perception_cycle.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <iostream>

#include <nlohmann/json.hpp>

#include "navigation/planner.h"
#include "scenarios/output.h"
#include "scenarios/params.h"
#include "sim/controller.h"
#include "viz/pages.h"
#include "viz/pictures.h"

namespace fognav::scenarios {
namespace {

using Clock = std::chrono::steady_clock;

double MillisecondsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

nlohmann::json StereoJson(const perception::StereoScore& s) {
  return {{"valid", s.valid},
          {"median_error_px", s.median_error_px},
          {"bad_1px", s.bad_1px},
          {"median_depth_error", s.median_depth_error}};
}

nlohmann::json ScoreJson(const perception::SegmentationScore& s) {
  return {{"accuracy", s.accuracy}, {"coverage", s.coverage}, {"correct", s.correct},
          {"over", s.over},         {"under", s.under},       {"missed", s.missed},
          {"noise", s.noise},       {"planes", s.planes},     {"truth_surfaces", s.truth_surfaces}};
}

}  // namespace

nlohmann::json FogScoreJson(const perception::FogScore& s) {
  nlohmann::json cells = nlohmann::json::object();
  for (int k = 0; k < perception::kNumFogCellComparisons; ++k) {
    cells[perception::FogCellComparisonName(perception::FogCellComparison(k))] = s.comparisons[k];
  }
  return {{"types", s.accuracy},
          {"traversability", s.traversability},
          {"unsafe_cells", s.unsafe_cells},
          {"unsafe_cells_strict", s.unsafe_cells_strict},
          {"observed_cells", s.observed},
          {"height_error",
           {{"median", s.height_error_median},
            {"p95", s.height_error_p95},
            {"max", s.height_error_max},
            {"cells", s.height_cells}}},
          {"cells", cells}};
}

std::vector<sim::HeadAngles> StartSweep() {
  sim::LookAroundParams params;
  params.tilts.push_back(0.15);
  return sim::LookAroundSweep(params);
}

perception::LabelImage WorldSurfaces(const perception::LabelImage& surfaces,
                                     const sim::Humanoid& humanoid) {
  perception::LabelImage world = surfaces;
  for (int32_t& id : world.data) {
    if (id >= 0 && humanoid.IsRobotGeom(sim::SurfaceGeom(id))) id = -1;
  }
  return world;
}

namespace {
// the depth of the points, NaN on the robot's own body (its boxes grown by `margin`): the body
// moves with the camera, and visual odometry must not follow it
perception::DepthImage DepthOffBody(const perception::PointImage& points_C,
                                    const Eigen::Isometry3d& X_RC,
                                    const std::vector<sim::RobotBox>& body_R, double margin) {
  perception::DepthImage depth = perception::DepthOf(points_C);
  std::vector<std::pair<Eigen::Isometry3f, Eigen::Array3f>> boxes_C;  // X_BC, half size
  for (const sim::RobotBox& box : body_R) {
    boxes_C.push_back({(box.X_RB.inverse() * X_RC).cast<float>(),
                       box.half_size.cast<float>().array() + float(margin)});
  }
  for (size_t i = 0; i < depth.data.size(); ++i) {
    if (!std::isfinite(depth.data[i])) continue;
    for (const auto& [X_BC, half] : boxes_C) {
      if (((X_BC * points_C.points[i]).array().abs() <= half).all()) {
        depth.data[i] = std::numeric_limits<float>::quiet_NaN();
        break;
      }
    }
  }
  return depth;
}
}  // namespace

ViewResult PerceiveView(const PerceptionParams& params, DepthMode mode, const StereoView& view,
                        const sim::Humanoid& humanoid, const perception::Pose2& robot_G,
                        double floor_z, const Eigen::Isometry3d& X_RC,
                        const std::vector<sim::RobotBox>& body_R, perception::MapState* maps,
                        perception::LocalizationState* localization) {
  ViewResult result;
  result.robot_G = robot_G;
  // range data: stereo matching of the pair, or the depth buffer
  auto start = Clock::now();
  if (mode == DepthMode::kStereo) {
    result.points = perception::StereoPointImage(view.left, view.right, view.intrinsics,
                                                 params.stereo, &result.disparity);
  } else {
    result.points = perception::DepthPointImage(view.depth, view.intrinsics);
  }
  perception::LabelImage truth = perception::JoinCoplanarSurfaces(
      WorldSurfaces(view.surfaces, humanoid),
      mode == DepthMode::kStereo ? perception::DepthPointImage(view.depth, view.intrinsics)
                                 : result.points);
  perception::DepthImage truth_depth = view.depth;
  if (params.subsample) {
    result.points = perception::Subsample2x(result.points);
    truth = perception::Subsample2x(truth);
    truth_depth = perception::Subsample2x(truth_depth);
  }
  // the intrinsics of result.points
  const perception::CameraIntrinsics K_points =
      params.subsample ? perception::Subsample2x(view.intrinsics) : view.intrinsics;
  result.stereo_ms = MillisecondsSince(start);
  result.stereo = perception::ScoreStereo(result.points, truth_depth, K_points);

  // planes, scored against the surfaces the renderer saw
  start = Clock::now();
  result.planes = perception::SegmentPlanes(
      result.points, mode == DepthMode::kStereo ? params.segment : params.segment_ideal);
  result.segmentation_ms = MillisecondsSince(start);
  result.segmentation = perception::ScoreSegmentation(result.planes.labels, truth, truth_depth);

  // the pose, corrected by the walls seen before; the camera and the body go with it
  if (localization != nullptr) {
    const auto start_localization = Clock::now();
    // the image and the depth off the body only for the visual odometry
    const bool visual = params.localization.mode == perception::LocalizationMode::kVisual &&
                        !params.subsample;
    const perception::GrayImage gray =
        visual ? perception::ToGray(view.left) : perception::GrayImage();
    const perception::DepthImage depth =
        visual ? DepthOffBody(result.points, X_RC, body_R, params.label.self_filter_margin)
               : perception::DepthImage();
    perception::LocalizationView in;
    in.planes_C = &result.planes.planes;
    in.image_pixels = result.points.width * result.points.height;
    in.gray = visual ? &gray : nullptr;
    in.depth = visual ? &depth : nullptr;
    in.intrinsics = view.intrinsics;
    in.X_RC = X_RC;
    in.floor_z = floor_z;
    result.localization = perception::LocalizeView(params.localization, params.visual_odometry,
                                                   in, robot_G, localization);
    result.robot_G = result.localization.pose_G;
    result.localization_ms = MillisecondsSince(start_localization);
  }
  const Eigen::Isometry3d X_GR = perception::Planar(result.robot_G, floor_z);
  const Eigen::Isometry3d X_GC = X_GR * X_RC;
  result.X_GC = X_GC;
  std::vector<perception::OrientedBox> body_G;
  for (const sim::RobotBox& box : body_R) body_G.push_back({X_GR * box.X_RB, box.half_size});

  // maps
  start = Clock::now();
  perception::MapInput input;
  input.robot_G = result.robot_G;
  input.p_GC = X_GC.translation();
  // stereo: rim points of nearer surfaces give no obstacles (they may be fattened)
  perception::Image<uint8_t> rims;
  if (mode == DepthMode::kStereo) {
    rims = perception::DepthEdgeRims(result.disparity, params.stereo);
    if (params.subsample) rims = perception::Subsample2x(rims);
  }
  perception::LabelParams label = params.label;
  label.keep_column_rims_above = floor_z + params.rim_keep_height;
  input.points = perception::LabelPoints(label, result.points, result.planes, X_GC, body_G,
                                         rims.empty() ? nullptr : &rims);
  perception::Image<uint8_t> textureless =
      perception::TexturelessPixels(params.map.no_floor, view.left);
  if (params.subsample) textureless = perception::Subsample2x(textureless);
  input.empty_rays_G = perception::EmptyRays(
      params.map.no_floor, result.points, textureless,
      K_points, X_GC, floor_z, body_G, label.self_filter_margin);
  input.floor_z = floor_z;
  perception::UpdateMaps(params.map, input, maps);
  result.mapping_ms = MillisecondsSince(start);
  result.labelled_G = std::move(input.points);
  return result;
}

perception::Fog TruthFog(const Scenario& scenario, const perception::GridWindow& window,
                         const perception::FogParams& params, const Eigen::Isometry3d& X_GW) {
  std::vector<perception::OrientedBox> solids_G;
  // the floor as a thin box whose top face is z = 0
  perception::OrientedBox floor;
  floor.X_FB = X_GW * Eigen::Translation3d(scenario.floor_center.x(), scenario.floor_center.y(), -0.005);
  floor.half_size = {scenario.floor_size.x() / 2, scenario.floor_size.y() / 2, 0.005};
  solids_G.push_back(floor);
  for (const Solid& solid : WorldSolids(scenario)) {
    perception::OrientedBox box = solid.box;
    box.X_FB = X_GW * box.X_FB;
    solids_G.push_back(box);
  }
  return perception::GroundTruthFog(solids_G, window, params);
}

void WriteViewFrames(const StereoView& view, const ViewResult& result, const std::string& dir,
                     const std::string& prefix) {
  MakeOutputFolder(dir);
  WritePng(view.left, dir + "/" + prefix + "_left.png");
  if (!result.disparity.empty()) {
    WritePng(viz::DrawDisparity(result.disparity), dir + "/" + prefix + "_disparity.png");
  }
  WritePng(viz::DrawSegments(result.planes), dir + "/" + prefix + "_segments.png");
}

std::string RunPerceive(const Scenario& scenario, const std::string& out_dir, bool quiet,
                        const PerceptionParams& params) {
  MakeOutputFolder(out_dir);
  sim::World world(MakeWorldSpec(scenario));
  sim::Controller controller(world.model());
  const sim::Humanoid& humanoid = controller.humanoid();
  const mjModel* m = world.model();
  mjData* d = world.data();
  controller.Reset(scenario.start, 0.0, m, d);
  sim::Renderer renderer(m);

  perception::MapState maps;
  nlohmann::json views = nlohmann::json::array();
  std::vector<perception::SegmentationScore> scores;
  std::vector<double> stereo_ms, segmentation_ms, mapping_ms;
  std::vector<perception::StereoScore> ranges;
  const auto sweep = StartSweep();
  for (size_t i = 0; i < sweep.size(); ++i) {
    controller.MoveHead(sweep[i]);
    controller.RunUntilIdle(m, d);
    // the robot believes where odometry says; the camera and body from its joint angles
    const Pose2 robot_G = controller.believed_pose();
    StereoView view = RenderStereo(&renderer, world,
                                   sim::HeadCameraPoseInWorld(humanoid, d, sim::Eye::kLeft),
                                   scenario.sensor);
    ViewResult result = PerceiveView(params, scenario.sensor.depth, view, humanoid, robot_G, 0.0,
                                     sim::HeadCameraPose(humanoid, d, sim::Eye::kLeft),
                                     sim::RobotBodyBoxes(humanoid, m, d), &maps);
    char prefix[32];
    std::snprintf(prefix, sizeof(prefix), "view%02zu", i);
    WriteViewFrames(view, result, out_dir + "/frames", prefix);
    scores.push_back(result.segmentation);
    ranges.push_back(result.stereo);
    stereo_ms.push_back(result.stereo_ms);
    segmentation_ms.push_back(result.segmentation_ms);
    mapping_ms.push_back(result.mapping_ms);
    nlohmann::json v = {{"pan", sweep[i].pan},
                        {"tilt", sweep[i].tilt},
                        {"segmentation", ScoreJson(result.segmentation)},
                        {"range", StereoJson(result.stereo)},
                        {"timing_ms",
                         {{"stereo", result.stereo_ms},
                          {"segmentation", result.segmentation_ms},
                          {"mapping", result.mapping_ms}}}};
    views.push_back(v);
    if (!quiet) {
      std::cerr << "view " << i + 1 << "/" << sweep.size() << ": " << result.planes.planes.size()
                << " planes, accuracy " << result.segmentation.accuracy << "\n";
    }
  }

  // maps against the ground truth of the world
  const Pose2 robot_G = controller.believed_pose();
  perception::Fog fog = perception::ComputeFog(params.map, maps);
  perception::Fog truth = TruthFog(scenario, fog.window, params.map.fog);
  const perception::FogScore fog_score = perception::ScoreFog(fog, truth, params.map.fog);
  viz::WriteMapPictures(out_dir + "/maps", fog, maps, params.map, robot_G);
  WritePng(viz::DrawFog(truth, robot_G), out_dir + "/maps/fog_truth.png");
  WritePng(viz::DrawFogErrors(fog, truth, params.map.fog, robot_G), out_dir + "/maps/fog_errors.png");
  viz::WriteFogTypes(out_dir + "/maps/fog_truth_types.png", truth);
  // what the planner makes of the perceived map: the plan a mission would start with
  RunParams run_params = ResolveParams(scenario.params);
  run_params.perception = params;
  navigation::PlannerParams planner_params = run_params.planner;
  planner_params.goal_tolerance = 0.5 * scenario.goal_tolerance;
  planner_params.kneel_offset = controller.KneelOffset();
  const navigation::PlanResult plan =
      navigation::Plan(fog, robot_G, scenario.goal, planner_params);
  WritePng(viz::DrawPlanPicture(fog, robot_G, plan, scenario.goal),
           out_dir + "/maps/plan.png");
  nlohmann::json plan_moves = nlohmann::json::object();
  for (const navigation::PathSegment& run : navigation::SegmentPath(plan)) {
    plan_moves[navigation::MoveName(run.move)] =
        plan_moves.value(navigation::MoveName(run.move), 0) + 1;
  }

  perception::SegmentationScore overall = perception::CombineScores(scores);
  const perception::StereoScore range = perception::CombineStereoScores(ranges);
  nlohmann::json confusion = nlohmann::json::object();
  for (int t = 0; t < perception::kNumCellTypes; ++t) {
    nlohmann::json row = nlohmann::json::object();
    for (int e = 0; e < perception::kNumCellTypes; ++e) {
      row[perception::CellTypeName(perception::CellType(e))] = fog_score.confusion[t][e];
    }
    confusion[perception::CellTypeName(perception::CellType(t))] = row;
  }
  nlohmann::json report = {
      {"scenario", scenario.name},
      {"depth", scenario.sensor.depth == DepthMode::kStereo ? "stereo" : "ideal"},
      {"views", views},
      {"segmentation", ScoreJson(overall)},
      {"range", StereoJson(range)},
      {"fog", FogScoreJson(fog_score)},
      {"fog_accuracy", fog_score.accuracy},
      {"fog_observed_cells", fog_score.observed},
      {"fog_confusion", confusion},
      {"floor_height_error",
       {{"median", fog_score.height_error_median}, {"max", fog_score.height_error_max},
        {"cells", fog_score.height_cells}}},
      {"map_memory_bytes", maps.MemoryBytes()},
      {"plan",
       {{"status", navigation::PlanStatusName(plan.status)},
        {"reason", navigation::NoPathReasonName(plan.reason)},
        {"reaches_goal", plan.reaches_goal},
        {"length", plan.length},
        {"runs", plan_moves}}},
      {"timing_ms",
       {{"stereo", perception::Median(stereo_ms)},
        {"segmentation", perception::Median(segmentation_ms)},
        {"mapping", perception::Median(mapping_ms)}}},
      {"params", ParamsJson(run_params)}};
  std::string text = report.dump(2);
  WriteFileAtomically(out_dir + "/perception.json", text + "\n");
  viz::WritePerceivePage(out_dir);
  return text;
}

std::string RunPerceiveBoth(const Scenario& scenario, const std::string& out_dir, bool quiet,
                            const PerceptionParams& params) {
  MakeOutputFolder(out_dir);
  nlohmann::json both = {{"scenario", scenario.name}, {"depth", "both"}};
  for (const DepthMode mode : {DepthMode::kStereo, DepthMode::kIdeal}) {
    const char* name = mode == DepthMode::kStereo ? "stereo" : "ideal";
    Scenario s = scenario;
    s.sensor.depth = mode;
    both[name] = nlohmann::json::parse(RunPerceive(s, out_dir + "/" + name, quiet, params));
  }
  std::string text = both.dump(2);
  WriteFileAtomically(out_dir + "/perception.json", text + "\n");
  return text;
}

}  // namespace fognav::scenarios
