#include "smart/hw/vicon.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "smart/agent/kinematics.hpp"

namespace smart::hw {

namespace {
constexpr std::size_t kItemHeader = 3;  // id + size
constexpr uint16_t kObjectSize = 72;    // name[24] + 6 doubles
template <class T>
T get(const uint8_t* p) {  // little-endian (every parser seen; x86 and ARM hosts alike)
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
}  // namespace

std::optional<ViconFrame> parse_vicon_datagram(const uint8_t* d, std::size_t n,
                                               std::string* error) {
  if (n < 5) {
    *error = "datagram of " + std::to_string(n) + " bytes is shorter than its 5-byte header";
    return std::nullopt;
  }
  ViconFrame f;
  f.frame = get<uint32_t>(d);
  const uint8_t items = d[4];
  std::size_t at = 5;
  for (uint8_t i = 0; i < items; ++i) {
    if (at + kItemHeader > n) {
      *error = "item " + std::to_string(i) + " of " + std::to_string(items) +
               " starts beyond the end of a " + std::to_string(n) + "-byte datagram";
      return std::nullopt;
    }
    const uint8_t id = d[at];
    const auto size = get<uint16_t>(d + at + 1);
    at += kItemHeader;
    if (at + size > n) {
      *error = "item " + std::to_string(i) + " claims " + std::to_string(size) +
               " bytes but the datagram ends first";
      return std::nullopt;
    }
    if (id != 0) {  // not an object item: skip it
      ++f.skipped_items;
      at += size;
      continue;
    }
    if (size != kObjectSize) {
      *error = "object item " + std::to_string(i) + " has size " + std::to_string(size) +
               ", expected 72 (name[24] + 6 doubles)";
      return std::nullopt;
    }
    ViconObject o;
    const char* name = reinterpret_cast<const char*>(d + at);
    o.name.assign(name, strnlen(name, 24));
    for (int k = 0; k < 3; ++k) o.position_mm[k] = get<double>(d + at + 24 + std::ptrdiff_t{8} * k);
    for (int k = 0; k < 3; ++k)
      o.rotation_rad[k] = get<double>(d + at + 48 + std::ptrdiff_t{8} * k);
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(o.position_mm[k]) || !std::isfinite(o.rotation_rad[k])) {
        *error = "object '" + o.name + "' has a non-finite value (occluded?)";
        return std::nullopt;
      }
    }
    f.objects.push_back(std::move(o));
    at += size;
  }
  return f;
}

std::vector<uint8_t> make_vicon_datagram(uint32_t frame, const std::vector<ViconObject>& objects) {
  std::vector<uint8_t> d(5);
  std::memcpy(d.data(), &frame, 4);
  d[4] = static_cast<uint8_t>(objects.size());
  for (const auto& o : objects) {
    d.push_back(0);
    const uint16_t size = kObjectSize;
    d.insert(d.end(), reinterpret_cast<const uint8_t*>(&size),
             reinterpret_cast<const uint8_t*>(&size) + 2);
    char name[24] = {};
    // A fixed 24-byte field, zero-padded, not a C string (Vicon DataStream UDP object layout).
    std::copy_n(o.name.data(), std::min<std::size_t>(o.name.size(), 24), name);
    d.insert(d.end(), name, name + 24);
    for (const double* v : {o.position_mm, o.rotation_rad}) {
      d.insert(d.end(), reinterpret_cast<const uint8_t*>(v),
               reinterpret_cast<const uint8_t*>(v) + 24);
    }
  }
  std::size_t padded = 256;
  while (padded < d.size()) padded *= 2;
  d.resize(padded, 0);
  return d;
}

bool rtps_may_use_port(uint16_t port) {
  constexpr int kBase = 7400, kDomainGain = 250;
  if (port < kBase) return false;
  const int offset = (port - kBase) % kDomainGain;
  return offset < 2 || offset >= 10;
}

