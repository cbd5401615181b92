#include <spindrift/version.h>
#include <spindrift/world.h>

namespace spindrift {

const char* versionString() { return SPINDRIFT_VERSION; }

}  // namespace spindrift
