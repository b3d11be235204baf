// Contact results per node and for the summary.
#include "signorini/post/contact_results.hpp"

#include <cmath>
#include <limits>

namespace signorini {

namespace {

/// A rank's share of the summary, reduced over the ranks by Summarise.
struct Partial {
  /// Sums: contact force (0-2), contact length or area (3), applied force (4-6), reaction force (8-10), strain energy
  /// (12), contact force on the master sides of pairs of bodies (13-15), friction force (16-18).
  double sum[19] = {0};
  /// Maxima: pressure, penetration, |lambda g|, -min lambda over the active pairs, |u|.
  double max[5] = {0, 0, 0, -std::numeric_limits<double>::infinity(), 0};
  PetscInt count[4] = {0, 0, 0, 0}; ///< candidate nodes, pairs, active pairs, active nodes
};

/// The friction force F = -sum_k t_k lambda_t,k per node, its traction F / area (the tributary area: length times
/// thickness in 2D), the slip and the set, and the total friction force (part of the contact force).
PetscErrorCode FrictionResults(const SolvedState &state, const std::vector<double> &area, NodeContact &nodes,
                               Partial &part) {
  const Friction &friction = *state.friction;
  const int dim = state.mesh.Dim(), m = friction.PerPair();
  const PetscInt nv = state.mesh.NumLocalVertices();
  std::vector<double> s;
  PetscFunctionBeginUser;
  PetscCall(friction.Slips(state.pairs, state.u_local.data(), s));
  nodes.friction.assign(nv * dim, 0.0);
  nodes.friction_traction.assign(nv * dim, 0.0);
  nodes.slip.assign(nv * dim, 0.0);
  nodes.friction_state.assign(nv, 0.0);
  for (std::size_t p = 0; p < state.pairs.size(); ++p) {
    const PetscInt v = state.pairs[p].vertex;
    for (int k = 0; k < m; ++k) {
      const double *t = friction.Tangent(p, k);
      for (int c = 0; c < dim; ++c) {
        const double f = -t[c] * friction.LambdaT(p)[k];
        nodes.friction[v * dim + c] += f;
        if (state.mesh.Owned(v)) part.sum[c] += f, part.sum[16 + c] += f;
        nodes.slip[v * dim + c] += t[c] * s[p * m + k];
      }
    }
    if (state.states[p].active) nodes.friction_state[v] = std::max(nodes.friction_state[v], (double)friction.State(p));
  }
  for (PetscInt v = 0; v < nv; ++v)
    if (area[v] > 0)
      for (int c = 0; c < dim; ++c) nodes.friction_traction[v * dim + c] = nodes.friction[v * dim + c] / area[v];
  PetscFunctionReturn(0);
}

/// The multipliers, pressures, gaps and active flags per node (nodes) from the pairs, with the contact force, length
/// and the maxima of the pairs (w: the tributary lengths or areas; area: in 2D the lengths times the thickness).
void NodeResults(const SolvedState &state, const std::vector<double> &w, const std::vector<double> &area,
                 NodeContact &nodes, Partial &part) {
  const Mesh &mesh = state.mesh;
  const int dim = mesh.Dim();
  const PetscInt nv = mesh.NumLocalVertices();
  const auto &pairs = state.pairs;
  const auto &states = state.states;
  const auto &normals = state.normals;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  double *local = part.sum, *maxes = part.max;
  PetscInt *counts = part.count;
  nodes.lambda.assign(nv, 0.0);
  nodes.pressure.assign(nv, 0.0);
  nodes.gap.assign(nv, nan);
  nodes.active.assign(nv, 0.0);
  counts[1] = (PetscInt)pairs.size();
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const PetscInt v = pairs[p].vertex;
    const PairState &st = states[p];
    nodes.lambda[v] += st.lambda;
    if (st.InZone()) nodes.gap[v] = std::isnan(nodes.gap[v]) ? st.gap : std::min(nodes.gap[v], st.gap);
    if (st.active) {
      nodes.active[v] = 1;
      counts[2]++;
      maxes[3] = std::max(maxes[3], -st.lambda);
    }
    for (int k = 0; k < dim; ++k) local[k] += st.lambda * normals[p][k];
    if (st.InZone()) maxes[1] = std::max(maxes[1], -st.gap);
    maxes[2] = std::max(maxes[2], std::abs(st.lambda * st.gap));
  }
  for (PetscInt v = 0; v < nv; ++v) {
    if (!mesh.Owned(v)) continue;
    counts[0] += state.candidates[v];
    if (area[v] > 0) nodes.pressure[v] = nodes.lambda[v] / area[v];
    if (nodes.active[v]) {
      counts[3]++;
      local[3] += w[v];
      maxes[0] = std::max(maxes[0], nodes.pressure[v]);
    }
  }
}

/// Applied load, reactions R = F_int - f - lambda n on the Dirichlet dofs, largest displacement, strain energy.
PetscErrorCode BodyResults(const SolvedState &state, Partial &part) {
  const Mesh &mesh = state.mesh;
  const DofMap &dofs = state.dofs;
  const int dim = mesh.Dim();
  const auto &pairs = state.pairs;
  double *local = part.sum;
  PetscFunctionBeginUser;
  const PetscScalar *fi, *fe;
  PetscCall(VecGetArrayRead(state.fint, &fi));
  PetscCall(VecGetArrayRead(state.fext, &fe));
  std::vector<double> contact_at(dofs.OwnedU(), 0.0);
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (int k = 0; k < dim; ++k)
      contact_at[dofs.LocalOffset(pairs[p].vertex, k)] += state.states[p].lambda * state.normals[p][k];
  if (state.friction) {
    // The friction forces on the pairs' nodes, and (pairs of bodies) on their master nodes, part of the master sides'.
    std::vector<double> slave(dofs.OwnedU(), 0.0);
    PetscCall(state.friction->AddForces(pairs, 1, false, slave.data(), dofs.OwnedU()));
    for (PetscInt i = 0; i < dofs.OwnedU(); ++i) contact_at[i] += slave[i];
    std::vector<double> master(dofs.OwnedU(), 0.0);
    PetscCall(state.friction->AddMasterForces(pairs, master.data(), dofs.OwnedU(), &local[13]));
  }
  if (state.mortar && !state.mortar->Empty()) {
    std::vector<double> lambda(pairs.size()), master;
    for (std::size_t p = 0; p < pairs.size(); ++p) lambda[p] = state.states[p].lambda;
    PetscCall(state.mortar->MasterForces(mesh, dofs, lambda, master, &local[13]));
    for (PetscInt i = 0; i < dofs.OwnedU(); ++i) contact_at[i] += master[i];
  }
  double umax = 0;
  for (PetscInt v = 0; v < mesh.NumLocalVertices(); ++v) {
    if (!mesh.Owned(v)) continue;
    double u2 = 0;
    for (int k = 0; k < dim; ++k) {
      const PetscInt i = dofs.LocalOffset(v, k);
      const double u = state.u_local[v * dim + k];
      u2 += u * u;
      local[4 + k] += fe[i];
      if (state.dirichlet.fixed[v * dim + k]) local[8 + k] += fi[i] - fe[i] - contact_at[i];
      local[12] += 0.5 * fi[i] * u;
    }
    umax = std::max(umax, std::sqrt(u2));
  }
  PetscCall(VecRestoreArrayRead(state.fint, &fi));
  PetscCall(VecRestoreArrayRead(state.fext, &fe));
  part.max[4] = umax;
  PetscFunctionReturn(0);
}

/// The summary from the ranks' shares. Collective.
PetscErrorCode Summarise(MPI_Comm comm, Partial &part, ContactSummary &s) {
  PetscFunctionBeginUser;
  part.max[0] = std::max(part.max[0], 0.0);
  double global[19], gmax[5];
  PetscInt gcounts[4];
  PetscCallMPI(MPI_Allreduce(part.sum, global, 19, MPI_DOUBLE, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(part.max, gmax, 5, MPI_DOUBLE, MPI_MAX, comm));
  PetscCallMPI(MPI_Allreduce(part.count, gcounts, 4, MPIU_INT, MPI_SUM, comm));
  s.candidates = gcounts[0];
  s.pairs = gcounts[1];
  s.active_pairs = gcounts[2];
  s.active_nodes = gcounts[3];
  double total[3] = {0, 0, 0}, na = 0, nc = 0;
  for (int k = 0; k < 3; ++k) {
    s.contact_force[k] = global[k];
    s.applied_force[k] = global[4 + k];
    s.reaction_force[k] = global[8 + k];
    s.master_force[k] = global[13 + k];
    s.friction_force[k] = global[16 + k];
    total[k] = global[k] + global[4 + k] + global[8 + k] + global[13 + k];
    na += global[4 + k] * global[4 + k];
    nc += global[k] * global[k];
  }
  const double ref = std::max(std::sqrt(na), std::sqrt(nc));
  s.force_balance = ref > 0 ? std::sqrt(total[0] * total[0] + total[1] * total[1] + total[2] * total[2]) / ref : 0;
  s.contact_length = global[3];
  s.strain_energy = global[12];
  s.max_pressure = gmax[0];
  s.max_penetration = std::max(0.0, gmax[1]);
  s.complementarity = gmax[2];
  s.min_lambda = s.active_pairs ? -gmax[3] : 0.0;
  s.max_displacement = gmax[4];
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ComputeContactResults(const SolvedState &state, const Material &material, NodeContact &nodes,
                                     ContactSummary &s) {
  PetscFunctionBeginUser;
  // The pressure is per tributary area: the length times the thickness of the faces' cells (2D).
  std::vector<double> w, area, thickness(state.mesh.NumLocalCells());
  for (PetscInt c = 0; c < state.mesh.NumLocalCells(); ++c) thickness[c] = material.CellThickness(c);
  PetscCall(TributaryLengths(state.mesh, state.candidates, w, &thickness, &area));
  Partial part;
  NodeResults(state, w, area, nodes, part);
  if (state.friction) PetscCall(FrictionResults(state, area, nodes, part));
  PetscCall(BodyResults(state, part));
  PetscCall(Summarise(state.mesh.Comm(), part, s));
  s.bodies = state.mortar && !state.mortar->Empty();
  s.friction = state.friction != nullptr;
  PetscFunctionReturn(0);
}

} // namespace signorini
