#include "geometry/involute_gear.h"

#include <Eigen/Geometry>

#include <cmath>
#include <numeric>
#include <sstream>

namespace gearkit
{
namespace
{
double
inv(double alpha)
{
  return std::tan(alpha) - alpha;
}

Vec2
e_r(double a)
{
  return {std::cos(a), std::sin(a)};
}

Vec2
e_theta(double a)
{
  return {-std::sin(a), std::cos(a)};
}

Vec2
rotate(const Vec2 &p, double a)
{
  const double c = std::cos(a), s = std::sin(a);
  return {c * p.x() - s * p.y(), s * p.x() + c * p.y()};
}

template <typename T>
std::string
str(const T &value)
{
  std::ostringstream s;
  s << value;
  return s.str();
}

// Throws InputError "<gear>: <parameter> = <value> <unit> is not allowed; <allowed>".
void
require(bool ok, const InvoluteGearData &d, const std::string &parameter, double value,
        const std::string &unit, const std::string &allowed)
{
  if (!ok)
    throw InputError(d.name + ": " + parameter + " = " + str(value) + (unit.empty() ? "" : " ") +
                     unit + " is not allowed; " + allowed);
}

// The data's own ranges, checked first: every derived quantity divides by or takes roots of
// them.
void
check_data(const InvoluteGearData &d)
{
  require(d.teeth >= 3, d, "number of teeth", d.teeth, "", "it must be >= 3");
  require(d.normal_module > 0, d, "normal module", d.normal_module * 1e3, "mm", "it must be > 0");
  require(d.normal_pressure_angle > 0 && d.normal_pressure_angle < pi / 4, d,
          "normal pressure angle", d.normal_pressure_angle * 180 / pi, "deg",
          "it must lie in (0, 45) deg");
  require(d.helix_angle >= 0 && d.helix_angle < 60 * pi / 180, d, "helix angle",
          d.helix_angle * 180 / pi, "deg", "it must lie in [0, 60) deg (the hand gives the sense)");
  require(d.face_width > 0, d, "face width", d.face_width * 1e3, "mm", "it must be > 0");
  require(d.addendum_factor > 0, d, "addendum factor", d.addendum_factor, "", "it must be > 0");
  require(d.dedendum_factor > d.root_radius_factor * (1 - std::sin(d.normal_pressure_angle)), d,
          "dedendum factor", d.dedendum_factor, "",
          "it must exceed root radius factor * (1 - sin alpha_n) so the rack flank has a straight "
          "part");
  require(d.root_radius_factor >= 0, d, "root radius factor", d.root_radius_factor, "",
          "it must be >= 0");
  require(d.density > 0, d, "density", d.density, "kg/m^3", "it must be > 0");
  require(d.bore_diameter >= 0, d, "bore diameter", d.bore_diameter * 1e3, "mm", "it must be >= 0");
}

// Modifications and deviations are micrometre-sized corrections of the involute: one that
// removes more than half the tooth's thickness at the tip removes the tooth. Refused before
// anything is computed on such a tooth (their lengths: check_modifications). `limit`: half the
// normal tooth thickness at the tip.
void
check_correction_sizes(const InvoluteGearData &d, double limit)
{
  const auto        fits = [&](double value) { return std::abs(value) <= limit; };
  const std::string within =
      "its size must be at most half the normal tooth thickness at the tip, s_an / 2 = " +
      str(limit * 1e6) + " um";
  for (const auto &[side, m] : {std::pair{"drive flank ", &d.drive_modifications},
                                {"coast flank ", &d.coast_modifications}})
    {
      const std::string s = side;
      for (const auto &[name, value] : {std::pair{"tip relief", m->tip_relief},
                                        {"root relief", m->root_relief},
                                        {"lead crowning", m->lead_crowning},
                                        {"end relief", m->end_relief},
                                        {"profile crowning", m->profile_crowning},
                                        {"profile slope deviation", m->profile_slope},
                                        {"helix slope deviation", m->helix_slope},
                                        {"waviness amplitude", m->waviness_amplitude}})
        require(fits(value), d, s + name, value * 1e6, "um", within);
    }
  require(d.runout.eccentricity <= limit, d, "runout", d.runout.eccentricity * 1e6, "um", within);
  for (const EccentricTooth &e : d.eccentric_teeth)
    require(fits(e.offset), d, "eccentric tooth offset", e.offset * 1e6, "um", within);
}

// The eccentric and chipped teeth's indices, and the chips' extent between the root and tip
// circles.
void
check_damaged_teeth(const InvoluteGearData &d, double root_radius, double tip_radius)
{
  for (const EccentricTooth &e : d.eccentric_teeth)
    require(e.tooth >= 0 && e.tooth < d.teeth, d, "eccentric tooth index", e.tooth, "",
            "it must lie in [0, " + str(d.teeth - 1) + "]");
  for (const ChippedTooth &c : d.chipped_teeth)
    {
      require(c.tooth >= 0 && c.tooth < d.teeth, d, "chipped tooth index", c.tooth, "",
              "it must lie in [0, " + str(d.teeth - 1) + "]");
      require(c.radius >= root_radius && c.radius < tip_radius, d, "chip diameter",
              2 * c.radius * 1e3, "mm",
              "it must lie in [d_f, d_a) = [" + str(2 * root_radius * 1e3) + ", " +
                  str(2 * tip_radius * 1e3) + ") mm");
      require(c.face_fraction > 0 && c.face_fraction <= 1, d, "chip face fraction", c.face_fraction,
              "", "it must lie in (0, 1]");
    }
}
} // namespace

std::shared_ptr<const InvoluteGear>
InvoluteGear::create(const InvoluteGearData &data)
{
  return std::shared_ptr<const InvoluteGear>(new InvoluteGear(data));
}

InvoluteGear::InvoluteGear(const InvoluteGearData &data)
    : d(data)
{
  // In this order: each phase uses what the ones before derived, and refuses what contradicts
  // it before anything is computed on it.
  check_data(d);
  set_nominal_geometry();
  set_form_circle();
  check_tip_thickness();
  set_tooth_angles();
  check_damaged_teeth(d, root_radius, tip_radius);
  set_modification_frame();
}

// The nominal dimensions (ISO 21771 symbols) from the data; a bore or a tip circle they
// contradict refused.
void
InvoluteGear::set_nominal_geometry()
{
  const double mn = d.normal_module, an = d.normal_pressure_angle, b = d.helix_angle;
  transverse_module         = mn / std::cos(b);
  transverse_pressure_angle = std::atan(std::tan(an) / std::cos(b));
  reference_radius          = d.teeth * transverse_module / 2;
  base_radius               = reference_radius * std::cos(transverse_pressure_angle);
  tip_radius                = reference_radius + (d.addendum_factor + d.profile_shift) * mn;
  root_radius               = reference_radius - (d.dedendum_factor - d.profile_shift) * mn;
  base_helix_angle          = std::atan(std::tan(b) * std::cos(transverse_pressure_angle));
  lead                      = b > 0 ? 2 * pi * reference_radius / std::tan(b) : 0;
  transverse_base_pitch     = pi * transverse_module * std::cos(transverse_pressure_angle);
  tooth_thickness_reference = transverse_module * (pi / 2 + 2 * d.profile_shift * std::tan(an));
  half_angle_base =
      tooth_thickness_reference / (2 * reference_radius) + inv(transverse_pressure_angle);
  helix_sign = d.hand == Hand::right ? 1.0 : -1.0;

  require(d.bore_diameter / 2 < root_radius, d, "bore diameter", d.bore_diameter * 1e3, "mm",
          "it must be smaller than the root diameter " + str(2 * root_radius * 1e3) + " mm");
  require(tip_radius > base_radius, d, "addendum factor", d.addendum_factor, "",
          "the tip circle must lie outside the base circle (d_b = " + str(2 * base_radius * 1e3) +
              " mm)");
}

// Where the involute starts: the form point generated by the cutter's straight flank, or with
// undercut the root trochoid's crossing; the rack heights that generate the form and tip points.
void
InvoluteGear::set_form_circle()
{
  const double mn = d.normal_module, an = d.normal_pressure_angle;
  // Rack heights (below the datum line, towards the gear centre) of the straight cutter flank:
  // its lower end, where the cutter tip rounding starts, generates the form point.
  const double rho = d.root_radius_factor * mn;
  rack_h_form      = d.dedendum_factor * mn - rho * (1 - std::sin(an));
  const double xm  = d.profile_shift * mn;
  // A rack point at depth h - xm below the rolling line touches on the line of action at
  // (h - xm) / sin(alpha_t) from the pitch point towards the base tangent point T, which lies
  // r sin(alpha_t) from the pitch point. Beyond T the straight flank undercuts the involute.
  const double st        = std::sin(transverse_pressure_angle);
  const double roll_form = reference_radius * st - (rack_h_form - xm) / st;
  gear_checks.undercut   = roll_form < 0;
  roll_angle_form        = std::max(roll_form, 0.0) / base_radius;
  form_radius            = base_radius * std::sqrt(1 + roll_angle_form * roll_angle_form);
  roll_angle_tip         = roll_angle(tip_radius);
  rack_h_tip             = xm - (base_radius * roll_angle_tip - reference_radius * st) * st;
  if (gear_checks.undercut)
    {
      // The cutter tip rounding cuts into the involute: the tooth is bounded by the trochoid
      // below the point where it crosses the involute and by the involute above it. Find the
      // crossing (first sign change of the polar-angle difference, refined by bisection) and end
      // the fillet there.
      auto inside = [&](double t) { // trochoid inside the involute at this radius?
        fillet_t_end   = t;
        const Vec2   q = fillet_point(1.0);
        const double r = q.norm();
        return r <= base_radius ||
               std::atan2(q.y(), q.x()) < half_angle_base - inv(std::acos(base_radius / r));
      };
      double lo = 0, hi = 1;
      for (int i = 1; i <= 1000; ++i)
        if (!inside(i / 1000.0))
          {
            lo = (i - 1) / 1000.0;
            hi = i / 1000.0;
            break;
          }
      for (int i = 0; i < 60; ++i)
        (inside(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
      fillet_t_end    = hi;
      form_radius     = fillet_point(1.0).norm();
      roll_angle_form = roll_angle(form_radius);
      gear_checks.warnings.push_back(d.name +
                                     ": the rack cutter undercuts the involute (profile shift " +
                                     str(d.profile_shift) + " is below the limit " +
                                     str((rack_h_form - reference_radius * st * st) / mn) +
                                     "); the involute starts at d = " + str(2 * form_radius * 1e3) +
                                     " mm where the root trochoid crosses it");
    }
  require(form_radius < tip_radius, d, "addendum factor", d.addendum_factor, "",
          "the tip circle (d_a = " + str(2 * tip_radius * 1e3) +
              " mm) must lie outside the form circle (d_Ff = " + str(2 * form_radius * 1e3) +
              " mm)");
}

// The tooth's normal thickness at the tip (refused where the tooth is pointed below the tip
// circle, a warning where it nearly is), which bounds the modifications' and deviations' sizes.
void
InvoluteGear::check_tip_thickness()
{
  const double mn = d.normal_module, b = d.helix_angle;
  const double s_at = tooth_thickness(tip_radius);
  require(s_at > 0, d, "addendum factor", d.addendum_factor, "",
          "the tooth is pointed below the tip circle (tip thickness " + str(s_at * 1e3) +
              " mm); reduce the addendum or the profile shift " + str(d.profile_shift));
  gear_checks.tip_thickness_normal =
      s_at * std::cos(std::atan(std::tan(b) * tip_radius / reference_radius));
  if (gear_checks.tip_thickness_normal < 0.2 * mn)
    gear_checks.warnings.push_back(
        d.name + ": tip thickness s_an = " + str(gear_checks.tip_thickness_normal * 1e3) +
        " mm is below 0.2 m_n (nearly pointed tooth)");
  check_correction_sizes(d, gear_checks.tip_thickness_normal / 2);
}

// Tooth positions with cumulative single pitch deviations (closure: they sum to zero).
void
InvoluteGear::set_tooth_angles()
{
  tooth_angle.resize(d.teeth);
  if (!d.single_pitch_deviations.empty())
    {
      require(static_cast<int>(d.single_pitch_deviations.size()) == d.teeth, d,
              "number of single pitch deviations", d.single_pitch_deviations.size(), "",
              "give one per tooth (" + str(d.teeth) + ")");
      const double sum =
          std::accumulate(d.single_pitch_deviations.begin(), d.single_pitch_deviations.end(), 0.0);
      require(std::abs(sum) < 1e-8, d, "sum of single pitch deviations", sum * 1e6, "um",
              "they must add up to zero within 0.01 um (the pitches close the circle)");
    }
  double cumulative = 0;
  for (int k = 0; k < d.teeth; ++k)
    {
      if (!d.single_pitch_deviations.empty() && k > 0)
        cumulative += d.single_pitch_deviations[k];
      tooth_angle[k] = 2 * pi * k / d.teeth + cumulative / reference_radius;
    }
}

// The extent the modifications refer to (from the start of the active profile where it is
// given), both sides' modifications checked against it.
void
InvoluteGear::set_modification_frame()
{
  require(d.active_profile_start_radius == 0 ||
              (d.active_profile_start_radius >= form_radius * (1 - 1e-12) &&
               d.active_profile_start_radius < tip_radius),
          d, "start of active profile diameter", 2 * d.active_profile_start_radius * 1e3, "mm",
          "it must lie in [d_Ff, d_a) = [" + str(2 * form_radius * 1e3) + ", " +
              str(2 * tip_radius * 1e3) + ") mm, or be 0 (not known)");
  frame = {base_radius * roll_angle_form, base_radius * roll_angle_tip, d.face_width,
           d.normal_module};
  if (d.active_profile_start_radius > 0)
    frame.roll_length_active_start =
        std::max(base_radius * roll_angle(d.active_profile_start_radius), frame.roll_length_form);
  check_modifications(d.drive_modifications, frame, d.name + " drive flank");
  check_modifications(d.coast_modifications, frame, d.name + " coast flank");
  for (const auto &[own, side] : {std::pair{&d.drive_tooth_deviations, " drive flank"},
                                  {&d.coast_tooth_deviations, " coast flank"}})
    {
      if (!own->empty() && own->size() != std::size_t(d.teeth))
        throw InputError(d.name + side + ": " + std::to_string(own->size()) +
                         " tooth deviations for " + std::to_string(d.teeth) +
                         " teeth; expected none or one per tooth");
      for (std::size_t k = 0; k < own->size(); ++k)
        check_modifications((*own)[k], frame, d.name + side + " of tooth " + std::to_string(k));
    }
}

double
InvoluteGear::roll_angle(double radius) const
{
  return std::sqrt(std::max(radius * radius / (base_radius * base_radius) - 1, 0.0));
}

double
InvoluteGear::tooth_thickness(double radius) const
{
  const double alpha_y = std::acos(base_radius / radius);
  return 2 * radius *
         (tooth_thickness_reference / (2 * reference_radius) + inv(transverse_pressure_angle) -
          inv(alpha_y));
}

Vec2
InvoluteGear::generate(const Vec2 &q, const Vec2 &n, Vec2 *gear_normal) const
{
  // Rack coordinates q = (zeta along the rack, h below the datum line towards the gear centre);
  // the datum line lies at r + x m_n, the rolling line at r. When the gear has turned by phi the
  // rack has moved r phi along y. A rack point generates the gear where its normal passes through
  // the pitch point (Willis): zeta + r phi + (x m_n - h) n_zeta / n_h = 0.
  const double r   = reference_radius;
  const double xm  = d.profile_shift * d.normal_module;
  const double phi = -(q.x() + (xm - q.y()) * n.x() / n.y()) / r;
  const Vec2   world(r + xm - q.y(), q.x() + r * phi);
  if (gear_normal)
    *gear_normal = rotate(Vec2(n.y(), -n.x()), -phi); // minus the cutter's outward normal
  return rotate(world, -phi);
}

std::pair<double, double>
InvoluteGear::rack_flank_height_range() const
{
  // The heights whose Willis contact lies at the tip and form roll lengths.
  const double st = std::sin(transverse_pressure_angle);
  const double xm = d.profile_shift * d.normal_module;
  return {rack_h_tip, xm + (reference_radius * st - base_radius * roll_angle_form) * st};
}

Vec2
InvoluteGear::rack_generated_flank_point(double h, Vec2 *normal) const
{
  // Transverse section of the straight rack flank on the drive side: the cutter tooth lies at
  // zeta > p_t / 4 + h tan(alpha_t); its outward normal points back into the tooth space.
  const double at = transverse_pressure_angle;
  const double pt = pi * transverse_module;
  return generate(Vec2(pt / 4 + h * std::tan(at), h), Vec2(-std::cos(at), std::sin(at)), normal);
}

Vec2
InvoluteGear::fillet_point(double t, Vec2 *normal) const
{
  // Cutter tip rounding: a circle of radius rho in the normal section, an ellipse with semi-axes
  // rho / cos(beta) (along the rack) and rho (height) in the transverse section. psi runs from
  // pi/2 (bottom of the rounding, generating the root circle) to alpha_n (tangent to the flank).
  const double mn = d.normal_module, an = d.normal_pressure_angle;
  const double cb  = std::cos(d.helix_angle);
  const double rho = d.root_radius_factor * mn;
  const double hc  = d.dedendum_factor * mn - rho;
  const double zc  = pi * mn / 4 + hc * std::tan(an) + rho / std::cos(an); // normal section
  const double psi = pi / 2 + t * fillet_t_end * (an - pi / 2);
  const Vec2   q((zc - rho * std::cos(psi)) / cb, hc + rho * std::sin(psi));
  const Vec2   n = Vec2(-std::cos(psi), std::sin(psi) / cb).normalized();
  if (rho == 0) // sharp cutter corner: the fillet degenerates to the trochoid of that corner
    {
      const double at = transverse_pressure_angle;
      const Vec2   corner(pi * transverse_module / 4 + rack_h_form * std::tan(at), rack_h_form);
      const double a = pi / 2 + t * fillet_t_end * (at - pi / 2);
      return generate(corner, Vec2(-std::cos(a), std::sin(a)), normal);
    }
  return generate(q, n, normal);
}

InvoluteFlank
InvoluteGear::flank(int tooth, FlankSide side) const
{
  if (tooth < 0 || tooth >= d.teeth)
    throw InputError(d.name + ": tooth index " + str(tooth) + " is outside [0, " +
                     str(d.teeth - 1) + "]");
  return InvoluteFlank(shared_from_this(), tooth, side);
}

std::vector<Vec2>
InvoluteGear::half_tooth_profile(int n) const
{
  // From the middle of the space (polar angle pi/z) along the root circle, up the fillet and the
  // involute, along the tip circle to the tooth centre line.
  std::vector<Vec2> p;
  const Vec2        f0          = fillet_point(0);
  const double      a_root_end  = std::atan2(f0.y(), f0.x());
  const double      a_space_mid = pi / d.teeth;
  for (int i = 0; i < n; ++i)
    p.push_back(root_radius * e_r(a_space_mid + (a_root_end - a_space_mid) * i / n));
  for (int i = 0; i < n; ++i)
    p.push_back(fillet_point(double(i) / n));
  for (int i = 0; i <= n; ++i)
    {
      const double xi = roll_angle_form + (roll_angle_tip - roll_angle_form) * i / n;
      const double a  = half_angle_base - xi;
      p.push_back(base_radius * (e_r(a) + xi * e_theta(a)));
    }
  const double a_tip = std::atan2(p.back().y(), p.back().x());
  for (int i = 1; i <= n; ++i)
    p.push_back(tip_radius * e_r(a_tip * (1.0 - double(i) / n)));
  return p;
}

std::vector<Vec2>
InvoluteGear::transverse_outline(int n) const
{
  // One tooth counter-clockwise: coast half (mirror of the drive half, reversed) then the drive
  // half reversed back down; then rotated to each tooth position (nominal spacing).
  const std::vector<Vec2> half = half_tooth_profile(n);
  std::vector<Vec2>       tooth;
  for (auto it = half.begin(); it != half.end(); ++it)
    tooth.emplace_back(it->x(), -it->y());
  for (auto it = half.rbegin() + 1; it != half.rend() - 1; ++it)
    tooth.push_back(*it);
  std::vector<Vec2> outline;
  for (int k = 0; k < d.teeth; ++k)
    for (const Vec2 &q : tooth)
      outline.push_back(rotate(q, 2 * pi * k / d.teeth));
  return outline;
}

MassProperties
InvoluteGear::mass_properties() const
{
  // The nominal section (modifications are micrometres and do not count), minus the bore,
  // extruded over the face; chipped regions subtracted with their own axial extent.
  constexpr int points_per_segment = 400; // polygon error ~ (1/400)^2 relative in the fillet
  AreaMoments   section            = polygon_moments(transverse_outline(points_per_segment));
  if (d.bore_diameter > 0)
    section -= disc_moments(d.bore_diameter / 2);
  MassProperties p = prism_mass_properties(section, d.face_width, d.density);

  for (const ChippedTooth &c : d.chipped_teeth)
    {
      // The tooth region outside radius c.radius: the tooth outline clipped by that circle.
      const std::vector<Vec2> half = half_tooth_profile(points_per_segment);
      std::vector<Vec2>       outer; // drive half above the radius, from the chip circle up
      for (std::size_t i = 1; i < half.size(); ++i)
        {
          const double r0 = half[i - 1].norm(), r1 = half[i].norm();
          if (r0 < c.radius && r1 >= c.radius)
            outer.push_back(half[i - 1] + (half[i] - half[i - 1]) * (c.radius - r0) / (r1 - r0));
          if (r1 >= c.radius && half[i].y() > 0)
            outer.push_back(half[i]);
        }
      // Up the drive side, across the tip, down the coast side, back along the chip circle.
      std::vector<Vec2> chip = outer;
      for (auto it = outer.rbegin(); it != outer.rend(); ++it)
        chip.emplace_back(it->x(), -it->y());
      const double a0 = std::atan2(outer.front().y(), outer.front().x());
      for (int i = 1; i < points_per_segment; ++i)
        chip.push_back(c.radius * e_r(-a0 + 2 * a0 * i / points_per_segment));
      AreaMoments m = polygon_moments(chip);
      if (m.area < 0) // orientation-independent
        {
          m.area      = -m.area;
          m.second_xx = -m.second_xx;
          m.second_yy = -m.second_yy;
        }
      const double length = c.face_fraction * d.face_width;
      const double z0 = -d.face_width / 2, z1 = z0 + length;
      const double mass = d.density * m.area * length;
      p.mass -= mass;
      p.volume -= m.area * length;
      p.polar_inertia -= d.density * length * m.polar();
      p.diametral_inertia -=
          d.density * (length * 0.5 * m.polar() + m.area * (z1 * z1 * z1 - z0 * z0 * z0) / 3);
    }
  return p;
}

InvoluteFlank::InvoluteFlank(std::shared_ptr<const InvoluteGear> g, int k, FlankSide s)
    : gear(std::move(g))
    , tooth(k)
    , side(s)
    , angle(gear->tooth_angle[k])
    , offset(0)
{
  for (const EccentricTooth &e : gear->d.eccentric_teeth)
    if (e.tooth == k && e.side == s)
      offset += e.offset;
  const std::vector<ToothModifications> &own =
      s == FlankSide::drive ? gear->d.drive_tooth_deviations : gear->d.coast_tooth_deviations;
  if (!own.empty() && own[std::size_t(k)].any())
    deviations = &own[std::size_t(k)];
}

FlankDomain
InvoluteFlank::domain() const
{
  return {gear->roll_angle_form, gear->roll_angle_tip, -gear->d.face_width / 2,
          gear->d.face_width / 2};
}

bool
InvoluteFlank::contains(double u, double v) const
{
  const InvoluteGear &g = *gear;
  for (const ChippedTooth &c : g.d.chipped_teeth)
    if (c.tooth == tooth && u > g.roll_angle(c.radius) &&
        (c.face_fraction >= 1 || v <= -g.d.face_width / 2 + c.face_fraction * g.d.face_width))
      return false;
  return true;
}

FlankPoint
InvoluteFlank::nominal(double xi, double z) const
{
  // Transverse involute of the drive side of tooth 0 (mirrored for the coast side), turned by
  // the tooth angle plus the helix twist phi(z) = +-z tan(beta) / r, lifted to height z:
  //   P(xi, z) = R(angle + phi(z)) M p(xi) + z e_z + runout.
  const InvoluteGear &g    = *gear;
  const double        s    = side == FlankSide::drive ? 1.0 : -1.0;
  const double        dphi = g.helix_sign * std::tan(g.d.helix_angle) / g.reference_radius;
  const double        rot  = angle + dphi * z;
  const double        a    = g.half_angle_base - xi;
  const double        rb   = g.base_radius;
  Vec2                p    = rb * (e_r(a) + xi * e_theta(a)); // p(xi)
  Vec2                dp   = rb * xi * e_r(a);                // p'(xi)
  p.y() *= s;
  dp.y() *= s;
  const Vec2 Rp = rotate(p, rot), Rdp = rotate(dp, rot);

  FlankPoint f;
  f.position =
      Vec3(Rp.x(), Rp.y(), z) +
      g.d.runout.eccentricity * Vec3(std::cos(g.d.runout.phase), std::sin(g.d.runout.phase), 0);
  f.d_du = Vec3(Rdp.x(), Rdp.y(), 0);
  f.d_dv = Vec3(-dphi * Rp.y(), dphi * Rp.x(), 1);
  // Outward normal: P_v x P_u on the drive side; the mirror reverses the orientation.
  f.normal = s * f.d_dv.cross(f.d_du).normalized();
  return f;
}

FlankPoint
InvoluteFlank::evaluate(double xi, double z) const
{
  FlankPoint                f = nominal(xi, z);
  const InvoluteGear       &g = *gear;
  const ToothModifications &m =
      side == FlankSide::drive ? g.d.drive_modifications : g.d.coast_modifications;
  if (!m.any() && offset == 0 && !deviations)
    return f;

  // Superpose delta(L, z) along the nominal normal: P~ = P + delta n. The tangents of the
  // modified surface need the derivatives of the nominal normal; they are exact here from the
  // second derivatives of P.
  const double    rb  = g.base_radius;
  NormalDeviation dev = evaluate_modifications(m, g.frame, rb * xi, z);
  dev.value += offset;
  if (deviations)
    {
      const NormalDeviation own = evaluate_modifications(*deviations, g.frame, rb * xi, z);
      dev.value += own.value, dev.d_dL += own.d_dL, dev.d_dz += own.d_dz;
    }

  const double s    = side == FlankSide::drive ? 1.0 : -1.0;
  const double dphi = g.helix_sign * std::tan(g.d.helix_angle) / g.reference_radius;
  const double rot  = angle + dphi * z;
  const double a    = g.half_angle_base - xi;
  Vec2         p    = rb * (e_r(a) + xi * e_theta(a));
  Vec2         dp   = rb * xi * e_r(a);
  Vec2         ddp  = rb * (e_r(a) - xi * e_theta(a));
  p.y() *= s;
  dp.y() *= s;
  ddp.y() *= s;
  auto       lift = [](const Vec2 &q) { return Vec3(q.x(), q.y(), 0); };
  auto       perp = [](const Vec2 &q) { return Vec2(-q.y(), q.x()); }; // d R(phi) q / d phi
  const Vec3 P_uu = lift(rotate(ddp, rot));
  const Vec3 P_uv = lift(rotate(perp(dp), rot)) * dphi;
  const Vec3 P_vv = -lift(rotate(p, rot)) * dphi * dphi;

  const Vec3            N    = s * f.d_dv.cross(f.d_du);
  const double          Nn   = N.norm();
  const Vec3            N_u  = s * (P_uv.cross(f.d_du) + f.d_dv.cross(P_uu));
  const Vec3            N_v  = s * (P_vv.cross(f.d_du) + f.d_dv.cross(P_uv));
  const Eigen::Matrix3d proj = Eigen::Matrix3d::Identity() - f.normal * f.normal.transpose();
  const Vec3            n_u  = proj * N_u / Nn;
  const Vec3            n_v  = proj * N_v / Nn;

  FlankPoint r;
  r.position = f.position + dev.value * f.normal;
  r.d_du     = f.d_du + (dev.d_dL * rb) * f.normal + dev.value * n_u;
  r.d_dv     = f.d_dv + dev.d_dz * f.normal + dev.value * n_v;
  r.normal   = s * r.d_dv.cross(r.d_du).normalized();
  return r;
}

double
working_pressure_angle(const InvoluteGear &p, const InvoluteGear &g)
{
  // Newton on inv(a) = rhs from alpha_t; inv is monotonic and convex on (0, pi/2).
  const double at  = p.transverse_pressure_angle;
  const double rhs = inv(at) + 2 * std::tan(p.data().normal_pressure_angle) *
                                   (p.data().profile_shift + g.data().profile_shift) /
                                   (p.teeth() + g.teeth());
  double a = at;
  for (int i = 0; i < 60; ++i)
    {
      const double f = inv(a) - rhs;
      a -= f / (std::tan(a) * std::tan(a));
      if (std::abs(f) < 1e-16)
        break;
    }
  return a;
}

double
working_centre_distance(const InvoluteGear &p, const InvoluteGear &g)
{
  return (p.base_radius + g.base_radius) / std::cos(working_pressure_angle(p, g));
}

double
active_profile_start_radius(const InvoluteGear &g, const InvoluteGear &mate, double a)
{
  const double rb = g.base_radius + mate.base_radius;
  if (!(a > rb))
    throw InputError("start of active profile of " + g.data().name + ": centre distance " +
                     std::to_string(a * 1e3) + " mm is not above the sum of the base radii " +
                     std::to_string(rb * 1e3) + " mm");
  const double sin_alpha = std::sqrt(1 - (rb / a) * (rb / a));
  const double L_A       = a * sin_alpha - std::sqrt(mate.tip_radius * mate.tip_radius -
                                                     mate.base_radius * mate.base_radius);
  if (!(L_A < g.base_radius * g.roll_angle_tip))
    throw InputError("start of active profile of " + g.data().name + ": the tip circle of " +
                     mate.data().name + " does not cross the line of action inside " +
                     g.data().name + "'s tip circle at centre distance " + std::to_string(a * 1e3) +
                     " mm; the pair does not mesh there");
  if (L_A <= g.base_radius * g.roll_angle_form)
    return g.form_radius; // the mate's tip reaches below the involute (into the fillet)
  return std::hypot(g.base_radius, L_A);
}

std::string
external_pair_mismatch(const InvoluteGearData &a, const InvoluteGearData &b)
{
  std::ostringstream why;
  if (std::abs(a.normal_module - b.normal_module) > 1e-12)
    why << "must have the same normal module (" << a.normal_module * 1e3 << " and "
        << b.normal_module * 1e3 << " mm)";
  else if (std::abs(a.normal_pressure_angle - b.normal_pressure_angle) > 1e-12)
    why << "must have the same normal pressure angle";
  else if (std::abs(a.helix_angle - b.helix_angle) > 1e-12)
    why << "must have the same helix angle (external parallel-axis pair)";
  else if (a.helix_angle > 0 && a.hand == b.hand)
    why << "must have opposite hands (external helical pair); both are "
        << (a.hand == Hand::right ? "right" : "left");
  return why.str();
}

std::pair<std::shared_ptr<const InvoluteGear>, std::shared_ptr<const InvoluteGear>>
create_pair(const InvoluteGearData &pinion, const InvoluteGearData &gear, double a)
{
  const auto p = InvoluteGear::create(pinion), g = InvoluteGear::create(gear);
  if (!(a > 0))
    a = working_centre_distance(*p, *g);
  InvoluteGearData dp = pinion, dg = gear;
  if (dp.active_profile_start_radius == 0)
    dp.active_profile_start_radius = active_profile_start_radius(*p, *g, a);
  if (dg.active_profile_start_radius == 0)
    dg.active_profile_start_radius = active_profile_start_radius(*g, *p, a);
  return {InvoluteGear::create(dp), InvoluteGear::create(dg)};
}

ContactRatios
contact_ratios(const InvoluteGear &p, const InvoluteGear &g, double a)
{
  const double rb = p.base_radius + g.base_radius;
  if (!(a > rb))
    throw InputError("contact ratio: centre distance " + std::to_string(a * 1e3) +
                     " mm is not above the sum of the base radii " + std::to_string(rb * 1e3) +
                     " mm");
  auto          path      = [](double ra, double rb_) { return std::sqrt(ra * ra - rb_ * rb_); };
  const double  sin_alpha = std::sqrt(1 - (rb / a) * (rb / a));
  ContactRatios c;
  c.transverse =
      (path(p.tip_radius, p.base_radius) + path(g.tip_radius, g.base_radius) - a * sin_alpha) /
      p.transverse_base_pitch;
  c.overlap = std::min(p.data().face_width, g.data().face_width) * std::sin(p.data().helix_angle) /
              (pi * p.data().normal_module);
  // roll lengths along the line of action from the pinion's base tangent point: the pinion's
  // involute spans [g_f1, g_a1], the gear's [L - g_a2, L - g_f2]
  const double L = a * sin_alpha;
  const double lower =
      std::max(p.base_radius * p.roll_angle_form, L - path(g.tip_radius, g.base_radius));
  const double upper =
      std::min(path(p.tip_radius, p.base_radius), L - g.base_radius * g.roll_angle_form);
  c.active_transverse = std::max(0.0, upper - lower) / p.transverse_base_pitch;
  return c;
}

double
circumferential_backlash(const InvoluteGear &p, const InvoluteGear &g, double a)
{
  const double a_w = working_centre_distance(p, g);
  if (!(a >= a_w * (1 - 1e-12)))
    throw InputError("backlash: centre distance " + std::to_string(a * 1e3) +
                     " mm is below the zero-backlash working centre distance " +
                     std::to_string(a_w * 1e3) + " mm (the teeth would overlap)");
  const double alpha = std::acos(std::min(1.0, (p.base_radius + g.base_radius) / a));
  return 2 * a * (inv(alpha) - inv(working_pressure_angle(p, g)));
}

double
centre_distance_for_backlash(const InvoluteGear &p, const InvoluteGear &g, double backlash)
{
  require_value(backlash >= 0 && std::isfinite(backlash), "centre distance for a backlash",
                "backlash [m]", backlash, ">= 0");
  // Newton on j_t(a) = backlash from the first-order estimate; dj_t/da = 2 inv(alpha') - 2
  // inv(alpha_w) + 2 tan(alpha') (d inv / da = tan(alpha') / a): increasing and convex.
  const double a_w     = working_centre_distance(p, g);
  const double alpha_w = working_pressure_angle(p, g);
  double       a       = a_w + backlash / (2 * std::tan(alpha_w));
  for (int i = 0; i < 50; ++i)
    {
      const double alpha = std::acos((p.base_radius + g.base_radius) / a);
      const double f     = 2 * a * (inv(alpha) - inv(alpha_w)) - backlash;
      const double slope = 2 * (inv(alpha) - inv(alpha_w)) + 2 * std::tan(alpha);
      a -= f / slope;
      if (std::abs(f) < 1e-15 * (1 + backlash))
        break;
    }
  return std::max(a, a_w);
}

FlankGrid
sample_flank(const Flank &flank, int n_u, int n_v, double margin)
{
  const FlankDomain dom = flank.domain();
  FlankGrid         g;
  g.n_u     = n_u;
  g.n_v     = n_v;
  auto axis = [margin](double lo, double hi, int n) {
    std::vector<double> t(n);
    const double        a = lo + margin * (hi - lo), b = hi - margin * (hi - lo);
    for (int i = 0; i < n; ++i)
      t[i] = n == 1 ? 0.5 * (a + b) : a + (b - a) * i / (n - 1);
    return t;
  };
  g.u = axis(dom.u_min, dom.u_max, n_u);
  g.v = axis(dom.v_min, dom.v_max, n_v);
  for (double u : g.u)
    for (double v : g.v)
      {
        const FlankPoint p = flank.evaluate(u, v);
        g.positions.push_back(p.position);
        g.normals.push_back(p.normal);
      }
  return g;
}
} // namespace gearkit
