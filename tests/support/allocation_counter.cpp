#include "tests/support/allocation_counter.hpp"

#include <cerrno>
#include <cstddef>

namespace {
thread_local long* counter = nullptr;  // trivially initialised: no allocation on first use
inline void note() {
  if (counter) ++*counter;
}
}  // namespace

#if defined(__SANITIZE_ADDRESS__)
// The sanitizer runtime's hook interface (sanitizer/allocator_interface.h, not shipped with
// every compiler package): called on every allocation the sanitizer's allocator makes.
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*, std::size_t),
                                                         void (*free_hook)(const volatile void*));

namespace {
void on_malloc(const volatile void*, std::size_t) { note(); }
void on_free(const volatile void*) {}
[[maybe_unused]] const int installed = __sanitizer_install_malloc_and_free_hooks(on_malloc, on_free);
}  // namespace
#else
// glibc's own entry points (exported by libc.so.6); every block still comes from and goes
// back to glibc's allocator, so free, malloc_usable_size etc. stay glibc's.
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);

void* malloc(std::size_t n) {
  note();
  return __libc_malloc(n);
}
void* calloc(std::size_t k, std::size_t n) {
  note();
  return __libc_calloc(k, n);
}
void* realloc(void* p, std::size_t n) {
  note();
  return __libc_realloc(p, n);
}
void* memalign(std::size_t a, std::size_t n) {
  note();
  return __libc_memalign(a, n);
}
void* aligned_alloc(std::size_t a, std::size_t n) {
  note();
  return __libc_memalign(a, n);
}
int posix_memalign(void** p, std::size_t a, std::size_t n) {
  note();
  void* q = __libc_memalign(a, n);
  if (!q) return ENOMEM;
  *p = q;
  return 0;
}
}
#endif

namespace nsb::test {

CountAllocations::CountAllocations() : saved_(counter) { counter = &count_; }
CountAllocations::~CountAllocations() { counter = saved_; }

}  // namespace nsb::test
