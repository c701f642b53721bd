#include "stocs_ros/stocs_node/estimation_setup.h"

#include <fmt/format.h>

#include "stocs/util/error.h"

namespace stocs_ros {

std::shared_ptr<const EstimationSetup> EstimationSetup::load(
    const std::filesystem::path& config_file, const std::filesystem::path& dataset,
    const std::function<void(const std::string&)>& log) {
  auto setup = std::make_shared<EstimationSetup>();
  setup->config = loadNodeConfig(config_file, dataset);
  const stocs::ModelCache cache(setup->config.model_cache);
  for (const ObjectConfig& o : setup->config.objects) {
    stocs::CacheReport report;
    try {
      stocs::PreparedModel m =
          cache.load(o.model.string(), o.unit_scale, setup->config.estimation.model, &report);
      m.symmetries = o.symmetries;
      setup->models.push_back(std::make_shared<const stocs::PreparedModel>(std::move(m)));
    } catch (const stocs::InputError& e) {
      throw stocs::InputError(fmt::format("object '{}': {}", o.name, e.what()));
    }
    const stocs::PreparedModel& m = *setup->models.back();
    log(fmt::format("object '{}' (id {}): {} samples, diameter {:.3f} m, PPF map {:.2f} MB, {}{}",
                    o.name, o.id, m.model.size(), m.model.diameter, m.ppf_map.memoryBytes() / 1e6,
                    toString(report.outcome),
                    report.detail.empty() ? "" : " (" + report.detail + ")"));
  }
  return setup;
}

}  // namespace stocs_ros
