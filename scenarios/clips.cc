#include "scenarios/clips.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "scenarios/scenario.h"
#include "scenarios/views.h"
#include "sim/controller.h"

namespace fognav::scenarios {
namespace {

struct ClipSpec {
  const char* motion;
  const char* objects;  // the scenario's world.objects, YAML flow sequence
  std::function<void(sim::Controller*)> commands;
  Eigen::Vector3d eye_R;  // clip camera in the robot frame at the start
};

// the course's treads, the controller test's table and gap
const char* kStairs =
    "[{stairs: {name: steps, start: [0.3, 0.0], width: 0.8, "
    "steps: [[0.25, 0.03], [0.35, 0.06], [0.25, 0.03]]}}]";
const char* kTable =
    "[{table: {name: desk, center: [0.85, 0.0], size: [0.6, 1.0], height: 0.38, top: 0.03, "
    "leg: 0.04}}]";
const char* kGap =
    "[{box: {name: block_left, center: [0.6, 0.31], size: [0.2, 0.4, 0.5]}}, "
    "{box: {name: block_right, center: [0.6, -0.31], size: [0.2, 0.4, 0.5]}}]";

const std::vector<ClipSpec>& Specs() {
  static const std::vector<ClipSpec> specs = {
      {"walk", "[]", [](sim::Controller* c) { c->Walk(1.0, 0, 0); }, {0.5, -1.2, 0.6}},
      {"sidestep",
       kGap,
       [](sim::Controller* c) {
         c->Walk(0, 0, M_PI / 2);
         c->Walk(0, -1.2, 0);  // facing +y, the robot's right is +x
         c->Walk(0, 0, -M_PI / 2);
       },
       {0.6, -1.0, 1.0}},
      {"turn", "[]", [](sim::Controller* c) { c->Walk(0, 0, M_PI / 2); }, {0.9, -0.9, 0.7}},
      // toes 2 cm before each riser, then one stride onto the tread
      {"stairs",
       kStairs,
       [](sim::Controller* c) {
         c->Walk(0.225, 0, 0);
         c->StepOnto(0.155, 0.03);
         c->Walk(0.095, 0, 0);
         c->StepOnto(0.16, 0.03);
         c->Walk(0.19, 0, 0);
         c->StepOnto(0.155, -0.03);
         c->Walk(0.095, 0, 0);
         c->StepOnto(0.155, -0.03);
       },
       {0.6, -1.2, 0.5}},
      {"crawl",
       kTable,
       [](sim::Controller* c) {
         c->GetDown();
         c->Crawl(1.26, 0);
         c->GetUp();
       },
       {0.7, -1.3, 0.3}},
  };
  return specs;
}

// a row of six frames spread over the clip, 2 px apart
void WriteStrip(const std::string& dir, int frames) {
  std::vector<cv::Mat> row;
  const int n = std::min(frames, 6);
  for (int k = 0; k < n; ++k) {
    const int frame = n > 1 ? int(std::lround(double(k) * (frames - 1) / (n - 1))) : 0;
    char name[32];
    std::snprintf(name, sizeof(name), "/frame_%05d.png", frame);
    cv::Mat image = cv::imread(dir + name);
    if (image.empty()) throw OutputError(dir + name + ": cannot read back the clip frame");
    if (!row.empty())
      row.push_back(cv::Mat(image.rows, 2, image.type(), cv::Scalar(255, 255, 255)));
    row.push_back(image);
  }
  cv::Mat strip;
  cv::hconcat(row, strip);
  if (!cv::imwrite(dir + "/strip.png", strip)) throw OutputError(dir + "/strip.png: cannot write");
}

}  // namespace

const std::vector<std::string>& ClipMotions() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for (const ClipSpec& s : Specs()) v.push_back(s.motion);
    return v;
  }();
  return names;
}

ClipResult RecordClip(const std::string& motion, const std::string& dir, int every) {
  auto spec = std::find_if(Specs().begin(), Specs().end(),
                           [&](const ClipSpec& s) { return motion == s.motion; });
  if (spec == Specs().end()) {
    std::string known;
    for (const std::string& m : ClipMotions()) known += (known.empty() ? "" : ", ") + m;
    throw InputError("clip motion '" + motion + "': unknown, expected one of " + known);
  }
  if (every <= 0) throw InputError("clip --every " + std::to_string(every) + ": must be positive");
  MakeOutputFolder(dir);

  const std::string yaml = std::string("name: clip_") + spec->motion +
                           "\nrobot: {start: [0, 0, 0]}\ngoal: {position: [1.5, 0]}\n"
                           "world: {floor: [4, 3], floor_center: [0.8, 0], objects: " +
                           spec->objects + "}\n";
  const Scenario scenario = ParseScenario(yaml, std::string("clip ") + spec->motion);
  sim::World world(MakeWorldSpec(scenario));
  const mjModel* m = world.model();
  mjData* d = world.data();
  sim::Controller controller(m, sim::ControllerParams{});
  controller.Reset({0, 0, 0}, 0.0, m, d);
  sim::ClipParams params;
  params.dir = dir;
  params.every = every;
  params.eye_R = spec->eye_R;
  sim::ClipRecorder clip(m, controller.humanoid(), params);
  spec->commands(&controller);
  controller.RunUntilIdle(m, d, [&](int tick) { clip(m, d, tick); });
  if (clip.frames() > 0) WriteStrip(dir, clip.frames());
  return {clip.frames(), int(controller.collisions().size())};
}

}  // namespace fognav::scenarios
