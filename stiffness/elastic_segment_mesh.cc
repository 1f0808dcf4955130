// The body of an elastic segment, in the order the constructor builds it: the gmsh mesh read and
// its cells checked, refined (globally, then about the boundaries asked for, new vertices on the
// exact surfaces), its dofs numbered and held, and the boundary faces' caches the loads use.
#include "stiffness/elastic_segment_impl.h"

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/manifold.h>
#include <deal.II/grid/tria.h>
#include <deal.II/numerics/rtree.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gearkit
{
namespace
{
/// The new vertices of a refined boundary face or edge placed on the exact surface: the
/// flat average of their parents, projected.
class ProjectedSurface : public Manifold<3>
{
public:
  ProjectedSurface(int boundary, std::function<SurfacePoint(int, const Vec3 &)> project)
      : boundary(boundary)
      , project(std::move(project))
  {
  }
  std::unique_ptr<Manifold<3>>
  clone() const override
  {
    return std::make_unique<ProjectedSurface>(boundary, project);
  }
  Point<3>
  get_new_point(const ArrayView<const Point<3>> &points,
                const ArrayView<const double>   &weights) const override
  {
    Vec3 x = Vec3::Zero();
    for (std::size_t i = 0; i < points.size(); ++i)
      x += weights[i] * Vec3(points[i][0], points[i][1], points[i][2]);
    const Vec3 y = project(boundary, x).position;
    if (!y.allFinite())
      throw InputError("elastic segment: the surface of boundary " + std::to_string(boundary) +
                       " has no point for a refined vertex near (" + std::to_string(x.x() * 1e3) +
                       ", " + std::to_string(x.y() * 1e3) + ", " + std::to_string(x.z() * 1e3) +
                       ") mm");
    return point(y);
  }

private:
  int                                            boundary;
  std::function<SurfacePoint(int, const Vec3 &)> project;
};

/// Refines (options.local_refinements times) the cells of `tria` with a vertex within
/// options.refine_distance (halved per pass if asked) of the samples of the faces of `mesh` (the
/// mesh read, whole on every process) with one of options.refine_boundaries (and inside one of
/// options.refine_boxes, if any).
void
refine_near_boundaries(const Triangulation<3> &mesh, parallel::shared::Triangulation<3> &tria,
                       const ElasticSegmentOptions &options)
{
  if (!(options.refine_distance >= 0) || options.refine_boundaries.empty())
    throw InputError("elastic segment: local refinement needs boundaries and a distance >= 0");
  // the boxes' centres in an R-tree; a point is in a box if it is in one of the nearest eight's
  std::vector<std::pair<Point<3>, std::size_t>> centres;
  for (std::size_t i = 0; i < options.refine_boxes.size(); ++i)
    centres.emplace_back(point(options.refine_boxes[i].centre), i);
  const auto centre_tree = pack_rtree(centres);
  auto       in_a_box    = [&](const Point<3> &x, double margin) {
    if (centres.empty())
      return true;
    std::vector<std::pair<Point<3>, std::size_t>> nearest;
    centre_tree.query(boost::geometry::index::nearest(x, 8), std::back_inserter(nearest));
    for (const auto &[c, i] : nearest)
      {
        const ElasticSegmentOptions::Box &b     = options.refine_boxes[i];
        const Vec3                        local = b.axes * (Vec3(x[0], x[1], x[2]) - b.centre);
        if ((local.cwiseAbs() - b.half_size).maxCoeff() <= margin)
          return true;
      }
    return false;
  };
  // the faces sampled at their vertices and centre; with halving distances or boxes on a grid
  // at most half the last pass's distance apart (the finest cells must all find the boundary)
  const double last = options.refine_distance *
                      (options.halve_refine_distance
                           ? std::ldexp(1.0, 1 - int(std::max(1u, options.local_refinements)))
                           : 1);
  std::vector<Point<3>> samples;
  for (const auto &face : mesh.active_face_iterators())
    if (face->at_boundary() && options.refine_boundaries.count(int(face->boundary_id())) &&
        in_a_box(face->center(), face->diameter()))
      {
        std::vector<Point<3>> x{face->center()};
        for (unsigned v = 0; v < 4; ++v)
          x.push_back(face->vertex(v));
        const int n = options.halve_refine_distance || !centres.empty()
                          ? std::max(1, int(std::ceil(2 * face->diameter() / last)))
                          : 1;
        if (n > 1)
          for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j)
              {
                const double a = double(i) / n, b = double(j) / n; // bilinear on the face
                x.push_back(Point<3>((1 - a) * (1 - b) * face->vertex(0) +
                                     a * (1 - b) * face->vertex(1) + (1 - a) * b * face->vertex(2) +
                                     a * b * face->vertex(3)));
              }
        std::copy_if(x.begin(), x.end(), std::back_inserter(samples),
                     [&](const Point<3> &y) { return in_a_box(y, 0); });
      }
  if (samples.empty())
    throw InputError("elastic segment: none of the boundaries to refine near is in the mesh" +
                     std::string(centres.empty() ? "" : " within the boxes given"));
  const auto     tree     = pack_rtree(samples);
  double         distance = options.refine_distance;
  const MPI_Comm comm     = tria.get_communicator();
  const double   have =
      options.memory_available > 0 ? options.memory_available : memory_available_now();
  for (unsigned pass = 0; pass < options.local_refinements;
       ++pass, distance *= options.halve_refine_distance ? 0.5 : 1)
    {
      // every process flags every cell alike (each refines the whole mesh)
      for (const auto &cell : tria.active_cell_iterators())
        for (unsigned v = 0; v < GeometryInfo<3>::vertices_per_cell; ++v)
          {
            std::vector<Point<3>> nearest;
            tree.query(boost::geometry::index::nearest(cell->vertex(v), 1),
                       std::back_inserter(nearest));
            if (nearest[0].distance(cell->vertex(v)) <= distance)
              {
                cell->set_refine_flag();
                break;
              }
          }
      // refused before the pass when the refined body's matrix would not fit (the same
      // estimate as before the assembly; each refined cell becomes eight)
      std::size_t flagged = 0;
      for (const auto &cell : tria.active_cell_iterators())
        flagged += cell->refine_flag_set() ? 1 : 0; // (a RefinementCase: 7 for isotropic)
      const double       cells_after = double(tria.n_active_cells() + 7 * flagged);
      const double       p           = options.degree;
      std::ostringstream what;
      what.precision(3);
      what << "local refinement pass " << pass + 1 << " of " << options.local_refinements
           << " would make about " << cells_after << " elements, whose stiffness matrix";
      require_memory(cells_after * 3 * p * p * p * matrix_bytes_per_dof(options.degree) /
                         Utilities::MPI::n_mpi_processes(comm),
                     have, comm, what.str(),
                     "Use fewer refinements (larger elements at the contact) or more machines "
                     "under mpirun");
      tria.execute_coarsening_and_refinement();
    }
}
} // namespace

