#pragma once
// A run described as data: the case of a study written in Python (nsbench.study, python/
// nsbench/study.py) and its result, both JSON, so that the study driver (studies/driver.hpp)
// pools, shards and merges them like any study's cases. The run is `nsbench run`'s (run/
// run_case.hpp: the same names, parameter routing, checks and messages), so its numbers are
// the command line's bit for bit.
//
// The case (keys other than these are the study's own labels, kept and ignored):
//   problem, integrator      names (find_problem, find_integrator)
//   set                      ["key=value", ...], routed as `--set` (core/parameters.hpp)
//   dt | cfl                 the step, or its fraction of the problem's stable step (stable_step(),
//                            the central-difference limit): dt = cfl * stable_step
//   t_end                    > 0
//   sample_every             record every k-th step and the first and last (default 1)
//   states                   record u, v and the impulses at the samples (default false); or a list
//                            of the arrays to record: some of u, v, impulses, tangential_impulses,
//                            tangential_impulses2
//   series                   a list of the series' columns to keep, in that order (default: all)
//   max_force_evaluations    the work budget (run/run.hpp; default 0: none)
//   cpu_repeats              > 0: also time the run, cpu_cost's median of that many unobserved
//                            runs after a warm-up, and its spread (studies/study.hpp; default 0)
//   observe                  a list of run measures, each {"kind": K, its parameters...}
//                            (studies/run_measure.hpp): the run is observed step by step, its
//                            result's "observed" the figures of each in order (no series); a
//                            kind that does not apply declines the case (n/a, the reason)
//   measures, reference      a list of [[measure]] tables and a [reference] table of the study-file
//                            language (docs/study_files.md): the run is then that study file's one
//                            case, its result the engine's (status, message, steps, work counters,
//                            "values": each measure's value in order, "run": its figures), no series
// The result of a case without measures:
//   status, message          the run's (ok, diverged, over budget), or n/a with the reason when
//                            the integrator declines the problem (its init) or cfl meets a
//                            problem without a finite stable step;
//   dt, steps, force_evaluations, summary (summary.json of `nsbench run`, as an object);
//   columns, series          the series' column names and, per column, its values (series[j]): the
//                            columns kept;
//   state_t, u, v, impulses, tangential_impulses, tangential_impulses2
//                            with states: the sample times, the states and the impulses of the
//                            step that ended there (Lambda_N, Lambda_T, Lambda_T2 per contact), a
//                            row per sample: the arrays named (all with states = true);
//   cpu, cpu_spread          with cpu_repeats.
// The series' columns, state_t and the state arrays are packed: {"shape": [n] or [samples, width],
// "float64": the base64 of the little-endian doubles, row after row}, a non-finite value NaN
// (nsbench.study reads them with NumPy). Elsewhere JSON has no NaN or infinity: a non-finite
// value is null (reals(), studies/study.hpp).
#include "studies/study.hpp"

namespace nsb {

// Throws InputError naming the key on a bad case (unknown names, parameters, a missing or
// mistyped key, a step or length out of range).
Json run_described_case(const Json& the_case);

// Why `result` is not one run_described_case returns for `the_case` ("" when it is): the check of
// a shard's results (studies/shard.hpp). Its shape follows the case: plain, measured or observed.
std::string described_result_damage(const Json& the_case, const Json& result);

}  // namespace nsb
