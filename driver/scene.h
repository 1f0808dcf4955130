// The scene file: a deal.II ParameterHandler input with one subsection per stage, turned into
// plain data for the stage libraries (which never see a ParameterHandler).
//
// Every section is a struct that declares its parameters, parses them and checks them, side by
// side in one source file (deal.II step-44 style): scene_flanks.cc (Flanks/<pair>),
// scene_measured.cc, scene_tca.cc, scene_stiffness.cc (Finite elements, Loaded contact),
// scene_dynamics.cc, scene_train.cc, scene_notes.cc (Notes/<pair or train>: caveats for the
// report, in no cache key). declare() runs with the ParameterHandler inside the section's
// subsection, parse() likewise, check() afterwards with the rest of the scene at hand: every check
// that the scene alone allows runs when the scene is read, before any stage.
#pragma once

#include "dynamics/integrators.h"
#include "dynamics/sweep.h"
#include "dynamics/train.h"
#include "geometry/bevel_gear.h"
#include "geometry/involute_gear.h"
#include "stiffness/contact_cells.h"
#include "stiffness/half_space.h"
#include "study/misalignment_study.h"
#include "study/modification_grid.h"
#include "study/tolerance_study.h"
#include "tca/paper_mode.h"
#include "tca/tooth_pairs.h"
#include "tca/unloaded_tca.h"

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

namespace dealii
{
class ParameterHandler;
}

namespace gearkit
{
using dealii::ParameterHandler;
struct Scene;
struct TcaScene;

enum class PairType
{
  involute,    ///< spur or helical, parallel axes (pinion, gear)
  spiral_bevel ///< face-milled spiral bevel (bevel, mismatch)
};

/// A gear pair as the flank stage needs it: pinion (driver) and gear (driven).
struct PairScene
{
  std::string      name;
  PairType         type                = PairType::involute;
  int              grid_profile_points = 9; ///< stored flank grids
  int              grid_face_points    = 29;
  InvoluteGearData pinion;
  InvoluteGearData gear;
  BevelPairDesign  bevel;
  PinionMismatch   mismatch;
  /// Spiral bevel: predesigned transmission error amplitude [rad] the modified roll is
  /// synthesised for (flanks stage); 0 = use mismatch.modified_roll_2c as given.
  double transmission_error_amplitude = 0;

  static void
  declare(ParameterHandler &prm);
  void
  parse(ParameterHandler &prm);
  /// Both members build and mesh with each other; modifications fit on the teeth. Before
  /// that, the values a unit slip gives (face width against the module, density, angles in
  /// radians) are refused by name, or added to `warnings` where a real design can have them.
  void
  check(std::vector<std::string> &warnings) const;
  /// The involute members, each with its start of active profile (where f_Halpha's evaluation
  /// range starts) from the other in the design mesh, at the zero-backlash working centre
  /// distance (geometry: create_pair). Only for what does not depend on the operating state
  /// (radii, a_w, masses, checks): an analysis takes the members at the centre distance it runs
  /// at (below).
  std::pair<std::shared_ptr<const InvoluteGear>, std::shared_ptr<const InvoluteGear>>
  involute_members() const;
  /// The involute members as they run at `operating_centre_distance` (the distance of the axes
  /// [m], > 0): each with its start of active profile, and so its profile evaluation range, from
  /// the other's tip circle on the line of action there.
  std::pair<std::shared_ptr<const InvoluteGear>, std::shared_ptr<const InvoluteGear>>
  involute_members(double operating_centre_distance) const;
  /// The same at the centre distance the pair runs at in the contact analysis `tca`.
  std::pair<std::shared_ptr<const InvoluteGear>, std::shared_ptr<const InvoluteGear>>
  involute_members(const TcaScene &tca) const;
  /// The centre distance an involute pair runs at in `tca`: its centre distance (0: the
  /// zero-backlash working one) plus the centre distance error, with the offset
  /// (operating_centre_distance in tca/assembly.h; the angles do not change it).
  double
  operating_centre_distance(const TcaScene &tca) const;
};

/// Tooth counts (z1, z2) of a pair of either type.
inline std::pair<int, int>
pair_teeth(const PairScene &p)
{
  return p.type == PairType::spiral_bevel ? std::pair{p.bevel.pinion_teeth, p.bevel.gear_teeth}
                                          : std::pair{p.pinion.teeth, p.gear.teeth};
}

/// Where the "measured" flanks of a pair come from.
enum class MeasuredSource
{
  none,
  virtual_cmm,     ///< sampled from the theoretical flanks (a perfect CMM)
  synthesised,     ///< theoretical + form error, waviness, roughness, noise, pitch errors
  cmm_files,       ///< one CMM point file per member
  topography_files ///< one topography deviation-grid file per member
};

struct MeasuredScene
{
  MeasuredSource   source = MeasuredSource::none;
  std::string      pinion_file, gear_file; ///< absolute paths (resolved against the scene file)
  int              profile_points = 9, face_points = 29;
  double           edge_margin = 0; ///< fraction of each parameter range left out at the edges
  std::vector<int> pinion_teeth, gear_teeth; ///< teeth to measure (empty = all)
  /// Files: every point within this distance of its nominal flank [m] (plausibility).
  double        nominal_tolerance   = 100e-6;
  unsigned long seed                = 1;
  double        form_error          = 0;
  double        waviness_amplitude  = 0;
  double        waviness_wavelength = 0;
  double        roughness           = 0;
  double        noise               = 0;
  double        pitch_error         = 0;

