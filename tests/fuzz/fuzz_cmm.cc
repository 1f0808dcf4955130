// libFuzzer target for the measured-flank readers (docs/cmm-format.md): every input is read as a
// CMM point file and as a flank topography file (the two share the tokenizer, header, block and
// number parsing; the `format` line sends an input down one or the other). Each read must end
// normally or with gearkit::InputError. What is read must also be what the format promises
// (grid sizes, finite values, unit normals); a violation aborts, which the fuzzer reports.
#include "geometry/measured_flank.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>

namespace
{
void
check(bool ok)
{
  if (!ok)
    std::abort();
}

void
read_cmm_input(const std::string &text)
{
  std::istringstream            in(text);
  const gearkit::MeasuredMember m = gearkit::read_cmm(in, "fuzz.cmm");
  check(m.teeth >= 1 && !m.flanks.empty());
  for (const gearkit::MeasuredFlank &f : m.flanks)
    {
      check(f.tooth >= 0 && f.tooth < m.teeth && f.n_profile >= 1 && f.n_face >= 1);
      check(f.points.size() == std::size_t(f.n_profile) * std::size_t(f.n_face));
      check(f.normals.empty() || f.normals.size() == f.points.size());
      for (const gearkit::Vec3 &p : f.points)
        check(p.allFinite());
      for (const gearkit::Vec3 &n : f.normals)
        check(std::abs(n.norm() - 1) <= 1e-6);
    }
}

void
read_topography_input(const std::string &text)
{
  std::istringstream              in(text);
  const gearkit::TopographyMember t = gearkit::read_topography(in, "fuzz.topo");
  check(t.teeth >= 1 && !t.flanks.empty());
  for (const gearkit::FlankTopography &f : t.flanks)
    {
      check(f.tooth >= 0 && f.tooth < t.teeth && !f.diameters.empty() && !f.face.empty());
      check(f.deviations.size() == f.diameters.size() * f.face.size());
      for (double d : f.deviations)
        check(std::isfinite(d));
    }
}
} // namespace

extern "C" int
LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char *>(data), size);
  for (auto read : {read_cmm_input, read_topography_input})
    try
      {
        read(text);
      }
    catch (const gearkit::InputError &)
      {
        // refused with a message: the expected end for malformed input
      }
  return 0;
}
