// Soak: the node fed the generated frame (organized cloud + one 32FC1 probability image) at `rate`
// Hz for `duration` seconds over loopback, with an ~estimate call every few seconds. Checks, after
// a warm-up of `warmup` seconds:
//  - memory: the node's resident set (VmRSS of /proc/<pid>/status; pid from the node's XML-RPC
//    getPid) at the end is less than 5% above its value just after the warm-up (medians of
//    kRssWindow one-second samples, so that one allocator hiccup does not decide);
//  - accounting: every published frame is accounted for on ~statistics: each message was received,
//    and sent = estimated + replaced + rejected + kept + dropped (by reason) + still queued, with
//    no frame in progress once the input stops; every estimated frame reached ~objects;
//  - backlog: no ~statistics message after the warm-up reports more than kMaxFramesInProgress
//    frames in progress (the node's design: one estimated, one waiting, replaced by a newer one);
//  - latency (input stamp to ~objects arrival) steady, in runs whose thirds hold at least
//    kLongRunSamples outputs (the 5-minute run, not CI's 25 s, whose 6.7 s thirds a burst of the
//    shared host's load decides), last third of the time after the warm-up against the first
//    third, each at most 1.5 times:
//     - the median of the latency relative to the output's own estimation time (the sum of its
//       objects' estimation_time). A backlog grows the wait before and after estimation, so this
//       ratio; a change of the machine's load scales both when the estimation is most of the
//       latency, but not when the wait is (in the 25 s run about 1 ms of 3 ms: a CI run on
//       2026-12-01 measured 3.58 -> 7.37 on a commit whose local runs passed);
//     - the node's CPU time per output (an estimation that slows down as the node runs);
//     - the p95 (a backlog that only the slowest frames hit), which fails only when it grew both
//       in seconds and relative to the estimation time. The raw p95 alone moves with the
//       machine's load: it did, both ways, when the virtual machine lost 40-90% of its CPU time
//       to the hypervisor for minutes (steal time). The ratio's p95 alone moves with the
//       estimation time's spread, now that estimation is a small part of the latency (a CI run:
//       3.26 -> 5.82 while the raw p95 stayed at 0.184 -> 0.189 s).
// Prints a summary line (RSS, counts, latency p50/p95, CPU, load) for docs/reliability.md.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <ros/master.h>
#include <ros/network.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/PointCloud2.h>
#include <stocs_ros/Estimate.h>
#include <stocs_ros/ObjectPoseArray.h>
#include <xmlrpcpp/XmlRpc.h>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include "ros_test_support.h"

namespace stocs_ros::test {
namespace {

struct SoakParams {
  std::string dataset;
  double duration = 25;  ///< seconds of input
  double rate = 30;      ///< frames per second
  double warmup = 5;     ///< seconds before memory and latency are judged
  double service_period = 5;
};
SoakParams g_params;

constexpr char kNode[] = "/stocs";
constexpr size_t kRssWindow = 5;           // one-second samples per median
constexpr double kMaxRssGrowth = 0.05;     // fraction
constexpr double kMaxLatencyGrowth = 1.5;  // last third / first third
// Outputs per third before latency and CPU per output are judged: the 5-minute run's, not CI's
// 25 s run (about 200 per third, 6.7 s each, where a burst of the shared host's load decides
// them; the measurements are in docs/reliability.md).
constexpr size_t kLongRunSamples = 400;
// One frame estimated, one waiting (a newer one replaces it) and one being handed to the worker.
constexpr uint64_t kMaxFramesInProgress = 3;
constexpr double kSettleTimeout = 60;  // seconds for the node to finish after the input stops

/// The pid of `node`, through the master's lookupNode and the node's XML-RPC getPid.
int nodePid(const std::string& node) {
  XmlRpc::XmlRpcValue args, result, uri;
  args[0] = ros::this_node::getName();
  args[1] = node;
  if (!ros::master::execute("lookupNode", args, result, uri, true)) return -1;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(uri), host, port)) return -1;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue params, reply;
  params[0] = ros::this_node::getName();
  if (!client.execute("getPid", params, reply) || reply.size() != 3 ||
      static_cast<int>(reply[0]) != 1) {
    return -1;
  }
  return static_cast<int>(reply[2]);
}