  static void
  declare(ParameterHandler &prm);
  /// File names relative to the scene's folder.
  void
  parse(ParameterHandler &prm, const std::string &scene_directory);
  void
  check(const PairScene &pair) const;
};

/// Unloaded tooth contact analysis of a pair.
struct TcaScene
{
  double       centre_distance = 0; ///< [m]; 0 = the zero-backlash working centre distance
  Misalignment misalignment;        ///< (for spiral bevel pairs: offset, axial shifts, shaft angle)
  TcaOptions   options;
  int          harmonics        = 10;      ///< mesh orders reported
  double       elastic_approach = 6.32e-6; ///< for the contact ellipses [m]
  /// Also run the fast discrete-point analysis on the pair's measured flanks (/measured).
  bool measured = false;
  /// Method for the measured flanks: the fast discrete-point analysis (false) or the seed's
  /// literal point-cloud method (paper mode, true) with the settings in `paper`.
  bool             paper_mode = false;
  PaperModeOptions paper;
  /// Analyse the whole hunting-tooth cycle (lcm(z1, z2) mesh cycles) and report the spectrum in
  /// pinion shaft orders (per-tooth errors give shaft orders and mesh sidebands).
  bool hunting = false;

  static void
  declare(ParameterHandler &prm);
  void
  parse(ParameterHandler &prm);
  /// Completes the options that follow from the pair (the hunting cycle's mesh cycles, the
  /// paper mode's copy of the positions) and checks the assembly: a centre distance at which the
  /// teeth would overlap, or not reach each other, is refused; a total contact ratio eps_gamma
  /// below 1 there (a gap in the contact every mesh cycle) is added to `warnings`.
  void
  complete_and_check(const PairScene &pair, const MeasuredScene &measured_flanks,
                     std::vector<std::string> &warnings);
};

/// Finite-element compliance of a pair's members (stage "compliance").
struct FeScene
{
  int      segment_teeth = 7;                                ///< teeth per member segment
  bool     hold_cuts     = true;                             ///< radial cuts held (else free)
  bool     whole_pinion = false, whole_gear = false;         ///< all teeth on the rim (involute)
  bool     whole_rim_pinion = false, whole_rim_gear = false; ///< the segment on the whole rim
  bool     cyclic              = true; ///< unit loads on the middle tooth, read for all turned
  double   flank_size          = 0.25; ///< element size at the flanks / m_n
  double   far_size            = 1.0;  ///< element size toward the bore / m_n
  double   other_size          = 0;    ///< at fillets and unloaded flanks / m_n; 0 = flank size
  double   fillet_size         = 0;    ///< at the root fillets / m_n; 0 = flank or other size
  unsigned degree              = 2;
  double   depth               = 3;    ///< response depth in flank element sizes
  bool     analytic_near_field = true; ///< near field = analytic (else: response depth)
  double   near_field_radius   = 2;    ///< [m_n]
  int      n_u = 9, n_v = 0;           ///< load grid per flank (n_v 0: from the face width)
  bool     graded_grid = true;         ///< load grid clustered towards the flank's edges
  /// Also the tables on a mesh of twice the element sizes at the flanks (coarsened(); 1.5 or
  /// 1.25 times where that cannot be meshed): the stiffness stage estimates each K_m's error.
  bool error_estimate = true;
  /// deal.II refinements at the loaded flanks of a segment meshed 2^k times coarser, and the
  /// depth they reach [unrefined flank element sizes] (MemberComplianceOptions).
  unsigned local_refinements = 0;
  double   refine_depth      = 1;
  Material material; ///< both members

