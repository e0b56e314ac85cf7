// COLLIDE_PROFILE_ZONE("name"): a zone from here to the end of the scope for the engine's profiler
// (collide/hooks.h, setProfileHooks), compiled in only with COLLIDE_PROFILE_ZONES=1 (the CMake
// option of that name).
#pragma once

#ifndef COLLIDE_PROFILE_ZONES
#define COLLIDE_PROFILE_ZONES 0
#endif

namespace collide::detail {

void profileBegin(const char* name);
void profileEnd();

struct ProfileZone {
  explicit ProfileZone(const char* name) { profileBegin(name); }
  ~ProfileZone() { profileEnd(); }
  ProfileZone(const ProfileZone&) = delete;
  ProfileZone& operator=(const ProfileZone&) = delete;
};

}  // namespace collide::detail

#define COLLIDE_PROFILE_CONCAT_(a, b) a##b
#define COLLIDE_PROFILE_CONCAT(a, b) COLLIDE_PROFILE_CONCAT_(a, b)
#if COLLIDE_PROFILE_ZONES
#define COLLIDE_PROFILE_ZONE(name) \
  const ::collide::detail::ProfileZone COLLIDE_PROFILE_CONCAT(collideZone, __LINE__)(name)
#else
#define COLLIDE_PROFILE_ZONE(name) static_cast<void>(0)
#endif
