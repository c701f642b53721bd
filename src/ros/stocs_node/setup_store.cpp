#include "stocs_ros/stocs_node/setup_store.h"

#include <fmt/format.h>
#include <ros/console.h>

#include "stocs/util/error.h"

namespace stocs_ros {
namespace {

/// Reload can change models and estimation parameters, not what the node subscribes to.
void checkSameInputs(const NodeConfig& now, const NodeConfig& fresh) {
  std::vector<std::string> names_now, names_fresh;
  for (const ObjectConfig& o : now.objects) names_now.push_back(o.name);
  for (const ObjectConfig& o : fresh.objects) names_fresh.push_back(o.name);
  const InputConfig &a = now.input, &b = fresh.input;
  if (names_now != names_fresh || a.depth != b.depth || a.probability != b.probability ||
      a.channels != b.channels || a.boundary != b.boundary || a.uint16_scale != b.uint16_scale ||
      a.labels != b.labels || a.label_confidence != b.label_confidence ||
      a.sync.tolerance != b.sync.tolerance || a.sync.queue_size != b.sync.queue_size ||
      a.sync.max_age != b.sync.max_age) {
    throw stocs::InputError(fmt::format(
        "{}: the object names or the input section changed; restart the node to apply that",
        fresh.file.string()));
  }
}

}  // namespace

SetupStore::SetupStore(std::string config_file, std::string dataset)
    : config_file_(std::move(config_file)), dataset_(std::move(dataset)), setup_(load()) {}

std::shared_ptr<const EstimationSetup> SetupStore::load() const {
  return EstimationSetup::load(config_file_, dataset_,
                               [](const std::string& line) { ROS_INFO("%s", line.c_str()); });
}

std::shared_ptr<const EstimationSetup> SetupStore::current() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return setup_;
}

std::string SetupStore::reload() {
  const std::shared_ptr<const EstimationSetup> fresh = load();
  checkSameInputs(current()->config, fresh->config);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    setup_ = fresh;
  }
  return fmt::format("reloaded {} objects from {}", fresh->config.objects.size(), config_file_);
}

void SetupStore::change(const std::function<NodeConfig(const NodeConfig&)>& change) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto changed = std::make_shared<EstimationSetup>(*setup_);
  changed->config = change(setup_->config);
  setup_ = std::move(changed);
}

}  // namespace stocs_ros
