// "fpcs": PCL's 4PCS (FPCSInitialAlignment), the Super4PCS family of the paper's evaluation, on the
// hard segment. Parameters: the table in four_pcs.cpp. Score: 1 - PCL's fitness, i.e. the share of
// source samples within 2 delta of a segment point.
#include "baseline_methods.h"
#include "four_pcs.h"

namespace stocs {
namespace {

class FpcsMethod : public BaselineMethod {
 public:
  using BaselineMethod::BaselineMethod;
  std::string name() const override { return "fpcs"; }

 protected:
  std::optional<BaselineHypothesis> search(const SoftSegment& segment,
                                           const ObjectInput& input) override {
    Reseeded<FourPcs> aligner(fourPcsSeed(input.params->stocs.seed));
    return alignFourPcs(aligner, segment, input);
  }
};

}  // namespace

std::unique_ptr<PoseMethod> makeFpcsMethod(const MethodOptions& options) {
  return std::make_unique<FpcsMethod>(options.hard_threshold);
}

}  // namespace stocs
