#include "problems/two_blocks.hpp"
#include "problems/registry.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace nsb {

namespace {

// The block-2d parameters each block takes under its prefix, with this problem's defaults.
constexpr const char* kBlockKeys[] = {"W", "H", "nx", "ny", "E", "nu", "rho", "material", "vx", "vy", "spin"};

struct BlockDefaults {
  const char* prefix;
  std::map<std::string, std::string> values;
};

const BlockDefaults kLower{"lower_", {{"W", "1"}, {"H", "0.3"}, {"nx", "5"}, {"ny", "2"}, {"vy", "0"}}};
const BlockDefaults kUpper{"upper_", {{"W", "0.5"}, {"H", "0.3"}, {"nx", "7"}, {"ny", "2"}, {"vy", "-1"}}};

void add_block_specs(const BlockDefaults& block, ParamSpecs& specs) {
  const ParamSpecs base = Block2d::parameters_spec();
  for (const char* key : kBlockKeys) {
    ParamSpec s = *std::find_if(base.begin(), base.end(), [&](const ParamSpec& b) { return b.name == key; });
    s.name = block.prefix + s.name;
    s.description = fmt::format("{} block: {}", block.prefix == kLower.prefix ? "lower" : "upper", s.description);
    if (const auto it = block.values.find(key); it != block.values.end()) s.default_value = it->second;
    specs.push_back(std::move(s));
  }
}

// The Block2d of one prefix: untilted, at `height`, with the shared g, e, mu and a fixed floor.
std::unique_ptr<Block2d> make_block(const Params& p, const std::string& prefix, double height) {
  std::map<std::string, std::string> o;
  for (const char* key : kBlockKeys) o[key] = p.values().at(prefix + key);
  for (const char* key : {"g", "e", "mu"}) o[key] = p.values().at(key);
  o["tilt"] = "0";
  o["floor_velocity"] = "0";
  o["height"] = fmt::format("{}", height);
  return std::make_unique<Block2d>(Params(Block2d::parameters_spec(), o));
}

// Rows of `A` (r x n) placed at row offset r0 and column offset c0.
void append(const SpMat& A, Index r0, Index c0, std::vector<Eigen::Triplet<double>>& t) {
  for (Index j = 0; j < A.outerSize(); ++j)
    for (SpMat::InnerIterator it(A, j); it; ++it) t.emplace_back(r0 + it.row(), c0 + it.col(), it.value());
}

// Writes the weights w of a node-to-segment contact into row r of the worst-case pattern:
// the top edge's dofs first (contiguous from first_top_dof, top_entries of them), then the
// upper node's x and y (dofs[0], dofs[1]); every other entry of the row is zero.
void write_segment_row(RowSpMat& rows, Index r, Index first_top_dof, Index top_entries, const Index (&dofs)[6],
                       const double (&w)[6]) {
  double* values = rows.valuePtr() + rows.outerIndexPtr()[r];
  std::fill_n(values, top_entries + 2, 0.0);
  for (int j = 0; j < 6; ++j) values[j < 2 ? top_entries + j : dofs[j] - first_top_dof] += w[j];
}

// The block-diagonal matrix diag(A, B).
SpMat block_diagonal(const SpMat& A, const SpMat& B) {
  std::vector<Eigen::Triplet<double>> t;
  append(A, 0, 0, t);
  append(B, A.rows(), A.cols(), t);
  SpMat D(A.rows() + B.rows(), A.cols() + B.cols());
  D.setFromTriplets(t.begin(), t.end());
  return D;
}

}  // namespace