ElasticSegment::Impl::Impl(unsigned degree, MPI_Comm communicator)
    : comm(communicator)
    , tria(communicator, Triangulation<3>::none, false,
           parallel::shared::Triangulation<3>::partition_zorder)
    , fe(FE_Q<3>(degree), 3)
    , scalar_fe(degree)
{
}

ElasticSegment::Impl::~Impl()
{
  if (surface_points)
    for (std::size_t i = 0; i < tria.n_active_cells() * 6 * face_rules; ++i)
      delete surface_points[i].load();
  if (factor)
    MatDestroy(&factor);
  if (ksp)
    KSPDestroy(&ksp);
  if (K)
    MatDestroy(&K);
}

void
ElasticSegment::Impl::read_mesh(Triangulation<3> &coarse) const
{
  {
    GridIn<3> in;
    in.attach_triangulation(coarse);
    try
      {
        in.read_msh(mesh_file);
      }
    catch (const std::exception &e)
      {
        throw InputError("elastic segment: " + mesh_file +
                         " is not a hexahedral gmsh mesh deal.II can read (" + e.what() + ")");
      }
  }
  if (coarse.n_active_cells() == 0 || !coarse.all_reference_cells_are_hyper_cube())
    throw InputError("elastic segment: " + mesh_file +
                     " must contain hexahedra only (gmsh: recombine and extrude, or subdivide)");
  {
    // Degenerate or inverted elements: the Jacobian at some corner not positive (relative to
    // the element's mean, so thin elements pass).
    const FE_Q<3>       q1(1);
    const QTrapezoid<3> corners;
    FEValues<3>         values(mapping, q1, corners, update_JxW_values);
    for (const auto &cell : coarse.active_cell_iterators())
      {
        values.reinit(cell);
        double mean = 0, worst = HUGE_VAL;
        for (unsigned q = 0; q < corners.size(); ++q)
          mean += std::abs(values.JxW(q)), worst = std::min(worst, values.JxW(q));
        if (!(worst > 1e-9 * mean))
          {
            std::ostringstream msg;
            msg << "elastic segment: " << mesh_file
                << " has a degenerate or inverted hexahedron (cell " << cell->index() << " at "
                << cell->center() * 1e3 << " mm: corner Jacobian " << worst / mean * corners.size()
                << " of its mean); allowed: positive Jacobians at every corner";
            throw InputError(msg.str());
          }
      }
  }
}

