#include "server.h"

#include <signal.h>
#include <sys/resource.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/address.hpp>
#include <boost/asio/signal_set.hpp>

#include <atomic>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <mutex>
#include <new>
#include <optional>
#include <system_error>
#include <thread>
#include <vector>

#include "catalogue.h"
#include "light_library.h"
#include "listener.h"
#include "root_dir.h"
#include "router.h"
#include "session.h"
#include "static_files.h"

namespace prt::serve {
namespace {

constexpr auto kShutdownGrace = std::chrono::seconds(10);
constexpr auto kRecheck = std::chrono::milliseconds(1000);

// Each connection holds a descriptor, and responses hold files: lift the soft limit
// (often 1024) to the hard one so --max-connections is what caps connections.
void raiseDescriptorLimit() {
  rlimit lim{};
  if (::getrlimit(RLIMIT_NOFILE, &lim) == 0 && lim.rlim_cur < lim.rlim_max) {
    lim.rlim_cur = lim.rlim_max;
    ::setrlimit(RLIMIT_NOFILE, &lim);
  }
}

std::chrono::milliseconds millis(double seconds) {
  return std::chrono::milliseconds(static_cast<std::int64_t>(seconds * 1000.0 + 0.5));
}

// Opens, binds and listens; the error says what to do about a busy port. Failing to bind
// or listen is kUnavailable (exit 7): the port or the address may be free later.
Status openAcceptor(asio::io_context& ioc, const ServeOptions& options, tcp::acceptor* out) {
  beast::error_code ec;
  const asio::ip::address address = asio::ip::make_address(options.bind, ec);
  // parseServeOptions has checked --bind already.
  if (ec) return Status::error(StatusCode::kInternal, "--bind '" + options.bind + "' is not an IP address");
  const tcp::endpoint endpoint(address, static_cast<unsigned short>(options.port));
  const std::string where = (address.is_v6() ? "[" + options.bind + "]" : options.bind) + ":" + std::to_string(options.port);
  tcp::acceptor acceptor(ioc);
  acceptor.open(endpoint.protocol(), ec);
  if (ec) {
    // Out of descriptors is a limit; no IPv6 on this host (EAFNOSUPPORT) is unavailable.
    const bool exhausted = ec == boost::system::errc::too_many_files_open ||
                           ec == boost::system::errc::too_many_files_open_in_system ||
                           ec == boost::system::errc::not_enough_memory;
    return Status::error(exhausted ? StatusCode::kResourceExhausted : StatusCode::kUnavailable,
                         "cannot open a socket: " + ec.message());
  }
  // Lets a restarted server bind while old connections sit in TIME_WAIT; on Linux it does
  // not let two servers listen on one port.
  acceptor.set_option(asio::socket_base::reuse_address(true), ec);
  acceptor.bind(endpoint, ec);
  if (ec) {
    std::string hint;
    if (ec == asio::error::address_in_use) hint = " (another server is using the port; stop it or pick another --port)";
    if (ec == asio::error::access_denied) hint = " (ports below 1024 need privileges; pick another --port)";
    if (ec == boost::system::errc::address_not_available) hint = " (no interface has this address; check --bind)";
    return Status::error(StatusCode::kUnavailable, "cannot listen on " + where + ": " + ec.message() + hint);
  }
  acceptor.listen(asio::socket_base::max_listen_connections, ec);
  if (ec) return Status::error(StatusCode::kUnavailable, "cannot listen on " + where + ": " + ec.message());
  *out = std::move(acceptor);
  return Status::ok();
}

Status run(const ServeOptions& options) {
  ::signal(SIGPIPE, SIG_IGN);  // sendfile to a closed socket must fail with EPIPE, not kill us
  raiseDescriptorLimit();

  RootDir root;
  PRT_RETURN_IF_ERROR(RootDir::open(options.root, "--root", &root));
  std::optional<RootDir> web;
  if (!options.web.empty()) {
    RootDir dir;
    PRT_RETURN_IF_ERROR(RootDir::open(options.web, "--web", &dir));
    web = std::move(dir);
  }
  const int threads = options.threads > 0 ? options.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));

  // Declared before the io_context, so they outlive every session it destroys.
  SessionRegistry registry;
  AccessLog log(!options.quiet);
  std::optional<Catalogue> catalogue;
  std::optional<LightLibrary> lights;
  std::optional<StaticFiles> staticFiles;
  std::optional<Router> router;
  std::optional<SessionContext> context;

  asio::io_context ioc(threads);
  tcp::acceptor acceptor(ioc);
  // Bound before the scan, so a busy port is reported at once and early clients wait in
  // the backlog instead of being refused.
  PRT_RETURN_IF_ERROR(openAcceptor(ioc, options, &acceptor));
  const unsigned short port = acceptor.local_endpoint().port();