ParamSpecs TwoBlocks::parameters_spec() {
  ParamSpecs specs;
  add_block_specs(kLower, specs);
  specs.push_back(ParamSpec::real("lower_height", 0.0, 0.0, 1e308, "lower block: its bottom above the floor [m]"));
  add_block_specs(kUpper, specs);
  specs.push_back(ParamSpec::real("upper_gap", 0.05, 0.0, 1e308, "upper block: its bottom above the lower block's top [m]"));
  specs.push_back(ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2] (0: off)"));
  specs.push_back(ParamSpec::real("e", 0.0, 0.0, 1.0, "Newton restitution coefficient (every contact)"));
  specs.push_back(ParamSpec::real("mu", 0.0, 0.0, 1e308, "Coulomb friction coefficient (every contact; 0: frictionless)"));
  specs.push_back(ParamSpec::choice("sliding", "small", {"small", "large"},
                                    "node-to-segment pairing: small (frozen in the reference configuration) or large "
                                    "(found from the current positions at every evaluation)"));
  return specs;
}

TwoBlocks::TwoBlocks(const Params& p) : params_(p) {
  const double Wl = p.real("lower_W"), Wu = p.real("upper_W");
  const long nxl = p.integer("lower_nx"), nxu = p.integer("upper_nx");
  if (Wu > Wl)
    throw InputError(fmt::format("problem two-blocks: upper_W = {} is wider than the lower block; valid: (0, lower_W = {}] "
                                 "(every bottom node of the upper block needs a segment of the lower block's top)",
                                 Wu, Wl));
  // Slave side at least as fine as the master: upper_W / upper_nx <= lower_W / lower_nx.
  const long min_nxu = static_cast<long>(std::ceil(Wu * double(nxl) / Wl * (1.0 - 1e-12)));
  if (nxu < min_nxu)
    throw InputError(fmt::format("problem two-blocks: upper_nx = {} is too coarse for the node-to-segment contact "
                                 "(the upper block's bottom must be meshed at least as finely as the lower block's top); "
                                 "valid: upper_nx >= {} (upper_W lower_nx / lower_W)",
                                 nxu, min_nxu));
  const double lower_height = p.real("lower_height");
  lower_ = make_block(p, "lower_", lower_height);
  upper_ = make_block(p, "upper_", lower_height + p.real("lower_H") + p.real("upper_gap"));
  nl_ = lower_->ndof();
  large_sliding_ = p.choice("sliding") == "large";

  // Contacts: the two floors, then node-to-segment.
  const Contacts& cl = lower_->contacts();
  const Contacts& cu = upper_->contacts();
  floor_contacts_ = cl.size() + cu.size();
  const Index nyl = lower_->parameters().integer("ny");
  const Index top0 = (nxl + 1) * nyl;  // first node of the lower block's top edge
  const Index nts = nxu + 1;
  top0_ = top0;
  segments_ = nxl;
  slaves_ = nts;
  const Index p_all = floor_contacts_ + nts;
  std::vector<Eigen::Triplet<double>> normal, tangent;
  append(cl.normal, 0, 0, normal);
  append(cu.normal, cl.size(), nl_, normal);
  contacts_.gap_offset.resize(p_all);
  contacts_.gap_offset << cl.gap_offset, cu.gap_offset, Vec::Zero(nts);
  const double hx = Wl / double(nxl);
  if (large_sliding_) add_large_sliding_rows(normal, tangent);
  for (Index k = 0; k < nts && !large_sliding_; ++k) {
    const Index a = k;  // bottom row of the upper block
    const Eigen::Vector2d Xa = upper_->reference_position(a);
    const Index i = std::clamp<Index>(static_cast<Index>(std::floor((Xa.x() + 0.5 * Wl) / hx)), 0, nxl - 1);
    const Index b0 = top0 + i, b1 = b0 + 1;
    const Eigen::Vector2d X0 = lower_->reference_position(b0), X1 = lower_->reference_position(b1);
    const double xi = std::clamp((Xa.x() - X0.x()) / (X1.x() - X0.x()), 0.0, 1.0);
    const Index r = floor_contacts_ + k;
    contacts_.gap_offset[r] = Xa.y() - ((1.0 - xi) * X0.y() + xi * X1.y());
    const std::pair<Index, double> entries[] = {{nl_ + 2 * a, 1.0}, {2 * b0, -(1.0 - xi)}, {2 * b1, -xi}};
    for (const auto& [dof, w] : entries)
      if (w != 0.0) {
        normal.emplace_back(r, dof + 1, w);  // y component
        tangent.emplace_back(r, dof, w);     // x component
      }
  }
  contacts_.normal.resize(p_all, ndof());
  contacts_.normal.setFromTriplets(normal.begin(), normal.end());
  contacts_.restitution = p.real("e");
  if (p.real("mu") > 0.0) {
    std::vector<Eigen::Triplet<double>> floor_t;
    append(cl.tangent, 0, 0, floor_t);
    append(cu.tangent, cl.size(), nl_, floor_t);
    floor_t.insert(floor_t.end(), tangent.begin(), tangent.end());
    SpMat T(p_all, ndof());
    T.setFromTriplets(floor_t.begin(), floor_t.end());
    contacts_.set_friction(std::move(T), p.real("mu"), 0.0);
  }
}