/// VmRSS of process `pid` in kB, or -1.
long residentKb(int pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  std::string key;
  while (status >> key) {
    if (key == "VmRSS:") {
      long kb = -1;
      status >> kb;
      return kb;
    }
    status.ignore(1 << 12, '\n');
  }
  return -1;
}

/// User + system CPU seconds of process `pid` so far (fields 14 and 15 of /proc/<pid>/stat), or -1.
double cpuSeconds(int pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  std::getline(stat, line);
  // The command name (field 2) may hold spaces: count fields after its closing parenthesis.
  const size_t close = line.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream fields(line.substr(close + 2));
  std::string field;
  unsigned long long utime = 0, stime = 0;
  for (int k = 3; k <= 15 && fields >> field; ++k) {
    if (k == 14) utime = std::stoull(field);
    if (k == 15) stime = std::stoull(field);
  }
  return static_cast<double>(utime + stime) / static_cast<double>(sysconf(_SC_CLK_TCK));
}

/// The 1-minute load average, or -1.
double loadAverage() {
  double load = -1;
  std::ifstream("/proc/loadavg") >> load;
  return load;
}

double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  return values[static_cast<size_t>(q * static_cast<double>(values.size() - 1) + 0.5)];
}

/// The latest ~statistics counters by key.
class StatisticsListener {
 public:
  StatisticsListener() {
    const boost::function<void(const diagnostic_msgs::DiagnosticArray::ConstPtr&)> on_message =
        [this](const diagnostic_msgs::DiagnosticArray::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          counts_ = statisticsCounts(*m);
          if (judging_)
            max_in_progress_ = std::max(max_in_progress_, counts_["frames in progress"]);
        };
    sub_ = ros::NodeHandle().subscribe<diagnostic_msgs::DiagnosticArray>(
        std::string(kNode) + "/statistics", 10, on_message);
  }

  std::map<std::string, uint64_t> counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
  }

  /// From now on, remember the most frames in progress that any message reports.
  void startJudging() {
    std::lock_guard<std::mutex> lock(mutex_);
    judging_ = true;
  }

  uint64_t maxInProgress() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return max_in_progress_;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, uint64_t> counts_;
  bool judging_ = false;
  uint64_t max_in_progress_ = 0;
  ros::Subscriber sub_;
};

struct Latency {
  double sent_at;  ///< seconds since the input started
  double seconds;
  double estimation;  ///< the output's summed estimation_time, seconds (0: no object found)
};

class Soak : public ::testing::Test {
 protected:
  void SetUp() override {
    ros::NodeHandle nh;
    cloud_pub_ = nh.advertise<sensor_msgs::PointCloud2>("/soak/cloud", 10);
    probability_pub_ = nh.advertise<sensor_msgs::Image>("/soak/probability/box", 10);
    const InputFrame frame = loadInputFrame(g_params.dataset);
    cloud_ = frame.cloud;
    probability_ = frame.probability;
    const boost::function<void(const ObjectPoseArray::ConstPtr&)> on_objects =
        [this](const ObjectPoseArray::ConstPtr& m) {
          const ros::Time now = ros::Time::now();
          double estimation = 0;
          for (const ObjectPose& o : m->objects) estimation += o.estimation_time;
          std::lock_guard<std::mutex> lock(mutex_);
          latencies_.push_back(
              {(m->header.stamp - start_).toSec(), (now - m->header.stamp).toSec(), estimation});
        };
    objects_sub_ = nh.subscribe<ObjectPoseArray>(std::string(kNode) + "/objects", 1000, on_objects);
    // The node subscribes once its model is ready.
    const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(120);
    while ((cloud_pub_.getNumSubscribers() == 0 || probability_pub_.getNumSubscribers() == 0 ||
            objects_sub_.getNumPublishers() == 0) &&
           ros::WallTime::now() < until) {
      ros::WallDuration(0.1).sleep();
    }
  }

