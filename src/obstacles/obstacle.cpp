// The registry of obstacle shapes and the reading of the -obstacle_ options.
#include "signorini/obstacles/obstacle.hpp"

#include "signorini/core/options.hpp"
#include "signorini/core/parse.hpp"

#include <string>

namespace signorini {

const std::vector<ShapeType> &ShapeRegistry() {
  static const std::vector<ShapeType> registry = {SegmentsShape(), ArcsShape(),     DiscsShape(),
                                                  PlanesShape(),   SpheresShape(), CylindersShape()};
  return registry;
}

PetscErrorCode ReadObstacle(MPI_Comm comm, Obstacle &obstacle) {
  std::vector<double> values;
  PetscFunctionBeginUser;
  obstacle.facets.clear();
  obstacle.shapes.clear();
  PetscOptionsBegin(comm, nullptr, "Rigid obstacle", "signorini");
  for (const ShapeType &shape : ShapeRegistry()) {
    PetscBool set = PETSC_FALSE;
    PetscCall(OptionsRealList(PetscOptionsObject, shape.option, shape.help, "no obstacle of this shape",
                              (std::to_string(shape.numbers) + " numbers per item").c_str(), values, &set));
    if (!set) continue;
    obstacle.shapes.push_back(&shape);
    const std::size_t n = values.size(), numbers = shape.numbers;
    PetscCheck(n % numbers == 0, comm, PETSC_ERR_USER_INPUT, "%s has %zu number(s); expected a multiple of %zu",
               shape.option, n, numbers);
    for (std::size_t k = 0; k < n / numbers; ++k) {
      const std::string error = shape.build(&values[k * numbers], obstacle.facets);
      PetscCheck(error.empty(), comm, PETSC_ERR_USER_INPUT, "%s item %zu %s", shape.option, k + 1, error.c_str());
    }
  }
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode CheckObstacleDimension(MPI_Comm comm, const Obstacle &obstacle, int dim) {
  PetscFunctionBeginUser;
  std::vector<std::string> fitting;
  for (const ShapeType &shape : ShapeRegistry())
    if (shape.dim == dim) fitting.push_back(shape.option);
  for (const ShapeType *shape : obstacle.shapes)
    PetscCheck(shape->dim == dim, comm, PETSC_ERR_USER_INPUT,
               "%s is a %dD shape but the mesh is %dD; expected %s", shape->option, shape->dim, dim,
               Join(fitting, ", ").c_str());
  PetscFunctionReturn(0);
}

} // namespace signorini
