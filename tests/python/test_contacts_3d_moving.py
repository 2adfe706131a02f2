"""3D and moving contacts from Python: Problem.contacts carries T2, w2 and cone; evaluate_contacts
gives g(u), L(u), T(u), T2(u) (checked against the rocking block's closed form and against
differences of g); an integrator written in Python declares the cone (treats_friction_cone) and
fills tangential_impulses2, and runs the sphere to its exact roll onset; without the declaration
the sphere is refused naming the cone."""
import math

import numpy as np
import pytest

import nsbench


class ConeEuler(nsbench.Integrator):
    """test: symplectic Euler, each closed contact's impulse on the Coulomb cone in closed form

    Needs a diagonal mass and contacts whose Delassus blocks [L; T; T2] M^-1 [L; T; T2]^T are
    diag(w_n, w_t, w_t) (a sphere on a plane; 2D contacts: diag(w_n, w_t)): then
    Lambda_N = -q_N / w_n and Lambda_T the trial -q_T / w_t scaled onto the disk (the interval in
    2D) of radius mu Lambda_N."""

    treats_friction = True
    treats_friction_cone = True

    def init(self, problem, initial):
        self.bind(problem, initial)
        c = problem.contacts
        self.minv = 1.0 / self.mass.diagonal()
        self.tangents = 2 if c["cone"] else 1
        rows = [c["L"], c["T"], c["T2"]][: 1 + self.tangents]
        # Each contact's rows, dense (k x n), and the obstacle's tangential velocity.
        self.rows = [np.vstack([r.tocsr()[i].toarray() for r in rows]) for i in range(c["g0"].shape[0])]
        self.w = np.stack([c["w"], c["w2"]], axis=1)[:, : self.tangents]
        self.g0, self.e, self.mu, self.L = c["g0"], c["e"], c["mu"], c["L"].tocsr()
        self.f_ext = problem.external_force(initial.t)
        self.blocks = []
        for R in self.rows:
            W = (R * self.minv) @ R.T
            if np.count_nonzero(W - np.diag(np.diag(W))) or len(set(np.diag(W)[1:])) != 1:
                raise ValueError(f"test-cone-euler needs contact blocks diag(w_n, w_t, w_t); {problem.name} has another")
            self.blocks.append((W[0, 0], W[1, 1]))

    def step(self, h):
        s = self.state
        v = s.v + h * self.minv * self.f_ext
        for impulses in (self.impulses, self.tangential_impulses, self.tangential_impulses2):
            impulses[:] = 0.0
        for i in np.flatnonzero(self.g0 + self.L @ (s.u + h * v) <= 0.0):
            R, (w_n, w_t) = self.rows[i], self.blocks[i]
            q = R @ v
            lam_n = max(0.0, -(q[0] + self.e * (R[0] @ s.v)) / w_n)
            lam_t = -(q[1:] - self.w[i]) / w_t
            if np.linalg.norm(lam_t) > self.mu[i] * lam_n:
                lam_t *= self.mu[i] * lam_n / np.linalg.norm(lam_t)
            self.impulses[i], self.tangential_impulses[i] = lam_n, lam_t[0]
            if self.tangents == 2:
                self.tangential_impulses2[i] = lam_t[1]
            v = v + self.minv * (R.T @ np.concatenate([[lam_n], lam_t]))
        s.u += h * v
        s.v[:] = v
        return h


class PlaneFriction(ConeEuler):
    """test: the same scheme, not declaring the cone"""

    treats_friction_cone = False


for name, cls in [("test-cone-euler", ConeEuler), ("test-plane-friction", PlaneFriction)]:
    if name not in {e["name"] for e in nsbench.integrators()}:
        nsbench.register_integrator(name, cls)


def test_the_sphere_has_a_second_tangent_row_and_the_cone():
    p = nsbench.Problem("sphere", R=0.1)
    c = p.contacts
    assert c["cone"] and c["T2"].shape == (1, 6) and c["w2"].shape == (1,)
    # The header's rows: slip w_y = v_y + R omega_x along T2.
    assert np.array_equal(c["T2"].toarray(), [[0, 1, 0, 0.1, 0, 0]])
    flat = nsbench.Problem("bouncing-mass").contacts
    assert not flat["cone"] and flat["T2"].nnz == 0 and np.array_equal(flat["w2"], np.zeros(1))
    assert not nsbench.Problem("sphere", mu=0).contacts["cone"]


def test_evaluate_contacts_follows_the_rocking_blocks_corners():
    b, h = 0.2, 0.6
    p = nsbench.Problem("rocking-block", b=b, h=h, mu=0.5)
    assert p.contacts_move and not nsbench.Problem("bouncing-mass").contacts_move
    rng = np.random.default_rng(3)
    for _ in range(5):
        u = np.array([0.0, 1.0, 0.0]) + rng.uniform(-0.3, 0.3, 3)
        at = p.evaluate_contacts(u)
        th = u[2]
        for i, px in enumerate([b, -b]):  # right corner (contact 0), left corner (contact 1)
            assert at["g"][i] == pytest.approx(u[1] + px * math.sin(th) - h * math.cos(th), abs=1e-14)
            assert np.allclose(at["L"][i].toarray(), [[0, 1, px * math.cos(th) + h * math.sin(th)]], atol=1e-14)
            assert np.allclose(at["T"][i].toarray(), [[1, 0, -px * math.sin(th) + h * math.cos(th)]], atol=1e-14)
        assert at["T2"].nnz == 0  # 2D contacts
        # L(u) is dg/du: central differences along a random direction.
        d, eps = rng.uniform(-1, 1, 3), 1e-6
        fd = (p.evaluate_contacts(u + eps * d)["g"] - p.evaluate_contacts(u - eps * d)["g"]) / (2 * eps)
        assert np.allclose(fd, at["L"] @ d, rtol=1e-8, atol=1e-10)
    with pytest.raises(ValueError, match="u: 2 values given"):
        p.evaluate_contacts(np.zeros(2))


def test_capabilities_are_read_from_the_class():
    info = {e["name"]: e for e in nsbench.integrators()}
    assert info["test-cone-euler"]["friction_cone"] and not info["test-cone-euler"]["moving_contacts"]
    assert not info["test-plane-friction"]["friction_cone"]
    assert info["cd-lagrange"]["friction_cone"] and info["cd-lagrange"]["moving_contacts"]


def test_a_python_cone_scheme_runs_the_sphere_to_its_roll_onset():
    dt = 1e-4
    r = nsbench.run("sphere", "test-cone-euler", dt=dt, t_end=0.6)
    assert r.status == "ok"
    t_roll = r.summary["problem_summary"]["t_roll_exact"]
    assert 0.0 < t_roll < 0.6
    sliding = r.t[r.slip_speed > 1e-9]
    # Rolling from the first step past the exact onset on (a first-order scheme: within a few steps).
    assert abs(sliding.max() - t_roll) < 3 * dt, (sliding.max(), t_roll)
    before = r.t < t_roll - 3 * dt
    assert np.allclose(r.slip_speed[before], r.slip_speed_exact[before], rtol=0, atol=1e-4)  # O(dt): 2.2e-5 at dt 1e-4


def test_without_the_declaration_the_cone_is_refused():
    with pytest.raises(ValueError, match="needs 2D contacts .* the Coulomb cone"):
        nsbench.run("sphere", "test-plane-friction", dt=1e-3, t_end=0.1)
    # The same class runs 2D friction: only the cone is refused.
    assert nsbench.run("sliding-mass", "test-plane-friction", dt=1e-3, t_end=0.1).status == "ok"
