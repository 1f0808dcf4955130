#include "geometry/bevel_gear.h"

#include <Eigen/Geometry>

#include <cmath>
#include <sstream>

namespace gearkit
{
namespace
{
void
require(bool ok, const std::string &parameter, double value, const std::string &allowed)
{
  if (ok)
    return;
  std::ostringstream m;
  m << "spiral bevel pair: " << parameter << " = " << value << "; expected " << allowed;
  throw InputError(m.str());
}
} // namespace

BevelPairGeometry
bevel_geometry(const BevelPairDesign &d)
{
  require(d.pinion_teeth >= 3, "pinion teeth", d.pinion_teeth, ">= 3");
  require(d.gear_teeth >= 3, "gear teeth", d.gear_teeth, ">= 3");
  require(d.shaft_angle > 0 && d.shaft_angle < pi, "shaft angle [deg]", d.shaft_angle * 180 / pi,
          "in (0, 180)");
  require(d.module > 0, "module [mm]", d.module * 1e3, "> 0");
  require(d.mean_spiral_angle >= 0 && d.mean_spiral_angle < 60 * pi / 180,
          "mean spiral angle [deg]", d.mean_spiral_angle * 180 / pi, "in [0, 60)");
  require(d.pressure_angle > 0 && d.pressure_angle < 45 * pi / 180, "pressure angle [deg]",
          d.pressure_angle * 180 / pi, "in (0, 45)");
  require(d.cutter_radius > 0, "cutter radius [mm]", d.cutter_radius * 1e3, "> 0");
  require(d.pinion_addendum > 0 && d.pinion_addendum < 2, "pinion addendum factor",
          d.pinion_addendum, "in (0, 2)");
  require(d.clearance >= 0 && d.clearance < 1, "clearance factor", d.clearance, "in [0, 1)");
  require(d.pinion_thickness > 0 && d.pinion_thickness < 1, "pinion thickness factor",
          d.pinion_thickness, "in (0, 1)");

  BevelPairGeometry g;
  const double      ratio = double(d.gear_teeth) / d.pinion_teeth;
  g.pitch_angle_pinion    = std::atan2(std::sin(d.shaft_angle), ratio + std::cos(d.shaft_angle));
  g.pitch_angle_gear      = d.shaft_angle - g.pitch_angle_pinion;
  const double s1         = std::sin(g.pitch_angle_pinion);
  const double cb         = std::cos(d.mean_spiral_angle);
  if (d.module_kind == BevelModule::outer_transverse)
    {
      g.outer_transverse_module = d.module;
      g.outer_cone_distance     = d.module * d.pinion_teeth / (2 * s1);
      g.mean_cone_distance      = g.outer_cone_distance - d.face_width / 2;
      g.mean_normal_module      = d.module * g.mean_cone_distance / g.outer_cone_distance * cb;
    }
  else
    {
      g.mean_normal_module      = d.module;
      g.mean_cone_distance      = d.module / cb * d.pinion_teeth / (2 * s1);
      g.outer_cone_distance     = g.mean_cone_distance + d.face_width / 2;
      g.outer_transverse_module = d.module / cb * g.outer_cone_distance / g.mean_cone_distance;
    }
  require(d.face_width > 0 && d.face_width < g.outer_cone_distance, "face width [mm]",
          d.face_width * 1e3,
          "in (0, outer cone distance = " + std::to_string(g.outer_cone_distance * 1e3) + " mm)");
  const double m = g.mean_normal_module;
  const double c = d.clearance * m;
  g.pinion       = {d.pinion_teeth, g.pitch_angle_pinion,  g.mean_cone_distance,
                    d.face_width,   d.pinion_addendum * m, (2 - d.pinion_addendum) * m + c};
  g.gear         = {d.gear_teeth, g.pitch_angle_gear,          g.mean_cone_distance,
                    d.face_width, (2 - d.pinion_addendum) * m, d.pinion_addendum * m + c};
  return g;
}

NominalSettings
nominal_settings(const BevelPairDesign &d)
{
  const BevelPairGeometry g  = bevel_geometry(d);
  const double            Am = g.mean_cone_distance, rc = d.cutter_radius;
  const double            sb = std::sin(d.mean_spiral_angle), cb = std::cos(d.mean_spiral_angle);
  NominalSettings         n;
  n.radial_setting       = std::sqrt(Am * Am + rc * rc - 2 * Am * rc * sb);
  n.cradle_angle         = std::atan2(rc * cb, Am - rc * sb);
  n.ratio_of_roll_pinion = 1 / std::sin(g.pitch_angle_pinion);
  n.ratio_of_roll_gear   = 1 / std::sin(g.pitch_angle_gear);
  return n;
}

std::pair<BevelMemberCut, BevelMemberCut>
conjugate_cuts(const BevelPairDesign &d)
{
  const BevelPairGeometry g = bevel_geometry(d);
  const NominalSettings   n = nominal_settings(d);
  // The generating gear's tooth traces are circles about the cutter centre; a positive cradle
  // angle puts the centre at +y_m, so the traces (and the pinion's teeth) turn about +a with
  // growing cone distance: right hand. The gear sees the generating gear from the other side of
  // the pitch plane (its machine frame is the pinion's turned by pi about x_m): the centre at
  // -y_m, the opposite hand, and each blade cone is the other blade kind.
  const double q    = d.pinion_hand == Hand::right ? n.cradle_angle : -n.cradle_angle;
  const double slot = (1 - d.pinion_thickness) * pi * g.mean_normal_module; // pinion, normal

  BevelMemberCut pinion, gear;
  pinion.blank = g.pinion;
  gear.blank   = g.gear;
  MachineSettings mp;
  mp.radial_setting      = n.radial_setting;
  mp.cradle_angle        = q;
  mp.root_angle          = g.pitch_angle_pinion;
  mp.ratio_of_roll       = n.ratio_of_roll_pinion;
  MachineSettings mg     = mp;
  mg.cradle_angle        = -q;
  mg.root_angle          = g.pitch_angle_gear;
  mg.ratio_of_roll       = n.ratio_of_roll_gear;
  pinion.outside_machine = pinion.inside_machine = mp;
  gear.outside_machine = gear.inside_machine = mg;

  const double a       = d.pressure_angle;
  pinion.outside_blade = {d.cutter_radius + slot / 2, a, +1};
  pinion.inside_blade  = {d.cutter_radius - slot / 2, a, -1};
  gear.inside_blade    = {d.cutter_radius + slot / 2, a, -1};
  gear.outside_blade   = {d.cutter_radius - slot / 2, a, +1};
  for (Blade *b :
       {&pinion.outside_blade, &pinion.inside_blade, &gear.outside_blade, &gear.inside_blade})
    b->edge_radius = d.edge_radius * g.mean_normal_module;
  return {pinion, gear};
}

std::pair<BevelMemberCut, BevelMemberCut>
formate_cuts(const BevelPairDesign &d)
{
  auto [pinion, gear]            = conjugate_cuts(d);
  const BevelPairGeometry g      = bevel_geometry(d);
  gear.outside_machine.generated = gear.inside_machine.generated = false;

  // The gear's machine frame seen from the pinion's: T = Ry(90 deg - gamma_2) Rx(pi) takes the
  // gear axis to -z and the gear's pitch element to the common element; the cutter (fixed in the
  // gear) then sits at T C' with its axis -T z' (blades toward the pinion).
  const MachineSettings &mg   = gear.outside_machine;
  const double           beta = pi / 2 - g.pitch_angle_gear;
  const Eigen::Matrix3d  T =
      (Eigen::AngleAxisd(beta, Vec3::UnitY()) * Eigen::AngleAxisd(pi, Vec3::UnitX()))
          .toRotationMatrix();
  const Vec3      C = T * Vec3(mg.radial_setting * std::cos(mg.cradle_angle),
                               mg.radial_setting * std::sin(mg.cradle_angle), 0);
  MachineSettings mp;
  mp.radial_setting      = C.head<2>().norm();
  mp.cradle_angle        = std::atan2(C.y(), C.x());
  mp.tilt                = beta;
  mp.swivel              = -mp.cradle_angle; // leaning toward +x
  mp.sliding_base        = C.z();
  mp.root_angle          = d.shaft_angle - pi / 2;
  mp.ratio_of_roll       = double(d.gear_teeth) / d.pinion_teeth;
  pinion.outside_machine = pinion.inside_machine = mp;
  // Each pinion blade is the gear's opposite blade cone seen from the other side.
  pinion.outside_blade       = gear.inside_blade;
  pinion.outside_blade.slope = +1;
  pinion.inside_blade        = gear.outside_blade;
  pinion.inside_blade.slope  = -1;
  return {pinion, gear};
}

std::pair<BevelMemberCut, BevelMemberCut>
mismatched_cuts(const BevelPairDesign &d, const PinionMismatch &m)
{
  auto [pinion, gear] = conjugate_cuts(d);
  // The mean point of each pinion flank: mean cone distance, middle of the working depth (the
  // gear's tip reaches h = -h_a2 on the pinion, the pinion's tip is at h = +h_a1).
  const double h_mid = 0.5 * (pinion.blank.addendum - gear.blank.addendum);
  for (auto [blade, machine] : {std::pair{&pinion.outside_blade, &pinion.outside_machine},
                                {&pinion.inside_blade, &pinion.inside_machine}})
    {
      // The outside blade (concave flank) grows by the change, the inside blade (convex flank)
      // shrinks by it: both pinion flanks then curve less lengthwise than the gear flanks they
      // meet need, which localises the bearing. The changed blade cone must touch the
      // conjugate one along the blade line that generates the flank's mean point: then that
      // point, its normal and the equation of meshing there are unchanged, the flank passes
      // through the mean point with the conjugate normal and the bearing is centred on it.
      // That line lies at the cutter angle theta of the mean point's generation, i.e. along
      // e = (cos theta, sin theta, 0) in the cutter frame: a blade radius change rho + change
      // about a centre moved by -change e keeps every point of that line in place. (Pivoting
      // on the line from the centre to the mean generating point (A_m, 0) of the cradle, as
      // before, kept the blade line through the point of the blade's pitch circle on that
      // line: about 1 mm from the mean point along the face in the seed pair.)
      const double                     change = blade->slope * m.cutter_radius;
      const GeneratedFlank             conjugate(pinion.blank, *blade, *machine);
      const GeneratedFlank::Generation mean = conjugate.generation(h_mid, 0);
      const Vec3 e = cutter_frame(*machine) * Vec3(std::cos(mean.theta), std::sin(mean.theta), 0);
      // The centre moves in the cradle plane; a component along the cradle axis (tilted
      // cutters only) is a sliding-base change (the blank's apex moved the other way).
      const Vec3 moved = Vec3(machine->radial_setting * std::cos(machine->cradle_angle),
                              machine->radial_setting * std::sin(machine->cradle_angle), 0) -
                         change * e;
      machine->radial_setting = moved.head<2>().norm();
      machine->cradle_angle   = std::atan2(moved.y(), moved.x());
      machine->sliding_base   = machine->sliding_base + moved.z();
      // The modified roll about the roll that generates the mean point: the blank turns there
      // at the plain ratio, so the point and its normal stay, and the parabola of transmission
      // error has its vertex where the mean point is in contact (about cradle angle 0, the
      // vertex and the bearing would lie apart by the mean point's roll).
      machine->modified_roll_2c     = m.modified_roll_2c;
      machine->modified_roll_6d     = m.modified_roll_6d;
      machine->modified_roll_centre = mean.psi_c;
      blade->pitch_radius += change;
      blade->curvature     = m.blade_curvature;
      blade->parabola_apex = 0;
    }
  return {pinion, gear};
}

CutterReach
cutter_reach(const BevelPairDesign &d, const PinionMismatch &mismatch)
{
  const auto [pinion, gear] = conjugate_cuts(d);
  const double Am = pinion.blank.mean_cone_distance, F = pinion.blank.face_width;
  const double h_mid = 0.5 * (pinion.blank.addendum - gear.blank.addendum); // as mismatched_cuts
  CutterReach  worst;
  worst.sin_spiral = -1;
  for (const BevelMemberCut *cut : {&pinion, &gear})
    for (const auto &[blade, machine] : {std::pair{&cut->outside_blade, &cut->outside_machine},
                                         {&cut->inside_blade, &cut->inside_machine}})
      {
        const double tan_a = std::tan(blade->angle);
        Vec2         centre(machine->radial_setting * std::cos(machine->cradle_angle),
                            machine->radial_setting * std::sin(machine->cradle_angle));
        double       radius = blade->pitch_radius;
        if (cut == &pinion && mismatch.cutter_radius != 0)
          {
            // the trace at the mean height meets A_m at X (the crossing nearer the mean point
            // (A_m, 0)); the changed blade keeps X: its centre moves by -change along X - C
            const double change = blade->slope * mismatch.cutter_radius;
            const double rho    = radius + blade->slope * tan_a * h_mid;
            const double S      = centre.norm();
            const double a      = (Am * Am - rho * rho + S * S) / (2 * S);
            const double q      = std::sqrt(std::max(0.0, Am * Am - a * a));
            const Vec2   e      = centre / S, n(-e.y(), e.x());
            const Vec2   x1 = a * e + q * n, x2 = a * e - q * n;
            const Vec2   X = (x1 - Vec2(Am, 0)).norm() <= (x2 - Vec2(Am, 0)).norm() ? x1 : x2;
            centre -= change * (X - centre).normalized();
            radius += change;
          }
        const double S   = centre.norm();
        const double rho = radius + blade->slope * tan_a * cut->blank.addendum;
        for (const bool heel : {false, true})
          {
            const double A = Am + (heel ? F / 2 : -F / 2);
            const double sin_beta =
                rho > 0 ? (A * A + rho * rho - S * S) / (2 * A * rho) : HUGE_VAL;
            if (std::abs(sin_beta) > worst.sin_spiral)
              worst = {std::abs(sin_beta),
                       cut == &pinion ? "pinion" : "gear",
                       blade->slope > 0 ? "concave" : "convex",
                       heel,
                       A,
                       rho};
          }
      }
  return worst;
}

double
least_cutter_radius(const BevelPairDesign &design, const PinionMismatch &mismatch)
{
  BevelPairDesign d       = design;
  const double    Am      = bevel_geometry(d).mean_cone_distance;
  auto            reaches = [&](double r) {
    d.cutter_radius = r;
    return cutter_reach(d, mismatch).generated();
  };
  double lo = 0, hi = Am / 64;
  while (!reaches(hi))
    {
      lo = hi, hi *= 2;
      if (hi > 1000 * Am)
        return HUGE_VAL;
    }
  while (hi - lo > 1e-9 * Am)
    {
      const double r         = 0.5 * (lo + hi);
      (reaches(r) ? hi : lo) = r;
    }
  return hi;
}

BevelMemberFlanks::BevelMemberFlanks(const BevelMemberCut &cut)
    : z(cut.blank.teeth)
{
  const GeneratedFlank outside(cut.blank, cut.outside_blade, cut.outside_machine);
  const GeneratedFlank inside(cut.blank, cut.inside_blade, cut.inside_machine);
  // At the mean point of the pitch cone: which flank faces +theta, and the polar angles.
  auto polar = [](const GeneratedFlank &f, double &facing) {
    const FlankPoint p = f.evaluate(0, 0);
    const Vec3       e_theta(-p.position.y(), p.position.x(), 0);
    facing = p.normal.dot(e_theta.normalized());
    return std::atan2(p.position.y(), p.position.x());
  };
  double       facing_out, facing_in;
  const double theta_out = polar(outside, facing_out);
  const double theta_in  = polar(inside, facing_in);
  if (!(facing_out * facing_in < 0))
    throw InputError("spiral bevel member: the outside and inside blades cut flanks facing the "
                     "same way; expected one flank of each side of the tooth");
  outside_is_drive         = facing_out > 0;
  const double theta_d     = outside_is_drive ? theta_out : theta_in;
  const double theta_c     = outside_is_drive ? theta_in : theta_out;
  const double pitch       = 2 * pi / z;
  const double thickness   = theta_d - theta_c - pitch * std::floor((theta_d - theta_c) / pitch);
  const GeneratedFlank &fd = outside_is_drive ? outside : inside;
  const GeneratedFlank &fc = outside_is_drive ? inside : outside;
  drive                    = std::make_unique<GeneratedFlank>(fd.rotated(thickness / 2 - theta_d));
  coast                    = std::make_unique<GeneratedFlank>(fc.rotated(-thickness / 2 - theta_c));
  for (int k = 0; k < z; ++k)
    {
      add(k, FlankSide::drive, std::make_unique<GeneratedFlank>(drive->rotated(k * pitch)));
      add(k, FlankSide::coast, std::make_unique<GeneratedFlank>(coast->rotated(k * pitch)));
    }
}
Vec3
BevelMemberFlanks::face_direction(const Vec3 &x) const
{
  const double gamma = drive->blank_data().pitch_angle, theta = std::atan2(x.y(), x.x());
  return {std::sin(gamma) * std::cos(theta), std::sin(gamma) * std::sin(theta), std::cos(gamma)};
}

std::pair<double, double>
BevelMemberFlanks::rotational_parameters(const Vec3 &x) const
{
  const BevelBlank &b  = drive->blank_data();
  const double      cg = std::cos(b.pitch_angle), sg = std::sin(b.pitch_angle);
  const double      r = std::hypot(x.x(), x.y());
  return {-x.z() * sg + r * cg, x.z() * cg + r * sg - b.mean_cone_distance};
}

VirtualCylindricalGears
virtual_cylindrical_gears(const BevelPairDesign &d)
{
  const BevelPairGeometry g = bevel_geometry(d);
  VirtualCylindricalGears v;
  const double            m = g.mean_normal_module, beta = d.mean_spiral_angle;
  const double            at = std::atan(std::tan(d.pressure_angle) / std::cos(beta));
  v.z1                       = d.pinion_teeth / std::cos(g.pitch_angle_pinion);
  v.z2                       = d.gear_teeth / std::cos(g.pitch_angle_gear);
  v.normal_module            = m;
  v.helix_angle              = beta;
  v.pressure_angle           = d.pressure_angle;
  v.transverse_angle         = at;
  v.r1                       = v.z1 * m / std::cos(beta) / 2;
  v.r2                       = v.z2 * m / std::cos(beta) / 2;
  v.addendum1                = d.pinion_addendum * m;
  v.addendum2                = (2 - d.pinion_addendum) * m;
  v.face_width               = d.face_width;
  auto path                  = [&](double r, double ha) {
    return std::sqrt(std::pow(r + ha, 2) - std::pow(r * std::cos(at), 2));
  };
  v.transverse_contact_ratio =
      (path(v.r1, v.addendum1) + path(v.r2, v.addendum2) - (v.r1 + v.r2) * std::sin(at)) /
      (pi * m * std::cos(at) / std::cos(beta));
  v.overlap_ratio = d.face_width * std::sin(beta) / (pi * m);
  return v;
}
} // namespace gearkit
