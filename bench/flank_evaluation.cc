// Cost of evaluating involute flanks: the nominal helicoid, the same with every modification
// superposed (exact tangents through the normal's derivatives), and a 9 x 29 virtual-CMM grid.
#include "geometry/involute_gear.h"

#include <benchmark/benchmark.h>

using namespace gearkit;

namespace
{
std::shared_ptr<const InvoluteGear>
gear(bool modified)
{
  InvoluteGearData d;
  d.teeth         = 17;
  d.normal_module = 8e-3;
  d.helix_angle   = 15.8 * pi / 180;
  d.profile_shift = 0.145;
  d.face_width    = 0.1;
  if (modified)
    {
      ToothModifications &m = d.drive_modifications;
      m.tip_relief = 20e-6, m.tip_relief_length = 3e-3, m.lead_crowning = 8e-6;
      m.waviness_amplitude = 1e-6, m.waviness_wavelength = 1e-3, m.profile_slope = 3e-6;
    }
  return InvoluteGear::create(d);
}

void
evaluate(benchmark::State &state)
{
  const auto          g = gear(state.range(0) != 0);
  const InvoluteFlank f = g->flank(3, FlankSide::drive);
  const FlankDomain   d = f.domain();
  double              u = d.u_min, v = d.v_min, sink = 0;
  for (auto _ : state)
    {
      sink += f.evaluate(u, v).position.x();
      u = u + 1e-3 > d.u_max ? d.u_min : u + 1e-3;
      v = v + 1e-4 > d.v_max ? d.v_min : v + 1e-4;
    }
  benchmark::DoNotOptimize(sink);
}
BENCHMARK(evaluate)->Arg(0)->Arg(1)->ArgName("modified");

void
cmm_grid(benchmark::State &state)
{
  const auto g = gear(true);
  for (auto _ : state)
    benchmark::DoNotOptimize(sample_flank(g->flank(0, FlankSide::drive), 9, 29));
}
BENCHMARK(cmm_grid);

void
mass_properties(benchmark::State &state)
{
  const auto g = gear(false);
  for (auto _ : state)
    benchmark::DoNotOptimize(g->mass_properties());
}
BENCHMARK(mass_properties)->Unit(benchmark::kMillisecond);
} // namespace

BENCHMARK_MAIN();