  static void
  declare(ParameterHandler &prm);
  void
  parse(ParameterHandler &prm);
  /// Its own consistency (odd segment teeth, face grid points, Young's modulus); with `run` (the
  /// finite elements run: stage compliance) also against the pair: segment teeth within the
  /// smaller member's teeth, whole gears and rims for spur and helical pairs only, and the
  /// element degree against the Poisson's ratio (volumetric locking: refused or a warning).
  void
  check(const PairScene &pair, bool run, std::vector<std::string> &warnings) const;
  /// The same with the element sizes at the flanks, fillets and other flanks times `factor`
  /// (the far size at least the new flank size): what the error estimate changes. With local
  /// refinements and factor 2: one refinement less of the same segment mesh.
  FeScene
  coarsened(double factor) const;
  /// Whether the pinion's (else the gear's) member is modelled whole.
  bool
  whole(bool pinion) const
  {
    return pinion ? whole_pinion : whole_gear;
  }
  /// Whether the pinion's (else the gear's) segment sits on the whole rim and bore.
  bool
  whole_rim(bool pinion) const
  {
    return pinion ? whole_rim_pinion : whole_rim_gear;
  }
};

/// Loaded contact over the mesh cycle (stage "stiffness").
struct LoadedScene
{
  std::vector<double> torques{100}; ///< pinion torques [N m]
  int                 positions = 20;
  ContactCellOptions  cells;
  bool                measured = false; ///< also the measured flanks, compliances reused
  bool follow_load = false; ///< the tables read following the load (FlankGridSpec::follow_load)
  /// Positions (indices into the mesh cycle) solved again in reference mode, with VTU files.
  std::vector<int> reference_positions;
  double           reference_elements_per_cell = 0.5;

  static void
  declare(ParameterHandler &prm);
  void
  parse(ParameterHandler &prm);
  /// With `run` (the stiffness stage runs) also the torques' plausibility.
  void
  check(const PairScene &pair, const MeasuredScene &measured, bool run,
        std::vector<std::string> &warnings) const;
};

/// Design study of a pair on its compliance (stage "study"): a micro-geometry map (the grid of
/// modification variants over the torques) or a tolerance Monte Carlo (samples of the design
/// within ISO 1328-1 classes).
struct StudyScene
{
  enum class Kind
  {
    microgeometry_map,
    tolerances,
    misalignments
  };
  Kind                kind = Kind::microgeometry_map;
  std::vector<double> torques; ///< pinion torques [N m], ascending; empty: Loaded contact's
  double              design_torque = 0;  ///< [N m], among the torques; 0: none
  int                 positions     = 40; ///< per mesh cycle
  double              widening      = 2;  ///< of the fixed contact zones (FixedZone)
  int                 harmonics     = 4;  ///< mesh orders of e_L summarised
  GridMembers         members       = GridMembers::both;
  std::vector<ModificationAxis> axes; ///< in the order of modification_field_names
  /// Misalignments: the grid's axes over Misalignment fields (misalignment_field_names), each
  /// replacing the TCA section's value; the contact pattern's raster on the gear flank.
  std::vector<GridAxis> misalignment_axes;
  int                   profile_bins = 16, face_bins = 40;
  /// Tolerances: the sampling (ISO 1328-1 classes, distribution, seed), the samples, the mesh
  /// cycles each runs over (0: a pinion revolution).
  ToleranceSampling sampling;
  int               samples     = 200;
  int               mesh_cycles = 0;

