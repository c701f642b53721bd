// `stocs meshes`: writes the project's own object models (object_catalogue.h) as a BOP models
// folder: obj_{id:06d}.ply in mm and models_info.json. meshes/ in the repository is its output.
#include <fmt/format.h>

#include <filesystem>

#include "commands.h"
#include "stocs/sim/bop_writer.h"
#include "stocs/util/error.h"

namespace stocs::tools {
namespace {

int runMeshes(const std::string& out) {
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (!std::filesystem::is_directory(out)) {
    throw InputError(fmt::format("{}: cannot create the folder", out));
  }
  const std::vector<CatalogueObject> objects = objectCatalogue();
  writeModels(out, objects);
  for (const CatalogueObject& o : objects) {
    fmt::print("obj_{:06d}.ply: {}, {} vertices, {} triangles\n", o.id, o.name,
               o.mesh.vertices.size(), o.mesh.triangles.size());
  }
  return 0;
}

}  // namespace

Command registerMeshes(CLI::App& app) {
  auto out = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "meshes", "Write the project's own object meshes (PLY in mm) and models_info.json");
  cmd->add_option("--out", *out, "Output folder (created if needed)")->required();
  return {cmd, [out] { return runMeshes(*out); }};
}

}  // namespace stocs::tools
