#include "insitu/live/live_server.h"

#include <arpa/inet.h>
#include <civetweb.h>
#include <netinet/in.h>
#include <sys/random.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <string_view>
#include <unordered_map>

#include "render/gl/embedded.h"
#include "voxspan/error.h"
#include "voxspan/log.h"

namespace voxspan {
namespace embedded {
std::span<const EmbeddedFile> live_page();  // insitu/live/live_page.html
}  // namespace embedded
namespace {

std::string_view live_page_html() { return embedded::live_page().front().text; }

std::string random_token() {
  unsigned char bytes[32];
  std::size_t got = 0;
  while (got < sizeof bytes) {
    const ssize_t n = getrandom(bytes + got, sizeof bytes - got, 0);
    if (n < 0) throw make_error("live page: no random bytes for the token: ", std::strerror(errno));
    got += std::size_t(n);
  }
  static constexpr char kHex[] = "0123456789abcdef";
  std::string token;
  for (unsigned char b : bytes) token += {kHex[b >> 4], kHex[b & 15]};
  return token;
}

// Why civetweb could not listen on `address`:`port`, in the system's words where a socket of our
// own cannot bind there either ("Address already in use": another program, or a run whose page
// still lingers), else civetweb's.
std::string why_not_listening(const std::string& address, int port, const std::string& civetweb) {
  sockaddr_in at{};
  at.sin_family = AF_INET;
  at.sin_port = htons(std::uint16_t(port));
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0 || ::inet_pton(AF_INET, address.c_str(), &at.sin_addr) != 1) {
    if (fd >= 0) ::close(fd);
    return civetweb;
  }
  const int one = 1;  // as civetweb binds: a port in TIME_WAIT is free
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  const bool bound = ::bind(fd, reinterpret_cast<const sockaddr*>(&at), sizeof at) == 0;
  const int error = errno;
  ::close(fd);
  if (bound) return civetweb;
  std::string why = std::strerror(error);
  if (error == EADDRINUSE)
    why += " (another program, or a run whose page lingers; live.port: 0 takes a free one)";
  return why;
}

// Equal strings, in a time that depends on the token's length only (which is no secret), not on
// where a guess first differs.
bool same_token(std::string_view given, std::string_view token) {
  volatile unsigned char diff = given.size() == token.size() ? 0 : 1;
  for (std::size_t i = 0; i < token.size(); ++i)
    diff = diff | static_cast<unsigned char>(token[i] ^ (i < given.size() ? given[i] : 0));
  return diff == 0;
}

// The value of `name` in a query string ("a=1&token=x"), as given (tokens need no decoding).
std::string_view query_value(const char* query, std::string_view name) {
  if (query == nullptr) return {};
  std::string_view q(query);
  while (!q.empty()) {
    const std::size_t end = q.find('&');
    const std::string_view pair = q.substr(0, end);
    if (pair.size() > name.size() && pair.substr(0, name.size()) == name &&
        pair[name.size()] == '=')
      return pair.substr(name.size() + 1);
    if (end == std::string_view::npos) break;
    q.remove_prefix(end + 1);
  }
  return {};
}

// Per client address: a bucket of kBurst requests, refilled at kRequestsPerSecond.
class RateLimit {
 public:
  bool allow(const char* address) {
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    if (buckets_.size() > kAddresses) buckets_.clear();  // a flood of addresses: start over
    auto [it, fresh] = buckets_.try_emplace(address, Bucket{LiveServer::kBurst, now});
    Bucket& b = it->second;
    if (!fresh) {
      b.tokens = std::min(LiveServer::kBurst,
                          b.tokens + LiveServer::kRequestsPerSecond *
                                         std::chrono::duration<double>(now - b.at).count());
      b.at = now;
    }
    if (b.tokens < 1) return false;
    b.tokens -= 1;
    return true;
  }

