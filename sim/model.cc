#include "sim/model.h"

#include <cstring>

namespace fognav::sim {
namespace internal {
const std::map<std::string, std::string>& EmbeddedModels();
}  // namespace internal

namespace {

void ThrowMujocoError(const char* message) {
  throw SimError(std::string("MuJoCo error: ") + message);
}

void IgnoreMujocoWarning(const char*) {}

// adds one in-memory file to a VFS; false if the VFS is full or the name repeats
bool AddBuffer(mjVFS* vfs, const std::string& name, const std::string& text) {
  if (mj_makeEmptyFileVFS(vfs, name.c_str(), int(text.size())) != 0) return false;
  int index = mj_findFileVFS(vfs, name.c_str());
  std::memcpy(vfs->filedata[index], text.data(), text.size());
  return true;
}

}  // namespace

void InstallMujocoErrorHandler() {
  mju_user_error = ThrowMujocoError;
  mju_user_warning = IgnoreMujocoWarning;
}

const std::string& ShippedModel(const std::string& file_name) {
  const auto& models = internal::EmbeddedModels();
  auto it = models.find(file_name);
  if (it == models.end()) throw std::out_of_range("no shipped model named '" + file_name + "'");
  return it->second;
}

ModelPtr LoadModelFromXml(const std::string& xml, const std::map<std::string, std::string>& files) {
  InstallMujocoErrorHandler();
  // mjVFS is large (it holds the name table); keep it off the stack
  auto vfs = std::make_unique<mjVFS>();
  mj_defaultVFS(vfs.get());
  const std::string main_name = "fognav_main_model.xml";
  bool ok = AddBuffer(vfs.get(), main_name, xml);
  for (const auto& [name, text] : files) ok = ok && AddBuffer(vfs.get(), name, text);
  for (const auto& [name, text] : internal::EmbeddedModels()) {
    if (!files.count(name)) ok = ok && AddBuffer(vfs.get(), name, text);
  }
  if (!ok) {
    mj_deleteVFS(vfs.get());
    throw SimError("could not place model files in MuJoCo's virtual file system");
  }
  char error[1024] = "";
  mjModel* m = mj_loadXML(main_name.c_str(), vfs.get(), error, sizeof(error));
  mj_deleteVFS(vfs.get());
  if (!m) throw SimError(std::string("MuJoCo could not compile the model: ") + error);
  return ModelPtr(m);
}

DataPtr MakeData(const mjModel* m) {
  mjData* d = mj_makeData(m);
  if (!d) throw SimError("MuJoCo could not allocate data for the model");
  return DataPtr(d);
}

}  // namespace fognav::sim