Eigen::Vector2d TwoBlocks::lower_position(ConstVecRef u, Index b) const {
  return lower_->reference_position(b) + u.segment<2>(2 * b);
}

TwoBlocks::SegmentContact TwoBlocks::segment_contact(ConstVecRef u, Index k) const {
  const Index a = nl_ + 2 * k;  // node k of the upper block's bottom row: its x dof
  const Eigen::Vector2d xa = upper_->reference_position(k) + u.segment<2>(a);
  // The segment: the first whose bisector at its right vertex has the node on its left side.
  Index i = 0;
  Eigen::Vector2d x0 = lower_position(u, top0_), x1 = lower_position(u, top0_ + 1);
  Eigen::Vector2d t = (x1 - x0).normalized();
  for (; i + 1 < segments_; ++i) {
    const Eigen::Vector2d x2 = lower_position(u, top0_ + i + 2);
    const Eigen::Vector2d t_next = (x2 - x1).normalized();
    if ((xa - x1).dot(t + t_next) < 0.0) break;
    x0 = x1;
    x1 = x2;
    t = t_next;
  }
  const double l = (x1 - x0).norm();
  const Eigen::Vector2d n(-t.y(), t.x());
  const double xi = (xa - x0).dot(t) / l, line_gap = (xa - x0).dot(n);
  const double X0 = lower_->reference_position(top0_ + i).x(), h = lower_->reference_position(top0_ + i + 1).x() - X0;
  SegmentContact c;
  c.segment = i;
  c.xi = xi;
  c.gap = line_gap;
  c.slide = X0 + h * xi;
  const Index b0 = 2 * (top0_ + i), b1 = b0 + 2;
  const Index dofs[6] = {a, a + 1, b0, b0 + 1, b1, b1 + 1};
  std::copy_n(dofs, 6, c.dofs);
  // L: +n on a, -(1 - xi) n on b0, -xi n on b1; past an end of the edge, the end vertex's.
  Eigen::Vector2d na = n, n0 = -(1.0 - xi) * n, n1 = -xi * n;
  const bool past_left = i == 0 && xi < 0.0, past_right = i + 1 == segments_ && xi > 1.0;
  if (past_left || past_right) {
    const Eigen::Vector2d d = xa - (past_left ? x0 : x1);
    c.gap = d.norm();
    na = c.gap > 0.0 ? Eigen::Vector2d(d / c.gap) : n;
    n0 = past_left ? Eigen::Vector2d(-na) : Eigen::Vector2d::Zero();
    n1 = past_left ? Eigen::Vector2d::Zero() : Eigen::Vector2d(-na);
  }
  // T = h dxi = (h / l) [t . (dx_a - (1 - xi) dx_b0 - xi dx_b1) + (g / l) n . (dx_b1 - dx_b0)].
  const double scale = h / l, w = line_gap / l;
  const Eigen::Vector2d ta = scale * t, t0 = -scale * ((1.0 - xi) * t + w * n), t1 = scale * (-xi * t + w * n);
  const Eigen::Vector2d* normal[3] = {&na, &n0, &n1};
  const Eigen::Vector2d* tangent[3] = {&ta, &t0, &t1};
  for (int j = 0; j < 6; ++j) {
    c.normal[j] = (*normal[j / 2])[j % 2];
    c.tangent[j] = (*tangent[j / 2])[j % 2];
  }
  return c;
}

