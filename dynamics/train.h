// Impact dynamics of a gear train (seeds 001 and 002): rigid rotors on fixed frictionless
// bearings, joined by gear meshes with backlash and by torsional shafts, optionally loaded by a
// crank-slider. Every body turns about its own fixed axis; its angle theta and speed are counted
// in the sense the train turns it when running forward (so a forward-running train has positive
// speeds everywhere: the sign flips of external meshes are in the meshes, not in the states).
//
// Tooth contact is per tooth pair (base/tooth_pairs.h): for every pairing near the line of action
// on both flanks the penetration d along the actual contact normal, from the members' flanks,
// so backlash, eccentric or chipped teeth and pitch errors enter by geometry. Each touching pair
// carries the MSC ADAMS IMPACT force (impact_force). The pinion of mesh m sits on body
// `driver` with phi = theta_driver + phi0, its gear on body `driven` with psi = theta_driven +
// psi0 (the TCA's angles).
//
// Equations (Lagrange; the forces are the derivatives of the potentials, so that the undamped
// model conserves energy exactly):
//   J_i(theta_i) theta_i'' + J_i'(theta_i) theta_i'^2 / 2 = T_i(t, theta_i') - sum_pairs F
//   dd/dtheta_i
//                                                          - shaft torques
// with J_i' of a crank-slider's configuration-dependent inertia. A body at constant speed is
// driven by whatever torque holds it (its work is counted).
//
// Time integration: CVODE (dynamics/cvode_solver.h; Adams with fixed-point iteration for soft
// contacts, BDF with Newton for stiff ones: TrainIntegrator) step by step, with event location
// where a mesh's flank side or one of its tooth pairs starts or stops touching and where a
// touching pair passes a kink of its tooth pair curve (the method restarts there), the forces' and
// penetrations' peaks located inside the steps (the cubic through a piece's end values and rates
// dF/dt, from the accelerations, where the rate falls through zero; golden-section search for a
// sharp peak a step strides over), the energy balance integrated alongside:
//   work of the torques = kinetic energy change + potential energy + dissipated energy.
// The steps never depend on the output rate: the samples are interpolated at the output times
// from the method's polynomial (or, recorded without aliasing, averaged from the cubic Hermite
// interpolant of every step piece's end values and rates), and the extremes, counts and
// impulses come from the steps and roots themselves, so they are the same at any output rate.
// A contact that changes and changes back inside a step is looked for at the step's midpoint
// where a side's touch function, as the cubic through its ends' values and rates, comes near
// zero.
#pragma once

#include "base/tooth_pairs.h"

#include <functional>
#include <string>
#include <vector>

