// PETSc's allocations in transparent huge pages.
#include "signorini/core/memory.hpp"

#include <sys/mman.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

namespace signorini {

namespace {

constexpr std::uintptr_t HUGE_PAGE = std::uintptr_t(2) << 20;

/// Advises the whole huge pages inside [p, p + bytes). A fresh block of this size is a mapping of its own that
/// nothing has touched yet, so its pages are then made huge as they are first written; advice only (an error leaves
/// 4 KiB pages).
void Advise(void *p, std::size_t bytes) {
  if (!p || bytes < HUGE_PAGE_MIN_BYTES) return;
  const std::uintptr_t begin = ((std::uintptr_t)p + HUGE_PAGE - 1) & ~(HUGE_PAGE - 1);
  const std::uintptr_t end = ((std::uintptr_t)p + bytes) & ~(HUGE_PAGE - 1);
  if (end > begin) (void)madvise((void *)begin, end - begin, MADV_HUGEPAGE);
}

} // namespace

bool HugePagesOnAdvice() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(in, line);
  return line.find("[always]") != std::string::npos || line.find("[madvise]") != std::string::npos;
}

// PETSc's default (PETSC_MEMALIGN 16 on this platform) takes malloc's 16-byte aligned blocks as they come; these do
// the same, so a block allocated before UseHugePages is freed here and the other way round.
PetscErrorCode HugePageMalloc(std::size_t bytes, PetscBool clear, int, const char[], const char[], void **result) {
  PetscFunctionBeginUser;
  if (!bytes) {
    *result = nullptr;
    PetscFunctionReturn(0);
  }
  *result = clear ? std::calloc(bytes, 1) : std::malloc(bytes);
  PetscCheck(*result, PETSC_COMM_SELF, PETSC_ERR_MEM, "out of memory: %zu bytes requested", bytes);
  Advise(*result, bytes);
  PetscFunctionReturn(0);
}

PetscErrorCode HugePageFree(void *ptr, int, const char[], const char[]) {
  PetscFunctionBeginUser;
  std::free(ptr);
  PetscFunctionReturn(0);
}

PetscErrorCode HugePageRealloc(std::size_t bytes, int, const char[], const char[], void **result) {
  PetscFunctionBeginUser;
  if (!bytes) {
    std::free(*result);
    *result = nullptr;
    PetscFunctionReturn(0);
  }
  void *p = std::realloc(*result, bytes);
  PetscCheck(p, PETSC_COMM_SELF, PETSC_ERR_MEM, "out of memory: %zu bytes requested", bytes);
  *result = p;
  Advise(p, bytes);
  PetscFunctionReturn(0);
}

PetscErrorCode UseHugePages() {
  PetscBool traced, each_call, nan;
  PetscFunctionBeginUser;
  static_assert(PETSC_MEMALIGN <= alignof(std::max_align_t), "malloc's blocks must have PETSc's alignment");
  PetscCall(PetscMallocGetDebug(&traced, &each_call, &nan));
  if (traced || !HugePagesOnAdvice()) {
    PetscCall(PetscInfo(nullptr, "PETSc's allocator kept (%s)\n",
                        traced ? "its allocations are traced" : "no transparent huge pages on advice"));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscMallocSet(HugePageMalloc, HugePageFree, HugePageRealloc));
  PetscCall(
      PetscInfo(nullptr, "PETSc's blocks of %zu bytes and more in transparent huge pages\n", HUGE_PAGE_MIN_BYTES));
  PetscFunctionReturn(0);
}

} // namespace signorini
