// Coulomb friction at the pairs against rigid obstacles: tangent bases and rows, slips, the stick/slip sets, the
// system's rows and the certificate (friction.hpp, docs/theory.md §9).
#include "signorini/contact/friction.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace signorini {

const char *const GRIP_NAMES[] = {"open", "slip", "stick"};

namespace {

/// An orthonormal tangent basis of the unit normal n: in 2D t = (n_y, -n_x) (along +x on a floor); in 3D t_1 is the
/// coordinate axis least aligned with n made orthogonal to it (the first at a tie: x on a floor), t_2 = n x t_1.
void TangentBasis(int dim, const double *n, std::array<std::array<double, 3>, 2> &t) {
  t = {};
  if (dim == 2) {
    t[0] = {n[1], -n[0], 0};
    return;
  }
  int e = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) < std::abs(n[e])) e = k;
  double norm = 0;
  for (int k = 0; k < 3; ++k) t[0][k] = (k == e) - n[e] * n[k], norm += t[0][k] * t[0][k];
  for (int k = 0; k < 3; ++k) t[0][k] /= std::sqrt(norm);
  t[1] = {n[1] * t[0][2] - n[2] * t[0][1], n[2] * t[0][0] - n[0] * t[0][2], n[0] * t[0][1] - n[1] * t[0][0]};
}

} // namespace

std::string FrictionCertificate::Violation() const {
  char text[512] = "";
  if (!on) return text;
  if (!(cone <= force_tol))
    std::snprintf(text, sizeof(text),
                  "friction: the tangential force of node %" PetscInt_FMT " exceeds mu times its normal force by %.6g "
                  "(tolerance %.6g)", node[0], cone, force_tol);
  else if (!(stick_slip <= slip_tol))
    std::snprintf(text, sizeof(text), "friction: stick node %" PetscInt_FMT " slipped by %.6g (tolerance %.6g)",
                  node[1], stick_slip, slip_tol);
  else if (!(slip_rule <= force_tol))
    std::snprintf(text, sizeof(text),
                  "friction: the tangential force of slip node %" PetscInt_FMT " differs from mu lambda_n s/|s| by "
                  "%.6g (tolerance %.6g)", node[2], slip_rule, force_tol);
  else if (!(open_force <= force_tol))
    std::snprintf(text, sizeof(text), "friction: open node %" PetscInt_FMT " carries a tangential force %.6g", node[3],
                  open_force);
  return text;
}

void Friction::Configure(const ContactOptions &opts, const Obstacle &obstacle) {
  mu_ = opts.friction, pair_mu_ = opts.pair_friction;
  kind_option_ = obstacle.friction_option;
  facet_mu_.assign(obstacle.facets.size(), -1.0);
  for (std::size_t f = 0; f < obstacle.facets.size() && f < obstacle.facet_kind.size(); ++f)
    if ((std::size_t)obstacle.facet_kind[f] < obstacle.kind_friction.size())
      facet_mu_[f] = obstacle.kind_friction[obstacle.facet_kind[f]];
}

std::string Friction::Describe() const {
  char text[64];
  bool kinds = false;
  for (double m : facet_mu_) kinds = kinds || m > 0;
  if (mu_ > 0) std::snprintf(text, sizeof(text), "-contact_friction %g", mu_);
  else if (kinds) return "-obstacle_friction " + kind_option_;
  else std::snprintf(text, sizeof(text), "-contact_pairs SLAVE:MASTER:MU with MU > 0");
  return text;
}

bool Friction::On() const {
  bool on = mu_ > 0;
  for (double m : pair_mu_) on = on || m > 0;
  for (double m : facet_mu_) on = on || m > 0;
  return on;
}

bool Friction::HasRow(const SparseRow &row) {
  double norm2 = 0;
  for (double c : row.coef) norm2 += c * c;
  return norm2 > 1e-12;
}

