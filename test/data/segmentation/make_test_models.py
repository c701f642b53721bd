#!/usr/bin/env python3
"""Writes the tiny ONNX models of test/unit/test_segmentation_network.cpp (python3-onnx only):

- pass_through.onnx: input 1x3x12x16, output = input (a 1x1 convolution with identity weights),
  so the test knows every output value from the input and the preprocessing parameters;
- half_size.onnx: the same through a 2x2 average pooling: output 1x3x6x8, which the network
  scales back to the image's size.

Run from this folder: python3 make_test_models.py
"""
import numpy as np
import onnx
from onnx import TensorProto, helper, numpy_helper


def model(name, nodes, output_shape, initializers):
    graph = helper.make_graph(
        nodes, name,
        [helper.make_tensor_value_info("rgb", TensorProto.FLOAT, [1, 3, 12, 16])],
        [helper.make_tensor_value_info("out", TensorProto.FLOAT, output_shape)],
        initializers)
    m = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 11)])
    onnx.checker.check_model(m)
    onnx.save(m, f"{name}.onnx")


identity = numpy_helper.from_array(np.eye(3, dtype=np.float32).reshape(3, 3, 1, 1), "w")
conv = helper.make_node("Conv", ["rgb", "w"], ["out"], kernel_shape=[1, 1])
model("pass_through", [conv], [1, 3, 12, 16], [identity])
conv_mid = helper.make_node("Conv", ["rgb", "w"], ["mid"], kernel_shape=[1, 1])
pool = helper.make_node("AveragePool", ["mid"], ["out"], kernel_shape=[2, 2], strides=[2, 2])
model("half_size", [conv_mid, pool], [1, 3, 6, 8], [identity])
