#pragma once
// nsbench 0.1.0's <nsbench/integrators/run.hpp>, kept one minor version: the header moved to
// <nsbench/run/run.hpp> (CHANGELOG.md, "Plugin API: what to change").
#pragma GCC warning "nsbench 0.2.0: include <nsbench/run/run.hpp> instead of <nsbench/integrators/run.hpp> (CHANGELOG.md, 'Plugin API: what to change')"
#include "run/run.hpp"
