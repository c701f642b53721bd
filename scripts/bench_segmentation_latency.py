#!/usr/bin/env python3
"""Latency of the segmentation node: publishes a colour image at RATE Hz, stamped right before it is
sent, for FRAMES frames, and takes, per probability image received, the time from that stamp to its
arrival; prints p50 and p95 and the node's own mean segmentation time from its statistics. Run
with the node up (roslaunch stocs_ros segmentation.launch image:=/bench/image); nothing else may
publish on /bench/image.
Usage: bench_segmentation_latency.py IMAGE.png [FRAMES [RATE]]
"""
import sys
import time

import numpy as np
import rospy
from diagnostic_msgs.msg import DiagnosticArray
from PIL import Image as PilImage
from sensor_msgs.msg import Image


def main():
    rgb = np.asarray(PilImage.open(sys.argv[1]).convert("RGB"))
    frames = int(sys.argv[2]) if len(sys.argv) > 2 else 100
    rate = float(sys.argv[3]) if len(sys.argv) > 3 else 5.0
    rospy.init_node("bench_segmentation_latency")
    latencies = []
    stats = {}
    rospy.Subscriber("/segmentation/probability", Image,
                     lambda m: latencies.append((rospy.Time.now() - m.header.stamp).to_sec()),
                     queue_size=5)
    rospy.Subscriber("/segmentation/statistics", DiagnosticArray,
                     lambda m: stats.update({kv.key: kv.value for kv in m.status[0].values}))
    pub = rospy.Publisher("/bench/image", Image, queue_size=2)
    while pub.get_num_connections() == 0 and not rospy.is_shutdown():
        time.sleep(0.1)
    msg = Image(height=rgb.shape[0], width=rgb.shape[1], encoding="rgb8", is_bigendian=0,
                step=rgb.shape[1] * 3, data=rgb.tobytes())
    msg.header.frame_id = "camera_optical_frame"
    start_cpu = time.process_time()
    for _ in range(frames):
        msg.header.stamp = rospy.Time.now()
        pub.publish(msg)
        time.sleep(1.0 / rate)
    time.sleep(2.0)
    lat = np.array(latencies) * 1000
    print(f"{len(lat)} of {frames} frames at {rgb.shape[1]}x{rgb.shape[0]}, {rate} Hz: latency "
          f"p50 {np.percentile(lat, 50):.1f} ms, p95 {np.percentile(lat, 95):.1f} ms; node's mean "
          f"segmentation time {float(stats.get('mean segmentation time (s)', 'nan')) * 1000:.1f} ms"
          f" (this script's CPU {time.process_time() - start_cpu:.1f} s)")


if __name__ == "__main__":
    main()