void Friction::Bind(const Mesh &mesh, const DofMap &dofs, const std::vector<char> &fixed,
                    const std::vector<ContactPair> &pairs, const std::vector<std::array<double, 3>> &normals,
                    const MortarCoupling &mortar) {
  dim_ = mesh.Dim();
  mesh_ = &mesh, dofs_ = &dofs, fixed_ = &fixed, mortar_ = mortar.Empty() ? nullptr : &mortar;
  const std::size_t n = pairs.size();
  const int m = PerPair();
  mu_pair_.assign(n, mu_);
  for (std::size_t p = 0; p < n; ++p)
    if (mortar.IsMortar(pairs[p])) {
      const std::size_t item = (std::size_t)(pairs[p].facet - mortar.FacetBase());
      if (item < pair_mu_.size() && pair_mu_[item] >= 0) mu_pair_[p] = pair_mu_[item];
    } else if ((std::size_t)pairs[p].facet < facet_mu_.size() && facet_mu_[pairs[p].facet] >= 0) {
      mu_pair_[p] = facet_mu_[pairs[p].facet];
    }
  tangents_.clear();
  origin_.assign(n * dim_, 0.0);
  grip_.assign(n, Grip::OPEN), next_ = grip_;
  dir_.assign(n * m, 0.0), next_dir_ = dir_;
  across_.assign(n, NAN), next_across_ = across_;
  lambda_t_.assign(n * m, 0.0), mult_t_ = lambda_t_;
  Frame(pairs, normals);
}

void Friction::Frame(const std::vector<ContactPair> &pairs, const std::vector<std::array<double, 3>> &normals) {
  const std::size_t n = pairs.size();
  const int m = PerPair();
  // What lives in the tangent plane (the slip directions, the multipliers) turns with it: to 3D vectors with the old
  // basis, back with the new one (the directions normalised again).
  std::vector<std::vector<double> *> planar = {&dir_, &next_dir_, &lambda_t_, &mult_t_};
  std::vector<std::vector<double>> v3(planar.size(), std::vector<double>(3 * n, 0.0));
  const bool turn = tangents_.size() == n;
  if (turn)
    for (std::size_t i = 0; i < planar.size(); ++i)
      for (std::size_t p = 0; p < n; ++p)
        for (int k = 0; k < m; ++k)
          for (int c = 0; c < 3; ++c) v3[i][3 * p + c] += (*planar[i])[p * m + k] * tangents_[p][k][c];
  tangents_.assign(n, {});
  rows_.assign(n * m, SparseRow());
  has_.assign(n * m, 0);
  pairs_vertex_.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    TangentBasis(dim_, normals[p].data(), tangents_[p]);
    const PetscInt v = pairs[p].vertex;
    pairs_vertex_[p] = v;
    // The tangents' free parts that the normal's free part (and the tangents before) do not already constrain: on a
    // symmetry plane (y fixed) a tangent close to y keeps only a sliver along z, a multiple of the normal row, which
    // made the system singular (two half-balls on a symmetry plane, the node at the contact point).
    const auto free_part = [&](const double *d, double *f) {
      for (int c = 0; c < 3; ++c) f[c] = c < dim_ && !(*fixed_)[v * dim_ + c] ? d[c] : 0.0;
    };
    std::vector<std::array<double, 3>> basis;
    bool independent[2] = {false, false};
    double nf[3];
    free_part(normals[p].data(), nf);
    const double nn = std::sqrt(nf[0] * nf[0] + nf[1] * nf[1] + nf[2] * nf[2]);
    if (nn > 0) basis.push_back({nf[0] / nn, nf[1] / nn, nf[2] / nn});
    for (int k = 0; k < m; ++k) {
      double tf[3];
      free_part(tangents_[p][k].data(), tf);
      for (const auto &b : basis) {
        const double dot = tf[0] * b[0] + tf[1] * b[1] + tf[2] * b[2];
        for (int c = 0; c < 3; ++c) tf[c] -= dot * b[c];
      }
      const double tn = std::sqrt(tf[0] * tf[0] + tf[1] * tf[1] + tf[2] * tf[2]);
      independent[k] = tn > 1e-6;
      if (independent[k]) basis.push_back({tf[0] / tn, tf[1] / tn, tf[2] / tn});
    }
    for (int k = 0; k < m; ++k) {
      // The columns of the normal row (EvaluatePairs, MortarCoupling::ExtendRows) in its order: the node's free
      // components, then the master nodes' with - w_jl t_k (the slip is u_j - sum_l w_jl u_l along t_k).
      SparseRow &row = rows_[p * m + k];
      for (int c = 0; c < dim_; ++c)
        if (!(*fixed_)[v * dim_ + c]) row.Add(dofs_->Row(v, c), tangents_[p][k][c]);
      // A tangent along which the supports fix the node (a symmetry plane) has no row, whatever its master nodes do:
      // their weighted motion alone would be a constraint on the master side (singular where slave nodes share
      // master nodes).
      has_[p * m + k] = independent[k] && HasRow(row);
      if (mortar_ && mortar_->IsMortar(pairs[p])) mortar_->MasterColumns(p, tangents_[p][k].data(), -1, row);
    }
  }
  if (!turn) return;
  for (std::size_t i = 0; i < planar.size(); ++i)
    for (std::size_t p = 0; p < n; ++p) {
      double norm = 0;
      for (int k = 0; k < m; ++k) {
        double x = 0;
        for (int c = 0; c < 3; ++c) x += v3[i][3 * p + c] * tangents_[p][k][c];
        (*planar[i])[p * m + k] = x, norm += x * x;
      }
      if (i < 2 && norm > 0)
        for (int k = 0; k < m; ++k) (*planar[i])[p * m + k] /= std::sqrt(norm);
    }
}