 private:
  static constexpr std::size_t kAddresses = 1024;
  struct Bucket {
    double tokens;
    std::chrono::steady_clock::time_point at;
  };
  std::mutex mutex_;
  std::unordered_map<std::string, Bucket> buckets_;
};

// Every answer says: not cached, not framed, no referrer, nothing loaded but what the page is.
void send(mg_connection* conn, int status, std::string_view type, std::string_view body,
          bool head = false, const char* extra_name = nullptr, const char* extra_value = nullptr) {
  mg_response_header_start(conn, status);
  mg_response_header_add(conn, "Content-Type", type.data(), int(type.size()));
  const std::string length = std::to_string(body.size());
  mg_response_header_add(conn, "Content-Length", length.c_str(), -1);
  mg_response_header_add(conn, "Cache-Control", "no-store", -1);
  mg_response_header_add(conn, "X-Content-Type-Options", "nosniff", -1);
  mg_response_header_add(conn, "X-Frame-Options", "DENY", -1);
  mg_response_header_add(conn, "Referrer-Policy", "no-referrer", -1);
  mg_response_header_add(conn, "Content-Security-Policy",
                         "default-src 'none'; script-src 'unsafe-inline'; style-src "
                         "'unsafe-inline'; img-src blob:; connect-src 'self'",
                         -1);
  if (extra_name != nullptr) mg_response_header_add(conn, extra_name, extra_value, -1);
  mg_response_header_send(conn);
  if (!head && !body.empty()) mg_write(conn, body.data(), body.size());
}

int refuse(mg_connection* conn, int status, std::string_view why, const char* extra_name = nullptr,
           const char* extra_value = nullptr) {
  send(conn, status, "text/plain; charset=utf-8", why, false, extra_name, extra_value);
  return status;
}

thread_local std::string start_error;  // what civetweb said while starting, on this thread

int log_message(const mg_connection*, const char* message) {
  start_error = message;
  return 1;  // not to stderr: said with the exception, or not at all
}

std::string listening_port(const std::string& address, int port) {
  return (address == "localhost" ? "127.0.0.1" : address) + ":" + std::to_string(port);
}

}  // namespace

struct LiveServer::Impl {
  const LiveFeed& feed;
  CameraMailbox* const cameras;
  const std::string token;
  std::string address;
  int port = 0;
  RateLimit rate;
  mg_context* context = nullptr;

  Impl(const LiveConfig& config, const LiveFeed& f, CameraMailbox* c)
      : feed(f), cameras(c), token(config.token.empty() ? random_token() : config.token) {
    address = config.address;
    mg_init_library(0);
    const std::string ports = listening_port(config.address, config.port);
    const std::string threads = std::to_string(kThreads),
                      queued = std::to_string(kQueuedConnections),
                      head = std::to_string(kMaxHeadBytes),
                      timeout = std::to_string(kRequestTimeoutMs);
    const char* options[] = {"listening_ports",
                             ports.c_str(),
                             "num_threads",
                             threads.c_str(),
                             "connection_queue",
                             queued.c_str(),
                             "listen_backlog",
                             queued.c_str(),
                             "max_request_size",
                             head.c_str(),
                             "request_timeout_ms",
                             timeout.c_str(),
                             "enable_keep_alive",
                             "no",
                             nullptr};
    mg_callbacks callbacks{};
    callbacks.log_message = log_message;
    // civetweb's master, workers and timer below the solver, like the feed's thread: 200
    // clients at once took a sixth more of the solver's time per render step on 2 cores.
    callbacks.init_thread = [](const mg_context*, int) -> void* {
      LiveFeed::lower_priority();
      return nullptr;
    };
    start_error.clear();
    context = mg_start(&callbacks, this, options);
    if (context == nullptr) {
      mg_exit_library();
      throw make_error(
          "live page: cannot listen on ", ports, ": ",
          why_not_listening(config.address, config.port,
                            start_error.empty() ? "civetweb did not start" : start_error));
    }
    mg_server_port bound[4];
    const int n = mg_get_server_ports(context, 4, bound);
    port = n > 0 ? bound[0].port : config.port;
    mg_set_request_handler(context, "/", handle, this);
  }

  ~Impl() {
    mg_stop(context);
    mg_exit_library();
  }

  static int handle(mg_connection* conn, void* self) {
    return static_cast<Impl*>(self)->answer(conn);
  }

