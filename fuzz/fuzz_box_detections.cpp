// 2D boxes files (BOP 2D detections, --prob boxes:FILE): the input is written as one, read by
// readBoxDetections, and every box read is drawn as a soft prior.
#include "fuzz_support.h"
#include "stocs/io/box_files.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = stocs::fuzz::scratchDir() / "boxes.json";
  stocs::fuzz::parseInputAs(file, data, size, [&] {
    for (const auto& [frame, boxes] : stocs::readBoxDetections(file)) {
      for (const stocs::BoxDetection& b : boxes) {
        stocs::boxProbability(boxes, b.class_id, cv::Size(64, 48), {});
      }
    }
  });
  return 0;
}
