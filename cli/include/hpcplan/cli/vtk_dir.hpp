#pragma once
// Output directories of the VTK writers (hpcplan sph, hpcplan sim).
#include <filesystem>
#include <string>

#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"

namespace hpcplan::cli {

// The VTK directory is created if its parent exists; anything else is bad input, found before
// the run starts.
inline void prepare_vtk_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(dir, ec)) {
    require_writable_destination(dir + "/fluid.pvd", "--vtk");
    return;
  }
  if (fs::exists(dir, ec)) throw InputError("--vtk '" + dir + "' exists and is not a directory");
  require_writable_destination(dir, "--vtk");  // its parent exists and is writable
  if (!fs::create_directory(dir, ec))
    throw InputError("--vtk '" + dir + "': cannot create the directory: " + ec.message());
}

}  // namespace hpcplan::cli