namespace gearkit
{
/// MSC ADAMS IMPACT: for penetration d > 0, F = K d^e + STEP(d, 0, 0, d_max, c_max) d', F >= 0
/// (the reference writes - STEP x' with x the distance, x' = -d'), STEP the cubic smooth step
/// from 0 at d = 0 to c_max at d >= d_max; F = 0 without contact.
struct ImpactLaw
{
  double stiffness = 0; ///< K [N / m^e]
  double exponent  = 1; ///< e (>= 1)
  double damping   = 0; ///< c_max [N s / m]
  double depth     = 0; ///< d_max [m] (> 0 when damping > 0)
};

/// IMPACT force [N] at penetration d [m] and rate d' [m/s].
double
impact_force(const ImpactLaw &law, double d, double d_rate);
/// Elastic energy K d^(e+1) / (e+1) [J] stored at penetration d (0 for d <= 0).
double
impact_energy(const ImpactLaw &law, double d);
/// The law's stiffness in SI from one given in model units of length (ADAMS: force / length^e):
/// K_SI = K_model / unit^e, e.g. unit = 1e-3 for N/mm^e, 0.0254 for force per inch^e.
double
impact_stiffness_si(double stiffness, double exponent, double length_unit);

/// T(t, w) = constant + step (1 - exp(-t / tau)) - viscous w [N m] (tau = 0: the step at once).
struct TorqueLaw
{
  double constant = 0, step = 0, time_constant = 0;
  double viscous = 0; ///< [N m s/rad]
  double
  operator()(double t, double speed) const;
};

/// Crank-slider on a body (the crank): crank radius r, connecting rod of length l (centre of
/// mass at l_c from the crank pin, mass m_r, inertia J_r about its centre of mass), piston of
/// mass m_s moving along the line through the crank axis at crank angle 0 (theta = 0: top dead
/// centre), optional constant gas force on the piston (> 0 pushes it toward the crank axis).
struct CrankSlider
{
  double crank_radius = 0, rod_length = 0, rod_centre = 0; ///< r, l, l_c [m]
  double rod_mass = 0, rod_inertia = 0, piston_mass = 0;   ///< [kg], [kg m^2], [kg]
  double piston_force  = 0;                                ///< [N]
  double crank_angle_0 = 0;                                ///< crank angle at body angle 0 [rad]
  /// Configuration-dependent inertia J(theta) it adds to the crank, and dJ/dtheta.
  std::pair<double, double>
  inertia(double crank_angle) const;
  /// Piston position from the crank axis [m] and its derivative by the crank angle.
  std::pair<double, double>
  piston(double crank_angle) const;
};

struct TrainBody
{
  std::string name;
  double      inertia       = 0; ///< about its axis, gears and shaft included [kg m^2]
  double      initial_angle = 0; ///< [rad]
  double      initial_speed = 0; ///< [rad/s]
  /// Held at this constant speed from t = 0 (its torque law is then ignored).
  bool        constant_speed = false;
  TorqueLaw   torque;
  bool        has_crank = false;
  CrankSlider crank;
};

struct TrainMesh
{
  std::string     name;
  int             driver = 0, driven = 1;               ///< body indices: pinion (phi), gear (psi)
  double          pinion_angle_0 = 0, gear_angle_0 = 0; ///< phi0, psi0 [rad]
  ToothPairTables teeth;
  ImpactLaw       law;
  /// Base radii [m] of the relative displacement along the line of action
  /// S = R_g ((z1/z2) phi + c - psi) (the seeds' S up to its sign: here S > 0 is the pinion
  /// ahead; for perfect flanks S >= B/2 is drive contact, S <= -B/2 coast contact), c the
  /// band centre (band_centre).
  double pinion_base_radius = 0, gear_base_radius = 0;
  /// Optional mesh stiffness K_m [N/m] from finite elements (the stiffness stage's
  /// K_m = F / (lambda (e_L - e_0)) at one torque): uniform samples over one pinion mesh cycle
  /// 2 pi / z1 from pinion angle `mesh_stiffness_start` (the TCA's phi), repeated, linear in
  /// between. When given it replaces the elastic part of IMPACT: on each side the deepest
  /// touching pair carries K_m(phi) d_max + STEP(d_max, 0, 0, d_max, c_max) d_max' (>= 0), all
  /// the side's elastic force - by K_m's definition its deflection lambda (e_L - e_0) is the
  /// penetration of the pair that touches first. The stored energy is K_m d_max^2 / 2; the
  /// work of the stiffness variation (K_m'(phi) phi' d_max^2 / 2) counts as work done on the
  /// train. K_m belongs to one load: it is the secant stiffness there.
  std::vector<double> mesh_stiffness;
  double              mesh_stiffness_start = 0;
};

/// The gear angle offset c of the backlash band's centre [rad]: the mean of band_edges. A mesh
/// placed with gear_angle_0 = c + (z1/z2) pinion_angle_0 starts in the middle of its backlash.
double
band_centre(const ToothPairTables &teeth);
/// The drive and coast touch offsets [rad] at the centre (local angle 0) of the nominal teeth:
/// the class pair of the pinion's and the gear's most common classes (a defective tooth does not
/// move the band of the others; when no class is more common than another, or that class pair
/// has no curve, pairing 0's classes). The mesh's relative displacement S is r_b2 (coast - drive)
/// / 2 at the nominal teeth's drive contact and minus that at their coast contact (half the
/// normal backlash for perfect flanks).
std::pair<double, double>
band_edges(const ToothPairTables &teeth);

/// A torsional shaft between two bodies turning together (ratio 1): torque k (theta_b -
/// theta_a) + c (w_b - w_a) on a, its opposite on b.
struct TrainShaft
{
  int    a = 0, b = 1;
  double stiffness = 0, damping = 0; ///< [N m/rad], [N m s/rad]
};

struct TrainModel
{
  std::vector<TrainBody>  bodies;
  std::vector<TrainMesh>  meshes;
  std::vector<TrainShaft> shafts;
  /// Throws InputError naming the body, mesh or shaft and the parameter: negative or zero
  /// inertias, unknown bodies, a mesh from a body to itself, curves without samples, bad laws.
  void
  check() const;
};

/// CVODE's method for the train. Adams (orders up to 12, fixed-point iteration: no Jacobian)
/// for contacts whose damping acts slower than about 10 us; BDF (Newton, dense Jacobian) for
/// stiff ones, where the iteration of Adams would not converge at the steps accuracy needs.
/// automatic: BDF where some mesh's damping time constant m_e / c_max (or a shaft's J / c) is
/// below 10 us (stiff_time_constant), Adams otherwise.
enum class TrainIntegrator
{
  adams,
  bdf,
  automatic
};

/// Below this damping time constant [s] a train is stiff (TrainIntegrator::automatic).
constexpr double stiff_time_constant = 1e-5;

/// The shortest damping time constant of the train [s]: m_e / c_max of each mesh's contact
/// (m_e = 1 / (r_bp^2 / J_p + r_bg^2 / J_g), bodies held at constant speed infinitely heavy)
/// and J_e / c of each shaft's damping (J_e = 1 / (1 / J_a + 1 / J_b)); infinite without damping.
double
damping_time_constant(const TrainModel &model);

/// The method `automatic` stands for with this model (the others as given).
TrainIntegrator
resolve_integrator(const TrainModel &model, TrainIntegrator method);

struct TrainRunOptions
{
  /// Names the run on a progress line over its samples (base/progress.h); empty: none.
  std::string     progress;
  double          duration    = 0.1;  ///< [s]
  double          sample_rate = 20e3; ///< output samples per second
  TrainIntegrator method      = TrainIntegrator::automatic;
  /// Local error tolerances: relative, and absolute as a length along the contact normal [m]
  /// (angles: this over the largest base radius; speeds: over it and the shortest contact
  /// time scale).
  /// The default relative 7e-9 locates the force peaks within 0.1 % of a run at 1e-12
  /// (seed 002's 3 s start-up with Adams: 9e-5, energy balance 3e-7, in 9.7 s; a stiff
  /// damped driven run with BDF: balance a few 1e-6). 1e-10 holds the energy balance to 1e-6 in the
  /// tests and cases; the absolute 1e-12 m matters there too (seed 002's damped contact:
  /// 1e-9 and 1e-10 m leave 4e-5: a speed error dw becomes a damping force error c r_b dw, and
  /// the drive's work balances only as well as the speeds are held).
  double relative_tolerance = 7e-9, absolute_tolerance = 1e-12;
  /// Error test of the energy balance's quadratures (work, dissipated energy), relative and
  /// absolute as a share of the initial kinetic energy (at least 1 uJ); 0: the relative
  /// tolerance. Their local errors add up over the steps: a long run whose work is large
  /// against its energies (a constant-speed drive against resistive torques) needs it smaller.
  double energy_tolerance = 0;
  /// CVODE steps allowed in the whole run: beyond, a clear failure, never a hang.
  long max_steps = 20000000;
  /// Pairings examined on each side of the one at the line of centres.
  int pairings_each_side = 3;
  /// Angles, speeds and mesh forces recorded without aliasing (base/decimator.h: quadratic
  /// B-spline averages of the integrator's solution at 8 points per output interval, decimated
  /// through a 70 dB low-pass; flat to 0.4 times the sample rate, nothing folds back from above
  /// half of it; the samples then lie on whole output intervals, k / sample_rate <= duration);
  /// false: the solution's point values at the sample times (they alias). S follows the angles;
  /// the touching pairs and the energies are point values either way.
  bool anti_alias = true;
};

/// One contact of a mesh's flank side, from the located touch to the located separation.
struct TrainImpact
{
  int    side       = 0;          ///< drive_side or coast_side
  double touch      = 0;          ///< [s]
  double separation = -1;         ///< [s] (-1: still touching at the end of the run)
  double peak = 0, peak_time = 0; ///< the side's largest force in the contact [N], its time [s]
  double impulse = 0;             ///< integral of the side's force over the contact [N s]
};

/// One mesh's outputs: its series at the sample times; its extremes, counts and contacts from
/// the continuous solution, the same at any output rate.
struct MeshSeries
{
  std::vector<double> relative; ///< S [m]
  std::vector<double> force;    ///< normal force, drive flanks + and coast - [N]
  /// Force magnitude, drive + coast flanks [N] (|force| unless both touch), the spectra's
  /// signal: recorded as its own channel, since |.| of anti-aliased samples would fold again
  std::vector<double> magnitude;
  std::vector<int>    pairs;             ///< tooth pairs touching
  std::size_t         impacts       = 0; ///< first touches of a side after separation
  std::size_t         drive_impacts = 0, coast_impacts = 0;
  /// Largest force of a side [N] and its time [s]: at every step's end, touch and separation,
  /// and at every peak located inside a step (where the side's force rate dF/dt falls through
  /// zero)
  double                   max_force = 0, max_force_time = 0;
  std::vector<TrainImpact> contacts; ///< every contact, in the order of their touches
  /// Deepest penetration of a tooth pair at every step's end and located event [m]: the tooth
  /// pair curves must
  /// reach this far beyond the conjugate touch (tca/tooth_pairs.h: their recess), or pairs leave
  /// their curves while still touching (their force and stored energy lost at once).
  double max_penetration = 0;
  double first_contact   = -1; ///< time of the first touch [s] (-1: none)
};

struct TrainResult
{
  std::vector<double>              t;            ///< [s]
  std::vector<std::vector<double>> angle, speed; ///< [body][sample] [rad], [rad/s]
  std::vector<MeshSeries>          meshes;
  /// Energy balance at the sample times [J]: work of the torques (incl. constant-speed drives;
  /// and of a finite-element K_m's variation, TrainMesh::mesh_stiffness), kinetic energy, stored
  /// elastic energy (contacts, shafts) and dissipated energy.
  std::vector<double> work, kinetic, potential, dissipated;
  std::size_t         steps = 0, events = 0;         ///< CVODE steps; located contact changes
  TrainIntegrator     method = TrainIntegrator::bdf; ///< the method run (never automatic)
  /// max |work - (kinetic - kinetic(0)) - (potential - potential(0)) - dissipated| over the
  /// run, relative to the largest of the terms.
  double energy_error = 0;
};

/// Integrates the train from its bodies' initial angles and speeds. Throws InputError for a
/// bad model or options and for integrator failures (naming the time and the CVODE flag).
TrainResult
simulate_train(const TrainModel &model, const TrainRunOptions &options);

/// Exact kinematics of the train running forward: the speed of every body for the given speed
/// of body `body`, through the meshes' tooth ratios and the shafts (constant speed bodies are
/// ignored). Throws InputError when the ratios do not close (a loop of meshes whose ratios
/// disagree).
std::vector<double>
train_speeds(const TrainModel &model, int body, double speed);

/// The kinematic frequencies of a train running forward with body `body` at `speed` [rad/s]
/// (train_speeds): every body's shaft frequency |w| / 2 pi and every mesh's tooth mesh
/// frequency z_pinion |w_driver| / 2 pi [Hz].
struct TrainFrequencies
{
  std::vector<double> shaft; ///< per body [Hz]
  std::vector<double> mesh;  ///< per mesh [Hz]
};
TrainFrequencies
train_frequencies(const TrainModel &model, int body, double speed);
} // namespace gearkit
