// Loaded tooth contact at one mesh position, fast (compliance) mode: the contact cells of the
// unloaded TCA, their compliance = structural part of each member (finite elements, without the
// local half-space part) + the half-space (Boussinesq/Love) part of the pair, and the contact
// problem with the torque balance. Gives the loaded transmission error e_L, the load per tooth
// pair, the pressure on the cells and the mesh stiffness K_m = F / (lambda (e_L - e_0)).
#pragma once

#include "stiffness/contact_cells.h"
#include "stiffness/contact_solver.h"
#include "stiffness/flank_compliance.h"
#include "stiffness/half_space.h"

#include <Eigen/Core>

#include <functional>
#include <mpi.h>
#include <string>
#include <type_traits>
#include <vector>

namespace gearkit
{
/// Structural compliance of one member [m/N]: normal approach at the response cell (moving
/// into the member's material) per unit normal force on the load cell, without the local
/// half-space part. Cells are identified on the member's flank: the pinion by (pinion_tooth,
/// table_u1, table_v1), the gear by (gear_tooth, table_u2, table_v2). Given pair by pair (any
/// callable), and optionally as the matrix over all the cells of a position at once (faster:
/// table_compliance).
class StructuralCompliance
{
public:
  using Pair = std::function<double(const ContactCell &load, const ContactCell &response)>;
  /// M(j, i): the approach at cells[j] per unit force on cells[i].
  using Matrix = std::function<Eigen::MatrixXd(const std::vector<ContactCell> &cells)>;

  StructuralCompliance(Pair pair, Matrix matrix);
  template <class F, std::enable_if_t<std::is_invocable_r_v<double, const F &, const ContactCell &,
                                                            const ContactCell &>,
                                      int> = 0>
  StructuralCompliance(F pair) // NOLINT(google-explicit-constructor): a callable is one
      : StructuralCompliance(Pair(std::move(pair)), nullptr)
  {
  }

