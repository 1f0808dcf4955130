// Sections Finite elements/<pair> (the members' tooth segments, elements, material) and Loaded
// contact/<pair> (torques, positions, contact cells, reference mode).
#include "driver/scene.h"
#include "driver/scene_parameters.h"

#include <algorithm>

namespace gearkit
{
void
FeScene::declare(ParameterHandler &prm)
{
  prm.declare_entry("segment teeth", "7", Patterns::Integer(3, 15),
                    "Teeth in each member's finite-element segment (odd, at least the teeth that "
                    "carry load over the mesh cycle, and with unit loads on the middle tooth "
                    "twice the teeth in contact at once less one; at most half the gear; bore "
                    "and radial cuts held). The held cuts stiffen the member: K_m from the "
                    "whole gears' +0.8 % with 9 teeth and +0.06 % with 15 (62/62 spur), +12 % "
                    "with 7 on the 16/24-tooth FZG C pair, +72 % on the ISO/TR 6336-30 pair "
                    "(K_m between the held bores: whole rims; bench/README.md).");
  prm.declare_entry("hold cuts", "true", Patterns::Bool(),
                    "Hold the segment's radial cut faces (true) or leave them free (false: "
                    "softer than the whole gear; held and free bracket it).");
  prm.declare_entry("whole gears", "false", Patterns::Selection("false|true|pinion|gear"),
                    "Model each member (true), or only the pinion or the gear, whole: all teeth "
                    "on the rim, the bore held, no cuts "
                    "(spur and helical pairs). The teeth that carry load over the mesh cycle get "
                    "the flank sizes, the others the far size; segment teeth and hold cuts are "
                    "then not used. The support the segments approximate (bench/README.md: "
                    "segment -> whole gear).");
  prm.declare_entry("whole rims", "false", Patterns::Selection("false|true|pinion|gear"),
                    "Put each member's segment (true), or only the pinion's or the gear's, on "
                    "the whole rim: the rim and the held bore all round, no cuts, teeth only on "
                    "the segment (spur and helical pairs; the segment may then span more than "
                    "half the gear). The whole gear's support at about the segment's cost: K_m "
                    "within 0.2 % of whole gears on FZG C and the 62/62 pair (the far teeth "
                    "hardly stiffen the body; bench/README.md). Hold cuts is then not used. The "
                    "reference mode meshes the whole bodies at the contact's resolution: "
                    "millions of unknowns (refused with its memory estimate when too large).");
  prm.declare_entry("unit loads", "middle tooth", Patterns::Selection("middle tooth|loaded teeth"),
                    "middle tooth: unit loads on the segment's middle tooth alone, its table "
                    "read for every tooth turned (every tooth of a gear alike: the one farthest "
                    "from the cuts speaks for all; only its flank refined), responses on the "
                    "teeth as far from it as teeth stand apart in contact at once (the segment "
                    "grows to hold them). loaded teeth: a unit-load grid on every tooth that can "
                    "carry load over the mesh cycle; those next to held cuts are stiffened by "
                    "them (62/62 on 9-tooth segments: K_m +1.65 % from the whole gear, middle "
                    "tooth +0.78 %, at two thirds of the time; bench/README.md).");
  prm.declare_entry("flank element size", "0.25", Patterns::Double(0.02, 2),
                    "Element size at the flanks and fillets / m_n.");
  prm.declare_entry("far element size", "1", Patterns::Double(0.05, 10),
                    "Element size toward the bore / m_n; at most a third of the rim's thickness "
                    "(root circle to bore) of each member (involute members).");
  prm.declare_entry("degree", "2", Patterns::Integer(1, 2),
                    "Finite-element degree (FE_Q). 1: linear elements, stiffer (K_m +2 % at "
                    "Poisson's ratio 0.3 on a 20/31 spur pair) and locking as the material "
                    "nears incompressibility: a warning above Poisson's ratio 0.35, refused "
                    "above 0.45 (bench/README.md).");
  prm.declare_entry("other element size", "0", Patterns::Double(0, 2),
                    "[m_n] Element size at the fillets and the flanks of the unloaded side; 0 = "
                    "the flank element size. Only the loaded flanks need fine elements: with the "
                    "analytic near field, flank 0.25 keeps every FZG C position within 1.1 % "
                    "of the reference mode (bench/README.md).");
  prm.declare_entry("fillet element size", "0", Patterns::Double(0, 2),
                    "[m_n] Element size at the root fillets of the teeth with fine elements "
                    "(spur and helical segments); 0 = the flank element size (the other "
                    "element size where set). The fillets are concave arcs of about the "
                    "cutter's tip radius (0.38 m_n): gmsh puts at least four elements on one, so "
                    "the flank element size refines them only below about 0.2 m_n, and their "
                    "chords add material at the tooth roots (K_m 0.5 % stiff at flank elements "
                    "of 0.25 m_n on a 20/31 spur pair, unseen by the error estimate). 0.1 (a "
                    "quarter of the fillet radius) removes that and lets K_m converge "
                    "monotonically with the flank element size, at about twice the elements "
                    "(bench/README.md, element refinement study).");
  prm.declare_entry("near field", "analytic", Patterns::Selection("analytic|response depth"),
                    "How the unit loads' 1/r near field is treated. analytic: Boussinesq's "
                    "field carried exactly (cut off within the near field radius), the finite "
                    "elements solve only the smooth remainder and are read at the flank; "
                    "converges at coarse elements (bench/README.md). response depth: the "
                    "elements are read a few element sizes below the flank and the half-space "
                    "part above is analytic (error first order in the element size).");
  prm.declare_entry("near field radius", "2", Patterns::Double(0.1, 10),
                    "[m_n] Radius within which the analytic near field is carried (less where "
                    "the body comes back across a load's normal or a held face is nearer): "
                    "the elements must resolve its smooth cut-off, about five across it.");
  prm.declare_entry("response depth", "3", Patterns::Double(1, 20),
                    "Depth below the flank, in flank element sizes, where the finite elements "
                    "are read (they resolve the Boussinesq field there); the half-space part "
                    "above it is analytic.");
  prm.declare_entry("profile grid points", "9", Patterns::Integer(2, 100),
                    "Unit-load points over the profile of each loaded flank.");
  prm.declare_entry("face grid points", "0", Patterns::Integer(0, 100),
                    "Unit-load points over the face of each loaded flank; 0: from the face "
                    "width b and the (normal) module m, 1 + ceil(2 b / m), at least 7 and at "
                    "most 25 (the table is bilinear between them and varies along the face on "
                    "the scale of the tooth; 62/62 spur, b = 10 m: 7 points give K_m 1.6 % soft; "
                    "bench/README.md).");
  prm.declare_entry("error estimate", "true", Patterns::Bool(),
                    "Also compute the tables on a mesh of twice the element sizes at the flanks, "
                    "fillets and other flanks (1.5 or 1.25 times where gmsh cannot mesh that; "
                    "with local refinements the same segment refined once less; "
                    "about a quarter more time) and write "
                    "each K_m's and e_L's estimated discretisation error: the change to that "
                    "mesh, |K(h) - K(c h)| / (c - 1), plus the change to half the contact cells "
                    "across and along (upper estimates wherever the error falls at least "
                    "linearly with the size).");
  prm.declare_entry("load grid", "graded", Patterns::Selection("uniform|graded"),
                    "Spacing of the unit-load points. graded: clustered towards the flank's "
                    "edges (Chebyshev-Lobatto), where the compliance rises steeply near the "
                    "face ends and the tip.");
  prm.declare_entry("local refinements", "0", Patterns::Integer(0, 3),
                    "k > 0: gmsh meshes the segment with every element size 2^k times larger and "
                    "deal.II refines the elements near the loaded flanks k times (hanging "
                    "nodes, new vertices on the exact flanks): the loaded flanks keep the sizes "
                    "above, the other teeth and the rim's face layers are coarse (62/62 pair on "
                    "9-tooth segments: 209k instead of 300k dofs a member, K_m within 0.1 % of "
                    "a twice-refined segment; bench/README.md). Where gmsh cannot mesh the "
                    "segment at the larger sizes it says so: use fewer.");
  prm.declare_entry("refine depth", "1", Patterns::Double(0, 20),
                    "With local refinements: the elements within this many (unrefined) flank "
                    "element sizes of the loaded flanks are refined.");
  prm.declare_entry("Young's modulus", "206", Patterns::Double(1),
                    "[GPa] Young's modulus of both members.");
  prm.declare_entry("Poisson's ratio", "0.3", Patterns::Double(-0.99, 0.499),
                    "Poisson's ratio of both members.");
}

void
FeScene::parse(ParameterHandler &prm)
{
  segment_teeth           = prm.get_integer("segment teeth");
  hold_cuts               = prm.get_bool("hold cuts");
  const std::string whole = prm.get("whole gears");
  whole_pinion            = whole == "true" || whole == "pinion";
  whole_gear              = whole == "true" || whole == "gear";
  const std::string rim   = prm.get("whole rims");
  whole_rim_pinion        = rim == "true" || rim == "pinion";
  whole_rim_gear          = rim == "true" || rim == "gear";
  cyclic                  = prm.get("unit loads") == "middle tooth";
  flank_size              = prm.get_double("flank element size");
  far_size                = prm.get_double("far element size");
  other_size              = prm.get_double("other element size");
  fillet_size             = prm.get_double("fillet element size");
  degree                  = unsigned(prm.get_integer("degree"));
  depth                   = prm.get_double("response depth");
  analytic_near_field     = prm.get("near field") == "analytic";
  near_field_radius       = prm.get_double("near field radius");
  n_u                     = prm.get_integer("profile grid points");
  n_v                     = prm.get_integer("face grid points");
  graded_grid             = prm.get("load grid") == "graded";
  error_estimate          = prm.get_bool("error estimate");
  local_refinements       = unsigned(prm.get_integer("local refinements"));
  refine_depth            = prm.get_double("refine depth");
  material = {prm.get_double("Young's modulus") * GPa, prm.get_double("Poisson's ratio")};
}

FeScene
FeScene::coarsened(double factor) const
{
  FeScene c = *this;
  c.flank_size *= factor, c.other_size *= factor, c.fillet_size *= factor;
  c.far_size = std::max(far_size, c.flank_size);
  // twice the sizes with local refinements: the same segment mesh refined once less
  if (factor == 2 && local_refinements > 0)
    c.local_refinements = local_refinements - 1;
  return c;
}

// Linear elements (FE_Q 1, full integration) lock volumetrically as Poisson's ratio nears 1/2:
// on the 20/31 spur pair of issue 36 (m 3 mm, b 15 mm, 100 N m, flank elements 0.25 m_n) K_m
// is 2.1 % above degree 2's at 0.3 (their ordinary discretisation error), 4.1 % at 0.45,
// 9.7 % at 0.49 and 28 % at 0.499 (bench/README.md, "Element refinement study"). Above
// 0.45 the locking outgrows the elements' own error: refused; from 0.35 on a warning.
constexpr double linear_elements_warned_above  = 0.35;
constexpr double linear_elements_refused_above = 0.45;

void
FeScene::check(const PairScene &pair, bool run, std::vector<std::string> &warnings) const
{
  const double nu = material.poisson_ratio;
  if (run && degree == 1 && nu > linear_elements_refused_above)
    throw InputError("Finite elements/" + pair.name +
                     "/degree = 1 is not allowed with Poisson's ratio = " + plausible_number(nu) +
                     ": linear elements lock near incompressibility (K_m of a 20/31 spur pair "
                     "9.7 % above degree 2's at 0.49, 28 % at 0.499); expected degree = 2 (the "
                     "default), or degree 1 only up to Poisson's ratio " +
                     plausible_number(linear_elements_refused_above));
  if (run && degree == 1 && nu > linear_elements_warned_above)
    warnings.push_back("Finite elements/" + pair.name +
                       "/degree = 1 with Poisson's ratio = " + plausible_number(nu) +
                       ": linear elements lock as the material nears incompressibility (K_m "
                       "of a 20/31 spur pair 4.1 % above degree 2's at 0.45, 2.1 % at 0.3); "
                       "degree = 2 (the default) locks far less");
  const std::string where = "Finite elements/" + pair.name + "/segment teeth = ";
  if (segment_teeth % 2 == 0)
    throw InputError(where + std::to_string(segment_teeth) +
                     " is not allowed; expected an odd number");
  if (n_v == 1)
    throw InputError("Finite elements/" + pair.name +
                     "/face grid points = 1 is not allowed; expected 0 (from the face width) or "
                     "at least 2");
  if ((whole_pinion && whole_rim_pinion) || (whole_gear && whole_rim_gear))
    throw InputError("Finite elements/" + pair.name +
                     "/whole rims and whole gears both name a member; expected one of them "
                     "(a whole gear has its rim already)");
  // Young's modulus: polymers from 1 GPa to tungsten carbide's 600 (diamond 1050); beyond
  // 1200 GPa no material, MPa typed in the GPa field (206000 for steel's 206).
  if (material.youngs_modulus > 1200 * GPa)
    {
      const double e = material.youngs_modulus / GPa;
      throw InputError("Finite elements/" + pair.name +
                       "/Young's modulus = " + plausible_number(e) +
                       " GPa is not allowed: real materials have 1 to 1200 GPa (steel 206)" +
                       (e / 1000 >= 1 && e / 1000 <= 1200
                            ? "; it looks like MPa typed in a GPa field (" + plausible_number(e) +
                                  " MPa = " + plausible_number(e / 1000) + " GPa)"
                            : std::string("; expected a value in that range")));
    }
  // Against the pair only where the finite elements run: the defaults (7 segment teeth) suit
  // no particular pair.
  if (!run)
    return;
  if ((whole_pinion || whole_gear) && pair.type != PairType::involute)
    throw InputError("Finite elements/" + pair.name +
                     "/whole gears = true is not allowed for this pair; whole gears are meshed "
                     "for spur and helical pairs (spiral bevel pairs: segments)");
  if ((whole_rim_pinion || whole_rim_gear) && pair.type != PairType::involute)
    throw InputError("Finite elements/" + pair.name +
                     "/whole rims is not allowed for this pair; expected false (whole rims are "
                     "meshed for spur and helical pairs; spiral bevel pairs: segments)");
  if (fillet_size > 0 && pair.type != PairType::involute)
    throw InputError("Finite elements/" + pair.name +
                     "/fillet element size = " + plausible_number(fillet_size) +
                     " is not allowed for this pair; expected 0 (spiral bevel segments size "
                     "their fillets with the flanks)");
  const int z = std::min(pair_teeth(pair).first, pair_teeth(pair).second);
  if (segment_teeth > z)
    throw InputError(where + std::to_string(segment_teeth) +
                     " is not allowed; a segment has at most the teeth of the smaller member (" +
                     std::to_string(z) + ")");
}

void
LoadedScene::declare(ParameterHandler &prm)
{
  prm.declare_entry("torques", "100", Patterns::List(Patterns::Double(0), 1),
                    "[N m] Pinion torques (one loaded analysis per torque; the compliances are "
                    "computed once).");
  prm.declare_entry("positions per mesh cycle", "20", Patterns::Integer(1, 10000),
                    "Pinion positions over one mesh cycle.");
  prm.declare_entry("cells across", "17", Patterns::Integer(1, 201),
                    "Contact cells across each contact line (odd: a row on the line).");
  prm.declare_entry("cells along", "24", Patterns::Integer(1, 1000),
                    "Contact cells along each contact line.");
  prm.declare_entry("cells along grading", "0", Patterns::Double(0, 1),
                    "How the cells along a contact line crowd towards an end at a flank's edge "
                    "(face end, tip) that the contact reaches, where a line contact's pressure "
                    "peaks: 0 uniform, 1 cosine spacing (FZG C at 350 N m: TE peak-to-peak "
                    "within 0.1 % of 4 times the cells along, uniform cells 0.45 % off; "
                    "bench/README.md).");
  prm.declare_entry("gap band", "0", Patterns::Double(0),
                    "[um] Where the contact zone starts: it reaches where the unloaded gap opens "
                    "to this. 0: from the load (four times the gap at the edge of Hertz's line "
                    "contact on the leading pair). Either way the zone is then fitted to the "
                    "solved contact at every torque and position (four times the gap at the "
                    "contact's edge: narrowed while the contact fills less than a third of it, "
                    "widened while it reaches its edge), so that light and heavy loads, small and "
                    "large gears are resolved alike; results: stiffness/<pair>/gap_band.");
  prm.declare_entry("reference positions", "", Patterns::List(Patterns::Integer(0), 0, 1000),
                    "Positions of the mesh cycle (0 = the first) solved again in reference mode "
                    "(both members meshed for the position and refined about its contact "
                    "cells, finite elements alone, minutes per position), with VTU files of "
                    "displacement and stress in <output>/vtu/.");
  prm.declare_entry("reference elements per cell", "0.5", Patterns::Double(0.1, 4),
                    "Reference mode: element size at the contact = cell width / this.");
  prm.declare_entry("table interpolation", "bilinear",
                    Patterns::Selection("bilinear|load following"),
                    "How the compliance tables are read between their unit loads. bilinear: in "
                    "both points' flank parameters. load following: on the load's own flank the "
                    "response is read at the same offset from each of the load's grid points, "
                    "which keeps the compliance's peak at the load (second order in both grid "
                    "directions: the tables' grid-converged K_m with fewer face points, more "
                    "profile points; bench/README.md).");
  prm.declare_entry("measured flanks", "false", Patterns::Bool(),
                    "Also the loaded contact of the measured flanks (Measured flanks section), "
                    "with the theoretical pair's compliances.");
}

void
LoadedScene::parse(ParameterHandler &prm)
{
  torques                     = get_doubles(prm, "torques");
  positions                   = prm.get_integer("positions per mesh cycle");
  cells.cells_across          = prm.get_integer("cells across");
  cells.cells_along           = prm.get_integer("cells along");
  cells.along_grading         = prm.get_double("cells along grading");
  cells.gap_band              = prm.get_double("gap band") * um;
  measured                    = prm.get_bool("measured flanks");
  follow_load                 = prm.get("table interpolation") == "load following";
  reference_positions         = get_integers(prm, "reference positions");
  reference_elements_per_cell = prm.get_double("reference elements per cell");
}

// The nominal tooth load F_t / (b m_n) of carburised test gears reaches about 400 MPa (FZG
// load stage 14 on the C pair: 415 MPa); beyond 500 MPa a warning. At 5000 MPa the root stress
// (a form factor of about 2.5 more) is some 6 times any steel's tensile strength: no gear
// carries it, refused; N mm typed in the N m field is the slip (1000 times).
void
check_torque(const std::string &parameter, double torque, const PairScene &pair,
             std::vector<std::string> &warnings)
{
  const PairScale s    = pair_scale(pair);
  const double    load = torque / s.pinion_radius / (s.face_width * s.module) / 1e6;
  check_plausible(parameter + " = " + plausible_number(torque) + " N m", load,
                  "the nominal tooth load F_t / (b m_n) [MPa] (pitch radius " +
                      plausible_number(s.pinion_radius / mm) + " mm, b " +
                      plausible_number(s.face_width / mm) + " mm, m_n " +
                      plausible_number(s.module / mm) + " mm)",
                  0, 500, 0, 5000,
                  {{1e-3, "N mm typed in a N m field (" + plausible_number(torque) +
                              " N mm = " + plausible_number(torque / 1000) + " N m)"}},
                  warnings);
}

void
LoadedScene::check(const PairScene &pair, const MeasuredScene &measured_flanks, bool run,
                   std::vector<std::string> &warnings) const
{
  const std::string where = "Loaded contact/" + pair.name + "/";
  if (run)
    for (const double t : torques)
      check_torque(where + "torques", t, pair, warnings);
  for (const int i : reference_positions)
    if (i >= positions)
      throw InputError(where + "reference positions: " + std::to_string(i) +
                       " is not a position of the mesh cycle (allowed: 0 to " +
                       std::to_string(positions - 1) + ")");
  if (measured && measured_flanks.source == MeasuredSource::none)
    throw InputError(where + "measured flanks = true needs measured flanks: set Measured flanks/" +
                     pair.name + "/source");
}
} // namespace gearkit
