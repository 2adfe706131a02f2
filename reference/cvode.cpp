#include "reference/cvode.hpp"

#include <cvode/cvode.h>
#include <fmt/format.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace nsb {

namespace {

Eigen::Map<const Vec> view(N_Vector v) { return {N_VGetArrayPointer(v), N_VGetLength(v)}; }
Eigen::Map<Vec> view_mut(N_Vector v) { return {N_VGetArrayPointer(v), N_VGetLength(v)}; }

// The callbacks run inside CVODE (C): an exception is parked in Cvode::pending and CVODE is
// told the failure is unrecoverable (-1), so that advance() can rethrow it.
template <class F>
int guarded(void* user, F&& f) {
  auto* self = static_cast<Cvode*>(user);
  try {
    f(*self);
    return 0;
  } catch (...) {
    self->pending = std::current_exception();
    return -1;
  }
}

int rhs_callback(realtype t, N_Vector y, N_Vector ydot, void* user) {
  return guarded(user, [&](Cvode& c) {
    auto out = view_mut(ydot);
    c.system().rhs(t, view(y), out);
  });
}

int root_callback(realtype t, N_Vector y, realtype* g, void* user) {
  return guarded(user, [&](Cvode& c) {
    Eigen::Map<Vec> out(g, static_cast<Index>(c.root_info().size()));
    c.system().roots(t, view(y), out);
  });
}

int jacobian_callback(realtype t, N_Vector y, N_Vector, SUNMatrix J, void* user, N_Vector, N_Vector, N_Vector) {
  return guarded(user, [&](Cvode& c) {
    c.system().jacobian(t, view(y), c.jacobian);
    c.copy_jacobian(c.jacobian, J);
  });
}

void error_handler(int, const char* module, const char* function, char* msg, void* user) {
  static_cast<Cvode*>(user)->last_error = fmt::format("{} {}: {}", module, function, msg);
}

}  // namespace

Cvode::Cvode(OdeSystem& system, Index size, int nroots, const CvodeSettings& settings)
    : system_(system), size_(size), nroots_(nroots), settings_(settings) {
  roots_found_.assign(static_cast<std::size_t>(nroots), 0);
  check(SUNContext_Create(nullptr, &context_), "SUNContext_Create");
  y_ = N_VNew_Serial(size, context_);
  mem_ = CVodeCreate(settings.bdf ? CV_BDF : CV_ADAMS, context_);
  if (!y_ || !mem_) throw std::runtime_error("CVODE: out of memory");
  N_VConst(0.0, y_);
}

Cvode::~Cvode() {
  CVodeFree(&mem_);
  if (linear_) SUNLinSolFree(linear_);
  if (nonlinear_) SUNNonlinSolFree(nonlinear_);
  if (matrix_) SUNMatDestroy(matrix_);
  if (y_) N_VDestroy(y_);
  SUNContext_Free(&context_);
}

void Cvode::check(int flag, const char* call) const {
  if (flag >= 0) return;
  throw std::runtime_error(fmt::format("{} failed: {}{}{}", call, CVodeGetReturnFlagName(flag),
                                       last_error.empty() ? "" : " - ", last_error));
}

void Cvode::restart(double t, ConstVecRef y) {
  view_mut(y_) = y;
  if (!started_) {
    check(CVodeInit(mem_, rhs_callback, t, y_), "CVodeInit");
    check(CVodeSetUserData(mem_, this), "CVodeSetUserData");
    check(CVodeSetErrHandlerFn(mem_, error_handler, this), "CVodeSetErrHandlerFn");
    if (settings_.quadratures > 0) {
      N_Vector atol = N_VClone(y_);
      if (!atol) throw std::runtime_error("CVODE: out of memory");
      view_mut(atol).setConstant(settings_.atol);
      view_mut(atol).tail(settings_.quadratures).setConstant(std::numeric_limits<double>::infinity());
      const int flag = CVodeSVtolerances(mem_, settings_.rtol, atol);  // copies atol
      N_VDestroy(atol);
      check(flag, "CVodeSVtolerances");
    } else {
      check(CVodeSStolerances(mem_, settings_.rtol, settings_.atol), "CVodeSStolerances");
    }
    check(CVodeSetMaxNumSteps(mem_, settings_.max_steps), "CVodeSetMaxNumSteps");
    if (settings_.bdf) {
      matrix_ = SUNSparseMatrix(size_, size_, std::max<Index>(size_, 1), CSR_MAT, context_);
      linear_ = SUNLinSol_KLU(y_, matrix_, context_);
      if (!matrix_ || !linear_) throw std::runtime_error("SUNLinSol_KLU: could not be created");
      check(CVodeSetLinearSolver(mem_, linear_, matrix_), "CVodeSetLinearSolver");
      check(CVodeSetJacFn(mem_, jacobian_callback), "CVodeSetJacFn");
    } else {
      nonlinear_ = SUNNonlinSol_FixedPoint(y_, 0, context_);
      if (!nonlinear_) throw std::runtime_error("SUNNonlinSol_FixedPoint: could not be created");
      check(CVodeSetNonlinearSolver(mem_, nonlinear_), "CVodeSetNonlinearSolver");
    }
    if (nroots_ > 0) {
      check(CVodeRootInit(mem_, nroots_, root_callback), "CVodeRootInit");
      check(CVodeSetNoInactiveRootWarn(mem_), "CVodeSetNoInactiveRootWarn");
      if (!directions_.empty()) check(CVodeSetRootDirection(mem_, directions_.data()), "CVodeSetRootDirection");
    }
    started_ = true;
    return;
  }
  base_ = base_ + read_counters();
  ++base_.restarts;
  check(CVodeReInit(mem_, t, y_), "CVodeReInit");
}