Friction::Memory Friction::Remember(const std::vector<ContactPair> &pairs) const {
  Memory mem;
  const int m = PerPair();
  for (std::size_t p = 0; p < pairs.size() && p < grip_.size(); ++p) {
    PairMemory &pm = mem[{pairs[p].vertex, pairs[p].facet}];
    pm.grip = grip_[p];
    for (int c = 0; c < 3; ++c) pm.origin[c] = c < dim_ ? origin_[p * dim_ + c] : 0.0;
    for (int c = 0; c < 3; ++c) {
      pm.dir[c] = pm.lambda_t[c] = pm.mult_t[c] = 0;
      for (int k = 0; k < m; ++k) {
        pm.dir[c] += dir_[p * m + k] * tangents_[p][k][c];
        pm.lambda_t[c] += lambda_t_[p * m + k] * tangents_[p][k][c];
        pm.mult_t[c] += mult_t_[p * m + k] * tangents_[p][k][c];
      }
    }
  }
  return mem;
}

void Friction::Recall(const Memory &mem, const std::vector<ContactPair> &pairs) {
  const int m = PerPair();
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const PetscInt v = pairs[p].vertex;
    const auto it = mem.find({v, pairs[p].facet});
    // A new pair against a rigid obstacle slips from its node's displacement at the start of the step.
    for (int c = 0; c < dim_; ++c)
      origin_[p * dim_ + c] = it != mem.end() ? it->second.origin[c]
                                              : (start_u_.empty() ? 0.0 : start_u_[v * dim_ + c]);
    if (it == mem.end()) continue;
    grip_[p] = next_[p] = it->second.grip;
    for (int k = 0; k < m; ++k) {
      double d = 0, l = 0, f = 0;
      for (int c = 0; c < 3; ++c)
        d += it->second.dir[c] * tangents_[p][k][c], l += it->second.lambda_t[c] * tangents_[p][k][c],
            f += it->second.mult_t[c] * tangents_[p][k][c];
      dir_[p * m + k] = next_dir_[p * m + k] = d, lambda_t_[p * m + k] = l, mult_t_[p * m + k] = f;
    }
  }
}

PetscErrorCode Friction::Relative(const std::vector<ContactPair> &pairs, const double *u_local,
                                  std::vector<double> &r) const {
  PetscFunctionBeginUser;
  r.assign(pairs.size() * dim_, 0.0);
  if (mortar_) PetscCall(mortar_->MasterDisplacements(*mesh_, *dofs_, u_local, r));
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (int c = 0; c < dim_; ++c) r[p * dim_ + c] = u_local[pairs[p].vertex * dim_ + c] - r[p * dim_ + c];
  PetscFunctionReturn(0);
}

PetscErrorCode Friction::BeginStep(const std::vector<ContactPair> &pairs, const std::vector<PairState> &states,
                                   const double *u_local) {
  PetscFunctionBeginUser;
  PetscCall(Relative(pairs, u_local, start_r_));
  origin_ = start_r_;
  // The last step's relative motion of each pair: r now less r at the last step's start, both with these pairs (a
  // step repeated after a failure starts where it started before: the step before it is still the last one).
  std::vector<double> u(u_local, u_local + mesh_->NumLocalVertices() * dim_);
  if (u != start_u_) last_start_u_.swap(start_u_);
  start_u_ = std::move(u);
  last_motion_.clear();
  if (!last_start_u_.empty()) {
    std::vector<double> before;
    PetscCall(Relative(pairs, last_start_u_.data(), before));
    last_motion_.resize(before.size());
    for (std::size_t i = 0; i < before.size(); ++i) last_motion_[i] = start_r_[i] - before[i];
  }
  start_gap_.resize(pairs.size());
  for (std::size_t p = 0; p < pairs.size(); ++p) start_gap_[p] = states[p].gap;
  PetscFunctionReturn(0);
}

