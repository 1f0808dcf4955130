// Stage "ste": unloaded tooth contact analysis of every pair — static transmission error e_0,
// its mesh-order harmonics, and per position and tooth pair the contact point, normals, moment
// arms and separations (the tables the FE stiffness and the dynamics read).
#include "driver/pair_tca.h"
#include "driver/stages.h"

namespace gearkit
{
void
run_ste_stage(const Scene &scene, const Upstream &upstream, const H5Group &out, std::ostream &log)
{
  std::size_t total = 0;
  for (const PairScene &pair : scene.pairs)
    {
      const TcaScene &t = scene.tca.at(pair.name);
      total += t.options.positions_per_mesh * t.options.mesh_cycles * (t.measured ? 2 : 1);
    }
  Progress   progress("ste", total);
  const auto step = [&] { progress.advance(); };

  for (const PairScene &pair : scene.pairs)
    {
      const TcaScene   &t = scene.tca.at(pair.name);
      const PairMembers members =
          theoretical_members(pair, t, upstream.at("flanks")->group(pair.name));
      const H5Group g = out.group(pair.name, "<pair>");
      g.attribute("method", "classical TCA on the theoretical flanks");
      // errors of the contact search (e.g. its bound on the work) name the pair's section
      const auto tca = [&](const MemberPointer &pinion, const MemberPointer &gear, bool measured,
                           PaperModeResult *paper) {
        try
          {
            return pair_tca(pinion, gear, members.assembly, t, measured, step, paper);
          }
        catch (const InputError &e)
          {
            throw InputError("TCA/" + pair.name + (measured ? " (measured flanks)" : "") + ": " +
                             e.what());
          }
      };
      const auto [pp, pairs] =
          write_tca_tables(tca(members.pinion, members.gear, false, nullptr), t, members, g);
      log << "  " << pair.name << ": e_0 peak-to-peak " << pp * 1e6
          << " urad, mean pairs in contact " << pairs << "\n";
      if (!t.measured)
        continue;
      // STE on the measured flanks of this pair (a measurement source is there:
      // TcaScene::complete_and_check)
      const auto [mp, mg] = measured_members(upstream.at("measured")->group(pair.name));
      const H5Group   gm  = g.group("measured");
      PaperModeResult paper;
      const TcaResult r = tca(mp, mg, true, &paper);
      if (t.paper_mode)
        {
          gm.attribute("method", "paper mode (the seed's point-cloud method) on the measured "
                                 "flanks");
          gm.write("paper_tolerance", paper.tolerance);
          gm.write("paper_points", double(paper.points));
          gm.write("seed_ste", paper.seed_ste, {paper.seed_ste.size()});
        }
      else
        gm.attribute("method", "fast discrete-point: exact contact search on the flanks "
                               "interpolated from the measured points");
      const auto [mpp, mpairs] = write_tca_tables(r, t, members, gm);
      log << "  " << pair.name << " measured (" << (t.paper_mode ? "paper mode" : "fast")
          << "): e_0 peak-to-peak " << mpp * 1e6 << " urad, mean pairs in contact " << mpairs
          << "\n";
    }
}
} // namespace gearkit
