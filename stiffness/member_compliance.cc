#include "stiffness/member_compliance.h"

#include "stiffness/elastic_segment.h"

#include <deal.II/base/mpi.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <type_traits>

namespace gearkit
{
namespace
{
double
seconds_since(std::chrono::steady_clock::time_point t0)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

std::pair<SegmentChoice, SegmentChoice>
loaded_segments(const std::vector<TcaPosition> &positions, int z1, int z2, double gap_band)
{
  auto choose = [&](bool pinion, int z) {
    int first = -1, lo = 0, hi = 0, span = 0;
    for (const TcaPosition &p : positions)
      {
        int here_lo = z, here_hi = -z;
        for (const PairContact &c : p.pairs)
          if (c.found && c.separation <= gap_band)
            {
              const int t = pinion ? c.pinion_tooth : c.gear_tooth;
              if (first < 0)
                first = t;
              const int d = ((t - first) % z + z + z / 2) % z - z / 2; // signed offset
              lo = std::min(lo, d), hi = std::max(hi, d);
              here_lo = std::min(here_lo, d), here_hi = std::max(here_hi, d);
            }
        span = std::max(span, here_hi - here_lo);
      }
    if (first < 0)
      throw InputError("member compliance: no tooth pair comes within the gap band at the "
                       "positions analysed");
    SegmentChoice s;
    s.central = mod(first + (lo + hi) / 2, z);
    s.teeth   = hi - lo + 1;
    s.span    = span;
    if (s.teeth % 2 == 0)
      ++s.teeth; // segments are odd: one tooth more on one side
    return s;
  };
  return {choose(true, z1), choose(false, z2)};
}

namespace
{
MemberComplianceOptions
with_radius(MemberComplianceOptions o, double module)
{
  if (!(o.near_field_radius > 0))
    o.near_field_radius = 2 * module;
  return o;
}

/// Tells the caller what comes next, if it listens.
void
phase(const MemberComplianceOptions &o, const std::string &what)
{
  if (o.on_phase)
    o.on_phase(what);
}

/// The segment mesh's options: the loaded flanks get the flank element size; with local
/// refinements k, every size 2^k times larger (deal.II refines at the loaded flanks).
SegmentMeshOptions
base_mesh(const MemberComplianceOptions &o, double module)
{
  SegmentMeshOptions mesh = o.mesh;
  mesh.fine_side          = o.side;
  if (o.local_refinements == 0)
    return mesh;
  const double scale = std::ldexp(1.0, int(o.local_refinements));
  mesh.flank_size    = (o.mesh.flank_size > 0 ? o.mesh.flank_size : module / 5) * scale;
  mesh.other_size *= scale;
  mesh.fillet_size *= scale;
  mesh.far_size = std::max(o.mesh.far_size > 0 ? o.mesh.far_size : module, mesh.flank_size);
  return mesh;
}

/// Where the body is crossed along rays x + s direction: the samples at steps of `step` in
/// (from, to] bracket the first s whose point is inside (`want_inside`) or outside, and
/// bisection narrows the bracket to `tolerance`. Per ray (lo, hi): hi the first s found on the
/// wanted side (or `to` when no sample is), lo the last s before it.
std::vector<std::pair<double, double>>
first_crossing(const ElasticSegment &body, const std::vector<Vec3> &x,
               const std::vector<Vec3> &direction, double from, double to, double step,
               double tolerance, bool want_inside)
{
  const std::size_t   n = x.size();
  std::vector<double> lo(n, from), hi(n, -1);
  const int           steps = int(std::ceil((to - from) / step));
  std::vector<Vec3>   samples;
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 1; k <= steps; ++k)
      samples.push_back(x[i] + std::min(to, from + k * step) * direction[i]);
  const std::vector<bool> inside = body.contains(samples);
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 1; k <= steps && hi[i] < 0; ++k)
      (inside[i * steps + k - 1] == want_inside ? hi[i] : lo[i]) = std::min(to, from + k * step);
  while (true)
    {
      bool              done = true;
      std::vector<Vec3> mid;
      for (std::size_t i = 0; i < n; ++i)
        {
          done = done && (hi[i] < 0 || hi[i] - lo[i] <= tolerance);
          mid.push_back(x[i] + (hi[i] < 0 ? lo[i] : (lo[i] + hi[i]) / 2) * direction[i]);
        }
      if (done)
        break;
      const std::vector<bool> in = body.contains(mid);
      for (std::size_t i = 0; i < n; ++i)
        if (hi[i] >= 0 && hi[i] - lo[i] > tolerance)
          (in[i] == want_inside ? hi[i] : lo[i]) = (lo[i] + hi[i]) / 2;
    }
  std::vector<std::pair<double, double>> out(n);
  for (std::size_t i = 0; i < n; ++i)
    out[i] = {lo[i], hi[i] < 0 ? to : hi[i]};
  return out;
}

/// The depth at which each grid point's response is read: the nominal depth, or half the chord
/// through the tooth along the point's response direction where the tooth is thinner (near the
/// tip). The chord is bracketed on steps of a quarter of the depth up to twice the depth and
/// then bisected eight times, so that neighbouring points get smoothly varying depths (a jump
/// would show in the table).
std::vector<double>
response_depths(const FlankCompliance &table, const ElasticSegment &body, double depth)
{
  const auto       &points = table.points();
  std::vector<Vec3> x, offset;
  for (const auto &p : points)
    x.push_back(p.position), offset.push_back(response_offset(p));
  // the bracket of a quarter depth is halved while wider than depth / 1000: eight times
  const auto chord = first_crossing(body, x, offset, 0, 2 * depth, depth / 4, depth / 1000, false);
  std::vector<double> depths(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    {
      const auto [in, out] = chord[i];
      if (out <= depth / 4) // the first sample was outside
        {
          std::ostringstream msg;
          msg << "member compliance: the tooth at the flank point ("
              << points[i].position.transpose() * 1e3 << ") mm is thinner than " << depth / 4 * 1e3
              << " mm along its normal; use smaller flank elements";
          throw InputError(msg.str());
        }
      depths[i] = std::min(depth, (in + out) / 4); // half the chord (no crossing: the depth)
    }
  return depths;
}

/// The table with the near field carried analytically: a unit force at each grid point of the
/// exact flank with Boussinesq's field cut off between half and the whole of its radius (and
/// away from the body across its normal: near_field_cutoff), the finite elements' remainder
/// read at every grid point moved along its inward normal onto the finite-element surface (the
/// facets lie inside the curved flank by their sagitta), the analytic part added at the exact
/// points and the point-force half-space displacement of the same tooth taken out (the contact
/// solver adds the exact half-space between cells).
void
fill_with_analytic_near_field(FlankCompliance &table, const ElasticSegment &body, double h,
                              const MemberComplianceOptions &o, MemberComplianceInfo &out)
{
  const auto       &points = table.points();
  const std::size_t n      = points.size();
  std::vector<Vec3> x, in, outward;
  for (const auto &p : points)
    x.push_back(p.position - 0.5 * h * p.normal), in.push_back(-p.normal),
        outward.push_back(p.normal);
  // the surface: the first point outside going out from half an element inside
  const auto        surface = first_crossing(body, x, outward, 0, h, h / 4, 1e-6 * h, false);
  std::vector<Vec3> on(n);
  for (std::size_t i = 0; i < n; ++i)
    on[i] = x[i] + (surface[i].second - 2e-6 * h) * outward[i]; // just inside
  // where the body comes back across a load's outward normal: the sphere stays short of it
  // (near_field_cutoff keeps the field off the body about the ray wherever the sphere reaches;
  // this keeps the remainder's traction off the next tooth)
  const auto       &loaded = table.load_points();
  std::vector<Vec3> load_on, load_out;
  for (std::size_t i : loaded)
    load_on.push_back(on[i]), load_out.push_back(outward[i]);
  const auto back = first_crossing(body, load_on, load_out, 4e-6 * h, 1.25 * o.near_field_radius,
                                   h / 4, 1e-3 * h, true);
  const std::vector<double>  held = body.distance_to_held(load_on);
  std::vector<NearFieldLoad> loads;
  std::vector<Probe>         probes;
  double                     smallest = HUGE_VAL;
  for (std::size_t k = 0; k < loaded.size(); ++k)
    {
      const std::size_t i = loaded[k];
      const double outer  = std::min({o.near_field_radius, 0.8 * back[k].second, 0.9 * held[k]});
      if (!(outer > 0))
        {
          std::ostringstream msg;
          msg << "member compliance: no room for the analytic near field of the unit load at "
              << "tooth " << points[i].tooth << " (u, v) = (" << points[i].u << ", " << points[i].v
              << "), " << on[i].transpose() * 1e3 << " mm: the body comes back "
              << "across its normal after " << back[k].second * 1e3 << " mm, a held face is "
              << held[k] * 1e3 << " mm away (elements of " << h * 1e3 << " mm)";
          throw InputError(msg.str());
        }
      smallest = std::min(smallest, outer);
      loads.push_back({points[i].position, in[i], outer / 2, outer});
    }
  for (std::size_t j = 0; j < n; ++j)
    probes.push_back({on[j], in[j]});
  out.min_near_field_radius = smallest;
  const Eigen::MatrixXd W   = body.remainder_response(loads, probes);
  Eigen::MatrixXd       S   = W;
  for (std::size_t k = 0; k < loaded.size(); ++k)
    for (std::size_t j = 0; j < n; ++j)
      if (j != loaded[k])
        {
          // the analytic part along the load's own direction: along the other point's normal
          // it would add the tilt of the normals, u_r theta -> (1 - 2 nu) / (4 pi G rho) cos^2,
          // a term whose limit at the load depends on the direction; bilinear interpolation of
          // the table would turn it into a ripple of the grid spacing (up to 0.5 % of K_m),
          // while along a contact line (a straight generator of the flank, or nearly) it is nil
          const std::size_t    i  = loaded[k];
          const NearFieldLoad &l  = loads[k];
          const Vec3          &at = points[j].position;
          const double chi = near_field_cutoff(at, l.point, l.direction, l.inner, l.outer).value;
          const Eigen::Index r = Eigen::Index(j), c = Eigen::Index(k);
          if (chi > 0)
            S(r, c) +=
                chi *
                point_force_field(at, l.point, l.direction, 1.0, o.material).u.dot(l.direction);
          if (points[i].tooth == points[j].tooth)
            S(r, c) -= point_load_displacement((at - l.point).norm(), 0, 1.0, o.material);
        }
  table.set(S);
}
} // namespace

SegmentMeshInfo
segment_mesh_on_first_process(const SegmentMesher &mesher, const std::string &path, MPI_Comm comm)
{
  SegmentMeshInfo info;
  std::string     error;
  const bool      first = dealii::Utilities::MPI::this_mpi_process(comm) == 0;
  if (first)
    try
      {
        info = mesher(path);
      }
    catch (const InputError &e)
      {
        error = e.what();
      }
  error = dealii::Utilities::MPI::broadcast(comm, error, 0);
  if (!error.empty())
    throw InputError(error);
  std::vector<double> numbers{double(info.hexahedra), double(info.nodes), info.analytic_volume,
                              info.rim_inner_radius, double(info.whole)};
  numbers           = dealii::Utilities::MPI::broadcast(comm, numbers, 0);
  info.member_teeth = dealii::Utilities::MPI::broadcast(comm, info.member_teeth, 0);
  info.hexahedra = std::size_t(numbers[0]), info.nodes = std::size_t(numbers[1]);
  info.analytic_volume = numbers[2], info.rim_inner_radius = numbers[3];
  info.whole = numbers[4] != 0;
  return info;
}

std::function<SurfacePoint(int, const Vec3 &)>
flank_surface(const MemberFlanks &flanks, const std::vector<int> &member_teeth, FlankSide side)
{
  return [&flanks, member_teeth, side](int id, const Vec3 &x) {
    const int tooth    = member_teeth.at(std::size_t((id - boundary::flank(0, side)) / 2));
    const auto [u, v]  = flanks.rotational_parameters(x);
    const FlankPoint p = flanks.flank(tooth, side).evaluate(u, v);
    return SurfacePoint{p.position, p.normal};
  };
}

FlankCompliance
involute_member_compliance(const InvoluteGear &gear, const MemberFlanks &flanks,
                           const MemberComplianceOptions &o, MemberComplianceInfo *info)
{
  const SegmentMeshOptions mesh = base_mesh(o, gear.data().normal_module);
  return member_compliance(
      flanks, gear.data().name,
      [&](const std::string &path) { return write_tooth_segment_mesh(gear, mesh, path); },
      o.mesh.flank_size > 0 ? o.mesh.flank_size : gear.data().normal_module / 5,
      with_radius(o, gear.data().normal_module), info);
}

FlankCompliance
bevel_member_compliance(const BevelMemberFlanks &flanks, const std::string &name, double module,
                        const MemberComplianceOptions &o, MemberComplianceInfo *info)
{
  const SegmentMeshOptions mesh = base_mesh(o, module);
  return member_compliance(
      flanks, name,
      [&](const std::string &path) { return write_bevel_segment_mesh(flanks, module, mesh, path); },
      o.mesh.flank_size > 0 ? o.mesh.flank_size : module / 5, with_radius(o, module), info);
}

FlankCompliance
member_compliance(const MemberFlanks &flanks, const std::string &member_name,
                  const SegmentMesher &mesher, double h, const MemberComplianceOptions &o,
                  MemberComplianceInfo *info)
{
  MemberComplianceInfo  local;
  MemberComplianceInfo &out = info ? *info : local;
  if (o.work_directory.empty() || !std::filesystem::is_directory(o.work_directory))
    throw InputError("member compliance: the work directory '" + o.work_directory +
                     "' does not exist");
  if (!(o.depth_elements > 0 && o.patch_elements > 0))
    throw InputError("member compliance: depth and patch radius (in element sizes) must be > 0");
  auto t0 = std::chrono::steady_clock::now();
  phase(o, "meshing");
  std::string name = member_name + "_segment";
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
  const std::string mesh_file =
      (std::filesystem::path(o.work_directory) / (name + ".msh")).string();
  const SegmentMeshInfo segment = segment_mesh_on_first_process(mesher, mesh_file, o.communicator);
  out.hexahedra                 = segment.hexahedra;
  out.mesh_seconds              = seconds_since(t0);

  out.depth        = o.depth_elements * h;
  out.patch_radius = o.patch_elements * h;
  FlankGridSpec spec;
  spec.teeth = o.loaded_teeth.empty() ? segment.member_teeth : o.loaded_teeth;
  spec.side  = o.side;
  spec.n_u = o.n_u, spec.n_v = o.n_v;
  spec.graded       = o.graded_grid;
  spec.cyclic_tooth = o.cyclic_tooth;
  spec.cyclic_reach = o.cyclic_reach;
  // the loaded flank of a member tooth: its boundary id in the segment mesh
  const auto loaded_flank = [&](int tooth) {
    const auto at = std::find(segment.member_teeth.begin(), segment.member_teeth.end(), tooth);
    if (at == segment.member_teeth.end())
      throw InputError("member compliance: loaded tooth " + std::to_string(tooth) +
                       " is not in the finite-element segment of " + member_name);
    return boundary::flank(int(at - segment.member_teeth.begin()), o.side);
  };
  FlankCompliance table(flanks, spec);
  for (int t : table.grid_teeth())
    loaded_flank(t);

  t0 = std::chrono::steady_clock::now();
  ElasticSegmentOptions eo;
  eo.degree           = o.degree;
  eo.material         = o.material;
  eo.communicator     = o.communicator;
  eo.memory_available = o.memory_available;
  eo.threads          = o.threads;
  eo.clamped          = {boundary::bore};
  if (o.hold_cuts && !segment.whole)
    eo.clamped.insert({boundary::cut_start, boundary::cut_end});
  // the loaded flanks on their exact surfaces (refined vertices, the near field's traction)
  for (int t : table.grid_teeth())
    eo.surface_boundaries.insert(loaded_flank(t));
  eo.boundary_surface = flank_surface(flanks, segment.member_teeth, o.side);
  if (o.local_refinements > 0)
    {
      // with a cyclic tooth only its flank carries loads: the others' responses are smooth
      eo.refine_boundaries =
          o.cyclic_tooth < 0 ? eo.surface_boundaries : std::set<int>{loaded_flank(o.cyclic_tooth)};
      eo.local_refinements = o.local_refinements;
      eo.refine_distance   = o.refine_depth * std::ldexp(h, int(o.local_refinements));
    }
  phase(o, "set-up");
  const ElasticSegment body(mesh_file, eo);
  out.hexahedra     = body.cells(); // after the local refinement
  out.dofs          = body.dofs();
  out.setup_seconds = seconds_since(t0);
  phase(o, std::to_string(table.load_points().size()) + " unit loads on " +
               std::to_string(out.dofs) + " dofs");
  // the solver's figures once the unit loads have set it up
  const auto solver_figures = [&] {
    out.out_of_core    = body.factors_out_of_core();
    out.solver_seconds = body.solver_seconds();
    out.factor_seconds = body.factorisation_seconds();
  };

  t0                          = std::chrono::steady_clock::now();
  const ElasticResponse solve = [&](const std::vector<FlankLoad>             &loads,
                                    const std::vector<std::pair<Vec3, Vec3>> &responses) {
    std::vector<PatchLoad> patches;
    for (const FlankLoad &l : loads)
      patches.push_back({l.point, l.direction, out.patch_radius, {loaded_flank(l.tooth)}});
    std::vector<Probe> probes;
    for (const auto &[x, d] : responses)
      probes.push_back({x, d});
    return body.response(patches, probes);
  };
  if (o.analytic_near_field)
    {
      fill_with_analytic_near_field(table, body, h, o, out);
      out.solve_seconds = seconds_since(t0);
      solver_figures();
      return table;
    }
  const std::vector<double> depths = response_depths(table, body, out.depth);
  out.min_depth                    = *std::min_element(depths.begin(), depths.end());
  out.shallow_points               = std::size_t(
                    std::count_if(depths.begin(), depths.end(), [&](double d) { return d < out.depth; }));
  fill_structural_compliance(table, solve, depths, o.material, out.patch_radius);
  out.solve_seconds = seconds_since(t0);
  solver_figures();
  return table;
}

namespace
{
using MemberResult = std::pair<FlankCompliance, MemberComplianceInfo>;

/// The table and its description that the process `root` of comm holds (`mine`), on every
/// process: the others build the grid from `flanks` and the sender's grid specification.
MemberResult
broadcast_result(const MemberFlanks &flanks, const std::optional<MemberResult> &mine, int root,
                 MPI_Comm comm)
{
  namespace mpi             = dealii::Utilities::MPI;
  const bool           here = int(mpi::this_mpi_process(comm)) == root;
  std::vector<double>  head; // the grid specification and the matrix's size, then the teeth
  MemberComplianceInfo info;
  if (here)
    {
      const FlankGridSpec   &g = mine->first.grid_spec();
      const Eigen::MatrixXd &S = mine->first.matrix();
      head                     = {double(g.side == FlankSide::drive ? 0 : 1),
                                  double(g.n_u),
                                  double(g.n_v),
                                  g.margin,
                                  double(g.graded),
                                  double(g.cyclic_tooth),
                                  double(g.cyclic_reach),
                                  double(g.follow_load),
                                  double(S.rows()),
                                  double(S.cols())};
      head.insert(head.end(), g.teeth.begin(), g.teeth.end());
      info = mine->second;
    }
  head = mpi::broadcast(comm, head, root);
  static_assert(std::is_trivially_copyable_v<MemberComplianceInfo>);
  MPI_Bcast(&info, int(sizeof info), MPI_BYTE, root, comm);
  Eigen::MatrixXd S =
      here ? mine->first.matrix() : Eigen::MatrixXd(Eigen::Index(head[8]), Eigen::Index(head[9]));
  MPI_Bcast(S.data(), int(S.size()), MPI_DOUBLE, root, comm);
  if (here)
    return *mine;
  FlankGridSpec g;
  g.side = head[0] == 0 ? FlankSide::drive : FlankSide::coast;
  g.n_u = int(head[1]), g.n_v = int(head[2]);
  g.margin       = head[3];
  g.graded       = head[4] != 0;
  g.cyclic_tooth = int(head[5]), g.cyclic_reach = int(head[6]);
  g.follow_load = head[7] != 0;
  g.teeth.assign(head.begin() + 10, head.end());
  FlankCompliance table(flanks, g);
  table.set(S);
  return {std::move(table), info};
}
} // namespace

std::vector<std::pair<FlankCompliance, MemberComplianceInfo>>
member_compliances(const std::vector<MemberJob> &jobs, MPI_Comm comm)
{
  namespace mpi     = dealii::Utilities::MPI;
  const int  rank   = int(mpi::this_mpi_process(comm));
  const int  size   = int(mpi::n_mpi_processes(comm));
  const int  groups = int(std::min<std::size_t>(jobs.size(), std::size_t(size)));
  const auto run    = [&](std::size_t k, MPI_Comm c, double memory) {
    MemberComplianceInfo info;
    FlankCompliance      table = jobs[k].compute(c, memory, info);
    info.processes             = int(mpi::n_mpi_processes(c));
    return MemberResult(std::move(table), info);
  };
  std::vector<MemberResult> out;
  if (groups <= 1)
    {
      for (std::size_t k = 0; k < jobs.size(); ++k)
        out.push_back(run(k, comm, 0));
      return out;
    }

  // 1. The groups, and each group's share of its machine's available memory.
  const int color = rank % groups;
  MPI_Comm  group, machine, machine_group;
  MPI_Comm_split(comm, color, rank, &group);
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &machine);
  MPI_Comm_split(machine, color, rank, &machine_group);
  const double share =
      memory_available_now() * mpi::n_mpi_processes(machine_group) / mpi::n_mpi_processes(machine);
  MPI_Comm_free(&machine_group);
  MPI_Comm_free(&machine);