PetscErrorCode Friction::Slips(const std::vector<ContactPair> &pairs, const double *u_local,
                               std::vector<double> &s) const {
  std::vector<double> r;
  PetscFunctionBeginUser;
  PetscCall(Relative(pairs, u_local, r));
  SlipsOf(r, s);
  PetscFunctionReturn(0);
}

void Friction::SlipsOf(const std::vector<double> &r, std::vector<double> &s) const {
  const int m = PerPair();
  const std::size_t n = r.size() / dim_;
  s.assign(n * m, 0.0);
  for (std::size_t p = 0; p < n; ++p)
    for (int k = 0; k < m; ++k) {
      // Along a tangent the supports fix, the motion is theirs: no slip of friction's.
      if (!has_[p * m + k]) continue;
      double v = 0;
      for (int c = 0; c < dim_; ++c) v += tangents_[p][k][c] * (r[p * dim_ + c] - origin_[p * dim_ + c]);
      s[p * m + k] = v;
    }
}

void Friction::First(const std::vector<char> &active) {
  for (std::size_t p = 0; p < grip_.size(); ++p) {
    next_[p] = !active[p] || mu_pair_[p] == 0 ? Grip::OPEN : grip_[p] == Grip::OPEN ? Grip::STICK : grip_[p];
    for (int k = 0; k < PerPair(); ++k) next_dir_[p * PerPair() + k] = dir_[p * PerPair() + k];
    // A new step's slip starts from 0: across the slip it sticks until the next update.
    next_across_[p] = next_[p] == Grip::SLIP ? 0.0 : NAN;
  }
}

PetscErrorCode Friction::Next(MPI_Comm comm, const std::vector<ContactPair> &pairs,
                              const std::vector<PairState> &states, const std::vector<char> &active,
                              const double *u_local, double c, PetscInt &changes, PetscInt &turns) {
  const int m = PerPair();
  std::vector<double> s, r;
  PetscInt counts[2] = {0, 0};
  PetscFunctionBeginUser;
  // A pair that closes in this step slips from where it touched, not from where its node was at the start of the step
  // (a point of a curved surface moves along the other before it touches it, which a stick row would undo): the
  // origin of its slip moves to the point of its path from the step's start, where the gap, linear along it, was 0.
  // That path is the last step's relative motion, repeated (the load ramps in equal increments); in the run's first
  // step, which has none, the motion to this iterate, where the pair was still open. An iterate of the active-set
  // search is no point of the load path: two equal cylinders pressed together (Cattaneo-Mindlin) locked a tangential
  // traction into the stick zone whose pairs closed at iterates far from the converged motion (the profile's rms
  // error against the contact's own Hertz profile 2.3-2.7 % with it, 1.3-2.3 % with the last step's motion).
  PetscCall(Relative(pairs, u_local, r));
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    const double g0 = start_gap_[p], g = states[p].gap;
    if (!active[p] || grip_[p] != Grip::OPEN || !(g0 > 0 && g < g0)) continue;
    const double theta = std::min(1.0, g0 / (g0 - g));
    for (int c = 0; c < dim_; ++c)
      origin_[p * dim_ + c] = start_r_[p * dim_ + c] + theta * (last_motion_.size() == r.size()
                                                                      ? last_motion_[p * dim_ + c]
                                                                      : r[p * dim_ + c] - start_r_[p * dim_ + c]);
  }
  SlipsOf(r, s);
  next_dir_ = dir_;
  next_across_.assign(pairs.size(), NAN);
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (!active[p] || mu_pair_[p] == 0) {
      next_[p] = Grip::OPEN;
    } else {
      // The complementarity function of the friction law: z = lambda_t + c s against the bound mu (lambda_n - c g).
      double z[2] = {0, 0}, zn = 0;
      for (int k = 0; k < m; ++k) {
        if (!has_[p * m + k]) continue; // fixed along that tangent
        z[k] = lambda_t_[p * m + k] + c * s[p * m + k];
        zn += z[k] * z[k];
      }
      zn = std::sqrt(zn);
      const double bound = mu_pair_[p] * std::max(0.0, states[p].lambda - c * states[p].gap);
      // 3D: a slip pair whose rule turns its direction by more than a right angle slipped against its own friction
      // force in the last solve (the force overshot): it sticks next. Otherwise the direction swung back and forth
      // at the edge of a contact without converging (two equal half-balls sheared: three pairs, period 2).
      double reverse = 0;
      for (int k = 0; k < m && m == 2 && grip_[p] == Grip::SLIP; ++k) reverse += z[k] * dir_[p * m + k];
      if (zn <= bound || reverse < 0) {
        next_[p] = Grip::STICK;
      } else {
        next_[p] = Grip::SLIP;
        double turn = 0;
        for (int k = 0; k < m; ++k) {
          next_dir_[p * m + k] = z[k] / zn;
          turn += std::pow(next_dir_[p * m + k] - dir_[p * m + k], 2);
        }
        // In 2D the direction is a sign: a slip that reverses changes the set; in 3D it turns.
        if (grip_[p] == Grip::SLIP && std::sqrt(turn) > DIRECTION_TOL) counts[m == 1 ? 0 : 1]++;
        // 3D: the spring across the slip, mu lambda_n / |s| (a slip of zero: it sticks across).
        const double force = mu_pair_[p] * states[p].lambda;
        double sn = 0;
        for (int k = 0; k < m; ++k) sn += s[p * m + k] * s[p * m + k];
        if (m == 2 && force > 0) next_across_[p] = -std::sqrt(sn) / force;
      }
    }
    counts[0] += next_[p] != grip_[p];
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, comm));
  changes = counts[0], turns = counts[1];
  PetscFunctionReturn(0);
}

