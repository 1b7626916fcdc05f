// Every open connection, for the connection caps and for shutdown: which ones are idle
// (waiting for the first byte of a request), and how many each client address holds.
// Admission happens here, so that at the global cap idle connections make room for a new
// client, oldest first, and no single address can take more than its share.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

namespace prt::serve {

class Session;

enum class Admission {
  kServe,         // serve it (idle connections may have been evicted to make room)
  kRefuseClient,  // 503: its address already holds its share, none of them idle
  kRefuseFull,    // 503: the server is at --max-connections, none of them idle
  kDrop,          // close without a word: too many 503s are being sent already
};

// Thread-safe.
class SessionRegistry {
 public:
  // Decides on a new connection from `client` (its address) and, when that makes room,
  // evicts idle connections, oldest idle first: one of the client's own when it is at
  // `maxPerClient`, then any when the server is at `maxConnections`.
  Admission admit(const std::string& client, std::size_t maxConnections, std::size_t maxPerClient);

  // Registers a session (`refusing`: it only sends 503 and closes; not counted per client).
  void add(Session* session, const std::shared_ptr<Session>& shared, const std::string& client, bool refusing);
  // Forgets a session; called from its destructor.
  void remove(Session* session);
  // The session waits for the first byte of a request: from now on it may be evicted.
  void markIdle(Session* session);
  // The session has input to read. False when it was chosen for eviction meanwhile: it
  // must close instead.
  bool leaveIdle(Session* session);

  std::size_t active() const;    // sessions serving requests
  std::size_t refusing() const;  // sessions only sending 503 before closing
  // Asks every session to finish its current response and close.
  void stopAll();
  // Waits until no session is left or `deadline` passes; true when none is left.
  bool waitEmpty(std::chrono::steady_clock::time_point deadline);

 private:
  struct Member {
    std::weak_ptr<Session> session;
    std::string client;
    bool refusing = false;
    bool evicted = false;       // chosen to make room; closing
    std::uint64_t idleKey = 0;  // its key in idle_, 0 when not idle
  };
  // Marks the oldest idle member (of `client`, unless empty) evicted; null when none.
  std::shared_ptr<Session> evictOldestIdleLocked(const std::string* client);

  mutable std::mutex mutex_;
  std::condition_variable empty_;
  std::unordered_map<Session*, Member> sessions_;
  std::map<std::uint64_t, Session*> idle_;  // by the order they became idle: oldest first
  std::uint64_t nextIdleKey_ = 1;
  std::unordered_map<std::string, std::size_t> perClient_;  // serving, not evicted
  std::size_t refusing_ = 0;
  std::size_t evicting_ = 0;  // evicted but not yet gone
};

}  // namespace prt::serve
