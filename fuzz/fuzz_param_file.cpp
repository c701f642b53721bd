// Parameter files (`--prob onnx:SETTINGS.yaml`, read through a ParamSet schema): the input is
// written as a YAML file and read into a struct with a field of every kind a schema holds.
#include "fuzz_support.h"
#include "stocs/util/param_file.h"

namespace {

struct EveryKind {
  enum class Mode { kA, kB };
  bool flag = false;
  int count = 1;
  float share = 0.5f;
  double seconds = 1;
  std::string name;
  std::vector<std::string> names;
  Mode mode = Mode::kA;

  static const stocs::ParamSet<EveryKind>& schema() {
    static const stocs::ParamSet<EveryKind> schema =
        stocs::ParamSet<EveryKind>()
            .add(&EveryKind::flag, "flag", "a flag")
            .add(&EveryKind::count, "count", "", stocs::ParamRange::closed(0, 100), "a count")
            .add(&EveryKind::share, "share", "", stocs::ParamRange::closed(0, 1), "a share")
            .add(&EveryKind::seconds, "seconds", "s", stocs::ParamRange::aboveUpTo(0, 60), "time")
            .add(&EveryKind::name, "name", "", std::nullopt, "a string")
            .add(&EveryKind::names, "names", "", std::nullopt, "a list")
            .choice(&EveryKind::mode, "mode", {{"a", Mode::kA}, {"b", Mode::kB}}, "a choice");
    return schema;
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path file = stocs::fuzz::scratchDir() / "settings.yaml";
  stocs::fuzz::parseInputAs(file, data, size, [&] {
    EveryKind params;
    stocs::readParamFile(file, EveryKind::schema(), params);
  });
  return 0;
}
