// Face-milled spiral bevel flanks generated on a cradle-type machine: a head cutter (blades of
// revolution about the cutter axis) carried by the cradle, the work blank rolling with the cradle
// at the ratio of roll, optionally with modified roll. In the spirit of Litvin & Fuentes, Gear
// Geometry and Applied Theory, ch. 20-21, with the frames below (their sign conventions differ
// between publications; these are ours, fixed and tested).
//
// Machine frame S_m: z_m is the cradle axis pointing at the work; the plane z_m = 0 is the pitch
// plane of the plane generating gear (the cradle); at cradle angle 0 the mean generating point
// lies on the +x_m axis at the mean cone distance. The head cutter's axis is parallel to z_m
// through C = (S_r cos q, S_r sin q, 0): radial setting S_r, cradle angle q, unless tilted (tilt
// i, swivel j: the axis leans by i toward the cradle-plane direction q + j). A blade is a line in
// a plane through the cutter axis, given by its radius at the pitch plane and its angle to the
// axis; s runs along it from the pitch plane toward the tip (+z_m, into the work; the tips, at
// the work's dedendum, cut the root). The cradle turns by psi_c about z_m.
//
// Blank (work) frame S_1: apex at O_1, axis z_1 = a = (cos gamma_m, 0, sin gamma_m) in S_m
// (gamma_m: machine root angle), x_1 = (sin gamma_m, 0, -cos gamma_m), y_1 = y_m. Machine
// settings move the apex: O_1 = E_m y_m - Delta X_B z_m - Delta X_D a (blank offset, sliding base,
// machine centre to back). The blank turns by psi_1 about a, psi_1 = R_a (psi_c - C dpsi^2 -
// D dpsi^3), dpsi = psi_c - psi_0 (ratio of roll R_a; modified roll 2C and 6D are the Gleason
// coefficients, expanded about the cradle angle psi_0, 0 unless set). A point
// fixed in the blank has coordinates Rz(-psi_1) r in the blank frame: those are the flank
// coordinates (member frame: apex at the origin, axis +z, teeth toward +z).
//
// The generated flank is the envelope of the blade surfaces: the points where the blade normal is
// perpendicular to the relative velocity of blade and blank (equation of meshing n . v = 0). It
// is parametrised over the blank's axial plane: u = h, the height above the pitch cone along its
// normal, v = A - A_m, the distance along the pitch element from the mean point; a flank point is
// the point of the generated surface whose axial-plane projection (axial position, radius) is
// that of (A, h) (the rotational projection CMMs use). The domain is the blank's working region:
// h from the root cone to the face cone, A from the toe to the heel.
#pragma once

#include "geometry/types.h"

#include <Eigen/Geometry>

#include <cmath>
#include <memory>
#include <vector>

namespace gearkit
{
/// One blade of the head cutter: a straight (or parabolic) line revolved about the cutter axis.
struct Blade
{
  /// Radius of the blade at the pitch plane z_m = 0 [m].
  double pitch_radius = 0;
  /// Angle between the blade and the cutter axis [rad] (the pressure angle it generates).
  double angle = 20 * pi / 180;
  /// +1: outside blade (its radius grows away from the tip; cuts the concave flank); -1: inside
  /// blade (cuts the convex flank).
  int slope = 1;
  /// Parabolic blade: the blade is displaced toward the work by curvature (s - s0)^2 along its
  /// normal (removing work material toward tip and root), s the distance along the blade from the
  /// pitch plane toward the tip [1/m]; 0: straight.
  double curvature     = 0;
  double parabola_apex = 0; ///< s0 [m]
  /// Edge radius of the blade tip [m]: the rounded tip cuts the root fillet; the working flank
  /// ends where the blade's straight (or parabolic) part meets the rounding.
  double edge_radius = 0;
};

/// Settings of the generating machine for one flank side.
struct MachineSettings
{
  double radial_setting = 0; ///< S_r [m]
  double cradle_angle   = 0; ///< q [rad]; its sign sets the hand
  double root_angle     = 0; ///< gamma_m, machine root angle [rad]
  /// Cutter tilt i: the cutter axis leans by i from the cradle axis, toward the direction at
  /// angle q + j (swivel j) in the cradle plane [rad]; 0: axis parallel to the cradle axis.
  double tilt                   = 0;
  double swivel                 = 0;
  double sliding_base           = 0; ///< Delta X_B [m]
  double machine_centre_to_back = 0; ///< Delta X_D [m]
  double blank_offset           = 0; ///< E_m [m]
  double ratio_of_roll          = 1; ///< R_a = d psi_1 / d psi_c at psi_c = psi_0
  double modified_roll_2c       = 0; ///< 2C: psi_1 = R_a (psi_c - C dpsi^2 - D dpsi^3)
  double modified_roll_6d       = 0; ///< 6D
  /// psi_0 [rad]: the cradle angle the modified roll is expanded about, dpsi = psi_c - psi_0;
  /// there the blank rolls at the plain ratio R_a (the point generated there is unmodified).
  double modified_roll_centre = 0;
  bool   generated            = true; ///< false: formate (no roll; the flank is the blade cone)
};

/// Axes of the head cutter's frame in the cradle frame S_m (columns): z along the cutter axis
/// (leaning by the tilt toward the swivel direction), x the cradle's x axis made perpendicular to
/// it; the identity without tilt. A blade point (s, theta) lies at C + R (rho(s) cos theta,
/// rho(s) sin theta, z(s)), C the cutter centre in the cradle plane.
Eigen::Matrix3d
cutter_frame(const MachineSettings &machine);

/// The blank of one member, in its own frame (apex at the origin, axis +z). Uniform depth: root
/// and face cones parallel to the pitch cone.
struct BevelBlank
{
  int    teeth              = 0;
  double pitch_angle        = 0; ///< gamma [rad]
  double mean_cone_distance = 0; ///< A_m [m]
  double face_width         = 0; ///< F [m]: toe at A_m - F/2, heel at A_m + F/2
  double addendum           = 0; ///< h_a at the mean point [m]
  double dedendum           = 0; ///< h_f [m]

