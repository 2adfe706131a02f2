#pragma once
// nsbench 0.1.0's <nsbench/integrators/lcp.hpp>, kept one minor version: the header moved to
// <nsbench/solvers/lcp.hpp> (CHANGELOG.md, "Plugin API: what to change").
#pragma GCC warning "nsbench 0.2.0: include <nsbench/solvers/lcp.hpp> instead of <nsbench/integrators/lcp.hpp> (CHANGELOG.md, 'Plugin API: what to change')"
#include "solvers/lcp.hpp"