void Friction::SetKey(const std::vector<char> &active, std::vector<char> &key) const {
  key.resize(active.size());
  for (std::size_t p = 0; p < active.size(); ++p) {
    // 2D: a slip to the other side is another set (3: slip along -t).
    const bool back = PerPair() == 1 && next_dir_[p] < 0;
    key[p] = !active[p] ? 0 : next_[p] == Grip::STICK ? 2 : back ? 3 : 1;
  }
}

void Friction::TurnedRow(std::size_t p, double a, double b, SparseRow &row) const {
  // The two rows have the same columns (Bind): their combination is the row along a t_1 + b t_2 (none when its slave
  // part vanishes, as in Frame).
  // Independent of the normal row where both tangents are (Frame); with one, only along that one (a tangent without
  // its row contributes nothing: the row is then a multiple of the fixed one, KeptGroups). No row: its columns kept
  // with zeros (SetConstraints then writes zeros over whatever the pattern held there).
  const bool h0 = has_[p * 2], h1 = has_[p * 2 + 1];
  row = rows_[p * 2];
  for (PetscInt i = 0; i < row.ncols; ++i)
    row.coef[i] = (h0 ? a * rows_[p * 2].coef[i] : 0.0) + (h1 ? b * rows_[p * 2 + 1].coef[i] : 0.0);
  const bool holds = (h0 && h1) || (h0 && std::abs(b) < 1e-9 * std::abs(a)) || (h1 && std::abs(a) < 1e-9 * std::abs(b));
  if (!holds) std::fill(row.coef.begin(), row.coef.end(), 0.0);
}

void Friction::SystemRow(std::size_t p, int k, SparseRow &row) const {
  const int m = PerPair();
  if (m == 1 || grip_[p] != Grip::SLIP) {
    row = rows_[p * m + k];
    if (!has_[p * m + k]) std::fill(row.coef.begin(), row.coef.end(), 0.0);
    return;
  }
  // 3D slip: along d, then across it (d_perp = (-d_2, d_1) in the tangent basis).
  const double d0 = dir_[p * 2], d1 = dir_[p * 2 + 1];
  if (k == 0) TurnedRow(p, d0, d1, row);
  else TurnedRow(p, -d1, d0, row);
}

