#include "driver/pair_tca.h"

#include "driver/stages.h"

#include <algorithm>
#include <cmath>

namespace gearkit
{
namespace
{
/// Classical (or fast discrete-point) TCA over the scene's positions.
TcaResult
analyse(const UnloadedTca &tca, const TcaScene &t, int z1, const std::function<void()> &step)
{
  TcaResult r;
  r.mesh_angle = 2 * pi / z1;
  const int n  = t.options.positions_per_mesh * t.options.mesh_cycles;
  for (int i = 0; i < n; ++i)
    {
      r.positions.push_back(
          tca.at(t.options.start_angle + r.mesh_angle * i / t.options.positions_per_mesh));
      step();
    }
  summarise(r);
  return r;
}

} // namespace

std::pair<MemberPointer, MemberPointer>
measured_members(const H5Group &m)
{
  return {std::make_shared<MeasuredMemberFlanks>(read_measured(m.group("pinion"), "pinion")),
          std::make_shared<MeasuredMemberFlanks>(read_measured(m.group("gear"), "gear"))};
}

TcaResult
pair_tca(const MemberPointer &pinion, const MemberPointer &gear, const Assembly &assembly,
         const TcaScene &t, bool measured, const std::function<void()> &step,
         PaperModeResult *paper)
{
  if (!(measured && t.paper_mode))
    return analyse(UnloadedTca(pinion, gear, assembly, t.options), t, pinion->teeth(), step);
  PaperModeOptions po = t.paper;
  po.on_position      = step;
  PaperModeResult r   = paper_mode_ste(*pinion, *gear, assembly, po);
  if (paper)
    *paper = r;
  return r.tca;
}

} // namespace gearkit
