// PETSc's allocations in transparent huge pages (UseHugePages).
#pragma once

#include <petscsys.h>

#include <cstddef>

namespace signorini {

/// PETSc's allocator from here on: its blocks from the C library as PETSc's own default allocator takes them
/// (interchangeable with it: a block of either is freed by either), each block of at least HUGE_PAGE_MIN_BYTES advised
/// into transparent huge pages (madvise MADV_HUGEPAGE on its 2 MiB-aligned interior) before anything touches it.
/// A first write to fresh memory costs about 1.7 us per 4 KiB page on the virtual machines measured, and the large
/// blocks (the matrices, GAMG's levels, the vectors) are written first in the set-up and the solves; with huge pages
/// the 824k-dof cube under a sphere (one rank) took 4.0-4.9 s of set-up against 4.7-7.8 s, its contact solve no
/// clearly different, 0.3 % more peak memory (docs/performance.md, fifteenth session). The C library's own
/// switch (GLIBC_TUNABLES=glibc.malloc.hugetlb=1) is read at the process's start, before a program can set it.
/// Nothing is changed when PETSc traces its allocations (-malloc_debug, -malloc_dump, -malloc_view: their checks
/// keep PETSc's allocator) or when the kernel gives no huge pages on advice. Call after PetscInitialize. Not
/// collective.
[[nodiscard]] PetscErrorCode UseHugePages();

/// Whether the kernel honours MADV_HUGEPAGE (/sys/kernel/mm/transparent_hugepage/enabled: "always" or "madvise").
bool HugePagesOnAdvice();

/// The allocator's entries (PetscMallocSet's signature), exposed for the unit tests.
PetscErrorCode HugePageMalloc(std::size_t bytes, PetscBool clear, int line, const char func[], const char file[],
                              void **result);
PetscErrorCode HugePageFree(void *ptr, int line, const char func[], const char file[]);
PetscErrorCode HugePageRealloc(std::size_t bytes, int line, const char func[], const char file[], void **result);

/// Blocks from this size on are advised into huge pages (two huge pages: a smaller block has no aligned one whole).
constexpr std::size_t HUGE_PAGE_MIN_BYTES = std::size_t(4) << 20;

} // namespace signorini
