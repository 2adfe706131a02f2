#pragma once
// Elementary functions that give the same bits on every machine, for nsbench's own numerics
// (models, exact solutions, references, integrators, measures).
//
// Why: glibc chooses its sin, cos, exp, log, pow, ... when the program loads, by the processor's
// features (an FMA variant where the CPU has FMA and AVX2), and the variants round differently in
// the last bit in about 2 % of arguments. So one build gave other results on another machine:
// modal-exact's hex8 bar (its modes advance by cos(w tau), sin(w tau)), the rocking block's and
// the Painleve rod's trajectories (tests/scripts/machine_settings_test.py runs them with and
// without glibc's FMA variants). These call SLEEF's deterministic scalar functions (the
// "cinz_...purec" entry points: portable C, no FMA, the same result on every platform), at most
// 1.0 ULP from the exact result (hypot 0.5 ULP), against glibc's < 1 ULP. A peer's own library
// (Siconos' OpenBLAS) keeps its machine-specific rounding: the one documented exception.
//
// Defined in core/deterministic_math.cpp: a plugin calling them needs no SLEEF header.
namespace nsb::dmath {

double sin(double x);
double cos(double x);
double tan(double x);
double asin(double x);
double atan2(double y, double x);
double exp(double x);
double expm1(double x);
double log(double x);
double pow(double x, double y);
double hypot(double x, double y);

}  // namespace nsb::dmath
