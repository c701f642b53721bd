#include "stocs_ros/config_reference/config_reference.h"

#include <fmt/format.h>

#include <algorithm>

#include "stocs/segmentation/segmentation_network_params.h"
#include "stocs/util/param_docs.h"
#include "stocs_ros/common/node_config.h"
#include "stocs_ros/demo_recorder/demo_recorder_params.h"
#include "stocs_ros/scene_publisher/scene_publisher_params.h"
#include "stocs_ros/segmentation_node/segmentation_output_params.h"
#include "stocs_ros/stocs_node/stocs_node_params.h"

namespace stocs_ros {
namespace {

constexpr char kYamlHead[] =
    R"(# stocs_ros node configuration: every key with its default value. Generated from the parameter
# schemas by scripts/update_config_reference.sh (docs/parameters.md has the same keys as a table);
# edit the schemas, not this file. Paths may be absolute, relative to this file,
# package://PKG/PATH, and may use $(env VAR) as in roslaunch and $(dataset): the node's ~dataset
# parameter, which the launch files set from their dataset:= argument.

# The objects to estimate. Each needs a name (topic and TF name: letters, digits, underscores) and a
# model; the example is object 6 (cat) of the real LM-O frame (lmo-cat in ../shared/datasets), its
# model named inside the dataset being played, so that
#   roslaunch stocs_ros bop_playback.launch dataset:=/path/to/lmo-cat
# needs no environment variable. Without a dataset (stocs.launch on a live camera) name models by
# path or package:// instead.
objects:
  - name: cat
    id: 6                      # numeric id in ~objects (default: position in this list + 1)
    model: $(dataset)/models/obj_000006.ply
    unit_scale: 0.001          # model units to metres (BOP models are in mm)
    mesh: ""                   # rviz mesh (package://, path); empty: an OBJ, STL, DAE, glTF or
                               # GLB model itself, else the model samples
    # mesh_scale: 0.001        # mesh units to metres (default: unit_scale)
    symmetries:                # as in BOP models_info.json, in model units
      discrete: []             # row-major 4x4 transforms, identity not listed
      continuous: []           # [{axis: [0, 0, 1], offset: [0, 0, 0]}]

)";

constexpr char kMarkdownHead[] = R"(# Parameters

Every key of the node's configuration file, with its default, unit, allowed values and meaning.
Generated from the parameter schemas by `scripts/update_config_reference.sh`, like
[`config/default.yaml`](../config/default.yaml), which lists the same keys with their defaults.
The estimation keys are also options of `stocs estimate`, `stocs bench` and `stocs prepare`.

## Objects

`objects` is a list; each entry has:

| key | default | meaning |
|---|---|---|
| `name` | required | topic and TF name: a letter, then letters, digits and underscores |
| `id` | position in the list + 1 | numeric id in `~objects` (the BOP `obj_id` for BOP models) |
| `model` | required | model file (PLY, PCD, OBJ, STL, DAE, glTF, GLB; its frame is the file's own, [models](ros.md#models)): absolute, relative to the configuration file, `package://PKG/PATH`, with `$(env VAR)` and `$(dataset)` (the node's `~dataset` parameter) |
| `unit_scale` | `0.001` | model units to metres (BOP models are in mm) |
| `mesh` | `""` | rviz mesh resource for the markers (empty: the model file itself for an OBJ, STL, DAE, glTF or GLB model, drawn in the frame the estimator reads it in; model points for PLY and PCD) |
| `mesh_scale` | `unit_scale` | mesh units to metres |
| `symmetries` | `models_info.json` beside a BOP model `obj_<id>.ply`, else none | `discrete` (4x4 row-major) and `continuous` (`axis`, `offset`), as in BOP `models_info.json`, model units; every output gives one of the equivalent poses: the one nearest the track's previous pose, else the one whose axes are nearest the camera's |

`input.channels` (with `input.probability: multichannel`) lists the object name of each channel of
`~probability` in order, `-` for a channel to ignore.

)";

/// The segmentation node's private parameters: the network's, then how it publishes the maps.
stocs::DescribedParams segmentationNodeKeys() {
  stocs::DescribedParams keys =
      stocs::SegmentationNetworkParams::schema().describe(stocs::SegmentationNetworkParams());
  for (auto& key : SegmentationOutputParams::schema().describe(SegmentationOutputParams())) {
    keys.push_back(std::move(key));
  }
  return keys;
}

}  // namespace

std::string defaultConfigYaml() {
  return kYamlHead + stocs::paramsYaml(NodeConfig::schema().describe(NodeConfig()));
}

std::string parametersMarkdown() {
  const NodeConfig node;
  stocs::DescribedParams node_keys = NodeConfig::schema().describe(node);
  node_keys.erase(std::remove_if(node_keys.begin(), node_keys.end(),
                                 [](const auto& p) {
                                   return p.first.key.rfind("estimation.", 0) == 0 ||
                                          p.first.key.rfind("tracking.", 0) == 0;
                                 }),
                  node_keys.end());
  return fmt::format(
             "{}## Inputs, outputs, cache\n\n{}\n## Estimation\n\nUnder `estimation:` in the file; "
             "the last column is the option of the `stocs` tool.\n\n{}\n## Tracking\n\nUnder "
             "`tracking:` in the file ([docs/ros.md](ros.md#tracking)); the last column is the "
             "option of "
             "`stocs estimate`, which detects every image unless given `--track`.\n\n{}\n## "
             "Segmentation "
             "network\n\nPrivate parameters of "
             "`segmentation_node` ([docs/ros.md](ros.md#segmentation-node)); config/segmenter.yaml "
             "sets "
             "them for the package's own network.\n\n{}\n## Scene publisher\n\nPrivate parameters "
             "of "
             "`scene_publisher` ([docs/ros.md](ros.md#scene-publisher)).\n\n{}\n## Demo "
             "recorder\n\n"
             "Private parameters of `demo_recorder`, the demo's listener "
             "(`launch/demo.launch`).\n\n{}",
             kMarkdownHead, stocs::paramsMarkdown(node_keys, "", false),
             stocs::paramsMarkdown(
                 stocs::PipelineParams::schema().describe(stocs::PipelineParams()), "estimation.",
                 true),
             stocs::paramsMarkdown(stocs::TrackingParams::schema().describe(node.tracking),
                                   "tracking.", true),
             stocs::paramsMarkdown(segmentationNodeKeys(), "", false),
             stocs::paramsMarkdown(ScenePublisherParams::schema().describe(ScenePublisherParams()),
                                   "", false),
             stocs::paramsMarkdown(DemoRecorderParams::schema().describe(DemoRecorderParams()), "",
                                   false)) +
         fmt::format(
             "\n## StoCS node\n\nPrivate ROS parameters of `stocs_node` and the nodelet, beside "
             "the configuration file ([docs/ros.md](ros.md#parameters)).\n\n{}",
             stocs::paramsMarkdown(StocsNodeParams::schema().describe(StocsNodeParams()), "",
                                   false));
}

}  // namespace stocs_ros
