#include "stocs/stocs.h"

#include <fmt/format.h>

#include <algorithm>

#include "stocs/util/error.h"

namespace stocs {

Estimator::Estimator(PipelineParams params, ModelCache cache)
    : params_((params.validate(), std::move(params))), cache_(std::move(cache)) {}

void Estimator::addObject(const std::string& name, const std::string& model_file,
                          float unit_scale) {
  addObject(name, std::make_shared<const PreparedModel>(
                      cache_.load(model_file, unit_scale, params_.model)));
}

void Estimator::addObject(const std::string& name, std::shared_ptr<const PreparedModel> model) {
  if (!model) throw InputError(fmt::format("object '{}': no model", name));
  if (this->model(name)) throw InputError(fmt::format("object '{}' is added already", name));
  objects_.emplace_back(name, std::move(model));
}

std::shared_ptr<const PreparedModel> Estimator::model(const std::string& name) const {
  const auto it = std::find_if(objects_.begin(), objects_.end(),
                               [&](const auto& o) { return o.first == name; });
  return it == objects_.end() ? nullptr : it->second;
}

std::vector<ObjectResult> Estimator::estimate(const Frame& frame) const {
  std::vector<FrameObject> objects;
  for (const auto& [name, model] : objects_) {
    if (frame.probabilities.count(name)) objects.push_back({name, model.get()});
  }
  return estimateFrame(frame, objects, params_);
}

PoseEstimate Estimator::estimate(const Frame& frame, const std::string& object) const {
  const std::shared_ptr<const PreparedModel> m = model(object);
  if (!m) throw InputError(fmt::format("unknown object '{}'", object));
  return estimateFrame(frame, {{object, m.get()}}, params_).front().estimate;
}

}  // namespace stocs