  // 2. Every group its jobs, at once.
  enum Status : int
  {
    done,
    refused, // for want of memory on the group: again on all processes
    bad_input,
    error
  };
  std::vector<std::optional<MemberResult>> mine(jobs.size());
  std::vector<int>                         status(jobs.size(), done);
  std::vector<std::string>                 message(jobs.size());
  for (std::size_t k = std::size_t(color); k < jobs.size(); k += std::size_t(groups))
    try
      {
        mine[k] = run(k, group, share);
      }
    catch (const MemoryRefusal &e)
      {
        status[k] = refused, message[k] = e.what();
      }
    catch (const InputError &e)
      {
        status[k] = bad_input, message[k] = e.what();
      }
    catch (const std::exception &e)
      {
        status[k] = error, message[k] = e.what();
      }
  MPI_Comm_free(&group);

  // 3. Each job's outcome from its group's first process (rank k modulo the groups) to all.
  std::vector<std::optional<MemberResult>> results(jobs.size());
  for (std::size_t k = 0; k < jobs.size(); ++k)
    {
      const int root = int(k % std::size_t(groups));
      MPI_Bcast(&status[k], 1, MPI_INT, root, comm);
      if (status[k] == done)
        results[k] = broadcast_result(*jobs[k].flanks, mine[k], root, comm);
      else
        message[k] = mpi::broadcast(comm, message[k], root);
    }
  for (std::size_t k = 0; k < jobs.size(); ++k)
    if (status[k] == bad_input)
      throw InputError(message[k]);
    else if (status[k] == error)
      throw std::runtime_error(message[k]);

  // 4. Jobs refused for memory on a group: on all processes, one after another.
  for (std::size_t k = 0; k < jobs.size(); ++k)
    {
      if (status[k] == refused)
        results[k] = run(k, comm, 0);
      out.push_back(std::move(*results[k]));
    }
  return out;
}
} // namespace gearkit