  /// Axial position and radius of the point at cone distance A and height h above the pitch cone.
  Vec2
  axial_plane(double A, double h) const
  {
    return {A * std::cos(pitch_angle) - h * std::sin(pitch_angle),
            A * std::sin(pitch_angle) + h * std::cos(pitch_angle)};
  }
};

/// A flank generated by one blade on one machine, in the blank's frame turned by `rotation`
/// about its axis. u = h in [h_form, h_a], v = A - A_m in [-F/2, F/2] (both metres); h_form is
/// where the working flank ends toward the root (blade tip reached, or undercut), the highest
/// along the face, so that the domain is a rectangle of generated flank.
class GeneratedFlank : public Flank
{
public:
  GeneratedFlank(const BevelBlank &blank, const Blade &blade, const MachineSettings &machine,
                 double rotation = 0);

  FlankPoint
  evaluate(double u, double v) const override;
  FlankDomain
  domain() const override;

  /// The generating motion that produces the flank point at (u, v).
  struct Generation
  {
    double s = 0, theta = 0,
           psi_c            = 0; ///< along the blade from the pitch plane, cutter angle, cradle
    double meshing_residual = 0; ///< n . v at the solution [m per rad of cradle]
    int    iterations       = 0;
  };
  Generation
  generation(double u, double v) const;

  /// The blade point (s, theta) carried to cradle angle psi_c, in the flank's frame (for tests:
  /// the family of blade surfaces the flank envelops), with the equation-of-meshing value there.
  FlankPoint
  blade_point(double s, double theta, double psi_c, double *meshing = nullptr) const;

  /// The surface the blade generates below the working flank, down to the root: the rest of the
  /// straight blade and the tip rounding (edge radius). t = 0 is the flank's lower edge (the
  /// point (u_min, v)), t = 1 the end of the rounding, on the root cone; v = A - A_m as on the
  /// flank. Needs an edge radius > 0.
  struct FilletPoint
  {
    Vec3   position, normal;     ///< flank frame; normal out of the material
    double height           = 0; ///< h of the point's axial-plane projection
    double s                = 0; ///< blade parameter (arc length beyond the rounding's start)
    double meshing_residual = 0;
  };
  FilletPoint
  fillet_point(double t, double v) const;

  /// True if the envelope's edge of regression, not the blade tip, ends the working flank
  /// toward the root somewhere along the face (the blade undercuts the tooth).
  bool
  undercut_found() const
  {
    return undercut;
  }
  const BevelBlank &
  blank_data() const
  {
    return blank;
  }
  /// Turned copy (another tooth, or the tooth-0 placement).
  GeneratedFlank
  rotated(double angle) const;

private:
  struct Guess
  {
    double          u, v;
    Eigen::Vector3d q;
  };
  /// Newton on (meshing, axial position, radius) for (s, theta, psi_c) from q; false if it fails.
  bool
  newton(double u, double v, Eigen::Vector3d &q, int &iterations) const;
  /// newton, throwing InputError when it fails.
  Eigen::Vector3d
  solve(double u, double v, Eigen::Vector3d q, int &iterations) const;
  /// The solution q at (u, v) followed from a known one at (u0, v0), halving the path as
  /// needed; false if it cannot be reached.
  bool
  follow(double u0, double v0, const Eigen::Vector3d &q0, double u, double v, Eigen::Vector3d &q,
         int depth = 0) const;

  BevelBlank         blank;
  Blade              blade;
  MachineSettings    machine;
  double             rotation;
  Eigen::Matrix3d    machine_to_blank; ///< rows x_1, y_1, z_1 in S_m
  Vec3               apex;             ///< O_1 in S_m
  double             form_height = 0;  ///< lowest h of the working flank (domain u_min)
  double             s_round     = 0;  ///< blade parameter where the tip rounding starts
  bool               undercut    = false;
  std::vector<Guess> guesses; ///< solved grid for first guesses
  int                guess_nu = 0, guess_nv = 0;
};
} // namespace gearkit
