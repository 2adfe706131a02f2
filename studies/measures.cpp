// The measures of studies/measures.hpp.
#include "studies/measures.hpp"
#include "core/deterministic_math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "integrators/cd_lagrange_adaptive.hpp"
#include "integrators/integrator.hpp"

namespace nsb {

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  LineFit fit;
  fit.points = static_cast<int>(std::min(x.size(), y.size()));
  if (fit.points < 2) return fit;
  const double n = fit.points;
  double mx = 0, my = 0;
  for (int i = 0; i < fit.points; ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxx = 0, sxy = 0;
  for (int i = 0; i < fit.points; ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxy += (x[i] - mx) * (y[i] - my);
  }
  if (!(sxx > 0.0)) return fit;
  fit.slope = sxy / sxx;
  if (fit.points < 3) return fit;
  double ssr = 0;
  for (int i = 0; i < fit.points; ++i) {
    const double r = y[i] - my - fit.slope * (x[i] - mx);
    ssr += r * r;
  }
  const double half = student_t975(fit.points - 2) * std::sqrt(ssr / (n - 2) / sxx);
  fit.low = fit.slope - half;
  fit.high = fit.slope + half;
  return fit;
}

void RunningSlope::add(double x, double y) {
  n_ += 1.0;
  const double dx = x - mean_x_;
  mean_x_ += dx / n_;
  mean_y_ += (y - mean_y_) / n_;
  cxy_ += dx * (y - mean_y_);
  cxx_ += dx * (x - mean_x_);
}

double RunningSlope::slope() const { return cxx_ > 0.0 ? cxy_ / cxx_ : kNaN; }

double above_round_off(double error) { return error > kRoundOffError ? error : kNaN; }

double observed_order(double h1, double e1, double h2, double e2) {
  if (!usable(e1) || !usable(e2) || h1 == h2) return kNaN;
  return nsb::dmath::log(e1 / e2) / nsb::dmath::log(h1 / h2);
}

double fitted_order(const std::vector<double>& h, const std::vector<double>& e) { return fit_order(h, e).order; }

double student_t975(int dof) {
  // Tabulated to 30 degrees of freedom; beyond, the Cornish-Fisher expansion about the normal
  // quantile (error below 1e-5 there).
  static const double table[] = {12.7062047, 4.3026527, 3.1824463, 2.7764451, 2.5705818, 2.4469119,
                                 2.3646243, 2.3060041, 2.2621572, 2.2281389, 2.2009852, 2.1788128,
                                 2.1603687, 2.1447867, 2.1314495, 2.1199053, 2.1098155, 2.1009220,
                                 2.0930241, 2.0859634, 2.0796138, 2.0738731, 2.0686576, 2.0638986,
                                 2.0595386, 2.0555294, 2.0518305, 2.0484071, 2.0452296, 2.0422725};
  if (dof < 1) return kNaN;
  if (dof <= 30) return table[dof - 1];
  const double z = 1.959963985, n = dof;
  return z + (z * z * z + z) / (4 * n) + (5 * nsb::dmath::pow(z, 5) + 16 * z * z * z + 3 * z) / (96 * n * n) +
         (3 * nsb::dmath::pow(z, 7) + 19 * nsb::dmath::pow(z, 5) + 17 * z * z * z - 15 * z) / (384 * n * n * n);
}

OrderFit fit_order(const std::vector<double>& h, const std::vector<double>& e) {
  std::vector<double> x, y, repeats;  // one point per distinct h: the mean of log e over its repeats
  for (std::size_t i = 0; i < h.size() && i < e.size(); ++i)
    if (usable(e[i]) && h[i] > 0.0 && std::isfinite(h[i])) {
      const double lh = nsb::dmath::log(h[i]);
      const auto at = std::find(x.begin(), x.end(), lh) - x.begin();
      if (at == static_cast<std::ptrdiff_t>(x.size())) {
        x.push_back(lh);
        y.push_back(0.0);
        repeats.push_back(0.0);
      }
      repeats[at] += 1.0;
      y[at] += (nsb::dmath::log(e[i]) - y[at]) / repeats[at];
    }
  const LineFit line = fit_line(x, y);
  return {line.slope, line.low, line.high, line.points};
}

MomentumBalance::MomentumBalance(const Problem& problem, const Vec& v0)
    : problem_(problem),
      ones_(Vec::Ones(problem.ndof())),
      mass_row_(problem.mass_matrix().transpose() * ones_),
      gap_row_(problem.gap_operator() * ones_),
      f_ext_(problem.ndof()),
      p0_(mass_row_.dot(v0)),
      speed_scale_(problem.mass_matrix().diagonal().cwiseProduct(v0).cwiseAbs().sum()) {
  if (problem.external_force_is_constant()) {  // summed once: the observer's cost stays that of a dot product
    problem.external_force(0.0, f_ext_);
    constant_force_sum_ = ones_.dot(f_ext_);
  }
}

void MomentumBalance::add(const Integrator& integrator, double dt) {
  double force_sum = constant_force_sum_;
  if (std::isnan(force_sum)) {
    problem_.external_force(integrator.state().t - dt, f_ext_);
    force_sum = ones_.dot(f_ext_);
  }
  impulse_sum_ += force_sum * variable_step_weight(integrator, dt).value_or(dt) + gap_row_.dot(integrator.impulses());
}

double MomentumBalance::residual(const Vec& v) const { return std::abs(signed_residual(v)); }

double MomentumBalance::signed_residual(const Vec& v) const { return mass_row_.dot(v) - p0_ - impulse_sum_; }

std::optional<double> variable_step_weight(const Integrator& integrator, double dt) {
  if (const auto* adaptive = dynamic_cast<const CdLagrangeAdaptive*>(&integrator)) return 0.5 * (dt + adaptive->next_step());
  return std::nullopt;
}

std::vector<std::string> MeshMomentum::components(const Problem& problem) {
  const auto mesh = problem.field_mesh();
  if (!mesh) return {};
  std::vector<std::string> out;
  for (int d = 0; d < mesh->dimension && d < 3; ++d) out.push_back(std::string("p") + "xyz"[d]);
  if (mesh->dimension == 3) out.insert(out.end(), {"jx", "jy", "jz"});
  // A plane deformable body's one angular momentum, about the normal: its elements' points carry
  // every dof (no vertex body, whose rotation dof x x p would miss).
  if (mesh->dimension == 2 && mesh->nelements() > 0 && mesh->nbodies() == 0) out.push_back("jz");
  return out;
}

MeshMomentum::MeshMomentum(const Problem& problem, const State& initial, const std::string& component)
    : problem_(problem), M_(problem.mass_matrix()), axis_(component[1] - 'x'), angular_(component[0] == 'j'),
      f_(problem.ndof()), f_ext_(problem.ndof()), p_(problem.ndof()) {
  if (problem.contacts_move()) moving_rows_ = problem.contact_geometry();
  const FieldMesh mesh = *problem.field_mesh();
  // Three columns whatever the dimension: a plane body's points at z = 0 with no z dof, so that
  // its jz is the same cross product as a solid's.
  points_ = Eigen::MatrixXd::Zero(mesh.points.rows(), 3);
  point_dofs_ = Eigen::MatrixXi::Constant(mesh.point_dofs.rows(), 3, -1);
  points_.leftCols(mesh.points.cols()) = mesh.points;
  point_dofs_.leftCols(mesh.point_dofs.cols()) = mesh.point_dofs;
  const Vec p0 = M_ * initial.v;
  if (angular_) {
    previous_ = angular_momentum(initial);
    for (Index a = 0; a < points_.rows(); ++a) {
      Eigen::Vector3d x = points_.row(a).transpose(), pa = Eigen::Vector3d::Zero();
      for (int d = 0; d < 3; ++d)
        if (const int dof = point_dofs_(a, d); dof >= 0) {
          x[d] += initial.u[dof];
          pa[d] = p0[dof];
        }
      scale_ += x.norm() * pa.norm();
    }
  } else {
    for (Index a = 0; a < points_.rows(); ++a)
      if (const int dof = point_dofs_(a, axis_); dof >= 0) previous_ += p0[dof];
    scale_ = M_.diagonal().cwiseProduct(initial.v).cwiseAbs().sum();
  }
}

double MeshMomentum::angular_momentum(const State& s) {
  p_.noalias() = M_ * s.v;
  return torque(s, p_);
}

// sum_a (x_a x f_a)_axis with x_a = X_a + u_a and f_a the entries of f on point a's dofs.
double MeshMomentum::torque(const State& s, const Vec& f) const {
  const int i = (axis_ + 1) % 3, j = (axis_ + 2) % 3;
  const auto position = [&](Index a, int d) { return points_(a, d) + (point_dofs_(a, d) >= 0 ? s.u[point_dofs_(a, d)] : 0.0); };
  const auto entry = [&](Index a, int d) { return point_dofs_(a, d) >= 0 ? f[point_dofs_(a, d)] : 0.0; };
  double sum = 0.0;
  for (Index a = 0; a < points_.rows(); ++a) sum += position(a, i) * entry(a, j) - position(a, j) * entry(a, i);
  return sum;
}

void MeshMomentum::add(const Integrator& integrator, double dt) {
  const State& s = integrator.state();
  problem_.external_force(s.t - dt, f_ext_);
  f_.noalias() = variable_step_weight(integrator, dt).value_or(dt) * f_ext_;
  if (moving_rows_) {
    problem_.evaluate_contacts(s.u, *moving_rows_);
    add_contact_impulses(*moving_rows_, integrator, f_);
  } else {
    add_contact_impulses(problem_.contacts(), integrator, f_);
  }
  ++steps_;
  if (angular_) {
    const double J = angular_momentum(s);
    if (steps_ >= 2) largest_ = std::max(largest_, std::abs(J - previous_ - torque(s, f_)));
    previous_ = J;
    return;
  }
  double P = 0.0, impulse = 0.0;
  p_.noalias() = M_ * s.v;
  for (Index a = 0; a < points_.rows(); ++a)
    if (const int dof = point_dofs_(a, axis_); dof >= 0) {
      P += p_[dof];
      impulse += f_[dof];
    }
  if (steps_ >= 2) largest_ = std::max(largest_, std::abs(P - previous_ - impulse));
  previous_ = P;
}

void Envelope::add(double t, double value) {
  if (!(t >= t0_)) return;
  const long j = static_cast<long>(std::floor((t - t0_) / window_));
  if (seen_ && j == index_) {
    current_ = std::max(current_, std::abs(value));
    return;
  }
  if (seen_) {
    times_.push_back(t0_ + (static_cast<double>(index_) + 0.5) * window_);
    maxima_.push_back(current_);
  }
  seen_ = true;
  index_ = j;
  current_ = std::abs(value);
}

Drift drift_rule(const std::vector<double>& times, const std::vector<double>& envelope, double round_off) {
  Drift d;
  d.windows = static_cast<int>(std::min(times.size(), envelope.size()));
  if (d.windows < kDriftMinWindows) return d;
  const LineFit fit = fit_line(times, envelope);
  d.drift = fit.slope;
  d.low = fit.low;
  d.high = fit.high;
  d.over_run = fit.slope * (times[d.windows - 1] - times.front());
  d.no_drift = (fit.low <= 0.0 && 0.0 <= fit.high) || std::abs(d.over_run) <= round_off;
  return d;
}

bool ContactPhases::add(double t, bool contact) {
  const bool starts = contact && !in_contact_ && t - last_contact_ > min_flight_;
  if (starts) starts_.push_back(t);
  if (contact) last_contact_ = t;
  in_contact_ = contact;
  return starts;
}

std::size_t compared_impacts(const std::vector<double>& exact, std::size_t count, double min_flight) {
  std::size_t n = 0;
  while (n < count && n < exact.size()) {
    if (min_flight > 0.0 && (n + 1 >= exact.size() || exact[n + 1] - exact[n] < min_flight)) break;
    ++n;
  }
  return n;
}

void FlightEnergies::add(double t, bool contact, double energy) {
  if (at_ == At::exact_mid_flight) {
    const std::size_t i = errors_.size();  // flight i + 1, after impact i + 1
    if (i < flights_ && i + 1 < impacts_.size() && t >= 0.5 * (impacts_[i] + impacts_[i + 1])) {
      measured_.push_back(energy);
      errors_.push_back(energy / energies_[i] - 1.0);
    }
    return;
  }
  if (errors_.size() >= flights_) return;
  if (phases_.add(t, contact)) {
    // Phase n starts at this step: flight n - 1 is over, its steps k_{n-1} .. k_n - 1 buffered.
    if (const std::size_t n = phases_.starts().size(); n >= 2) {
      measured_.push_back(since_start_[since_start_.size() / 2]);
      errors_.push_back(measured_.back() / energies_[n - 2] - 1.0);
    }
    since_start_.clear();
  }
  if (!phases_.starts().empty()) since_start_.push_back(energy);
}

double FlightEnergies::largest() const {
  double largest = errors_.empty() ? kNaN : 0.0;
  for (double x : errors_) largest = std::max(largest, std::abs(x));
  return largest;
}

double rest_bound(double at_most, int power, double dt) {
  for (int k = 0; k < power; ++k) at_most *= dt;
  return at_most;
}

double ContactPhases::span(double dt) const {
  return starts_.empty() ? std::numeric_limits<double>::quiet_NaN() : last_contact_ - starts_.front() + dt;
}

void Chatter::add(double value) {
  if (values_ >= 2) {
    const double d2 = 0.25 * (value - 2.0 * last_ + before_);
    square_ += d2 * d2;
  }
  zeros_ += value == 0.0;
  before_ = last_;
  last_ = value;
  ++values_;
}

double Chatter::rms() const {
  return values_ < 3 ? std::numeric_limits<double>::quiet_NaN() : std::sqrt(square_ / static_cast<double>(values_ - 2));
}

ContactImpacts::ContactImpacts(const Vec& initial_gaps, double initial_value) : previous_(initial_value) {
  const double carrying = -std::numeric_limits<double>::infinity();
  for (Index i = 0; i < initial_gaps.size(); ++i) {
    carrying_.push_back(initial_gaps[i] <= 0.0);
    open_peak_.push_back(carrying_.back() ? carrying : initial_gaps[i]);
    last_gap_.push_back(initial_gaps[i]);
  }
}

void ContactImpacts::add(double t, const Vec& impulses, const Vec& gaps, double value) {
  bool struck = false;
  for (std::size_t i = 0; i < carrying_.size(); ++i) {
    const auto k = static_cast<Index>(i);
    const bool carries = impulses[k] > 0.0;
    const bool approached = open_peak_[i] > 0.0 && last_gap_[i] < open_peak_[i];
    struck = struck || (carries && !carrying_[i] && approached);
    carrying_[i] = carries;
    open_peak_[i] = carries ? -std::numeric_limits<double>::infinity() : std::max(open_peak_[i], gaps[k]);
    last_gap_[i] = gaps[k];
  }
  if (struck)
    impacts_.push_back({t, previous_, value, 0.0});
  else if (!impacts_.empty())
    impacts_.back().amplitude = std::max(impacts_.back().amplitude, std::abs(value));
  previous_ = value;
}

double rocking_law_ratio(const Problem& problem, ImpactLaw law) {
  const ExactSolution* exact = problem.exact();
  const ExactValue ratio = law == ImpactLaw::housner ? ExactValue::housner_ratio : ExactValue::impact_ratio;
  return (exact ? exact->value(ratio) : std::nullopt).value_or(kNaN);
}

std::size_t rocking_exact_impacts(const Problem& problem) {
  return problem.exact() ? problem.exact()->amplitudes_after_impacts().size() : 0;
}

double rocking_amplitude_after(const Problem& problem, std::size_t k) {
  const std::vector<double> amplitudes = problem.exact() ? problem.exact()->amplitudes_after_impacts() : std::vector<double>{};
  return k == 0 || k > amplitudes.size() ? kNaN : amplitudes[k - 1];
}

double rocking_rest_time(const Problem& problem) {
  return (problem.exact() ? problem.exact()->event_time(ExactEvent::rest) : std::nullopt).value_or(kNaN);
}

double painleve_jam_time(const Problem& problem) {
  return (problem.exact() ? problem.exact()->event_time(ExactEvent::jam) : std::nullopt).value_or(kNaN);
}

double summary_value(const Problem& problem, const std::string& name) {
  for (const auto& [key, value] : problem.summary_values())
    if (key == name) return value;
  return kNaN;
}

Column cost_column() {
  return {"CPU", "s", "{:.2e}", "thread CPU time of the stepping of the observed run (observer excluded)", true};
}

}  // namespace nsb
