#pragma once
// One CVODE solver (SUNDIALS 6.x) behind a small RAII class, shared by the reference
// integrators. CVODE integrates y' = f(t, y) with
//   - BDF (orders 1-5), Newton iteration on  (I - gamma J) dy = r,  J = df/dy given
//     analytically in sparse CSR form and factorised by KLU (SUNLinSol_KLU, SuiteSparse); or
//   - Adams-Moulton (orders 1-12) with fixed-point iteration (no Jacobian; non-stiff);
// local error test  ||e_n||_WRMS <= 1  with weights 1 / (rtol |y_i| + atol) (0 for the
// trailing quadrature components, CvodeSettings::quadratures);
// root finding on g(t, y) with a direction per root (CVodeSetRootDirection), so that a
// root function that starts a mode at zero cannot fire again on its way out (CVODE ignores
// a function that is zero at the restart until it has left zero; but if its first step is
// shorter than its root tolerance, 100 ulp(t), a function still at zero there is reported
// again: see reference/penalty.cpp).
// CVODE's counters are reset by CVodeReInit: this class keeps the running totals.
//
// References: A. C. Hindmarsh et al., SUNDIALS: Suite of nonlinear and
// differential/algebraic equation solvers, ACM TOMS 31 (2005) 363-396; the CVODE user
// guide v6.4.1 (sundials.readthedocs.io): CVode in CV_NORMAL mode, root finding,
// CVodeReInit, SUNLinSol_KLU.
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nonlinearsolver.h>
#include <sundials/sundials_nvector.h>

#include <Eigen/SparseCore>
#include <exception>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"

namespace nsb {

// The Jacobian type handed to KLU: compressed sparse rows with SUNDIALS' index type.
using CsrMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, sunindextype>;

// What CVODE integrates. Each call may throw: the exception is carried through CVODE and
// rethrown by Cvode::advance.
class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  virtual void rhs(double t, ConstVecRef y, VecRef ydot) = 0;
  // J = df/dy at (t, y). Keeping one sparsity pattern for the whole run (explicit zeros
  // allowed) spares KLU a new symbolic analysis; a changed pattern is detected and handled.
  virtual void jacobian(double t, ConstVecRef y, CsrMatrix& J) = 0;
  virtual void roots(double t, ConstVecRef y, VecRef g) = 0;
};

struct CvodeSettings {
  bool bdf = true;        // false: Adams with fixed-point iteration
  double rtol = 1e-10;
  double atol = 1e-12;
  long max_steps = 1000000;  // internal steps per call of advance
  // The last `quadratures` components are time integrals nothing else depends on: they are
  // left out of the error test (infinite absolute tolerance, weight 0), as CVODES does with
  // its quadrature variables by default. Their accuracy is that of what they integrate.
  Index quadratures = 0;
};

class Cvode {
 public:
  Cvode(OdeSystem& system, Index size, int nroots, const CvodeSettings& settings);
  ~Cvode();
  Cvode(const Cvode&) = delete;
  Cvode& operator=(const Cvode&) = delete;

  // (Re)starts the integration at (t, y): after an event, the history is discarded.
  void restart(double t, ConstVecRef y);
  // Direction of each root: -1 only decreasing, +1 only increasing, 0 both.
  void set_root_directions(const std::vector<int>& directions);
  // Integrates towards tout. Returns true when a root is found first (t, y at the root;
  // root_info() tells which, with the sign of the crossing), false at tout (y interpolated
  // at tout: CVODE may have stepped beyond it, which is not a restart).
  bool advance(double tout, double& t, VecRef y);
  const std::vector<int>& root_info() const { return roots_found_; }

  // Totals since construction: steps, RHS evaluations, Jacobian evaluations, linear-solver
  // setups (KLU factorisations), Newton iterations; root-function evaluations, error-test
  // failures and restarts in `extra`.
  void add_work(WorkCounters& w) const;

  // CVODE's own handlers, public for the C callbacks only.
  OdeSystem& system() { return system_; }
  CsrMatrix jacobian;  // filled by the system, copied into CVODE's matrix
  void copy_jacobian(const CsrMatrix& J, SUNMatrix target);
  std::exception_ptr pending;
  std::string last_error;

 private:
  void check(int flag, const char* call) const;

  OdeSystem& system_;
  Index size_;
  int nroots_;
  CvodeSettings settings_;
  SUNContext context_ = nullptr;
  void* mem_ = nullptr;
  N_Vector y_ = nullptr;
  SUNMatrix matrix_ = nullptr;             // BDF only
  SUNLinearSolver linear_ = nullptr;       // BDF only
  SUNNonlinearSolver nonlinear_ = nullptr;  // Adams only
  bool started_ = false;
  std::vector<int> roots_found_;
  std::vector<int> directions_;
  std::vector<sunindextype> pattern_;  // outer then inner indices of the last Jacobian
  CsrMatrix zero_diagonal_, with_diagonal_;  // see copy_jacobian
  struct Totals {
    long steps = 0, rhs = 0, jac = 0, setups = 0, newton = 0, roots = 0, error_fails = 0, restarts = 0;
    Totals operator+(const Totals& o) const;
  };
  Totals read_counters() const;  // CVODE's counts since the last (re)start
  Totals base_;  // up to the last restart
};

}  // namespace nsb