void Friction::SystemRows(const std::vector<SparseRow> &normal_rows, const std::vector<char> &active,
                          std::vector<SparseRow> &rows, std::vector<char> &flags,
                          std::vector<std::vector<double>> &columns, std::vector<double> &diag,
                          std::vector<char> *heavy, double light_weight, double kept_weight) const {
  const int m = PerPair();
  const std::size_t n = normal_rows.size();
  rows = normal_rows;
  rows.resize(n + rows_.size());
  flags.assign(rows.size(), 0);
  columns.assign(rows.size(), {});
  diag.assign(rows.size(), 0.0);
  if (heavy) heavy->assign(rows.size(), 0);
  for (std::size_t p = 0; p < n; ++p) {
    flags[p] = active[p];
    if (heavy) (*heavy)[p] = active[p];
    bool spring_near_light = false;
    for (int k = 0; k < m; ++k) {
      const std::size_t i = n + p * m + k;
      SystemRow(p, k, rows[i]);
      // Stick rows hold; a 3D slip pair's row across the slip is its spring.
      const bool across = m == 2 && k == 1 && grip_[p] == Grip::SLIP && std::isfinite(across_[p]);
      flags[i] = (grip_[p] == Grip::STICK || across) && HasRow(rows[i]);
      if (across) diag[i] = across_[p];
      // A spring k = -1/D near the light weight w would make 1 + w D vanish in the augmented form.
      if (across) spring_near_light = std::fabs(1.0 + light_weight * across_[p]) < 0.5;
      // On the kept factorisation, whose weight is fixed, a spring within KEPT_SPRING_MARGIN of it moves to that
      // margin instead: only the Newton step across the slip changes, by that fraction, not its fixed point, where
      // lambda_perp = 0 whatever the spring (the slip rule then makes the solved slip parallel to lambda_t + c s).
      // Moved to 1 + w D = +-0.5 (as the heavy weight's rule), the cube of partial slip took 14 iterations, not 7.
      const double margin = 1.0 + kept_weight * across_[p];
      if (across && kept_weight > 0 && std::fabs(margin) < KEPT_SPRING_MARGIN)
        diag[i] = ((margin < 0 ? -KEPT_SPRING_MARGIN : KEPT_SPRING_MARGIN) - 1.0) / kept_weight;
    }
    // The augmented form's weight: one per pair for its tangential rows (they turn together), the full one while it
    // sticks.
    if (heavy)
      for (int k = 0; k < m; ++k) (*heavy)[n + p * m + k] = grip_[p] == Grip::STICK || spring_near_light;
    if (grip_[p] != Grip::SLIP) continue;
    // The slip pair's normal multiplier also carries its friction force mu lambda_n d: the force on the body per unit
    // lambda_n is n - mu sum_k d_k t_k, and its column -(n - ...) (the row's coefficients are -n).
    // The tangential rows have the normal row's columns (Bind).
    const SparseRow &row = normal_rows[p];
    std::vector<double> &col = columns[p];
    col = row.coef;
    for (int k = 0; k < m; ++k)
      if (has_[p * m + k])
        for (PetscInt i = 0; i < row.ncols; ++i) col[i] += mu_pair_[p] * dir_[p * m + k] * rows_[p * m + k].coef[i];
  }
}

void Friction::KeptGroups(const std::vector<SparseRow> &normal_rows, std::vector<SparseRow> &fixed,
                          std::vector<RowGroup> &groups) const {
  const int m = PerPair(), size = 1 + m;
  const std::size_t n = normal_rows.size();
  fixed = normal_rows;
  fixed.resize(n + rows_.size());
  for (std::size_t i = 0; i < rows_.size(); ++i) {
    fixed[n + i] = rows_[i];
    if (!has_[i]) std::fill(fixed[n + i].coef.begin(), fixed[n + i].coef.end(), 0.0);
  }
  groups.assign(n, RowGroup());
  for (std::size_t p = 0; p < n; ++p) {
    RowGroup &g = groups[p];
    g.rows.push_back((PetscInt)p);
    for (int k = 0; k < m; ++k) g.rows.push_back((PetscInt)(n + p * m + k));
    // Q: the rows of SystemRow in the fixed ones (3D slip: along d, then across it).
    g.q.assign(size * size, 0.0);
    for (int i = 0; i < size; ++i) g.q[i * size + i] = 1.0;
    if (m == 2 && grip_[p] == Grip::SLIP) {
      const double d0 = dir_[p * 2], d1 = dir_[p * 2 + 1];
      g.q[1 * size + 1] = d0, g.q[1 * size + 2] = d1, g.q[2 * size + 1] = -d1, g.q[2 * size + 2] = d0;
    }
    // P: the columns; a slip pair's normal column carries mu d along its tangents (SystemRows).
    g.p = g.q;
    if (grip_[p] == Grip::SLIP)
      for (int k = 0; k < m; ++k)
        if (has_[p * m + k]) g.p[1 + k] += mu_pair_[p] * dir_[p * m + k];
  }
}

