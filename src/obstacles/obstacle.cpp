// The registry of obstacle shapes and the reading of the -obstacle_ options.
#include "signorini/obstacles/obstacle.hpp"

#include <algorithm>
#include <cmath>

namespace signorini {

const std::vector<ShapeType> &ShapeRegistry() {
  static const std::vector<ShapeType> registry = {SegmentsShape(), ArcsShape(), DiscsShape()};
  return registry;
}

PetscErrorCode ReadObstacle(MPI_Comm comm, Obstacle &obstacle) {
  constexpr PetscInt MAX_VALUES = 60000;
  std::vector<PetscReal> values(MAX_VALUES);
  PetscFunctionBeginUser;
  obstacle.facets.clear();
  PetscOptionsBegin(comm, nullptr, "Rigid obstacle", "signorini");
  for (const ShapeType &shape : ShapeRegistry()) {
    std::fill(values.begin(), values.end(), 0.0);
    PetscInt n = MAX_VALUES;
    PetscBool set = PETSC_FALSE;
    PetscCall(PetscOptionsRealArray(shape.option, shape.help, "", values.data(), &n, &set));
    if (!set) continue;
    PetscCheck(n > 0 && n % shape.numbers == 0, comm, PETSC_ERR_USER_INPUT,
               "%s has %" PetscInt_FMT " number(s); expected a multiple of %d", shape.option, n, shape.numbers);
    for (PetscInt i = 0; i < n; ++i)
      PetscCheck(std::isfinite(values[i]), comm, PETSC_ERR_USER_INPUT,
                 "%s value %" PetscInt_FMT " is not finite; expected finite numbers", shape.option, i + 1);
    for (PetscInt k = 0; k < n / shape.numbers; ++k) {
      const std::string error = shape.build(&values[k * shape.numbers], obstacle.facets);
      PetscCheck(error.empty(), comm, PETSC_ERR_USER_INPUT, "%s item %" PetscInt_FMT " %s", shape.option, k + 1,
                 error.c_str());
    }
  }
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

} // namespace signorini
