// The remainder loads of unit point forces whose near field is carried analytically
// (ElasticSegment::remainder_response): the quadratures of the cut-off's shell and of the faces
// about the force, the exact surfaces the facets stand for, and the balance of each load.
#include "stiffness/elastic_segment_impl.h"

#include <deal.II/base/qprojector.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/numerics/rtree.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace gearkit
{
namespace
{
/// (xi, eta) of the point of the bilinear face (vertices in lexicographic order: (0, 0),
/// (1, 0), (0, 1), (1, 1)) nearest to x, by Gauss-Newton; not clamped to the face.
std::pair<double, double>
bilinear_coordinates(const std::array<Point<3>, 4> &v, const Point<3> &x)
{
  double xi = 0.5, eta = 0.5;
  for (int it = 0; it < 8; ++it)
    {
      const Tensor<1, 3> r = v[0] * (1 - xi) * (1 - eta) + v[1] * xi * (1 - eta) +
                             v[2] * (1 - xi) * eta + v[3] * xi * eta - x;
      const Tensor<1, 3> dxi  = (v[1] - v[0]) * (1 - eta) + (v[3] - v[2]) * eta;
      const Tensor<1, 3> deta = (v[2] - v[0]) * (1 - xi) + (v[3] - v[1]) * xi;
      const double       a = dxi * dxi, b = dxi * deta, c = deta * deta;
      const double       p = -(dxi * r), q = -(deta * r), det = a * c - b * b;
      const double       step_xi = (c * p - b * q) / det, step_eta = (a * q - b * p) / det;
      xi += step_xi;
      eta += step_eta;
      if (std::abs(step_xi) + std::abs(step_eta) < 1e-13)
        break;
    }
  return {xi, eta};
}

/// How often to subdivide the Gauss rule on a cell or face of about `size` (an edge) for it
/// to resolve a cut-off shell of width `shell`: into parts of at most half the shell. Measured
/// on a shell one element wide: the remainder at the force moved by 30 % as the force moved
/// within an element on the plain rule, by 3 % on rules subdivided twice or four times.
unsigned
rule_subdivisions(double size, double shell)
{
  return unsigned(std::clamp(std::ceil(2 * size / shell), 1.0, double(max_rule_subdivisions)));
}
} // namespace

ElasticSegment::Impl::FaceNormals
ElasticSegment::Impl::face_normals(const typename DoFHandler<3>::active_cell_iterator &cell,
                                   unsigned                                            f) const
{
  const auto  face = cell->face(f);
  FaceNormals out;
  out.boundary = int(face->boundary_id());
  for (unsigned k = 0; k < 4; ++k)
    {
      out.vertex[k] = face->vertex(k);
      out.sum[k]    = vertex_normals.at({face->vertex_index(k), int(face->boundary_id())});
      out.length[k] = out.sum[k].norm();
    }
  return out;
}

Tensor<1, 3>
ElasticSegment::Impl::smooth_normal(const FaceNormals &face, const Point<3> &x)
{
  // the vertex normals interpolated with the bilinear face's weights at x
  const auto [xi, eta] = bilinear_coordinates(face.vertex, x);
  const double w[4]    = {(1 - xi) * (1 - eta), xi * (1 - eta), (1 - xi) * eta, xi * eta};
  Tensor<1, 3> n;
  for (unsigned k = 0; k < 4; ++k)
    n += w[k] * face.sum[k] / face.length[k];
  return n / n.norm();
}

std::pair<Point<3>, Tensor<1, 3>>
ElasticSegment::Impl::surface_point(const FaceNormals &face, const Point<3> &x) const
{
  if (!options.surface_boundaries.count(face.boundary))
    return {x, smooth_normal(face, x)};
  const SurfacePoint s = options.boundary_surface(face.boundary, Vec3(x[0], x[1], x[2]));
  if (!(s.position.allFinite() && s.normal.allFinite() && std::abs(s.normal.norm() - 1) < 1e-6))
    {
      std::ostringstream msg;
      msg << "elastic segment: the exact surface of boundary " << face.boundary
          << " has no point with a unit normal for (" << 1e3 * x << ") mm";
      throw InputError(msg.str());
    }
  return {point(s.position), Tensor<1, 3>({s.normal.x(), s.normal.y(), s.normal.z()})};
}

ElasticSegment::Impl::SplitRule
ElasticSegment::Impl::split_face_rule(const typename Triangulation<3>::active_cell_iterator &cell,
                                      unsigned face, const Point<3> &x, double within) const
{
  SplitRule rule;
  // the face's point nearest to x: (xi, eta) on the bilinear face of the corners, clamped
  std::array<Point<3>, 4> corner;
  auto                    nearest = [&] {
    auto [xi, eta] = bilinear_coordinates(corner, x);
    xi = std::clamp(xi, 0.0, 1.0), eta = std::clamp(eta, 0.0, 1.0);
    const Point<3> at = corner[0] * (1 - xi) * (1 - eta) + corner[1] * xi * (1 - eta) +
                        corner[2] * (1 - xi) * eta + corner[3] * xi * eta;
    return std::make_pair(Point<2>(xi, eta), at.distance(x));
  };
  // first on the face's own vertices (lexicographic in the face): most faces are farther
  for (unsigned k = 0; k < 4; ++k)
    corner[k] = cell->face(face)->vertex(k);
  if (!(nearest().second < within))
    return rule;
  // then in the coordinates of the rules projected to the face
  static const Quadrature<2> corner_rule(
      std::vector<Point<2>>{Point<2>(0, 0), Point<2>(1, 0), Point<2>(0, 1), Point<2>(1, 1)},
      std::vector<double>(4, 0.25));
  const Quadrature<3> corners_in_cell =
      QProjector<3>::project_to_face(ReferenceCells::Hexahedron, corner_rule, face);
  for (unsigned k = 0; k < 4; ++k)
    corner[k] = mapping.transform_unit_to_real_cell(cell, corners_in_cell.point(k));
  const QSplit<2>     split(QDuffy(options.degree + 4, 1.0), nearest().first);
  const Quadrature<3> in_cell =
      QProjector<3>::project_to_face(ReferenceCells::Hexahedron, split, face);
  rule.values = std::make_unique<FEValues<3>>(
      mapping, scalar_fe, in_cell, update_values | update_quadrature_points | update_jacobians);
  rule.values->reinit(cell);
  // the surface weight: the reference face's two axes mapped, their cross product's length
  const unsigned a = (face / 2 + 1) % 3, b = (face / 2 + 2) % 3;
  for (unsigned q = 0; q < in_cell.size(); ++q)
    {
      const DerivativeForm<1, 3, 3> &J = rule.values->jacobian(q);
      Tensor<1, 3>                   ta, tb;
      for (unsigned d = 0; d < 3; ++d)
        ta[d] = J[d][a], tb[d] = J[d][b];
      rule.JxW.push_back(split.weight(q) * cross_product_3d(ta, tb).norm());
    }
  return rule;
}

ElasticSegment::Impl::RemainderScratch::RemainderScratch(const Impl &m)
    : near_face(m.mapping, m.scalar_fe, QIterated<2>(QGauss<1>(m.options.degree + 1), 8),
                update_values | update_quadrature_points | update_JxW_values)
    , body(m.scalar_fe.n_dofs_per_cell(), 3)
    , spread(m.scalar_fe.n_dofs_per_cell())
    , f(m.dofs.n_dofs())
    , g(m.dofs.n_dofs())
{
  for (unsigned i = 0; i < m.fe.n_dofs_per_cell(); ++i)
    component.push_back(m.fe.system_to_component_index(i).first),
        scalar.push_back(m.fe.system_to_component_index(i).second);
  const auto flags = update_values | update_quadrature_points | update_JxW_values;
  for (unsigned k = 1; k <= max_rule_subdivisions; ++k)
    {
      volume.emplace_back(m.scalar_fe, m.options.degree + 2, k);
      face.push_back(std::make_unique<FEFaceValues<3>>(
          m.mapping, m.scalar_fe, QIterated<2>(QGauss<1>(m.options.degree + 2), k), flags));
    }
}

ElasticSegment::Impl::SubdividedRule::SubdividedRule(const FiniteElement<3> &scalar_fe,
                                                     unsigned gauss, unsigned subdivisions)
    : k(subdivisions)
{
  const QGauss<3> base(gauss);
  per_subcell = base.size();
  for (unsigned sz = 0; sz < k; ++sz)
    for (unsigned sy = 0; sy < k; ++sy)
      for (unsigned sx = 0; sx < k; ++sx)
        for (unsigned q = 0; q < base.size(); ++q)
          {
            const Point<3> &p = base.point(q);
            points.emplace_back((sx + p[0]) / k, (sy + p[1]) / k, (sz + p[2]) / k);
            weights.push_back(base.weight(q) / (k * k * k));
          }
  phi.resize(scalar_fe.n_dofs_per_cell(), Eigen::Index(points.size()));
  for (unsigned a = 0; a < scalar_fe.n_dofs_per_cell(); ++a)
    for (std::size_t q = 0; q < points.size(); ++q)
      phi(a, Eigen::Index(q)) = scalar_fe.shape_value(a, points[q]);
}

void
ElasticSegment::Impl::check_near_field_loads(const std::vector<NearFieldLoad> &loads) const
{
  for (const NearFieldLoad &load : loads)
    if (!(load.inner > 0 && load.outer > load.inner) || !load.point.allFinite() ||
        !(std::abs(load.direction.norm() - 1) < 1e-9))
      throw InputError("elastic segment: a near-field load needs 0 < inner < outer radius, a "
                       "finite point and a unit direction");
  // on every process together (a throw on one alone would leave the others waiting)
  std::vector<double> held_at(loads.size());
  for (std::size_t i = 0; i < loads.size(); ++i)
    held_at[i] = local_distance_to_held(point(loads[i].point));
  Utilities::MPI::min(held_at, comm, held_at);
  for (std::size_t i = 0; i < loads.size(); ++i)
    if (held_at[i] < loads[i].outer)
      {
        std::ostringstream msg;
        msg << "elastic segment: the near field of the load at ("
            << loads[i].point.transpose() * 1e3 << ") mm reaches a held boundary "
            << held_at[i] * 1e3 << " mm away (cut-off radius " << loads[i].outer * 1e3
            << " mm); expected a smaller radius";
        throw InputError(msg.str());
      }
}

const ElasticSegment::Impl::SurfacePoints &
ElasticSegment::Impl::face_surface_points(
    const typename Triangulation<3>::active_cell_iterator &cell, unsigned face, unsigned rule,
    const FaceNormals &normals, const FEFaceValues<3> &values) const
{
  std::atomic<SurfacePoints *> &slot =
      surface_points[(cell->active_cell_index() * 6 + face) * face_rules + rule];
  if (const SurfacePoints *known = slot.load(std::memory_order_acquire))
    return *known;
  auto made = std::make_unique<SurfacePoints>();
  for (unsigned q = 0; q < values.n_quadrature_points; ++q)
    {
      const auto [at, normal] = surface_point(normals, values.quadrature_point(q));
      made->at.push_back(at), made->normal.push_back(normal);
    }
  SurfacePoints *expected = nullptr; // another thread may have made it meanwhile: the same
  if (slot.compare_exchange_strong(expected, made.get(), std::memory_order_acq_rel))
    return *made.release();
  return *expected;
}

/// A near-field load's cut-off chi and field chi u, and the resolution its quadratures need.
/// The body force lives where the cut-off varies: in the shell between the radii and where the
/// body rises 30 to 60 degrees above the load's tangent plane (near_field_cutoff); the traction
/// on every boundary face within the outer radius, on faces near the force with a finely
/// subdivided rule (the residual traction of a curved surface grows like 1/r toward the force).
/// The length the rules must resolve: the shell's thickness, or the elevation step's width at
/// the distance of an object (centre, radius) that may meet it.
struct ElasticSegment::Impl::LoadShell
{
  const NearFieldLoad &load;
  const Point<3>       x0;
  const Material      &material;
  const Vec3           axis;
  const double         thickness; ///< the shell's

  LoadShell(const NearFieldLoad &load, const Material &material)
      : load(load)
      , x0(point(load.point))
      , material(material)
      , axis(load.direction.normalized())
      , thickness(load.outer - load.inner)
  {
  }
  Cutoff
  cutoff(const Point<3> &x) const
  {
    return near_field_cutoff(Vec3(x[0], x[1], x[2]), load.point, axis, load.inner, load.outer);
  }
  NearField
  near(const Point<3> &x, const Cutoff &chi, const Tensor<1, 3> &normal) const
  {
    const Vec3 y(x[0], x[1], x[2]);
    return cut_off_near_field(point_force_field(y, load.point, load.direction, 1.0, material), chi,
                              Vec3(normal[0], normal[1], normal[2]), material);
  }
  /// The lowest and highest elevation above the force's tangent plane of the ball about centre
  /// of the given radius (which must not contain the force), seen from it.
  std::pair<double, double>
  elevations(const Point<3> &centre, double radius) const
  {
    const double reach = centre.distance(x0);
    const double elevation =
        std::asin(std::clamp(-((centre - x0) * point(axis)) / reach, -1.0, 1.0));
    const double spread = std::asin(std::min(1.0, radius / reach));
    return std::make_pair(elevation - spread, elevation + spread);
  }
  /// The length a rule must resolve on the ball about centre of the given radius.
  double
  scale(const Point<3> &centre, double radius) const
  {
    const double reach = centre.distance(x0);
    if (reach <= radius)
      return 0.0; // contains the force: the finest rule
    const auto [lowest, highest] = elevations(centre, radius);
    const bool steps             = highest > pi / 6 && lowest < pi / 3;
    return steps ? std::min(thickness, 0.5 * (reach - radius)) : thickness;
  }
  /// chi (near_field_cutoff: radial step from inner to outer times the elevation step from 30
  /// to 60 degrees) constant, 0 or 1, on the ball about centre of the given radius (with a
  /// margin of rounding)
  bool
  cutoff_constant_on(const Point<3> &centre, double radius) const
  {
    const double reach = centre.distance(x0), margin = 1e-9 * load.outer;
    if (reach - radius >= load.outer + margin)
      return true; // chi = 0
    if (reach <= radius + margin)
      return false; // contains the force
    const auto [lowest, highest] = elevations(centre, radius + margin);
    if (lowest > pi / 3 + 1e-9)
      return true;                                                           // chi = 0
    return reach + radius <= load.inner - margin && highest < pi / 6 - 1e-9; // chi = 1
  }
};

void
ElasticSegment::Impl::assemble_remainder_load(const NearFieldLoad &load,
                                              RemainderScratch    &scratch) const
{
  const LoadShell                      shell(load, options.material);
  const Point<3>                      &x0 = shell.x0;
  const unsigned                       n  = fe.n_dofs_per_cell();
  Vector<double>                       local(n);
  std::vector<types::global_dof_index> indices(n);
  // the cells whose bounding boxes meet the cube about the outer sphere
  Point<3> low = x0, high = x0;
  for (unsigned d = 0; d < 3; ++d)
    low[d] -= load.outer, high[d] += load.outer;
  std::vector<std::pair<BoundingBox<3>, typename Triangulation<3>::active_cell_iterator>>
      near_cells;
  cache_ptr->get_locally_owned_cell_bounding_boxes_rtree().query(
      boost::geometry::index::intersects(BoundingBox<3>(std::make_pair(low, high))),
      std::back_inserter(near_cells));
  for (const auto &[box, tria_cell] : near_cells)
    {
      const typename DoFHandler<3>::active_cell_iterator cell(*tria_cell, &dofs);
      const double reach = cell->center().distance(x0), radius = cell->diameter() / 2;
      if (reach - radius > load.outer)
        continue;
      local                 = 0;
      const double resolved = shell.scale(cell->center(), radius);
      if (reach + radius > load.inner || resolved < shell.thickness)
        add_remainder_body_force(shell, tria_cell, cell, radius, resolved, scratch, local, indices);
      add_remainder_traction(shell, tria_cell, cell, scratch, local);
      cell->get_dof_indices(indices);
      constraints.distribute_local_to_global(local, indices, scratch.f);
    }
}

void
ElasticSegment::Impl::add_remainder_body_force(
    const LoadShell &shell, const typename Triangulation<3>::active_cell_iterator &tria_cell,
    const typename DoFHandler<3>::active_cell_iterator &cell, double radius, double resolved,
    RemainderScratch &scratch, Vector<double> &local,
    std::vector<types::global_dof_index> &indices) const
{
  const unsigned        n = fe.n_dofs_per_cell();
  const SubdividedRule &rule =
      scratch.volume[rule_subdivisions(2 * radius / std::sqrt(3.0), resolved) - 1];
  // the cell's trilinear map (MappingQ1's), x = c0 + c1 xi + c2 eta + c3 zeta + c4 xi eta
  // + c5 xi zeta + c6 eta zeta + c7 xi eta zeta from its vertices (lexicographic)
  std::array<Tensor<1, 3>, 8> c;
  {
    std::array<Tensor<1, 3>, 8> X;
    for (unsigned v = 0; v < 8; ++v)
      X[v] = tria_cell->vertex(v);
    c = {{X[0], X[1] - X[0], X[2] - X[0], X[4] - X[0], X[3] - X[1] - X[2] + X[0],
          X[5] - X[1] - X[4] + X[0], X[6] - X[2] - X[4] + X[0],
          X[7] - X[3] - X[5] - X[6] + X[1] + X[2] + X[4] - X[0]}};
  }
  const auto map = [&c](const Point<3> &xi) {
    return Point<3>(c[0] + xi[0] * c[1] + xi[1] * c[2] + xi[2] * c[3] + xi[0] * xi[1] * c[4] +
                    xi[0] * xi[2] * c[5] + xi[1] * xi[2] * c[6] + xi[0] * xi[1] * xi[2] * c[7]);
  };
  const auto jacobian_determinant = [&c](const Point<3> &xi) {
    const Tensor<1, 3> d0 = c[1] + xi[1] * c[4] + xi[2] * c[5] + xi[1] * xi[2] * c[7],
                       d1 = c[2] + xi[0] * c[4] + xi[2] * c[6] + xi[0] * xi[2] * c[7],
                       d2 = c[3] + xi[0] * c[5] + xi[1] * c[6] + xi[0] * xi[1] * c[7];
    return d0 * cross_product_3d(d1, d2);
  };
  const unsigned m_q = rule.per_subcell, k = rule.k;
  scratch.body.setZero();
  scratch.spread.setZero();
  for (unsigned sub = 0; sub < k * k * k; ++sub)
    {
      // a sub-cell lies within the ball about its mapped corners' mean through the
      // farthest of them (a trilinear map keeps it in their convex hull): skipped where
      // chi is constant on that ball
      const unsigned          sx = sub % k, sy = (sub / k) % k, sz = sub / (k * k);
      std::array<Point<3>, 8> corner;
      Point<3>                centre;
      for (unsigned v = 0; v < 8; ++v)
        {
          corner[v] = map(Point<3>(double(sx + (v & 1)) / k, double(sy + ((v >> 1) & 1)) / k,
                                   double(sz + ((v >> 2) & 1)) / k));
          centre += corner[v] / 8;
        }
      double rho = 0;
      for (const Point<3> &c : corner)
        rho = std::max(rho, c.distance(centre));
      if (shell.cutoff_constant_on(centre, rho))
        continue;
      scratch.forces.setZero(m_q, 3);
      scratch.spread_at.setZero(m_q);
      for (unsigned q = 0; q < m_q; ++q)
        {
          const Point<3> &xi  = rule.points[sub * m_q + q];
          const Point<3>  x   = map(xi);
          const Cutoff    chi = shell.cutoff(x);
          if (!chi.varies())
            continue; // chi constant: no body force
          const double dx       = jacobian_determinant(xi) * rule.weights[sub * m_q + q];
          scratch.forces.row(q) = shell.near(x, chi, Tensor<1, 3>()).body * dx;
          scratch.spread_at(q)  = chi.gradient.norm() * dx;
        }
      scratch.body.noalias() += rule.phi.middleCols(sub * m_q, m_q) * scratch.forces;
      scratch.spread.noalias() += rule.phi.middleCols(sub * m_q, m_q) * scratch.spread_at;
    }
  for (unsigned i = 0; i < n; ++i)
    local(i) += scratch.body(scratch.scalar[i], scratch.component[i]);
  if (scratch.spread.sum() > 0)
    {
      Vector<double> spread(n);
      for (unsigned i = 0; i < n; ++i)
        spread(i) = scratch.spread(scratch.scalar[i]);
      cell->get_dof_indices(indices);
      constraints.distribute_local_to_global(spread, indices, scratch.g);
    }
}

void
ElasticSegment::Impl::add_remainder_traction(
    const LoadShell &shell, const typename Triangulation<3>::active_cell_iterator &tria_cell,
    const typename DoFHandler<3>::active_cell_iterator &cell, RemainderScratch &scratch,
    Vector<double> &local) const
{
  const unsigned  n  = fe.n_dofs_per_cell();
  const Point<3> &x0 = shell.x0;
  for (unsigned face = 0; face < GeometryInfo<3>::faces_per_cell; ++face)
    if (cell->face(face)->at_boundary() &&
        cell->face(face)->center().distance(x0) - cell->face(face)->diameter() / 2 <
            shell.load.outer)
      {
        const double      diameter = cell->face(face)->diameter();
        const bool        close    = cell->face(face)->center().distance(x0) < 2 * diameter;
        const FaceNormals normals  = face_normals(cell, face);
        // next to the force, a rule split at the face's point nearest to it (Duffy:
        // exact for the residual traction's 1/r there, wherever the force falls)
        const SplitRule split =
            close ? split_face_rule(tria_cell, face, x0, 0.25 * diameter) : SplitRule();
        const unsigned rule =
            close ? face_rules - 1
                  : rule_subdivisions(diameter / std::sqrt(2.0),
                                      shell.scale(cell->face(face)->center(), diameter / 2)) -
                        1;
        FEFaceValues<3>     &v      = close ? scratch.near_face : *scratch.face[rule];
        const SurfacePoints *cached = nullptr;
        if (!split.values)
          {
            v.reinit(tria_cell, face);
            cached = &face_surface_points(tria_cell, face, rule, normals, v);
          }
        const unsigned n_q =
            split.values ? split.values->n_quadrature_points : v.n_quadrature_points;
        for (unsigned q = 0; q < n_q; ++q)
          {
            // on a boundary with an exact surface, the point of the surface the facet's
            // point stands for: the force lies on it, so the traction left to the elements
            // is the surface's curvature's, ~ 1 / r, not the facets' tilt's, ~ 1 / r^2
            const auto [at, normal] =
                cached ? std::make_pair(cached->at[q], cached->normal[q])
                       : surface_point(normals, split.values->quadrature_point(q));
            if (at.distance(x0) < 1e-12 * cell->diameter())
              continue; // the force itself (its part is carried by chi u)
            const Cutoff chi = shell.cutoff(at);
            if (chi.value == 0)
              continue;
            const Vec3 t =
                shell.near(at, chi, normal).traction * (split.values ? split.JxW[q] : v.JxW(q));
            for (unsigned i = 0; i < n; ++i)
              local(i) -= (split.values ? split.values->shape_value(scratch.scalar[i], q)
                                        : v.shape_value(scratch.scalar[i], q)) *
                          t[scratch.component[i]];
          }
      }
}

std::vector<Vec3>
ElasticSegment::Impl::balance_remainder_loads(const std::vector<NearFieldLoad>         &loads,
                                              const std::vector<std::vector<PetscInt>> &rows,
                                              std::vector<std::vector<double>>         &values,
                                              const std::vector<std::vector<double>> &spreads) const
{
  // The continuous remainder's load (the body force of chi u in the cut-off's shell, less its
  // traction on the boundary) balances the unit force exactly: the finite elements must carry
  // all of it to the held faces. The body force is integrated over the elements' faceted body,
  // the traction on the exact flank it stands for; between the two lie the slivers between
  // facets and the curved flank (and fillet), where the shell's body force is large, so the
  // assembled load is out of balance by 0.2 to 5 % of the force (most near the base circle and
  // the tip, where the involute is most curved; bench/README.md, issue 36), by an amount that
  // changes with the mesh, and the whole structural response with it. The missing force goes
  // back where the slivers lie: spread over the shell like |grad chi|, a smooth field the
  // elements resolve as they resolve the body force.
  const std::size_t   n = loads.size();
  std::vector<double> sums(4 * n, 0.0); // per load: the resultant, then the spread's integral
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t e = 0; e < rows[k].size(); ++e)
      {
        const unsigned c = dof_component[std::size_t(rows[k][e])];
        sums[4 * k + c] += values[k][e];
        if (c == 0) // the scalar shape functions sum to 1: one component's weights integrate it
          sums[4 * k + 3] += spreads[k][e];
      }
  Utilities::MPI::sum(sums, comm, sums);
  std::vector<Vec3> before(n);
  for (std::size_t k = 0; k < n; ++k)
    {
      before[k]           = Vec3(sums[4 * k], sums[4 * k + 1], sums[4 * k + 2]);
      const double spread = sums[4 * k + 3];
      if (!(spread > 0))
        throw std::logic_error("elastic segment: a near-field load whose cut-off shell misses "
                               "the body");
      const Vec3 missing = loads[k].direction.normalized() - before[k];
      for (std::size_t e = 0; e < rows[k].size(); ++e)
        values[k][e] += missing[dof_component[std::size_t(rows[k][e])]] * spreads[k][e] / spread;
    }
  return before;
}
} // namespace gearkit