void Friction::HeldDirections(std::size_t p, std::vector<std::array<double, 3>> &dirs) const {
  const int m = PerPair();
  dirs.clear();
  for (int k = 0; k < m; ++k) {
    const bool across = m == 2 && k == 1 && grip_[p] == Grip::SLIP && std::isfinite(across_[p]);
    if (!(grip_[p] == Grip::STICK || across) || !has_[p * m + k]) continue;
    std::array<double, 3> d = tangents_[p][k];
    if (across) {
      const double d0 = dir_[p * 2], d1 = dir_[p * 2 + 1];
      for (int c = 0; c < 3; ++c) d[c] = -d1 * tangents_[p][0][c] + d0 * tangents_[p][1][c];
    }
    dirs.push_back(d);
  }
}

PetscErrorCode Friction::RowRhs(const std::vector<ContactPair> &pairs, const double *u_local, PetscScalar *b) const {
  const int m = PerPair();
  std::vector<double> s;
  PetscFunctionBeginUser;
  PetscCall(Slips(pairs, u_local, s));
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (int k = 0; k < m; ++k) {
      double v = 0;
      if (grip_[p] == Grip::STICK) v = -s[p * m + k];
      // 3D slip: across the slip, -d_perp . s.
      else if (grip_[p] == Grip::SLIP && m == 2 && k == 1 && std::isfinite(across_[p]))
        v = -(-dir_[p * 2 + 1] * s[p * 2] + dir_[p * 2] * s[p * 2 + 1]);
      b[p * m + k] = v;
    }
  PetscFunctionReturn(0);
}

void Friction::Read(const PetscScalar *x_t, const std::vector<double> &lambda_n, const std::vector<double> &mult_n) {
  const int m = PerPair();
  for (std::size_t p = 0; p < grip_.size(); ++p) {
    const double *d = &dir_[p * m];
    for (int k = 0; k < m; ++k) {
      const std::size_t i = p * m + k;
      if (grip_[p] == Grip::STICK) {
        lambda_t_[i] = x_t[i], mult_t_[i] = x_t[i];
      } else if (grip_[p] == Grip::OPEN) {
        lambda_t_[i] = 0, mult_t_[i] = x_t[i];
      } else if (m == 1) {
        // 2D slip: the row along t is inactive (x_t: a stabilisation spring's force at most).
        lambda_t_[i] = mu_pair_[p] * d[0] * lambda_n[p];
        mult_t_[i] = x_t[i] + mu_pair_[p] * d[0] * mult_n[p];
      }
    }
    if (m == 2 && grip_[p] == Grip::SLIP) {
      // 3D slip: along d mu lambda_n (plus the inactive row's spring, if any), across it the solved lambda_perp.
      const double along = x_t[p * 2], across = x_t[p * 2 + 1];
      const double l = mu_pair_[p] * lambda_n[p], f = mu_pair_[p] * mult_n[p] + along;
      lambda_t_[p * 2] = l * d[0] - across * d[1], lambda_t_[p * 2 + 1] = l * d[1] + across * d[0];
      mult_t_[p * 2] = f * d[0] - across * d[1], mult_t_[p * 2 + 1] = f * d[1] + across * d[0];
    }
  }
}

PetscErrorCode Friction::AddForces(const std::vector<ContactPair> &pairs, double scale, bool solved, double *r,
                                  PetscInt n) const {
  const int m = PerPair();
  const std::vector<double> &l = solved ? mult_t_ : lambda_t_;
  std::vector<double> F(pairs.size() * dim_, 0.0); // the friction force on each pair's node
  PetscFunctionBeginUser;
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (int k = 0; k < m; ++k)
      for (int c = 0; c < dim_; ++c) F[p * dim_ + c] -= tangents_[p][k][c] * l[p * m + k];
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (int c = 0; c < dim_; ++c) r[dofs_->LocalOffset(pairs[p].vertex, c)] += scale * F[p * dim_ + c];
  if (mortar_) PetscCall(mortar_->AddMasterVectorForces(F, scale, r, n));
  PetscFunctionReturn(0);
}

