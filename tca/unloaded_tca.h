// Unloaded tooth contact analysis of a gear pair from its flank surfaces.
//
// For a pinion rotation phi, every pinion flank point X has a "touch angle": the gear rotation
// psi at which the mating gear flank passes through X (solved by Newton from r_g(u2, v2) =
// Rz(psi) Q(X)). The gear cannot turn less than the largest touch angle over all points and all
// tooth pairs in mesh, so that maximum is the gear's position; where it is attained, the surfaces
// touch (an interior maximum is the classical coincidence of positions and normals, a maximum on
// the flank boundary an edge contact). The other pairs stand apart by their angular gap.
// Transmission error (the seed's convention, pinion radians): e = phi - (z2/z1) psi; it is zero for
// perfect involutes on the zero-backlash centre distance.
#pragma once

#include "geometry/member_flanks.h"
#include "tca/assembly.h"

#include <memory>
#include <vector>

namespace gearkit
{
struct TcaOptions
{
  FlankSide side               = FlankSide::drive; ///< working flanks (drive: pinion drives)
  int       positions_per_mesh = 50;               ///< pinion positions per mesh cycle
  int       mesh_cycles        = 1;                ///< mesh cycles to analyse
  double    start_angle        = 0;                ///< first pinion angle [rad]
  int       profile_samples    = 17; ///< initial search grid over each pinion flank ...
  int       face_samples       = 9;  ///< ... refined by successive zooms around the maximum
  /// Pairs closer than this [m] count as touching; 0: 3e-7 of the pinion's transverse module
  /// (about 1 nm at 3 mm: relative, so that a pair and its scaled copy count alike).
  double contact_tolerance = 0;
  /// A more thorough search for edge contacts (the tooth pair curves, tca/tooth_pairs.h): the
  /// pattern search also starts from the grid's other local maxima (the best four) and from the
  /// neighbouring position's contact (pair(k, phi, near)), not only the best sample; and a
  /// pinion point whose mate lies beyond an end of the gear's face is moved along the pinion's
  /// face to where the gear's face end meets it, so that the search follows a face-end edge
  /// contact (a modified helical pinion's face edge stands off its face plane by the
  /// modification times sin(beta_b), just beyond the gear's face). Without it, a pair entering
  /// or leaving mesh by an edge (a tip, a chip, a face end) can be found on a lower local
  /// maximum, or ~0.1 um off at a face end. Off by default: slower, and a face-end contact's
  /// normal is found only to ~1e-7, so that where it ties with another pair's conjugate contact
  /// within rounding the leading pair may change.
  bool robust_search = false;
  /// The most flank samples (touch-angle solves) one tooth pair's contact search at one
  /// position may take; beyond, the search throws InputError naming the pair and the position
  /// rather than running on. A search takes a few hundred (a grid of profile x face samples,
  /// then about 8 per step of the pattern search), a few thousand where it follows a ridge (near
  /// line contact, see UnloadedTca::pair).
  int most_samples = 100000;
};

/// One tooth pair at one position.
struct PairContact
{
  int    pinion_tooth = 0, gear_tooth = 0;
  bool   found       = false; ///< the flanks can meet at all in this position
  double touch_angle = 0;     ///< gear rotation at which this pair touches [rad]
  double separation  = 0;     ///< normal gap at the gear's actual rotation [m] (0: touching)
  bool   edge        = false; ///< the closest point lies on a flank boundary
  double u1 = 0, v1 = 0, u2 = 0, v2 = 0; ///< flank parameters of the (closest) contact point
  Vec3   position      = Vec3::Zero();   ///< global contact point [m]
  Vec3   normal_pinion = Vec3::Zero();   ///< n_p, outward normal of the pinion flank (global)
  Vec3   normal_gear   = Vec3::Zero();   ///< n_g, outward normal of the gear flank (global)
  Vec3   lambda_pinion = Vec3::Zero();   ///< lambda_p = r_p x n_p about the pinion centre [m]
  Vec3   lambda_gear   = Vec3::Zero();   ///< lambda_g = r_g x n_g about the gear centre [m]
  /// Principal relative curvatures of the pair at the contact point [1/m]: the gap between the
  /// flanks grows as (k_min x^2 + k_max y^2) / 2 in the common tangent plane (k_min ~ 0: line
  /// contact), and the direction of k_min (the contact ellipse's major axis), global.
  double curvature_min = 0, curvature_max = 0;
  Vec3   major_direction = Vec3::Zero();
};

/// Semi-axes (major, minor) [m] of the instantaneous contact ellipse at elastic approach
/// `approach` [m]: sqrt(2 approach / k); a vanishing curvature (line contact) gives 1 m.
std::pair<double, double>
contact_ellipse(const PairContact &contact, double approach);

struct TcaPosition
{
  double                   pinion_angle       = 0;  ///< phi [rad]
  double                   gear_angle         = 0;  ///< psi [rad]
  double                   transmission_error = 0;  ///< e_0 = phi - (z2/z1) psi [rad, pinion]
  int                      leading            = -1; ///< index into pairs of the touching pair
  int                      touching           = 0;  ///< pairs within the contact tolerance
  std::vector<PairContact> pairs;
};

struct TcaResult
{
  std::vector<TcaPosition> positions;
  double                   mesh_angle = 0; ///< pinion rotation of one mesh cycle, 2 pi / z1
  /// Mean number of touching pairs: the contact ratio for conjugate flanks.
  double mean_pairs_in_contact = 0;
  /// Positions where the leading pair changes (index of the first position of the new pair).
  std::vector<int> transfers;
};

/// Fills c.position, the normals and the moment arms from the flank parameters c.u1, c.v1,
/// c.u2, c.v2 (contact point taken on the pinion flank) at pinion angle phi and gear angle psi.
void
set_contact_geometry(PairContact &c, const Assembly &assembly, const Flank &pinion_flank,
                     const Flank &gear_flank, double phi, double psi);

/// Fills c.curvature_min, c.curvature_max and c.major_direction from both flanks' second
/// fundamental forms (normal derivatives by central differences) at c's parameters.
void
set_relative_curvature(PairContact &c, const Assembly &assembly, const Flank &pinion_flank,
                       const Flank &gear_flank, double phi, double psi);

/// Fills result.mean_pairs_in_contact and result.transfers from result.positions.
void
summarise(TcaResult &result);

class UnloadedTca
{
public:
  /// Any flank surfaces: theoretical, or interpolated from measured points (the fast
  /// discrete-point mode).
  UnloadedTca(std::shared_ptr<const MemberFlanks> pinion, std::shared_ptr<const MemberFlanks> gear,
              double centre_distance, const Misalignment &misalignment = {},
              const TcaOptions &options = {});
  /// Any flank surfaces in any assembly (e.g. Assembly::bevel for a spiral bevel pair).
  UnloadedTca(std::shared_ptr<const MemberFlanks> pinion, std::shared_ptr<const MemberFlanks> gear,
              const Assembly &assembly, const TcaOptions &options = {});
  /// Involute members; checks that they can mesh (same normal module, pressure and helix angle,
  /// opposite hands).
  UnloadedTca(std::shared_ptr<const InvoluteGear> pinion, std::shared_ptr<const InvoluteGear> gear,
              double centre_distance, const Misalignment &misalignment = {},
              const TcaOptions &options = {});