  CatalogueOptions catalogueOptions;
  catalogueOptions.recheck = kRecheck;
  catalogueOptions.maxPartsBytes = static_cast<std::uint64_t>(options.maxPartsMiB) << 20;
  catalogue.emplace(root, catalogueOptions);
  lights.emplace(root, kRecheck);
  if (web) staticFiles.emplace(*web);
  router.emplace(*catalogue, *lights, staticFiles ? &*staticFiles : nullptr);
  context.emplace(SessionContext{*router, log, registry, millis(options.readTimeoutSeconds),
                                 millis(options.writeTimeoutSeconds)});

  const auto snapshot = catalogue->current();
  std::fprintf(stderr, "prt-serve: %d usable of %zu assets and %zu environment maps under %s%s%s; %d threads\n",
               snapshot->usableCount, snapshot->entries.size(), lights->count(), root.path().c_str(),
               web ? "; web client from " : "", web ? web->path().c_str() : "", threads);

  // Signals: the first asks for a graceful stop, a second for an immediate one.
  std::mutex stopMutex;
  std::condition_variable stopCv;
  int signalsSeen = 0;
  asio::signal_set signals(ioc, SIGINT, SIGTERM);
  std::function<void(beast::error_code, int)> onSignal = [&](beast::error_code ec, int) {
    if (ec) return;
    {
      std::lock_guard lock(stopMutex);
      ++signalsSeen;
    }
    stopCv.notify_all();
    signals.async_wait(onSignal);
  };
  signals.async_wait(onSignal);

  auto listener = std::make_shared<Listener>(ioc, std::move(acceptor), *context,
                                             static_cast<std::size_t>(options.maxConnections),
                                             static_cast<std::size_t>(options.perClientLimit()));
  listener->start();

  std::vector<std::thread> pool;
  for (int i = 0; i < threads; ++i) {
    pool.emplace_back([&ioc] {
      for (;;) {
        try {
          ioc.run();
          return;
        } catch (const std::exception& e) {
          // Handlers catch what they can; this is the last wall, and serving goes on.
          std::fprintf(stderr, "prt-serve: internal error in a handler: %s\n", e.what());
        }
      }
    });
  }
  const std::string bindShown = options.bind.find(':') != std::string::npos ? "[" + options.bind + "]" : options.bind;
  std::printf("prt-serve: listening on http://%s:%u/\n", bindShown.c_str(), static_cast<unsigned>(port));
  std::fflush(stdout);

  {
    std::unique_lock lock(stopMutex);
    stopCv.wait(lock, [&] { return signalsSeen > 0; });
  }
  std::fprintf(stderr, "prt-serve: stopping: finishing %zu open connections\n", registry.active());
  listener->stop();
  registry.stopAll();
  const auto deadline = std::chrono::steady_clock::now() + kShutdownGrace;
  std::size_t left = 0;
  while (!registry.waitEmpty(std::min(deadline, std::chrono::steady_clock::now() + std::chrono::milliseconds(50)))) {
    std::lock_guard lock(stopMutex);
    if (signalsSeen > 1 || std::chrono::steady_clock::now() >= deadline) {
      left = registry.active();
      break;
    }
  }
  ioc.stop();
  for (std::thread& t : pool) t.join();
  // Before the io_context goes: waiting lights requests hold sessions, whose sockets
  // belong to it.
  lights->stop();
  if (left == 0) {
    std::fprintf(stderr, "prt-serve: stopped\n");
  } else {
    std::fprintf(stderr, "prt-serve: stopped; %zu connections were closed without finishing\n", left);
  }
  return Status::ok();
}

}  // namespace

Status runServer(const ServeOptions& options) noexcept {
  try {
    return run(options);
  } catch (const std::bad_alloc&) {
    return Status::error(StatusCode::kResourceExhausted, "out of memory");
  } catch (const std::system_error& e) {
    // std::thread reports a process out of threads as EAGAIN.
    const bool exhausted = e.code() == std::errc::resource_unavailable_try_again;
    return Status::error(exhausted ? StatusCode::kResourceExhausted : StatusCode::kInternal,
                         std::string(exhausted ? "" : "internal error: ") + e.what());
  } catch (const std::exception& e) {
    // Handlers catch their own; what reaches here (a thread that cannot start, a throwing
    // constructor) is a failure to start or stop the server.
    return Status::error(StatusCode::kInternal, std::string("internal error: ") + e.what());
  } catch (...) {
    return Status::error(StatusCode::kInternal, "internal error");
  }
}

}  // namespace prt::serve
