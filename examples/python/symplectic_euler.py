"""py-symplectic-euler: an integrator written in Python (nsbench.Integrator).

Symplectic Euler (velocity first) with Moreau's velocity-level impulse contact, the scheme of the
C++ plugin example (examples/plugin/symplectic_euler.cpp):

    v_free   = v_k + h M^{-1} (F_ext(t_k) - F_int(u_k))
    u_pred   = u_k + h v_free                         (contacts closing within the step)
    Lambda_i = 0 where g_i(u_pred) > 0; on the others, by projected Gauss-Seidel,
               0 <= Lambda  _|_  g'_free + H Lambda + e g'_k >= 0,   H = L M^{-1} L^T
    v_{k+1}  = v_free + M^{-1} L^T Lambda
    u_{k+1}  = u_k + h v_{k+1}

First order, explicit (stable below the problem's stable step); needs a diagonal mass with
positive entries. References: Hairer, Lubich, Wanner, Geometric Numerical Integration (2006),
section VI.3; J.J. Moreau, CISM Courses 302 (1988).
"""
import numpy as np

import nsbench


class SymplecticEuler(nsbench.Integrator):
    """Python example: symplectic Euler, velocity-level impulse contact (Moreau)"""

    conditionally_stable = True

    def init(self, problem, initial):
        self.bind(problem, initial)
        m = self.mass.diagonal()
        if self.mass.count_nonzero() != np.count_nonzero(m) or not (m > 0).all():
            raise ValueError(f"py-symplectic-euler needs a diagonal mass with positive entries; {problem.name} has another")
        self.minv = 1.0 / m
        self.f_int = np.zeros(problem.ndof)
        self.f_ext = problem.external_force(initial.t)
        contacts = problem.contacts
        self.L, self.g0, self.e = contacts["L"].tocsr(), contacts["g0"], contacts["e"]

    def step(self, h):
        p, s = self.problem, self.state
        p.internal_force(s.u, out=self.f_int)
        self.work.force_evaluations += 1
        if not p.external_force_is_constant:
            self.f_ext = p.external_force(s.t)
        v = s.v + h * self.minv * (self.f_ext - self.f_int)
        lam = self.impulses
        lam[:] = 0.0
        closing = np.flatnonzero(self.g0 + self.L @ (s.u + h * v) <= 0.0)
        if closing.size:
            Lc = self.L[closing]
            H = (Lc.multiply(self.minv) @ Lc.T).toarray()
            rate, target = Lc @ v, -self.e * (Lc @ s.v)  # g'(+) >= -e g'(-)
            x = np.zeros(closing.size)
            for _ in range(self.params["iterations"]):
                change = 0.0
                for i in range(closing.size):
                    xi = max(0.0, x[i] - (rate[i] - target[i] + H[i] @ x) / H[i, i])
                    change, x[i] = max(change, abs(xi - x[i])), xi
                if change <= 1e-15 * max(1.0, np.abs(x).max()):
                    break
            lam[closing] = x
            v += self.minv * (Lc.T @ x)
        s.u += h * v
        s.v[:] = v
        return h  # the step taken: nsbench advances s.t by it and counts the step


def register(name="py-symplectic-euler"):
    nsbench.register_integrator(name, SymplecticEuler, parameters=[
        nsbench.Parameter.integer("iterations", 100, 1, 100000, "projected Gauss-Seidel sweeps per step (at most)")])
