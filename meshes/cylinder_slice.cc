#include "meshes/cylinder_slice.h"

#include "geometry/types.h"
#include "meshes/gmsh_session.h"

#include <gmsh.h>

#include <cmath>
#include <sstream>
#include <tuple>

namespace gearkit
{
CylinderSliceInfo
write_cylinder_slice_mesh(const CylinderSliceOptions &o, const std::string &path)
{
  if (!(o.radius > 0 && o.contact_size > 0 && o.far_size >= o.contact_size &&
        o.grading_distance > 0 && o.fine_distance >= 0 && o.thickness > 0 &&
        o.contact_size < o.radius))
    throw InputError("cylinder slice mesh: needs radius, sizes, grading distance and thickness "
                     "> 0, contact size <= far size and below the radius");
  CylinderSliceInfo info;
  info.analytic_volume = pi * o.radius * o.radius / 2 * o.thickness;
  with_gmsh("cylinder slice mesh", [&] {
    namespace geo = gmsh::model::geo;
    gmsh::model::add("cylinder_slice");
    const double s = o.upper ? 1 : -1, R = o.radius;
    // Half disc facing the contact: arcs from (-R, sR) through the contact point (0, 0) to
    // (R, sR), closed by the diameter.
    const int c = geo::addPoint(0, s * R, 0), left = geo::addPoint(-R, s * R, 0);
    const int bottom = geo::addPoint(0, 0, 0), right = geo::addPoint(R, s * R, 0);
    const int a1 = geo::addCircleArc(left, c, bottom), a2 = geo::addCircleArc(bottom, c, right);
    const int diameter = geo::addLine(right, left);
    const int loop     = geo::addCurveLoop(o.upper ? std::vector<int>{a1, a2, diameter}
                                                   : std::vector<int>{-diameter, -a2, -a1});
    const int surface  = geo::addPlaneSurface({loop});
    geo::mesh::setRecombine(2, surface);
    gmsh::vectorpair out;
    geo::extrude({{2, surface}}, 0, 0, o.thickness, out, {1}, {}, true);
    geo::synchronize();

    const int distance = gmsh::model::mesh::field::add("Distance");
    gmsh::model::mesh::field::setNumbers(distance, "PointsList", {double(bottom)});
    const int threshold = gmsh::model::mesh::field::add("Threshold");
    gmsh::model::mesh::field::setNumber(threshold, "InField", distance);
    // sizes doubled: the all-hexahedra subdivision halves them
    gmsh::model::mesh::field::setNumber(threshold, "SizeMin", 2 * o.contact_size);
    gmsh::model::mesh::field::setNumber(threshold, "SizeMax", 2 * o.far_size);
    gmsh::model::mesh::field::setNumber(threshold, "DistMin", o.fine_distance);
    gmsh::model::mesh::field::setNumber(threshold, "DistMax", o.fine_distance + o.grading_distance);
    gmsh::model::mesh::field::setAsBackgroundMesh(threshold);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.Algorithm", 6);
    gmsh::option::setNumber("Mesh.RecombinationAlgorithm", 1);
    gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", 2);
    // The subdivision splits the single layer too; the slice stays plane strain with rollers.
    const int              top = out[0].second, volume = out[1].second;
    const std::vector<int> lateral{out[2].second, out[3].second, out[4].second};
    const int              arc_a = o.upper ? lateral[0] : lateral[2], arc_b = lateral[1];
    const int              cut = o.upper ? lateral[2] : lateral[0];
    auto group = [](int dim, const std::vector<int> &tags, int id, const char *name) {
      gmsh::model::setPhysicalName(dim, gmsh::model::addPhysicalGroup(dim, tags, id), name);
    };
    group(2, {arc_a, arc_b}, cylinder_boundary::contact, "contact");
    group(2, {cut}, cylinder_boundary::cut, "cut");
    group(2, {surface}, cylinder_boundary::front, "front");
    group(2, {top}, cylinder_boundary::back, "back");
    group(3, {volume}, 1, "body");
    gmsh::model::mesh::generate(3);
    std::tie(info.hexahedra, info.nodes) = require_hexahedra("cylinder slice mesh");
    write_mesh_atomically(path);
  });
  std::ostringstream json;
  json.precision(12);
  json << "{\n  \"gear\": \"cylinder R = " << o.radius * 1e3
       << " mm\",\n  \"analytic_volume\": " << info.analytic_volume
       << ",\n  \"hexahedra\": " << info.hexahedra << ",\n  \"nodes\": " << info.nodes
       << ",\n  \"physical_surfaces\": {\"contact\": 1, \"cut\": 2, \"front\": 3, \"back\": 4},"
       << "\n  \"physical_volumes\": {\"body\": 1}\n}\n";
  write_text_atomically(path + ".json", json.str());
  return info;
}
} // namespace gearkit
