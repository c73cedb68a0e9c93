// Short clips of each motion of the stepping controller (walk, side-step, turn, stairs, crawl),
// seen from an external camera, so a reviewer can watch a motion without running a mission.
#ifndef FOGNAV_SCENARIOS_CLIPS_H_
#define FOGNAV_SCENARIOS_CLIPS_H_

#include <string>
#include <vector>

namespace fognav::scenarios {

// The motions RecordClip knows: "walk" (1 m ahead), "sidestep" (through a 0.22 m gap), "turn"
// (90 degrees in place), "stairs" (up and down treads of 3 and 6 cm), "crawl" (under a table
// whose underside is at 0.35 m, then up again).
const std::vector<std::string>& ClipMotions();

// What a clip gave: frames written, and the collisions the controller counted (none expected).
struct ClipResult {
  int frames = 0;
  int collisions = 0;
};

// Runs `motion` in a small world of its own and writes DIR/frame_00000.png, ... (one frame
// every `every` control ticks, 320x240, from a camera beside the course) and DIR/strip.png (six
// frames across the motion side by side). Throws InputError for an unknown motion or a
// non-positive `every`, OutputError for an unwritable DIR, sim::SimError if the simulator cannot
// run.
ClipResult RecordClip(const std::string& motion, const std::string& dir, int every = 5);

}  // namespace fognav::scenarios

#endif  // FOGNAV_SCENARIOS_CLIPS_H_