void Cvode::set_root_directions(const std::vector<int>& directions) {
  directions_ = directions;
  if (started_ && nroots_ > 0) check(CVodeSetRootDirection(mem_, directions_.data()), "CVodeSetRootDirection");
}

bool Cvode::advance(double tout, double& t, VecRef y) {
  last_error.clear();
  realtype treached = t;
  const int flag = CVode(mem_, tout, y_, &treached, CV_NORMAL);
  if (pending) {
    auto e = pending;
    pending = nullptr;
    std::rethrow_exception(e);
  }
  check(flag, "CVode");
  t = treached;
  y = view(y_);
  if (flag == CV_ROOT_RETURN) {
    check(CVodeGetRootInfo(mem_, roots_found_.data()), "CVodeGetRootInfo");
    return true;
  }
  std::fill(roots_found_.begin(), roots_found_.end(), 0);
  return false;
}

void Cvode::copy_jacobian(const CsrMatrix& system_jacobian, SUNMatrix target) {
  if (!system_jacobian.isCompressed()) throw std::logic_error("Cvode: the Jacobian must be compressed");
  // CVODE forms I - gamma J in this matrix. SUNMatScaleAddI_Sparse works in place only when
  // every diagonal entry is in the pattern, and otherwise rebuilds the matrix at each Newton
  // setup: 85% of penalty-bdf's run time on the 32x32 block. Explicit zeros put them there.
  if (zero_diagonal_.rows() != size_) {
    zero_diagonal_.resize(size_, size_);
    zero_diagonal_.setIdentity();
    zero_diagonal_ *= 0.0;
  }
  with_diagonal_ = system_jacobian + zero_diagonal_;
  with_diagonal_.makeCompressed();
  const CsrMatrix& J = with_diagonal_;
  const sunindextype nnz = J.nonZeros();
  if (SM_NNZ_S(target) < nnz) SUNSparseMatrix_Reallocate(target, nnz);
  const sunindextype* outer = J.outerIndexPtr();
  const sunindextype* inner = J.innerIndexPtr();
  std::copy(outer, outer + size_ + 1, SM_INDEXPTRS_S(target));
  std::copy(inner, inner + nnz, SM_INDEXVALS_S(target));
  std::copy(J.valuePtr(), J.valuePtr() + nnz, SM_DATA_S(target));
  // KLU refactors on the pattern it analysed first: a new pattern needs a new analysis.
  const bool same = pattern_.size() == static_cast<std::size_t>(size_ + 1 + nnz) &&
                    std::equal(outer, outer + size_ + 1, pattern_.begin()) &&
                    std::equal(inner, inner + nnz, pattern_.begin() + size_ + 1);
  if (!same) {
    if (!pattern_.empty()) SUNLinSol_KLUReInit(linear_, target, SM_NNZ_S(target), SUNKLU_REINIT_PARTIAL);
    pattern_.assign(outer, outer + size_ + 1);
    pattern_.insert(pattern_.end(), inner, inner + nnz);
  }
}

Cvode::Totals Cvode::read_counters() const {
  Totals c;
  if (!started_) return c;
  CVodeGetNumSteps(mem_, &c.steps);
  CVodeGetNumRhsEvals(mem_, &c.rhs);
  CVodeGetNumGEvals(mem_, &c.roots);
  CVodeGetNumErrTestFails(mem_, &c.error_fails);
  CVodeGetNumNonlinSolvIters(mem_, &c.newton);
  if (settings_.bdf) {
    CVodeGetNumJacEvals(mem_, &c.jac);
    CVodeGetNumLinSolvSetups(mem_, &c.setups);
  }
  return c;
}

Cvode::Totals Cvode::Totals::operator+(const Totals& o) const {
  return {steps + o.steps, rhs + o.rhs, jac + o.jac, setups + o.setups, newton + o.newton,
          roots + o.roots, error_fails + o.error_fails, restarts + o.restarts};
}

void Cvode::add_work(WorkCounters& w) const {
  const Totals now = base_ + read_counters();
  w.steps = now.steps;
  w.force_evaluations = now.rhs;
  w.tangent_evaluations = now.jac;
  w.factorizations = now.setups;
  w.linear_solves = settings_.bdf ? now.newton : 0;
  w.extra["nonlinear_iterations"] = static_cast<double>(now.newton);
  w.extra["root_evaluations"] = static_cast<double>(now.roots);
  w.extra["error_test_failures"] = static_cast<double>(now.error_fails);
  w.extra["restarts"] = static_cast<double>(now.restarts);
}

}  // namespace nsb
