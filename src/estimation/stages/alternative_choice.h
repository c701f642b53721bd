#pragma once
// Which way the object faces: a pose and its shape alternatives (near_symmetries.h) fit the
// segment's shape about equally, so each is refined and judged on what tells them apart, and the
// best is kept. Where nothing does, the instance names the alternatives that fit as well.

#include <vector>

#include "candidate_refinement.h"
#include "stocs/estimation/pose_estimate.h"
#include "stocs/estimation/stages/frame_evidence.h"
#include "stocs/model/model_cache.h"

namespace stocs {

/// Two alternatives whose judgements differ by less than this fit the data equally: a share of the
/// visible surface, above the noise of refinement (a few percent).
constexpr float kAlternativeTie = 0.03f;

/// Each instance against its model's shape alternatives (less the declared symmetries): every
/// alternative pose refined by ICP; the instance and the alternatives whose objective, or ranking
/// (objective times the share not in free space), is within a tenth of the instance's (the shape
/// fits them alike) judged by their colour agreement
/// (colour_agreement.h, where every candidate has colour evidence) less the share of their visible
/// surface in free space, the share of the segment they leave unexplained and the share of the
/// measured surface confirmed under another candidate that they leave out, and how far their
/// underside lies from the plane under the object where another candidate rests on it
/// (support_plane.h: a box turned onto a narrower side floats over the table; also in the
/// ranking). An alternative
/// judged better than the instance by kAlternativeTie or more replaces it (objective, covariance);
/// the distinct poses within kAlternativeTie of the kept one, support left out (a prior, not
/// data), are named in InstancePose::ambiguous,
/// and its covariance spans them. A lathe's body turns by any angle, so the kept pose turned
/// between its steps about the model's lathe axis is judged and named alike. A lathe whose ends
/// differ (a mug) has the candidates judged near the best slid along its axis, where ICP barely
/// moves them, to where the estimator's ranking is highest (least_constrained_slide.h), and judged
/// there. Adds the ICP steps
/// taken to `steps`.
void chooseAmongAlternatives(std::vector<InstancePose>& instances, const PreparedModel& model,
                             const SoftSegment& segment, const RefinementContext& context,
                             const FrameEvidence& evidence, int threads, long& steps);

}  // namespace stocs
