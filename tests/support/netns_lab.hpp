// A LAN of hosts on one machine, for tests of what crosses a network: one Linux network
// namespace per host, each with its own loopback and an `eth0` (a veth) at 10.99.0.<i+1>/24,
// all joined by a bridge that lives in a namespace of its own (the "switch"), so nothing is added
// to the machine's own namespace and two labs (tests run in parallel) never see each other.
// Multicast is flooded by the bridge (snooping off) as on a small switch, so DDS discovery works
// as on a LAN. Needs root (CAP_SYS_ADMIN and CAP_NET_ADMIN), as CI runs; create() says why it
// cannot be made otherwise, and the test skips with that message.
//
// Links can be made lossy or cut from the host's side with nftables (this kernel has no netem):
// a table `smart_lab` in the host's namespace drops a share of its packets, or all of them,
// both ways. Everything is removed by the destructor (also when a test fails); namespaces a
// crashed test process left behind are swept at the next create() (names carry the pid).
//
// iproute2: ip-netns(8), ip-link(8) (veth, bridge mcast_snooping); nftables: nft(8) (numgen).
#pragma once

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "smart/common/child_process.hpp"
#include "support/dds_test_support.hpp"

namespace smart::test {

class NetnsLab {
 public:
  // A lab of `hosts` hosts; null, with `why` set, when namespaces cannot be created here.
  static std::unique_ptr<NetnsLab> create(int hosts, std::string& why) {
    sweep_stale();
    auto lab = std::unique_ptr<NetnsLab>(new NetnsLab());
    if (!lab->build(hosts, why)) return nullptr;
    return lab;
  }
  ~NetnsLab() {
    for (const auto& ns : namespaces_) run("ip netns delete " + ns);
  }
  NetnsLab(const NetnsLab&) = delete;
  NetnsLab& operator=(const NetnsLab&) = delete;

  const std::string& host(int i) const { return hosts_.at(static_cast<std::size_t>(i)); }
  static std::string address(int i) { return "10.99.0." + std::to_string(i + 1); }

  // argv run inside host i's namespace.
  std::vector<std::string> in_host(int i, const std::vector<std::string>& argv) const {
    std::vector<std::string> a{"/usr/bin/env", "ip", "netns", "exec", host(i)};
    a.insert(a.end(), argv.begin(), argv.end());
    return a;
  }
  // `smart args...` in host i, stdout (and, with_stderr, stderr) to `out`.
  common::ChildProcess start_smart(int i, const std::vector<std::string>& args,
                                   const std::filesystem::path& out,
                                   bool with_stderr = false) const {
    std::vector<std::string> argv{smart_exe().string()};
    argv.insert(argv.end(), args.begin(), args.end());
    if (with_stderr) argv.insert(argv.begin(), {"/bin/sh", "-c", "exec \"$0\" \"$@\" 2>&1"});
    return common::ChildProcess(in_host(i, argv), out);
  }

  // Host i's link drops `per_mille` of its packets each way (0: none; 1000: the link is cut).
  bool set_loss(int i, int per_mille) const {
    const std::string ns = "ip netns exec " + host(i) + " ";
    run(ns + "nft delete table inet smart_lab");
    if (per_mille <= 0) return true;
    const std::string drop = per_mille >= 1000 ? "counter drop"
                                               : "numgen random mod 1000 < " +
                                                     std::to_string(per_mille) + " counter drop";
    std::ostringstream rules;
    rules << "table inet smart_lab {\n"
          << "  chain in { type filter hook input priority 0; iifname \"eth0\" " << drop << "; }\n"
          << "  chain out { type filter hook output priority 0; oifname \"eth0\" " << drop
          << "; }\n}\n";
    const auto file = temp_file("nft-" + host(i));
    std::ofstream(file) << rules.str();
    const bool ok = run(ns + "nft -f " + file.string());
    std::filesystem::remove(file);
    return ok;
  }
  bool cut(int i) const { return set_loss(i, 1000); }
  bool restore(int i) const { return set_loss(i, 0); }

  // Packets host i's eth0 sent (the kernel's counter; what nftables dropped is not sent).
  uint64_t sent_packets(int i) const {
    return std::strtoull(
        capture("ip netns exec " + host(i) + " cat /sys/class/net/eth0/statistics/tx_packets")
            .c_str(),
        nullptr, 10);
  }
  // Packets host i's loss rules dropped so far (both ways).
  uint64_t dropped_packets(int i) const {
    const auto listing = capture("ip netns exec " + host(i) + " nft list table inet smart_lab");
    uint64_t total = 0;
    for (std::size_t at = listing.find("packets "); at != std::string::npos;
         at = listing.find("packets ", at + 8)) {
      total += std::strtoull(listing.c_str() + at + 8, nullptr, 10);
    }
    return total;
  }

 private:
  NetnsLab() = default;

  static bool run(const std::string& cmd) {
    return std::system((cmd + " >/dev/null 2>&1").c_str()) == 0;
  }
  static std::string capture(const std::string& cmd) {
    std::string out;
    if (FILE* f = popen((cmd + " 2>/dev/null").c_str(), "r")) {
      char buf[4096];
      for (std::size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
      pclose(f);
    }
    return out;
  }
  static std::string prefix(pid_t pid) { return "smartlab-" + std::to_string(pid) + "-"; }

  // Namespaces of test processes that are gone (a crash, a kill) are deleted.
  static void sweep_stale() {
    const std::filesystem::path dir = "/run/netns";
    std::error_code ec;
    if (!std::filesystem::exists(dir, ec)) return;
    for (const auto& e : std::filesystem::directory_iterator(dir, ec)) {
      const auto name = e.path().filename().string();
      if (name.rfind("smartlab-", 0) != 0) continue;
      const auto pid = std::atoi(name.substr(9).c_str());
      if (pid > 0 && pid != getpid() && kill(pid, 0) != 0) run("ip netns delete " + name);
    }
  }

  bool add_namespace(const std::string& ns, std::string& why) {
    if (!run("ip netns add " + ns)) {
      why = "cannot create network namespace " + ns +
            " (needs root: CAP_SYS_ADMIN and CAP_NET_ADMIN, as CI runs; `ip netns add` failed)";
      return false;
    }
    namespaces_.push_back(ns);
    return run("ip -n " + ns + " link set lo up");
  }

  bool build(int hosts, std::string& why) {
    static int labs = 0;
    const std::string base = prefix(getpid()) + std::to_string(++labs);
    const std::string sw = base + "-sw";
    if (!add_namespace(sw, why)) return false;
    bool ok = run("ip -n " + sw + " link add br0 type bridge mcast_snooping 0") &&
              run("ip -n " + sw + " link set br0 up");
    for (int i = 0; ok && i < hosts; ++i) {
      const std::string h = base + "-h" + std::to_string(i);
      const std::string port = "p" + std::to_string(i);
      ok = add_namespace(h, why) &&
           run("ip link add eth0 netns " + h + " type veth peer name " + port + " netns " + sw) &&
           run("ip -n " + sw + " link set " + port + " master br0 up") &&
           run("ip -n " + h + " addr add " + address(i) + "/24 dev eth0") &&
           run("ip -n " + h + " link set eth0 up") &&
           run("ip -n " + h + " route add 224.0.0.0/4 dev eth0");
      hosts_.push_back(h);
    }
    if (!ok && why.empty())
      why = "could not wire the namespaces of " + base + " (iproute2 veth, bridge)";
    return ok;
  }

  std::vector<std::string> namespaces_;  // hosts and the switch, deleted at the end
  std::vector<std::string> hosts_;
};

}  // namespace smart::test
