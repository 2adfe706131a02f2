#pragma once
// nsbench 0.1.0's <nsbench/integrators/coulomb.hpp>, kept one minor version: the header moved to
// <nsbench/solvers/coulomb.hpp> (CHANGELOG.md, "Plugin API: what to change").
#pragma GCC warning "nsbench 0.2.0: include <nsbench/solvers/coulomb.hpp> instead of <nsbench/integrators/coulomb.hpp> (CHANGELOG.md, 'Plugin API: what to change')"
#include "solvers/coulomb.hpp"
