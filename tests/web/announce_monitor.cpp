// A test intruder for the browser test (web/test/viewer.test.mjs): on DDS domain ARGV[1], it
// learns the run going on from its monitor's windows (heard through the "smart.run.*" wildcard:
// their run id, and their writer's partition, which names the run) and announces, in that run's
// own partition, a monitor of the run whose host name is ARGV[2] (markup: issue 25, a DDS host
// name ran as script in the --watch view), every 100 ms until it is killed.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "smart/dds/wire.hpp"
#include "support/dds_test_support.hpp"

int main(int argc, char** argv) {
  using namespace smart;
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s DOMAIN HOST\n", argv[0]);
    return 2;
  }
  dds::Domain domain(static_cast<dds_domainid_t>(std::atoi(argv[1])), test::loopback());
  const auto qos = dds::find_qos_profile("lan");
  dds::Participant spy_p(domain, "*");
  dds::WireReader<smart_msg_ActionWindow> spy(spy_p, qos);
  std::optional<std::pair<uint64_t, std::string>> run;  // id, name
  while (!run) {
    spy.take_each_from([&](const smart_msg_ActionWindow& w, dds_instance_handle_t from) {
      const auto parts = spy.partitions_of(from);
      const std::string prefix = smart_msg_RUN_PARTITION_PREFIX;
      if (parts && parts->size() == 1 && parts->front().rfind(prefix, 0) == 0) {
        run.emplace(w.run_id, parts->front().substr(prefix.size()));
      }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  dds::Participant p(domain, run->second);
  dds::WireWriter<smart_msg_MonitorInfo> out(p, qos, 0);
  smart_msg_MonitorInfo m{};
  m.monitor_id = 77;
  m.run_id = run->first;
  std::snprintf(m.host, sizeof(m.host), "%s", argv[2]);
  m.pid = 4242;
  m.strength = smart_msg_MONITOR_STRENGTH_MIN;
  for (;;) {
    out.write(m);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
}
