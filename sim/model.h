// Loading MuJoCo models: owned model/data handles, the models shipped in models/, and the
// error type of the simulator.
#ifndef FOGNAV_SIM_MODEL_H_
#define FOGNAV_SIM_MODEL_H_

#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include <mujoco/mujoco.h>

namespace fognav::sim {

// The simulator could not run: MuJoCo rejected a model, an OpenGL context could not be made.
// The program maps it to exit code 3.
class SimError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
using ModelPtr = std::unique_ptr<mjModel, ModelDeleter>;
using DataPtr = std::unique_ptr<mjData, DataDeleter>;

// Text of a model file shipped in models/ (embedded at build time), e.g. "humanoid.xml".
// Throws std::out_of_range naming the file if there is no such model.
const std::string& ShippedModel(const std::string& file_name);

// Compiles MJCF text. `files` are further in-memory files the text may <include> by name;
// every shipped model is available for inclusion too. Throws SimError with MuJoCo's message.
ModelPtr LoadModelFromXml(const std::string& xml, const std::map<std::string, std::string>& files = {});

// Makes mjData for a model. Throws SimError if MuJoCo cannot allocate it.
DataPtr MakeData(const mjModel* m);

// Installs MuJoCo's user error and warning handlers: errors throw SimError instead of exiting
// the process. Called by LoadModelFromXml; idempotent.
void InstallMujocoErrorHandler();

}  // namespace fognav::sim

#endif  // FOGNAV_SIM_MODEL_H_
