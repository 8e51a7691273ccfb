#include "smart/bridge/foxglove_server.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <boost/asio.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <deque>
#include <map>
#include <set>
#include <thread>

namespace smart::bridge {

namespace net = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = net::ip::tcp;

namespace {
constexpr std::size_t kMaxClientMessage = std::size_t{64} * 1024;

bool offers_subprotocol(std::string_view header) {
  // Sec-WebSocket-Protocol: a comma-separated list (RFC 6455, 11.3.4).
  std::size_t at = 0;
  while (at <= header.size()) {
    const auto end = std::min(header.find(',', at), header.size());
    auto item = header.substr(at, end - at);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    if (item == kSubprotocol) return true;
    at = end + 1;
  }
  return false;
}
}  // namespace

struct FoxgloveServer::Impl : std::enable_shared_from_this<Impl> {
  // Nested, not in an anonymous namespace: Session holds them, and g++ warns
  // (-Wsubobject-linkage) when a unity build includes this file into another.
  struct Frame {
    std::shared_ptr<const std::string> bytes;
    bool binary = true;
  };
  struct Session;
  ServerOptions options;
  std::vector<Channel> channels;
  std::vector<uint32_t> channel_ids;
  net::io_context ioc;
  tcp::acceptor acceptor{ioc};
  std::set<std::shared_ptr<Session>> sessions;  // I/O thread only
  std::map<uint32_t, std::pair<uint64_t, std::shared_ptr<const std::string>>> last;  // latched
  uint64_t next_session = 0;
  std::thread thread;

  void accept();
  void publish(uint32_t channel, uint64_t stamp_ns,
               const std::shared_ptr<const std::string>& payload);
  void broadcast_time(uint64_t t_ns);
};

struct FoxgloveServer::Impl::Session : std::enable_shared_from_this<Session> {
  Impl& server;
  websocket::stream<beast::tcp_stream> ws;
  beast::flat_buffer buffer;
  http::request<http::string_body> request;
  ClientSubscriptions subs;
  std::deque<Frame> queue;
  bool writing = false, open = false;
  uint64_t dropped = 0;

  Session(Impl& s, tcp::socket socket) : server(s), ws(std::move(socket)), subs(s.channel_ids) {}

  void start() {
    http::async_read(
        ws.next_layer(), buffer, request,
        [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_request(ec); });
  }
  void on_request(beast::error_code ec) {
    if (ec) return close();
    if (!websocket::is_upgrade(request) ||
        !offers_subprotocol(std::string(request[http::field::sec_websocket_protocol]))) {
      return refuse();
    }
    ws.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws.set_option(websocket::stream_base::decorator([](websocket::response_type& res) {
      res.set(http::field::sec_websocket_protocol, std::string(kSubprotocol));
      res.set(http::field::server, "smart-dds bridge");
    }));
    ws.read_message_max(kMaxClientMessage);
    ws.async_accept(request, [self = shared_from_this()](beast::error_code e) {
      if (e) return self->close();
      self->open = true;
      self->send_text(
          server_info_json(self->server.options.name, std::to_string(self->server.next_session++)));
      self->send_text(advertise_json(self->server.channels));
      self->read();
    });
  }
  // Not a foxglove.websocket.v1 upgrade: a plain HTTP answer saying what this port is.
  void refuse() {
    auto res = std::make_shared<http::response<http::string_body>>(http::status::bad_request,
                                                                   request.version());
    res->set(http::field::content_type, "text/plain");
    res->body() =
        "This is a Foxglove WebSocket bridge (subprotocol foxglove.websocket.v1): open it "
        "in Foxglove or Lichtblick with \"Foxglove WebSocket\" and this URL.\n";
    res->prepare_payload();
    http::async_write(
        ws.next_layer(), *res,
        [self = shared_from_this(), res](beast::error_code, std::size_t) { self->close(); });
  }
  void read() {
    buffer.clear();
    ws.async_read(buffer, [self = shared_from_this()](beast::error_code ec, std::size_t) {
      if (ec) return self->close();
      ClientSubscriptions::Outcome out;
      try {
        out = self->ws.got_text()
                  ? self->subs.on_text(beast::buffers_to_string(self->buffer.data()))
                  : self->subs.on_binary();
      } catch (const std::exception& e) {  // never the bridge's end: this client's only
        spdlog::warn("bridge: closing a client whose message could not be handled: {}", e.what());
        return self->close();
      }
      for (const auto& r : out.replies) self->send_text(r);
      for (const auto& [sub, channel] : out.subscribed) {
        const auto it = self->server.last.find(channel);
        if (it != self->server.last.end()) {
          self->send(std::make_shared<const std::string>(
              message_frame(sub, it->second.first, *it->second.second)));
        }
      }
      self->read();
    });
  }
  void send_text(std::string text) {
    queue.push_back({std::make_shared<const std::string>(std::move(text)), false});
    write();
  }
  void send(std::shared_ptr<const std::string> frame) {
    if (queue.size() >= server.options.max_queue) {
      // Drop the oldest binary frame not being written (texts are replies and the channels).
      for (auto it = queue.begin() + (writing ? 1 : 0); it != queue.end(); ++it) {
        if (it->binary) {
          queue.erase(it);
          if (dropped++ == 0) spdlog::warn("bridge: a slow client; dropping its oldest frames");
          break;
        }
      }
    }
    queue.push_back({std::move(frame), true});
    write();
  }
  void write() {
    if (writing || queue.empty() || !open) return;
    writing = true;
    ws.binary(queue.front().binary);
    ws.async_write(net::buffer(*queue.front().bytes),
                   [self = shared_from_this()](beast::error_code ec, std::size_t) {
                     self->writing = false;
                     if (ec) return self->close();
                     self->queue.pop_front();
                     self->write();
                   });
  }
  void close() {
    open = false;
    beast::error_code ignored;
    ws.next_layer().socket().close(ignored);
    server.sessions.erase(shared_from_this());
  }
};

void FoxgloveServer::Impl::accept() {
  acceptor.async_accept([self = shared_from_this()](beast::error_code ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted) return;
    if (!ec && self->sessions.size() < self->options.max_clients) {
      auto s = std::make_shared<Session>(*self, std::move(socket));
      self->sessions.insert(s);
      s->start();
    }
    self->accept();
  });
}

