#include "session_registry.h"

#include <vector>

#include "session.h"

namespace prt::serve {
namespace {

// Connections beyond a cap that may be waiting for their 503 at once; past this they are
// closed without a word (a flood should not cost memory).
constexpr std::size_t kMaxRefusing = 64;

}  // namespace

std::shared_ptr<Session> SessionRegistry::evictOldestIdleLocked(const std::string* client) {
  for (auto it = idle_.begin(); it != idle_.end(); ++it) {
    Member& m = sessions_.at(it->second);
    if (client && m.client != *client) continue;
    std::shared_ptr<Session> victim = m.session.lock();
    if (!victim) continue;  // being destroyed; remove() will tidy up
    m.idleKey = 0;
    m.evicted = true;
    idle_.erase(it);
    ++evicting_;
    if (--perClient_[m.client] == 0) perClient_.erase(m.client);
    return victim;
  }
  return nullptr;
}

Admission SessionRegistry::admit(const std::string& client, std::size_t maxConnections, std::size_t maxPerClient) {
  std::vector<std::shared_ptr<Session>> victims;
  Admission outcome = Admission::kServe;
  {
    std::lock_guard lock(mutex_);
    const auto held = perClient_.find(client);
    if (held != perClient_.end() && held->second >= maxPerClient) {
      if (auto v = evictOldestIdleLocked(&client)) {
        victims.push_back(std::move(v));
      } else {
        outcome = Admission::kRefuseClient;
      }
    }
    const std::size_t serving = sessions_.size() - refusing_ - evicting_;
    if (outcome == Admission::kServe && serving >= maxConnections) {
      if (auto v = evictOldestIdleLocked(nullptr)) {
        victims.push_back(std::move(v));
      } else {
        outcome = Admission::kRefuseFull;
      }
    }
    if (outcome != Admission::kServe && refusing_ >= kMaxRefusing) outcome = Admission::kDrop;
  }
  // Outside the lock: evict() only posts to the victim's strand.
  for (const auto& v : victims) v->evict();
  return outcome;
}

void SessionRegistry::add(Session* session, const std::shared_ptr<Session>& shared, const std::string& client,
                          bool refusing) {
  std::lock_guard lock(mutex_);
  sessions_.emplace(session, Member{shared, client, refusing, false, 0});
  if (refusing) {
    ++refusing_;
  } else {
    ++perClient_[client];
  }
}

void SessionRegistry::remove(Session* session) {
  std::lock_guard lock(mutex_);
  const auto it = sessions_.find(session);
  if (it == sessions_.end()) return;
  const Member& m = it->second;
  if (m.idleKey != 0) idle_.erase(m.idleKey);
  if (m.refusing) {
    --refusing_;
  } else if (m.evicted) {
    --evicting_;
  } else if (--perClient_[m.client] == 0) {
    perClient_.erase(m.client);
  }
  sessions_.erase(it);
  if (sessions_.empty()) empty_.notify_all();
}

void SessionRegistry::markIdle(Session* session) {
  std::lock_guard lock(mutex_);
  const auto it = sessions_.find(session);
  if (it == sessions_.end() || it->second.evicted || it->second.idleKey != 0) return;
  it->second.idleKey = nextIdleKey_++;
  idle_.emplace(it->second.idleKey, session);
}

bool SessionRegistry::leaveIdle(Session* session) {
  std::lock_guard lock(mutex_);
  const auto it = sessions_.find(session);
  if (it == sessions_.end() || it->second.evicted) return false;
  if (it->second.idleKey != 0) idle_.erase(it->second.idleKey);
  it->second.idleKey = 0;
  return true;
}

std::size_t SessionRegistry::active() const {
  std::lock_guard lock(mutex_);
  return sessions_.size() - refusing_;
}

std::size_t SessionRegistry::refusing() const {
  std::lock_guard lock(mutex_);
  return refusing_;
}

void SessionRegistry::stopAll() {
  std::vector<std::shared_ptr<Session>> live;
  {
    std::lock_guard lock(mutex_);
    for (auto& [raw, member] : sessions_) {
      if (auto s = member.session.lock()) live.push_back(std::move(s));
    }
  }
  for (auto& s : live) s->stop();
}

bool SessionRegistry::waitEmpty(std::chrono::steady_clock::time_point deadline) {
  std::unique_lock lock(mutex_);
  return empty_.wait_until(lock, deadline, [&] { return sessions_.empty(); });
}

}  // namespace prt::serve
