#pragma once
// Steps of estimateFrame (frame.cpp) that the frame explainer (frame_explainer.h) repeats when it
// searches an object again; not part of the public API.

#include <string>

#include "stocs/estimation/frame.h"

namespace stocs {

/// The probability map of `name` in `frame`, checked against the cloud's size; throws InputError.
const cv::Mat& probabilityOf(const Frame& frame, const std::string& name);

/// Runs `estimate` on `input` into `result`: the estimate and the CPU time it took.
void estimateObject(const ObjectInput& input, const ObjectEstimator& estimate,
                    ObjectResult& result);

}  // namespace stocs
