#pragma once
// Counts the heap allocations made by the calling thread while a CountAllocations is alive:
// every malloc, calloc, realloc and aligned allocation, so operator new, Eigen's
// aligned_malloc and CHOLMOD's allocations alike (allocation_counter.cpp replaces glibc's
// malloc entry points in the test binary and forwards to glibc; under AddressSanitizer it
// installs ASan's allocation hooks instead). Other threads and other tests are not counted.
namespace nsb::test {

class CountAllocations {
 public:
  CountAllocations();
  ~CountAllocations();
  CountAllocations(const CountAllocations&) = delete;
  CountAllocations& operator=(const CountAllocations&) = delete;
  long count() const { return count_; }

 private:
  long count_ = 0;
  long* saved_;
};

}  // namespace nsb::test
