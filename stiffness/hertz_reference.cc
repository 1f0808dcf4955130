#include "stiffness/hertz_reference.h"

#include "meshes/cylinder_slice.h"
#include "stiffness/contact_solver.h"
#include "stiffness/elastic_segment.h"

#include <Eigen/Dense>

#include <chrono>
#include <cmath>
#include <filesystem>

namespace gearkit
{
HertzResult
solve_hertz_reference(const HertzCase &c, const std::string &dir)
{
  const auto start = std::chrono::steady_clock::now();
  if (!(c.half_width > 0 && c.element_size > 0 && c.element_size < c.half_width && c.zone > 1))
    throw InputError("Hertz reference: needs 0 < element size < half-width and a zone > 1");
  const double R1 = c.radius_upper, R2 = c.radius_lower, R = 1 / (1 / R1 + 1 / R2);
  const double Es = contact_modulus(c.material, c.material);
  const double q  = c.half_width * c.half_width * pi * Es / (4 * R); // load per length
  const double dx = c.cell_size > 0 ? c.cell_size : c.element_size;
  const double t  = c.element_size; // slice thickness: one element
  const int    n  = 2 * int(std::ceil(c.zone * c.half_width / dx));

  HertzResult r;
  r.applied_force       = q * t;
  r.exact_peak_pressure = 2 * q / (pi * c.half_width);
  r.cells               = n;

  Eigen::MatrixXd     C = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd     gap(n);
  std::vector<double> x(n);
  for (int j = 0; j < n; ++j)
    {
      x[j]   = (j + 0.5 - n / 2.0) * dx;
      gap[j] = (R1 - std::sqrt(R1 * R1 - x[j] * x[j])) + (R2 - std::sqrt(R2 * R2 - x[j] * x[j]));
    }
  for (bool upper : {true, false})
    {
      CylinderSliceOptions mo;
      mo.radius           = upper ? R1 : R2;
      mo.upper            = upper;
      mo.contact_size     = c.element_size;
      mo.fine_distance    = c.zone * c.half_width;
      mo.far_size         = mo.radius / 10;
      mo.grading_distance = mo.radius / 2;
      mo.thickness        = t;
      const std::string file =
          (std::filesystem::path(dir) / (upper ? "hertz_upper.msh" : "hertz_lower.msh")).string();
      write_cylinder_slice_mesh(mo, file);
      ElasticSegmentOptions eo;
      eo.degree   = unsigned(c.degree);
      eo.material = c.material;
      eo.clamped  = {cylinder_boundary::cut};
      eo.rollers  = {{cylinder_boundary::front, 2}, {cylinder_boundary::back, 2}};
      const ElasticSegment body(file, eo);
      r.dofs += body.dofs();
      // The contact force pushes each body into its material: +y on the upper one.
      const double           s = upper ? 1 : -1;
      std::vector<PatchLoad> loads;
      std::vector<Probe>     probes;
      for (int j = 0; j < n; ++j)
        {
          const double y = s * (mo.radius - std::sqrt(mo.radius * mo.radius - x[j] * x[j]));
          loads.push_back({Vec3(x[j], y, t / 2),
                           Vec3(0, s, 0),
                           0,
                           {cylinder_boundary::contact},
                           Vec3(dx / 2, mo.radius, t)});
          // a hair inside: the straight element faces cut the circle's arcs
          probes.push_back({Vec3(x[j], y + s * 1e-3 * c.element_size, t / 2), Vec3(0, s, 0)});
        }
      C += body.response(loads, probes);
    }
  ContactProblem p;
  p.compliance            = (C + C.transpose()) / 2;
  p.gap                   = gap;
  p.lever                 = Eigen::VectorXd::Ones(n);
  p.load                  = r.applied_force;
  const ContactSolution s = solve_contact(p);
  r.total_force           = s.force.sum();
  r.active_cells          = s.active;

  // Fit p^2 = p0^2 - (p0^2 / a^2) x^2 over the active cells away from the edge of contact.
  std::vector<std::pair<double, double>> pts;
  double                                 pmax = 0;
  for (int j = 0; j < n; ++j)
    pmax = std::max(pmax, s.force[j] / (dx * t));
  for (int j = 0; j < n; ++j)
    {
      const double pj = s.force[j] / (dx * t);
      if (pj > 0.3 * pmax)
        pts.emplace_back(x[j] * x[j], pj * pj);
    }
  Eigen::MatrixXd A(pts.size(), 2);
  Eigen::VectorXd b(pts.size());
  for (std::size_t k = 0; k < pts.size(); ++k)
    A(k, 0) = 1, A(k, 1) = pts[k].first, b[k] = pts[k].second;
  const Eigen::Vector2d fit = A.colPivHouseholderQr().solve(b);
  r.peak_pressure           = std::sqrt(fit[0]);
  r.half_width              = std::sqrt(-fit[0] / fit[1]);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}
} // namespace gearkit