  static void
  declare(ParameterHandler &prm);
  void
  parse(ParameterHandler &prm);
  /// With `run` (the study stage runs): an involute pair (maps and tolerances), plausible
  /// torques, the design torque among them, the grid's size.
  void
  check(const PairScene &pair, const LoadedScene &loaded, bool run,
        std::vector<std::string> &warnings) const;
  /// kind = misalignments: a known grid, no modification values, misalignments within the
  /// face width (else a unit slip), plausible torques.
  void
  check_misalignments(const PairScene &pair, const LoadedScene &loaded,
                      std::vector<std::string> &warnings) const;
  /// The torques the study runs: its own, else the Loaded contact section's; ascending.
  std::vector<double>
  study_torques(const LoadedScene &loaded) const;
};

/// 14-DOF pair dynamics (stage "dynamics"): the model's parameters and the speed sweep.
struct DynamicsScene
{
  bool                fe_stiffness   = true;   ///< K_m over the mesh cycle from the stiffness stage
  double              mesh_stiffness = 0;      ///< else constant K_m [N/m] ...
  double              stiffness_variation = 0; ///< ... varying by this fraction (first mesh order)
  bool                tca_transmission_error       = true; ///< E_t from the TCA, else analytic:
  double              transmission_error_amplitude = 0;    ///< E_t = this sin(2 pi phase) [m]
  double              torque = 0; ///< pinion (motor) torque [N m]; K_m from the nearest FE torque
  PairModelParameters model;      ///< axes, the mesh tables and the teeth come from the pair
  double              speed_from = 0, speed_to = 0; ///< [rad/s]
  int                 speeds = 0;
  /// The sweep as the dynamics library runs it (dynamics/sweep.h), its defaults the library's:
  /// settle and record cycles, steady tolerance, accuracy, time series speeds [rad/s], spectrum
  /// orders, and in `run` the integrator (the scene's default: Newmark, the fast path), the
  /// least Newmark steps per mesh cycle and the samples recorded per mesh cycle (32, or the
  /// steps where fewer: the multiple Newmark's steps come in). The speeds and the torques are
  /// the stage's.
  SweepOptions sweep = newmark_sweep();
  /// The tables from the TCA at the position the static load deflects the pair to
  /// (dynamics/deflection.h), else as assembled.
  bool system_deflection = true;
  /// Excitations swept: the theoretical flanks' tables, and the measured flanks' (needs the
  /// TCA of the measured flanks).
  bool theoretical = true, measured = false;
  /// Mesh cycles of the measured flanks' TCA that form one period of their excitation (0: all
  /// the TCA computed - the hunting cycle when it ran over it).
  int excitation_cycles = 0;
  /// Each sweep in this many blocks of speeds (run in parallel on threads and MPI processes),
  /// each but the first started this many speeds early.
  int sweep_blocks = 1, warmup_speeds = 3;

