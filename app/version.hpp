#pragma once
// What `poundbench --version` prints: the version of CMake's project(VERSION) and the
// commit the binary was built from. Their source is written at every build by
// cmake/version.cmake (so a rebuild after a commit, without a configure, updates them).

namespace pb::app {

extern const char* const kVersion;  // "0.1"
// The short hash of HEAD, "<hash> (with uncommitted changes)" when tracked files differed
// from it at build time, or "unknown" outside a git checkout (a source tarball).
extern const char* const kCommit;

}  // namespace pb::app
