// libFuzzer target: the scenario loader with its validation. Any text either loads or is
// refused with an InputError; any other exception, a crash or undefined behaviour is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scenarios/params.h"
#include "scenarios/scenario.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const fognav::scenarios::Scenario scenario =
        fognav::scenarios::ParseScenario(text, "fuzz.yaml");
    // what the program does next with a loaded scenario, short of the simulator
    fognav::scenarios::WorldSolids(scenario);
    fognav::scenarios::Summary(scenario);
    fognav::scenarios::ParamsJson(fognav::scenarios::ResolveParams(scenario.params));
  } catch (const fognav::scenarios::InputError&) {
  }
  return 0;
}