  int answer(mg_connection* conn) {
    const mg_request_info& r = *mg_get_request_info(conn);
    if (!rate.allow(r.remote_addr))
      return refuse(conn, 429, "too many requests\n", "Retry-After", "1");
    // civetweb keeps the first 64 headers and drops the rest: a request that fills them all
    // may have lost some.
    if (r.num_headers >= MG_MAX_HEADERS) return refuse(conn, 431, "too many headers\n");
    const std::string_view path = r.local_uri_raw != nullptr ? r.local_uri_raw : "";
    const char* header = mg_get_header(conn, "Authorization");
    constexpr std::string_view kBearer = "Bearer ";
    const bool by_header = header != nullptr && std::string_view(header).starts_with(kBearer) &&
                           same_token(std::string_view(header).substr(kBearer.size()), token);
    const bool by_query = path == "/" && same_token(query_value(r.query_string, "token"), token);
    if (!by_header && !by_query)
      return refuse(conn, 401, "a token is needed: open the URL the job printed\n",
                    "WWW-Authenticate", "Bearer");
    const std::string_view method = r.request_method;
    if (path == "/camera") return camera(conn, r, method);
    const bool head = method == "HEAD";
    if (method != "GET" && !head)
      return refuse(conn, 405, "read-only: GET or HEAD\n", "Allow", "GET, HEAD");
    if (r.content_length > 0) return refuse(conn, 413, "no body expected\n");
    if (path == "/") {
      send(conn, 200, "text/html; charset=utf-8", live_page_html(), head);
      return 200;
    }
    const std::shared_ptr<const LiveSnapshot> s = feed.snapshot();
    if (path == "/state.json") {
      send(conn, 200, "application/json", s->state, head);
      return 200;
    }
    const std::vector<std::string>& names = feed.view_names();
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (path != "/view/" + names[i] + ".png") continue;
      if (!s->pictures[i]) return refuse(conn, 404, "no picture yet\n");
      send(conn, 200, "image/png", *s->pictures[i], head);
      return 200;
    }
    return refuse(conn, 404, "not found\n");
  }

  // POST /camera: checked, read whole (it is small), merged into the mailbox.
  int camera(mg_connection* conn, const mg_request_info& r, std::string_view method) {
    if (cameras == nullptr)
      return refuse(conn, 403,
                    "read-only: this job's page may not turn the cameras "
                    "(live.interactive is off)\n");
    if (method != "POST") return refuse(conn, 405, "POST only\n", "Allow", "POST");
    const char* type = mg_get_header(conn, "Content-Type");
    if (type == nullptr || !std::string_view(type).starts_with("application/x-www-form-urlencoded"))
      return refuse(conn, 415, "expected application/x-www-form-urlencoded\n");
    if (r.content_length < 0) return refuse(conn, 411, "a Content-Length is needed\n");
    if (r.content_length > kMaxCameraBodyBytes)
      return refuse(conn, 413, "at most " + std::to_string(kMaxCameraBodyBytes) + " bytes\n");
    char body[kMaxCameraBodyBytes];
    std::size_t got = 0;
    while (got < std::size_t(r.content_length)) {
      const int n = mg_read(conn, body + got, std::size_t(r.content_length) - got);
      if (n <= 0) return refuse(conn, 400, "the body ended early\n");
      got += std::size_t(n);
    }
    CameraRequest request;
    const std::string why = parse_camera_request({body, got}, feed.view_names(), request);
    if (!why.empty()) return refuse(conn, 400, why + "\n");
    cameras->post(request);
    send(conn, 202, "text/plain; charset=utf-8", "accepted: applied at the next render step\n");
    return 202;
  }
};

LiveServer::LiveServer(const LiveConfig& config, const LiveFeed& feed, CameraMailbox* cameras)
    : impl_(std::make_unique<Impl>(config, feed, cameras)) {}

LiveServer::~LiveServer() = default;

int LiveServer::port() const { return impl_->port; }
const std::string& LiveServer::token() const { return impl_->token; }

std::string LiveServer::url() const {
  return "http://" + impl_->address + ":" + std::to_string(impl_->port) + "/?token=" + impl_->token;
}

}  // namespace voxspan
