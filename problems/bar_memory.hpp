#pragma once
// The memory check of the bar problems (signorini-bar and its variants, two-bars,
// mass-on-bar), before anything of size N is allocated (without it a bar too large for the
// memory ended in std::bad_alloc or in the OOM killer: docs/measurements.md). The estimate is
// kBarBytesPerElement per element: the construction's triplet lists, K, M and the element
// stiffnesses, and a run's state and work vectors (the peak of a large run:
// docs/measurements.md).
#include <string>

namespace nsb {

inline constexpr double kBarBytesPerElement = 200.0;

// Throws InputError "WHAT needs about X GiB, more than the Y GiB available (SOURCE); valid:
// PARAM <= Z" (Z the most elements that fit) when `elements` bar elements do not fit in
// memory_available() (core/environment.hpp).
void require_bar_memory(double elements, const std::string& what, const std::string& param);

// The same for elements of `bytes_per_element` bytes each (bar-3d's hexahedra).
void require_element_memory(double elements, double bytes_per_element, const std::string& what, const std::string& param);

}  // namespace nsb
