// Results do not depend on the thread count (core/threads.hpp): the block's element loops
// (F_int, K, strain energy) and a whole CD-Lagrange run with contacts give bit-identical
// numbers on 1, 2 and 3 threads (3: rows split unevenly between threads).
#include <catch2/catch.hpp>

#include "core/threads.hpp"
#include "integrators/cd_lagrange.hpp"
#include "run/run.hpp"
#include "problems/block_2d.hpp"
#include "problems/signorini_bar.hpp"

namespace {

nsb::Block2d make_threaded_block(const std::string& material) {
  // Large enough for the loops to go parallel (block_2d.cpp: 2048 elements, threads.hpp:
  // 4096 dofs per thread); an odd row count, so the two parities hold different numbers of rows.
  return nsb::Block2d(nsb::Params(nsb::Block2d::parameters_spec(),
                                  {{"nx", "128"}, {"ny", "65"}, {"material", material}, {"spin", "2"}, {"height", "0.001"}}));
}

struct Evaluations {
  nsb::Vec f;
  nsb::Vec k;  // K's values
  double energy;
  nsb::State final;
};

Evaluations evaluate(const nsb::Block2d& b, int threads) {
  const nsb::ThreadScope scope(threads);
  REQUIRE(nsb::run_threads() == threads);
  Evaluations out;
  nsb::Vec u(b.ndof());
  for (nsb::Index i = 0; i < u.size(); ++i) u[i] = 1e-4 * std::sin(0.37 * static_cast<double>(i));
  out.f.resize(b.ndof());
  b.internal_force(u, out.f);
  nsb::SpMat K;
  b.tangent_stiffness(u, K);
  out.k = K.coeffs();
  out.energy = b.strain_energy(u);
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  integ.init(b, b.initial_state());
  nsb::RunOptions options;
  options.dt = 0.9 * b.stable_step();
  options.t_end = 20 * options.dt;  // falls 1 mm and hits the floor
  options.sample_every = 1000;
  const auto result = nsb::run(b, integ, options);
  REQUIRE(result.status == nsb::RunStatus::Ok);
  out.final = integ.state();
  return out;
}

}  // namespace

TEST_CASE("threads: block-2d forces, tangent, energy and a CD-Lagrange run are bit-identical for 1, 2, 3 threads",
          "[core][threads]") {
  for (const std::string material : {"svk", "neo-hookean"}) {
    const auto b = make_threaded_block(material);
    const auto one = evaluate(b, 1);
    REQUIRE(one.final.u.cwiseAbs().maxCoeff() > 1e-3);  // the run moved
    REQUIRE(one.final.u.size() >= 3 * 4096);            // and its vector update was split
    for (const int threads : {2, 3}) {
      INFO(material << ", " << threads << " threads");
      const auto many = evaluate(b, threads);
      CHECK((many.f.array() == one.f.array()).all());
      CHECK((many.k.array() == one.k.array()).all());
      CHECK(many.energy == one.energy);
      CHECK((many.final.u.array() == one.final.u.array()).all());
      CHECK((many.final.v.array() == one.final.v.array()).all());
    }
  }
}

TEST_CASE("threads: the Signorini bar's F_int and a CD-Lagrange run into the wall are bit-identical for 1, 2, 3 threads",
          "[core][threads]") {
  // N = 3 x 4096 + 5: every count splits the nodes, unevenly for 2 and 3.
  const nsb::SignoriniBar bar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"N", "12293"}, {"mass", "singular"}}));
  const auto evaluate_bar = [&](int threads) {
    const nsb::ThreadScope scope(threads);
    nsb::Vec u(bar.ndof()), f(bar.ndof());
    for (nsb::Index i = 0; i < u.size(); ++i) u[i] = 1e-4 * std::sin(0.37 * static_cast<double>(i));
    bar.internal_force(u, f);
    nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
    integ.init(bar, bar.initial_state());
    const double dt = 0.9 * bar.stable_step();
    for (int k = 0; k < 40; ++k) integ.step(dt);  // g0 = 0: against the wall from the first step
    return std::make_pair(f, integ.state());
  };
  const auto [f1, s1] = evaluate_bar(1);
  REQUIRE(s1.u.cwiseAbs().maxCoeff() > 0.0);
  for (const int threads : {2, 3}) {
    INFO(threads << " threads");
    const auto [f, s] = evaluate_bar(threads);
    CHECK((f.array() == f1.array()).all());
    CHECK((s.u.array() == s1.u.array()).all());
    CHECK((s.v.array() == s1.v.array()).all());
  }
}

TEST_CASE("threads: a ThreadScope sets the count on its own thread and restores it", "[core][threads]") {
  const int outer = nsb::run_threads();
  {
    const nsb::ThreadScope serial(1);
    CHECK(nsb::run_threads() == 1);
    {
      const nsb::ThreadScope two(2);
      CHECK(nsb::run_threads() == 2);
    }
    CHECK(nsb::run_threads() == 1);
  }
  CHECK(nsb::run_threads() == outer);
}