void
ElasticSegment::Impl::refine(Triangulation<3> &coarse)
{
  // The faces and edges of boundaries with an exact surface refined onto it (manifold id =
  // boundary id).
  if (!options.surface_boundaries.empty() && !options.boundary_surface)
    throw InputError("elastic segment: boundaries with an exact surface need its function");
  for (int id : options.surface_boundaries)
    coarse.set_all_manifold_ids_on_boundary(types::boundary_id(id), types::manifold_id(id));
  tria.copy_triangulation(coarse);
  for (int id : options.surface_boundaries)
    tria.set_manifold(types::manifold_id(id), ProjectedSurface(id, options.boundary_surface));
  tria.refine_global(options.refinements);
  if (options.local_refinements > 0)
    refine_near_boundaries(coarse, tria, options);
  cache_ptr = std::make_unique<GridTools::Cache<3>>(tria, mapping);
}

std::set<types::boundary_id>
ElasticSegment::Impl::boundary_ids() const
{
  std::set<types::boundary_id> present;
  for (const auto &face : tria.active_face_iterators())
    if (face->at_boundary())
      present.insert(face->boundary_id());
  return Utilities::MPI::compute_set_union(present, comm);
}

void
ElasticSegment::Impl::distribute_dofs()
{
  dofs.reinit(tria);
  dofs.distribute_dofs(fe);
  owned = dofs.locally_owned_dofs();
  // the component of every dof a remainder load can reach (balance_remainder_loads)
  dof_component.assign(dofs.n_dofs(), 0);
  std::vector<types::global_dof_index> indices(fe.n_dofs_per_cell());
  for (const auto &cell : dofs.active_cell_iterators())
    if (!cell->is_artificial())
      {
        cell->get_dof_indices(indices);
        for (unsigned i = 0; i < indices.size(); ++i)
          dof_component[indices[i]] =
              static_cast<unsigned char>(fe.system_to_component_index(i).first);
      }
}

