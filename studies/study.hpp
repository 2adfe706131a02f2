#pragma once
// A study runs a grid of cases and returns tables. Studies are listed by name in
// studies/registry.cpp (one line each) and run by the nsbench-study driver.
#include <filesystem>
#include <string>
#include <vector>

#include "studies/table.hpp"

namespace nsb {

struct StudyOptions {
  bool full = false;  // the long sweep (finer steps, bigger meshes) instead of the default
};

struct StudyEntry {
  std::string name;
  std::string description;
  std::vector<Table> (*run)(const StudyOptions&);
};

const std::vector<StudyEntry>& study_registry();

// Observed order between two refinements: log(e1/e2) / log(h1/h2); NaN when an error is
// not positive and finite.
double observed_order(double h1, double e1, double h2, double e2);
// Least-squares slope of log e against log h over the points with positive finite error;
// NaN with fewer than two such points.
double fitted_order(const std::vector<double>& h, const std::vector<double>& e);

}  // namespace nsb