PetscErrorCode Friction::AddMasterForces(const std::vector<ContactPair> &pairs, double *r, PetscInt n,
                                        double *sum) const {
  const int m = PerPair();
  std::vector<double> F(pairs.size() * dim_, 0.0), master(n, 0.0);
  PetscFunctionBeginUser;
  if (!mortar_) PetscFunctionReturn(0);
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (int k = 0; k < m; ++k)
      for (int c = 0; c < dim_; ++c) F[p * dim_ + c] -= tangents_[p][k][c] * lambda_t_[p * m + k];
  PetscCall(mortar_->AddMasterVectorForces(F, 1, master.data(), n));
  for (PetscInt i = 0; i < n; ++i) r[i] += master[i];
  for (PetscInt v = 0; v < mesh_->NumLocalVertices(); ++v)
    if (mesh_->Owned(v))
      for (int c = 0; c < dim_; ++c) sum[c] += master[dofs_->LocalOffset(v, c)];
  PetscFunctionReturn(0);
}

PetscErrorCode Friction::Certify(MPI_Comm comm, const std::vector<ContactPair> &pairs,
                                 const std::vector<PairState> &states, const double *u_local, double lambda_tol,
                                 double slip_tol, FrictionCertificate &cert) const {
  const int m = PerPair();
  std::vector<double> s;
  // Per condition the largest violation and its node (file numbering, from 1); the largest lambda_n; the counts and
  // the total friction force.
  struct {
    double value;
    int node;
  } worst[4], global[4];
  for (auto &w : worst) w = {-INFINITY, -1};
  double lmax = 0, force[3] = {0, 0, 0};
  PetscInt counts[2] = {0, 0};
  PetscFunctionBeginUser;
  PetscCall(Slips(pairs, u_local, s));
  const auto note = [&](int i, double value, PetscInt vertex) {
    const int node = (int)mesh_->VertexOriginal(vertex) + 1;
    if (value > worst[i].value || (value == worst[i].value && node < worst[i].node)) worst[i] = {value, node};
  };
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (mu_pair_[p] == 0) continue;
    const PetscInt v = pairs[p].vertex;
    double lt = 0, sn = 0;
    for (int k = 0; k < m; ++k) {
      lt += lambda_t_[p * m + k] * lambda_t_[p * m + k], sn += s[p * m + k] * s[p * m + k];
      for (int c = 0; c < dim_; ++c) force[c] -= tangents_[p][k][c] * lambda_t_[p * m + k];
    }
    lt = std::sqrt(lt), sn = std::sqrt(sn);
    lmax = std::max(lmax, states[p].lambda);
    if (!states[p].active) {
      note(3, lt, v);
      continue;
    }
    note(0, lt - mu_pair_[p] * std::max(0.0, states[p].lambda), v);
    if (grip_[p] == Grip::STICK) {
      counts[0]++;
      note(1, sn, v);
    } else if (grip_[p] == Grip::SLIP) {
      counts[1]++;
      // A slip node that has not moved (|s| within the tolerance) is on the border of the stick zone: only the cone
      // applies to it.
      if (sn > slip_tol) {
        double d = 0;
        for (int k = 0; k < m; ++k)
          d += std::pow(lambda_t_[p * m + k] - mu_pair_[p] * states[p].lambda * s[p * m + k] / sn, 2);
        note(2, std::sqrt(d), v);
      }
    }
  }
  PetscCallMPI(MPI_Allreduce(worst, global, 4, MPI_DOUBLE_INT, MPI_MAXLOC, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &lmax, 1, MPI_DOUBLE, MPI_MAX, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, force, 3, MPI_DOUBLE, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPIU_INT, MPI_SUM, comm));
  cert.on = true;
  cert.cone = std::max(0.0, global[0].value);
  cert.stick_slip = std::max(0.0, global[1].value);
  cert.slip_rule = std::max(0.0, global[2].value);
  cert.open_force = std::max(0.0, global[3].value);
  for (int i = 0; i < 4; ++i) cert.node[i] = global[i].node;
  cert.force_tol = std::max(FrictionCertificate::FORCE_RTOL * lmax, lambda_tol);
  cert.slip_tol = slip_tol;
  cert.stick = counts[0], cert.slip = counts[1];
  std::copy(force, force + 3, cert.tangential_force);
  PetscFunctionReturn(0);
}

} // namespace signorini