  /// The contact at one pinion angle. Throws InputError if no tooth pair can meet (flanks that
  /// do not mesh at this centre distance, face widths that do not overlap).
  TcaPosition
  at(double pinion_angle) const;

  /// Tooth pairing k alone at pinion angle phi, on options.side: pinion tooth mod(-k, z1) (the
  /// k-th tooth to pass the line of centres) with gear tooth mod(k - 1, z2) on the drive flanks,
  /// mod(k, z2) on the coast flanks (base/tooth_pairs.h). Not found when the flanks cannot meet
  /// in this position (or a flank is missing); separation is left 0 (it needs the other pairs).
  /// `near`: this pairing's contact at a nearby pinion angle, if known; the search then also
  /// looks around its flank point (it follows an edge contact whose touching region is a sliver
  /// the search grid misses, as at a helical gear's tip corner entering mesh).
  /// The search: a grid over the pinion flank, then a pattern search (eight neighbours, the step
  /// halved where none is better) to the touch angle's maximum, then Newton on its
  /// stationarity. Near line contact the maximum lies on a ridge along the contact line, whose
  /// cross curvature exceeds its length curvature by orders of magnitude (a 5 m head cutter
  /// mismatched by 2 mm: about 1e4): a ridge oblique to the flank parameters that the pattern
  /// search would crawl along in steps of its current size, about that ratio of steps. After 64
  /// moves at one step size the search therefore takes a Newton step on the touch angle's
  /// quadratic model (backtracked until it gains), which goes along the ridge at once; once one
  /// has gained, after every 8 moves. (The shipped cases' searches move at most 48 times at one
  /// step size: their results are those of the plain pattern search.)
  PairContact
  pair(int k, double pinion_angle, const PairContact *near = nullptr) const;
  /// Pairing k's contact searched from a pinion flank point (u1, v1) alone, where the contact
  /// is known to lie nearby (a variant of a pair, from the first touch of its contact cells):
  /// the pattern search starts there with steps (du, dv) (about a cell) instead of covering the
  /// flank, halves them once, and is pinned by Newton as pair's (where Newton does not
  /// converge, the pattern search goes on to the end). Returns a contact not found where the gear
  /// flank reaches no point of the search (then search the whole flank with pair).
  PairContact
  pair_from(int k, double pinion_angle, double u1, double v1, double du, double dv) const;

  /// options.positions_per_mesh x options.mesh_cycles positions from options.start_angle.
  TcaResult
  run() const;

  /// Gear rotation at which gear tooth `gear_tooth`'s flank passes through the global point X,
  /// near `expected`; false if Newton fails or the point lies off the gear flank.
  bool
  touch_angle(int gear_tooth, const Vec3 &X, double expected, double &psi, double &u2,
              double &v2) const;

  const MemberFlanks &
  pinion_flanks() const
  {
    return *pinion;
  }
  const MemberFlanks &
  gear_flanks() const
  {
    return *gear;
  }
  const Assembly &
  assembly_data() const
  {
    return assembly;
  }
  const TcaOptions &
  options_data() const
  {
    return options;
  }

private:
  /// Pairing k's teeth at pinion angle phi, their contact where find(ContactSearch &) returns
  /// the maximum (pair's and pair_from's searches; defined and used in unloaded_tca.cc).
  template <class Find>
  PairContact
  pair_contact(int k, double phi, Find &&find) const;
  /// pair_contact's search in its phases (unloaded_tca.cc).
  class ContactSearch;
  /// touch_angle's solve: none (no solution near `expected`, or off the flank), beyond_face
  /// (on the gear flank's surface continued beyond an end of its face: v2 outside the domain),
  /// on_flank.
  enum class Touch
  {
    none,
    beyond_face,
    on_flank
  };
  Touch
  solve_touch(int gear_tooth, const Vec3 &X, double expected, double &psi, double &u2,
              double &v2) const;

  std::shared_ptr<const MemberFlanks> pinion, gear;
  Assembly                            assembly;
  TcaOptions                          options;
  double                              ratio; ///< z1 / z2
};
} // namespace gearkit