  double
  operator()(const ContactCell &load, const ContactCell &response) const
  {
    return pair(load, response);
  }
  /// M(j, i) over the cells: the matrix form if given, else pair by pair.
  Eigen::MatrixXd
  matrix(const std::vector<ContactCell> &cells) const;

private:
  Pair   pair;
  Matrix all;
};

/// A member's compliance table read at the cells' parameters on the pinion (table_u1, table_v1)
/// or the gear (table_u2, table_v2); keeps a reference to the table.
StructuralCompliance
table_compliance(const FlankCompliance &table, bool pinion);

struct LoadedContactOptions
{
  /// The cells; cells.gap_band is where the zone starts (0: from the load, by Hertz's line
  /// contact on the leading pair) when adapt_band is set.
  ContactCellOptions cells;
  /// Fit the zone to the load: the band is set to four times the gap at the contact's edge
  /// (the contact about half the zone across, whatever the load), narrowed while the contact
  /// fills less than a third of the zone, widened while it reaches the zone's edge. Without
  /// it the band is cells.gap_band, only widened.
  bool     adapt_band = true;
  Material pinion_material, gear_material;
  bool     half_space = true; ///< add the half-space part between cells of a pair
  /// Sets a cell's table_* parameters when the flanks are not those of the compliance tables
  /// (measured flanks: the theoretical flank's parameters at the cell's position).
  std::function<void(ContactCell &)> table_parameters;
  /// Whether the compliance tables cover a tooth pair (pinion tooth, gear tooth); pairs they do
  /// not cover are left out while they stand apart, and refused when they touch.
  std::function<bool(int, int)> covered;
  /// Positions loaded_contact_cycle solves at once (threads; the results do not depend on it);
  /// 0: as many as the hardware runs.
  unsigned threads = 0;
  /// The processes loaded_contact_cycle shares the positions among (each solves every size-th
  /// (torque, position), every process receives all); MPI_COMM_SELF: this process alone.
  MPI_Comm communicator = MPI_COMM_SELF;
};

struct LoadedPosition
{
  double              pinion_angle = 0; ///< phi [rad]
  double              e0           = 0; ///< unloaded TE [rad, pinion]
  double              eL           = 0; ///< loaded TE [rad, pinion]
  double              torque       = 0; ///< pinion torque [N m]
  double              normal_force = 0; ///< F, sum of the cell forces [N]
  double              lever = 0; ///< lambda = torque / F [m] (the base radius for spur gears)
  double              mesh_stiffness = 0; ///< K_m = F / (lambda (e_L - e_0)) [N/m]; 0 at zero load
  std::vector<double> pair_force;         ///< normal force per entry of TcaPosition::pairs [N]
  std::vector<ContactCell> cells;
  Eigen::VectorXd          force; ///< per cell [N]; pressure = force / (ds dt)
  int                      active_cells = 0;
  int                      iterations   = 0;
  double                   gap_band     = 0; ///< of the cell zone used [m]
  /// Contact in the outermost row of a zone the gap band cut short of the flank: the zone was
  /// too narrow for the load (loaded_contact widens it and solves again).
  bool zone_edge_reached = false;
  int  zone_edge_cell    = -1; ///< the most loaded such cell (index into cells)
  /// Edge contact: the force on cells at an edge of either flank (tip, face end, start of the
  /// working flank) [N] and the most loaded of them (-1: none loaded).
  double edge_force = 0;
  int    edge_cell  = -1;
  int    zones      = 0; ///< cell zones solved (the band fitted to the load)
};

/// Solves the loaded contact at one position of the unloaded TCA under a pinion torque >= 0.
/// The zone is fitted to the load (LoadedContactOptions::adapt_band); pairs standing apart that
/// the approach would bring into contact join, and the position is solved again. Throws
/// InputError when no cell lies within the gap band and when the zone does not settle.
LoadedPosition
loaded_contact(const UnloadedTca &tca, const TcaPosition &position, double torque,
               const LoadedContactOptions &options, const StructuralCompliance &pinion,
               const StructuralCompliance &gear);

/// The cells loaded_contact solves on at a position: those of the covered pairs, with their
/// table parameters set. Throws InputError when none lies within the gap band and when an
/// uncovered pair touches.
std::vector<ContactCell>
loaded_cells(const UnloadedTca &tca, const TcaPosition &position,
             const LoadedContactOptions &options);

/// The whole compliance of the cells [m/N]: both members' structural parts and, with
/// options.half_space, the half-space part between cells of one pair. C(j, i): the approach at
/// cells[j] per unit normal force on cells[i].
Eigen::MatrixXd
zone_compliance(const std::vector<ContactCell> &cells, const LoadedContactOptions &options,
                const StructuralCompliance &pinion, const StructuralCompliance &gear);

/// The contact problem on given cells with their whole compliance (both members and the local
/// part): compliance(j, i) is the approach at cell j per unit normal force on cell i [m/N].
LoadedPosition
solve_loaded_contact(const UnloadedTca &tca, const TcaPosition &position, double torque,
                     std::vector<ContactCell> cells, const Eigen::MatrixXd &compliance);

/// The tables of a solved contact problem on `cells` at `position` (the gaps relative to its
/// gear angle): `first_touch` is the pinion rotation beyond it at which the flanks the gaps
/// belong to touch unloaded (0 for the position's own flanks), so that e_0 = the position's
/// e_0 + first_touch and K_m = F / (lambda (approach - first_touch)) (drive side; the coast
/// side's signs turn). Throws InputError when the loaded approach does not exceed the first
/// touch.
LoadedPosition
loaded_position(const UnloadedTca &tca, const TcaPosition &position, double torque,
                std::vector<ContactCell> cells, const ContactSolution &solution,
                double first_touch);

/// The loaded contact over one mesh cycle: `positions` equal steps of the pinion over 2 pi / z1
/// from the TCA's start angle, at every torque. Tables by torque (M), position (N), pair slot of
/// the unloaded TCA (S: the most pairs at any position) and cell (C: the most cells).
struct MeshCycleContact
{
  std::size_t         torques = 0, positions = 0, slots = 0, cells = 0;
  std::vector<double> pinion_angle;   ///< phi [N] [rad]
  std::vector<double> unloaded_te;    ///< e_0 [N] [rad, pinion]
  std::vector<int>    slot_tooth;     ///< pinion tooth of each slot, -1 empty [N][S]
  std::vector<double> loaded_te;      ///< e_L [M][N] [rad, pinion]
  std::vector<double> mesh_stiffness; ///< K_m [M][N] [N/m]
  std::vector<double> normal_force;   ///< F [M][N] [N]
  std::vector<double> lever;          ///< lambda [M][N] [m]
  std::vector<double> pair_force;     ///< per slot [M][N][S] [N]
  std::vector<double> peak_pressure;  ///< largest cell pressure [M][N] [Pa]
  /// largest pressure off the flanks' edges [M][N] [Pa] (Hertz's where the flanks are smooth)
  std::vector<double> interior_peak_pressure;
  std::vector<double> edge_load_share; ///< force on cells at a flank edge / F [M][N]
  /// the most loaded edge cell's pinion point: radius, axial position [M][N][2] [m] (0: none)
  std::vector<double> edge_position;
  std::vector<double> gap_band;      ///< of the cell zone fitted to the load [M][N] [m]
  std::vector<double> cell_pressure; ///< pinion tooth (-1 unused), u1, v1, p [M][N][C][4]
  std::vector<double> cell_gear;     ///< the cells' gear flank parameters u2, v2 [M][N][C][2]
  double              mean_pairs_in_contact = 0; ///< of the unloaded TCA (eps_gamma, conjugate)
  /// Per torque [M]: empty when every position was solved, else why the first position that
  /// failed did (its rows of the tables hold zeros; the other torques are unaffected).
  std::vector<std::string> torque_failure;
};

/// Solves loaded_contact at every position and torque; `step` (optional) is called after each.
/// A torque some position of which fails (InputError: an active set that does not settle, a pair
/// the segments do not cover) is marked in torque_failure; the others are kept.
MeshCycleContact
loaded_contact_cycle(const UnloadedTca &tca, int positions, const std::vector<double> &torques,
                     const LoadedContactOptions &options, const StructuralCompliance &pinion,
                     const StructuralCompliance &gear, const std::function<void()> &step = {});

/// The mesh cycle at the torques `keep` (indices, in the order given) alone.
MeshCycleContact
select_torques(const MeshCycleContact &cycle, const std::vector<std::size_t> &keep);

/// The discretisation error estimate of a mesh cycle's K_m and e_L [M][N], from the same cycle
/// on compliance tables of elements `coarsening` (c > 1) times larger and on half the contact
/// cells (halved_cells): |K(h) - K(c h)| / (c - 1) + |K(cells) - K(cells / 2)|, each an upper
/// estimate wherever the error falls at least linearly with the size.
struct MeshCycleError
{
  std::vector<double> mesh_stiffness, loaded_te;                 ///< the estimates [N/m], [rad]
  std::vector<double> stiffness_by_elements, stiffness_by_cells; ///< its two parts [N/m]
};
MeshCycleError
mesh_cycle_error(const MeshCycleContact &result, const MeshCycleContact &coarse_elements,
                 double coarsening, const MeshCycleContact &half_cells);

/// The cells of the error estimate: half as many across (odd) and along.
ContactCellOptions
halved_cells(ContactCellOptions cells);
} // namespace gearkit
