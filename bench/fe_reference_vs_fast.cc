// Reference mode (finite elements alone, meshes graded to each position's contact lines)
// against the fast mode (FE compliance tables + half-space contact) over one mesh cycle of the
// FZG C spur pair, on the same tooth segments and contact cells: e_L and K_m per position,
// their differences (worst position), sizes, times and the memory peak.
// usage: bench_fe_reference_vs_fast [positions = 20] [torque = 200 N m]
//          [reference elements per cell = 1] [reference layers per cell = 1]
//          [cells across = 17] [cells along = 14] [fast flank size / m_n = 0.2]
//          [segment teeth = 3] [first position = 0] [last position = positions - 1]
//          [fast grid n_u = 9] [n_v = 7] [reference flank size / m_n = 0.2] [reference: 1|0]
//          [fast response depth in elements = 3] [fast other flanks and fillets size / m_n = same]
//          [fast near field: 0 response depth, 1 analytic = 0] [near-field radius / m_n = 2]
//          [fast load grid: 0 uniform, 1 graded towards the flank's edges = 1]
#include "base/blas_kernels.h"
#include "stiffness/loaded_contact.h"
#include "stiffness/member_compliance.h"
#include "stiffness/reference_contact.h"
#include "tests/fzg_c_pair.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

using namespace gearkit;

namespace
{
double
seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

int
main(int argc, char **argv)
{
  gearkit::use_fitting_blas_kernels(argv); // before MPI: may run the program again
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);