  /// The library's sweep options with the integrator Newmark.
  static SweepOptions
  newmark_sweep();
  static void
  declare(ParameterHandler &prm);
  void
  parse(ParameterHandler &prm);
  /// With `run` (the dynamics is an output) also the plausibility of the model: masses and
  /// inertias against those the geometry implies, stiffness magnitudes, bearing positions
  /// against the member's size, speeds against the pitch-line velocity a gear survives;
  /// refused by name, or added to `warnings` where a real design can have them.
  void
  check(const PairScene &pair, const TcaScene &tca, bool run,
        std::vector<std::string> &warnings) const;
  void
  check_plausibility(const PairScene &pair, std::vector<std::string> &warnings) const;
};

/// One body of a gear train (Train/<train>/Bodies/<body>): a rigid rotor with its gears.
struct TrainBodyScene
{
  std::string name;
  /// Inertia about its axis [kg m^2]; auto: the polar inertias of its gears from their
  /// geometry (InvoluteGear::mass_properties, chipped teeth included) plus shaft_inertia.
  bool   inertia_auto  = false;
  double inertia       = 0;
  double shaft_inertia = 0;
  /// Initial speed [rad/s]; kinematic: from the first body with a number, through the ratios.
  bool        kinematic_speed = true;
  double      initial_speed   = 0;
  double      initial_angle   = 0; ///< [rad]
  bool        constant_speed  = false;
  TorqueLaw   torque; ///< SI
  bool        has_crank = false;
  CrankSlider crank;
  /// Axis position in the plane of the train [m] (optional): fixes the centre distances.
  bool   placed = false;
  double x = 0, y = 0;
  /// A torsional shaft to another body (empty: none): stiffness [N m/rad], damping [N m s/rad].
  std::string shaft_to;
  double      shaft_stiffness = 0, shaft_damping = 0;
};

/// Where a mesh starts within its backlash.
enum class MeshStart
{
  centre, ///< in the middle of the backlash
  drive,  ///< the drive flanks of pairing 0 touching
  coast   ///< the coast flanks of pairing 0 touching
};

/// One mesh of a train (Train/<train>/Meshes/<mesh>): an involute pair between two bodies.
struct TrainMeshScene
{
  std::string name, pair, pinion_body, gear_body;
  /// Circumferential backlash on the operating pitch circles [m], added by the centre
  /// distance (centre_distance_for_backlash from the pair's TCA centre distance); 0: the TCA
  /// centre distance as it is.
  double backlash = 0;
  double pinion_angle =
      0; ///< pinion angle on its body [rad] (pairing 0 at the line of centres at 0)
  MeshStart start = MeshStart::centre;
  /// The elastic contact force: IMPACT per tooth pair (false) or the stiffness stage's K_m
  /// over the mesh cycle (TrainMesh::mesh_stiffness), at the loaded-contact torque nearest
  /// `stiffness_torque` [N m] (0: the largest).
  bool   fe_stiffness     = false;
  double stiffness_torque = 0;
};

/// A gear train's impact dynamics (stage "train", section Train/<train>).
struct TrainScene
{
  std::string                 name;
  std::vector<TrainBodyScene> bodies;
  std::vector<TrainMeshScene> meshes;
  ImpactLaw                   law;    ///< SI, every mesh
  ToothPairOptions            curves; ///< of every mesh's tooth pair tables
  TrainRunOptions             run;
  /// Spectra of the mesh forces from this time on [s] (0: the second half of the run), lines
  /// looked for at GMF harmonics 1..harmonics and sidebands 1..sidebands shaft orders away.
  double spectrum_start = 0;
  int    harmonics = 4, sidebands = 2;
  double spectrum_max_frequency = 0; ///< stored bins up to this [Hz] (0: all)
  /// Spectrogram of the first mesh's force: window [s], overlap, top frequency [Hz] (0: Nyquist).
  double spectrogram_window = 0.05, spectrogram_overlap = 0.8, spectrogram_max_frequency = 0;
  /// The body whose mean speed over the spectrum interval sets the kinematic frequencies (empty:
  /// the first constant-speed body, else the first body).
  std::string reference_body;
  /// The most estimated run time allowed [s] (train_cost_estimate); beyond it the scene is
  /// refused before any stage.
  double maximum_cost = 600;