void FoxgloveServer::Impl::publish(uint32_t channel, uint64_t stamp_ns,
                                   const std::shared_ptr<const std::string>& payload) {
  if (std::find(options.latched.begin(), options.latched.end(), channel) != options.latched.end()) {
    last[channel] = {stamp_ns, payload};
  }
  for (const auto& s : sessions) {
    if (const uint32_t* sub = s->subs.subscription_of(channel); sub && s->open) {
      s->send(std::make_shared<const std::string>(message_frame(*sub, stamp_ns, *payload)));
    }
  }
}

void FoxgloveServer::Impl::broadcast_time(uint64_t t_ns) {
  const auto frame = std::make_shared<const std::string>(time_frame(t_ns));
  for (const auto& s : sessions) {
    if (s->open) s->send(frame);
  }
}

FoxgloveServer::FoxgloveServer(ServerOptions options, std::vector<Channel> channels)
    : impl_(std::make_shared<Impl>()) {
  impl_->options = std::move(options);
  impl_->channels = std::move(channels);
  for (const auto& c : impl_->channels) impl_->channel_ids.push_back(c.id);
  const std::string where = impl_->options.bind + ":" + std::to_string(impl_->options.port);
  try {
    const tcp::endpoint ep(net::ip::make_address(impl_->options.bind), impl_->options.port);
    impl_->acceptor.open(ep.protocol());
    impl_->acceptor.set_option(net::socket_base::reuse_address(true));
    impl_->acceptor.bind(ep);
    impl_->acceptor.listen();
  } catch (const std::exception& e) {
    throw std::runtime_error("Foxglove bridge: cannot listen on " + where + ": " + e.what() +
                             " (pick another --foxglove-port, or --bind an address of this host)");
  }
  impl_->accept();
  impl_->thread = std::thread([impl = impl_] { impl->ioc.run(); });
}

FoxgloveServer::~FoxgloveServer() {
  // Closing the acceptor and every socket completes their pending operations (aborted): their
  // handlers run, start nothing new and release the Impl they hold, and run() returns once no
  // work is left. Stopping the io_context instead would leave those handlers, and with them the
  // Impl that owns the io_context, alive (a leak LeakSanitizer reported).
  net::post(impl_->ioc, [impl = impl_] {
    beast::error_code ignored;
    impl->acceptor.close(ignored);
    for (const auto& s : std::set(impl->sessions)) s->close();
  });
  impl_->thread.join();
}

uint16_t FoxgloveServer::port() const { return impl_->acceptor.local_endpoint().port(); }

void FoxgloveServer::publish(uint32_t channel, uint64_t stamp_ns, std::string payload) {
  net::post(impl_->ioc, [impl = impl_, channel, stamp_ns,
                         p = std::make_shared<const std::string>(std::move(payload))] {
    impl->publish(channel, stamp_ns, p);
  });
}

void FoxgloveServer::add_channels(std::vector<Channel> channels, bool latched) {
  net::post(impl_->ioc, [impl = impl_, channels = std::move(channels), latched] {
    std::vector<uint32_t> ids;
    for (const auto& c : channels) ids.push_back(c.id);
    impl->channels.insert(impl->channels.end(), channels.begin(), channels.end());
    impl->channel_ids.insert(impl->channel_ids.end(), ids.begin(), ids.end());
    if (latched) impl->options.latched.insert(impl->options.latched.end(), ids.begin(), ids.end());
    const std::string advertise = advertise_json(channels);
    for (const auto& s : impl->sessions) {
      s->subs.add_channels(ids);
      if (s->open) s->send_text(advertise);
    }
  });
}

void FoxgloveServer::time(uint64_t time_ns) {
  net::post(impl_->ioc, [impl = impl_, time_ns] { impl->broadcast_time(time_ns); });
}

}  // namespace smart::bridge