void TwoBlocks::add_large_sliding_rows(std::vector<Eigen::Triplet<double>>& normal,
                                       std::vector<Eigen::Triplet<double>>& tangent) {
  const Vec u0 = initial_state().u;
  for (Index k = 0; k < slaves_; ++k) {
    const Index r = floor_contacts_ + k;
    // The worst-case pattern: every top-edge node's x and y (explicit zeros off the segment).
    for (Index dof = 2 * top0_; dof < 2 * (top0_ + segments_ + 1); ++dof) {
      normal.emplace_back(r, dof, 0.0);
      tangent.emplace_back(r, dof, 0.0);
    }
    const SegmentContact c = segment_contact(u0, k);
    double row_u0 = 0.0;
    for (int j = 0; j < 6; ++j) {
      normal.emplace_back(r, c.dofs[j], c.normal[j]);
      tangent.emplace_back(r, c.dofs[j], c.tangent[j]);
      row_u0 += c.normal[j] * u0[c.dofs[j]];
    }
    contacts_.gap_offset[r] = c.gap - row_u0;
  }
}

void TwoBlocks::evaluate_contacts(ConstVecRef u, ContactGeometry& out) const {
  if (!large_sliding_) {
    Problem::evaluate_contacts(u, out);
    return;
  }
  for (Index r = 0; r < floor_contacts_; ++r) {  // the floor rows are constant
    double gap = contacts_.gap_offset[r];
    for (RowSpMat::InnerIterator it(out.normal, r); it; ++it) gap += it.value() * u[it.col()];
    out.gap[r] = gap;
  }
  const Index top_entries = 2 * (segments_ + 1);
  for (Index k = 0; k < slaves_; ++k) {
    const Index r = floor_contacts_ + k;
    const SegmentContact c = segment_contact(u, k);
    out.gap[r] = c.gap;
    write_segment_row(out.normal, r, 2 * top0_, top_entries, c.dofs, c.normal);
    if (out.tangent.rows() > 0) write_segment_row(out.tangent, r, 2 * top0_, top_entries, c.dofs, c.tangent);
  }
}

void TwoBlocks::contact_slide(ConstVecRef u, VecRef s) const {
  if (contacts_.tangent.rows() == 0) {  // frictionless: no tangent rows to integrate
    s.setZero();
    return;
  }
  Problem::contact_slide(u, s);
  if (large_sliding_)
    for (Index k = 0; k < slaves_; ++k) s[floor_contacts_ + k] = segment_contact(u, k).slide;
}

SpMat TwoBlocks::mass_matrix() const { return block_diagonal(lower_->mass_matrix(), upper_->mass_matrix()); }

void TwoBlocks::internal_force(ConstVecRef u, VecRef f) const {
  lower_->internal_force(u.head(nl_), f.head(nl_));
  upper_->internal_force(u.tail(ndof() - nl_), f.tail(ndof() - nl_));
}

void TwoBlocks::tangent_stiffness(ConstVecRef u, SpMat& K) const {
  // The blocks' tangents, kept per thread so that a refill allocates nothing; diag(Kl, Ku)
  // in compressed column storage is Kl's arrays followed by Ku's, shifted.
  thread_local SpMat Kl, Ku;
  lower_->tangent_stiffness(u.head(nl_), Kl);
  upper_->tangent_stiffness(u.tail(ndof() - nl_), Ku);
  const Index nnz = Kl.nonZeros() + Ku.nonZeros();
  bool same = K.rows() == ndof() && K.cols() == ndof() && K.isCompressed() && K.nonZeros() == nnz;
  for (Index j = 0; same && j <= nl_; ++j) same = K.outerIndexPtr()[j] == Kl.outerIndexPtr()[j];
  for (Index j = 0; same && j <= ndof() - nl_; ++j) same = K.outerIndexPtr()[nl_ + j] == Kl.nonZeros() + Ku.outerIndexPtr()[j];
  for (Index k = 0; same && k < Kl.nonZeros(); ++k) same = K.innerIndexPtr()[k] == Kl.innerIndexPtr()[k];
  for (Index k = 0; same && k < Ku.nonZeros(); ++k) same = K.innerIndexPtr()[Kl.nonZeros() + k] == nl_ + Ku.innerIndexPtr()[k];
  if (!same) {
    K = block_diagonal(Kl, Ku);  // setFromTriplets keeps explicit zeros: the pattern checked above
    K.makeCompressed();
  }
  std::copy_n(Kl.valuePtr(), Kl.nonZeros(), K.valuePtr());
  std::copy_n(Ku.valuePtr(), Ku.nonZeros(), K.valuePtr() + Kl.nonZeros());
}

