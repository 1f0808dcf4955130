// Stage "measured": measured flank point sets per pair and member.
#include "stages.h"

namespace gearkit
{
void
run_measured_stage(const Scene &, const Upstream &, const H5Group &, std::ostream &)
{
  throw InputError("the measured stage is not built yet");
}
} // namespace gearkit
