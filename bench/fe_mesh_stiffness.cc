// Fast (compliance) mode over one mesh cycle of the FZG C spur pair: FE compliance of both
// members (tooth segments, Q2), then the contact at every position. Prints sizes, times, the
// loaded TE and K_m, for a mesh-density study.
// usage: bench_fe_mesh_stiffness [flank size / m_n = 0.2] [positions = 20] [torque = 200 N m]
//                                [depth in elements = 3] [cells across = 17] [cells along = 24]
//                                [pair: fzg | pe62] [segment teeth at least = 3] [cuts: held|free]
// pe62: the 62/62 spur pair of reference-data.md section 4 (m 2 mm, b 20 mm, alpha 20 deg).
#include "base/blas_kernels.h"
#include "stiffness/loaded_contact.h"
#include "stiffness/member_compliance.h"
#include "tests/fzg_c_pair.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

using namespace gearkit;

int
main(int argc, char **argv)
{
  gearkit::use_fitting_blas_kernels(argv); // before MPI: may run the program again
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const double                             size_factor = argc > 1 ? std::atof(argv[1]) : 0.2;
  const int                                positions   = argc > 2 ? std::atoi(argv[2]) : 20;
  const double                             torque      = argc > 3 ? std::atof(argv[3]) : 200;
  const double                             depth       = argc > 4 ? std::atof(argv[4]) : 3;
  const int                                across      = argc > 5 ? std::atoi(argv[5]) : 17;
  const int                                along       = argc > 6 ? std::atoi(argv[6]) : 24;
  const std::string                        pair        = argc > 7 ? argv[7] : "fzg";
  const int                                min_teeth   = argc > 8 ? std::atoi(argv[8]) : 3;
  const bool hold_cuts = argc > 9 ? std::string(argv[9]) != "free" : true;
  try
    {
      auto [pd, gd] = test_data::fzg_c_pair();
      if (pair == "pe62")
        {
          for (InvoluteGearData *d : {&pd, &gd})
            {
              d->teeth = 62, d->normal_module = 2e-3, d->face_width = 20e-3;
              d->profile_shift = 0;
            }
          gd.hand = Hand::left;
        }
      const auto        pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
      const auto        pf = std::make_shared<InvoluteMemberFlanks>(pinion);
      const auto        gf = std::make_shared<InvoluteMemberFlanks>(gear);
      const double      a  = working_centre_distance(*pinion, *gear);
      const UnloadedTca tca(pf, gf, a);
      const std::string dir = "/tmp/gearkit-bench-fe";
      std::filesystem::create_directories(dir);
      const Material           steel{206e9, 0.3};
      auto                     t0 = std::chrono::steady_clock::now();
      std::vector<TcaPosition> at;
      for (int i = 0; i < positions; ++i)
        at.push_back(tca.at(2 * pi / pd.teeth * i / positions));
      const auto segments = loaded_segments(at, pd.teeth, gd.teeth, 20e-6);
      auto member = [&](const InvoluteGear &g, const MemberFlanks &f, const SegmentChoice &s) {
        MemberComplianceOptions o;
        o.mesh.teeth         = std::max(min_teeth, s.teeth);
        o.hold_cuts          = hold_cuts;
        o.mesh.central_tooth = s.central;
        o.mesh.flank_size    = size_factor * g.data().normal_module;
        o.material           = steel;
        o.depth_elements     = depth;
        o.work_directory     = dir;
        MemberComplianceInfo info;
        FlankCompliance      c = involute_member_compliance(g, f, o, &info);
        std::printf("%s: %zu hexahedra, %zu dofs, depth %.2f mm, mesh %.1f s, setup %.1f s, "
                    "%zu loads %.1f s\n",
                    g.data().name.c_str(), info.hexahedra, info.dofs, info.depth * 1e3,
                    info.mesh_seconds, info.setup_seconds, c.points().size(), info.solve_seconds);
        return c;
      };
      const FlankCompliance cp = member(*pinion, *pf, segments.first);
      const FlankCompliance cg = member(*gear, *gf, segments.second);
      const double          t_fe =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const StructuralCompliance sp = table_compliance(cp, true), sg = table_compliance(cg, false);
      LoadedContactOptions       lo;
      lo.pinion_material = lo.gear_material = steel;
      lo.cells.cells_across = across, lo.cells.cells_along = along;
      lo.covered   = [&](int p, int g) { return cp.covers(p) && cg.covers(g); };
      t0           = std::chrono::steady_clock::now();
      double k_sum = 0, k_min = HUGE_VAL, k_max = 0, de_min = HUGE_VAL, de_max = -HUGE_VAL;
      for (int i = 0; i < positions; ++i)
        {
          const double         phi = 2 * pi / pd.teeth * i / positions;
          const LoadedPosition r   = loaded_contact(tca, at[i], torque, lo, sp, sg);
          k_sum += r.mesh_stiffness, k_min = std::min(k_min, r.mesh_stiffness);
          k_max  = std::max(k_max, r.mesh_stiffness);
          de_min = std::min(de_min, r.eL - r.e0), de_max = std::max(de_max, r.eL - r.e0);
          std::printf("  phi %.4f  e_L-e_0 %.3f urad  K_m %.4g N/m  pairs", phi,
                      (r.eL - r.e0) * 1e6, r.mesh_stiffness);
          for (double f : r.pair_force)
            if (f > 0)
              std::printf(" %.0f", f);
          std::printf(" N\n");
        }
      const double t_contact =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      dealii::Utilities::System::MemoryStats mem;
      dealii::Utilities::System::get_memory_stats(mem);
      std::printf(
          "flank size %.3f m_n: K_m mean %.4g min %.4g max %.4g N/m; e_L - e_0 %.3f..%.3f urad; "
          "FE %.1f s, contact %.1f s (%d positions), peak RSS %.0f MB\n",
          size_factor, k_sum / positions, k_min, k_max, de_min * 1e6, de_max * 1e6, t_fe, t_contact,
          positions, mem.VmHWM / 1024.0);
    }
  catch (const InputError &e)
    {
      std::fprintf(stderr, "%s\n", e.what());
      return 1;
    }
}
