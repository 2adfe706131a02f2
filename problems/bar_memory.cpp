#include "problems/bar_memory.hpp"

#include <fmt/format.h>

#include "core/environment.hpp"
#include "core/parameters.hpp"

namespace nsb {

void require_bar_memory(double elements, const std::string& what, const std::string& param) {
  require_element_memory(elements, kBarBytesPerElement, what, param);
}

void require_element_memory(double elements, double bytes_per_element, const std::string& what, const std::string& param) {
  std::string source;
  const double needed = elements * bytes_per_element, available = memory_available(source);
  if (needed > available)
    throw InputError(fmt::format("{} needs about {:.3g} GiB, more than the {:.3g} GiB available ({}); valid: {} <= {}", what,
                                 needed / 1073741824.0, available / 1073741824.0, source, param,
                                 static_cast<long>(available / bytes_per_element)));
}

}  // namespace nsb
