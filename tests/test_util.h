// Helpers shared by the tests: a process-wide EGL context, temporary folders, running commands.
#pragma once

#include "gi/platform/egl_context.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace gi::test {

// The one headless context of the test process, created on first use.
EGLContextHeadless& context();

// A fresh empty folder under the system temp dir, named after the running test.
std::filesystem::path tempDir();

struct CommandResult {
    int exitCode = -1;
    std::string output;  // stdout and stderr together
};
CommandResult runCommand(const std::string& command);

// A GL test fails on any GL debug error raised during it.
class GLTest : public ::testing::Test {
protected:
    void SetUp() override;
    void TearDown() override;

private:
    uint64_t mErrorsBefore = 0;
};

}  // namespace gi::test