  /// Declares the section of a train with these body and mesh names.
  static void
  declare(ParameterHandler &prm, const std::vector<std::string> &bodies,
          const std::vector<std::string> &meshes);
  void
  parse(ParameterHandler &prm);
  /// Pairs named and involute, bodies named, no mesh from a body to itself, inertias, ratios
  /// and centre distances that close, a speed to start from, constant speeds that agree with
  /// the ratios, plausible pitch-line velocities, run and spectrum settings, and (with `run`:
  /// the train is an output) an estimated cost within maximum_cost. Values a real design can
  /// have but that look like a slip go to `warnings`.
  void
  check(const Scene &scene, bool run, std::vector<std::string> &warnings) const;
  /// The pitch-line velocities at the initial speeds, and the mesh frequencies against the
  /// sample rate (check()).
  void
  check_plausibility(const Scene &scene, const TrainModel &model,
                     std::vector<std::string> &warnings) const;

  /// Index of a body by name (-1: none).
  int
  body_index(const std::string &body) const;
  /// The reference body's index.
  int
  reference() const;
  /// The train model without its tooth pair tables (the train stage adds those and the mesh
  /// angles): bodies with their inertias (auto: from the gears' geometry) and initial speeds
  /// (kinematic ones through the ratios), meshes with their bodies, tooth counts, base radii and
  /// contact law.
  TrainModel
  model(const Scene &scene) const;
};

/// What a train's run will cost: the CVODE steps and the run time they take on the 2-core
/// machine of bench/README.md (bench_train_startup), estimated from the initial speeds.
struct TrainCost
{
  double mesh_cycles = 0; ///< of every mesh over the run
  double steps       = 0;
  double seconds     = 0;
};
TrainCost
train_cost_estimate(const TrainScene &train, const TrainModel &model);

/// The centre distance of a train's mesh [m]: the pair's TCA centre distance (0 there: the
/// zero-backlash working one) opened by the mesh's backlash.
double
train_mesh_centre_distance(const Scene &scene, const TrainMeshScene &mesh);

/// A caveat carried with the numbers (section Notes/<name>, optional): the report shows `text`
/// next to the numbers of `area` of the pair or train `name`. Notes enter no stage's cache key:
/// changing one recomputes nothing.
struct SceneNote
{
  std::string name; ///< a pair of Scene/pairs or a train of Scene/trains
  std::string area; ///< one of note_areas()
  std::string text; ///< one line: no tabs or line breaks (those read as spaces), not empty
};

/// The report areas a note can qualify, in the report's order, as the entries of Notes/<name>
/// name them: gear data, unloaded TCA, loaded contact, dynamics, gear train.
const std::vector<std::string> &
note_areas();

/// Section Notes/<name> (scene_notes.cc): one optional text per report area.
struct NotesScene
{
  static void
  declare(ParameterHandler &prm);
  /// The entries that are set (not empty) as notes of `name`, in the order of note_areas().
  static std::vector<SceneNote>
  parse(ParameterHandler &prm, const std::string &name);
  /// The names the scene opens under Notes must each be a pair or a train of the scene; else an
  /// InputError naming the section, the name and the pairs and trains allowed.
  static void
  check_names(const std::vector<std::string> &names, const std::vector<std::string> &pairs,
              const std::vector<std::string> &trains);
};

/// The notes as results.h5 carries them (root attribute `notes`): one line per note,
/// "<name>\t<area>\t<text>\n"; empty without notes.
std::string
notes_text(const std::vector<SceneNote> &notes);

struct Scene
{
  std::string                          file;    ///< the scene file as given
  std::string                          name;    ///< results go to <output root>/<name>/
  std::vector<std::string>             outputs; ///< what the user asked for
  std::vector<PairScene>               pairs;
  std::map<std::string, MeasuredScene> measured; ///< by pair name
  std::map<std::string, TcaScene>      tca;      ///< by pair name
  std::map<std::string, FeScene>       fe;       ///< by pair name
  std::map<std::string, LoadedScene>   loaded;   ///< by pair name
  std::map<std::string, DynamicsScene> dynamics; ///< by pair name
  std::map<std::string, StudyScene>    study;    ///< by pair name
  std::vector<TrainScene>              trains;   ///< Train/<train>, in the order of Scene/trains
  /// Notes/<name>: the pairs' notes in the order of Scene/pairs, then the trains' in the order
  /// of Scene/trains, each's in the order of note_areas(). In no stage's cache key.
  std::vector<SceneNote> notes;
  /// The scene's parameters in canonical text form, one block per top-level subsection
  /// ("Scene", "Flanks", "Measured flanks", ..., "Notes" where the scene has notes); the cache
  /// keys hash the blocks of their stages' sections (Notes in none).
  std::map<std::string, std::string> sections;
  /// Values a real design can have but that look like a unit slip or a typing error (the
  /// parameter, the value, the plausible range, the likely slip): the run goes on, and the log,
  /// results.h5 (root attribute `warnings`) and report.html show each loudly.
  std::vector<std::string> warnings;