namespace {

// A UDP socket bound to address:port, and the port it got; throws with the reason.
std::pair<int, uint16_t> bind_udp(const std::string& address, uint16_t port) {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) throw std::runtime_error(std::string("vicon: socket: ") + std::strerror(errno));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  if (::inet_pton(AF_INET, address.c_str(), &a.sin_addr) != 1) {
    ::close(fd);
    throw std::invalid_argument("vicon: '" + address +
                                "' is not an IPv4 address; give --vicon-bind as a.b.c.d");
  }
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) < 0) {
    const std::string err = std::strerror(errno);
    ::close(fd);
    throw std::runtime_error("vicon: cannot listen on UDP " + address + ":" + std::to_string(port) +
                             ": " + err + "; is another program using the port?");
  }
  socklen_t len = sizeof a;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
  return {fd, ntohs(a.sin_port)};
}

// Port 0: the first free port below the RTPS ports (DDS never sends there).
std::pair<int, uint16_t> bind_vicon_socket(const std::string& address, uint16_t port) {
  if (port != 0) return bind_udp(address, port);
  constexpr uint16_t kFirst = 7399, kLast = 1024;
  for (uint16_t p = kFirst; p >= kLast; --p) {
    try {
      return bind_udp(address, p);
    } catch (const std::runtime_error&) {
      // in use: the next one down
    }
  }
  throw std::runtime_error("vicon: no free UDP port in " + std::to_string(kLast) + "-" +
                           std::to_string(kFirst) + " on " + address + "; give --vicon-port");
}

}  // namespace

ViconReceiver::ViconReceiver(const std::string& bind_address, uint16_t port,
                             geometry::FrameTransform t, const std::vector<std::string>& objects,
                             std::function<double()> now_s)
    : transform_(std::move(t)), now_s_(std::move(now_s)) {
  for (auto& o : objects) latest_[o] = std::nullopt;
  std::tie(fd_, port_) = bind_vicon_socket(bind_address, port);
  thread_ = std::thread([this] { loop(); });
}

ViconReceiver::~ViconReceiver() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
  if (fd_ >= 0) ::close(fd_);
}

void ViconReceiver::loop() {
  std::vector<uint8_t> buf(65536);
  while (!stop_) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, 50) <= 0) continue;
    const auto n = ::recv(fd_, buf.data(), buf.size(), 0);
    if (n > 0) handle(buf.data(), static_cast<std::size_t>(n));
  }
}

void ViconReceiver::handle(const uint8_t* data, std::size_t size) {
  std::string error;
  const auto frame = parse_vicon_datagram(data, size, &error);
  const double now = now_s_();
  std::lock_guard<std::mutex> lock(mutex_);
  ++stats_.datagrams;
  if (!frame) {
    ++stats_.malformed;
    return;
  }
  for (const auto& o : frame->objects) {
    auto it = latest_.find(o.name);
    if (it == latest_.end()) {
      ++stats_.unknown_names;
      continue;
    }
    // Tracker's Euler XYZ: the third angle is the heading for a robot on a level floor.
    const Eigen::Vector2d xy = transform_.apply({o.position_mm[0], o.position_mm[1]});
    agent::PoseSample p;
    p.pose = {xy.x(), xy.y(), transform_.apply_yaw(o.rotation_rad[2])};
    p.stamp_s = now;
    p.valid = true;
    if (it->second && now > it->second->stamp_s) {
      const auto& q = *it->second;
      const double dt = now - q.stamp_s;
      const double dx = p.pose.x_m - q.pose.x_m, dy = p.pose.y_m - q.pose.y_m;
      p.linear_mps = (dx * std::cos(p.pose.yaw_rad) + dy * std::sin(p.pose.yaw_rad)) / dt;
      p.angular_radps = agent::wrap_angle(p.pose.yaw_rad - q.pose.yaw_rad) / dt;
    }
    it->second = p;
    ++stats_.poses;
  }
}

std::optional<agent::PoseSample> ViconReceiver::latest(const std::string& object) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = latest_.find(object);
  return it == latest_.end() ? std::nullopt : it->second;
}

ViconStats ViconReceiver::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

ViconPoseSource::ViconPoseSource(const ViconReceiver& r, std::string object, double max_age_s,
                                 std::function<double()> now_s)
    : receiver_(r), object_(std::move(object)), max_age_s_(max_age_s), now_s_(std::move(now_s)) {}

agent::PoseSample ViconPoseSource::read() {
  auto p = receiver_.latest(object_);
  if (!p) return {};
  // An old pose is no pose: the agent's watchdog then stops the wheels.
  if (now_s_() - p->stamp_s > max_age_s_) p->valid = false;
  return *p;
}

}  // namespace smart::hw
