#include "perception/mapping.h"

namespace fognav::perception {

const char* CellTypeName(CellType type) {
  switch (type) {
    case CellType::kUnknown: return "unknown";
    case CellType::kFloor: return "floor";
    case CellType::kStairs: return "stairs";
    case CellType::kBorder: return "border";
    case CellType::kTunnel: return "tunnel";
    case CellType::kObstacle: return "obstacle";
  }
  return "invalid";
}

}  // namespace fognav::perception
