// Structural compliance of one member on grids of flank points, the table the fast mode reads:
// unit normal loads at every grid point of the flanks that can carry load (a few teeth, one
// side), the normal displacements at every grid point, without the local half-space part
// (finite elements give it at a depth below the surface where they are accurate; the
// Boussinesq solution at that depth is subtracted, the exact half-space part is added per cell
// pair by the contact solver). Interpolated bilinearly in both points' flank parameters, or
// following the load on its own flank (FlankGridSpec::follow_load).
#pragma once

#include "geometry/member_flanks.h"
#include "stiffness/half_space.h"

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace gearkit
{
struct FlankGridSpec
{
  std::vector<int> teeth; ///< member teeth that can carry load
  FlankSide        side   = FlankSide::drive;
  int              n_u    = 7;    ///< grid points over the profile (u)
  int              n_v    = 7;    ///< grid points over the face (v)
  double           margin = 0.02; ///< grid kept this fraction of each range inside the flank
  /// Grid points clustered towards the flank's edges (Chebyshev-Lobatto in both directions:
  /// x_j = (1 - cos(pi j / (n - 1))) / 2 of each range) rather than equally spaced: the
  /// compliance rises steeply within a few tenths of a millimetre of a free face end or tip,
  /// which equal spacing smears over a whole grid interval.
  bool graded = true;
  /// -1: unit loads on every tooth of `teeth`, responses read there. Otherwise the one tooth
  /// that carries the unit loads, responses read on the teeth within `cyclic_reach` of it, its
  /// table read for a load on any tooth of `teeth` turned by the teeth between (the gear's
  /// rotational periodicity: every tooth alike, each seeing its surroundings as the segment's
  /// middle tooth does). `cyclic_reach`: at least the largest offset between teeth in contact
  /// at once.
  int cyclic_tooth = -1, cyclic_reach = 0;
  /// Reading between the unit loads: false, bilinear in both points' flank parameters; true, on
  /// the load's own flank the response read at the same parameter offset from each of the
  /// load's grid points (weighted bilinearly): the compliance's peak at the load (a kink where
  /// the flank curves) stays at the grid points instead of being cut off between them, so both
  /// grid directions converge at second order (bench/README.md).
  bool follow_load = false;
};

/// Unit-load points along the face for a flank of face width b and (normal) module m: the
/// tables are bilinear between points and vary along the face on the scale of the tooth's
/// height, so the middle intervals of the graded grid are kept to about one module:
/// 1 + ceil(2 b / m), at least 7 and at most 25 (bench/README.md: K_m converges like the
/// square of the spacing; 62/62 spur, b = 10 m: 7 points 1.6 % soft, 15 points 0.06 %).
int
face_grid_points(double face_width, double module);

class FlankCompliance
{
public:
  /// A grid point in the member frame; `normal` points out of the material.
  struct Point
  {
    int    tooth = 0;
    double u = 0, v = 0;
    Vec3   position = Vec3::Zero(), normal = Vec3::Zero();
    Vec3   face_direction = Vec3::UnitZ(); ///< along the face width (MemberFlanks::face_direction)
  };

  FlankCompliance(const MemberFlanks &flanks, const FlankGridSpec &spec);

  /// Points, tooth by tooth, u-major then v: where the responses are read.
  const std::vector<Point> &
  points() const
  {
    return grid;
  }
  /// The points that carry unit loads (indices into points()): all, or the cyclic tooth's.
  const std::vector<std::size_t> &
  load_points() const
  {
    return loaded;
  }
  /// S(j, k): approach of point j into the material per unit normal force on load point k
  /// (points()[load_points()[k]]) [m/N].
  void
  set(const Eigen::MatrixXd &compliance);
  /// True if the tooth can carry load (FlankGridSpec::teeth).
  bool
  covers(int tooth) const;
  /// The grid as asked for (teeth that can carry load, cyclic tooth and reach), and the teeth
  /// with a grid of points.
  const FlankGridSpec &
  grid_spec() const
  {
    return spec;
  }
  const std::vector<int> &
  grid_teeth() const
  {
    return with_grid;
  }
  const Eigen::MatrixXd &
  matrix() const
  {
    return S;
  }
  /// Interpolated compliance from a load at (tooth_i, u_i, v_i) to (tooth_j, u_j, v_j); throws
  /// InputError for a tooth outside the grid (with a cyclic tooth: an offset tooth_j - tooth_i
  /// beyond its reach).
  double
  operator()(int tooth_i, double u_i, double v_i, int tooth_j, double u_j, double v_j) const;
  /// A point on a member tooth's flank, by its flank parameters.
  struct Location
  {
    int    tooth = 0;
    double u = 0, v = 0;
  };
  /// M(j, i) = operator()(at[i], at[j]) for every pair of the points, the same numbers, with
  /// each point's interpolation weights found once (per tooth it is read on) instead of per
  /// pair: what the loaded contact needs at a position.
  Eigen::MatrixXd
  matrix(const std::vector<Location> &at) const;

private:
  struct Weights
  {
    int    index[4];
    double weight[4];
    double u[4], v[4]; ///< the corner nodes' flank parameters
  };
  Weights
  weights(int tooth, double u, double v) const;
  /// Teeth from `from` to `to`, signed, the nearer way round the gear.
  int
  tooth_offset(int from, int to) const;
  /// The tooth `offset` teeth from the cyclic tooth.
  int
  cyclic_turned(int offset) const;
  /// The table between the load's corners (wi) and the response's (wj), term by term.
  double
                           interpolate(const Weights &wi, const Weights &wj) const;
  FlankGridSpec            spec;
  std::vector<int>         with_grid; ///< teeth with grid points
  int                      member_teeth = 0;
  std::vector<Point>       grid;
  std::vector<std::size_t> loaded;           ///< load points (indices into grid)
  int                      load_base = 0;    ///< with a cyclic tooth: its first grid index
  std::vector<double>      u_nodes, v_nodes; ///< grid points as fractions of each range, in [0, 1]
  std::vector<std::pair<double, double>> u_range, v_range; ///< per tooth entry
  Eigen::MatrixXd                        S;
};

/// A unit normal load on a grid point of a tooth: the force points into the material.
struct FlankLoad
{
  int  tooth = 0;
  Vec3 point = Vec3::Zero(), direction = Vec3::Zero();
};

/// The member's elastic response: D(j, i), the displacement of response point j along its
/// direction per unit load i (finite elements, e.g. ElasticSegment on the tooth segment).
using ElasticResponse = std::function<Eigen::MatrixXd(
    const std::vector<FlankLoad> &loads, const std::vector<std::pair<Vec3, Vec3>> &responses)>;

/// Where a grid point's response is read, per unit depth: along the part of the inward normal
/// across the face direction (the transverse part on cylindrical gears: the normal itself on spur
/// flanks; on helical and spiral bevel flanks this keeps responses inside the face width at the
/// face ends), scaled so that `depth` times it lies `depth` below the point's tangent plane.
Vec3
response_offset(const FlankCompliance::Point &point);

/// Fills the table from unit normal loads at its load points, read depths[i] below every point
/// i (position + depths[i] response_offset); the half-space displacement there of the load as
/// applied (a unit force spread uniformly over a disk of `patch_radius`; 0: a point force) is
/// subtracted for points of the same tooth.
void
fill_structural_compliance(FlankCompliance &table, const ElasticResponse &solve,
                           const std::vector<double> &depths, const Material &material,
                           double patch_radius = 0);

/// Normal displacement of a half-space at depth z and horizontal distance r from the centre of
/// a unit normal force spread uniformly over a disk of the given radius (0: Boussinesq's point
/// force) [m/N].
double
disk_load_displacement(double r, double z, double radius, const Material &material);
} // namespace gearkit