  const int    positions = argc > 1 ? std::atoi(argv[1]) : 20;
  const double torque    = argc > 2 ? std::atof(argv[2]) : 200;
  const double per_cell  = argc > 3 ? std::atof(argv[3]) : 1;
  const int    layers    = argc > 4 ? std::atoi(argv[4]) : 1;
  const int    across    = argc > 5 ? std::atoi(argv[5]) : 17;
  const int    along     = argc > 6 ? std::atoi(argv[6]) : 14;
  const double fast_size = argc > 7 ? std::atof(argv[7]) : 0.2;
  const int    teeth     = argc > 8 ? std::atoi(argv[8]) : 3;
  const int    first     = argc > 9 ? std::atoi(argv[9]) : 0;
  const int    last      = argc > 10 ? std::atoi(argv[10]) : positions - 1;
  const int    n_u       = argc > 11 ? std::atoi(argv[11]) : 9;
  const int    n_v       = argc > 12 ? std::atoi(argv[12]) : 7;
  const double ref_size  = argc > 13 ? std::atof(argv[13]) : 0.2;
  const bool   reference = argc > 14 ? std::atoi(argv[14]) != 0 : true;
  const double depth     = argc > 15 ? std::atof(argv[15]) : 3;
  const double other     = argc > 16 ? std::atof(argv[16]) : 0;
  const bool   analytic  = argc > 17 ? std::atoi(argv[17]) != 0 : false;
  const double radius    = argc > 18 ? std::atof(argv[18]) : 2;
  const bool   graded    = argc > 19 ? std::atoi(argv[19]) != 0 : true;
  try
    {
      const auto [pd, gd]      = test_data::fzg_c_pair();
      const auto        pinion = InvoluteGear::create(pd), gear = InvoluteGear::create(gd);
      const auto        pf = std::make_shared<InvoluteMemberFlanks>(pinion);
      const auto        gf = std::make_shared<InvoluteMemberFlanks>(gear);
      const UnloadedTca tca(pf, gf, working_centre_distance(*pinion, *gear));
      const std::string dir = "/tmp/gearkit-bench-reference";
      std::filesystem::create_directories(dir);
      const Material           steel{206e9, 0.3};
      std::vector<TcaPosition> at;
      for (int i = 0; i < positions; ++i)
        at.push_back(tca.at(2 * pi / pd.teeth * i / positions));
      auto segments         = loaded_segments(at, pd.teeth, gd.teeth, 20e-6);
      segments.first.teeth  = std::max(segments.first.teeth, teeth);
      segments.second.teeth = std::max(segments.second.teeth, teeth);

      // Fast mode on these segments.
      auto t0     = std::chrono::steady_clock::now();
      auto member = [&](const InvoluteGear &g, const MemberFlanks &f, const SegmentChoice &s) {
        MemberComplianceOptions o;
        o.mesh.teeth = s.teeth, o.mesh.central_tooth = s.central;
        o.mesh.flank_size = fast_size * g.data().normal_module;
        o.material = steel, o.work_directory = dir;
        o.n_u = n_u, o.n_v = n_v;
        o.graded_grid         = graded;
        o.depth_elements      = depth;
        o.mesh.other_size     = other * g.data().normal_module;
        o.analytic_near_field = analytic;
        o.near_field_radius   = radius * g.data().normal_module;
        return involute_member_compliance(g, f, o);
      };
      const FlankCompliance cp        = member(*pinion, *pf, segments.first);
      const FlankCompliance cg        = member(*gear, *gf, segments.second);
      const double          t_fast_fe = seconds_since(t0);
      LoadedContactOptions  lo;
      lo.pinion_material = lo.gear_material = steel;
      lo.cells.cells_across = across, lo.cells.cells_along = along;
      lo.covered                    = [&](int p, int g) { return cp.covers(p) && cg.covers(g); };
      const StructuralCompliance sp = table_compliance(cp, true), sg = table_compliance(cg, false);

      ReferenceContactOptions ro;
      ro.cells          = lo;
      ro.pinion_segment = segments.first, ro.gear_segment = segments.second;
      ro.elements_per_cell = per_cell, ro.layers_per_cell = layers;
      ro.work_directory = dir;
      ro.flank_size     = ref_size * pd.normal_module;

      double      t_fast_contact = 0, t_reference = 0, worst_e = 0, worst_k = 0;
      double      k_fast = 0, k_ref = 0;
      int         worst_e_at = -1, worst_k_at = -1;
      std::size_t dofs_max = 0;
      std::printf("position  phi[rad]  eL-e0 fast/ref [urad]  K_m fast/ref [N/um]  diff e, K [%%]  "
                  "pairs ref [N]  dofs  time ref [s]\n");
      for (int i = first; i <= last; ++i)
        {
          t0                     = std::chrono::steady_clock::now();
          const LoadedPosition f = loaded_contact(tca, at[i], torque, lo, sp, sg);
          t_fast_contact += seconds_since(t0);
          if (!reference)
            {
              std::printf("%3d  %.5f  %8.3f  %7.2f\n", i, at[i].pinion_angle, (f.eL - f.e0) * 1e6,
                          f.mesh_stiffness * 1e-6);
              k_fast += f.mesh_stiffness;
              continue;
            }
          t0 = std::chrono::steady_clock::now();
          ReferenceContactInfo info;
          const LoadedPosition r =
              reference_contact(*pinion, *gear, tca, at[i], {torque}, ro, &info).front();
          const double t = seconds_since(t0);
          t_reference += t;
          dofs_max        = std::max(dofs_max, info.dofs);
          const double de = (f.eL - f.e0) / (r.eL - r.e0) - 1;
          const double dk = f.mesh_stiffness / r.mesh_stiffness - 1;
          if (std::abs(de) > std::abs(worst_e))
            worst_e = de, worst_e_at = i;
          if (std::abs(dk) > std::abs(worst_k))
            worst_k = dk, worst_k_at = i;
          k_fast += f.mesh_stiffness, k_ref += r.mesh_stiffness;
          std::printf("%3d  %.5f  %8.3f %8.3f  %7.2f %7.2f  %+6.2f %+6.2f  ", i, at[i].pinion_angle,
                      (f.eL - f.e0) * 1e6, (r.eL - r.e0) * 1e6, f.mesh_stiffness * 1e-6,
                      r.mesh_stiffness * 1e-6, 100 * de, 100 * dk);
          for (double p : r.pair_force)
            if (p > 0)
              std::printf("%.0f ", p);
          std::printf(" %zu  %.1f (mesh %.1f, FE %.1f)\n", info.dofs, t, info.mesh_seconds,
                      info.solve_seconds);
          std::fflush(stdout);
        }
      const int                              n = last - first + 1;
      dealii::Utilities::System::MemoryStats mem;
      dealii::Utilities::System::get_memory_stats(mem);
      std::printf("K_m mean fast %.2f ref %.2f N/um; worst e_L-e_0 difference %+.2f %% at %d, "
                  "worst K_m %+.2f %% at %d\nfast: FE %.1f s + contact %.2f s; reference %.1f s "
                  "(%.1f s per position, up to %zu dofs); peak RSS %.0f MB\n",
                  k_fast / n * 1e-6, k_ref / n * 1e-6, 100 * worst_e, worst_e_at, 100 * worst_k,
                  worst_k_at, t_fast_fe, t_fast_contact, t_reference, t_reference / n, dofs_max,
                  mem.VmHWM / 1024.0);
    }
  catch (const InputError &e)
    {
      std::fprintf(stderr, "%s\n", e.what());
      return 1;
    }
}
