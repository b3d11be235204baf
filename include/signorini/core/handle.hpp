// Move-only RAII owners for PETSc objects, and the compile-time PETSc version check.
#pragma once

#include <petscdmplex.h>
#include <petscksp.h>
#include <petscsf.h>
#include <petscversion.h>

#include <utility>

#if PETSC_VERSION_LT(3, 18, 0)
#error "signorini needs PETSc 3.18 or newer"
#endif

namespace signorini {

/// Owns one PETSc object and destroys it when it goes out of scope (on the ranks of the object's communicator).
template <typename T, PetscErrorCode (*Destroy)(T *)> class Handle {
public:
  Handle() = default;
  explicit Handle(T obj) : obj_(obj) {}
  Handle(const Handle &) = delete;
  Handle &operator=(const Handle &) = delete;
  Handle(Handle &&other) noexcept : obj_(std::exchange(other.obj_, nullptr)) {}
  Handle &operator=(Handle &&other) noexcept {
    if (this != &other) {
      Reset();
      obj_ = std::exchange(other.obj_, nullptr);
    }
    return *this;
  }
  ~Handle() { Reset(); }

  /// Destroys the held object (collective on its communicator).
  void Reset() noexcept {
    if (obj_) (void)Destroy(&obj_);
    obj_ = nullptr;
  }
  T get() const { return obj_; }
  operator T() const { return obj_; }
  /// Address for PETSc "create" functions; the previous object is destroyed first.
  T *out() {
    Reset();
    return &obj_;
  }
  explicit operator bool() const { return obj_ != nullptr; }

private:
  T obj_ = nullptr;
};

using VecH = Handle<Vec, VecDestroy>;
using MatH = Handle<Mat, MatDestroy>;
using KSPH = Handle<KSP, KSPDestroy>;
using ISH = Handle<IS, ISDestroy>;
using DMH = Handle<DM, DMDestroy>;
using SectionH = Handle<PetscSection, PetscSectionDestroy>;
using SFH = Handle<PetscSF, PetscSFDestroy>;
using ViewerH = Handle<PetscViewer, PetscViewerDestroy>;
using NullSpaceH = Handle<MatNullSpace, MatNullSpaceDestroy>;

/// The block of options between PetscOptionsBegin and PetscOptionsEnd, ended on an early return: declared right after
/// PetscOptionsBegin, it ends the block as PetscOptionsEnd would when a reader leaves it on an error (a PetscCall that
/// returns), so that the error path frees the block's strings; after PetscOptionsEnd (which frees the title) it does
/// nothing.
class OptionsBlockGuard {
public:
  explicit OptionsBlockGuard(PetscOptionItems *items) : items_(items) {}
  OptionsBlockGuard(const OptionsBlockGuard &) = delete;
  OptionsBlockGuard &operator=(const OptionsBlockGuard &) = delete;
  ~OptionsBlockGuard() {
    if (items_->title) (void)PetscOptionsEnd_Private(items_);
  }

private:
  PetscOptionItems *items_;
};

} // namespace signorini
