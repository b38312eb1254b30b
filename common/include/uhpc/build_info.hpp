#pragma once
// Version and git commit of this build (generated at build time by cmake/WriteBuildInfo.cmake).

namespace uhpc {
const char* build_version();
const char* build_git_commit();  // "<sha>", "<sha>-dirty" or "unknown"
}  // namespace uhpc