  /// Calls ~estimate every service_period seconds until `stop`; counts calls and failures.
  void callEstimateUntil(const std::atomic<bool>& stop) {
    while (!stop) {
      ros::WallDuration(g_params.service_period).sleep();
      Estimate srv;
      const bool called = callService(std::string(kNode) + "/estimate", srv);
      ++service_calls_;
      if (!called || !srv.response.success) {
        ++service_failures_;
        ROS_WARN("soak: ~estimate failed: %s", srv.response.message.c_str());
      }
    }
  }

  ros::Publisher cloud_pub_, probability_pub_;
  ros::Subscriber objects_sub_;
  sensor_msgs::PointCloud2 cloud_;
  sensor_msgs::Image probability_;
  std::mutex mutex_;  // guards start_ and latencies_
  ros::Time start_;
  std::vector<Latency> latencies_;
  std::atomic<uint64_t> service_calls_{0}, service_failures_{0};
};

TEST_F(Soak, MemoryCountsAndLatencyStaySteady) {
  ASSERT_GT(cloud_pub_.getNumSubscribers(), 0u) << "the node never subscribed /soak/cloud";
  const int pid = nodePid(kNode);
  ASSERT_GT(pid, 0) << "no pid for " << kNode;
  ASSERT_GT(residentKb(pid), 0) << "no VmRSS in /proc/" << pid << "/status";
  StatisticsListener statistics;

  std::vector<std::pair<double, long>> rss;  // (seconds since start, kB)
  double cpu_at_warmup = -1, load_at_warmup = -1;
  // The node's CPU seconds at the end of the first third and at the start of the last one.
  const double third = (g_params.duration - g_params.warmup) / 3;
  double cpu_first_end = -1, cpu_last_start = -1;
  uint64_t sent = 0;
  std::atomic<bool> stop{false};
  const ros::Time start = ros::Time::now();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    start_ = start;
  }
  std::thread service([&] { callEstimateUntil(stop); });
  ros::WallRate rate(g_params.rate);
  for (double t = 0; t < g_params.duration; t = (ros::Time::now() - start).toSec()) {
    const ros::Time stamp = ros::Time::now();
    cloud_.header.stamp = probability_.header.stamp = stamp;
    cloud_pub_.publish(cloud_);
    probability_pub_.publish(probability_);
    ++sent;
    if (rss.empty() || t - rss.back().first >= 1.0) rss.emplace_back(t, residentKb(pid));
    if (cpu_at_warmup < 0 && t >= g_params.warmup) {
      cpu_at_warmup = cpuSeconds(pid);
      load_at_warmup = loadAverage();
      statistics.startJudging();
    }
    if (cpu_first_end < 0 && t >= g_params.warmup + third) cpu_first_end = cpuSeconds(pid);
    if (cpu_last_start < 0 && t >= g_params.duration - third) cpu_last_start = cpuSeconds(pid);
    rate.sleep();
  }
  const double cpu_at_end = cpuSeconds(pid);
  const double cpu_after_warmup = cpu_at_end - cpu_at_warmup;
  const double load_at_end = loadAverage();
  stop = true;
  service.join();

  // Wait until the node has taken every message and finished the last frame.
  std::map<std::string, uint64_t> c;
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(kSettleTimeout);
  const std::string cloud_topic = "/soak/cloud", probability_topic = "/soak/probability/box";
  while (ros::WallTime::now() < until) {
    ros::WallDuration(1.5).sleep();  // > the statistics period
    c = statistics.counts();
    if (c["received " + cloud_topic] == sent && c["received " + probability_topic] == sent &&
        c["frames in progress"] == 0) {
      break;
    }
  }

  // Accounting: nothing lost in transport, nothing dropped without a reason.
  EXPECT_EQ(c["received " + cloud_topic], sent);
  EXPECT_EQ(c["received " + probability_topic], sent);
  for (const std::string& topic : {cloud_topic, probability_topic}) {
    EXPECT_EQ(c["received " + topic],
              c["frames matched"] + droppedMessages(c, topic) + c["queued " + topic])
        << topic;
  }
  const uint64_t dropped_cloud = droppedMessages(c, cloud_topic);
  EXPECT_EQ(c["frames in progress"], 0u);
  EXPECT_EQ(c["frames rejected"], 0u) << "good frames were rejected";
  EXPECT_EQ(sent, c["frames estimated"] + c["frames replaced"] + c["frames rejected"] +
                      c["frames kept"] + dropped_cloud + c["queued " + cloud_topic]);
  EXPECT_GT(c["frames estimated"], 0u);
  EXPECT_EQ(c["service calls"], service_calls_.load());
  EXPECT_EQ(service_failures_.load(), 0u);

  // Every estimated frame and every answered ~estimate call publishes on ~objects. The node
  // publishes an output before it counts it, but ~objects and ~statistics are separate
  // connections and callbacks: give the last outputs kSettleTimeout to arrive.
  const uint64_t outputs = c["frames estimated"] + service_calls_ - service_failures_;
  std::vector<Latency> latencies;
  for (const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(kSettleTimeout);;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      latencies = latencies_;
    }
    if (latencies.size() >= outputs || ros::WallTime::now() > until) break;
    ros::WallDuration(0.1).sleep();
  }
  EXPECT_EQ(latencies.size(), outputs) << "outputs missing on ~objects";

  // Memory: median of the first kRssWindow samples after the warm-up against the last ones.
  std::vector<double> after;
  for (const auto& [t, kb] : rss) {
    if (t >= g_params.warmup) after.push_back(static_cast<double>(kb));
  }
  ASSERT_GE(after.size(), 2 * kRssWindow) << "run longer than warm-up + 10 s";
  const double rss_start =
      quantile(std::vector<double>(after.begin(), after.begin() + kRssWindow), 0.5);
  const double rss_end = quantile(std::vector<double>(after.end() - kRssWindow, after.end()), 0.5);
  const double rss_max = *std::max_element(after.begin(), after.end());

  // Latency: first against last third of the time after the warm-up.
  std::vector<double> all, first, last, ratio_first, ratio_last;
  for (const Latency& l : latencies) {
    if (l.sent_at < g_params.warmup) continue;
    all.push_back(l.seconds);
    const bool in_first = l.sent_at < g_params.warmup + third;
    const bool in_last = l.sent_at >= g_params.duration - third;
    if (in_first) first.push_back(l.seconds);
    if (in_last) last.push_back(l.seconds);
    if (l.estimation > 0 && in_first) ratio_first.push_back(l.seconds / l.estimation);
    if (l.estimation > 0 && in_last) ratio_last.push_back(l.seconds / l.estimation);
  }
  const double p50_first = quantile(first, 0.5), p50_last = quantile(last, 0.5);
  const double p95_first = quantile(first, 0.95), p95_last = quantile(last, 0.95);
  const double ratio_p50_first = quantile(ratio_first, 0.5);
  const double ratio_p50_last = quantile(ratio_last, 0.5);
  const double ratio_p95_first = quantile(ratio_first, 0.95);
  const double ratio_p95_last = quantile(ratio_last, 0.95);
  // Outputs include the ~estimate answers, which come at the same period in both thirds.
  const double cpu_per_output_first =
      (cpu_first_end - cpu_at_warmup) / std::max<size_t>(1, first.size());
  const double cpu_per_output_last =
      (cpu_at_end - cpu_last_start) / std::max<size_t>(1, last.size());

  const std::string summary = fmt::format(
      "soak: {:.0f} s at {:.0f} Hz, warm-up {:.0f} s: {} frames sent; ~statistics: {} estimated, "
      "{} replaced, {} rejected, {} kept, {} cloud messages dropped, {} queued, at most {} in "
      "progress after warm-up; {} service calls; "
      "RSS {:.0f} kB after warm-up, {:.0f} kB at the end ({:+.2f}%), max {:.0f} kB; latency of "
      "{} outputs after warm-up p50 {:.3f} s, p95 {:.3f} s; first third ({} outputs) p50 {:.3f} s, "
      "p95 {:.3f} s, latency / estimation time p50 {:.2f} p95 {:.2f}, node CPU per output {:.3f} "
      "s; "
      "last third ({} outputs) p50 {:.3f} s, p95 {:.3f} s, latency / estimation time p50 {:.2f} "
      "p95 {:.2f}, node CPU per output {:.3f} s; node CPU after warm-up "
      "{:.1f} s ({:.0f}% of one core); load average {:.1f} after warm-up, {:.1f} at the end",
      g_params.duration, g_params.rate, g_params.warmup, sent, c["frames estimated"],
      c["frames replaced"], c["frames rejected"], c["frames kept"], dropped_cloud,
      c["queued " + cloud_topic], statistics.maxInProgress(), service_calls_.load(), rss_start,
      rss_end, 100 * (rss_end / rss_start - 1), rss_max, all.size(), quantile(all, 0.5),
      quantile(all, 0.95), first.size(), p50_first, p95_first, ratio_p50_first, ratio_p95_first,
      cpu_per_output_first, last.size(), p50_last, p95_last, ratio_p50_last, ratio_p95_last,
      cpu_per_output_last, cpu_after_warmup,
      100 * cpu_after_warmup / (g_params.duration - g_params.warmup), load_at_warmup, load_at_end);
  std::cout << summary << std::endl;
  ROS_INFO("%s", summary.c_str());

  EXPECT_LT(rss_end, rss_start * (1 + kMaxRssGrowth))
      << "resident memory grew from " << rss_start << " kB to " << rss_end << " kB";
  // A backlog in the node is frames piling up between the inputs and the worker.
  EXPECT_LE(statistics.maxInProgress(), kMaxFramesInProgress)
      << "more frames in progress at once than one estimated, one waiting and one handed over";
  ASSERT_GE(ratio_first.size(), 10u) << "too few found objects in the first third";
  ASSERT_GE(ratio_last.size(), 10u) << "too few found objects in the last third";
  if (first.size() >= kLongRunSamples && last.size() >= kLongRunSamples) {
    EXPECT_LE(cpu_per_output_last, kMaxLatencyGrowth * cpu_per_output_first)
        << "the node's CPU time per output grew from " << cpu_per_output_first << " s to "
        << cpu_per_output_last << " s (raw latency median " << p50_first << " s -> " << p50_last
        << " s)";
  }
  if (ratio_first.size() >= kLongRunSamples && ratio_last.size() >= kLongRunSamples) {
    EXPECT_LE(ratio_p50_last, kMaxLatencyGrowth * ratio_p50_first)
        << "the median latency / estimation time grew from " << ratio_p50_first << " to "
        << ratio_p50_last;
    // A backlog lengthens the tail in seconds and in estimation times alike. The machine's load
    // moves the seconds alone when it slows the transport more than the estimation, and the
    // estimation time's spread moves the ratio alone when the estimation is a small part of the
    // latency: either passes, both together fail.
    const bool tail_grew = p95_last > kMaxLatencyGrowth * p95_first &&
                           ratio_p95_last > kMaxLatencyGrowth * ratio_p95_first;
    EXPECT_FALSE(tail_grew) << "the latency's p95 grew from " << p95_first << " s to " << p95_last
                            << " s, and from " << ratio_p95_first << " to " << ratio_p95_last
                            << " estimation times";
  }
}

}  // namespace
}  // namespace stocs_ros::test

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_soak");
  ros::NodeHandle pnh("~");
  using stocs_ros::test::g_params;
  pnh.getParam("dataset", g_params.dataset);
  pnh.getParam("duration", g_params.duration);
  pnh.getParam("rate", g_params.rate);
  pnh.getParam("warmup", g_params.warmup);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  return RUN_ALL_TESTS();
}