  const PairScene &
  pair(const std::string &name) const;

  /// Section "Scene": name, outputs, pairs, trains.
  static void
  declare(ParameterHandler &prm);
};

/// A unit slip a plausibility check looks for: the value times `factor` is what the user
/// meant if it was typed in the other unit; `what` says so with both values ("metres in a mm
/// field: 0.01 m = 10 mm").
struct UnitSlip
{
  double      factor;
  std::string what;
};

/// A plausibility check (scene_flanks.cc). `parameter` names the entry and its value with its
/// unit ("Flanks/p/Pinion/face width = 0.01 mm"), `measure` is the quantity judged (the value or
/// a ratio such as b / m_n) and `measure_text` says what it is. Within [plausible_low,
/// plausible_high]: nothing. Outside [possible_low, possible_high], where no real design goes:
/// an InputError naming the parameter, the value, the plausible range and the first slip that
/// brings the measure into the plausible range. In between: the same words in `warnings`.
void
check_plausible(const std::string &parameter, double measure, const std::string &measure_text,
                double plausible_low, double plausible_high, double possible_low,
                double possible_high, const std::vector<UnitSlip> &slips,
                std::vector<std::string> &warnings);

/// A number as the plausibility messages print it (4 significant digits).
std::string
plausible_number(double x);

/// The scales of a pair the plausibility checks compare with: the pinion's pitch radius (a
/// bevel pinion's at the mean point), the face width (the narrower member's) and the normal
/// module (a bevel pair's mean normal module) [m].
struct PairScale
{
  double pinion_radius = 0, face_width = 0, module = 0;
};
PairScale
pair_scale(const PairScene &pair);

/// A pinion torque [N m] against what the teeth carry: the nominal tooth load F_t / (b m_n)
/// [MPa] (scene_stiffness.cc).
void
check_torque(const std::string &parameter, double torque, const PairScene &pair,
             std::vector<std::string> &warnings);

/// The index of the loaded contact's torque a K_m table is taken at (the dynamics' pinion
/// torque, a train mesh's stiffness torque): the nearest to `wanted` (the first of two as near),
/// the largest where `wanted` is 0. K_m is the secant stiffness at one load: read_scene warns
/// where the torque asked for is not one the loaded contact computes.
std::size_t
nearest_torque(const std::vector<double> &torques, double wanted);

/// Reads and checks a scene file. Throws InputError naming the file, line, parameter and what is
/// allowed. Input files named relative (CMM files) are found relative to `base_directory`, by
/// default the scene file's folder (the Python module reads a scene it rewrote in a temporary
/// folder against the original's).
Scene
read_scene(const std::string &file, const std::string &base_directory = "");

/// The fully documented parameter list (defaults, patterns, help) for a scene with the given
/// pair names.
void
print_parameters(std::ostream &out, const std::vector<std::string> &pairs = {"pair"});
} // namespace gearkit