void TwoBlocks::external_force(double t, VecRef f) const {
  lower_->external_force(t, f.head(nl_));
  upper_->external_force(t, f.tail(ndof() - nl_));
}

double TwoBlocks::strain_energy(ConstVecRef u) const {
  return lower_->strain_energy(u.head(nl_)) + upper_->strain_energy(u.tail(ndof() - nl_));
}

double TwoBlocks::load_potential(ConstVecRef u) const {
  return lower_->load_potential(u.head(nl_)) + upper_->load_potential(u.tail(ndof() - nl_));
}

std::optional<FieldMesh> TwoBlocks::field_mesh() const {
  FieldMesh mesh = *lower_->field_mesh();
  mesh.append(*upper_->field_mesh(), nl_, 1);
  return mesh;
}

void TwoBlocks::cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const {
  const Index cl = lower_->parameters().integer("nx") * lower_->parameters().integer("ny");
  lower_->cell_stress(u.head(nl_), out.topRows(cl));
  upper_->cell_stress(u.tail(ndof() - nl_), out.bottomRows(out.rows() - cl));
}

State TwoBlocks::initial_state() const {
  const State l = lower_->initial_state(), h = upper_->initial_state();
  State s;
  s.u.resize(ndof());
  s.v.resize(ndof());
  s.u << l.u, h.u;
  s.v << l.v, h.v;
  return s;
}

double TwoBlocks::stable_step() const { return std::min(lower_->stable_step(), upper_->stable_step()); }

Eigen::Vector2d TwoBlocks::linear_momentum(ConstVecRef v) const {
  return lower_->linear_momentum(v.head(nl_)) + upper_->linear_momentum(v.tail(ndof() - nl_));
}

std::vector<std::string> TwoBlocks::observable_names() const {
  std::vector<std::string> names = lower_->observable_names();
  names.push_back("closed_between");
  return names;
}

void TwoBlocks::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  // block-2d's columns are additive (energies, momenta, closed floor contacts) and read no
  // impulse: each block is observed as at a sample without a step.
  const std::size_t k = lower_->observable_names().size();
  std::vector<double> lo(k), up(k);
  State part;
  part.t = s.t;
  part.u = s.u.head(nl_);
  part.v = s.v.head(nl_);
  lower_->observe(part, Vec(), 0.0, lo);
  part.u = s.u.tail(ndof() - nl_);
  part.v = s.v.tail(ndof() - nl_);
  upper_->observe(part, Vec(), 0.0, up);
  long between = 0;
  if (large_sliding_) {
    for (Index k = 0; k < slaves_; ++k) between += segment_contact(s.u, k).gap <= 0.0;
  } else {
    const Vec g = contacts_.gap_offset + contacts_.normal * s.u;
    between = (g.tail(g.size() - floor_contacts_).array() <= 0.0).count();
  }
  for (std::size_t c = 0; c < k; ++c) out[c] = lo[c] + up[c];
  out[k - 1] += static_cast<double>(between);  // closed_contacts: every contact
  out[k] = static_cast<double>(between);
}

NSBENCH_PROBLEM({"two-blocks", "two hyperelastic Q4 blocks stacked on a rigid floor, non-matching node-to-segment contact between them",
                 &TwoBlocks::parameters_spec, &make_from_params<Problem, TwoBlocks>});

}  // namespace nsb