void
ElasticSegment::Impl::make_constraints(const std::set<types::boundary_id> &present)
{
  auto require = [&](int id) {
    if (!present.count(types::boundary_id(id)))
      throw InputError("elastic segment: boundary id " + std::to_string(id) + " is not in " +
                       mesh_file);
  };
  DoFTools::extract_locally_relevant_dofs(dofs, relevant);
  constraints.reinit(relevant);
  DoFTools::make_hanging_node_constraints(dofs, constraints);
  for (int id : options.clamped)
    {
      require(id);
      VectorTools::interpolate_boundary_values(mapping, dofs, types::boundary_id(id),
                                               Functions::ZeroFunction<3>(3), constraints);
    }
  for (const auto &[id, component] : options.rollers)
    {
      require(id);
      if (component < 0 || component > 2)
        throw InputError("elastic segment: roller component must be 0, 1 or 2");
      ComponentMask mask(3, false);
      mask.set(component, true);
      VectorTools::interpolate_boundary_values(mapping, dofs, types::boundary_id(id),
                                               Functions::ZeroFunction<3>(3), constraints, mask);
    }
  constraints.close();
}

void
ElasticSegment::Impl::cache_boundary_faces()
{
  // Boundary quadrature cache for the loads.
  const unsigned  n = fe.n_dofs_per_cell();
  const QGauss<2> face_quadrature(options.degree + 2);
  FEFaceValues<3> face_values(mapping, fe, face_quadrature,
                              update_values | update_quadrature_points | update_JxW_values);
  for (const auto &cell : dofs.active_cell_iterators())
    if (cell->is_locally_owned())
      for (unsigned f = 0; f < GeometryInfo<3>::faces_per_cell; ++f)
        if (cell->face(f)->at_boundary())
          {
            face_values.reinit(cell, f);
            Impl::FaceData d;
            d.boundary = int(cell->face(f)->boundary_id());
            d.centre   = cell->face(f)->center();
            d.diameter = cell->face(f)->diameter();
            d.dof_indices.resize(n);
            cell->get_dof_indices(d.dof_indices);
            d.cell    = cell;
            d.face_no = f;
            for (unsigned v = 0; v < 4; ++v)
              d.vertices[v] = cell->face(f)->vertex(v);
            for (unsigned q = 0; q < face_quadrature.size(); ++q)
              {
                d.q_points.push_back(face_values.quadrature_point(q));
                d.JxW.push_back(face_values.JxW(q));
                for (unsigned i = 0; i < n; ++i)
                  {
                    std::array<double, 3> s{{0, 0, 0}};
                    s[fe.system_to_component_index(i).first] = face_values.shape_value(i, q);
                    d.shape.push_back(s);
                  }
              }
            faces.push_back(std::move(d));
          }
  for (const auto &cell : dofs.active_cell_iterators())
    if (cell->is_locally_owned() || cell->is_ghost())
      for (unsigned f = 0; f < GeometryInfo<3>::faces_per_cell; ++f)
        if (cell->face(f)->at_boundary())
          {
            const auto         face = cell->face(f);
            Tensor<1, 3>       a    = cross_product_3d(face->vertex(3) - face->vertex(0),
                                                       face->vertex(2) - face->vertex(1));
            const Tensor<1, 3> out  = face->center() - cell->center();
            if (a * out < 0)
              a = -a;
            for (unsigned v = 0; v < 4; ++v)
              vertex_normals[{face->vertex_index(v), int(face->boundary_id())}] += a;
          }
  fine_face_values = std::make_unique<FEFaceValues<3>>(
      mapping, fe, QIterated<2>(QGauss<1>(options.degree + 1), 8),
      update_values | update_quadrature_points | update_JxW_values);
}

bool
ElasticSegment::Impl::held(int boundary) const
{
  return options.clamped.count(boundary) ||
         std::any_of(options.rollers.begin(), options.rollers.end(),
                     [&](const auto &r) { return r.first == boundary; });
}

double
ElasticSegment::Impl::local_distance_to_held(const Point<3> &x) const
{
  double d = HUGE_VAL;
  for (const FaceData &face : faces)
    if (held(face.boundary))
      d = std::min(d, face.centre.distance(x) - face.diameter / 2);
  return d;
}
} // namespace gearkit
